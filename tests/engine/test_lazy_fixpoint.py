"""``fixpoint``'s lazy match sets (:mod:`vaultgram.engine.incremental`, issue 18): a rule that calls a
non-local function is searched when the fixpoint asks it (the rules of higher priority have no match),
not after every application of a rule above it, and the fixpoint applies exactly what the eager sets
applied, in the same order, with the same result."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from vaultgram.engine import strategy
from vaultgram.engine.errors import RewriteError
from vaultgram.engine.expressions import Functions
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.incremental import MatchSet
from vaultgram.engine.strategy import Runner

from strategies.graphs import build_graph, typed_graphs
from strategies.rules import book

RULES = """
rule grow priority 1 { match { a: A { w < 4 } } set a.w = a.w + 1 }
rule seen { match { a: A } where watched(a) and total(A) > 1000 }
rule link priority 2 { match { a: A  c: C { w: 0 } } not { a -D-> c } where total(A) > 6 create a -D-> c { m = 1 } }
rule spread priority 1 { match { a: A  b: A  a -E- b } where a.w < b.w and total(A) < 24 set a.w = a.w + 1 }
rule settle { match { c: C { w < 3 } } where total(A) > 2 * c.w set c.w = c.w + 1 }
rule tidy { match { a: A  b: A { w: 0 }  e: a -E- b } where total(A) > 12 delete e }
"""


def _book(calls: list | None = None):
    """The rulebook, its ``watched`` counting the nodes it is asked about in ``calls`` (non-local, as
    the vault's chord helpers are), ``total(A)`` the sum of the weights of every A node (naming the type
    it reads: the rules that call it are re-matched after a change of an A node's weight, which a
    lazy set, searching later, would otherwise see where an eager one did not)."""
    f = Functions()
    f.register("watched", lambda g, a: calls.append(a) or True, ("node",), "bool", uses_graph=True, local=False)
    f.register("total", lambda g, types: sum(g.get(n, "w") for n in g.of_types(types)), ("type",), "int",
               uses_graph=True, local=False)
    return book(RULES, f)


def _eager(monkeypatch) -> None:
    """Every fixpoint's sets eager: re-matched after each application, as before the lazy sets."""
    monkeypatch.setattr(strategy, "MatchSet", lambda matcher, lazy=False: MatchSet(matcher))


def _chain(rb, n: int) -> HostGraph:
    g = HostGraph(rb.schema)
    for _ in range(n):
        g.add_node("A")
    return g


def test_a_rule_below_one_that_fires_is_searched_once(monkeypatch):
    """``grow`` fires 4 times at each of 5 nodes (20 applications); ``seen``, below it, asks its
    non-local condition of each node once when ``grow`` stops (5 calls), where eager sets asked it after
    every application too (5 x 21 = 105)."""
    calls: list = []
    rb = _book(calls)
    g = _chain(rb, 5)
    assert Runner(rb, g).fixpoint(["grow", "seen"]) == 20
    assert len(calls) == 5 and sorted(calls) == sorted(g.nodes())
    _eager(monkeypatch)
    calls.clear()
    assert Runner(rb, _chain(rb, 5)).fixpoint(["grow", "seen"]) == 20
    assert len(calls) == 105


def _run(rb, spec, names):
    """The applications (rule and binding, in order) of a fixpoint of ``names`` on the graph ``spec``,
    its node weights after, or the error it raised."""
    g = build_graph(rb.schema, spec)
    runner = Runner(rb, g)
    try:
        runner.fixpoint(names, max_steps=60)
    except RewriteError as exc:
        return str(exc)
    return ([(app.rule, sorted(app.binding.items())) for app in runner.trace.applications],
            sorted((n, g.get(n, "w")) for n in g.nodes()))


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(typed_graphs(max_nodes=12, max_edges=24), st.permutations(["link", "spread", "settle", "tidy", "grow"]))
def test_lazy_sets_apply_what_eager_sets_apply(monkeypatch, spec, names):
    """On random graphs and rule orders (rules of three priorities, all non-local but ``grow``), the lazy
    fixpoint applies the same matches in the same order as the eager one and leaves the same weights
    (or fails with the same error at the step limit)."""
    rb = _book()
    lazy = _run(rb, spec, names)
    with monkeypatch.context() as m:
        _eager(m)
        eager = _run(rb, spec, names)
    assert lazy == eager


def test_a_choose_fixpoint_keeps_eager_sets():
    """A ``choose`` fixpoint asks every set each step (its options), so it makes them eager."""
    made = []
    original = strategy.MatchSet

    def spy(matcher, lazy=False):
        made.append(lazy)
        return original(matcher, lazy)

    rb = _book([])
    with pytest.MonkeyPatch.context() as m:
        m.setattr(strategy, "MatchSet", spy)
        runner = Runner(rb, _chain(rb, 2))
        runner._fixpoint([runner.matcher("grow")], 10, True)
    assert made == [False]
