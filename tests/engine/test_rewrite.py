"""Rewrite statements, matching features (conditions, constraints, NACs, parameters) and why-not."""

from __future__ import annotations

import math

import pytest

from vaultgram.engine.errors import RewriteError  # noqa: E402
from vaultgram.engine.expressions import Functions  # noqa: E402
from vaultgram.engine.graph import HostGraph  # noqa: E402
from vaultgram.engine.matcher import Matcher  # noqa: E402
from vaultgram.engine.rewriter import apply_rule  # noqa: E402
from vaultgram.engine.strategy import Runner  # noqa: E402
from vaultgram.engine.whynot import why_not  # noqa: E402

from strategies.rules import book  # noqa: E402


def matches(rb, g, rule, params=None):
    return [dict(m.binding) for m in Matcher(rb.rules[rule], g, params).all()]


def star(rb, center="A", leaves=("A", "A", "A")):
    """A center node joined by E edges to leaves."""
    g = HostGraph(rb.schema)
    c = g.add_node(center)
    ls = [g.add_node(t) for t in leaves]
    es = [g.add_edge("E", c, leaf) for leaf in ls]
    return g, c, ls, es


# ------------------------------------------------------------------------------------------------
# delete / detach delete / DPO
# ------------------------------------------------------------------------------------------------


def test_delete_edge():
    rb = book("rule r { match { a: A  b: A  e: a -E- b } delete e }")
    g, c, ls, es = star(rb)
    r = Runner(rb, g)
    app = r.apply_once("r")
    assert app.deleted_edges == [es[0]]
    assert g.num_edges == 2 and len(g) == 4


def test_dpo_refuses_node_with_other_edges():
    rb = book("rule r { match { a: A  b: A  e: a -E- b } delete e, a }")
    g, c, ls, es = star(rb)
    # the centre has 3 edges: deleting it with one of them would leave two dangling -> not a match;
    # a leaf has only one edge, which the rule deletes -> a match
    found = matches(rb, g, "r")
    assert found and all(m["a"] != c for m in found)
    assert sorted(m["a"] for m in found) == ls
    snap = g.snapshot()
    Runner(rb, g).apply_all("r")
    assert g.num_edges == 0 and len(g) == 1
    assert snap != g.snapshot()


def test_dpo_refusal_single_node():
    rb = book("rule r { match { a: A } delete a }")
    g, c, ls, es = star(rb)
    assert matches(rb, g, "r") == []
    w = why_not(Matcher(rb.rules["r"], g))
    assert w.matches == 0 and "dangling" in w.failed
    g.add_node("A")
    assert matches(rb, g, "r") == [{"a": 4}]


def test_detach_delete():
    rb = book("rule r { match { a: A { w: 5 } } detach delete a }")
    g, c, ls, es = star(rb)
    g.add_edge("E", ls[0], ls[1])
    g.set_node_attr(c, "w", 5)
    app = Runner(rb, g).apply_once("r")
    assert app.deleted_nodes == [c]
    assert sorted(app.deleted_edges) == sorted(es)
    assert g.nodes() == ls and g.num_edges == 1


# ------------------------------------------------------------------------------------------------
# create
# ------------------------------------------------------------------------------------------------


def test_create_node_and_edges_with_expressions_and_functions():
    f = Functions()
    f.register("triple", lambda x: 3 * x, ("int",), "int")
    rb = book(
        """
rule r(k: int = 2) {
  match { a: A  c: C  a -D-> c }
  create n: B { w = triple(a.w) + k }
  create e: n -E- a { m = c.w * 2 }
  create n -D-> c
  create c <-D- a { m = 1 }
}""",
        f,
    )
    g = HostGraph(rb.schema)
    a = g.add_node("A", {"w": 3})
    c = g.add_node("C", {"w": 4})
    g.add_edge("D", a, c)
    app = Runner(rb, g).apply_once("r", {"k": 1})
    (n,) = app.created_nodes
    assert g.node_type(n) == "B" and g.get(n, "w") == 10
    e_new, d1, d2 = app.created_edges
    assert g.edge_type(e_new) == "E" and set(g.ends(e_new)) == {n, a} and g.get_edge(e_new, "m") == 8
    assert g.edge_type(d1) == "D" and g.ends(d1) == (n, c) and g.get_edge(d1, "m") == 0
    assert g.ends(d2) == (a, c) and g.get_edge(d2, "m") == 1


