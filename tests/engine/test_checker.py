"""The engine's checker: every static error with its message and its line/column."""

from __future__ import annotations

import pytest

from vaultgram.engine.errors import RuleTypeError, SourcePos
from vaultgram.engine.expressions import Functions
from vaultgram.engine.rulebook import rulebook_from_text

from strategies.rules import SCHEMA, book

BASE = SCHEMA.count("\n")  # rules start on line BASE + 1


def fns():
    f = Functions()
    f.register("dist", lambda a, b: 0.0, ("vec2", "vec2"), "float")
    return f


def error(text: str) -> RuleTypeError:
    with pytest.raises(RuleTypeError) as info:
        book(text, fns())
    return info.value


CASES = [
    # (id, rule text, message fragment, line (relative), column or None)
    ("unknown node type", "rule r {\n  match { a: Nope }\n}", "unknown node type 'Nope'", 2, 11),
    ("unknown edge type", "rule r {\n  match { a: A  b: A  a -Nope- b }\n}", "unknown edge type 'Nope'", 2, 23),
    ("unknown attribute", "rule r {\n  match { a: A }\n  where a.zz > 1\n}", "no attribute 'zz'", 3, None),
    ("unknown attribute inline", "rule r {\n  match { a: A { zz: 1 } }\n}", "no attribute 'zz'", 2, None),
    ("unknown attribute in set", "rule r {\n  match { a: A }\n  set a.zz = 1\n}", "zz", 3, None),
    ("unknown attribute in create", "rule r {\n  match { }\n  create a: A { zz = 1 }\n}", "zz", 3, None),
    ("unknown function", "rule r {\n  match { a: A }\n  where frob(a.w) > 1\n}", "unknown function 'frob'", 3, 9),
    ("unbound variable", "rule r {\n  match { a: A }\n  where q.w > 1\n}", "unknown name 'q'", 3, 9),
    ("unbound in create edge", "rule r {\n  match { a: A }\n  create a -E- zz\n}", "zz", 3, None),
    ("undirected with arrow", "rule r {\n  match { a: A  b: A  a -E-> b }\n}", "edge type E is undirected", 2, 23),
    ("endpoints never fit", "rule r {\n  match { a: C  b: C  a -E- b }\n}", "can never fit", 2, 23),
    ("directed endpoints reversed", "rule r {\n  match { a: A  c: C  c -D-> a }\n}", "can never fit", 2, 23),
    (
        "abstract create",
        "schema x { abstract node Z }\nrule r {\n  match { }\n  create z: Z\n}",
        "abstract",
        4,
        3,
    ),
    (
        "missing required attribute",
        "schema x { node Q { req: int } }\nrule r {\n  match { }\n  create q: Q\n}",
        "req",
        4,
        3,
    ),
    ("next outside foreach", "rule r {\n  match { a: A  b: A }\n  create a -E- next(b)\n}", "next()/prev()", 3, None),
    ("prev outside foreach", "rule r {\n  match { a: A  b: A }\n  create a -E- prev(b)\n}", "next()/prev()", 3, None),
    ("wrong argument type", "rule r {\n  match { a: A }\n  where dist(a.w, a.w) > 1\n}", "must be vec2", 3, None),
    ("wrong argument count", "rule r {\n  match { a: A }\n  where dist(vec2(1, 2)) > 1\n}",
     "takes 2 argument(s), got 1", 3, 9),
    ("too many arguments", "rule r {\n  match { a: A }\n  where abs(1, 2) > 1\n}", "argument", 3, 9),
    ("set wrong type", "rule r {\n  match { a: A }\n  set a.w = \"s\"\n}", "attribute 'w' is int", 3, None),
    ("create wrong type", "rule r {\n  match { }\n  create a: A { w = 1.5 }\n}", "attribute 'w' is int", 3, None),
    ("duplicate rule", "rule r { match { } }\nrule r { match { } }", "defined twice", 2, 1),
    ("unknown rule in strategy", "rule r { match { } }\nstrategy s {\n  rr once\n}", "unknown rule 'rr'", 3, 3),
    ("unknown param in strategy", "rule r(k: int = 1) { match { } }\nstrategy s {\n  r(kk = 2) once\n}",
     "no parameter 'kk'", 3, None),
    ("param type in strategy", "rule r(k: int = 1) { match { } }\nstrategy s {\n  r(k = \"a\") once\n}",
     "must be int", 3, None),
    ("strategy cycle", "strategy s1 { run s2 }\nstrategy s2 { run s1 }", "cycle: s1 -> s2 -> s1", 1, 1),
    ("strategy self cycle", "strategy s1 {\n  run s1\n}", "cycle", 1, 1),
    ("unknown strategy", "strategy s1 {\n  run s3\n}", "unknown strategy 's3'", 2, 3),
    ("duplicate type", "schema x {\n  node A\n}", "declared twice", 2, None),
    ("delete unknown var", "rule r {\n  match { a: A }\n  delete zz\n}", "zz", 3, None),
    ("retype to abstract", "schema x { abstract node Z }\nrule r {\n  match { a: A }\n  retype a as Z\n}",
     "abstract", 4, 3),
    ("foreach center not a node", "rule r {\n  match { a: A }\n  foreach zz -E- n { }\n}", "zz", 3, None),
    ("duplicate variable", "rule r {\n  match { a: A  a: C }\n}", "'a'", 2, None),
]


