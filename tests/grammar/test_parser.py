"""Tests of the rule language's parser: grammar/rules.lark and grammar/parser.py.

Most tests compare the exact AST with positions stripped (``_nopos``), and check positions separately.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

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
    ListExpr,
    Literal,
    Merge,
    Name,
    NodePattern,
    NodeRef,
    NodeTypeDecl,
    Param,
    Pattern,
    Retype,
    RuleRef,
    Run,
    Schema,
    SetAttr,
    Step,
    Unary,
)
from vaultgram.grammar.errors import RuleSyntaxError, SourcePos
from vaultgram.grammar.parser import load_files, parse_file, parse_text

from paths import REPO

F = "t.vgr"


def P(line: int, column: int) -> SourcePos:
    return SourcePos(F, line, column)


def _nopos(value):
    """A copy of an AST value with every ``pos`` set to None."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        changes = {f.name: _nopos(getattr(value, f.name)) for f in dataclasses.fields(value)}
        if "pos" in changes:
            changes["pos"] = None
        return dataclasses.replace(value, **changes)
    if isinstance(value, tuple):
        return tuple(_nopos(v) for v in value)
    return value


# Position-free constructors for expected ASTs.
def lit(v):
    return Literal(v, None)


def nm(n):
    return Name(n, None)


def bn(op, left, right):
    return Binary(op, left, right, None)


def un(op, operand):
    return Unary(op, operand, None)


def at(target, attr):
    return Attr(target, attr, None)


def call(f, *args):
    return Call(f, tuple(args), None)


def ref(v, step=0):
    return NodeRef(v, step, None)


def parse(text: str):
    return parse_text(text, F)


def rule_of(body: str, header: str = "rule r"):
    return parse(f"{header} {{\n{body}\n}}").rules[0]


def expr(text: str):
    """The AST (without positions) of one expression, parsed as a where condition."""
    return _nopos(parse(f"rule r {{ match {{ }} where {text} }}").rules[0].match.conditions[0])


def syntax_error(text: str) -> RuleSyntaxError:
    with pytest.raises(RuleSyntaxError) as info:
        parse(text)
    return info.value


# --------------------------------------------------------------------------------------------
# Lexical structure
# --------------------------------------------------------------------------------------------


def test_empty_file_and_comments():
    rf = parse("# only a comment\n\n   # another\n")
    assert rf.path == F
    assert rf.schemas == rf.rules == rf.strategies == rf.includes == ()


def test_separators_are_optional_everywhere():
    a = parse("rule r { match { a: X; b: Y, a -E- b } where a.k > 1; delete a; set b.k = 1 }")
    b = parse("rule r {\n match {\n a: X\n b: Y\n a -E- b\n }\n where a.k > 1\n delete a\n set b.k = 1\n}")
    assert _nopos(a) == _nopos(b)


def test_literals():
    assert expr("12") == lit(12)
    assert expr("1.5") == lit(1.5)
    assert expr("1e-3") == lit(0.001)
    assert expr(".5") == lit(0.5)
    assert expr("2.") == lit(2.0)
    assert expr("2.5E+2") == lit(250.0)
    assert expr("true") == lit(True)
    assert expr("false") == lit(False)
    assert expr("none") == lit(None)
    assert expr(r'"a\"b\\c\nd\te\u00e9"') == lit('a"b\\c\nd\te\u00e9')
    assert expr('"# not a comment"') == lit("# not a comment")


def test_keywords_are_words():
    # names that merely start with a keyword are names
    assert expr("matches + nothing + order + index + creates") == bn(
        "+", bn("+", bn("+", bn("+", nm("matches"), nm("nothing")), nm("order")), nm("index")), nm("creates")
    )
    # contextual keywords are names outside their place
    assert expr("max(once, all) + next(fixpoint) + prev") == bn(
        "+", bn("+", call("max", nm("once"), nm("all")), call("next", nm("fixpoint"))), nm("prev")
    )


def test_keyword_glued_to_name_is_a_name_not_two_tokens():
    err = syntax_error("rule r { match { } createn: X }")
    assert (err.pos.line, err.pos.column) == (1, 20)
    assert err.message == "unexpected 'createn'"


