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
from .plan import Bound, Check, Extend, Scan, build_plan, describe_step, step_pos


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
    g = matcher.graph
    given = frozenset(matcher.fixed) | frozenset(matcher.values)
    plan = build_plan(rule.pattern, given, g.count)
    best = {"depth": -1, "binding": {}, "failed": "", "pos": rule.source.pos}
    binding = {**matcher.values, **matcher.fixed}

    def note(depth: int, failed: str, pos) -> None:
        if depth > best["depth"]:
            best.update(depth=depth, binding={k: v for k, v in binding.items() if k not in matcher.values},
                        failed=failed, pos=pos)

    def go(i: int, used_nodes: set, used_edges: set) -> None:
        if i == len(plan):
            reason = matcher.rejection(binding)
            if reason and reason[0] == "nac":
                nac = rule.nacs[reason[1]]
                note(i, f"refused by NAC #{reason[1] + 1}, which matches here", nac.pos)
            elif reason:
                edges = "; ".join(f"node {n} keeps edges {es}" for n, es in reason[1].items())
                note(i, f"refused by the dangling condition (DPO): {edges}", rule.source.pos)
            return
        step = plan[i]
        found = False
        for var_values in _candidates(g, step, binding, used_nodes, used_edges):
            found = True
            binding.update(var_values)
            new_nodes = {v for k, v in var_values.items() if k in rule.pattern.nodes}
            new_edges = {v for k, v in var_values.items() if k not in rule.pattern.nodes}
            go(i + 1, used_nodes | new_nodes, used_edges | new_edges)
            for k in var_values:
                del binding[k]
        if not found:
            note(i, f"no {describe_step(step)} found" if not isinstance(step, Check)
                 else f"{describe_step(step)} is false", step_pos(step))

    go(0, {binding[v] for v in matcher.fixed}, set())
    return WhyNot(rule.name, 0, best["binding"], best["failed"], best["pos"])


def _candidates(g: HostGraph, step, binding: dict, used_nodes: set, used_edges: set):
    """The bindings a single plan step can add (the same tests as the matcher, one step at a time)."""
    for b in run_plan(g, [step], dict(binding), set(used_nodes), set(used_edges), "why-not", {}):
        if isinstance(step, Check):
            yield {}
        elif isinstance(step, Bound):
            yield {}
        elif isinstance(step, Scan):
            yield {step.node.var: b[step.node.var]}
        elif isinstance(step, Extend):
            out = {step.edge.var: b[step.edge.var]}
            if step.end_node is not None:
                out[step.end] = b[step.end]
            yield out
