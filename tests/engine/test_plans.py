"""Search plans kept on their pattern (issue 13): the plan a new matcher gets is the one
``build_plan`` builds from the graph's type counts now, and is built once for those counts."""

from __future__ import annotations

from vaultgram.engine import plan as plan_module
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.matcher import Matcher
from vaultgram.engine.plan import Scan, build_plan, pattern_plan
from vaultgram.engine.rulebook import rulebook_from_text

BOOK = rulebook_from_text("schema s { node A  node B  edge E (A -- B) }\nrule ab { match { a: A  b: B  a -E- b } }")


def star(n_a: int, n_b: int) -> HostGraph:
    """``n_a`` A nodes and ``n_b`` B nodes, every A joined to the first B."""
    g = HostGraph(BOOK.schema)
    a, b = [g.add_node("A") for _ in range(n_a)], [g.add_node("B") for _ in range(n_b)]
    for x in a:
        g.add_edge("E", x, b[0])
    return g


def test_a_kept_plan_is_the_plan_built_for_the_counts_now():
    pattern = BOOK.rules["ab"].pattern
    pattern.plans.clear()
    g = star(5, 1)
    first = pattern_plan(pattern, frozenset(), g.count)
    assert first == build_plan(pattern, frozenset(), g.count) and first[0] == Scan(pattern.nodes["b"])  # rarer type
    assert Matcher(BOOK.rules["ab"], g).plan(frozenset()) is first and len(pattern.plans) == 1  # kept, not rebuilt
    mark = g.mark()
    for _ in range(10):
        g.add_node("B")  # now B is the commoner type: another plan, scanning A
    other = Matcher(BOOK.rules["ab"], g).plan(frozenset())
    assert other == build_plan(pattern, frozenset(), g.count) and other[0] == Scan(pattern.nodes["a"])
    assert len(Matcher(BOOK.rules["ab"], g).all()) == 5 and len(pattern.plans) == 2
    g.rollback(mark)
    assert Matcher(BOOK.rules["ab"], g).plan(frozenset()) is first  # the counts as before: the same plan


def test_a_pattern_keeps_a_bounded_number_of_plans(monkeypatch):
    monkeypatch.setattr(plan_module, "PLANS_PER_PATTERN", 3)
    pattern = BOOK.rules["ab"].pattern
    pattern.plans.clear()
    for n in range(1, 6):
        count = star(n, 1).count
        assert pattern_plan(pattern, frozenset(), count) == build_plan(pattern, frozenset(), count)
    assert len(pattern.plans) == 3 and [key[1] for key in pattern.plans] == [(3, 1), (4, 1), (5, 1)]
