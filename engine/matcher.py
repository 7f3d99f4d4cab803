"""Finding matches: injective, typed, with conditions, negative application conditions and DPO.

A :class:`Matcher` runs a rule's search plans (:mod:`.plan`) over a host graph. A *match* binds
every pattern variable to a distinct element of a fitting type such that the inline constraints and
``where`` conditions hold, no NAC can be matched around it, and (for rules that delete nodes) the
dangling condition holds. Matches are ordered by their *key*: the ids bound to the pattern's
variables in declaration order, so "the first match" never depends on hash seeds or insertion order.
"""

from __future__ import annotations

import functools
import itertools
from typing import Iterator, Mapping, NamedTuple, Sequence

import numpy as np

from .checker import CompiledRule
from .columnar import Table, nac_rows, run_columnar
from .errors import RewriteError
from .graph import HostGraph
from .memo import TableMemo
from .plan import Bound, Check, Extend, Scan, Step, pattern_plan
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


class Matches(Sequence):
    """Every match of a rule, sorted by key: the key columns of the match table, each :class:`Match`
    made only when it is read (issue 18: a Match object costs some 20 times its row, and ``first``
    reads one). Equal to a list or tuple of the same matches."""

    __slots__ = ("rule", "vars", "_columns", "_rows")

    #: Rows turned into Python values at a time while iterating.
    BATCH = 4096

    def __init__(self, rule: str, vars: tuple[str, ...], table: Table):
        self.rule, self.vars, self._rows = rule, vars, table.rows
        self._columns = [table.column(v) for v in vars] if table.rows else []

    def __len__(self) -> int:
        return self._rows

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(self._rows))]
        k = i + self._rows if i < 0 else i
        if not 0 <= k < self._rows:
            raise IndexError("match index out of range")
        return Match(self.rule, self.vars, tuple(int(c[k]) for c in self._columns))

    def __iter__(self) -> Iterator[Match]:
        rule, vars = self.rule, self.vars
        return (Match(rule, vars, key) for key in self.keys())

    def keys(self) -> Iterator[tuple]:
        """The key of each match, in order (the rows of the table, as Python ints)."""
        for lo in range(0, self._rows, self.BATCH):
            hi = min(lo + self.BATCH, self._rows)
            columns = [c[lo:hi].tolist() for c in self._columns]
            yield from zip(*columns) if columns else [()] * (hi - lo)

    def bindings(self) -> Iterator[dict[str, int]]:
        """The binding of each match, in order: a new dict each, without making the Match."""
        vars = self.vars
        return (dict(zip(vars, key)) for key in self.keys())

    def __eq__(self, other) -> bool:
        if isinstance(other, (Matches, list, tuple)):
            return len(self) == len(other) and all(a == b for a, b in zip(self, other))
        return NotImplemented

    __hash__ = None

    def __repr__(self) -> str:
        return f"Matches({self.rule}, {len(self)} match(es))"


class Rejection(NamedTuple):
    """Why a complete positive match is refused: the index of a NAC that matches around it, or the
    nodes a plain ``delete`` would leave with edges (the dangling condition), node -> edge ids."""

    nac: int | None = None
    dangling: dict[int, list[int]] | None = None


