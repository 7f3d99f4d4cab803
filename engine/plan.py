"""Search plans: the order in which a pattern's elements are bound, decided once per rule.

A plan is a list of steps (GP 2 and GrGen.NET compile rules the same way):

* ``Bound(var)`` -- a node given from outside (a parameter, the anchor of an incremental re-match,
  or a variable of the enclosing match for a NAC): check its type and inline constraints;
* ``Scan(var)`` -- try every node of the variable's type (and subtypes) from the type index; the
  plan scans the variable with the fewest candidates, and only when nothing bound is adjacent;
* ``Extend(edge, from, to)`` -- follow the typed adjacency of a bound node along the pattern edge,
  binding the edge and, unless it is already bound, the node at its other end;
* ``Check(condition)`` -- a ``where`` condition (one conjunct of it), placed right after its last
  variable is bound; but a conjunct that is not a plain attribute or degree test (a host function,
  arithmetic) also waits for the conjuncts written before it, so that it runs only where they hold,
  as ``and`` reads: ``where long(p) and diagonal(p, x, o)`` never computes the diagonal of a patch
  that is not long, even when ``long`` needs a variable bound later.

The greedy order prefers closing cycles (both ends bound: a check, no branching), then extending
along the rarest edge type, and scans only to start a new connected component.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Union

from .checker import CompiledPattern, Condition, PatternEdge, PatternNode


@dataclass(frozen=True)
class _NodeStep:
    """A step about one pattern node. Every step also tells the variables it ``binds``, its ``pos``
    in the rule, and what is ``missing()`` when it finds nothing (for why-not reports)."""

    node: PatternNode

    @property
    def pos(self):
        return self.node.pos


@dataclass(frozen=True)
class Bound(_NodeStep):
    binds = ()

    def missing(self) -> str:
        return f"no node {self.node.var}: {self.node.type} found"


@dataclass(frozen=True)
class Scan(_NodeStep):
    @property
    def binds(self) -> tuple[str, ...]:
        return (self.node.var,)

    def missing(self) -> str:
        return f"no a node {self.node.var}: {self.node.type} found"


@dataclass(frozen=True)
class Extend:
    edge: PatternEdge
    start: str  # bound variable the search leaves from
    end: str  # variable at the other end
    end_node: PatternNode | None  # None when ``end`` is already bound
    forward: bool  # for a directed ("out") edge: start is its source

    @property
    def binds(self) -> tuple[str, ...]:
        return (self.edge.var,) if self.end_node is None else (self.edge.var, self.end)

    @property
    def pos(self):
        return self.edge.pos

    def missing(self) -> str:
        e = self.edge
        arrow = f"-{e.type}->" if e.mode == "out" else f"-{e.type}-"
        name = "" if e.var.startswith("_") else f"{e.var}: "
        return f"no edge {name}{e.source} {arrow} {e.target} found"


@dataclass(frozen=True)
class Check:
    condition: Condition

    binds = ()

    @property
    def pos(self):
        return self.condition.pos

    def missing(self) -> str:
        return f"condition `{self.condition.text}` is false"


Step = Union[Bound, Scan, Extend, Check]  # not `Bound | Scan | ...`: evaluated at import, 3.10+


#: Plans a pattern keeps (the most recently built), by given variables and type counts.
PLANS_PER_PATTERN = 64


def pattern_plan(
    pattern: CompiledPattern, given: frozenset[str], count: Callable[[frozenset[str]], int]
) -> list[Step]:
    """:func:`build_plan`, kept on the pattern (shared: never change it) under what decides it:
    the given variables and the counts of the pattern's node and edge types. Every search makes
    a new :class:`~.matcher.Matcher`, and a strategy run makes one per rule and step, so a search
    that steps through many graph states (exploration, issue 13) built the same plan again and
    again; looking up the counts costs a few of the ``count`` calls that building it makes."""
    key = (given, tuple(count(node.types) for node in pattern.nodes.values()),
           tuple(count(edge.types) for edge in pattern.edges))
    plan = pattern.plans.get(key)
    if plan is None:
        plan = pattern.plans[key] = build_plan(pattern, given, count)
        if len(pattern.plans) > PLANS_PER_PATTERN:
            del pattern.plans[next(iter(pattern.plans))]
    return plan


def build_plan(
    pattern: CompiledPattern, given: frozenset[str], count: Callable[[frozenset[str]], int]
) -> list[Step]:
    """Order the pattern's elements for search, given the variables bound before the search starts.

    ``count(types)`` estimates how many elements have one of ``types`` (the graph's type index).
    """
    bound = set(given)
    steps: list[Step] = []
    conditions = list(pattern.conditions)

    def place_conditions():
        blocked = False  # an earlier-written condition is still waiting for its variables
        for c in list(conditions):
            if c.reads <= bound and (c.column is not None or not blocked):
                steps.append(Check(c))
                conditions.remove(c)
            else:
                blocked = True

    for var, node in pattern.nodes.items():
        if var in given:
            steps.append(Bound(node))
    place_conditions()

    edges = list(pattern.edges)
    while edges or any(v not in bound for v in pattern.nodes):
        closing = [e for e in edges if e.source in bound and e.target in bound]
        if closing:
            e = closing[0]
            steps.append(Extend(e, e.source, e.target, None, True))
            edges.remove(e)
        else:
            leaving = [e for e in edges if e.source in bound or e.target in bound]
            if leaving:
                e = min(leaving, key=lambda e: count(e.types))
                forward = e.source in bound
                start, end = (e.source, e.target) if forward else (e.target, e.source)
                steps.append(Extend(e, start, end, pattern.nodes[end], forward))
                edges.remove(e)
                bound.add(end)
            else:
                free = [v for v in pattern.nodes if v not in bound]
                var = min(free, key=lambda v: count(pattern.nodes[v].types))
                steps.append(Scan(pattern.nodes[var]))
                bound.add(var)
        bound.update(e.var for e in pattern.edges if e not in edges)
        place_conditions()
    place_conditions()
    assert not conditions, f"conditions read unbound variables: {[c.text for c in conditions]}"
    return steps
