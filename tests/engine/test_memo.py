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