class Matcher:
    """Matches of one rule in one graph, for given parameter values; with a ``memo``, whole-graph
    searches at a graph state searched before are looked up (:mod:`.memo`)."""

    def __init__(self, rule: CompiledRule, graph: HostGraph, params: Mapping[str, object] | None = None,
                 memo: TableMemo | None = None):
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
        self.memo = memo
        self._memo_key = _memo_key(rule.match_key, self.fixed, self.values) if memo is not None else None

    # -- public ----------------------------------------------------------------------------------

    def all(self) -> "Matches":
        """Every match, sorted by key (a sequence that makes each Match when it is read)."""
        return Matches(self.rule.name, self.rule.key_vars, self.table())

    def table(self) -> Table:
        """Every match as columns (one per pattern variable), sorted by key: the whole-graph search
        (looked up in the memo when this state was searched before)."""
        if self._memo_key is None:
            return self._table()
        key = (self._memo_key, self.graph.state_id())
        table = self.memo.get(key)
        if table is None:
            table = self._table()
            self.memo.put(key, table)
        return table

    def _table(self) -> Table:
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
            table = table.reorder(np.lexsort([table.column(v) for v in reversed(rule.key_vars)]))
        return table

    def first(self) -> Match | None:
        matches = self.all()
        return matches[0] if matches else None

    def count_upto(self, limit: int) -> int:
        """How many matches there are, counting no further than ``limit``: a depth-first search that
        stops at the ``limit``-th match (in no particular order) instead of finding every one."""
        return sum(1 for _ in itertools.islice(self._search(dict(self.fixed)), limit)) if limit > 0 else 0

    def anchored(self, var: str, node: int) -> Iterator[Match]:
        """Matches in which ``var`` is bound to ``node`` (used to re-match near a change)."""
        if var in self.fixed and self.fixed[var] != node:
            return iter(())
        return self._search({**self.fixed, var: node})

    def check(self, binding: Mapping[str, int]) -> bool:
        """Whether a complete binding is (still) a match."""
        given = dict(binding)
        g = self.graph
        for var in self.rule.pattern.nodes:
            if var not in given or not g.has_node(given[var]):
                return False
        for pe in self.rule.pattern.edges:
            if pe.var not in given or not g.has_edge(given[pe.var]):
                return False
        return any(True for _ in self._search(given))

    def still_matches(self, binding: Mapping[str, int]) -> bool:
        """:meth:`check` for a match found in this graph when only creations happened since (no
        element deleted, retyped or set: an ``all`` step of rules that only create). Its elements,
        types and attributes are as they were; when its conditions only test attributes, only its
        NACs may have changed, so only they are searched (none: it still matches)."""
        if not self._attribute_tests_only:
            return self.check(binding)
        return not self.rule.nacs or self.rejection({**self.values, **binding}) is None

    @functools.cached_property
    def _attribute_tests_only(self) -> bool:
        """Whether every condition of the pattern (``where`` and inline) compares an attribute of a
        matched element with parameters and literals (no degree, no function): creations elsewhere
        cannot change it."""
        pattern = self.rule.pattern
        tests = [*pattern.conditions, *(c for n in pattern.nodes.values() for c in n.checks),
                 *(c for e in pattern.edges for c in e.checks)]
        return all(c.column is not None and c.column.types is None for c in tests)

    def scope(self, match: Match) -> dict:
        """Parameter values and bindings: what the rewrite's expressions see."""
        return {**self.values, **match.binding}

    # -- search ----------------------------------------------------------------------------------

    def plan(self, given: frozenset[str]) -> list[Step]:
        plan = self._plans.get(given)
        if plan is None:
            plan = pattern_plan(self.rule.pattern, given | frozenset(self.values), self.graph.count)
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

    def rejection(self, binding: dict) -> Rejection | None:
        """Why a complete positive match is refused, or None when it is a match."""
        for i in range(len(self.rule.nacs)):
            if self.nac_matches(i, binding):
                return Rejection(nac=i)
        if self.rule.deletes_nodes:
            dangling = footprint(self.rule, self.graph, binding).dangling(self.graph)
            if dangling:
                return Rejection(dangling=dangling)
        return None

    def _nac_plan(self, i: int) -> list[Step]:
        while len(self._nac_plans) <= i:
            k = len(self._nac_plans)
            self._nac_plans.append(pattern_plan(self.rule.nacs[k], self.rule.nacs[k].outer, self.graph.count))
        return self._nac_plans[i]

    def nac_matches(self, i: int, binding: dict) -> dict | None:
        """A binding of NAC ``i`` around the complete positive ``binding``, or None when it has none."""
        node_vars, edge_vars = self._pattern_vars
        used_nodes = set(map(binding.__getitem__, node_vars))
        used_edges = set(map(binding.__getitem__, edge_vars))
        plans = self._nac_plans
        plan = plans[i] if i < len(plans) else self._nac_plan(i)
        return next(run_plan(self.graph, plan, dict(binding), used_nodes, used_edges, self.rule.name, {}), None)

    @functools.cached_property
    def _pattern_vars(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The pattern's node variables and edge variables."""
        pattern = self.rule.pattern
        return tuple(pattern.nodes), tuple(e.var for e in pattern.edges)


def _memo_key(rule: str, fixed: dict, values: dict) -> tuple | None:
    """What, beside the graph state, a rule's matches depend on: the rule as written (its
    ``match_key``, shared by the rules written alike) and its parameter values (None when a value
    cannot be hashed: such a matcher does not use the memo)."""
    key = (rule, tuple(sorted(fixed.items())), tuple(sorted(values.items())))
    try:
        hash(key)
    except TypeError:
        return None
    return key


def _row_bindings(table: Table):
    names = [*table.nodes, *table.edges]
    columns = [table.column(v).tolist() for v in names]
    for row in zip(*columns):
        yield dict(zip(names, row))


def run_plan(
    g: HostGraph, plan: list[Step], binding: dict, used_nodes: set, used_edges: set, rule: str, fixed_edges: dict
) -> Iterator[dict]:
    """Execute a plan depth-first, yielding each complete binding (the same dict, mutated).

    ``used_nodes`` and ``used_edges`` are the elements already bound (matching is injective);
    ``fixed_edges`` binds edge variables in advance (pattern variable -> the only edge it may take).
    """
    return _Search(g, plan, binding, used_nodes, used_edges, rule, fixed_edges).run(0)


class _Search:
    """One depth-first run of a plan: the binding being built and, for each kind of step, a generator
    that binds the step's variables in every possible way and continues with the next step."""

    __slots__ = ("g", "node_type", "ends", "typed", "binding", "used_nodes", "used_edges", "rule", "fixed_edges",
                 "steps")

    def __init__(self, g: HostGraph, plan, binding, used_nodes, used_edges, rule: str, fixed_edges: dict):
        self.g = g
        self.node_type, _, self.ends, self.typed = g.incidence
        self.binding, self.used_nodes, self.used_edges = binding, used_nodes, used_edges
        self.rule, self.fixed_edges = rule, fixed_edges
        self.steps = plan

    def run(self, i: int) -> Iterator[dict]:
        """The complete bindings that extend the current one from step ``i`` on."""
        if i == len(self.steps):
            return iter((self.binding,))
        step = self.steps[i]
        return _PHASES[type(step)](self, step, i + 1)

    def holds(self, conditions) -> bool:
        g, binding = self.g, self.binding
        for c in conditions:
            try:
                if not c.fn(g, binding):
                    return False
            except Exception as exc:  # a host function or arithmetic failing on this graph
                raise c.failure(self.rule, exc) from None
        return True

    def bound(self, step: Bound, nxt: int) -> Iterator[dict]:
        """A node given from outside: it must still exist, have a fitting type and pass its checks."""
        pn = step.node
        n = self.binding[pn.var]
        if self.g.has_node(n) and self.node_type[n] in pn.types and self.holds(pn.checks):
            yield from self.run(nxt)

    def scan(self, step: Scan, nxt: int) -> Iterator[dict]:
        """Every unused node of a fitting type, in id order."""
        pn = step.node
        binding, used_nodes = self.binding, self.used_nodes
        for n in sorted(self.g.of_types(pn.types)):
            if n in used_nodes:
                continue
            binding[pn.var] = n
            used_nodes.add(n)
            if self.holds(pn.checks):
                yield from self.run(nxt)
            used_nodes.discard(n)
            del binding[pn.var]

    def check(self, step: Check, nxt: int) -> Iterator[dict]:
        if self.holds((step.condition,)):
            yield from self.run(nxt)

    def extend(self, step: Extend, nxt: int) -> Iterator[dict]:
        """Every unused edge of the pattern edge's types and direction at the bound start node whose
        other end is the bound end node, or an unused node of a fitting type that it then binds."""
        binding, used_nodes, used_edges, ends, node_type = (
            self.binding, self.used_nodes, self.used_edges, self.ends, self.node_type)
        pe, end_node = step.edge, step.end_node
        start = binding[step.start]
        target = None if end_node is not None else binding[step.end]
        checks = pe.checks if end_node is None else end_node.checks + pe.checks
        directed, forward = pe.mode == "out", step.forward
        for e in self.edges_at(pe.var, pe.types, start):
            if e in used_edges:
                continue
            u, v = ends[e]
            if directed:
                if (u if forward else v) != start:
                    continue
                other = v if forward else u
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
            if not checks or self.holds(checks):
                yield from self.run(nxt)
            if target is None:
                used_nodes.discard(other)
                del binding[step.end]
            used_edges.discard(e)
            del binding[pe.var]

    def edges_at(self, var: str, types, start: int) -> list[int]:
        """The edges of ``types`` at node ``start`` (only the one fixed for ``var``, if it is fixed)."""
        wanted = self.fixed_edges.get(var)
        at = self.typed[start]
        out: list[int] = []
        for t in types:
            bucket = at.get(t)
            if bucket:
                if wanted is None:
                    out.extend(bucket)
                elif wanted in bucket:
                    out.append(wanted)
        return out


_PHASES = {Bound: _Search.bound, Scan: _Search.scan, Check: _Search.check, Extend: _Search.extend}