@pytest.mark.parametrize("text, fragment, line, column", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_checker_error(text, fragment, line, column):
    err = error(text)
    assert fragment in err.message
    assert err.pos is not None
    assert err.pos.file == "<string>"
    assert err.pos.line - BASE == line
    if column is not None:
        assert err.pos.column == column
    assert f"<string>:{err.pos.line}:{err.pos.column}:" in str(err)


def test_hints():
    err = error("rule r { match { } }\nstrategy s {\n  rr once\n}")
    assert err.hint == "did you mean 'r'?"
    err = error("rule r {\n  match { a: A }\n  where frob(a.w) > 1\n}")
    assert err.hint


def test_valid_rulebook_checks():
    rb = book(
        """
rule ok(k: int = 2) priority 3 {
  match { a: A { w >= 0 }  b: B  a -E- b  c: C  a -D-> c }
  where degree(a, E) >= k and c.w in [0, 1, 2]
  not { b -E- x  x: A }
  set a.w = a.w + 1
}
strategy s { ok(k = 1) once }
""",
        fns(),
    )
    assert rb.rules["ok"].priority == 3
    assert len(rb.rules["ok"].nacs) == 1
    assert rb.arguments(rb.strategies["s"].steps[0].rules[0]) == {"k": 1}


def test_unknown_attribute_type():
    """An attribute type that is not a value type (engine/values.py) is reported where it is written
    (moved from the grammar tests: the parser no longer checks attribute types)."""
    with pytest.raises(RuleTypeError) as info:
        rulebook_from_text("schema s {\n  node A { x: vec4 }\n}", filename="t.vgr")
    err = info.value
    assert err.pos == SourcePos("t.vgr", 2, 15)
    assert "vec4" in err.message and "vec3" in err.hint
    assert str(err) == (
        "t.vgr:2:15: unknown attribute type 'vec4'\n  hint: attribute types are: int float bool str vec2 vec3 list any"
    )


# -- the checker and the docs agree (issue 14) ---------------------------------------------------


def test_set_of_the_new_types_attribute_after_retype():
    from vaultgram.engine.graph import HostGraph
    from vaultgram.engine.strategy import Runner

    rb = book("""
schema extra { node Big : A { size: int = 0 } }
rule grow { match { a: A { w: 1 } } retype a as Big  set a.size = 7 }
strategy s { grow all }""")
    g = HostGraph(rb.schema)
    n = g.add_node("A", {"w": 1})
    Runner(rb, g).run("s")
    assert g.node_type(n) == "Big" and g.get(n, "size") == 7


def test_foreach_narrows_the_neighbour_type():
    from vaultgram.engine.graph import HostGraph
    from vaultgram.engine.strategy import Runner

    rb = book("""
schema extra { node Big : A { size: int = 0 } }
rule count_big { match { a: A { w: 1 } } foreach a -E- n: Big { set n.size = n.size + 1 } set a.w = 2 }
strategy s { count_big all }""")
    g = HostGraph(rb.schema)
    a = g.add_node("A", {"w": 1})
    big, plain = g.add_node("Big"), g.add_node("A")
    g.add_edge("E", a, big)
    g.add_edge("E", a, plain)
    Runner(rb, g).run("s")
    assert g.get(big, "size") == 1 and g.get(plain, "w") == 0
    with pytest.raises(RuleTypeError, match="never a C"):
        book("rule r { match { a: A } foreach a -E- n: C { set n.w = 1 } }")


def test_a_missing_rule_parameter_is_a_load_time_error():

    with pytest.raises(RuleTypeError, match=r"rule r needs parameter\(s\) k \(no default\)") as info:
        book("rule r(k: int) { match { a: A { w < k } } set a.w = k }\nstrategy s { r all }")
    assert info.value.pos.line == 10 and info.value.pos.column == 14


def test_every_language_reference_example_type_checks(tmp_path):
    """docs/language.md's complete examples (a block that starts with its schema, and the §9 files
    that include one another) load without a type error, with the vault's functions."""
    from vaultgram.engine.rulebook import load_rulebook
    from vaultgram.topology.functions import vault_functions

    from paths import REPO

    doc = (REPO / "docs" / "language.md").read_text(encoding="utf-8")
    blocks = [b for b in doc.split("```")[1::2] if b.split() and b.split()[0] == "schema" and "..." not in b]
    assert len(blocks) >= 3
    for block in blocks:
        rulebook_from_text(block, vault_functions())
    examples = doc.split("## 9. Examples")[1].split("```")[1::2]
    (tmp_path / "skeleton.vgr").write_text(examples[0])
    (tmp_path / "main.vgr").write_text(examples[1] + "\n" + examples[2])
    book = load_rulebook([tmp_path / "main.vgr"], vault_functions())
    assert set(book.rules) == {"prune", "contract", "explode"} and set(book.strategies) == {"clean", "refine"}
