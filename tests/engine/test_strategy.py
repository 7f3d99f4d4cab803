"""Strategies (once / all / fixpoint / groups / choose / run), traces and replay."""

from __future__ import annotations

import json

import pytest

from vaultgram.engine.errors import RewriteError  # noqa: E402
from vaultgram.engine.graph import HostGraph  # noqa: E402
from vaultgram.engine.strategy import Runner  # noqa: E402
from vaultgram.engine.trace import load_trace, replay  # noqa: E402

from strategies.rules import book  # noqa: E402

RULES = """
rule bump(k: int = 1) { match { a: A { w < 3 } } set a.w = a.w + k }
rule mark_b priority 5 { match { b: B { w: 0 } } set b.w = 9 }
rule grow { match { a: A } create n: A  create a -E- n }
rule link { match { a: A { w: 3 }  b: A { w: 3 } } not { a -E- b } create a -E- b }
rule unlink { match { a: A  b: A  e: a -E- b } delete e }
rule take { match { a: A { w: 0 } } set a.w = 1 }
rule other_take { match { a: A { w: 0 } } set a.w = 2 }
strategy s_once { bump once }
strategy s_all { bump(k = 2) all }
strategy s_fix { bump fixpoint }
strategy s_grow { grow fixpoint max 5 }
strategy s_group { { bump, mark_b } once }
strategy s_choose { choose { take, other_take } once }
strategy s_choose_all { choose { take, other_take } all }
strategy s_choose_fix { choose { take, other_take } fixpoint }
strategy s_run { run s_once  run s_once  link all }
"""


@pytest.fixture(scope="module")
def rb():
    return book(RULES)


def graph(rb, types=("A", "A", "A")):
    g = HostGraph(rb.schema)
    for t in types:
        g.add_node(t)
    return g


def ws(g):
    return [g.get(n, "w") for n in g.nodes()]


def test_once_applies_first_match(rb):
    g = graph(rb)
    r = Runner(rb, g)
    r.run("s_once")
    assert ws(g) == [1, 0, 0]
    assert len(r.trace) == 1 and r.reports[0].applications == 1
    assert r.reports[0].by_rule == {"bump": 1}


def test_once_without_match_does_nothing(rb):
    g = graph(rb, ())
    r = Runner(rb, g)
    r.run("s_once")
    assert len(r.trace) == 0 and r.reports[0].applications == 0


def test_all_applies_every_independent_match(rb):
    g = graph(rb)
    Runner(rb, g).run("s_all")
    assert ws(g) == [2, 2, 2]


def test_all_skips_overlapping_matches(rb):
    g = graph(rb, ("A", "A", "A", "A"))
    for u, v in ((0, 1), (1, 2), (2, 3)):
        g.add_edge("E", u, v)
    apps = Runner(rb, g).apply_all("unlink")
    # 6 matches (3 edges x 2 orientations) all bind their edge; the first match of each edge wins
    assert len(apps) == 3 and g.num_edges == 0


def test_all_rechecks_nac_before_applying(rb):
    g = graph(rb, ("A", "A"))
    for n in g.nodes():
        g.set_node_attr(n, "w", 3)
    apps = Runner(rb, g).apply_all("link")
    # (0,1) and (1,0) are two matches that read the same nodes but only create: both independent,
    # yet after the first one the NAC of the second holds -> it must be skipped
    assert len(apps) == 1 and g.num_edges == 1


def test_fixpoint_terminates(rb):
    g = graph(rb)
    r = Runner(rb, g)
    r.run("s_fix")
    assert ws(g) == [3, 3, 3]
    assert len(r.trace) == 9
    assert r.fixpoint(["bump"]) == 0


def test_fixpoint_step_limit_names_rule(rb):
    g = graph(rb, ("A",))
    snap_len = len(g)
    with pytest.raises(RewriteError, match="grow") as info:
        Runner(rb, g).run("s_grow")
    assert "5" in str(info.value)
    assert len(g) == snap_len + 5  # the 5 allowed applications happened
    with pytest.raises(RewriteError, match="within 3 steps; rules still firing: grow"):
        Runner(rb, graph(rb, ("A",))).fixpoint(["grow", "bump"], max_steps=3)


def test_group_by_priority(rb):
    g = graph(rb, ("A", "B"))
    r = Runner(rb, g)
    r.run("s_group")
    # mark_b (priority 5) goes first although bump is named first in the group
    assert ws(g) == [0, 9]
    assert r.trace.applications[0].rule == "mark_b"
    r.run("s_group")
    assert ws(g) == [1, 9]


def test_group_order_when_priorities_tie():
    rb = book(
        """
rule p { match { a: A { w: 0 } } set a.w = 1 }
rule q { match { a: A { w: 0 } } set a.w = 2 }
strategy pq { { p, q } once }
strategy qp { { q, p } once }
"""
    )
    g = graph(rb, ("A",))
    Runner(rb, g).run("qp")
    assert ws(g) == [2]
    g = graph(rb, ("A",))
    Runner(rb, g).run("pq")
    assert ws(g) == [1]