# --------------------------------------------------------------------------------------------
# Schema
# --------------------------------------------------------------------------------------------

SCHEMA = """\
schema decomposition {
  abstract node Point { pos: vec2 }
  node Singularity : Point { valence: int = 0, kind: str = "a" }
  node Corner : Point
  edge Branch (Point -- Point) { length: float = 0.0 }
  edge Dual (Singularity -> Corner)
  edge Rebranch : Branch
  abstract edge Link
  edge Sub : Dual (Singularity -> Corner) { w: list = [1, 2] }
}
"""


def test_schema_ast():
    (schema,) = parse(SCHEMA).schemas
    assert _nopos(schema) == Schema(
        name="decomposition",
        nodes=(
            NodeTypeDecl("Point", None, (AttrDecl("pos", "vec2", None, None),), True, None),
            NodeTypeDecl(
                "Singularity",
                "Point",
                (AttrDecl("valence", "int", lit(0), None), AttrDecl("kind", "str", lit("a"), None)),
                False,
                None,
            ),
            NodeTypeDecl("Corner", "Point", (), False, None),
        ),
        edges=(
            EdgeTypeDecl(
                "Branch", None, "Point", "Point", False, (AttrDecl("length", "float", lit(0.0), None),), False, None
            ),
            EdgeTypeDecl("Dual", None, "Singularity", "Corner", True, (), False, None),
            EdgeTypeDecl("Rebranch", "Branch", None, None, None, (), False, None),
            EdgeTypeDecl("Link", None, None, None, None, (), True, None),
            EdgeTypeDecl(
                "Sub", "Dual", "Singularity", "Corner", True,
                (AttrDecl("w", "list", ListExpr((lit(1), lit(2)), None), None),), False, None,
            ),
        ),
        pos=None,
    )


def test_schema_positions():
    (schema,) = parse(SCHEMA).schemas
    assert schema.pos == P(1, 1)
    assert schema.nodes[0].pos == P(2, 3)  # at `abstract`
    assert schema.nodes[0].attrs[0].pos == P(2, 25)
    assert schema.nodes[1].pos == P(3, 3)
    assert schema.nodes[1].attrs[0].default.pos == P(3, 45)
    assert schema.edges[0].pos == P(5, 3)
    assert schema.edges[2].pos == P(7, 3)


def test_all_attribute_types():
    types = ["int", "float", "bool", "str", "vec2", "vec3", "list", "any"]
    text = "schema s { node A { " + " ".join(f"a{i}: {t}" for i, t in enumerate(types)) + " } }"
    assert [a.type for a in parse(text).schemas[0].nodes[0].attrs] == types
    # an unknown type is the engine's to report (tests/engine: test_unknown_attribute_type); the
    # parser only records where it is written
    assert parse("schema s {\n  node A { x: vec4 }\n}").schemas[0].nodes[0].attrs[0].type_pos == P(2, 15)


# --------------------------------------------------------------------------------------------
# Patterns
# --------------------------------------------------------------------------------------------


def test_node_pattern_with_constraints():
    rule = rule_of('match {\n  s: Singularity { valence >= 3, kind: "a" }\n  c: Corner {}\n}')
    s, c = rule.match.nodes
    assert _nopos(s) == NodePattern(
        "s", "Singularity", (Constraint("valence", ">=", lit(3), None), Constraint("kind", "==", lit("a"), None)), None
    )
    assert _nopos(c) == NodePattern("c", "Corner", (), None)
    assert s.pos == P(3, 3)
    assert s.constraints[0].pos == P(3, 20)
    assert s.constraints[1].pos == P(3, 34)
    assert s.constraints[1].value.pos == P(3, 40)
    assert rule.match.pos == P(2, 1)


def test_constraint_operators():
    rule = rule_of("match { a: X { p == 1 q != 2 r < 3 s <= 4 t > 5 u >= 6 v in [1] } }")
    assert [(c.attr, c.op) for c in rule.match.nodes[0].constraints] == [
        ("p", "=="), ("q", "!="), ("r", "<"), ("s", "<="), ("t", ">"), ("u", ">="), ("v", "in"),
    ]


