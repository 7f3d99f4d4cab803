"""Applying a rule to a match: the rewrite, done as one transaction.

Semantics (documented in docs/language.md):

* statements run in their written order, and every expression sees the graph as matched plus the
  elements the rule has created so far;
* deletions happen last (edges, then merges, then nodes), so expressions may still read what is
  deleted; a plain ``delete`` of a node is double-pushout: the match is refused beforehand when the
  node has edges the rule does not delete (the *dangling condition*, see :func:`footprint`);
  ``detach delete`` removes the remaining edges too;
* ``merge a into b`` moves a's edges to b (keeping their ids and attributes; edges between a and b
  disappear) and deletes a;
* ``foreach`` iterates over the center's edges of the given type in rotation order; first the body's
  node creations run for every iteration, then the other statements, so that ``next(r)`` and
  ``prev(r)`` can name the node created in the cyclically next or previous iteration.

If anything fails (a schema violation, a host function raising), the graph is rolled back exactly
and a :class:`RewriteError` names the rule and the statement.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

from .checker import CCreateEdge, CCreateNode, CDelete, CForeach, CMerge, CompiledRule, CRetype, CSet, End
from .errors import RewriteError, SchemaError, SelfLoop
from .graph import HostGraph


@dataclass
class Footprint:
    """The elements an application will delete or change (computed before applying it)."""

    deleted_nodes: set[int] = field(default_factory=set)
    detached_nodes: set[int] = field(default_factory=set)
    deleted_edges: set[int] = field(default_factory=set)
    changed_nodes: set[int] = field(default_factory=set)
    changed_edges: set[int] = field(default_factory=set)

    def writes(self) -> set[tuple[str, int]]:
        nodes = self.deleted_nodes | self.detached_nodes | self.changed_nodes
        edges = self.deleted_edges | self.changed_edges
        return {("n", n) for n in nodes} | {("e", e) for e in edges}

    def dangling(self, graph: HostGraph) -> dict[int, list[int]]:
        """Nodes deleted by a plain ``delete`` that keep edges the rule does not delete."""
        out = {}
        for n in sorted(self.deleted_nodes):
            left = sorted(e for e in graph.incident(n) if e not in self.deleted_edges)
            if left:
                out[n] = left
        return out


@dataclass
class Application:
    """The record of one rule application (the unit of traces and undo)."""

    rule: str
    params: dict
    binding: dict
    created_nodes: list[int]
    created_edges: list[int]
    deleted_nodes: list[int]
    deleted_edges: list[int]
    mark: int  # journal position before the application: graph.rollback(mark) undoes it
    retyped: list = field(default_factory=list)  # [node, old type, new type]
    set: list = field(default_factory=list)  # [kind ("node" or "edge"), id, attribute, value]
    choice: int | None = None  # the option a chooser took at a choose step


class Iteration(NamedTuple):
    """One iteration of a ``foreach``: the edge and the neighbour it reaches."""

    edge: int
    neighbour: int


def foreach_iterations(graph: HostGraph, stmt: CForeach, scope: dict) -> list[Iteration]:
    """The iterations of a foreach, in the rotation order around its center."""
    center = scope[stmt.center]
    out = []
    for e in graph.rotation(center):
        if graph.edge_type(e) not in stmt.types:
            continue
        u, v = graph.ends(e)
        if stmt.direction == "->" and u != center or stmt.direction == "<-" and v != center:
            continue
        n = v if u == center else u
        if stmt.neighbour_types is not None and graph.node_type(n) not in stmt.neighbour_types:
            continue
        if stmt.condition is not None:
            inner = {**scope, stmt.edge_var: e, stmt.neighbour: n}
            if not stmt.condition.fn(graph, inner):
                continue
        out.append(Iteration(e, n))
    return out


def _iteration_scopes(graph: HostGraph, stmt: CForeach, scope: dict) -> list[dict]:
    """The scope of each iteration of a foreach: ``scope`` with its edge and neighbour bound."""
    return [{**scope, stmt.edge_var: e, stmt.neighbour: n} for e, n in foreach_iterations(graph, stmt, scope)]


def footprint(rule: CompiledRule, graph: HostGraph, scope: dict) -> Footprint:
    """What applying ``rule`` with this binding (and parameter values) would delete or change."""
    fp = Footprint()
    _collect(rule.statements, graph, scope, fp)
    return fp


def _collect(statements, graph: HostGraph, scope: dict, fp: Footprint) -> None:
    for s in statements:
        collect = _FOOTPRINTS.get(type(s))
        if collect is not None:
            collect(s, graph, scope, fp)


def _delete_footprint(s: CDelete, graph: HostGraph, scope: dict, fp: Footprint) -> None:
    for var in s.vars:
        if var not in scope:
            continue
        if var in s.node_vars:
            (fp.detached_nodes if s.detach else fp.deleted_nodes).add(scope[var])
        else:
            fp.deleted_edges.add(scope[var])


def _retype_footprint(s: CRetype, graph: HostGraph, scope: dict, fp: Footprint) -> None:
    if s.var in scope:
        fp.changed_nodes.add(scope[s.var])


def _set_footprint(s: CSet, graph: HostGraph, scope: dict, fp: Footprint) -> None:
    if s.var in scope:
        (fp.changed_nodes if s.kind == "node" else fp.changed_edges).add(scope[s.var])


def _merge_footprint(s: CMerge, graph: HostGraph, scope: dict, fp: Footprint) -> None:
    fp.changed_nodes.update(scope[v] for v in (s.source, s.target) if v in scope)


def _foreach_footprint(s: CForeach, graph: HostGraph, scope: dict, fp: Footprint) -> None:
    for inner in _iteration_scopes(graph, s, scope):
        _collect(s.body, graph, inner, fp)


#: What each kind of statement adds to a footprint (creations add nothing).
_FOOTPRINTS = {
    CDelete: _delete_footprint,
    CRetype: _retype_footprint,
    CSet: _set_footprint,
    CMerge: _merge_footprint,
    CForeach: _foreach_footprint,
}


def only_creates(statements) -> bool:
    """Whether statements (foreach bodies included) only create: then every footprint is empty, so
    an ``all`` step need not compute footprints to keep its matches independent."""
    return all(isinstance(s, (CCreateNode, CCreateEdge)) or (isinstance(s, CForeach) and only_creates(s.body))
               for s in statements)


class _Run:
    """The state of one application while its statements execute.

    Each statement is run by the method the table ``_STATEMENTS`` names for its class, with the scope
    (variables -> ids, parameters -> values) and, inside a foreach, the scopes of the cyclically next
    and previous iterations (for ``next(v)`` and ``prev(v)``).
    """

    __slots__ = ("rule", "graph", "created_nodes", "created_edges", "delete_edges", "delete_nodes", "merges",
                 "retyped", "set")

    def __init__(self, rule: CompiledRule, graph: HostGraph):
        self.rule = rule
        self.graph = graph
        self.created_nodes: list[int] = []
        self.created_edges: list[int] = []
        self.delete_edges: list[int] = []
        self.delete_nodes: list[tuple[int, bool]] = []  # (node, detach)
        self.merges: list[tuple[int, int]] = []  # (merged node, node it is merged into)
        self.retyped: list = []
        self.set: list = []

    def execute(self, statements, scope: dict, neighbours: tuple[dict, dict] | None = None) -> None:
        for s in statements:
            self._STATEMENTS[type(s)](self, s, scope, neighbours)

    def create_node(self, s: CCreateNode, scope: dict, neighbours) -> None:
        if s.var not in scope:  # already created in a foreach's first pass
            g = self.graph
            scope[s.var] = g.add_node(s.type, {name: fn(g, scope) for name, fn in s.attrs})
            self.created_nodes.append(scope[s.var])

    def create_edge(self, s: CCreateEdge, scope: dict, neighbours) -> None:
        g = self.graph
        u = self.endpoint(s.source, scope, neighbours)
        v = self.endpoint(s.target, scope, neighbours)
        if u == v:  # next(r) of a foreach with one iteration, say: the rule does not apply here
            raise SelfLoop(f"rule {self.rule.name} ({s.pos}): would join node {u} to itself; not applied")
        e = g.add_edge(s.type, u, v, {name: fn(g, scope) for name, fn in s.attrs})
        self.created_edges.append(e)
        if s.var:
            scope[s.var] = e

    def retype(self, s: CRetype, scope: dict, neighbours) -> None:
        self.retyped.append([scope[s.var], self.graph.node_type(scope[s.var]), s.type])
        self.graph.retype(scope[s.var], s.type)

    def set_attr(self, s: CSet, scope: dict, neighbours) -> None:
        g = self.graph
        value = s.value(g, scope)
        self.set.append([s.kind, scope[s.var], s.attr, value])
        if s.kind == "node":
            g.set_node_attr(scope[s.var], s.attr, value)
        else:
            g.set_edge_attr(scope[s.var], s.attr, value)

    def merge(self, s: CMerge, scope: dict, neighbours) -> None:
        self.merges.append((scope[s.source], scope[s.target]))

    def delete(self, s: CDelete, scope: dict, neighbours) -> None:
        for var in s.vars:
            if var in s.node_vars:
                self.delete_nodes.append((scope[var], s.detach))
            else:
                self.delete_edges.append(scope[var])

    def foreach(self, s: CForeach, scope: dict, neighbours) -> None:
        scopes = _iteration_scopes(self.graph, s, scope)
        creations = [c for c in s.body if isinstance(c, CCreateNode)]
        for inner in scopes:
            for c in creations:
                self.create_node(c, inner, None)
        k = len(scopes)
        for i, inner in enumerate(scopes):
            self.execute(s.body, inner, (scopes[(i + 1) % k], scopes[(i - 1) % k]))

    _STATEMENTS = {
        CCreateNode: create_node,
        CCreateEdge: create_edge,
        CRetype: retype,
        CSet: set_attr,
        CMerge: merge,
        CDelete: delete,
        CForeach: foreach,
    }

    @staticmethod
    def endpoint(ref: End, scope: dict, neighbours) -> int:
        if ref.step == 0:
            return scope[ref.var]
        return (neighbours[0] if ref.step > 0 else neighbours[1])[ref.var]

    def finish(self) -> tuple[list[int], list[int]]:
        """Run the deferred deletions and merges; return the deleted node and edge ids."""
        if not (self.delete_edges or self.merges or self.delete_nodes):  # a rule that only creates or sets
            return [], []
        deleted_edges = self._delete_edges()
        deleted_nodes = self._merge_nodes(deleted_edges)
        self._delete_nodes(deleted_nodes, deleted_edges)
        return deleted_nodes, deleted_edges

    def _delete_edges(self) -> list[int]:
        g = self.graph
        deleted: list[int] = []
        for e in dict.fromkeys(self.delete_edges):
            if g.has_edge(e):
                g.remove_edge(e)
                deleted.append(e)
        return deleted

    def _merge_nodes(self, deleted_edges: list[int]) -> list[int]:
        """Move each merged node's edges (same ids) to its target, dropping those between the two."""
        g = self.graph
        deleted: list[int] = []
        for a, b in self.merges:
            for e in g.rotation(a):
                u, v = g.ends(e)
                type_name, attrs = g.edge_type(e), dict(g.edge_attrs(e))
                g.remove_edge(e)
                if b in (u, v):
                    deleted_edges.append(e)
                    continue
                g.add_edge(type_name, b if u == a else u, b if v == a else v, attrs, id=e)
            g.remove_node(a)
            deleted.append(a)
        return deleted

    def _delete_nodes(self, deleted_nodes: list[int], deleted_edges: list[int]) -> None:
        g = self.graph
        for n, detach in dict.fromkeys(self.delete_nodes):
            if not g.has_node(n):
                continue
            if detach:
                for e in g.rotation(n):
                    g.remove_edge(e)
                    deleted_edges.append(e)
            g.remove_node(n)
            deleted_nodes.append(n)