def test_statements_run_in_order_create_sees_earlier_set():
    rb = book(
        """
rule r {
  match { a: A }
  set a.w = a.w + 10
  create n: A { w = a.w }
}"""
    )
    g = HostGraph(rb.schema)
    a = g.add_node("A", {"w": 1})
    app = Runner(rb, g).apply_once("r")
    # documented (docs/language.md 3.5): statements run in order, a later create sees an earlier set
    assert g.get(a, "w") == 11
    assert g.get(app.created_nodes[0], "w") == 11


def test_later_set_sees_earlier_set():
    rb = book("rule r { match { a: A  b: A { w: 5 } } set a.w = 1  set b.w = a.w }")
    g = HostGraph(rb.schema)
    a = g.add_node("A", {"w": 0})
    b = g.add_node("A", {"w": 5})
    Runner(rb, g).apply_once("r")
    assert g.get(a, "w") == 1 and g.get(b, "w") == 1


def test_failing_function_rolls_back():
    f = Functions()

    def boom(x):
        raise ValueError("no")

    f.register("boom", boom, ("int",), "int")
    rb = book("rule r { match { a: A } create n: A create n -E- a set a.w = boom(a.w) }", f)
    g = HostGraph(rb.schema)
    g.add_node("A")
    snap = g.snapshot()
    with pytest.raises(RewriteError, match="rule r"):
        Runner(rb, g).apply_once("r")
    assert g.snapshot() == snap


# ------------------------------------------------------------------------------------------------
# retype / set / merge
# ------------------------------------------------------------------------------------------------


def test_retype_and_subtype_matching():
    rb = book("rule r { match { a: A { w: 1 } } retype a as B }\nrule q { match { b: B } set b.w = 2 }")
    g = HostGraph(rb.schema)
    a = g.add_node("A", {"w": 1})
    g.add_node("A", {"w": 0})
    Runner(rb, g).apply_once("r")
    assert g.node_type(a) == "B" and g.get(a, "w") == 1
    assert matches(rb, g, "q") == [{"b": a}]


def test_retype_endpoint_violation_is_rewrite_error_and_graph_unchanged():
    rb = book("rule r { match { a: A  c: C  a -D-> c } retype a as C  set c.w = 9 }")
    g = HostGraph(rb.schema)
    a = g.add_node("A")
    c = g.add_node("C")
    g.add_edge("D", a, c)
    snap = g.snapshot()
    with pytest.raises(RewriteError, match="rule r"):
        Runner(rb, g).apply_once("r")
    assert g.snapshot() == snap


def test_set_node_and_edge_attributes():
    rb = book("rule r { match { a: A  b: A  e: a -E- b { m: 0 } } set e.m = a.w + b.w  set a.w = 7 }")
    g = HostGraph(rb.schema)
    a = g.add_node("A", {"w": 2})
    b = g.add_node("A", {"w": 3})
    e = g.add_edge("E", a, b)
    Runner(rb, g).apply_once("r")
    assert g.get_edge(e, "m") == 5 and g.get(a, "w") == 7


def test_merge_moves_edges_and_removes_shared():
    rb = book("rule r { match { a: A { w: 1 }  b: A { w: 2 }  a -E- b } merge a into b }")
    g = HostGraph(rb.schema)
    a = g.add_node("A", {"w": 1})
    b = g.add_node("A", {"w": 2})
    x = g.add_node("A")
    c = g.add_node("C")
    ab = g.add_edge("E", a, b)
    ax = g.add_edge("E", x, a, {"m": 2})
    ac = g.add_edge("D", a, c)
    app = Runner(rb, g).apply_once("r")
    assert not g.has_node(a) and app.deleted_nodes == [a]
    assert not g.has_edge(ab)
    assert g.ends(ax) == (x, b) and g.get_edge(ax, "m") == 2
    assert g.ends(ac) == (b, c) and g.edge_type(ac) == "D"
    assert g.degree(b) == 2


# ------------------------------------------------------------------------------------------------
# foreach
# ------------------------------------------------------------------------------------------------

RING = """
rule explode {
  match { s: A { w: 9 } }
  foreach e: s -E- n {
    create r: B { w = n.w }
    create r -E- n
    create r -E- next(r)
    delete e
  }
  delete s
}
"""


def test_foreach_next_builds_ring_in_rotation_order():
    rb = book(RING)
    g = HostGraph(rb.schema)
    s = g.add_node("A", {"w": 9})
    leaves = [g.add_node("A", {"w": i}) for i in range(4)]
    for leaf in leaves:
        g.add_edge("E", s, leaf)
    app = Runner(rb, g).apply_once("r" if False else "explode")
    assert not g.has_node(s)
    ring = app.created_nodes
    assert len(ring) == 4
    # r_i copies leaf i's w and is joined to leaf i and to r_{i+1}
    for i, r in enumerate(ring):
        assert g.get(r, "w") == i
        nbrs = {g.other(e, r) for e in g.incident(r)}
        assert nbrs == {leaves[i], ring[(i + 1) % 4], ring[(i - 1) % 4]}
    assert g.num_edges == 8


