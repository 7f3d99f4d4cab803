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

__all__ = ["per_state", "STATES", "by_content"]

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

