"""Expressions in rules: static typing, compilation to Python closures, and the function registry.

An expression is checked once, when its rule file is loaded, against a *scope* (which names are
pattern nodes, pattern edges or parameters, and their types): unknown names, attributes and
functions, wrong argument counts and mixed-up types are reported there with the source position.
It is then compiled to a closure ``f(graph, binding)`` so that matching never re-walks the syntax tree.

Functions are either builtins (graph queries such as ``degree`` and a little arithmetic) or registered
by the host application with a signature; the engine itself knows nothing about geometry.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass, field
from typing import Callable, Mapping, NamedTuple

from vaultgram.grammar import ast

from .errors import RuleTypeError, did_you_mean
from .schema import TypeSchema
from .values import NUMERIC, VECTORS, passable

# ----------------------------------------------------------------------------------------------
# Static types
# ----------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class VType:
    """The static type of an expression: a value type, a node or edge of a declared type, or a type name."""

    kind: str  # "value", "node", "edge" or "type"
    name: str  # value type name ("int", "vec2", "any", ...), element type name, or "" for kind "type"

    def __str__(self) -> str:
        return self.name if self.kind == "value" else f"{self.kind} {self.name}".strip()


ANY = VType("value", "any")
BOOL = VType("value", "bool")
INT = VType("value", "int")
FLOAT = VType("value", "float")
STR = VType("value", "str")
NONE = VType("value", "none")
LIST = VType("value", "list")
TYPE = VType("type", "")


@dataclass(frozen=True)
class Symbol:
    """What a name in a rule stands for: its static type, and (for types) the set of matching types."""

    type: VType
    types: frozenset[str] = frozenset()


# ----------------------------------------------------------------------------------------------
# Functions
# ----------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Function:
    """A callable usable in rules.

    ``params`` are parameter kinds: a value type name, ``"node"``, ``"edge"``, ``"type"``, ``"vec"``
    (vec2 or vec3), ``"number"`` or ``"any"``; a trailing ``"?"`` marks an optional parameter and
    ``"*"`` a variadic one. ``uses_graph`` functions receive the host graph first. ``local`` declares
    that the function only reads its arguments and the elements incident to them, which lets the engine
    re-match incrementally; a non-local function makes rules that call it re-match the whole graph.
    """

    name: str
    fn: Callable
    params: tuple[str, ...]
    returns: str
    uses_graph: bool = False
    local: bool = True


@dataclass
class Functions:
    """The registry of functions that rules may call: builtins plus what the host application registers."""

    table: dict[str, Function] = field(default_factory=dict)

    def __post_init__(self):
        for f in _builtins():
            self.table.setdefault(f.name, f)

    def register(self, name: str, fn: Callable, params, returns: str, *, uses_graph=False, local=True) -> None:
        """Register ``fn`` under ``name`` with a signature (see :class:`Function`)."""
        self.table[name] = Function(name, fn, tuple(params), returns, uses_graph, local)

    def __contains__(self, name: str) -> bool:
        return name in self.table

    def __getitem__(self, name: str) -> Function:
        return self.table[name]


def _vector(*components):
    return tuple(float(c) for c in components)


def graph_degree(g, n, types=None) -> int:
    """The builtin ``degree``: edges at node ``n`` (of ``types``, a type and its subtypes)."""
    return g.degree(n, types)


def _builtins() -> list[Function]:
    def indegree(g, n, types=None):
        return sum(1 for e in g.incident(n, types) if g.is_directed(e) and g.ends(e)[1] == n)

    def outdegree(g, n, types=None):
        return sum(1 for e in g.incident(n, types) if g.is_directed(e) and g.ends(e)[0] == n)

    return [
        Function("degree", graph_degree, ("node", "type?"), "int", True),
        Function("indegree", indegree, ("node", "type?"), "int", True),
        Function("outdegree", outdegree, ("node", "type?"), "int", True),
        Function("other", lambda g, e, n: g.other(e, n), ("edge", "node"), "node", True),
        Function("source", lambda g, e: g.ends(e)[0], ("edge",), "node", True),
        Function("target", lambda g, e: g.ends(e)[1], ("edge",), "node", True),
        Function("next_around", lambda g, n, e: g.next_around(n, e, 1), ("node", "edge"), "edge", True),
        Function("prev_around", lambda g, n, e: g.next_around(n, e, -1), ("node", "edge"), "edge", True),
        Function("type_of", lambda g, x: g.node_type(x), ("node",), "str", True),
        Function("is_a", lambda g, x, types: g.node_type(x) in types, ("node", "type"), "bool", True),
        Function("abs", abs, ("number",), "float"),
        Function("min", min, ("number", "number*"), "float"),
        Function("max", max, ("number", "number*"), "float"),
        Function("sqrt", math.sqrt, ("number",), "float"),
        Function("floor", math.floor, ("number",), "int"),
        Function("ceil", math.ceil, ("number",), "int"),
        Function("round", round, ("number",), "int"),
        Function("len", len, ("any",), "int"),
        Function("vec2", _vector, ("number", "number"), "vec2"),
        Function("vec3", _vector, ("number", "number", "number"), "vec3"),
        Function("dot", lambda a, b: sum(x * y for x, y in zip(a, b)), ("vec", "vec"), "float"),
        Function("norm", lambda a: math.sqrt(sum(x * x for x in a)), ("vec",), "float"),
    ]


# ----------------------------------------------------------------------------------------------
# Compilation
# ----------------------------------------------------------------------------------------------

Compiled = Callable[[object, Mapping[str, object]], object]


class Typed(NamedTuple):
    """A compiled expression: the closure, its static type and the names (variables, parameters) it reads."""

    fn: Compiled
    type: VType
    reads: frozenset[str]


_LITERAL_TYPES = {bool: BOOL, int: INT, float: FLOAT, str: STR}
_COMPARISONS = {"==": operator.eq, "!=": operator.ne, "<": operator.lt, "<=": operator.le, ">": operator.gt,
                ">=": operator.ge}
_ARITHMETIC = {"+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv, "%": operator.mod}


def _reads(parts) -> frozenset[str]:
    return frozenset().union(*(p.reads for p in parts))


class ExpressionCompiler:
    """Type-checks expressions against a scope and compiles them to closures ``f(graph, binding)``."""

    def __init__(self, schema: TypeSchema, functions: Functions):
        self.schema = schema
        self.functions = functions
        self._parts: dict[int, Typed] | None = None  # while compile_parts runs: what it returns

    def compile(self, expr, scope: Mapping[str, Symbol]) -> Typed:
        """Return the closure, the static type and the names (variables/parameters) the expression reads."""
        typed = self._COMPILE[type(expr)](self, expr, scope)
        if self._parts is not None:
            self._parts[id(expr)] = typed
        return typed

    def compile_parts(self, expr, scope: Mapping[str, Symbol]) -> tuple[Typed, dict[int, Typed]]:
        """:meth:`compile`, and the compiled form of every sub-expression it compiled on the way, by ``id``
        (those in a quantifier's body too, with its variable in scope): what a condition's why-not operands
        and vectorised form are made of, without compiling each again (issue 18)."""
        self._parts = parts = {}
        try:
            return self.compile(expr, scope), parts
        finally:
            self._parts = None

    def reads_nonlocal(self, expr) -> bool:
        """Whether the expression calls a function declared non-local, or quantifies over the graph."""
        return any(isinstance(e, ast.Quantifier) or (isinstance(e, ast.Call) and e.func in self.functions
                                                     and not self.functions[e.func].local) for e in walk(expr))

    # -- atoms -----------------------------------------------------------------------------------

    def _literal(self, expr: ast.Literal, scope) -> Typed:
        value = expr.value
        return Typed(lambda g, b: value, _LITERAL_TYPES.get(type(value), NONE), frozenset())

    def _name(self, expr: ast.Name, scope) -> Typed:
        sym = scope.get(expr.name)
        if sym is None:
            known = [n for n in scope if not n.startswith("_")]
            raise RuleTypeError(
                f"unknown name '{expr.name}' (not a pattern variable, parameter or type)",
                expr.pos,
                did_you_mean(expr.name, known),
            )
        if sym.type.kind == "type":
            types = sym.types
            return Typed(lambda g, b: types, sym.type, frozenset())
        name = expr.name
        return Typed(lambda g, b: b[name], sym.type, frozenset([name]))

    def _list(self, expr: ast.ListExpr, scope) -> Typed:
        parts = [self.compile(item, scope) for item in expr.items]
        fns = [p.fn for p in parts]
        return Typed(lambda g, b: tuple(f(g, b) for f in fns), LIST, _reads(parts))

    def _attr(self, expr: ast.Attr, scope) -> Typed:
        target, ttype, reads = self.compile(expr.target, scope)
        attr = expr.attr
        if ttype.kind in ("node", "edge"):
            spec = self.schema.attrs(ttype.name).get(attr)
            if spec is None:
                raise RuleTypeError(
                    f"{ttype.kind} type {ttype.name} has no attribute '{attr}'",
                    expr.pos,
                    did_you_mean(attr, self.schema.attrs(ttype.name)),
                )
            getter = (lambda g, b: g.node_attrs(target(g, b))[attr]) if ttype.kind == "node" else (
                lambda g, b: g.get_edge(target(g, b), attr)
            )
            return Typed(getter, VType("value", spec.type), reads)
        if ttype.name in VECTORS + ("any",) and attr in ("x", "y", "z"):
            if ttype.name == "vec2" and attr == "z":
                raise RuleTypeError("a vec2 has no component 'z'", expr.pos)
            k = "xyz".index(attr)
            return Typed(lambda g, b: target(g, b)[k], FLOAT if ttype.name != "any" else ANY, reads)
        raise RuleTypeError(f"cannot take attribute '{attr}' of a value of type {ttype}", expr.pos)

    def _index(self, expr: ast.Index, scope) -> Typed:
        target, ttype, r1 = self.compile(expr.target, scope)
        index, itype, r2 = self.compile(expr.index, scope)
        if ttype.name not in VECTORS + ("list", "any") or ttype.kind != "value":
            raise RuleTypeError(f"cannot index a value of type {ttype}", expr.pos)
        if itype.name not in ("int", "any"):
            raise RuleTypeError(f"an index must be an int, not {itype}", expr.index.pos)
        result = FLOAT if ttype.name in VECTORS else ANY
        return Typed(lambda g, b: target(g, b)[index(g, b)], result, r1 | r2)

    def _call(self, expr: ast.Call, scope) -> Typed:
        func = self.functions.table.get(expr.func)
        if func is None:
            raise RuleTypeError(
                f"unknown function '{expr.func}'",
                expr.pos,
                did_you_mean(expr.func, self.functions.table)
                or "the host application registers functions rules may call",
            )
        parts = [self.compile(a, scope) for a in expr.args]
        _check_arguments(func, expr, [p.type for p in parts])
        fns = tuple(p.fn for p in parts)
        fn = func.fn
        if func.uses_graph:
            call = lambda g, b: fn(g, *[f(g, b) for f in fns])  # noqa: E731
        else:
            call = lambda g, b: fn(*[f(g, b) for f in fns])  # noqa: E731
        return Typed(call, self._result_type(func, parts), _reads(parts))

    def _result_type(self, func: Function, parts: list[Typed]) -> VType:
        """A function's static result type; ``source(e)`` and ``target(e)`` of an edge of a declared
        type are nodes of that type's endpoint types (so ``source(e).sides`` type-checks)."""
        if func.name in ("source", "target") and parts and parts[0].type.kind == "edge":
            info = self.schema.edge_types.get(parts[0].type.name)
            if info is not None and info.directed:
                return VType("node", info.source if func.name == "source" else info.target)
        return _return_type(func.returns)

    def _quantifier(self, expr: ast.Quantifier, scope) -> Typed:
        """``forall/exists/count/sum v: Type { body }``: the body for each element of the type (and its
        subtypes), in id order; ``forall`` and ``exists`` stop at the first element that decides."""
        kind = "node" if self.schema.is_node_type(expr.type) else "edge" if expr.type in self.schema.edge_types else ""
        if not kind:
            known = [t for t in (*self.schema.node_types, *self.schema.edge_types) if t not in ("Node", "Edge")]
            raise RuleTypeError(f"unknown node or edge type '{expr.type}'", expr.pos, did_you_mean(expr.type, known))
        if expr.var in scope:
            raise RuleTypeError(f"'{expr.var}' is already a name here; quantify over a new variable", expr.pos)
        body = self.compile(expr.body, {**scope, expr.var: Symbol(VType(kind, expr.type))})
        wanted = ("float", "int") if expr.kind == "sum" else ("bool",)
        if body.type.kind != "value" or body.type.name not in (*wanted, "any"):
            raise RuleTypeError(f"the body of {expr.kind} must be {' or '.join(wanted)}, not {body.type}",
                                expr.body.pos)
        types, var, fn = self.schema.subtypes(expr.type), expr.var, body.fn

        def values(g, b):
            inner = dict(b)
            for x in sorted(g.of_types(types)):
                inner[var] = x
                yield fn(g, inner)

        result = {"forall": (all, BOOL), "exists": (any, BOOL), "count": (lambda v: sum(map(bool, v)), INT),
                  "sum": (sum, body.type if body.type.name == "int" else FLOAT)}
        reduce, rtype = result[expr.kind]
        return Typed(lambda g, b: reduce(values(g, b)), rtype, body.reads - {var})

    # -- operators -------------------------------------------------------------------------------

    def _unary(self, expr: ast.Unary, scope) -> Typed:
        operand, t, reads = self.compile(expr.operand, scope)
        if expr.op == "not":
            return Typed(lambda g, b: not operand(g, b), BOOL, reads)
        if t.kind != "value" or t.name not in NUMERIC + VECTORS + ("any",):
            raise RuleTypeError(f"cannot negate a value of type {t}", expr.pos)
        if t.name in VECTORS:
            return Typed(lambda g, b: tuple(-c for c in operand(g, b)), t, reads)
        return Typed(lambda g, b: -operand(g, b), t, reads)

    def _binary(self, expr: ast.Binary, scope) -> Typed:
        left = self.compile(expr.left, scope)
        right = self.compile(expr.right, scope)
        fn, result = _BINARY[expr.op](expr, left, right)
        return Typed(fn, result, left.reads | right.reads)

    _COMPILE = {
        ast.Literal: _literal,
        ast.Name: _name,
        ast.ListExpr: _list,
        ast.Attr: _attr,
        ast.Index: _index,
        ast.Call: _call,
        ast.Unary: _unary,
        ast.Binary: _binary,
        ast.Quantifier: _quantifier,
    }


# -- binary operators: (expr, left, right) -> (closure, static type) ----------------------------


def _logic(expr, left: Typed, right: Typed):
    lf, rf = left.fn, right.fn
    if expr.op == "and":
        return (lambda g, b: bool(lf(g, b)) and bool(rf(g, b))), BOOL
    return (lambda g, b: bool(lf(g, b)) or bool(rf(g, b))), BOOL


def _equality(expr, left: Typed, right: Typed):
    _check_comparable(left.type, right.type, expr)
    lf, rf, f = left.fn, right.fn, _COMPARISONS[expr.op]
    return (lambda g, b: f(lf(g, b), rf(g, b))), BOOL


def _membership(expr, left: Typed, right: Typed):
    rt = right.type
    if rt.kind != "value" or rt.name not in ("list", "any", "vec2", "vec3"):
        raise RuleTypeError(f"'in' needs a list on its right, not {rt}", expr.right.pos)
    lf, rf = left.fn, right.fn
    return (lambda g, b: lf(g, b) in rf(g, b)), BOOL


def _ordering(expr, left: Typed, right: Typed):
    lt, rt = left.type, right.type
    if not (_both(lt, rt, NUMERIC) or _both(lt, rt, ("str",))):
        raise RuleTypeError(f"cannot compare {lt} {expr.op} {rt}", expr.pos)
    lf, rf, f = left.fn, right.fn, _COMPARISONS[expr.op]
    return (lambda g, b: f(lf(g, b), rf(g, b))), BOOL


def _arithmetic(expr, left: Typed, right: Typed):
    op, lt, rt = expr.op, left.type, right.type
    lf, rf, f = left.fn, right.fn, _ARITHMETIC[op]
    if _both(lt, rt, NUMERIC):
        result = INT if lt.name == rt.name == "int" and op != "/" else FLOAT
        if ANY in (lt, rt):
            result = ANY
        return (lambda g, b: f(lf(g, b), rf(g, b))), result
    if op == "+" and lt == rt == STR:
        return (lambda g, b: lf(g, b) + rf(g, b)), STR
    if op in "+-" and lt.name in VECTORS and lt == rt:
        return (lambda g, b: tuple(f(x, y) for x, y in zip(lf(g, b), rf(g, b)))), lt
    if op in "*/" and lt.name in VECTORS and rt.name in NUMERIC:
        return (lambda g, b: tuple(f(x, rf(g, b)) for x in lf(g, b))), lt
    if op == "*" and lt.name in NUMERIC and rt.name in VECTORS:
        return (lambda g, b: tuple(lf(g, b) * y for y in rf(g, b))), rt
    raise RuleTypeError(f"operator '{op}' does not apply to {lt} and {rt}", expr.pos)


_BINARY = {
    "and": _logic, "or": _logic,
    "==": _equality, "!=": _equality,
    "in": _membership,
    "<": _ordering, "<=": _ordering, ">": _ordering, ">=": _ordering,
    **dict.fromkeys(_ARITHMETIC, _arithmetic),
}

_CHILDREN = {
    ast.Attr: lambda e: (e.target,),
    ast.Index: lambda e: (e.target, e.index),
    ast.Call: lambda e: e.args,
    ast.ListExpr: lambda e: e.items,
    ast.Unary: lambda e: (e.operand,),
    ast.Binary: lambda e: (e.left, e.right),
    ast.Quantifier: lambda e: (e.body,),
}


def walk(expr):
    """Every sub-expression of ``expr`` (itself included), parents before their children, children in
    their order. By a stack, not by nested generators: each of those passed every value up through
    every level above it, and checking a rulebook walks its expressions thousands of times.

    >>> f = ast.Call("f", (ast.Name("b", None), ast.Literal(1, None)), None)
    >>> [getattr(e, "name", None) or type(e).__name__ for e in walk(ast.Binary("+", f, ast.Name("a", None), None))]
    ['Binary', 'Call', 'b', 'Literal', 'a']
    """
    stack = [expr]
    while stack:
        e = stack.pop()
        yield e
        children = _CHILDREN.get(type(e))
        if children is not None:
            stack.extend(reversed(children(e)))


def _both(a: VType, b: VType, names) -> bool:
    ok = lambda t: t.kind == "value" and (t.name in names or t.name == "any")  # noqa: E731
    return ok(a) and ok(b)


def _check_comparable(a: VType, b: VType, expr) -> None:
    if ANY in (a, b) or NONE in (a, b):
        return
    if a.kind != b.kind:
        raise RuleTypeError(f"comparing {a} with {b} is always false", expr.pos)
    if a.kind == "value" and not (a.name == b.name or _both(a, b, NUMERIC)):
        raise RuleTypeError(f"comparing {a} with {b} is always false", expr.pos)


def _return_type(name: str) -> VType:
    if name in ("node", "edge"):
        return VType(name, "Node" if name == "node" else "Edge")
    return VType("value", name)


def _accepts(kind: str, t: VType) -> bool:
    kind = kind.rstrip("?*")
    if kind == "any" or t == ANY:
        return True
    if kind in ("node", "edge", "type"):
        return t.kind == kind
    return t.kind == "value" and passable(kind, t.name)


def _check_arguments(func: Function, expr, types: list[VType]) -> None:
    required = [p for p in func.params if not p.endswith(("?", "*"))]
    variadic = func.params and func.params[-1].endswith("*")
    if len(types) < len(required) or (not variadic and len(types) > len(func.params)):
        sig = ", ".join(func.params)
        raise RuleTypeError(f"{func.name}({sig}) takes {len(required)} argument(s), got {len(types)}", expr.pos)
    for i, t in enumerate(types):
        kind = func.params[min(i, len(func.params) - 1)]
        if not _accepts(kind, t):
            raise RuleTypeError(
                f"argument {i + 1} of {func.name} must be {kind.rstrip('?*')}, got {t}", expr.args[i].pos
            )