def test_foreach_prev_and_where():
    rb = book(
        """
rule r {
  match { s: A { w: 9 } }
  foreach s -E- n where n.w > 0 {
    create x: B { w = n.w }
    create x -E- n
    create x -E- prev(x)
  }
}"""
    )
    g = HostGraph(rb.schema)
    s = g.add_node("A", {"w": 9})
    leaves = [g.add_node("A", {"w": w}) for w in (1, 0, 2, 3)]
    for leaf in leaves:
        g.add_edge("E", s, leaf)
    app = Runner(rb, g).apply_once("r")
    xs = app.created_nodes
    assert [g.get(x, "w") for x in xs] == [1, 2, 3]  # the skipped leaf (w=0) gets no iteration
    assert g.degree(leaves[1]) == 1
    for i, x in enumerate(xs):
        assert {g.other(e, x) for e in g.incident(x)} == {
            [leaves[0], leaves[2], leaves[3]][i], xs[i - 1], xs[(i + 1) % 3]
        }
    assert len(app.created_edges) == 6


def test_foreach_next_of_neighbour():
    rb = book(
        """
rule r {
  match { s: A { w: 9 } }
  foreach s -E- n {
    create n -E- next(n)
  }
}"""
    )
    g = HostGraph(rb.schema)
    s = g.add_node("A", {"w": 9})
    leaves = [g.add_node("A") for _ in range(3)]
    for leaf in leaves:
        g.add_edge("E", s, leaf)
    app = Runner(rb, g).apply_once("r")
    assert len(app.created_edges) == 3


def test_foreach_uses_geometric_rotation():
    rb = book(
        """
schema geo {
  node P { pos: vec2 }
  edge L (P -- P)
}
rule ring {
  match { s: P { pos: vec2(0, 0) } }
  foreach s -L- n {
    create r: P { pos = n.pos }
    create r -L- next(r)
  }
}"""
    )

    def angle(g, e, n):
        p, q = g.get(n, "pos"), g.get(g.other(e, n), "pos")
        return math.atan2(q[1] - p[1], q[0] - p[0])

    g = HostGraph(rb.schema, angle)
    s = g.add_node("P", {"pos": (0.0, 0.0)})
    pts = [(1, 0), (-1, 0), (0, 1), (0, -1)]  # insertion order differs from angular order
    for p in pts:
        g.add_edge("L", s, g.add_node("P", {"pos": p}))
    app = Runner(rb, g).apply_once("ring")
    ring = app.created_nodes
    positions = [g.get(r, "pos") for r in ring]
    assert positions == [(0, -1), (1, 0), (0, 1), (-1, 0)]  # counter-clockwise from -90deg
    for i, r in enumerate(ring):
        assert {g.other(e, r) for e in g.incident(r)} == {ring[(i + 1) % 4], ring[(i - 1) % 4]}


# ------------------------------------------------------------------------------------------------
# conditions, constraints, NACs, parameters
# ------------------------------------------------------------------------------------------------


def test_where_arithmetic_degree_in_and_function():
    f = Functions()
    f.register("parity", lambda x: x % 2, ("int",), "int")
    rb = book(
        """
rule arith { match { a: A } where (a.w * 2 + 1) % 3 == 0 }
rule deg { match { a: A } where degree(a, E) >= 2 and degree(a, D) == 0 }
rule member { match { a: A } where a.w in [1, 3] }
rule fn { match { a: A } where parity(a.w) == 1 and not (a.w > 2) }
""",
        f,
    )
    g = HostGraph(rb.schema)
    ns = [g.add_node("A", {"w": w}) for w in range(5)]
    c = g.add_node("C")
    g.add_edge("E", ns[0], ns[1])
    g.add_edge("E", ns[0], ns[2])
    g.add_edge("E", ns[3], ns[1])
    g.add_edge("D", ns[3], c)
    assert [m["a"] for m in matches(rb, g, "arith")] == [1, 4]
    assert [m["a"] for m in matches(rb, g, "deg")] == [0, 1]
    assert [m["a"] for m in matches(rb, g, "member")] == [1, 3]
    assert [m["a"] for m in matches(rb, g, "fn")] == [1]