def test_edge_patterns():
    rule = rule_of(
        "match {\n"
        "  b: s -Branch- c\n"
        "  s -Dual-> v\n"
        "  v <-Dual- s\n"
        "  e: a -Long_2- b2 { length < 3.5 }\n"
        "  x -E->y\n"
        "}"
    )
    assert _nopos(rule.match.edges) == (
        EdgePattern("b", "s", "c", "Branch", False, (), None),
        EdgePattern(None, "s", "v", "Dual", True, (), None),
        EdgePattern(None, "s", "v", "Dual", True, (), None),  # reversed arrow: source s, target v
        EdgePattern("e", "a", "b2", "Long_2", False, (Constraint("length", "<", lit(3.5), None),), None),
        EdgePattern(None, "x", "y", "E", True, (), None),
    )
    assert [e.pos for e in rule.match.edges] == [P(3, 3), P(4, 3), P(5, 3), P(6, 3), P(7, 3)]
    assert rule.match.nodes == ()


def test_empty_match_and_defaults():
    rule = rule_of("match { }")
    assert _nopos(rule.match) == Pattern((), (), (), None)
    assert rule.params == () and rule.priority == 0 and rule.nacs == () and rule.statements == ()
    assert rule.name == "r" and rule.pos == P(1, 1)


def test_where_and_nacs():
    rule = rule_of(
        "match { s: S  c: C }\n"
        "where degree(s, Branch) >= 3\n"
        "not { s -Rebranch- c }\n"
        "where s.k < 1\n"
        "not { w: Corner  s -Branch- w  where w.valence == 2  where true }"
    )
    assert _nopos(rule.match.conditions) == (
        bn(">=", call("degree", nm("s"), nm("Branch")), lit(3)),
        bn("<", at(nm("s"), "k"), lit(1)),
    )
    n1, n2 = rule.nacs
    assert _nopos(n1) == Pattern((), (EdgePattern(None, "s", "c", "Rebranch", False, (), None),), (), None)
    assert _nopos(n2) == Pattern(
        (NodePattern("w", "Corner", (), None),),
        (EdgePattern(None, "s", "w", "Branch", False, (), None),),
        (bn("==", at(nm("w"), "valence"), lit(2)), lit(True)),
        None,
    )
    assert n1.pos == P(4, 1) and n2.pos == P(6, 1)
    assert rule.match.conditions[0].pos == P(3, 25)  # a Binary is at its operator


def test_where_inside_match_block_comes_first():
    rule = rule_of("match { a: X where a.k > 0 }\nwhere a.j > 0")
    assert _nopos(rule.match.conditions) == (
        bn(">", at(nm("a"), "k"), lit(0)),
        bn(">", at(nm("a"), "j"), lit(0)),
    )


# --------------------------------------------------------------------------------------------
# Expressions
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("op", ["+", "-", "*", "/", "%", "==", "!=", "<", "<=", ">", ">=", "and", "or", "in"])
def test_binary_operators(op):
    assert expr(f"a {op} b") == bn(op, nm("a"), nm("b"))


def test_unary_operators():
    assert expr("-a") == un("-", nm("a"))
    assert expr("not a") == un("not", nm("a"))
    assert expr("-2") == lit(-2)  # a negative number literal is folded
    assert expr("-1.5") == lit(-1.5)
    assert expr("- -a") == un("-", un("-", nm("a")))
    assert expr("not not a") == un("not", un("not", nm("a")))
    assert expr("a<-1") == bn("<", nm("a"), lit(-1))  # not a reversed edge arrow


def test_postfix():
    assert expr("s.pos") == at(nm("s"), "pos")
    assert expr("s.pos.x") == at(at(nm("s"), "pos"), "x")
    assert expr("s.pos[0]") == Index(at(nm("s"), "pos"), lit(0), None)
    assert expr("f()") == call("f")
    assert expr("f(x, y.z, 1,)") == call("f", nm("x"), at(nm("y"), "z"), lit(1))
    assert expr("f(x).y[1]") == Index(at(call("f", nm("x")), "y"), lit(1), None)
    assert expr("[1, 2][0]") == Index(ListExpr((lit(1), lit(2)), None), lit(0), None)
    assert expr("(a + b).c") == at(bn("+", nm("a"), nm("b")), "c")
    assert expr("[]") == ListExpr((), None)