def apply_rule(rule: CompiledRule, graph: HostGraph, binding: dict, values: dict,
               params: dict | None = None) -> Application:
    """Apply ``rule`` at a match (``binding``: pattern variable -> element id, kept by the returned
    record) with parameter ``values``; the record's ``params`` are ``params`` (a copy of ``values``
    when None).

    The caller is responsible for the match being valid (see :class:`~.matcher.Matcher`). On any
    failure the graph is left exactly as it was and a :class:`RewriteError` is raised; a
    :class:`SelfLoop` when the application would join a node to itself (the rule does not apply at
    that match). The rollback is :meth:`HostGraph.transaction`'s, spelled out: the context manager
    cost a tenth of an application of a rule that adds one edge (issue 18).
    """
    mark = graph.mark()
    run = _Run(rule, graph)
    scope = {**values, **binding}
    try:
        try:
            run.execute(rule.statements, scope)
            deleted_nodes, deleted_edges = run.finish()
        except BaseException:
            graph.rollback(mark)
            raise
    except SelfLoop:
        raise
    except SchemaError as exc:
        raise RewriteError(f"rule {rule.name} ({rule.source.pos}): {exc}") from None
    except (ArithmeticError, TypeError, ValueError, KeyError, IndexError) as exc:
        raise RewriteError(f"rule {rule.name} ({rule.source.pos}): evaluating the rewrite failed: {exc!r}") from None
    return Application(
        rule=rule.name,
        params=dict(values) if params is None else params,
        binding=binding,
        created_nodes=run.created_nodes,
        created_edges=run.created_edges,
        deleted_nodes=deleted_nodes,
        deleted_edges=deleted_edges,
        mark=mark,
        retyped=run.retyped,
        set=run.set,
    )
