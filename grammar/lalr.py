"""The lark side of the rule-language parser: the LALR parser built from ``rules.lark``, the
translation of its errors into :class:`~vaultgram.grammar.errors.RuleSyntaxError` with a hint,
and the transformer from its parse trees to the AST.

:mod:`vaultgram.grammar.parser` imports this module (and lark) only when a file is not in the
parse cache (:mod:`vaultgram.grammar.cache`): a warm run of the pipeline never imports lark
(issue 18).
"""

from __future__ import annotations

import functools
from pathlib import Path
from typing import NamedTuple

from lark import Lark, Token, Transformer_NonRecursive, v_args
from lark.exceptions import (
    LarkError,
    UnexpectedCharacters,
    UnexpectedEOF,
    UnexpectedInput,
    UnexpectedToken,
    VisitError,
)

from vaultgram.grammar import cache
from vaultgram.grammar.ast import (
    Attr,
    AttrDecl,
    AttrInit,
    Binary,
    Call,
    Constraint,
    CreateEdge,
    CreateNode,
    Delete,
    EdgePattern,
    EdgeTypeDecl,
    Foreach,
    Include,
    Index,
    Invariant,
    ListExpr,
    Literal,
    Merge,
    Name,
    NodePattern,
    NodeRef,
    NodeTypeDecl,
    Param,
    Pattern,
    Quantifier,
    Retype,
    Rule,
    RuleFile,
    RuleRef,
    Run,
    Schema,
    SetAttr,
    Step,
    Strategy,
    Unary,
)
from vaultgram.grammar.errors import RuleSyntaxError, SourcePos

__all__ = ["KEYWORDS", "CONTEXTUAL_KEYWORDS", "parsed"]

#: Reserved words: never a name.
KEYWORDS = frozenset(
    "include schema abstract node edge rule priority match where not and or in delete detach create "
    "retype as set merge into foreach strategy choose run true false none invariant forall exists count sum".split()
)

#: Words that are keywords only where the grammar expects them.
CONTEXTUAL_KEYWORDS = frozenset("once all fixpoint max next prev after each at end".split())

_GRAMMAR_FILE = Path(__file__).with_name("rules.lark")


@functools.lru_cache(maxsize=1)
def _lark() -> Lark:
    """The LALR parser, built once from ``rules.lark``."""
    return Lark(
        _GRAMMAR_FILE.read_text(encoding="utf-8"),
        parser="lalr",
        lexer="contextual",
        propagate_positions=True,
        maybe_placeholders=True,
        cache=cache.lark_cache(),
    )


def parsed(text: str, filename: str) -> RuleFile:
    """:func:`parse_text` without the cache."""
    try:
        tree = _parse_tree(text, filename)
        return _ToAst(filename).transform(tree)
    except RuleSyntaxError:
        raise
    except VisitError as exc:
        if isinstance(exc.orig_exc, RuleSyntaxError):
            raise exc.orig_exc from None
        raise RuleSyntaxError(f"cannot parse: {exc.orig_exc}", SourcePos(filename, 1, 1)) from None
    except LarkError as exc:  # pragma: no cover - every lark error is translated in _parse_tree
        raise RuleSyntaxError(f"cannot parse: {exc}", SourcePos(filename, 1, 1)) from None

# --------------------------------------------------------------------------------------------
# Parse errors
# --------------------------------------------------------------------------------------------