def test_precedence():
    a, b, c, d = nm("a"), nm("b"), nm("c"), nm("d")
    assert expr("a or b and c") == bn("or", a, bn("and", b, c))
    assert expr("a and b or c") == bn("or", bn("and", a, b), c)
    assert expr("not a and b") == bn("and", un("not", a), b)
    assert expr("not a == b") == un("not", bn("==", a, b))
    assert expr("a + b < c * d") == bn("<", bn("+", a, b), bn("*", c, d))
    assert expr("a - b - c") == bn("-", bn("-", a, b), c)
    assert expr("a + b * c") == bn("+", a, bn("*", b, c))
    assert expr("a * b % c / d") == bn("/", bn("%", bn("*", a, b), c), d)
    assert expr("-a * b") == bn("*", un("-", a), b)
    assert expr("-a.b") == un("-", at(a, "b"))
    assert expr("(a + b) * c") == bn("*", bn("+", a, b), c)
    assert expr("a in [1, 2] or b") == bn("or", bn("in", a, ListExpr((lit(1), lit(2)), None)), b)
    assert expr("s.pos[0] > -1.5 * (2 + 3) % 4 or not (c.valence in [1, 2, 3])") == bn(
        "or",
        bn(">", Index(at(nm("s"), "pos"), lit(0), None), bn("%", bn("*", lit(-1.5), bn("+", lit(2), lit(3))), lit(4))),
        un("not", bn("in", at(nm("c"), "valence"), ListExpr((lit(1), lit(2), lit(3)), None))),
    )


def test_expression_positions():
    e = parse("rule r { match { } where\n  f(a.b, -x) + 1 }").rules[0].match.conditions[0]
    assert e.pos == P(2, 14)  # the `+`
    call_ = e.left
    assert call_.pos == P(2, 3)
    assert call_.args[0].pos == P(2, 7)  # Attr: at the attribute name
    assert call_.args[0].target.pos == P(2, 5)
    assert call_.args[1].pos == P(2, 10) and call_.args[1].operand.pos == P(2, 11)
    assert e.right.pos == P(2, 16)


def test_comparisons_do_not_chain():
    err = syntax_error("rule r { match { } where a < b < c }")
    assert err.pos == P(1, 32)
    assert "chain" in err.message and "and" in err.hint


# --------------------------------------------------------------------------------------------
# Rules: params, priority, statements
# --------------------------------------------------------------------------------------------


def test_params_and_priority():
    rf = parse(
        "rule a(max_len: float = 2.5, seed: Singularity, n: int = -1) priority 10 { match { } }\n"
        "rule b() priority -3 { match { } }\n"
        "rule c { match { } }"
    )
    a, b, c = rf.rules
    assert _nopos(a.params) == (
        Param("max_len", "float", lit(2.5), None),
        Param("seed", "Singularity", None, None),
        Param("n", "int", lit(-1), None),
    )
    assert a.params[1].pos == P(1, 30)
    assert (a.priority, b.priority, c.priority) == (10, -3, 0)
    assert b.params == c.params == ()
    assert [r.pos for r in rf.rules] == [P(1, 1), P(2, 1), P(3, 1)]


def test_delete_statements():
    rule = rule_of("match { }\ndelete b\ndelete a, b,\n  c; detach delete c\ndetach delete x, y")
    assert _nopos(rule.statements) == (
        Delete(("b",), False, None),
        Delete(("a", "b", "c"), False, None),
        Delete(("c",), True, None),
        Delete(("x", "y"), True, None),
    )
    assert [s.pos for s in rule.statements] == [P(3, 1), P(4, 1), P(5, 6), P(6, 1)]


