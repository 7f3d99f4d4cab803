"""Static checking: turn a parsed rule into a :class:`CompiledRule`, or report what is wrong and where.

Everything that can be known before touching a graph is checked here, when the rule file is loaded:
unknown types, attributes, functions and variables; pattern edges whose endpoint types can never fit
the edge type; creations of abstract types or with missing attributes; ``next``/``prev`` outside
``foreach``; values of the wrong type. Each error is a :class:`RuleTypeError` with file:line:col.

The compiled rule also carries what the engine needs to re-match incrementally: the types the rule
reads, and how far from a change a match can be affected (its *radius*).
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass, field
from typing import Callable, NamedTuple

from vaultgram.grammar import ast

from .errors import RewriteError, RuleTypeError, did_you_mean
from .expressions import _COMPARISONS, ANY, TYPE, Compiled, ExpressionCompiler, Symbol, VType, graph_degree, walk
from .schema import TypeSchema
from .values import VALUE_TYPES, storable, value_conforms

# ----------------------------------------------------------------------------------------------
# Compiled forms
# ----------------------------------------------------------------------------------------------


class ColumnTest(NamedTuple):
    """A condition ``degree(var, Types) op rhs`` or ``var.attr op rhs`` (``rhs`` reading only
    parameters and literals), in the form the whole-graph matcher evaluates for a whole column of
    matches at once: ``types`` for a degree, ``attr`` (and ``kind``, node or edge) for an attribute."""

    var: str
    op: Callable[[object, object], object]
    rhs: Compiled
    types: frozenset | None = None
    attr: str | None = None
    kind: str = "node"


@dataclass(frozen=True)
class Condition:
    """A compiled boolean test with the variables it reads and where it was written; ``column`` is
    its vectorised form when it has one."""

    fn: Compiled
    reads: frozenset[str]
    text: str
    pos: object
    column: ColumnTest | None = None
    operands: tuple[tuple[object, Compiled], ...] = ()  # its attributes and calls, for why-not reports

    def values(self, graph, binding) -> dict[str, object]:
        """The value of each attribute and function call in the condition at ``binding``, by its text
        (the first of those written alike; those that cannot be evaluated there are left out): what a
        why-not report shows. The texts are rendered here, not when the rule is compiled: most
        conditions never need them."""
        out = {}
        for sub, fn in self.operands:
            text = describe(sub)
            if text in out:
                continue
            try:
                out[text] = fn(graph, binding)
            except Exception:  # noqa: BLE001 - a report must not fail where the condition itself would
                continue
        return out

    def failure(self, rule: str, exc: Exception) -> RewriteError:
        """The error to raise when evaluating the test raised ``exc`` (a host function or arithmetic
        failing on this graph)."""
        return RewriteError(f"rule {rule}: {self.pos}: evaluating `{self.text}` failed: {exc!r}")


@dataclass(frozen=True)
class PatternNode:
    var: str
    type: str
    types: frozenset[str]
    checks: tuple[Condition, ...]
    pos: object


@dataclass(frozen=True)
class PatternEdge:
    """An edge of a pattern; ``mode`` is ``"out"`` (source -> target) or ``"any"`` (either direction)."""

    var: str
    source: str
    target: str
    type: str
    types: frozenset[str]
    mode: str
    checks: tuple[Condition, ...]
    pos: object


@dataclass
class CompiledPattern:
    """Nodes, edges and conditions of a ``match`` or ``not`` block; ``outer`` are variables bound before it."""

    nodes: dict[str, PatternNode]
    edges: list[PatternEdge]
    conditions: list[Condition]
    outer: frozenset[str]
    pos: object
    plans: dict = field(default_factory=dict, compare=False, repr=False)  # kept by :func:`.plan.pattern_plan`

    @property
    def variables(self) -> list[str]:
        return [*self.nodes, *(e.var for e in self.edges)]


@dataclass(frozen=True)
class CDelete:
    vars: tuple[str, ...]
    detach: bool
    node_vars: tuple[str, ...]
    pos: object


@dataclass(frozen=True)
class CCreateNode:
    var: str
    type: str
    attrs: tuple[tuple[str, Compiled], ...]
    pos: object


class End(NamedTuple):
    """An endpoint of a created edge: a variable, in this iteration of the enclosing foreach (step 0),
    the next one (+1, ``next(v)``) or the previous one (-1, ``prev(v)``)."""

    var: str
    step: int


@dataclass(frozen=True)
class CCreateEdge:
    var: str | None
    source: End
    target: End
    type: str
    attrs: tuple[tuple[str, Compiled], ...]
    pos: object


@dataclass(frozen=True)
class CRetype:
    var: str
    type: str
    pos: object


@dataclass(frozen=True)
class CSet:
    var: str
    kind: str  # "node" or "edge"
    attr: str
    value: Compiled
    pos: object


@dataclass(frozen=True)
class CMerge:
    source: str
    target: str
    pos: object


@dataclass(frozen=True)
class CForeach:
    edge_var: str
    center: str
    neighbour: str
    types: frozenset[str]
    direction: str
    condition: Condition | None
    body: tuple
    pos: object
    neighbour_types: frozenset | None = None  # `foreach c -T- n: Type`: only neighbours of these types


@dataclass
class CompiledRule:
    """A checked rule, ready for matching and rewriting."""

    name: str
    params: dict[str, ast.Param]
    node_params: dict[str, str]  # node-typed parameters: name -> type
    defaults: dict[str, object]
    priority: int
    pattern: CompiledPattern
    nacs: list[CompiledPattern]
    statements: tuple
    reads_types: frozenset[str]
    radius: int | None  # None: any change anywhere may matter (re-match the whole graph)
    deletes_nodes: bool
    source: ast.Rule
    key_vars: tuple[str, ...] = field(default=())
    match_key: str = field(default="", compare=False)  # the first rule written alike (match_key)


# ----------------------------------------------------------------------------------------------
# Checking
# ----------------------------------------------------------------------------------------------


def match_key(rule: ast.Rule, deletes_nodes: bool) -> tuple:
    """What a rule's matches depend on, as written: its parameters, its match block and its NACs
    (and its statements when it deletes nodes, since a match that would leave an edge dangling is
    dropped), without its name, priority or source positions. Rules of one rulebook with the same
    key find the same matches in every graph, so a memo of match tables can share them (two rules
    written alike, one taking the match the other leaves, as a choice point's options): a compiled
    rule's ``match_key`` names the first rule of its rulebook with its key."""
    return (written(rule.params), written(rule.match), written(rule.nacs),
            written(rule.statements) if deletes_nodes else None)


def written(node) -> object:
    """An AST value as nested tuples of its node kinds and fields, its source positions left out."""
    if isinstance(node, (tuple, list)):
        return tuple(written(item) for item in node)
    names = _compared_fields(type(node))
    if names is None:
        return node
    return (type(node).__name__, *(written(getattr(node, name)) for name in names))


@functools.lru_cache(maxsize=None)
def _compared_fields(kind: type) -> tuple[str, ...] | None:
    """The fields :func:`written` keeps of an AST node class (those compared, but its position), or None
    for a class that is not a dataclass (a value kept as it is). Once per class: a rulebook's match keys
    ask thousands of times."""
    if not dataclasses.is_dataclass(kind):
        return None
    return tuple(f.name for f in dataclasses.fields(kind) if f.compare and f.name != "pos")


class RuleChecker:
    """Checks and compiles the rules of a rulebook against its schema and function registry."""

    def __init__(self, schema: TypeSchema, compiler: ExpressionCompiler):
        self.schema = schema
        self.compiler = compiler
        self.type_symbols = {
            name: Symbol(TYPE, schema.subtypes(name)) for name in (*schema.node_types, *schema.edge_types)
        }
        self._match_keys: dict[tuple, str] = {}  # match_key -> the first rule compiled with it

    def compile_rule(self, rule: ast.Rule) -> CompiledRule:
        self._created = set()
        scope = dict(self.type_symbols)
        params = {p.name: p for p in rule.params}
        node_params, defaults = self._params(rule.params, scope)
        pattern = self._pattern(rule.match, scope, frozenset(params), node_params)
        outer = frozenset({*pattern.variables, *params})
        nacs = [self._pattern(nac, dict(scope), outer, {}) for nac in rule.nacs]
        statements = self._statements(rule.statements, scope, None)
        deletes_nodes = any(isinstance(s, CDelete) and s.node_vars and not s.detach for s in flatten(statements))
        compiled = CompiledRule(
            name=rule.name,
            params=params,
            node_params=node_params,
            defaults=defaults,
            priority=rule.priority,
            pattern=pattern,
            nacs=nacs,
            statements=statements,
            reads_types=frozenset(),
            radius=0,
            deletes_nodes=deletes_nodes,
            source=rule,
            key_vars=tuple(pattern.variables),
            match_key=self._match_keys.setdefault(match_key(rule, deletes_nodes), rule.name),
        )
        compiled.reads_types = self._reads_types(rule, compiled)
        compiled.radius = self._radius(rule, compiled)
        return compiled

    def _params(self, params, scope: dict) -> tuple[dict[str, str], dict[str, object]]:
        """Put the rule's parameters in scope; return its node parameters (name -> type) and the
        values of its value parameters' defaults."""
        node_params: dict[str, str] = {}
        defaults: dict[str, object] = {}
        for p in params:
            self._fresh(p.name, scope, p.pos)
            if self.schema.is_node_type(p.type):
                node_params[p.name] = p.type
                scope[p.name] = Symbol(VType("node", p.type))
                if p.default is not None:
                    raise RuleTypeError(f"node parameter '{p.name}' cannot have a default", p.pos)
            elif p.type in VALUE_TYPES:
                scope[p.name] = Symbol(VType("value", p.type))
                if p.default is not None:
                    value = self.compiler.compile(p.default, self.type_symbols).fn(None, {})
                    if not value_conforms(value, p.type):
                        raise RuleTypeError(f"default of parameter '{p.name}' must be {p.type}", p.default.pos)
                    defaults[p.name] = value
            else:
                raise RuleTypeError(
                    f"parameter '{p.name}': unknown type '{p.type}'",
                    p.pos,
                    did_you_mean(p.type, [*VALUE_TYPES, *self.schema.node_types]),
                )
        return node_params, defaults

    # -- patterns --------------------------------------------------------------------------------

    def _pattern(self, pat: ast.Pattern, scope: dict, outer: frozenset, node_params: dict) -> CompiledPattern:
        nodes: dict[str, PatternNode] = {}
        for name, type_name in node_params.items():
            nodes[name] = PatternNode(name, type_name, self.schema.subtypes(type_name), (), pat.pos)
        for n in pat.nodes:
            self._fresh(n.var, scope, n.pos)
            self._node_type(n.type, n.pos)
            scope[n.var] = Symbol(VType("node", n.type))
        for n in pat.nodes:
            checks = tuple(self._constraint(c, n.var, scope) for c in n.constraints)
            nodes[n.var] = PatternNode(n.var, n.type, self.schema.subtypes(n.type), checks, n.pos)

        edges = [self._pattern_edge(e, f"_edge{len(outer)}_{k}", scope) for k, e in enumerate(pat.edges)]
        for i, e in enumerate(pat.edges):
            if e.constraints:
                scope_var = edges[i].var
                if not e.var:
                    scope[scope_var] = Symbol(VType("edge", e.type))
                checks = tuple(self._constraint(c, scope_var, scope) for c in e.constraints)
                edges[i] = PatternEdge(**{**edges[i].__dict__, "checks": checks})
        conditions = [self._condition(c, scope) for expr in pat.conditions for c in conjuncts(expr)]
        return CompiledPattern(nodes, edges, conditions, outer, pat.pos)

    def _pattern_edge(self, e: ast.EdgePattern, anonymous: str, scope: dict) -> PatternEdge:
        """An edge of a pattern, without its constraints (they may name edges declared after it);
        an anonymous edge gets the variable name ``anonymous``."""
        info = self._edge_type(e.type, e.pos)
        for end in (e.source, e.target):
            sym = scope.get(end)
            if sym is None or sym.type.kind != "node":
                raise RuleTypeError(
                    f"'{end}' is not a node of the pattern",
                    e.pos,
                    f"declare it first, e.g. `{end}: {info.source}`",
                )
        if e.source == e.target:
            raise RuleTypeError("an edge pattern cannot join a node to itself", e.pos)
        if e.directed and not info.directed:
            raise RuleTypeError(f"edge type {e.type} is undirected: write {e.source} -{e.type}- {e.target}", e.pos)
        self._check_endpoint_fit(e, info, scope)
        if e.var:
            self._fresh(e.var, scope, e.pos)
            scope[e.var] = Symbol(VType("edge", e.type))
        types = self.schema.subtypes(e.type)
        if e.directed:
            types = frozenset(t for t in types if self.schema.edge_types[t].directed)
        mode = "out" if e.directed else "any"
        return PatternEdge(e.var or anonymous, e.source, e.target, e.type, types, mode, (), e.pos)

    def _check_endpoint_fit(self, e: ast.EdgePattern, info, scope) -> None:
        s_type = scope[e.source].type.name
        t_type = scope[e.target].type.name
        fits = self.schema.endpoints_fit(e.type, s_type, t_type, could=True)
        if not fits and not e.directed and info.directed:  # -T- on a directed type: either direction
            fits = self.schema.endpoints_fit(e.type, t_type, s_type, could=True)
        if not fits:
            arrow = "->" if info.directed else "--"
            raise RuleTypeError(
                f"edge {e.type} joins {info.source} {arrow} {info.target}; "
                f"{e.source}: {s_type} and {e.target}: {t_type} can never fit it",
                e.pos,
            )

    def _constraint(self, c: ast.Constraint, var: str, scope) -> Condition:
        expr = ast.Binary(c.op, ast.Attr(ast.Name(var, c.pos), c.attr, c.pos), c.value, c.pos)
        return self._condition(expr, scope, text=f"{var}.{c.attr} {c.op} ...")

    def _condition(self, expr, scope, text: str | None = None) -> Condition:
        compiled, parts = self.compiler.compile_parts(expr, scope)
        bound = _quantified(expr)  # the attributes and calls outside quantifiers (shown when it fails)
        operands = tuple((sub, parts[id(sub)].fn) for sub in walk(expr)
                         if isinstance(sub, (ast.Attr, ast.Call)) and id(sub) not in bound)
        return Condition(compiled.fn, compiled.reads, text or describe(expr), expr.pos,
                         self._column_test(expr, scope, parts), operands)

    def _column_test(self, expr, scope, parts: dict) -> ColumnTest | None:
        """The vectorised form of ``degree(var, Types) op rhs`` or ``var.attr op rhs``, if ``expr`` is
        one (``rhs`` reading parameters and literals only, ``degree`` the builtin); ``parts`` are its
        compiled sub-expressions (:meth:`ExpressionCompiler.compile_parts`)."""
        if not (isinstance(expr, ast.Binary) and expr.op in _COMPARISONS):
            return None
        rhs = parts[id(expr.right)]
        if any(scope[name].type.kind != "value" for name in rhs.reads):
            return None
        left, op = expr.left, _COMPARISONS[expr.op]
        if isinstance(left, ast.Attr) and isinstance(left.target, ast.Name):
            sym = scope.get(left.target.name)
            if sym is None or sym.type.kind not in ("node", "edge"):
                return None
            return ColumnTest(left.target.name, op, rhs.fn, attr=left.attr, kind=sym.type.kind)
        builtin = self.compiler.functions.table.get("degree")
        if not isinstance(left, ast.Call) or left.func != "degree" or builtin is None or \
                builtin.fn is not graph_degree or len(left.args) != 2 or \
                not all(isinstance(a, ast.Name) for a in left.args):
            return None
        node, types = (scope.get(a.name) for a in left.args)
        if node is None or types is None or node.type.kind != "node" or types.type.kind != "type":
            return None
        return ColumnTest(left.args[0].name, op, rhs.fn, types=frozenset(types.types))

    # -- statements ------------------------------------------------------------------------------

    def _statements(self, statements, scope: dict, foreach_created: set | None) -> tuple:
        """The compiled statements; ``foreach_created`` collects the nodes created in a foreach body
        (None outside foreach)."""
        return tuple(self._STATEMENTS[type(s)](self, s, scope, foreach_created) for s in statements)

    def _delete(self, s: ast.Delete, scope: dict, foreach_created) -> CDelete:
        for var in s.vars:
            sym = self._element(var, scope, s.pos)
            if s.detach and sym.type.kind != "node":
                raise RuleTypeError(f"'detach delete' applies to nodes; '{var}' is an edge", s.pos)
            if var in self._created:
                raise RuleTypeError(f"'{var}' is created by this rule; deleting it makes no sense", s.pos)
        nodes = tuple(v for v in s.vars if scope[v].type.kind == "node")
        return CDelete(s.vars, s.detach, nodes, s.pos)

    def _create_node(self, s: ast.CreateNode, scope: dict, foreach_created) -> CCreateNode:
        info = self._node_type(s.type, s.pos)
        if info.abstract:
            raise RuleTypeError(f"node type {s.type} is abstract and cannot be created", s.pos)
        attrs = self._attr_inits(s.type, s.attrs, scope, s.pos)
        self._fresh(s.var, scope, s.pos)
        scope[s.var] = Symbol(VType("node", s.type))
        self._created.add(s.var)
        if foreach_created is not None:
            foreach_created.add(s.var)
        return CCreateNode(s.var, s.type, attrs, s.pos)

    def _retype(self, s: ast.Retype, scope: dict, foreach_created) -> CRetype:
        sym = self._element(s.var, scope, s.pos)
        info = self._node_type(s.type, s.pos)
        if sym.type.kind != "node":
            raise RuleTypeError(f"only nodes can be retyped; '{s.var}' is an edge", s.pos)
        if info.abstract:
            raise RuleTypeError(f"cannot retype to abstract type {s.type}", s.pos)
        scope[s.var] = Symbol(VType("node", s.type))  # later statements see the new type's attributes
        return CRetype(s.var, s.type, s.pos)

    def _set(self, s: ast.SetAttr, scope: dict, foreach_created) -> CSet:
        sym = self._element(s.var, scope, s.pos)
        spec = self.schema.attrs(sym.type.name).get(s.attr)
        if spec is None:
            raise RuleTypeError(
                f"{sym.type.kind} type {sym.type.name} has no attribute '{s.attr}'",
                s.pos,
                did_you_mean(s.attr, self.schema.attrs(sym.type.name)),
            )
        value = self.compiler.compile(s.value, scope)
        self._check_value_type(value.type, spec.type, s.attr, s.value.pos)
        return CSet(s.var, sym.type.kind, s.attr, value.fn, s.pos)

    def _merge(self, s: ast.Merge, scope: dict, foreach_created) -> CMerge:
        for var in (s.source, s.target):
            if self._element(var, scope, s.pos).type.kind != "node":
                raise RuleTypeError(f"only nodes can be merged; '{var}' is an edge", s.pos)
        if s.source == s.target:
            raise RuleTypeError("cannot merge a node into itself", s.pos)
        return CMerge(s.source, s.target, s.pos)

    def _create_edge(self, s: ast.CreateEdge, scope, foreach_created):
        info = self._edge_type(s.type, s.pos)
        if info.abstract:
            raise RuleTypeError(f"edge type {s.type} is abstract and cannot be created", s.pos)
        if s.directed != info.directed:
            arrow = "->" if info.directed else "--"
            raise RuleTypeError(
                f"edge type {s.type} is {'directed' if info.directed else 'undirected'}: "
                f"write {s.source.var} -{s.type}{arrow[-1] if info.directed else '-'} {s.target.var}",
                s.pos,
            )
        ends = []
        for ref in (s.source, s.target):
            sym = scope.get(ref.var)
            if sym is None or sym.type.kind != "node":
                raise RuleTypeError(f"'{ref.var}' is not a node in this rule", ref.pos, did_you_mean(ref.var, scope))
            if ref.step != 0 and (foreach_created is None or ref.var not in foreach_created):
                raise RuleTypeError(
                    f"next()/prev() names the neighbour of the enclosing foreach or a node created in it; "
                    f"'{ref.var}' is neither",
                    ref.pos,
                )
            ends.append(sym.type.name)
        if (s.source.var, s.source.step) == (s.target.var, s.target.step):
            raise RuleTypeError("an edge cannot join a node to itself", s.pos)
        if not self.schema.endpoints_fit(s.type, ends[0], ends[1]):
            raise RuleTypeError(
                f"edge {s.type} joins {info.source} and {info.target}; "
                f"{s.source.var} is {ends[0]} and {s.target.var} is {ends[1]}",
                s.pos,
                "narrow the pattern types so the endpoints are always of the declared types",
            )
        attrs = self._attr_inits(s.type, s.attrs, scope, s.pos)
        if s.var:
            self._fresh(s.var, scope, s.pos)
            scope[s.var] = Symbol(VType("edge", s.type))
            self._created.add(s.var)
        source, target = End(s.source.var, s.source.step), End(s.target.var, s.target.step)
        return CCreateEdge(s.var, source, target, s.type, attrs, s.pos)

    def _foreach(self, s: ast.Foreach, scope: dict, foreach_created) -> CForeach:
        center = scope.get(s.center)
        if center is None or center.type.kind != "node":
            raise RuleTypeError(f"foreach: '{s.center}' is not a node of the pattern", s.pos)
        info = self._edge_type(s.type, s.pos)
        if s.direction != "--" and not info.directed:
            raise RuleTypeError(f"edge type {s.type} is undirected: write -{s.type}-", s.pos)
        inner = dict(scope)
        edge_var = s.edge_var or f"_foreach{s.pos.line}_{s.pos.column}"
        self._fresh(edge_var, inner, s.pos)
        self._fresh(s.neighbour, inner, s.pos)
        inner[edge_var] = Symbol(VType("edge", s.type))
        other = self._neighbour_type(info, s.direction, center.type.name)
        narrowed = None
        if s.neighbour_type is not None:
            self._node_type(s.neighbour_type, s.pos)
            if not self.schema.compatible(s.neighbour_type, other):
                raise RuleTypeError(f"foreach: a neighbour along {s.type} is a {other}, never a {s.neighbour_type}",
                                    s.pos)
            other, narrowed = s.neighbour_type, self.schema.subtypes(s.neighbour_type)
        inner[s.neighbour] = Symbol(VType("node", other))
        condition = self._condition(s.condition, inner) if s.condition is not None else None
        local = {s.neighbour}  # next()/prev() may name the neighbour or a node created in the body
        body = self._statements(s.body, inner, local)
        return CForeach(
            edge_var, s.center, s.neighbour, self.schema.subtypes(s.type), s.direction, condition, body, s.pos,
            narrowed,
        )

    def _neighbour_type(self, info, direction: str, center_type: str) -> str:
        """The static type of a foreach neighbour: the edge type's other endpoint type."""
        if direction == "->":
            return info.target
        if direction == "<-":
            return info.source
        as_source = self.schema.compatible(center_type, info.source)
        as_target = self.schema.compatible(center_type, info.target)
        if as_source and not as_target:
            return info.target
        if as_target and not as_source:
            return info.source
        return self.schema.common_ancestor(info.source, info.target)

    def _attr_inits(self, type_name: str, inits, scope, pos):
        specs = self.schema.attrs(type_name)
        out = []
        seen = set()
        for init in inits:
            spec = specs.get(init.attr)
            if spec is None:
                raise RuleTypeError(
                    f"type {type_name} has no attribute '{init.attr}'", init.pos, did_you_mean(init.attr, specs)
                )
            if init.attr in seen:
                raise RuleTypeError(f"attribute '{init.attr}' is set twice", init.pos)
            seen.add(init.attr)
            value = self.compiler.compile(init.value, scope)
            self._check_value_type(value.type, spec.type, init.attr, init.value.pos)
            out.append((init.attr, value.fn))
        missing = [name for name, spec in specs.items() if spec.required and name not in seen]
        if missing:
            raise RuleTypeError(
                f"creating a {type_name} needs attribute(s) {', '.join(missing)}",
                pos,
                f"write {{ {missing[0]} = ... }}",
            )
        return tuple(out)

    def _check_value_type(self, vtype: VType, declared: str, attr: str, pos) -> None:
        if vtype == ANY or declared == "any":
            return
        if not (vtype.kind == "value" and storable(vtype.name, declared)):
            raise RuleTypeError(f"attribute '{attr}' is {declared} but the value is {vtype}", pos)

    # -- helpers ---------------------------------------------------------------------------------

    _created: set

    def _fresh(self, name: str, scope, pos) -> None:
        if name in scope:
            what = "a type name" if scope[name].type == TYPE else "already used in this rule"
            raise RuleTypeError(f"'{name}' is {what}", pos, "choose another variable name")

    def _element(self, var: str, scope, pos) -> Symbol:
        sym = scope.get(var)
        if sym is None or sym.type.kind not in ("node", "edge"):
            known = [n for n, s in scope.items() if s.type.kind in ("node", "edge") and not n.startswith("_")]
            raise RuleTypeError(f"'{var}' is not a node or edge of this rule", pos, did_you_mean(var, known))
        return sym

    def _node_type(self, name: str, pos):
        info = self.schema.node_types.get(name)
        if info is None:
            known = [t for t in self.schema.node_types if t != "Node"]
            raise RuleTypeError(f"unknown node type '{name}'", pos, did_you_mean(name, known))
        return info

    def _edge_type(self, name: str, pos):
        info = self.schema.edge_types.get(name)
        if info is None:
            known = [t for t in self.schema.edge_types if t != "Edge"]
            raise RuleTypeError(f"unknown edge type '{name}'", pos, did_you_mean(name, known))
        return info

    def _reads_types(self, rule: ast.Rule, compiled: CompiledRule) -> frozenset[str]:
        """Types whose changes can change this rule's matches."""
        all_edges = frozenset(self.schema.edge_types)
        types: set[str] = set()
        for pat in (compiled.pattern, *compiled.nacs):
            for n in pat.nodes.values():
                types |= n.types
            for e in pat.edges:
                types |= e.types
        for s in flatten(compiled.statements):
            if isinstance(s, CForeach):
                types |= s.types
        if compiled.deletes_nodes:
            types |= all_edges
        for expr in rule_expressions(rule):
            for sub in walk(expr):
                if isinstance(sub, ast.Quantifier):  # the body may read any element of the graph
                    types |= frozenset(self.type_symbols)
                if isinstance(sub, ast.Call) and self.compiler.functions.table.get(sub.func, None) is not None:
                    f = self.compiler.functions[sub.func]
                    if f.uses_graph:
                        named = [a for a in sub.args if isinstance(a, ast.Name) and a.name in self.type_symbols]
                        if named:
                            for a in named:
                                types |= self.type_symbols[a.name].types
                        else:
                            types |= all_edges
        return frozenset(types)

    def _radius(self, rule: ast.Rule, compiled: CompiledRule) -> int | None:
        """How far (in edges) from a changed node a match of this rule can be affected; None = anywhere."""
        if any(self.compiler.reads_nonlocal(e) for e in rule_expressions(rule)):
            return None
        if not compiled.pattern.nodes:
            return None
        radius = 0
        positive = set(compiled.pattern.nodes)
        for nac in compiled.nacs:
            depth = {v: 0 for v in positive}
            frontier = list(positive)
            while frontier:
                nxt = []
                for v in frontier:
                    for e in nac.edges:
                        for a, b in ((e.source, e.target), (e.target, e.source)):
                            if a == v and b not in depth:
                                depth[b] = depth[v] + 1
                                nxt.append(b)
                frontier = nxt
            if any(v not in depth for v in nac.nodes):
                return None  # a NAC part not connected to the match: anything may matter
            radius = max(radius, *(depth[v] for v in nac.nodes), 0)
        return radius

    _STATEMENTS = {
        ast.Delete: _delete,
        ast.CreateNode: _create_node,
        ast.CreateEdge: _create_edge,
        ast.Retype: _retype,
        ast.SetAttr: _set,
        ast.Merge: _merge,
        ast.Foreach: _foreach,
    }


def flatten(statements):
    """Statements with foreach bodies expanded (for static summaries)."""
    for s in statements:
        yield s
        if isinstance(s, CForeach):
            yield from flatten(s.body)


def rule_expressions(rule: ast.Rule):
    """Every expression written in a rule."""
    for pat in (rule.match, *rule.nacs):
        yield from pat.conditions
        for n in pat.nodes:
            yield from (c.value for c in n.constraints)
        for e in pat.edges:
            yield from (c.value for c in e.constraints)
    yield from _statement_expressions(rule.statements)


def _statement_expressions(statements):
    for s in statements:
        if isinstance(s, (ast.CreateNode, ast.CreateEdge)):
            yield from (a.value for a in s.attrs)
        elif isinstance(s, ast.SetAttr):
            yield s.value
        elif isinstance(s, ast.Foreach):
            if s.condition is not None:
                yield s.condition
            yield from _statement_expressions(s.body)


def describe(expr) -> str:
    """A short source-like rendering of an expression, for messages.

    >>> describe(ast.Binary("<", ast.Attr(ast.Name("a", None), "w", None), ast.Literal(2, None), None))
    'a.w < 2'
    """
    render = _DESCRIBE.get(type(expr))
    return render(expr) if render else "?"


def _literal_text(value) -> str:
    return str(value).lower() if isinstance(value, bool) else repr(value)


def _operand(expr) -> str:
    """An operand of a binary operator, in parentheses when it is itself an operation."""
    text = describe(expr)
    return f"({text})" if isinstance(expr, (ast.Binary, ast.Unary)) else text


_DESCRIBE = {
    ast.Literal: lambda e: _literal_text(e.value),
    ast.Name: lambda e: e.name,
    ast.Attr: lambda e: f"{describe(e.target)}.{e.attr}",
    ast.Index: lambda e: f"{describe(e.target)}[{describe(e.index)}]",
    ast.Call: lambda e: f"{e.func}({', '.join(describe(a) for a in e.args)})",
    ast.ListExpr: lambda e: f"[{', '.join(describe(a) for a in e.items)}]",
    ast.Unary: lambda e: f"not {_operand(e.operand)}" if e.op == "not" else f"-{_operand(e.operand)}",
    ast.Binary: lambda e: f"{_operand(e.left)} {e.op} {_operand(e.right)}",
    ast.Quantifier: lambda e: f"{e.kind} {e.var}: {e.type} {{ {describe(e.body)} }}",
}


def _quantified(expr) -> set[int]:
    """The ``id`` of every sub-expression of ``expr`` inside a quantifier (its variable is not bound
    outside), by one walk of each quantifier's body."""
    return {id(s) for q in walk(expr) if isinstance(q, ast.Quantifier) for s in walk(q.body)}


def conjuncts(expr) -> list:
    """The operands of a chain of ``and`` (each a condition of its own, tested in order)."""
    if isinstance(expr, ast.Binary) and expr.op == "and":
        return conjuncts(expr.left) + conjuncts(expr.right)
    return [expr]
