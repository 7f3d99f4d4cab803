"""Why-not reports: for a rule that does not match, its nearest partial matches and what stopped each.

The report runs the rule's search plan with every node of the graph tried as the start and keeps the
partial matches that reached the deepest step (up to a limit), each with the pattern element or
condition that failed next, its source position and, for a condition, the values of the attributes
and function calls in it at that binding. If complete positive matches exist but are refused, it says
which NAC matched or which edges would dangle.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .graph import HostGraph
from .matcher import Matcher, run_plan
from .plan import Check, build_plan

#: How many near matches a report lists.
REASONS = 10


@dataclass
class Reason:
    """One near match: its binding, what failed next and where, and the values in a failed condition."""

    binding: dict[str, int]
    failed: str
    pos: object
    values: dict[str, object] = field(default_factory=dict)

    def __str__(self) -> str:
        bound = ", ".join(f"{k}={v}" for k, v in self.binding.items() if not k.startswith("_")) or "nothing"
        shown = ", ".join(f"{k} = {_short(v)}" for k, v in self.values.items())
        return f"binds {bound}; {self.failed} ({self.pos})" + (f" with {shown}" if shown else "")


@dataclass
class WhyNot:
    """The outcome of :func:`why_not`: the match count, or the nearest partial matches (``reasons``,
    deepest first found; ``partial``, ``failed`` and ``pos`` are the first one's)."""

    rule: str
    matches: int
    partial: dict[str, int]
    failed: str
    pos: object
    reasons: list[Reason] = field(default_factory=list)

    def __str__(self) -> str:
        if self.matches:
            return f"rule {self.rule} has {self.matches} match(es)"
        lines = [f"rule {self.rule} does not match; its {len(self.reasons)} nearest partial match(es):"]
        return "\n".join(lines + [f"  {r}" for r in self.reasons])


def why_not(matcher: Matcher, limit: int = REASONS) -> WhyNot:
    """Explain why ``matcher``'s rule has no match in its graph (or count its matches)."""
    rule = matcher.rule
    count = len(matcher.all())
    if count:
        return WhyNot(rule.name, count, {}, "", rule.source.pos)
    search = _DeepestSearch(matcher, limit)
    search.go(0, set(search.binding[v] for v in matcher.fixed), set())
    reasons = search.reasons or [Reason({}, "nothing to match", rule.source.pos)]
    first = reasons[0]
    return WhyNot(rule.name, 0, first.binding, first.failed, first.pos, reasons)


def _short(value) -> str:
    """A value for a report: floats and vectors rounded, long lists cut."""
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, (tuple, list)):
        items = [_short(v) for v in value[:4]]
        return "(" + ", ".join(items) + (", ..." if len(value) > 4 else "") + ")"
    return repr(value)


class _DeepestSearch:
    """The matcher's plan run one step at a time, keeping the deepest failures."""

    def __init__(self, matcher: Matcher, limit: int):
        self.matcher = matcher
        self.rule = matcher.rule
        given = frozenset(matcher.fixed) | frozenset(matcher.values)
        self.plan = build_plan(self.rule.pattern, given, matcher.graph.count)
        self.binding = {**matcher.values, **matcher.fixed}
        self.depth = -1
        self.limit = limit
        self.reasons: list[Reason] = []

    def note(self, depth: int, failed: str, pos, values=None) -> None:
        if depth < self.depth or (depth == self.depth and len(self.reasons) >= self.limit):
            return
        if depth > self.depth:
            self.depth, self.reasons = depth, []
        binding = {k: v for k, v in self.binding.items() if k not in self.matcher.values}
        self.reasons.append(Reason(binding, failed, pos, values or {}))

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
            shown = step.condition.values(self.matcher.graph, self.binding) if isinstance(step, Check) else None
            self.note(i, step.missing(), step.pos, shown)

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