# How terminals are named in "expected ..." hints (punctuation is shown quoted).
_TERMINAL_WORDS = {
    "NAME": "a name",
    "STRING": "a string",
    "INT": "an integer",
    "SIGNED_INT": "an integer",
    "FLOAT": "a number",
    "EDGE_UNDIRECTED": "an edge -Type-",
    "EDGE_OUT": "an edge -Type->",
    "EDGE_IN": "an edge <-Type-",
    "$END": "end of file",
}
_EXPRESSION_START = {"NAME", "INT", "FLOAT", "STRING", "LPAR", "LSQB", "SUB", "NOT", "_TRUE", "_FALSE", "_NONE"}
_BINARY_OPS = {"OR", "AND", "EQ", "NE", "LT", "LE", "GT", "GE", "IN", "ADD", "SUB", "MUL", "DIV", "MOD"}
_COMPARISONS = {"EQ", "NE", "LT", "LE", "GT", "GE", "IN"}
_EDGES = {"EDGE_UNDIRECTED", "EDGE_OUT", "EDGE_IN"}
_STATEMENT_START = {"_DELETE", "_DETACH", "_CREATE", "_RETYPE", "_SET", "_MERGE", "_FOREACH"}
_MODES = {"_ONCE", "_ALL", "_FIXPOINT"}
_EDGE_HINT = "an edge pattern is written a -Type- b, a -Type-> b or a <-Type- b, with no spaces inside the arrow"
# What a NAME means right after these tokens.
_NAME_ROLE = {
    "_NODE": "a node type name",
    "_EDGE": "an edge type name",
    "_AS": "a node type name",
    "_RULE": "a rule name",
    "_STRATEGY": "a strategy name",
    "_SCHEMA": "a schema name",
    "_RUN": "a strategy name",
    "_DELETE": "a variable",
    "_RETYPE": "a variable",
    "_MERGE": "a variable",
    "_INTO": "a variable",
    "_SET": "a variable",
    "_FOREACH": "a variable",
    "DOT": "an attribute name",
}


@functools.lru_cache(maxsize=1)
def _terminal_words() -> dict[str, str]:
    words = dict(_TERMINAL_WORDS)
    for term in _lark().terminals:
        if term.name in words:
            continue
        if term.pattern.type == "str":
            words[term.name] = repr(term.pattern.value)
        elif term.name.lstrip("_").lower() in KEYWORDS | CONTEXTUAL_KEYWORDS:
            words[term.name] = repr(term.name.lstrip("_").lower())
    return words


def _describe_expected(expected: set[str], prev: Token | None) -> list[str]:
    """Readable words for a set of expected terminals, grouping expression starts and operators."""
    words = _terminal_words()
    expected = set(expected)
    out: list[str] = []
    if {"ADD", "MUL"} <= expected:
        expected -= _BINARY_OPS | {"DOT", "LSQB"}
        out.append("an operator")
    if "SEMICOLON" in expected:  # the optional separators are never worth suggesting
        expected -= {"SEMICOLON", "COMMA"}
    if _EXPRESSION_START - {"NOT"} <= expected:
        expected -= _EXPRESSION_START
        out.append("an expression")
    if _STATEMENT_START <= expected:
        expected -= _STATEMENT_START
        out.append("a statement (delete, detach delete, create, retype, set, merge, foreach)")
    if _EDGES <= expected:
        expected -= _EDGES
        out.append("an edge -Type-, -Type-> or <-Type-")
    if "NAME" in expected:
        expected.discard("NAME")
        role = _NAME_ROLE.get(prev.type) if prev is not None else None
        if role is None and prev is not None and prev.type == "COLON" and expected <= {"RBRACE"}:
            role = "a type name"
        out.append(role or "a name")
    rest = sorted(words.get(t, t) for t in expected if t not in _TERMINAL_WORDS or t == "$END")
    rest += sorted(words[t] for t in expected if t in _TERMINAL_WORDS and t != "$END")
    return out + rest


def _expected_hint(expected: set[str], prev: Token | None) -> str:
    described = _describe_expected(expected, prev)
    if not described:
        return ""
    if len(described) == 1:
        return f"expected {described[0]}"
    return "expected one of: " + ", ".join(described)


def _token_text(token: Token) -> str:
    if token.type == "$END":
        return "end of file"
    if token.type == "STRING":
        return f"string {token.value}"
    return repr(str(token.value))


def _end_pos(text: str, filename: str) -> SourcePos:
    lines = text.split("\n")
    return SourcePos(filename, len(lines), len(lines[-1]) + 1)


