"""Invariants and quantifiers (engine/invariants.py, expressions): semantics, checking, errors, traces."""

import pytest

from vaultgram.engine.errors import RuleTypeError
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.invariants import InvariantError
from vaultgram.engine.strategy import Runner
from vaultgram.engine.trace import Trace, replay

from strategies.rules import book

GROW = """
rule bump { match { a: A { w < 3 } } set a.w = a.w + 1 }
rule mark { match { c: C { w: 0 } } set c.w = 1 }
strategy grow { bump fixpoint }
strategy marks { mark all }
"""


def graph(rb, ws):
    g = HostGraph(rb.schema)
    for w in ws:
        g.add_node("A", {"w": w})
    g.add_node("C")
    return g


def condition(rb, text):
    """The closure of an invariant's condition, on its own (for the quantifiers' values)."""
    from vaultgram.grammar.parser import parse_text
    expr = parse_text(f"invariant x at end {{ {text} }}").invariants[0].condition
    return rb.checker.compiler.compile(expr, rb.checker.type_symbols).fn


@pytest.mark.parametrize("text, value", [
    ("forall a: A { a.w >= 0 }", True), ("forall a: A { a.w > 0 }", False),
    ("exists a: A { a.w == 2 }", True), ("exists c: C { c.w > 0 }", False),
    ("count a: A { a.w >= 1 }", 2), ("sum a: A { a.w }", 3), ("count e: E { true }", 1),
    ("forall a: A { exists b: A { b.w > a.w } or a.w == 2 }", True),
])
def test_quantifier_values(text, value):
    rb = book()
    g = graph(rb, [0, 1, 2])
    g.add_edge("E", 0, 1)
    assert condition(rb, text)(g, {}) == value


def test_quantifiers_include_subtypes():
    rb = book()
    g = HostGraph(rb.schema)
    g.add_node("B", {"w": 5})  # B : A
    assert condition(rb, "sum a: A { a.w }")(g, {}) == 5


@pytest.mark.parametrize("text, message", [
    ("invariant i at end { forall x: Nope { true } }", "unknown node or edge type 'Nope'"),
    ("invariant i at end { forall a: A { a.w } }", "body of forall must be bool"),
    ("invariant i at end { sum a: A { a.w } }", "must be a condition"),
    ("invariant i at end { forall a: A { a.nope > 0 } }", "has no attribute 'nope'"),
    ("invariant i at end in nowhere { true }", "unknown strategy 'nowhere'"),
    ("invariant grow at end { true }", "reuses a rule, strategy or invariant name"),
    ("invariant i at end { forall a: A { forall a: A { true } } }", "already a name"),
])
def test_invariant_type_errors_name_the_place(text, message):
    with pytest.raises(RuleTypeError, match=message) as info:
        book(GROW + text)
    assert "<string>:" in str(info.value)


def test_after_each_names_the_rule_the_part_and_the_element():
    rb = book(GROW + "invariant small after each { exists a: A { true } and forall a: A { a.w < 2 } }")
    g = graph(rb, [0, 1])
    with pytest.raises(InvariantError) as info:
        Runner(rb, g, check_invariants=True).run("grow")
    exc = info.value
    assert (exc.invariant, exc.rule, exc.application.binding) == ("small", "bump", {"a": 0})
    assert "a.w < 2 is false for a = 0 (A)" in exc.reason


def test_at_end_and_scoped_invariants():
    rb = book(GROW + "invariant low at end in marks { forall a: A { a.w < 2 } }"
                     "invariant marked at end in marks { forall c: C { c.w == 1 } }")
    g = graph(rb, [0])
    runner = Runner(rb, g, check_invariants=True)
    runner.run("grow")  # w reaches 3: not checked, the invariant is about `marks` only
    with pytest.raises(InvariantError, match="at the end of strategy marks") as info:
        runner.run("marks")
    assert info.value.invariant == "low" and info.value.rules_run == {"bump": 3, "mark": 1}


def test_invariants_are_not_checked_unless_asked():
    rb = book(GROW + "invariant never after each { false }")
    runner = Runner(rb, graph(rb, [0]))
    runner.run("grow")
    assert runner.invariant_checks == 0 and len(runner.trace) == 3


def test_invariants_in_the_summary():
    rb = book(GROW + "invariant low at end in marks, grow { true }")
    assert rb.summary()["invariants"] == {"low": "at end in marks, grow"}


def test_trace_records_set_retype_choice_and_edits():
    rb = book(GROW + """
rule promote { match { a: A { w: 3 } } retype a as B }
strategy pick { choose { promote, bump } once }
""")
    g = graph(rb, [2])
    start = g.to_json()
    runner = Runner(rb, g, chooser=lambda options: len(options) - 1)
    runner.run("grow")
    c = g.add_node("C", {"w": 0})
    runner.trace.record_edit([{"id": c, "type": "C", "w": 0}], [])
    runner.run("pick")
    records = runner.trace.to_json()
    assert records[0]["set"] == [["node", 0, "w", 3]] and records[0]["choice"] is None
    assert records[1] == {"rule": None, "edit": {"nodes": [{"id": c, "type": "C", "w": 0}], "edges": []}}
    assert records[2]["rule"] == "promote" and records[2]["retyped"] == [[0, "A", "B"]]
    assert records[2]["choice"] == 0  # the only option that applies
    fresh = HostGraph.from_json(start, rb.schema)
    assert isinstance(replay(records, rb, fresh), Trace)
    assert fresh.snapshot() == g.snapshot()