def test_inline_constraints_on_nodes_and_edges():
    rb = book("rule r { match { a: A { w >= 1, w != 3 }  b: A  e: a -E- b { m: 2 } } }")
    g = HostGraph(rb.schema)
    ns = [g.add_node("A", {"w": w}) for w in (0, 1, 3)]
    g.add_edge("E", ns[0], ns[1], {"m": 2})
    g.add_edge("E", ns[1], ns[2], {"m": 1})
    g.add_edge("E", ns[2], ns[0], {"m": 2})
    assert matches(rb, g, "r") == [{"a": 1, "b": 0, "e": 0}]


def test_several_nacs():
    rb = book(
        """
rule r {
  match { a: A }
  not { a -D-> c  c: C }
  not { a -E- x  x: B }
}"""
    )
    g = HostGraph(rb.schema)
    free = g.add_node("A")
    with_d = g.add_node("A")
    with_b = g.add_node("A")
    b = g.add_node("B")
    c = g.add_node("C")
    g.add_edge("D", with_d, c)
    g.add_edge("E", with_b, b)
    assert [m["a"] for m in matches(rb, g, "r")] == [free, b]
    w = why_not(Matcher(rb.rules["r"], g, {}))
    assert w.matches == 2


def test_nac_injective_against_match():
    # NAC variable x cannot be b itself
    rb = book("rule r { match { a: A  b: A  a -E- b } not { a -E- x  x: A } }")
    g = HostGraph(rb.schema)
    a = g.add_node("A")
    b = g.add_node("A")
    g.add_edge("E", a, b)
    assert len(matches(rb, g, "r")) == 2
    x = g.add_node("A")
    g.add_edge("E", a, x)
    assert [(m["a"], m["b"]) for m in matches(rb, g, "r")] == [(b, a), (x, a)]


def test_nac_with_where():
    rb = book("rule r { match { a: A } not { a -E- x  x: A  where x.w > 1 } }")
    g = HostGraph(rb.schema)
    a = g.add_node("A")
    x = g.add_node("A", {"w": 1})
    g.add_edge("E", a, x)
    assert a in [m["a"] for m in matches(rb, g, "r")]
    g.set_node_attr(x, "w", 2)
    assert a not in [m["a"] for m in matches(rb, g, "r")]


def test_node_parameter_binds_start():
    rb = book("rule r(start: A) { match { start -E- b  b: A } set b.w = 1 }")
    g, c, ls, es = star(rb)
    assert sorted(m["b"] for m in matches(rb, g, "r", {"start": c})) == ls
    assert [m["b"] for m in matches(rb, g, "r", {"start": ls[0]})] == [c]
    with pytest.raises(RewriteError):
        Matcher(rb.rules["r"], g, {"start": 99})
    Runner(rb, g).apply_once("r", {"start": ls[1]})
    assert g.get(c, "w") == 1 and all(g.get(leaf, "w") == 0 for leaf in ls)


def test_value_params_defaults_and_missing():
    rb = book("rule r(k: int = 2) { match { a: A { w >= k } } }\nrule q(k: int) { match { a: A { w == k } } }")
    g = HostGraph(rb.schema)
    for w in range(4):
        g.add_node("A", {"w": w})
    assert [m["a"] for m in matches(rb, g, "r")] == [2, 3]
    assert [m["a"] for m in matches(rb, g, "r", {"k": 3})] == [3]
    with pytest.raises(RewriteError, match="need a value"):
        Matcher(rb.rules["q"], g, {})
    with pytest.raises(RewriteError, match="no parameter"):
        Matcher(rb.rules["r"], g, {"zz": 1})


def test_matching_is_injective_and_directed():
    rb = book(
        """
rule any { match { a: A  c: C  a -D- c } }
rule fwd { match { a: A  c: C  a -D-> c } }
rule back { match { a: A  c: C  c <-D- a } }
rule tri { match { a: A  b: A  x: A  a -E- b  b -E- x  x -E- a } }
"""
    )
    g = HostGraph(rb.schema)
    a, b, x = (g.add_node("A") for _ in range(3))
    c = g.add_node("C")
    g.add_edge("D", a, c)
    g.add_edge("E", a, b)
    g.add_edge("E", b, x)
    g.add_edge("E", x, a)
    assert len(matches(rb, g, "any")) == len(matches(rb, g, "fwd")) == len(matches(rb, g, "back")) == 1
    assert len(matches(rb, g, "tri")) == 6  # 3! automorphisms, all distinct nodes