def _parse_tree(text: str, filename: str):
    """Parse ``text`` with lark, turning every lark error into a RuleSyntaxError."""
    parser = _lark().parse_interactive(text)
    prev: Token | None = None
    try:
        for token in parser.iter_parse():
            prev = token
        return parser.feed_eof(prev)
    except UnexpectedToken as exc:
        raise _token_error(exc, text, filename, prev) from None
    except UnexpectedCharacters as exc:
        raise _character_error(exc, text, filename, prev) from None
    except UnexpectedEOF as exc:  # pragma: no cover - LALR reports the end as an UnexpectedToken
        raise RuleSyntaxError(
            "unexpected end of file", _end_pos(text, filename), _expected_hint(set(exc.expected), prev)
        ) from None
    except UnexpectedInput as exc:  # pragma: no cover
        raise RuleSyntaxError(f"syntax error: {exc}", SourcePos(filename, exc.line, exc.column)) from None


def _token_error(exc: UnexpectedToken, text: str, filename: str, prev: Token | None) -> RuleSyntaxError:
    token = exc.token
    expected = set(exc.expected)
    at_end = token.type == "$END"
    pos = _end_pos(text, filename) if at_end else SourcePos(filename, token.line, token.column)
    message = "unexpected end of file" if at_end else f"unexpected {_token_text(token)}"
    hint = _expected_hint(expected, prev)
    word = str(token.value)
    extra = None

    after = text[token.end_pos : token.end_pos + 1] if not at_end and token.end_pos is not None else ""

    if token.type in {"INT", "FLOAT", "SIGNED_INT"} and (after.isalnum() or after in "._"):
        message, extra = "malformed number", "numbers are written 3, 2.5, .5 or 1e-3"
    elif expected & _EDGES:
        if token.type in {"SUB", "LT", "__ANON_0", "__ANON_1"}:
            message = "malformed edge pattern"
        extra = _EDGE_HINT
    elif prev is not None and prev.type == "COMMA" and expected == {"NAME"} and token.type in _STATEMENT_START:
        extra = "after delete a comma continues the list of variables; separate statements with ';' or a new line"
    elif word in KEYWORDS and "NAME" in expected:
        extra = f"'{word}' is a reserved keyword and cannot be used as a name"
    elif token.type in _COMPARISONS and "AND" in expected and "OR" in expected:
        message = f"comparisons do not chain: unexpected {_token_text(token)}"
        hint, extra = None, "write a < b and b < c"
    elif token.type == "EQUAL" and "EQ" in expected:
        hint, extra = None, "use == to compare; = only gives values in create, set and parameter defaults"
    elif "_MATCH" in expected:
        extra = "a rule body starts with its match block: match { ... } (it may be empty)"
    elif token.type in {"_WHERE", "NOT"} and _STATEMENT_START <= expected:
        hint, extra = None, "where and not { ... } come after match { ... } and before the rule's statements"
    elif expected & _MODES and not at_end:
        extra = "a strategy step ends with its mode: once, all or fixpoint [max N]"
    elif (prev is not None and prev.type == "_SET" and not at_end) or expected == {"DOT"}:
        extra = "set changes one attribute: set var.attr = value"
    elif at_end and "RBRACE" in expected:
        extra = "a block opened with '{' is not closed"
    if extra:
        hint = f"{hint}; {extra}" if hint else extra
    return RuleSyntaxError(message, pos, hint or None)


def _character_error(exc: UnexpectedCharacters, text: str, filename: str, prev: Token | None) -> RuleSyntaxError:
    pos = SourcePos(filename, exc.line, exc.column)
    char = exc.char
    allowed = set(exc.allowed or ())
    if char == '"':
        return RuleSyntaxError("unterminated string", pos, 'a string is written on one line between double quotes')
    if allowed & _EDGES and char in "-<":
        return RuleSyntaxError("malformed edge pattern", pos, _EDGE_HINT)
    if char.isdigit() or (char == "." and text[exc.pos_in_stream + 1 : exc.pos_in_stream + 2].isdigit()):
        return RuleSyntaxError("malformed number", pos, "numbers are written 3, 2.5, .5 or 1e-3")
    if char.isspace() or not char.isprintable():
        shown = repr(char)
    else:
        shown = f"'{char}'"
    return RuleSyntaxError(f"unexpected character {shown}", pos, _expected_hint(allowed, prev) or None)