def test_create_statements():
    rule = rule_of(
        "match { }\n"
        "create n: Singularity { pos = midpoint(s.pos, c.pos), valence = 3 }\n"
        "create m: Corner\n"
        "create s -Rebranch- v\n"
        "create e: n -Dual-> v { }\n"
        "create v <-Dual- n { w = 1.0 }"
    )
    assert _nopos(rule.statements) == (
        CreateNode(
            "n",
            "Singularity",
            (
                AttrInit("pos", call("midpoint", at(nm("s"), "pos"), at(nm("c"), "pos")), None),
                AttrInit("valence", lit(3), None),
            ),
            None,
        ),
        CreateNode("m", "Corner", (), None),
        CreateEdge(None, ref("s"), ref("v"), "Rebranch", False, (), None),
        CreateEdge("e", ref("n"), ref("v"), "Dual", True, (), None),
        CreateEdge(None, ref("n"), ref("v"), "Dual", True, (AttrInit("w", lit(1.0), None),), None),
    )
    first = rule.statements[0]
    assert first.pos == P(3, 1) and first.attrs[1].pos == P(3, 55)
    edge = rule.statements[3]
    assert edge.pos == P(6, 1) and edge.source.pos == P(6, 11) and edge.target.pos == P(6, 21)


def test_retype_set_merge():
    rule = rule_of("match { }\nretype s as Corner\nset s.valence = s.valence + 1\nmerge c into s")
    assert _nopos(rule.statements) == (
        Retype("s", "Corner", None),
        SetAttr("s", "valence", bn("+", at(nm("s"), "valence"), lit(1)), None),
        Merge("c", "s", None),
    )
    assert [s.pos for s in rule.statements] == [P(3, 1), P(4, 1), P(5, 1)]


def test_foreach_with_next_and_prev():
    rule = rule_of(
        "match { s: Singularity }\n"
        "foreach e: s -Branch- m where m.valence > 0 {\n"
        "  create r: Singularity { pos = lerp(s.pos, m.pos, 0.3) }\n"
        "  create r -Branch- next(r)\n"
        "  create prev(r) -Branch-> r\n"
        "  delete e\n"
        "}\n"
        "foreach s -Dual-> v { }\n"
        "foreach s <-Dual- v { foreach v -X- w { merge w into v } }"
    )
    f1, f2, f3 = rule.statements
    assert _nopos(f1) == Foreach(
        edge_var="e",
        center="s",
        neighbour="m",
        type="Branch",
        direction="--",
        condition=bn(">", at(nm("m"), "valence"), lit(0)),
        body=(
            CreateNode(
                "r",
                "Singularity",
                (AttrInit("pos", call("lerp", at(nm("s"), "pos"), at(nm("m"), "pos"), lit(0.3)), None),),
                None,
            ),
            CreateEdge(None, ref("r"), ref("r", 1), "Branch", False, (), None),
            CreateEdge(None, ref("r", -1), ref("r"), "Branch", True, (), None),
            Delete(("e",), False, None),
        ),
        pos=None,
    )
    assert _nopos(f2) == Foreach(None, "s", "v", "Dual", "->", None, (), None)
    assert _nopos(f3) == Foreach(
        None,
        "s",
        "v",
        "Dual",
        "<-",
        None,
        (Foreach(None, "v", "w", "X", "--", None, (Merge("w", "v", None),), None),),
        None,
    )
    assert f1.pos == P(3, 1) and f2.pos == P(9, 1)
    assert f1.body[1].target.pos == P(5, 21)  # at `next`
    assert f1.body[2].source.pos == P(6, 10)


def test_full_rule_order():
    rule = rule_of(
        "match { a: X }\nwhere a.k > 0\nnot { a -E- b }\ndelete a\ncreate b: X",
        header="rule full(k: int = 1) priority 2",
    )
    assert rule.name == "full" and rule.priority == 2 and len(rule.params) == 1
    assert len(rule.match.conditions) == 1 and len(rule.nacs) == 1
    assert [type(s) for s in rule.statements] == [Delete, CreateNode]


# --------------------------------------------------------------------------------------------
# Strategies
# --------------------------------------------------------------------------------------------


