"""Keeping a rule's match set current while the graph changes, by re-matching only near the changes.

After a rewrite, a match can only appear or disappear if it contains a changed node, or if one of
its NACs reaches a changed node; so a :class:`MatchSet` drops the matches within the rule's *radius*
of the changed nodes and searches again from exactly those nodes (every pattern variable whose type
fits is tried as the anchor). Rules none of whose read types were touched are not looked at at all.
Rules that call non-local host functions (radius None) are re-matched over the whole graph.

The smallest match key is kept in a heap with lazy deletion, so ``fixpoint`` always applies the
first match in the same deterministic order as a full search would.

A *lazy* set (``fixpoint``'s, of a rule that calls a non-local function) searches the whole graph only
when asked (:meth:`MatchSet.first`, ``len``, :meth:`MatchSet.discard`): at first, and after changes
where it would re-match. ``fixpoint`` asks its sets in priority order and stops at the first
with a match, so a rule below one that keeps firing is searched once when that one stops, not after
each of its applications (the vault rules' reflex-corner chords, below the strip rules that carry each
chord across the layout: issue 18). The search then finds what the skipped ones would have found last
(less the matches discarded since, as they would be): the current graph's matches, which are the
same as at the last change of a type the rule reads (``reads_types``) wherever the engine's premise
for re-matching at all holds, that a rule's matches change only with such changes (a host function
that reads node attributes names the types it reads: ``f(A)``, :class:`~.expressions.Function`).
"""

from __future__ import annotations

import heapq

from .graph import ChangeSet, HostGraph
from .matcher import Match, Matcher


class MatchSet:
    """All current matches of one rule (with fixed parameters) in a graph."""

    def __init__(self, matcher: Matcher, lazy: bool = False):
        self.matcher = matcher
        self.rule = matcher.rule
        self.graph: HostGraph = matcher.graph
        self.matches: dict[tuple, Match] = {}
        self._by_node: dict[int, set[tuple]] = {}
        self._heap: list[tuple] = []
        # a rule that calls a non-local function searches when asked (module docstring), the others as before
        self.lazy = lazy and self.rule.radius is None
        self.stale = self.lazy  # ``matches`` is then current only after asking
        if not self.lazy:
            self.rematch_all()

    def __len__(self) -> int:
        self._fresh()
        return len(self.matches)

    def first(self) -> Match | None:
        self._fresh()
        while self._heap and self._heap[0] not in self.matches:
            heapq.heappop(self._heap)
        return self.matches[self._heap[0]] if self._heap else None

    def discard(self, m: Match) -> None:
        """Drop a match (one that cannot be applied) until a change near it finds it again."""
        self._fresh()
        if m.key in self.matches:
            self._remove(m.key)

    def rematch_all(self) -> None:
        self.stale = False
        self.matches.clear()
        self._by_node.clear()
        self._heap = []
        for m in self.matcher.all():
            self._add(m)

    def update(self, changes: ChangeSet) -> None:
        """Bring the match set up to date after the changes described by ``changes`` (a lazy set: mark
        it stale where it would search the whole graph; a stale one stays so)."""
        if self.stale or not changes.types & self.rule.reads_types and not self._params_touched(changes):
            return
        if self.rule.radius is None:
            if self.lazy:
                self.stale = True
            else:
                self.rematch_all()
            return
        region = self._region(changes.nodes, self.rule.radius)
        stale = set()
        for n in region:
            stale |= self._by_node.get(n, set())
        for key in stale:
            self._remove(key)
        g = self.graph
        pattern_nodes = self.rule.pattern.nodes
        for n in sorted(region):
            if not g.has_node(n):
                continue
            t = g.node_type(n)
            for var, pn in pattern_nodes.items():
                if t in pn.types:
                    for m in self.matcher.anchored(var, n):
                        if m.key not in self.matches:
                            self._add(m)

    # -- internals -------------------------------------------------------------------------------

    def _fresh(self) -> None:
        if self.stale:
            self.rematch_all()

    def _params_touched(self, changes: ChangeSet) -> bool:
        return any(n in changes.nodes for n in self.matcher.fixed.values())

    def _region(self, nodes, radius: int) -> set[int]:
        g = self.graph
        region = set(nodes)
        frontier = [n for n in nodes if g.has_node(n)]
        for _ in range(radius):
            nxt = []
            for n in frontier:
                for e in g.incident(n):
                    m = g.other(e, n)
                    if m not in region:
                        region.add(m)
                        nxt.append(m)
            frontier = nxt
        return region

    def _add(self, m: Match) -> None:
        self.matches[m.key] = m
        heapq.heappush(self._heap, m.key)
        for n in self._nodes_of(m):
            self._by_node.setdefault(n, set()).add(m.key)

    def _remove(self, key: tuple) -> None:
        m = self.matches.pop(key)
        for n in self._nodes_of(m):
            keys = self._by_node.get(n)
            if keys is not None:
                keys.discard(key)
                if not keys:
                    del self._by_node[n]

    def _nodes_of(self, m: Match) -> list[int]:
        return [m.binding[v] for v in self.rule.pattern.nodes]