# --------------------------------------------------------------------------------------------
# Parse tree -> AST
# --------------------------------------------------------------------------------------------


class _Where:
    """A ``where`` condition, until the rule or pattern that owns it is built."""

    __slots__ = ("expr",)

    def __init__(self, expr):
        self.expr = expr


class _Nac:
    """A ``not { ... }`` pattern, until its rule is built."""

    __slots__ = ("pattern",)

    def __init__(self, pattern: Pattern):
        self.pattern = pattern


_ESCAPES = {'"': '"', "\\": "\\", "n": "\n", "t": "\t", "r": "\r", "0": "\0"}


class _Edge(NamedTuple):
    """The parts of ``[var:] a -Type- b {...}`` (``<-Type-`` already turned around)."""

    var: str | None
    source: object  # a NAME token, or a NodeRef in a create statement
    target: object
    type: str
    directed: bool
    block: tuple  # constraints or attribute initialisations


def _by_class(items, *classes) -> tuple[tuple, ...]:
    """For each class, the items of that class, in their order."""
    return tuple(tuple(i for i in items if isinstance(i, c)) for c in classes)


def _constant(value):
    """A transformer method whose result is always ``value``."""
    return lambda self, meta, children: value


def _literal(convert):
    """A transformer method making a Literal of ``convert(token)`` (None: no token)."""
    return lambda self, meta, children: Literal(convert(*children), self._pos(meta))


def _endpoint(step: int):
    """A transformer method making the NodeRef of ``v``, ``next(v)`` (+1) or ``prev(v)`` (-1)."""
    return lambda self, meta, children: NodeRef(str(children[0]), step, self._pos(meta))


