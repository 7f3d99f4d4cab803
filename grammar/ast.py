"""The abstract syntax of the rule language: plain dataclasses with source positions.

The parser (:mod:`vaultgram.grammar.parser`) builds these from ``rules.lark``; the engine gives them
meaning. Nothing here knows about graphs or vaults: it is the written form of a rule file.

Every node carries ``pos`` (file, line, column) so that later checks can point at the exact place.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Union

from vaultgram.grammar.errors import SourcePos

# --------------------------------------------------------------------------------------------
# Expressions
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Literal:
    """A number, string, boolean or ``none``."""

    value: object
    pos: SourcePos


@dataclass(frozen=True)
class Name:
    """A bare identifier: a pattern variable, a rule parameter or a type name."""

    name: str
    pos: SourcePos


@dataclass(frozen=True)
class Attr:
    """``target.attr`` -- an attribute of a node or edge (or a component such as ``p.x`` of a vector)."""

    target: "Expr"
    attr: str
    pos: SourcePos


@dataclass(frozen=True)
class Index:
    """``target[index]``."""

    target: "Expr"
    index: "Expr"
    pos: SourcePos


@dataclass(frozen=True)
class Call:
    """``func(args...)`` -- a builtin or a function registered by the host application."""

    func: str
    args: tuple["Expr", ...]
    pos: SourcePos


@dataclass(frozen=True)
class ListExpr:
    """``[a, b, c]``."""

    items: tuple["Expr", ...]
    pos: SourcePos


@dataclass(frozen=True)
class Unary:
    """``-x`` or ``not x``; ``op`` is ``"-"`` or ``"not"``."""

    op: str
    operand: "Expr"
    pos: SourcePos


@dataclass(frozen=True)
class Binary:
    """``left op right``; ``op`` is one of ``+ - * / % == != < <= > >= and or in``."""

    op: str
    left: "Expr"
    right: "Expr"
    pos: SourcePos


@dataclass(frozen=True)
class Quantifier:
    """``forall v: Type { body }`` (also ``exists``, ``count``, ``sum``): ``body`` evaluated with ``v``
    bound to each element of ``Type`` (a node or edge type, with its subtypes) of the host graph."""

    kind: str  # "forall", "exists", "count" or "sum"
    var: str
    type: str
    body: "Expr"
    pos: SourcePos


Expr = Union[Literal, Name, Attr, Index, Call, ListExpr, Unary, Binary, Quantifier]

# --------------------------------------------------------------------------------------------
# Schema
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class AttrDecl:
    """``name: type [= default]`` inside a node or edge declaration.

    ``type`` is the word written (the engine accepts ``int float bool str vec2 vec3 list any``);
    ``type_pos`` is where it is written (left out of comparisons, like a second ``pos``).
    """

    name: str
    type: str
    default: Expr | None
    pos: SourcePos
    type_pos: SourcePos | None = field(default=None, compare=False)


@dataclass(frozen=True)
class NodeTypeDecl:
    """``[abstract] node Name [: Parent] { attrs }``."""

    name: str
    parent: str | None
    attrs: tuple[AttrDecl, ...]
    abstract: bool
    pos: SourcePos


@dataclass(frozen=True)
class EdgeTypeDecl:
    """``[abstract] edge Name [: Parent] [(Source -- Target) | (Source -> Target)] { attrs }``.

    ``directed`` is None when the declaration inherits directedness and endpoints from its parent.
    """

    name: str
    parent: str | None
    source: str | None
    target: str | None
    directed: bool | None
    attrs: tuple[AttrDecl, ...]
    abstract: bool
    pos: SourcePos


@dataclass(frozen=True)
class Schema:
    """``schema name { node ... edge ... }``."""

    name: str
    nodes: tuple[NodeTypeDecl, ...]
    edges: tuple[EdgeTypeDecl, ...]
    pos: SourcePos


# --------------------------------------------------------------------------------------------
# Patterns
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Constraint:
    """An inline attribute constraint ``attr op value`` (``attr: value`` is ``attr == value``)."""

    attr: str
    op: str
    value: Expr
    pos: SourcePos


@dataclass(frozen=True)
class NodePattern:
    """``var: Type { constraints }``."""

    var: str
    type: str
    constraints: tuple[Constraint, ...]
    pos: SourcePos


@dataclass(frozen=True)
class EdgePattern:
    """``[var:] source -Type- target`` (undirected) or ``source -Type-> target`` (directed).

    ``<-Type-`` is parsed into the directed form with source and target swapped. ``var`` is None for an
    anonymous edge.
    """

    var: str | None
    source: str
    target: str
    type: str
    directed: bool
    constraints: tuple[Constraint, ...]
    pos: SourcePos


@dataclass(frozen=True)
class Pattern:
    """The graph part of a ``match { ... }`` or ``not { ... }`` block, with its ``where`` conditions."""

    nodes: tuple[NodePattern, ...]
    edges: tuple[EdgePattern, ...]
    conditions: tuple[Expr, ...]
    pos: SourcePos


# --------------------------------------------------------------------------------------------
# Rewrites
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class NodeRef:
    """An endpoint in a ``create`` edge: a variable, or ``next(v)`` / ``prev(v)`` inside ``foreach``.

    ``step`` is 0 for the variable itself, +1 for ``next(v)`` (the same variable in the cyclically next
    iteration of the enclosing ``foreach``) and -1 for ``prev(v)``.
    """

    var: str
    step: int
    pos: SourcePos


@dataclass(frozen=True)
class AttrInit:
    """``attr = expr`` inside a ``create`` or ``set``."""

    attr: str
    value: Expr
    pos: SourcePos


@dataclass(frozen=True)
class Delete:
    """``delete a, b`` (DPO: refused when it would leave dangling edges) or ``detach delete a``."""

    vars: tuple[str, ...]
    detach: bool
    pos: SourcePos


@dataclass(frozen=True)
class CreateNode:
    """``create var: Type { attr = expr, ... }``."""

    var: str
    type: str
    attrs: tuple[AttrInit, ...]
    pos: SourcePos


@dataclass(frozen=True)
class CreateEdge:
    """``create [var:] a -Type- b { attr = expr }`` or with ``->`` for a directed edge."""

    var: str | None
    source: NodeRef
    target: NodeRef
    type: str
    directed: bool
    attrs: tuple[AttrInit, ...]
    pos: SourcePos


@dataclass(frozen=True)
class Retype:
    """``retype var as Type``."""

    var: str
    type: str
    pos: SourcePos


@dataclass(frozen=True)
class SetAttr:
    """``set var.attr = expr``."""

    var: str
    attr: str
    value: Expr
    pos: SourcePos


@dataclass(frozen=True)
class Merge:
    """``merge a into b``: a's edges move to b, a is deleted."""

    source: str
    target: str
    pos: SourcePos


