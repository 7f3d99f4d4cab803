"""Match tables kept across rollbacks (engine/memo.py) and the graph state id they key on."""

from __future__ import annotations

from vaultgram.engine.graph import HostGraph
from vaultgram.engine.memo import TableMemo
from vaultgram.engine.strategy import Runner

from strategies.rules import book

RULES = """
rule link { match { a: A { w: 0 }  b: A { w: 0 } } not { a -E- b } create a -E- b }
rule bump { match { a: A { w < 2 } } set a.w = a.w + 1 }
strategy s { link all  bump fixpoint }
"""


def line(rb, n=4) -> HostGraph:
    g = HostGraph(rb.schema)
    for _ in range(n):
        g.add_node("A")
    g.forget()
    return g


def test_state_id_comes_back_with_rollback_and_differs_elsewhere():
    rb = book(RULES)
    g = line(rb)
    root = g.state_id()
    mark = g.mark()
    n = g.add_node("A")
    one = g.state_id()
    g.rollback(mark)
    assert g.state_id() == root
    g.add_node("A", id=n)  # the same contents again, but another history: another id (never a false hit)
    assert g.state_id() not in (root, one)
    g.rollback(mark)
    g.forget()
    assert g.state_id() == root  # forgetting the journal keeps the state's id


def test_memo_gives_the_same_run_and_hits_after_rollback():
    rb = book(RULES)
    plain, memoised = line(rb), line(rb)
    Runner(rb, plain).run("s")
    memo = TableMemo()
    runner = Runner(rb, memoised, memo=memo)
    runner.run("s")
    assert memoised.snapshot() == plain.snapshot()
    first_misses = memo.misses
    assert memo.hits == 0 and first_misses > 0
    memoised.rollback(0)
    runner.run("s")  # the same searches at the same states: the first step's is a look-up
    assert memoised.snapshot() == plain.snapshot()
    assert memo.hits >= 1
    # a changed graph is a new state: its searches are not looked up
    memoised.rollback(0)
    hits = memo.hits
    memoised.set_node_attr(memoised.nodes()[0], "w", 5)
    Runner(rb, memoised, memo=memo).run("s")
    assert memo.hits == hits
    assert [memoised.get(n, "w") for n in memoised.nodes()] == [5, 2, 2, 2]


ALIKE = """
rule join priority 1 { match { a: A { w: 0 }  b: A } not { a -E- b } create a -E- b }
rule leave_be priority -1 { match { a: A { w: 0 }  b: A } not { a -E- b } set a.w = 1 }
rule join_two { match { a: A { w: 1 }  b: A } not { a -E- b } create a -E- b }
rule drop { match { a: A { w: 0 }  b: A } not { a -E- b } delete a }
rule drop_other { match { a: A { w: 0 }  b: A } not { a -E- b } delete b }
"""


def test_rules_written_alike_share_their_tables_and_no_others():
    # a choice point's two options written with the same match, NACs and parameters (another name,
    # priority and statements) find the same matches: the memo's second search is a look-up; a
    # constraint of another value, or other deletions (a match may leave another edge dangling),
    # is another search
    rb = book(ALIKE)
    keys = {name: rule.match_key for name, rule in rb.rules.items()}
    assert keys["join"] == keys["leave_be"] == "join"
    assert len({keys["join"], keys["join_two"], keys["drop"], keys["drop_other"]}) == 4
    g = line(rb)
    g.add_edge("E", *g.nodes()[:2])
    memo = TableMemo()
    runner = Runner(rb, g, memo=memo)
    first = runner.matcher("join").table()
    hits = memo.hits
    shared = runner.matcher("leave_be").table()
    assert memo.hits == hits + 1 and shared is first
    fresh = runner.matcher("leave_be")._table()
    assert fresh.rows == first.rows == 10 and all(
        (fresh.column(v) == first.column(v)).all() for v in ("a", "b"))
    runner.matcher("join_two").table()
    assert memo.hits == hits + 1  # another constraint: searched
