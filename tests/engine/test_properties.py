"""Property tests of the engine on random typed graphs (schema in tests/strategies/rules.py)."""

from __future__ import annotations

import itertools

import networkx as nx
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from networkx.algorithms import isomorphism

from vaultgram.engine.incremental import MatchSet  # noqa: E402
from vaultgram.engine.matcher import Matcher  # noqa: E402
from vaultgram.engine.strategy import Runner  # noqa: E402
from vaultgram.engine.trace import replay  # noqa: E402

from strategies.graphs import GraphSpec, build_graph, build_graph_in_bulk, permutations, typed_graphs  # noqa: E402
from strategies.rules import book  # noqa: E402

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
FEW = settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])

RULES = """
rule add_d { match { a: A  c: C } not { a -D-> c } create a -D-> c { m = 7 } }
rule remove_d { match { a: A  c: C  e: a -D-> c { m: 7 } } delete e }
rule add_n { match { a: A } create n: C { w = 3 } create a -D-> n { m = 5 } }
rule del_n { match { a: A  n: C { w: 3 }  e: a -D-> n { m: 5 } } delete e, n }

rule bump { match { a: A  b: A  a -E- b } where a.w <= b.w set a.w = b.w + 1 }
rule cut { match { a: A  b: A  e: a -E- b { m: 1 } } delete e }
rule join { match { a: B  b: A { w: 0 } } not { a -E- b } create a -E- b { m = 2 } }
rule promote { match { a: A { w >= 2 } } where type_of(a) == "A" not { a -D-> c  c: C } retype a as B }
rule drop_c { match { c: C { w: 1 } } detach delete c }
rule lone { match { a: A } delete a }
rule fuse { match { a: B { w: 3 }  b: B  a -E- b } merge a into b }
rule tag { match { a: A  c: C  e: a -D-> c } where c.w > a.w set e.m = 2 set c.w = a.w }

rule nac_plain { match { a: A  b: A  a -E- b } not { b -D-> c  c: C } }
rule nac_where { match { a: A  b: A  a -E- b } not { a -E- x  x: B  where x.w > a.w } }
rule nac_two { match { a: A } not { a -D-> c  c: C { w: 0 } } not { a -E- x  x: B } }

strategy mix { { bump, cut } all  join all  promote fixpoint max 100  drop_c all  tag all  fuse once }
"""

RB = book(RULES)
SCHEMA = RB.schema
MUTATORS = ["bump", "cut", "join", "promote", "drop_c", "lone", "fuse", "tag", "add_d", "remove_d", "add_n", "del_n"]


def typed_nx(g):
    return g.to_networkx()


def iso(g1, g2) -> bool:
    nm = isomorphism.categorical_node_match(["type", "w"], [None, None])
    em = isomorphism.categorical_multiedge_match(["type", "m"], [None, None])
    return nx.is_isomorphic(typed_nx(g1), typed_nx(g2), node_match=nm, edge_match=em)


def all_keys(rule, g, params=None):
    return [m.key for m in Matcher(RB.rules[rule], g, params).all()]


# ------------------------------------------------------------------------------------------------
# 1. rule followed by its inverse
# ------------------------------------------------------------------------------------------------


@SETTINGS
@given(typed_graphs(), st.data())
def test_rule_then_inverse_is_isomorphic(spec, data):
    g = build_graph(SCHEMA, spec)
    original = build_graph(SCHEMA, spec)
    r = Runner(RB, g)
    for make, undo in (("add_d", "remove_d"), ("add_n", "del_n")):
        ms = Matcher(RB.rules[make], g).all()
        if not ms:
            continue
        m = data.draw(st.sampled_from(ms))
        r.apply(Matcher(RB.rules[make], g), m)
        assert not iso(g, original)
        inv = Matcher(RB.rules[undo], g).all()
        assert len(inv) == 1
        r.apply(Matcher(RB.rules[undo], g), inv[0])
        assert iso(g, original)
        # everything but the id counters is restored exactly
        s1, s0 = g.snapshot(), original.snapshot()
        assert {k: s1[k] for k in ("nodes", "edges", "rotations")} == {
            k: s0[k] for k in ("nodes", "edges", "rotations")
        }


# ------------------------------------------------------------------------------------------------
# 2. NACs block exactly what they should
# ------------------------------------------------------------------------------------------------


def _positive(rule_text_name, g):
    """Matches of the NAC rule's positive part (a copy of the rule without its NACs)."""
    return [dict(m.binding) for m in Matcher(NO_NAC.rules[rule_text_name], g).all()]


NO_NAC = book(
    """
rule nac_plain { match { a: A  b: A  a -E- b } }
rule nac_where { match { a: A  b: A  a -E- b } }
rule nac_two { match { a: A } }
"""
)


