"""Finding matches: injective, typed, with conditions, negative application conditions and DPO.

A :class:`Matcher` runs a rule's search plans (:mod:`.plan`) over a host graph. A *match* binds
every pattern variable to a distinct element of a fitting type such that the inline constraints and
``where`` conditions hold, no NAC can be matched around it, and (for rules that delete nodes) the
dangling condition holds. Matches are ordered by their *key*: the ids bound to the pattern's
variables in declaration order, so "the first match" never depends on hash seeds or insertion order.
"""

from __future__ import annotations

from typing import Iterator, Mapping

import numpy as np

from .checker import CompiledPattern, CompiledRule, Condition
from .columnar import Table, nac_rows, run_columnar
from .errors import RewriteError
from .graph import HostGraph
from .plan import Check, Extend, Scan, Step, build_plan
from .rewriter import footprint


class Match:
    """A match of a rule: its ordering key (the ids bound to the pattern variables, in declaration
    order) and, derived from it, the binding pattern variable -> element id."""

    __slots__ = ("rule", "vars", "key")

    def __init__(self, rule: str, vars: tuple[str, ...], key: tuple):
        self.rule = rule
        self.vars = vars
        self.key = key

    @property
    def binding(self) -> dict[str, int]:
        return dict(zip(self.vars, self.key))

    def __eq__(self, other) -> bool:
        return isinstance(other, Match) and (self.rule, self.vars, self.key) == (other.rule, other.vars, other.key)

    def __hash__(self) -> int:
        return hash((self.rule, self.key))

    def __repr__(self) -> str:
        return f"Match({self.rule}, {self.binding})"


class Matcher:
    """Matches of one rule in one graph, for given parameter values."""

    def __init__(self, rule: CompiledRule, graph: HostGraph, params: Mapping[str, object] | None = None):
        self.rule = rule
        self.graph = graph
        params = dict(params or {})
        unknown = set(params) - set(rule.params)
        if unknown:
            raise RewriteError(f"rule {rule.name} has no parameter(s) {', '.join(sorted(unknown))}")
        self.values = {**rule.defaults, **{k: v for k, v in params.items() if k not in rule.node_params}}
        self.fixed = {k: v for k, v in params.items() if k in rule.node_params}
        missing = [p for p in rule.params if p not in rule.node_params and p not in self.values]
        if missing:
            raise RewriteError(f"rule {rule.name}: parameter(s) {', '.join(missing)} need a value")
        for name, node in self.fixed.items():
            if not graph.has_node(node):
                raise RewriteError(f"rule {rule.name}: parameter {name} = {node} is not a node of the graph")
        self._plans: dict[frozenset[str], list[Step]] = {}
        self._nac_plans: list[list[Step]] = []

    # -- public ----------------------------------------------------------------------------------

    def all(self) -> list[Match]:
        """Every match, sorted by key."""
        table = self.table()
        if table.rows == 0:
            return []
        key_vars = self.rule.key_vars
        columns = [table.column(v).tolist() for v in key_vars]
        keys = zip(*columns) if columns else [()] * table.rows
        return [Match(self.rule.name, key_vars, key) for key in keys]

    def table(self) -> Table:
        """Every match as columns (one per pattern variable), sorted by key: the whole-graph search."""
        rule = self.rule
        plan = self.plan(frozenset(self.fixed))
        table = run_columnar(self.graph, plan, Table.start(self.fixed), self.values, rule.name)
        for i in range(len(rule.nacs)):
            if table.rows:
                table = table.filter(~nac_rows(self.graph, self._nac_plan(i), table, self.values, rule.name))
        if rule.deletes_nodes and table.rows:
            keep = [
                not footprint(rule, self.graph, {**self.values, **binding}).dangling(self.graph)
                for binding in _row_bindings(table)
            ]
            table = table.filter(np.array(keep, dtype=bool))
        if rule.key_vars and table.rows > 1:
            table = table.take(np.lexsort([table.column(v) for v in reversed(rule.key_vars)]))
        return table

    def first(self) -> Match | None:
        matches = self.all()
        return matches[0] if matches else None

    def anchored(self, var: str, node: int) -> Iterator[Match]:
        """Matches in which ``var`` is bound to ``node`` (used to re-match near a change)."""
        if var in self.fixed and self.fixed[var] != node:
            return iter(())
        return self._search({**self.fixed, var: node})

    def check(self, binding: Mapping[str, int]) -> bool:
        """Whether a complete binding is (still) a match."""
        given = dict(binding)
        g = self.graph
        for var, pn in self.rule.pattern.nodes.items():
            if var not in given or not g.has_node(given[var]):
                return False
        for pe in self.rule.pattern.edges:
            if pe.var not in given or not g.has_edge(given[pe.var]):
                return False
        return any(True for _ in self._search(given))

    def scope(self, match: Match) -> dict:
        """Parameter values and bindings: what the rewrite's expressions see."""
        return {**self.values, **match.binding}

    # -- search ----------------------------------------------------------------------------------

    def plan(self, given: frozenset[str]) -> list[Step]:
        plan = self._plans.get(given)
        if plan is None:
            plan = build_plan(self.rule.pattern, given | frozenset(self.values), self.graph.count)
            self._plans[given] = plan
        return plan

    def _search(self, given: dict) -> Iterator[Match]:
        pattern = self.rule.pattern
        node_vars = frozenset(v for v in given if v in pattern.nodes)
        edge_vars = {v: given[v] for v in given if v not in pattern.nodes}
        plan = self.plan(node_vars)
        binding = {**self.values, **{v: given[v] for v in node_vars}}
        used_nodes = set(binding[v] for v in node_vars)
        if len(used_nodes) != len(node_vars):
            return
        key_vars = self.rule.key_vars
        for b in run_plan(self.graph, plan, binding, used_nodes, set(), self.rule.name, edge_vars):
            if self._accept(b):
                yield Match(self.rule.name, key_vars, tuple(b[v] for v in key_vars))

    def _accept(self, binding: dict) -> bool:
        if not self.rule.nacs and not self.rule.deletes_nodes:
            return True
        return self.rejection(binding) is None

    def rejection(self, binding: dict) -> tuple[str, object] | None:
        """Why a complete positive match is refused: ("nac", index) or ("dangling", {node: edges})."""
        for i, nac in enumerate(self.rule.nacs):
            if self.nac_matches(i, nac, binding):
                return ("nac", i)
        if self.rule.deletes_nodes:
            dangling = footprint(self.rule, self.graph, binding).dangling(self.graph)
            if dangling:
                return ("dangling", dangling)
        return None

    def _nac_plan(self, i: int) -> list[Step]:
        while len(self._nac_plans) <= i:
            k = len(self._nac_plans)
            self._nac_plans.append(build_plan(self.rule.nacs[k], self.rule.nacs[k].outer, self.graph.count))
        return self._nac_plans[i]

    def nac_matches(self, i: int, nac: CompiledPattern, binding: dict) -> dict | None:
        self._nac_plan(i)
        used_nodes = {binding[v] for v in self.rule.pattern.nodes}
        used_edges = {binding[e.var] for e in self.rule.pattern.edges}
        for b in run_plan(self.graph, self._nac_plans[i], dict(binding), used_nodes, used_edges, self.rule.name, {}):
            return b
        return None