def test_strategy_forms():
    (s,) = parse(
        "strategy topology {\n"
        "  prune all\n"
        "  rebranch(max_len = 3.0, k = -1) once\n"
        "  { split_a, split_b } fixpoint max 500\n"
        "  { split_a split_b; c() } fixpoint\n"
        "  choose { variant_a, variant_b } once\n"
        "  run other_strategy\n"
        "}"
    ).strategies
    assert s.name == "topology" and s.pos == P(1, 1)
    assert _nopos(s.steps) == (
        Step((RuleRef("prune", (), None),), "all", None, False, None),
        Step((RuleRef("rebranch", (("max_len", lit(3.0)), ("k", lit(-1))), None),), "once", None, False, None),
        Step((RuleRef("split_a", (), None), RuleRef("split_b", (), None)), "fixpoint", 500, False, None),
        Step(
            (RuleRef("split_a", (), None), RuleRef("split_b", (), None), RuleRef("c", (), None)),
            "fixpoint",
            None,
            False,
            None,
        ),
        Step((RuleRef("variant_a", (), None), RuleRef("variant_b", (), None)), "once", None, True, None),
        Run("other_strategy", None),
    )
    assert [step.pos for step in s.steps] == [P(2, 3), P(3, 3), P(4, 3), P(5, 3), P(6, 3), P(7, 3)]
    assert s.steps[1].rules[0].pos == P(3, 3)
    assert s.steps[2].rules[1].pos == P(4, 14)


def test_contextual_keywords_as_rule_names():
    (s,) = parse("strategy s { once once  all all  max fixpoint max 3  next once }").strategies
    assert [(st.rules[0].name, st.mode, st.max_steps) for st in s.steps] == [
        ("once", "once", None), ("all", "all", None), ("max", "fixpoint", 3), ("next", "once", None),
    ]


# --------------------------------------------------------------------------------------------
# The example from the brief, whole
# --------------------------------------------------------------------------------------------


FULL = """\
include "schema.vgr"
schema decomposition {
  abstract node Point { pos: vec2 }
  node Singularity : Point { valence: int = 0 }
  node Corner : Point
  edge Branch (Point -- Point) { length: float = 0.0 }
  edge Dual (Singularity -> Corner)
  edge Rebranch : Branch
}
rule prune_corner_branch(max_len: float = 2.5) priority 10 {
  match {
    s: Singularity { valence >= 3, kind: "a" }
    c: Corner
    b: s -Branch- c
    s -Dual-> v
    v <-Dual- s
    v: Corner
  }
  where degree(s, Branch) >= 3 and distance(s.pos, c.pos) < max_len
  not { s -Rebranch- v }
  delete b
  detach delete c
  create n: Singularity { pos = midpoint(s.pos, c.pos), valence = 3 }
  create e: n -Dual-> v { }
  retype s as Corner
  set s.valence = s.valence + 1
  merge c into s
  foreach e: s -Branch- m where m.valence > 0 {
    create r -Branch- next(r)
  }
}
strategy topology {
  prune_corner_branch all
  run other
}
"""


def test_full_example_parses():
    rf = parse(FULL)
    assert _nopos(rf.includes) == (Include("schema.vgr", None),)
    assert rf.includes[0].pos == P(1, 1)
    assert len(rf.schemas) == 1 and len(rf.rules) == 1 and len(rf.strategies) == 1
    rule = rf.rules[0]
    assert len(rule.match.nodes) == 3 and len(rule.match.edges) == 3
    assert len(rule.statements) == 8


# --------------------------------------------------------------------------------------------
# Includes
# --------------------------------------------------------------------------------------------


def _write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def test_parse_file_records_includes(tmp_path):
    f = _write(tmp_path / "a.vgr", 'include "b.vgr"\ninclude "sub/c.vgr"\n')
    rf = parse_file(f)
    assert rf.path == str(f)
    assert [i.path for i in rf.includes] == ["b.vgr", "sub/c.vgr"]
    assert rf.includes[1].pos == SourcePos(str(f), 2, 1)