@v_args(meta=True)
class _ToAst(Transformer_NonRecursive):
    """Builds AST nodes; each method is named after the grammar rule (or alias) it transforms."""

    def __init__(self, filename: str):
        super().__init__()
        self.file = filename

    # -- helpers ------------------------------------------------------------------------------

    def _pos(self, meta) -> SourcePos:
        return SourcePos(self.file, meta.line, meta.column)

    def _tpos(self, token: Token) -> SourcePos:
        return SourcePos(self.file, token.line, token.column)

    @staticmethod
    def _present(children) -> list:
        return [c for c in children if c is not None]

    def _arrow(self, token: Token) -> tuple[str, str]:
        """(type name, direction "--" | "->" | "<-") of an edge arrow token."""
        if token.type == "EDGE_OUT":
            return token.value[1:-2], "->"
        if token.type == "EDGE_IN":
            return token.value[2:-1], "<-"
        return token.value[1:-1], "--"

    def _edge(self, children) -> _Edge:
        *var, source, arrow, target, block = children
        type_, direction = self._arrow(arrow)
        if direction == "<-":
            source, target = target, source
        return _Edge(str(var[0]) if var else None, source, target, type_, direction != "--", block)

    # -- file ---------------------------------------------------------------------------------

    def start(self, meta, children):
        parts = _by_class(children, Schema, Rule, Strategy, Include, Invariant)
        return RuleFile(self.file, *parts)

    def include(self, meta, children):
        (path,) = children
        return Include(self._unescape(path), self._pos(meta))

    # -- schema -------------------------------------------------------------------------------

    def schema(self, meta, children):
        name, *decls = children
        return Schema(str(name), *_by_class(decls, NodeTypeDecl, EdgeTypeDecl), self._pos(meta))

    def node_decl(self, meta, children):
        abstract, name, parent, attrs = children
        return NodeTypeDecl(str(name), parent, attrs, abstract, self._pos(meta))

    def edge_decl(self, meta, children):
        abstract, name, parent, (source, target, directed), attrs = children
        return EdgeTypeDecl(str(name), parent, source, target, directed, attrs, abstract, self._pos(meta))

    def abstract(self, meta, children):
        return bool(children)

    def parent(self, meta, children):
        return str(children[0]) if children else None

    no_endpoints = _constant((None, None, None))  # (source, target, directed)

    def undirected_endpoints(self, meta, children):
        return (*map(str, children), False)

    def directed_endpoints(self, meta, children):
        return (*map(str, children), True)

    def attr_decls(self, meta, children):
        return tuple(children)

    def attr_decl(self, meta, children):
        name, type_, *default = children
        return AttrDecl(str(name), str(type_), default[0] if default else None, self._pos(meta), self._tpos(type_))

    # -- rules --------------------------------------------------------------------------------

    def rule(self, meta, children):
        name, params, priority, match, *rest = children
        conditions = list(match.conditions)
        nacs: list[Pattern] = []
        statements = []
        for item in rest:
            if isinstance(item, _Where):
                conditions.append(item.expr)
            elif isinstance(item, _Nac):
                nacs.append(item.pattern)
            else:
                statements.append(item)
        match = Pattern(match.nodes, match.edges, tuple(conditions), match.pos)
        return Rule(str(name), params, priority, match, tuple(nacs), tuple(statements), self._pos(meta))

    def params(self, meta, children):
        return tuple(self._present(children))

    def param(self, meta, children):
        name, type_, *default = children
        return Param(str(name), str(type_), default[0] if default else None, self._pos(meta))

    def priority(self, meta, children):
        return int(children[0]) if children else 0

    def _pattern(self, meta, items) -> Pattern:
        nodes, edges, wheres = _by_class(items, NodePattern, EdgePattern, _Where)
        return Pattern(nodes, edges, tuple(w.expr for w in wheres), self._pos(meta))

    def match(self, meta, children):
        return self._pattern(meta, children)

    def nac(self, meta, children):
        _not, *items = children
        return _Nac(self._pattern(meta, items))

    def where(self, meta, children):
        return _Where(children[0])

    def node_pattern(self, meta, children):
        var, type_, constraints = children
        return NodePattern(str(var), str(type_), constraints, self._pos(meta))

    def edge_pattern(self, meta, children):
        e = self._edge(children)
        return EdgePattern(e.var, str(e.source), str(e.target), e.type, e.directed, e.block, self._pos(meta))

    def constraints(self, meta, children):
        return tuple(children)

    def constraint_eq(self, meta, children):
        attr, value = children
        return Constraint(str(attr), "==", value, self._pos(meta))

    def constraint_op(self, meta, children):
        attr, op, value = children
        return Constraint(str(attr), str(op), value, self._pos(meta))

    # -- statements ---------------------------------------------------------------------------

    def delete(self, meta, children):
        return Delete(tuple(str(c) for c in children), False, self._pos(meta))

    def detach_delete(self, meta, children):
        return Delete(tuple(str(c) for c in children), True, self._pos(meta))

    def create_node(self, meta, children):
        var, type_, attrs = children
        return CreateNode(str(var), str(type_), attrs, self._pos(meta))

    def create_edge(self, meta, children):
        e = self._edge(children)
        return CreateEdge(e.var, e.source, e.target, e.type, e.directed, e.block, self._pos(meta))

    endpoint_var = _endpoint(0)
    endpoint_next = _endpoint(1)
    endpoint_prev = _endpoint(-1)

    def attr_inits(self, meta, children):
        return tuple(children)

    def attr_init(self, meta, children):
        attr, value = children
        return AttrInit(str(attr), value, self._pos(meta))

    def retype(self, meta, children):
        var, type_ = children
        return Retype(str(var), str(type_), self._pos(meta))

    def set_attr(self, meta, children):
        var, attr, value = children
        return SetAttr(str(var), str(attr), value, self._pos(meta))

    def merge(self, meta, children):
        source, target = children
        return Merge(str(source), str(target), self._pos(meta))

    def foreach(self, meta, children):
        i = next(k for k, c in enumerate(children) if isinstance(c, Token) and c.type in _EDGES)
        edge_var = str(children[0]) if i == 2 else None
        center, arrow, neighbour = children[i - 1], children[i], children[i + 1]
        narrowed, condition = children[i + 2], children[i + 3]
        type_, direction = self._arrow(arrow)
        return Foreach(
            edge_var=edge_var,
            center=str(center),
            neighbour=str(neighbour),
            type=type_,
            direction=direction,
            condition=condition,
            body=tuple(children[i + 4 :]),
            pos=self._pos(meta),
            neighbour_type=narrowed,
        )

    def foreach_type(self, meta, children):
        return str(children[0]) if children else None

    def foreach_where(self, meta, children):
        return children[0] if children else None

    # -- invariants ---------------------------------------------------------------------------

    def invariant(self, meta, children):
        name, when, strategies, condition = children
        return Invariant(str(name), when, strategies, condition, self._pos(meta))

    after_each = _constant("each")
    at_end = _constant("end")

    def invariant_scope(self, meta, children):
        return tuple(str(c) for c in children if c is not None and c.type == "NAME")

    def quantifier(self, meta, children):
        kind, var, type_, body = children
        return Quantifier(str(kind), str(var), str(type_), body, self._pos(meta))

    # -- strategies ---------------------------------------------------------------------------

    def strategy(self, meta, children):
        name, *steps = children
        return Strategy(str(name), tuple(steps), self._pos(meta))

    def step(self, meta, children):
        *rules, (mode, max_steps) = children
        return Step(tuple(rules), mode, max_steps, False, self._pos(meta))

    def choose_step(self, meta, children):
        *rules, (mode, max_steps) = children
        return Step(tuple(rules), mode, max_steps, True, self._pos(meta))

    def run(self, meta, children):
        return Run(str(children[0]), self._pos(meta))

    def rule_ref(self, meta, children):
        name, *args = self._present(children)
        return RuleRef(str(name), tuple(args), self._pos(meta))

    def rule_arg(self, meta, children):
        name, value = children
        return (str(name), value)

    mode_once = _constant(("once", None))  # (mode, max_steps)
    mode_all = _constant(("all", None))

    def mode_fixpoint(self, meta, children):
        return ("fixpoint", int(children[0]) if children else None)

    # -- expressions --------------------------------------------------------------------------

    def binary(self, meta, children):
        left, op, right = children
        return Binary(str(op), left, right, self._tpos(op))

    def unary(self, meta, children):
        op, operand = children
        if (
            op == "-"
            and isinstance(operand, Literal)
            and isinstance(operand.value, (int, float))
            and not isinstance(operand.value, bool)
        ):
            return Literal(-operand.value, self._tpos(op))
        return Unary(str(op), operand, self._tpos(op))

    def attr(self, meta, children):
        target, name = children
        return Attr(target, str(name), self._tpos(name))

    def index(self, meta, children):
        target, index = children
        return Index(target, index, self._pos(meta))

    def call(self, meta, children):
        func, *args = self._present(children)
        return Call(str(func), tuple(args), self._pos(meta))

    def name(self, meta, children):
        return Name(str(children[0]), self._pos(meta))

    int_literal = _literal(int)
    float_literal = _literal(float)
    true_literal = _literal(lambda: True)
    false_literal = _literal(lambda: False)
    none_literal = _literal(lambda: None)

    def string_literal(self, meta, children):
        return Literal(self._unescape(children[0]), self._pos(meta))

    def list_expr(self, meta, children):
        return ListExpr(tuple(self._present(children)), self._pos(meta))

    def _unescape(self, token: Token) -> str:
        body = token.value[1:-1]
        out: list[str] = []
        i = 0
        while i < len(body):
            ch = body[i]
            if ch != "\\":
                out.append(ch)
                i += 1
                continue
            esc = body[i + 1]
            where = SourcePos(self.file, token.line, token.column + 1 + i)
            if esc in _ESCAPES:
                out.append(_ESCAPES[esc])
                i += 2
            elif esc == "u" and len(body) >= i + 6 and all(c in "0123456789abcdefABCDEF" for c in body[i + 2 : i + 6]):
                out.append(chr(int(body[i + 2 : i + 6], 16)))
                i += 6
            else:
                raise RuleSyntaxError(
                    f"unknown escape '\\{esc}' in string",
                    where,
                    'escapes are \\" \\\\ \\n \\t \\r \\0 and \\uXXXX',
                )
        return "".join(out)
