"""Searching no more than needed: conditions in written order, choice points found without every
option, all steps whose rules only create (engine/plan.py, Runner.offers_choice, Runner._all)."""

from __future__ import annotations

import pytest

from vaultgram.engine.expressions import Functions
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.matcher import Matcher
from vaultgram.engine.plan import Check, build_plan
from vaultgram.engine.rewriter import only_creates
from vaultgram.engine.strategy import Option, Runner

from strategies.rules import book

CALLS: list[tuple[int, int]] = []


def costly(a: int, b: int) -> bool:
    """A host function that records its calls (a stand-in for a geometric test)."""
    CALLS.append((a, b))
    return True


RULES = """
rule pair { match { a: A  b: A  c: A  a -E- b  b -E- c } where costly(a, b) and c.w == 1 }
rule pair_late { match { a: A  b: A  c: A  a -E- b  b -E- c } where c.w == 1 and a != c and costly(a, b) }
rule one { match { a: A { w: 1 } } set a.w = 5 }
rule two { match { a: A { w: 2 } } set a.w = 6 }
rule link { match { a: A  b: A  a -E- b } not { c: C  a -D-> c } create c: C  create a -D-> c }
rule lift { match { a: A { w: 1 } } set a.w = 3 }
rule thicken { match { a: A  b: A  a -E- b } where degree(a, E) < 3 create a -E- b }
strategy s_once { choose { one, two } once }
strategy s_fix { choose { one, two } fixpoint }
strategy s_all { choose { one, two } all }
"""


@pytest.fixture(scope="module")
def rb():
    f = Functions()
    f.register("costly", costly, ("node", "node"), "bool")
    return book(RULES, f)


def path(rb, ws) -> HostGraph:
    """A path of A nodes with the weights ``ws``."""
    g = HostGraph(rb.schema)
    nodes = [g.add_node("A", {"w": w}) for w in ws]
    for u, v in zip(nodes, nodes[1:]):
        g.add_edge("E", u, v)
    return g


def test_a_host_function_conjunct_waits_for_the_conjuncts_written_before_it(rb):
    g = path(rb, [0, 0, 0, 0, 1])  # c.w == 1 holds only at the end of the path
    plan = build_plan(rb.rules["pair_late"].pattern, frozenset(), g.count)
    texts = [step.condition.text for step in plan if isinstance(step, Check)]
    assert texts.index("costly(a, b)") > texts.index("a != c")  # a bound before c, checked after it
    CALLS.clear()
    matches = Matcher(rb.rules["pair_late"], g).all()
    assert {m.binding["c"] for m in matches} == {4} and set(CALLS) == {(2, 3)}  # only where c.w == 1
    # written first, it is evaluated first (for every a-b-c path), and the matches are the same set
    CALLS.clear()
    first = Matcher(rb.rules["pair"], g).all()
    assert sorted(m.key for m in first) == sorted(m.key for m in matches) and len(CALLS) > 1


@pytest.mark.parametrize("ws", [[0, 0], [1, 0], [1, 1], [1, 2], [2, 2, 1]])
@pytest.mark.parametrize("strategy", ["s_once", "s_fix", "s_all"])
def test_offers_choice_says_whether_the_chooser_would_be_asked(rb, ws, strategy):
    g = path(rb, ws)
    asked: list[list[Option]] = []

    def chooser(options):
        asked.append(list(options))
        return 0

    step = rb.strategies[strategy].steps[0]
    offered = Runner(rb, g).offers_choice(step)
    mark = g.mark()
    Runner(rb, g, chooser=chooser).run_step(step)
    g.rollback(mark)
    assert offered == (bool(asked) and len(asked[0]) >= 2)


def test_all_for_rules_that_only_create_checks_each_match_again(rb):
    assert only_creates(rb.rules["link"].statements) and not only_creates(rb.rules["lift"].statements)
    g = path(rb, [0, 0, 0])  # two matches at node 1 (1-0 and 1-2, besides 0-1 and 2-1)
    apps = Runner(rb, g).apply_all("link")
    # the NAC is checked again before each application: each node gets one C, the first time
    assert sorted(app.binding["a"] for app in apps) == [0, 1, 2] and g.count(["C"]) == 3


def test_all_for_rules_that_only_create_checks_a_degree_condition_again(rb):
    g = path(rb, [0, 0, 0])  # degrees 1, 2, 1: all four (a, b) pairs match at first
    apps = Runner(rb, g).apply_all("thicken")
    # (0, 1) makes node 1's degree 3, so (1, 0) and (1, 2) no longer hold; (2, 1) still does
    assert [(app.binding["a"], app.binding["b"]) for app in apps] == [(0, 1), (2, 1)]
    assert not Matcher(rb.rules["thicken"], g)._attribute_tests_only
    assert Matcher(rb.rules["link"], g)._attribute_tests_only