def test_choose_default_takes_first(rb):
    g = graph(rb, ("A", "A"))
    Runner(rb, g).run("s_choose")
    assert ws(g) == [1, 0]


def test_choose_with_custom_chooser(rb):
    seen = []

    def last(options):
        seen.append([(name, dict(m.binding)) for name, m in options])
        return len(options) - 1

    g = graph(rb, ("A", "A"))
    Runner(rb, g, chooser=last).run("s_choose")
    assert seen[0] == [("take", {"a": 0}), ("take", {"a": 1}), ("other_take", {"a": 0}), ("other_take", {"a": 1})]
    assert ws(g) == [0, 2]

    g = graph(rb, ("A", "A"))
    Runner(rb, g, chooser=last).run("s_choose_all")
    assert ws(g) == [2, 2]

    g = graph(rb, ("A", "A", "A"))
    picks = iter([1, 0, 1])
    Runner(rb, g, chooser=lambda options: next(picks)).run("s_choose_fix")
    assert ws(g) == [2, 1, 2]


def test_run_nested_strategy(rb):
    g = graph(rb, ("A", "A"))
    r = Runner(rb, g)
    r.run("s_run")
    assert ws(g) == [2, 0]
    assert [rep.step for rep in r.reports] == ["bump once", "bump once", "link all"]


def test_unknown_rule_and_strategy_at_runtime(rb):
    r = Runner(rb, graph(rb))
    with pytest.raises(RewriteError):
        r.run("nope")
    with pytest.raises(RewriteError):
        r.apply_once("nope")


def test_trace_save_and_replay(rb, tmp_path):
    g = graph(rb, ("A", "B", "A"))
    g.add_edge("E", 0, 1)
    start = g.snapshot()
    r = Runner(rb, g)
    r.run("s_group")
    r.apply_once("grow")
    r.run("s_fix")
    r.apply_all("unlink")
    r.apply_once("bump", {"k": 2})
    path = tmp_path / "trace.json"
    path.write_text(json.dumps(r.trace.to_json()))
    records = load_trace(path)
    assert records == json.loads(json.dumps(r.trace.to_json()))
    assert [rec["rule"] for rec in records][:2] == ["mark_b", "grow"]

    g2 = graph(rb, ("A", "B", "A"))
    g2.add_edge("E", 0, 1)
    assert g2.snapshot() == start
    t2 = replay(records, rb, g2)
    assert len(t2) == len(r.trace)
    assert g2.snapshot() == g.snapshot()


def test_trace_records_are_the_applications_fields_copied(rb):
    # the records are the applications' fields but the journal mark, parameters' tuples as lists,
    # equal to dataclasses.asdict's copy and sharing no list or dict with the application
    from dataclasses import asdict

    g = graph(rb, ("A", "B", "A"))
    g.add_edge("E", 0, 1)
    r = Runner(rb, g)
    r.run("s_group")
    r.apply_once("grow")
    r.apply_once("bump", {"k": 2})
    records = r.trace.to_json()
    assert len(records) == len(r.trace) >= 3 and any(rec["set"] for rec in records)
    for app, rec in zip(r.trace.applications, records):
        expected = {k: v for k, v in asdict(app).items() if k != "mark"}
        expected["params"] = {k: list(v) if isinstance(v, tuple) else v for k, v in expected["params"].items()}
        assert rec == expected and list(rec) == list(expected)
        for name in ("binding", "created_nodes", "created_edges", "retyped", "set"):
            assert rec[name] is not getattr(app, name)
        assert all(a is not b for a, b in zip(rec["set"], app.set))


def test_replay_refuses_wrong_graph(rb):
    g = graph(rb, ("A",))
    r = Runner(rb, g)
    r.apply_once("take")
    with pytest.raises(RewriteError, match="does not match"):
        replay(r.trace.to_json(), rb, graph(rb, ("C",)))
    with pytest.raises(RewriteError, match="unknown rule"):
        replay([{"rule": "zz"}], rb, graph(rb))


def test_a_self_loop_does_not_apply_and_is_counted():
    """`create r -E- next(r)` around a node with one neighbour would join r to itself: that match is
    skipped (counted), the others apply, and a fixpoint terminates."""
    rb = book("""
rule ring { match { a: A { w: 1 } }
  foreach a -E- m { create r: A { w = 5 }  create r -E- m  create r -E- next(r) }
  set a.w = 0 }
strategy once_ { ring once }
strategy fix { ring fixpoint }
strategy every { ring all }""")
    for strategy in ("once_", "fix", "every"):
        g = HostGraph(rb.schema)
        lone, hub = g.add_node("A", {"w": 1}), g.add_node("A", {"w": 1})
        g.add_edge("E", lone, g.add_node("A"))
        for _ in range(3):
            g.add_edge("E", hub, g.add_node("A"))
        before = g.snapshot()
        r = Runner(rb, g)
        r.run(strategy)
        assert r.self_loops >= 1 and g.get(lone, "w") == 1  # never applied at the lone node
        if strategy != "once_":
            assert g.get(hub, "w") == 0 and len(r.trace) == 1
        else:
            assert g.snapshot() == before and len(r.trace) == 0