def _e_neighbours(g, n):
    return [g.other(e, n) for e in g.incident(n, ["E"])]


def _out_d(g, n):
    return [g.ends(e)[1] for e in g.incident(n, ["D"]) if g.ends(e)[0] == n]


def brute_nac(rule, g, b) -> bool:
    """True when the NAC(s) of ``rule`` hold (i.e. block) at binding ``b``."""
    used = {b[v] for v in ("a", "b") if v in b}
    if rule == "nac_plain":
        return any(c not in used for c in _out_d(g, b["b"]))
    if rule == "nac_where":
        a = b["a"]
        return any(
            x not in used and g.node_type(x) == "B" and g.get(x, "w") > g.get(a, "w") for x in _e_neighbours(g, a)
        )
    if rule == "nac_two":
        a = b["a"]
        return any(g.get(c, "w") == 0 for c in _out_d(g, a)) or any(
            g.node_type(x) == "B" and x != a for x in _e_neighbours(g, a)
        )
    raise AssertionError(rule)


@SETTINGS
@given(typed_graphs(max_nodes=15, max_edges=30))
def test_nac_blocks_exactly(spec):
    g = build_graph(SCHEMA, spec)
    for rule in ("nac_plain", "nac_where", "nac_two"):
        with_nac = [dict(m.binding) for m in Matcher(RB.rules[rule], g).all()]
        without = _positive(rule, g)
        expected = [b for b in without if not brute_nac(rule, g, b)]
        assert with_nac == expected, rule


# ------------------------------------------------------------------------------------------------
# 3. `all` applies only parallel-independent matches (and a maximal set of them)
# ------------------------------------------------------------------------------------------------


def writes_of(rule: str, binding: dict, app) -> set:
    w = {("n", n) for n in app.deleted_nodes} | {("e", e) for e in app.deleted_edges}
    changed = {"bump": ["a"], "promote": ["a"], "fuse": ["a", "b"], "tag": ["c", "e"]}.get(rule, [])
    for v in changed:
        w.add(("e" if v == "e" else "n", binding[v]))
    return w


def reads_of(rule: str, binding: dict) -> set:
    nodes = RB.rules[rule].pattern.nodes
    return {("n" if v in nodes else "e", i) for v, i in binding.items()}


@SETTINGS
@given(typed_graphs(max_nodes=15, max_edges=30), st.sampled_from(["bump", "cut", "drop_c", "lone", "fuse", "tag"]))
def test_all_applies_parallel_independent_matches(spec, rule):
    g = build_graph(SCHEMA, spec)
    before = Matcher(RB.rules[rule], build_graph(SCHEMA, spec)).all()
    apps = Runner(RB, g).apply_all(rule)
    rw = [(reads_of(rule, a.binding), writes_of(rule, a.binding, a)) for a in apps]
    for (r1, w1), (r2, w2) in itertools.combinations(rw, 2):
        assert not (w1 & r2) and not (w2 & r1)
    # maximal: every match not applied conflicts with an applied one
    applied = {tuple(sorted(a.binding.items())) for a in apps}
    for m in before:
        if tuple(sorted(m.binding.items())) in applied:
            continue
        r = reads_of(rule, dict(m.binding))
        assert any(r & w for _, w in rw) or any(
            rr & {x for x in r if x[0] == "e" or rule in ("bump", "promote", "fuse", "tag", "drop_c", "lone")}
            for rr, _ in rw
        )


# ------------------------------------------------------------------------------------------------
# 4. undo restores the graph exactly
# ------------------------------------------------------------------------------------------------


