"""The type schema of a host graph: node and edge types with single inheritance and typed attributes.

A schema is declared in rule files (``schema name { node ... edge ... }``) and is the contract between
the rules and the host application: every node and edge of the host graph has exactly one declared
type, rules match types *with their subtypes* (a ``Corner`` is a ``BoundaryVertex`` is a ``Point``),
and edges may only join nodes of the endpoint types their type declares.

Two root types always exist: ``Node`` (every node type inherits from it) and ``Edge`` (every edge type
inherits from it; undirected, joining any two nodes). Both are abstract.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Mapping

from .errors import RuleTypeError, SchemaError, did_you_mean
from .values import check_type_name, normalise_column, normalise_value, value_conforms

if TYPE_CHECKING:
    import numpy as np

ROOT_NODE = "Node"
ROOT_EDGE = "Edge"


@dataclass(frozen=True)
class AttrSpec:
    """An attribute of a node or edge type; ``required`` when it has no default."""

    name: str
    type: str
    default: object
    required: bool


@dataclass(frozen=True)
class NodeType:
    name: str
    parent: str | None
    attrs: Mapping[str, AttrSpec]  # own and inherited
    abstract: bool


@dataclass(frozen=True)
class EdgeType:
    name: str
    parent: str | None
    source: str
    target: str
    directed: bool
    attrs: Mapping[str, AttrSpec]
    abstract: bool


class TypeSchema:
    """Node and edge types with their inheritance, attributes and (for edges) endpoint types."""

    def __init__(self, node_types: Mapping[str, NodeType], edge_types: Mapping[str, EdgeType]):
        self.node_types = dict(node_types)
        self.edge_types = dict(edge_types)
        self._subtypes: dict[str, frozenset[str]] = {}
        for table in (self.node_types, self.edge_types):
            for name in table:
                self._subtypes[name] = frozenset(t for t in table if self._is_subtype_walk(t, name, table))

    @staticmethod
    def _is_subtype_walk(t: str, ancestor: str, table) -> bool:
        while t is not None:
            if t == ancestor:
                return True
            t = table[t].parent
        return False

    def is_node_type(self, name: str) -> bool:
        return name in self.node_types

    def subtypes(self, name: str) -> frozenset[str]:
        """The type and all its descendants (the types a pattern element of this type matches)."""
        return self._subtypes[name]

    def is_subtype(self, t: str, ancestor: str) -> bool:
        return t in self._subtypes[ancestor]

    def compatible(self, a: str, b: str) -> bool:
        """Whether some element could have both types (one is a subtype of the other)."""
        return self.is_subtype(a, b) or self.is_subtype(b, a)

    def endpoints_fit(self, edge_type: str, a: str, b: str, could: bool = False) -> bool:
        """Whether an edge of ``edge_type`` may join nodes of types ``a`` and ``b`` (in that order if directed).

        With ``could`` the question is whether *some* nodes of those types (or of their subtypes)
        could be joined -- the static question for patterns -- rather than every node of them.
        """
        info = self.edge_types[edge_type]
        fits = self.compatible if could else self.is_subtype
        ok = fits(a, info.source) and fits(b, info.target)
        return ok or (not info.directed and fits(b, info.source) and fits(a, info.target))

    def common_ancestor(self, a: str, b: str) -> str:
        """The most specific type that both ``a`` and ``b`` are subtypes of."""
        table = self.node_types if a in self.node_types else self.edge_types
        while not self.is_subtype(b, a):
            a = table[a].parent
        return a

    def attrs(self, type_name: str) -> Mapping[str, AttrSpec]:
        table = self.node_types if type_name in self.node_types else self.edge_types
        return table[type_name].attrs

    def fill_attrs(self, type_name: str, given: Mapping[str, object], where: str) -> dict[str, object]:
        """Check given attribute values against the type and add defaults; raise SchemaError if wrong."""
        out = {name: self.checked_value(type_name, name, value, where) for name, value in given.items()}
        for name, spec in self.attrs(type_name).items():
            if name not in out:
                if spec.required:
                    raise SchemaError(f"{where}: {type_name} needs attribute '{name}' ({spec.type})")
                out[name] = spec.default
        return out

    def filled_columns(self, type_name: str, columns: Mapping[str, object], n: int,
                       what: str) -> dict[str, np.ndarray | list]:
        """Attribute values of ``n`` elements by column, checked (each column as a whole, or value by
        value to name the first bad one) and with the defaults of the columns not given: numpy
        arrays of numbers as :func:`~.values.normalise_column` keeps them, lists of plain values."""
        out = {}
        for name, values in columns.items():
            spec = self.attrs(type_name).get(name)
            if spec is None:
                raise SchemaError(f"{what}: type {type_name} has no attribute '{name}'")
            column = normalise_column(values, spec.type)
            if column is None:
                column = [self.checked_value(type_name, name, v, f"{what} {k}") for k, v in enumerate(values)]
            if len(column) != n:
                raise SchemaError(f"{what}: attribute '{name}' has {len(column)} values for {n} elements")
            out[name] = column
        for name, spec in self.attrs(type_name).items():
            if name not in out:
                if spec.required:
                    raise SchemaError(f"{what}: {type_name} needs attribute '{name}' ({spec.type})")
                out[name] = [spec.default] * n
        return out

    def checked_value(self, type_name: str, name: str, value: object, where: str) -> object:
        """``value`` made plain, if the type has attribute ``name`` and the value fits it; else SchemaError."""
        spec = self.attrs(type_name).get(name)
        if spec is None:
            raise SchemaError(f"{where}: type {type_name} has no attribute '{name}'")
        value = normalise_value(value)
        if not value_conforms(value, spec.type):
            raise SchemaError(f"{where}: attribute '{name}' of {type_name} must be {spec.type}, got {value!r}")
        return value

    def summary(self) -> dict:
        """A plain description (used by ``vaultgram rules check``)."""
        return {
            "nodes": {n: t.parent for n, t in self.node_types.items() if n != ROOT_NODE},
            "edges": {
                n: f"{t.source} {'->' if t.directed else '--'} {t.target}"
                for n, t in self.edge_types.items()
                if n != ROOT_EDGE
            },
        }


def build_schema(schemas, evaluate_constant) -> TypeSchema:
    """Build a :class:`TypeSchema` from parsed ``schema`` blocks, reporting every mistake with its position.

    ``evaluate_constant(expr)`` turns a default-value expression into a value (or raises RuleTypeError).
    """
    _check_attribute_types(schemas)
    node_decls: dict = {}
    edge_decls: dict = {}
    for schema in schemas:
        for decl in schema.nodes:
            _declare(decl, node_decls, edge_decls)
        for decl in schema.edges:
            _declare(decl, edge_decls, node_decls)

    def node_type(decl, parent: str, base: NodeType) -> NodeType:
        return NodeType(decl.name, parent, _merge_attrs(base.attrs, decl, evaluate_constant), decl.abstract)

    def edge_type(decl, parent: str, base: EdgeType) -> EdgeType:
        if decl.source is None:
            ends = (base.source, base.target, base.directed)
        else:
            _check_endpoint_types(decl, node_decls)
            ends = (decl.source, decl.target, decl.directed)
        return EdgeType(decl.name, parent, *ends, _merge_attrs(base.attrs, decl, evaluate_constant), decl.abstract)

    node_types = _resolve_all(node_decls, NodeType(ROOT_NODE, None, {}, True), "node", node_type)
    edge_types = _resolve_all(
        edge_decls, EdgeType(ROOT_EDGE, None, ROOT_NODE, ROOT_NODE, False, {}, True), "edge", edge_type
    )
    return TypeSchema(node_types, edge_types)


def _resolve_all(decls: dict, root, kind: str, make) -> dict:
    """The root and every declared type of one kind, each built by ``make(decl, parent, base)`` after
    its parent, otherwise in declaration order."""
    built = {root.name: root}

    def resolve(name: str):
        if name not in built:
            decl = decls[name]
            parent = decl.parent or root.name
            _check_parent(decl, parent, decls, built, kind)
            _check_no_cycle(decl, decls)
            built[name] = make(decl, parent, resolve(parent))
        return built[name]

    for name in decls:
        resolve(name)
    return built


def _check_attribute_types(schemas) -> None:
    """Every attribute is declared with a value type (checked before anything else in the schemas)."""
    for schema in schemas:
        for decl in (*schema.nodes, *schema.edges):
            for a in decl.attrs:
                check_type_name(a.type, a.type_pos or a.pos)


def _check_endpoint_types(decl, node_decls: dict) -> None:
    for end in (decl.source, decl.target):
        if end not in node_decls and end != ROOT_NODE:
            raise RuleTypeError(f"edge {decl.name}: unknown node type '{end}'", decl.pos, did_you_mean(end, node_decls))


def _declare(decl, same_kind: dict, other_kind: dict) -> None:
    if decl.name in (ROOT_NODE, ROOT_EDGE):
        raise RuleTypeError(f"'{decl.name}' is a built-in root type and cannot be redeclared", decl.pos)
    for table in (same_kind, other_kind):
        if decl.name in table:
            first = table[decl.name].pos
            raise RuleTypeError(f"type '{decl.name}' is declared twice (first at {first})", decl.pos)
    same_kind[decl.name] = decl


def _check_parent(decl, parent: str, decls: dict, built: dict, kind: str) -> None:
    if parent not in decls and parent not in built:
        raise RuleTypeError(
            f"{kind} {decl.name}: unknown parent {kind} type '{parent}'", decl.pos, did_you_mean(parent, decls)
        )


def _check_no_cycle(decl, decls: dict) -> None:
    seen = {decl.name}
    parent = decl.parent
    while parent in decls:
        if parent in seen:
            raise RuleTypeError(f"type '{decl.name}' inherits from itself through '{parent}'", decl.pos)
        seen.add(parent)
        parent = decls[parent].parent


def _merge_attrs(inherited: Mapping[str, AttrSpec], decl, evaluate_constant) -> dict[str, AttrSpec]:
    attrs = dict(inherited)
    for a in decl.attrs:
        if a.name in attrs and attrs[a.name].type != a.type:
            raise RuleTypeError(
                f"attribute '{a.name}' of {decl.name} is {a.type} but the parent type declares it {attrs[a.name].type}",
                a.pos,
            )
        default = None
        if a.default is not None:
            default = normalise_value(evaluate_constant(a.default))
            if not value_conforms(default, a.type):
                raise RuleTypeError(f"default of '{a.name}' must be {a.type}, got {default!r}", a.pos)
        attrs[a.name] = AttrSpec(a.name, a.type, default, a.default is None)
    return attrs