def test_load_files_order_and_relative_paths(tmp_path):
    _write(tmp_path / "schema.vgr", "schema s { node A }")
    _write(tmp_path / "lib" / "helpers.vgr", 'include "../schema.vgr"\nrule h { match { } }')
    _write(tmp_path / "lib" / "more.vgr", 'include "helpers.vgr"\nrule m { match { } }')
    main = _write(tmp_path / "main.vgr", 'include "lib/more.vgr"\ninclude "schema.vgr"\nrule r { match { } }')
    other = _write(tmp_path / "other.vgr", 'include "lib/helpers.vgr"\nstrategy s { r once }')
    files = load_files([main, other, main])
    names = [Path(f.path).name for f in files]
    assert names == ["schema.vgr", "helpers.vgr", "more.vgr", "main.vgr", "other.vgr"]
    assert files[1].path == str(tmp_path / "lib" / "helpers.vgr")
    assert files[0].schemas[0].name == "s" and files[3].rules[0].name == "r"


def test_include_cycle(tmp_path):
    _write(tmp_path / "a.vgr", 'include "b.vgr"')
    _write(tmp_path / "b.vgr", '# b\n  include "a.vgr"')
    with pytest.raises(RuleSyntaxError) as info:
        load_files([tmp_path / "a.vgr"])
    err = info.value
    assert err.pos == SourcePos(str(tmp_path / "b.vgr"), 2, 3)
    assert "cycle" in err.message and "a.vgr -> " in err.message


def test_self_include(tmp_path):
    _write(tmp_path / "a.vgr", 'include "a.vgr"')
    with pytest.raises(RuleSyntaxError) as info:
        load_files([tmp_path / "a.vgr"])
    assert info.value.pos == SourcePos(str(tmp_path / "a.vgr"), 1, 1)


def test_missing_include(tmp_path):
    _write(tmp_path / "a.vgr", 'rule r { match { } }\ninclude "nope.vgr"')
    with pytest.raises(RuleSyntaxError) as info:
        load_files([tmp_path / "a.vgr"])
    err = info.value
    assert err.pos == SourcePos(str(tmp_path / "a.vgr"), 2, 1)
    assert "nope.vgr" in err.message


def test_missing_top_level_file(tmp_path):
    missing = tmp_path / "missing.vgr"
    with pytest.raises(RuleSyntaxError) as info:
        load_files([missing])
    assert str(missing) in str(info.value) and info.value.pos is None
    with pytest.raises(RuleSyntaxError):
        parse_file(missing)


def test_syntax_error_in_included_file(tmp_path):
    _write(tmp_path / "a.vgr", 'include "b.vgr"')
    _write(tmp_path / "b.vgr", "rule r {\n  match { a -E b }\n}")
    with pytest.raises(RuleSyntaxError) as info:
        load_files([tmp_path / "a.vgr"])
    assert info.value.pos == SourcePos(str(tmp_path / "b.vgr"), 2, 13)


# --------------------------------------------------------------------------------------------
# Syntax errors
# --------------------------------------------------------------------------------------------

ERRORS = [
    # text, line, column, words in the message, words in the hint
    ("rule r {\n  match { s -Branch c }\n}", 2, 13, "malformed edge pattern", "a -Type- b"),
    ("rule r { match { s - Branch - c } }", 1, 20, "malformed edge pattern", "no spaces"),
    ("rule r {\n  delete a\n}", 2, 3, "unexpected 'delete'", "match {"),
    ("rule r { match { } where a = b }", 1, 28, "unexpected '='", "=="),
    ("rule r { match { }\n delete a\n where x }", 3, 2, "unexpected 'where'", "before the rule's statements"),
    ("strategy s {\n  foo\n}", 3, 1, "unexpected '}'", "once, all or fixpoint"),
    ("rule r { match { } delete a, create b: X }", 1, 30, "unexpected 'create'", "separate statements"),
    ("rule r { match { } set s = 3 }", 1, 26, "unexpected '='", "set var.attr = value"),
    ("rule r { match {\n  a: X\n", 3, 1, "unexpected end of file", "'}'"),
    ('include "abc\n', 1, 9, "unterminated string", "double quotes"),
    ("rule r { match { a: X } @ }", 1, 25, "unexpected character '@'", "statement"),
    ("schema s { node }", 1, 17, "unexpected '}'", "a node type name"),
    ("rule match { }", 1, 6, "unexpected 'match'", "reserved keyword"),
    ("rule r { match { s: } }", 1, 21, "unexpected '}'", "a type name"),
    ("rule r { match { } where 1abc }", 1, 26, "malformed number", "1e-3"),
    ('rule r { match { a: X { k: "x\\q" } } }', 1, 30, "unknown escape", "\\uXXXX"),
    ("rule r { match { } } }", 1, 22, "unexpected '}'", "'rule'"),
    ("rule r { match { } where }", 1, 26, "unexpected '}'", "an expression"),
    ("rule r(a float) { match { } }", 1, 10, "unexpected 'float'", "':'"),
    ("rule r { match { } create n: X { a: 1 } }", 1, 35, "unexpected ':'", "'='"),
    ("strategy s { { } once }", 1, 16, "unexpected '}'", "a name"),
    ("rule r priority x { match { } }", 1, 17, "unexpected 'x'", "an integer"),
    ("schema s { edge E (A <- B) }", 1, 22, "unexpected", "'--'"),
]