def _row_bindings(table: Table):
    names = [*table.nodes, *table.edges]
    columns = [table.column(v).tolist() for v in names]
    for row in zip(*columns):
        yield dict(zip(names, row))


def run_plan(
    g: HostGraph, plan: list[Step], binding: dict, used_nodes: set, used_edges: set, rule: str, fixed_edges: dict
) -> Iterator[dict]:
    """Execute a plan depth-first, yielding each complete binding (the same dict, mutated)."""
    n_steps = len(plan)
    node_type = g._node_type
    ends = g._ends
    inc = g._inc

    def holds(c: Condition) -> bool:
        try:
            return bool(c.fn(g, binding))
        except Exception as exc:  # a host function or arithmetic failing on this graph
            raise RewriteError(f"rule {rule}: {c.pos}: evaluating `{c.text}` failed: {exc!r}") from None

    def go(i: int) -> Iterator[dict]:
        if i == n_steps:
            yield binding
            return
        step = plan[i]
        if isinstance(step, Extend):
            pe = step.edge
            start = binding[step.start]
            wanted = fixed_edges.get(pe.var)
            end_node = step.end_node
            target = None if end_node is not None else binding[step.end]
            start_inc = inc[start]
            for t in pe.types:
                bucket = start_inc.get(t)
                if not bucket:
                    continue
                for e in list(bucket) if wanted is None else ([wanted] if wanted in bucket else []):
                    if e in used_edges:
                        continue
                    u, v = ends[e]
                    if pe.mode == "out":
                        if step.forward:
                            if u != start:
                                continue
                            other = v
                        else:
                            if v != start:
                                continue
                            other = u
                    else:
                        other = v if u == start else u
                    if target is not None:
                        if other != target:
                            continue
                    elif other in used_nodes or node_type[other] not in end_node.types:
                        continue
                    binding[pe.var] = e
                    used_edges.add(e)
                    if target is None:
                        binding[step.end] = other
                        used_nodes.add(other)
                        if all(holds(c) for c in end_node.checks) and all(holds(c) for c in pe.checks):
                            yield from go(i + 1)
                        used_nodes.discard(other)
                        del binding[step.end]
                    elif all(holds(c) for c in pe.checks):
                        yield from go(i + 1)
                    used_edges.discard(e)
                    del binding[pe.var]
        elif isinstance(step, Check):
            if holds(step.condition):
                yield from go(i + 1)
        elif isinstance(step, Scan):
            pn = step.node
            for n in sorted(g.of_types(pn.types)):
                if n in used_nodes:
                    continue
                binding[pn.var] = n
                used_nodes.add(n)
                if all(holds(c) for c in pn.checks):
                    yield from go(i + 1)
                used_nodes.discard(n)
                del binding[pn.var]
        else:  # Bound
            pn = step.node
            n = binding[pn.var]
            if g.has_node(n) and node_type[n] in pn.types and all(holds(c) for c in pn.checks):
                yield from go(i + 1)

    yield from go(0)