@SETTINGS
@given(typed_graphs(), st.lists(st.tuples(st.sampled_from(MUTATORS), st.integers(0, 1000)), max_size=12))
def test_undo_restores_exactly(spec, steps):
    g = build_graph(SCHEMA, spec)
    snap = g.snapshot()
    mark = g.mark()
    r = Runner(RB, g)
    inner = []
    for rule, k in steps:
        ms = Matcher(RB.rules[rule], g).all()
        if ms:
            inner.append((g.mark(), g.snapshot()))
            r.apply(Matcher(RB.rules[rule], g), ms[k % len(ms)])
    # undo the applications one by one, then all at once
    for m, s in reversed(inner[len(inner) // 2:]):
        g.rollback(m)
        assert g.snapshot() == s
    g.rollback(mark)
    assert g.snapshot() == snap


# ------------------------------------------------------------------------------------------------
# 5. results do not depend on insertion order
# ------------------------------------------------------------------------------------------------


@FEW
@given(typed_graphs(), st.data())
def test_insertion_order_irrelevant(spec, data):
    node_order = data.draw(permutations(len(spec.nodes)))
    edge_order = data.draw(permutations(len(spec.edges)))
    g1 = build_graph(SCHEMA, spec)
    g2 = build_graph(SCHEMA, spec, node_order, edge_order)
    assert g1.snapshot() == g2.snapshot()
    r1, r2 = Runner(RB, g1), Runner(RB, g2)
    r1.run("mix")
    r2.run("mix")
    assert r1.trace.to_json() == r2.trace.to_json()
    assert g1.snapshot() == g2.snapshot()


@FEW
@given(typed_graphs(), st.lists(st.tuples(st.sampled_from(MUTATORS), st.integers(0, 1000)), max_size=8))
def test_a_graph_built_in_bulk_rewrites_as_one_built_element_by_element(spec, steps):
    """The bulk path keeps attributes, types, ends and the type index in arrays until they are used:
    the same rewrites (reading and writing elements never used before) find the same matches in
    the same order and leave the same graph, type index (in its iteration order) and journal."""
    one, bulk = build_graph(SCHEMA, spec), build_graph_in_bulk(SCHEMA, spec)
    for rule, k in steps:
        found = [m.key for m in Matcher(RB.rules[rule], one).all()]
        assert [m.key for m in Matcher(RB.rules[rule], bulk).all()] == found
        if found:
            for g in (one, bulk):
                matcher = Matcher(RB.rules[rule], g)
                Runner(RB, g).apply(matcher, matcher.all()[k % len(found)])
    for t in ("A", "B", "C", "E", "D"):
        assert list(bulk.of_types([t])) == list(one.of_types([t])) and bulk.count([t]) == one.count([t])
    sizes = lambda g: (len(g), g.num_edges, g.nodes(), g.edges())  # noqa: E731
    assert sizes(bulk) == sizes(one)
    assert bulk.changes_since(0) == one.changes_since(0)
    assert bulk.snapshot() == one.snapshot()


@FEW
@given(typed_graphs())
def test_a_strategy_on_a_graph_built_in_bulk_then_undone(spec):
    """A strategy run on a graph just built in bulk, then undone, then the bulk additions undone."""
    one, bulk = build_graph(SCHEMA, spec), build_graph_in_bulk(SCHEMA, spec)
    built = bulk.mark()
    r1, r2 = Runner(RB, one), Runner(RB, bulk)
    r1.run("mix")
    r2.run("mix")
    assert r2.trace.to_json() == r1.trace.to_json() and bulk.snapshot() == one.snapshot()
    bulk.rollback(built)
    assert bulk.snapshot() == build_graph(SCHEMA, spec).snapshot()
    bulk.rollback(0)
    assert bulk.snapshot() == build_graph(SCHEMA, GraphSpec((), ())).snapshot()


# ------------------------------------------------------------------------------------------------
# 6. the matcher finds exactly the matches of a brute-force (networkx) search
# ------------------------------------------------------------------------------------------------

PATTERNS = {
    # name: (rule text, pattern nodes {var: type}, pattern edges [(u, v, type)], filter)
    "edge": ("match { a: A  b: A  a -E- b }", {"a": "A", "b": "A"}, [("a", "b", "E")], None),
    "path": (
        "match { a: A  b: B  x: A  a -E- b  b -E- x }",
        {"a": "A", "b": "B", "x": "A"},
        [("a", "b", "E"), ("b", "x", "E")],
        None,
    ),
    "triangle": (
        "match { a: A  b: A  x: A  a -E- b  b -E- x  x -E- a }",
        {"a": "A", "b": "A", "x": "A"},
        [("a", "b", "E"), ("b", "x", "E"), ("x", "a", "E")],
        None,
    ),
    "directed": ("match { a: A  c: C  a -D-> c }", {"a": "A", "c": "C"}, [("a", "c", "D>")], None),
    "directed_back": ("match { c: C  a: B  c <-D- a }", {"a": "B", "c": "C"}, [("a", "c", "D>")], None),
    "mixed": (
        "match { a: B  b: A  c: C  a -E- b  b -D-> c  d: C  a -D- d }",
        {"a": "B", "b": "A", "c": "C", "d": "C"},
        [("a", "b", "E"), ("b", "c", "D>"), ("a", "d", "D>")],
        None,
    ),
    "condition": (
        "match { a: A  b: A  a -E- b  c: C  b -D-> c } where a.w > b.w and c.w != 0",
        {"a": "A", "b": "A", "c": "C"},
        [("a", "b", "E"), ("b", "c", "D>")],
        lambda g, b: g.get(b["a"], "w") > g.get(b["b"], "w") and g.get(b["c"], "w") != 0,
    ),
    "disconnected": ("match { a: B  c: C { w: 1 } }", {"a": "B", "c": "C"}, [], lambda g, b: g.get(b["c"], "w") == 1),
    "star": (
        "match { a: A  x: A  y: A  a -E- x  a -E- y } where x.w <= y.w",
        {"a": "A", "x": "A", "y": "A"},
        [("a", "x", "E"), ("a", "y", "E")],
        lambda g, b: g.get(b["x"], "w") <= g.get(b["y"], "w"),
    ),
}

PATTERN_RB = book("\n".join(f"rule p_{name} {{ {text} }}" for name, (text, *_rest) in PATTERNS.items()))


def _as_digraph(nodes, edges):
    """Undirected edges as two arcs, directed ones as one arc; type on nodes and arcs."""
    d = nx.MultiDiGraph()
    for n, t in nodes:
        d.add_node(n, type=t)
    for u, v, t in edges:
        if t.endswith(">"):
            d.add_edge(u, v, type=t[:-1])
        else:
            d.add_edge(u, v, type=t)
            d.add_edge(v, u, type=t)
    return d


def reference(g, pnodes, pedges, flt):
    host = _as_digraph(
        [(n, g.node_type(n)) for n in g.nodes()],
        [(*g.ends(e), g.edge_type(e) + (">" if g.is_directed(e) else "")) for e in g.edges()],
    )
    pat = _as_digraph(list(pnodes.items()), pedges)

    def node_match(h, p):
        return h["type"] in SCHEMA.subtypes(p["type"])

    def edge_match(h, p):
        want = {d["type"] for d in p.values()}
        (t,) = want
        return sum(1 for d in h.values() if d["type"] in SCHEMA.subtypes(t)) >= len(p)

    gm = isomorphism.MultiDiGraphMatcher(host, pat, node_match=node_match, edge_match=edge_match)
    out = set()
    for mapping in gm.subgraph_monomorphisms_iter():
        b = {pv: hn for hn, pv in mapping.items()}
        if flt is None or flt(g, b):
            out.add(tuple(sorted(b.items())))
    return out


@SETTINGS
@given(typed_graphs(max_nodes=9, max_edges=16))
def test_matcher_equals_networkx(spec):
    g = build_graph(SCHEMA, spec)
    for name, (_text, pnodes, pedges, flt) in PATTERNS.items():
        rule = PATTERN_RB.rules[f"p_{name}"]
        found = Matcher(rule, g).all()
        got = {tuple(sorted((v, m.binding[v]) for v in pnodes)) for m in found}
        assert got == reference(g, pnodes, pedges, flt), name
        # the depth-first (anchored) search agrees with the full search
        anchored = set()
        var = next(iter(pnodes))
        for n in g.nodes():
            anchored |= {m.key for m in Matcher(rule, g).anchored(var, n)}
        assert anchored == {m.key for m in found}, name
        # keys are sorted and unique, every match re-checks
        keys = [m.key for m in found]
        assert keys == sorted(set(keys))
        assert all(Matcher(rule, g).check(m.binding) for m in found[:5])


# ------------------------------------------------------------------------------------------------
# 7. incremental match sets equal full searches
# ------------------------------------------------------------------------------------------------

WATCHED = ["bump", "cut", "join", "promote", "tag", "nac_plain", "nac_where", "nac_two", "add_d", "del_n", "lone"]


@SETTINGS
@given(
    typed_graphs(max_nodes=15, max_edges=30),
    st.lists(st.tuples(st.sampled_from(MUTATORS), st.integers(0, 1000)), max_size=10),
)
def test_incremental_equals_full(spec, steps):
    g = build_graph(SCHEMA, spec)
    sets = {name: MatchSet(Matcher(RB.rules[name], g)) for name in WATCHED}
    r = Runner(RB, g)
    for rule, k in steps:
        ms = Matcher(RB.rules[rule], g).all()
        if not ms:
            continue
        app = r.apply(Matcher(RB.rules[rule], g), ms[k % len(ms)])
        changes = g.changes_since(app.mark)
        for name, s in sets.items():
            s.update(changes)
            full = all_keys(name, g)
            assert sorted(s.matches) == full, (name, rule)
            assert (s.first().key if s.first() else None) == (full[0] if full else None)


# ------------------------------------------------------------------------------------------------
# 8. trace replay gives the same snapshot
# ------------------------------------------------------------------------------------------------


@FEW
@given(typed_graphs(), st.lists(st.tuples(st.sampled_from(MUTATORS), st.integers(0, 1000)), max_size=8))
def test_trace_replay_same_snapshot(spec, steps):
    g = build_graph(SCHEMA, spec)
    r = Runner(RB, g)
    for rule, k in steps:
        ms = Matcher(RB.rules[rule], g).all()
        if ms:
            r.apply(Matcher(RB.rules[rule], g), ms[k % len(ms)])
    r.run("mix")
    fresh = build_graph(SCHEMA, spec)
    replay(r.trace.to_json(), RB, fresh)
    assert fresh.snapshot() == g.snapshot()