@pytest.mark.parametrize("text, line, column, message, hint", ERRORS)
def test_syntax_errors(text, line, column, message, hint):
    err = syntax_error(text)
    assert err.pos == P(line, column), str(err)
    assert message in err.message, str(err)
    assert err.hint and hint in err.hint, str(err)
    assert str(err).startswith(f"{F}:{line}:{column}: ")


# --------------------------------------------------------------------------------------------
# Robustness: nothing but RuleSyntaxError ever escapes
# --------------------------------------------------------------------------------------------

TOKENS = [
    "rule", "schema", "strategy", "include", "node", "edge", "abstract", "match", "where", "not", "and",
    "or", "in", "delete", "detach", "create", "retype", "as", "set", "merge", "into", "foreach", "choose",
    "run", "once", "all", "fixpoint", "max", "next", "prev", "priority", "true", "false", "none",
    "a", "b", "X", "Branch", "f", "{", "}", "(", ")", "[", "]", ":", ";", ",", ".", "=", "==", "!=",
    "<", "<=", ">", ">=", "+", "-", "*", "/", "%", "--", "->", "-E-", "-E->", "<-E-", "-E", "1", "2.5",
    ".5", "1e3", '"s"', '"', "\\", "#c\n", "\n", "@", "é", "\t", "\x00",
]


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.sampled_from(TOKENS), max_size=40), st.sampled_from([" ", "", "\n"]))
def test_token_soup_only_raises_syntax_errors(tokens, joiner):
    try:
        parse(joiner.join(tokens))
    except RuleSyntaxError as err:
        assert err.pos is not None and err.pos.line >= 1 and err.pos.column >= 1


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_mutated_files_only_raise_syntax_errors(data):
    text = FULL
    for _ in range(data.draw(st.integers(1, 4))):
        i = data.draw(st.integers(0, len(text)))
        j = data.draw(st.integers(i, min(len(text), i + 12)))
        insert = data.draw(st.sampled_from(["", "x", "-", "<", "{", "}", '"', "not", " where ", "(", ",", "1."]))
        text = text[:i] + insert + text[j:]
    try:
        rf = parse(text)
    except RuleSyntaxError as err:
        assert err.pos is not None
        lines = text.split("\n")
        assert 1 <= err.pos.line <= len(lines)
        assert 1 <= err.pos.column <= len(lines[err.pos.line - 1]) + 1
    else:
        assert rf.path == F


def test_deep_nesting_is_not_a_crash():
    parse("rule r { match { } where " + "(" * 3000 + "1" + ")" * 3000 + " }")


def test_language_reference_examples_parse():
    doc = REPO / "docs" / "language.md"
    if not doc.exists():
        pytest.skip("docs/language.md not present")
    blocks = doc.read_text(encoding="utf-8").split("```")[1::2]
    starts = ("schema", "rule", "include", "strategy", "invariant")
    complete = [b for b in blocks if b.split() and b.split()[0] in starts and "..." not in b]
    assert len(complete) >= 5
    for block in complete:
        parse(block)
