"""What the rule helpers work out from the rule graph, kept per state of the graph.

Exploration (issue 13) rolls the graph back and forth between the states of its search and asks the
rules' geometric helpers the same questions in each: the faces of the plan, the sides and strips of
a patch, the rings. :meth:`HostGraph.state_id <vaultgram.engine.graph.HostGraph.state_id>` is the
same again after a rollback to a state, so a result keyed by it is found again there, where a key by
``graph.changes`` (which undo moves on) was lost at the first rollback.

>>> from vaultgram.engine.graph import HostGraph
>>> from vaultgram.engine.rulebook import rulebook_from_text
>>> import weakref
>>> g, cache, calls = HostGraph(rulebook_from_text("schema s { node A }").schema), weakref.WeakKeyDictionary(), []
>>> count = lambda graph: calls.append(1) or len(list(graph.nodes()))
>>> mark = g.mark(); n = g.add_node("A")
>>> per_state(cache, g, count), per_state(cache, g, count)
(1, 1)
>>> g.rollback(mark); per_state(cache, g, count)
0
>>> n = g.add_node("A"); per_state(cache, g, count), len(calls)
(1, 3)
"""

from __future__ import annotations

import weakref
from collections import OrderedDict

__all__ = ["per_state", "memo_at", "STATES", "by_content", "Untouched", "untouched"]

#: The states of one graph whose results are kept (the most recently asked).
STATES = 64


def per_state(cache: weakref.WeakKeyDictionary, graph, make):
    """``make(graph)``, computed once per state of ``graph`` and kept in ``cache`` (a weak dictionary
    of the helper's own) for its last :data:`STATES` states."""
    states = cache.get(graph)
    if states is None:
        states = cache[graph] = OrderedDict()
    key = graph.state_id()
    if key in states:
        states.move_to_end(key)
        return states[key]
    value = states[key] = make(graph)
    if len(states) > STATES:
        states.popitem(last=False)
    return value


def memo_at(cache: weakref.WeakKeyDictionary, graph, key, make):
    """``make()``, computed once per ``key`` and state of ``graph``: a rule helper's answer for one
    corner or branch (its ``key``) kept in a per-state dictionary (:func:`per_state`) of the helper's own
    ``cache``, so that a rule's condition and its action ask it once.

    >>> from vaultgram.engine.graph import HostGraph
    >>> from vaultgram.engine.rulebook import rulebook_from_text
    >>> g, cache = HostGraph(rulebook_from_text("schema s { node A }").schema), weakref.WeakKeyDictionary()
    >>> calls = []
    >>> [memo_at(cache, g, k, lambda: calls.append(k) or k * 2) for k in (1, 2, 1)], calls
    ([2, 4, 2], [1, 2])
    """
    memo = per_state(cache, graph, lambda g: {})
    if key not in memo:
        memo[key] = make()
    return memo[key]


_MISSING = object()  # by_content's mark of a key not kept


def by_content(cache: OrderedDict, key, make, size: int):
    """``make()``, kept in ``cache`` under ``key`` (what the result is made of, hashable) for the last
    ``size`` keys asked. Where a result depends on a few nodes' and edges' values only, keying it by
    those values finds it again in every state of the graph that has them (a face that a rewrite
    elsewhere left alone), where :func:`per_state` finds it only in the same state.

    >>> cache, calls = OrderedDict(), []
    >>> [by_content(cache, k, lambda: calls.append(k) or k * 2, 2) for k in (1, 2, 1, 3, 2)], calls
    ([2, 4, 2, 6, 4], [1, 2, 3, 2])
    """
    value = cache.pop(key, _MISSING)  # hashing a key is most of a hit's cost: once to take it out,
    if value is _MISSING:  # once to put it back last (the most recently asked)
        value = make()
    cache[key] = value
    if len(cache) > size:
        cache.popitem(last=False)
    return value


class Untouched:
    """Results kept while the graph's changes touch none of the nodes each was worked out from, found
    again in every later state of the graph that left those nodes alone (where :func:`per_state` finds a
    result only in the state it was made in: every rule application makes a new state, and a rule whose
    condition calls a helper of the whole graph asks it again at every candidate after each one, issue
    18). The caller names the nodes (a result's *footprint*): every node whose type, attributes or edges
    (their attributes and the order round the node too) the result read, and the ends of every edge it
    read. The graph's journal says what each change touched (``record.touched``, as for
    :meth:`~vaultgram.engine.graph.HostGraph.changes_since`): the records since the last question, those a
    rollback undoes (:meth:`~vaultgram.engine.graph.HostGraph.watch`) and those the graph forgets. A result
    whose footprint one of them touched is dropped; nothing is dropped for changes elsewhere.

    >>> from vaultgram.engine.graph import HostGraph
    >>> from vaultgram.engine.rulebook import rulebook_from_text
    >>> g = HostGraph(rulebook_from_text("schema s { node A { x: int = 0 } }").schema)
    >>> a, b = g.add_node("A"), g.add_node("A")
    >>> kept, calls = Untouched(g), []
    >>> x_of = lambda n: lambda: (calls.append(n) or g.get(n, "x"), {n})
    >>> g.set_node_attr(b, "x", 1); kept.get(g, a, x_of(a)), kept.get(g, b, x_of(b))
    (0, 1)
    >>> mark = g.mark(); g.set_node_attr(b, "x", 2); kept.get(g, a, x_of(a)), kept.get(g, b, x_of(b))
    (0, 2)
    >>> g.rollback(mark); kept.get(g, a, x_of(a)), kept.get(g, b, x_of(b)), calls
    (0, 1, [0, 1, 1, 1])
    """

    def __init__(self, graph):
        self._synced = graph.mark()  # the journal records before this one are accounted for
        self._kept: dict = {}  # key -> (result, its footprint)
        self._by_node: dict = {}  # node -> the keys whose footprint holds it
        graph.watch(self)

    def get(self, graph, key, make):
        """The result kept under ``key`` (hashable: what it is of besides its footprint), or ``make()``'s:
        ``(result, footprint)``, the footprint an iterable of node ids, or None for a result not to keep
        beyond this question."""
        self._sync(graph)
        found = self._kept.get(key)
        if found is not None:
            return found[0]
        result, nodes = make()
        if nodes is not None:
            nodes = frozenset(nodes)
            self._kept[key] = (result, nodes)
            for n in nodes:
                self._by_node.setdefault(n, set()).add(key)
        return result

    def undoing(self, graph, record) -> None:
        """Account for a record about to be undone (:meth:`~vaultgram.engine.graph.HostGraph.watch`)."""
        self._account(graph, record)
        self._synced = min(self._synced, graph.mark())

    def forgetting(self, graph) -> None:
        """Account for the whole journal before the graph drops it."""
        self._sync(graph)
        self._synced = 0

    def _sync(self, graph) -> None:
        mark = graph.mark()
        if mark != self._synced:
            for record in graph.journal_since(self._synced):
                self._account(graph, record)
            self._synced = mark

    def _account(self, graph, record) -> None:
        nodes: set = set()
        record.touched(graph, nodes, set())
        for n in nodes:
            for key in self._by_node.pop(n, ()):
                found = self._kept.pop(key, None)
                for m in found[1] if found is not None else ():
                    if m != n and key in self._by_node.get(m, ()):
                        self._by_node[m].discard(key)


def untouched(cache: weakref.WeakKeyDictionary, graph) -> Untouched:
    """The :class:`Untouched` results of ``graph`` in ``cache`` (a weak dictionary of the helper's own)."""
    kept = cache.get(graph)
    if kept is None:
        kept = cache[graph] = Untouched(graph)
    return kept
