"""Why-not reports: for a rule that does not match, the largest partial match and what stopped it.

The report runs the rule's search plan with every node of the graph tried as the start, records the
deepest step reached, and names the pattern element or condition that failed next, with its source
position. If complete positive matches exist but are refused, it says which NAC matched or which
edges would dangle.
"""

from __future__ import annotations

from dataclasses import dataclass

from .graph import HostGraph
from .matcher import Matcher, run_plan
from .plan import build_plan


@dataclass
class WhyNot:
    """The outcome of :func:`why_not`."""

    rule: str
    matches: int
    partial: dict[str, int]  # the largest partial binding found
    failed: str  # what could not be found next, or why complete matches were refused
    pos: object

    def __str__(self) -> str:
        if self.matches:
            return f"rule {self.rule} has {self.matches} match(es)"
        bound = ", ".join(f"{k}={v}" for k, v in self.partial.items() if not k.startswith("_")) or "nothing"
        return f"rule {self.rule} does not match: best partial match binds {bound}; {self.failed} ({self.pos})"


def why_not(matcher: Matcher) -> WhyNot:
    """Explain why ``matcher``'s rule has no match in its graph (or count its matches)."""
    rule = matcher.rule
    count = len(matcher.all())
    if count:
        return WhyNot(rule.name, count, {}, "", rule.source.pos)
    search = _DeepestSearch(matcher)
    search.go(0, set(search.binding[v] for v in matcher.fixed), set())
    best = search.best
    return WhyNot(rule.name, 0, best.binding, best.failed, best.pos)


@dataclass
class _Deepest:
    """The deepest step a search reached, the binding it had there, and what failed next."""

    depth: int
    binding: dict[str, int]
    failed: str
    pos: object


class _DeepestSearch:
    """The matcher's plan run one step at a time, noting the deepest failure."""

    def __init__(self, matcher: Matcher):
        self.matcher = matcher
        self.rule = matcher.rule
        given = frozenset(matcher.fixed) | frozenset(matcher.values)
        self.plan = build_plan(self.rule.pattern, given, matcher.graph.count)
        self.binding = {**matcher.values, **matcher.fixed}
        self.best = _Deepest(-1, {}, "", self.rule.source.pos)

    def note(self, depth: int, failed: str, pos) -> None:
        if depth > self.best.depth:
            values = self.matcher.values
            self.best = _Deepest(depth, {k: v for k, v in self.binding.items() if k not in values}, failed, pos)

    def go(self, i: int, used_nodes: set, used_edges: set) -> None:
        if i == len(self.plan):
            self.refused(i)
            return
        step = self.plan[i]
        nodes = self.rule.pattern.nodes
        found = False
        for values in _candidates(self.matcher.graph, step, self.binding, used_nodes, used_edges):
            found = True
            self.binding.update(values)
            new_nodes = {v for k, v in values.items() if k in nodes}
            new_edges = {v for k, v in values.items() if k not in nodes}
            self.go(i + 1, used_nodes | new_nodes, used_edges | new_edges)
            for k in values:
                del self.binding[k]
        if not found:
            self.note(i, step.missing(), step.pos)

    def refused(self, depth: int) -> None:
        """Note why a complete positive match is refused (a NAC, or the dangling condition)."""
        reason = self.matcher.rejection(self.binding)
        if reason is None:
            return
        if reason.nac is not None:
            nac = self.rule.nacs[reason.nac]
            self.note(depth, f"refused by NAC #{reason.nac + 1}, which matches here", nac.pos)
        else:
            edges = "; ".join(f"node {n} keeps edges {es}" for n, es in reason.dangling.items())
            self.note(depth, f"refused by the dangling condition (DPO): {edges}", self.rule.source.pos)


def _candidates(g: HostGraph, step, binding: dict, used_nodes: set, used_edges: set):
    """The bindings a single plan step can add (the same tests as the matcher, one step at a time)."""
    for b in run_plan(g, [step], dict(binding), set(used_nodes), set(used_edges), "why-not", {}):
        yield {var: b[var] for var in step.binds}