def test_parallel_edges_are_distinct_matches():
    rb = book("rule r { match { a: A  b: A  e: a -E- b  f: a -E- b } }")
    g = HostGraph(rb.schema)
    a, b = g.add_node("A"), g.add_node("A")
    g.add_edge("E", a, b)
    assert matches(rb, g, "r") == []
    g.add_edge("E", a, b)
    assert len(matches(rb, g, "r")) == 4  # 2 orientations x 2 edge orders


# ------------------------------------------------------------------------------------------------
# why-not
# ------------------------------------------------------------------------------------------------


def test_why_not_messages():
    rb = book(
        """
rule r {
  match { a: A  c: C  a -D-> c }
  where c.w > 5
}
rule n {
  match { a: A }
  not { a -E- b  b: B }
}"""
    )
    g = HostGraph(rb.schema)
    a = g.add_node("A")
    w = why_not(Matcher(rb.rules["r"], g))
    assert w.matches == 0 and "no" in w.failed
    assert "does not match" in str(w)
    c = g.add_node("C")
    g.add_edge("D", a, c)
    w = why_not(Matcher(rb.rules["r"], g))
    assert w.partial.get("a") == a and w.partial.get("c") == c
    assert "false" in w.failed
    assert w.pos.line == rb.rules["r"].source.pos.line + 2
    g.set_node_attr(c, "w", 6)
    w = why_not(Matcher(rb.rules["r"], g))
    assert w.matches == 1 and "1 match" in str(w)
    b = g.add_node("B")
    g.add_edge("E", a, b)
    # 'n' still matches b (a B is an A, and b has no B neighbour) -- restrict to a
    g2 = HostGraph(rb.schema)
    a2 = g2.add_node("A")
    b2 = g2.add_node("B")
    g2.add_edge("E", a2, b2)
    g2.add_edge("E", b2, g2.add_node("B"))
    w = why_not(Matcher(rb.rules["n"], g2))
    assert w.matches == 0 and "NAC #1" in w.failed


def test_apply_rule_directly():
    rb = book("rule r { match { a: A } set a.w = 4 }")
    g = HostGraph(rb.schema)
    a = g.add_node("A")
    m = Matcher(rb.rules["r"], g)
    app = apply_rule(rb.rules["r"], g, dict(m.first().binding), m.values)
    assert app.rule == "r" and g.get(a, "w") == 4
    g.rollback(app.mark)
    assert g.get(a, "w") == 0


def test_no_match_is_empty_list_not_keyerror():
    # minimal repro of the columnar bug: one A, no C; the plan scans a, then extends to c and empties
    rb = book("rule q { match { a: A  c: C  a -D-> c } }")
    g = HostGraph(rb.schema)
    g.add_node("A")
    assert Matcher(rb.rules["q"], g).all() == []


def test_no_match_in_empty_graph():
    rb = book("rule r { match { a: A  b: A } }")
    assert Matcher(rb.rules["r"], HostGraph(rb.schema)).all() == []


def test_empty_pattern_with_nac_and_directed_and_nested_foreach():
    rb = book(
        """
rule seed { match { } not { a: A } create a: A }
rule out { match { a: A { w: 0 } } foreach a -D-> c { set c.w = 5 } }
rule nest { match { a: A { w: 0 } } foreach a -E- b { foreach b -D-> c { set c.w = 4 } } }
strategy s { seed fixpoint max 3 }
"""
    )
    g = HostGraph(rb.schema)
    r = Runner(rb, g)
    r.run("s")
    assert len(g) == 1 and r.reports[0].applications == 1
    assert matches(rb, g, "seed") == []
    a = g.nodes()[0]
    c, c2 = g.add_node("C"), g.add_node("C")
    g.add_edge("D", a, c)
    b = g.add_node("A", {"w": 1})
    g.add_edge("E", a, b)
    g.add_edge("D", b, c2)
    r.apply_once("out")
    assert (g.get(c, "w"), g.get(c2, "w")) == (5, 0)
    r.apply_once("nest")
    assert (g.get(c, "w"), g.get(c2, "w")) == (5, 4)


def test_no_match_is_empty_list():
    # regression: the columnar search used to raise KeyError('c') when it emptied before the last step
    rb = book("rule q { match { a: A  c: C  a -D-> c } }\nrule r { match { a: A  b: A } }")
    g = HostGraph(rb.schema)
    assert Matcher(rb.rules["r"], g).all() == []
    g.add_node("A")
    assert Matcher(rb.rules["q"], g).all() == []
    assert Matcher(rb.rules["r"], g).first() is None