@dataclass(frozen=True)
class Foreach:
    """``foreach [e:] center -Type- n [where cond] { statements }``.

    Iterates over the edges of ``Type`` around the matched node ``center`` in their cyclic order
    (the host graph's rotation system) and runs ``body`` once for each, with ``e`` bound to the edge
    and ``n`` to the neighbour. ``direction`` is ``"--"`` (any), ``"->"`` (out) or ``"<-"`` (in);
    ``n: Type`` narrows the iterations to the neighbours of that type (and its subtypes).
    """

    edge_var: str | None
    center: str
    neighbour: str
    type: str
    direction: str
    condition: Expr | None
    body: tuple["Statement", ...]
    pos: SourcePos
    neighbour_type: str | None = None  # `foreach c -T- n: Type`: only neighbours of that type


Statement = Union[Delete, CreateNode, CreateEdge, Retype, SetAttr, Merge, Foreach]

# --------------------------------------------------------------------------------------------
# Rules and strategies
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Param:
    """``name: type [= default]`` in a rule's parameter list; ``type`` may be a node type name."""

    name: str
    type: str
    default: Expr | None
    pos: SourcePos


@dataclass(frozen=True)
class Rule:
    """``rule name(params) [priority N] { match {...} where ... not {...} statements }``."""

    name: str
    params: tuple[Param, ...]
    priority: int
    match: Pattern
    nacs: tuple[Pattern, ...]
    statements: tuple[Statement, ...]
    pos: SourcePos


@dataclass(frozen=True)
class RuleRef:
    """A rule named in a strategy, with keyword arguments: ``keystone(min_valency = 5)``."""

    name: str
    args: tuple[tuple[str, Expr], ...]
    pos: SourcePos


@dataclass(frozen=True)
class Step:
    """One step of a strategy: a group of rules and a mode.

    ``mode`` is ``once``, ``all`` or ``fixpoint`` (with ``max_steps``); ``choose`` marks a choice point.
    Rules in a group are tried by priority (highest first), then by their order in the group.
    """

    rules: tuple[RuleRef, ...]
    mode: str
    max_steps: int | None
    choose: bool
    pos: SourcePos


@dataclass(frozen=True)
class Run:
    """``run other_strategy``: run another strategy as a step."""

    strategy: str
    pos: SourcePos


@dataclass(frozen=True)
class Strategy:
    """``strategy name { steps }``."""

    name: str
    steps: tuple[Union[Step, Run], ...]
    pos: SourcePos


@dataclass(frozen=True)
class Invariant:
    """``invariant name after each|at end [in strategy, ...] { condition }``.

    ``when`` is ``"each"`` (after every rule application) or ``"end"`` (when a strategy has run);
    ``strategies`` limits the check to those strategies (empty: every strategy).
    """

    name: str
    when: str
    strategies: tuple[str, ...]
    condition: Expr
    pos: SourcePos


@dataclass(frozen=True)
class Include:
    """``include "path"`` -- relative to the including file."""

    path: str
    pos: SourcePos


@dataclass(frozen=True)
class RuleFile:
    """Everything one file (and, after loading, the files it includes) declares."""

    path: str
    schemas: tuple[Schema, ...] = field(default=())
    rules: tuple[Rule, ...] = field(default=())
    strategies: tuple[Strategy, ...] = field(default=())
    includes: tuple[Include, ...] = field(default=())
    invariants: tuple[Invariant, ...] = field(default=())
