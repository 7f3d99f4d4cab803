"""Unit tests of the typed host graph (engine/graph.py)."""

from __future__ import annotations

import math

import pytest

from vaultgram.engine.errors import SchemaError
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.rulebook import rulebook_from_text

SCHEMA = """
schema s {
  abstract node Point { pos: vec2 }
  node Sing : Point { valence: int = 0, label: str = "x" }
  node Bnd : Point
  node Corner : Bnd
  node Other { need: int }
  edge Branch (Point -- Point) { length: float = 0.0 }
  edge Dual (Sing -> Bnd)
  abstract edge Link (Point -- Point)
  edge SubLink : Link
}
"""


@pytest.fixture(scope="module")
def schema():
    return rulebook_from_text(SCHEMA).schema


def P(x=0.0, y=0.0):
    return {"pos": (x, y)}


def test_type_index_and_subtypes(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P())
    b = g.add_node("Bnd", P(1))
    c = g.add_node("Corner", P(2))
    assert schema.subtypes("Bnd") == {"Bnd", "Corner"}
    assert schema.subtypes("Point") == {"Point", "Sing", "Bnd", "Corner"}
    assert sorted(g.of_types(schema.subtypes("Bnd"))) == [b, c]
    assert sorted(g.of_types(["Corner"])) == [c]
    assert g.count(schema.subtypes("Point")) == 3
    e = g.add_edge("Branch", s, c)
    assert list(g.of_types(["Branch"])) == [e]
    g.remove_edge(e)
    assert list(g.of_types(["Branch"])) == []
    g.retype(c, "Bnd")
    assert sorted(g.of_types(["Bnd"])) == [b, c] and list(g.of_types(["Corner"])) == []
    g.remove_node(c)
    assert sorted(g.of_types(["Bnd"])) == [b]


def test_endpoint_types_enforced(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P())
    c = g.add_node("Corner", P(1))
    o = g.add_node("Other", {"need": 1})
    g.add_edge("Dual", s, c)  # Corner is a Bnd
    with pytest.raises(SchemaError):
        g.add_edge("Dual", c, s)  # wrong direction
    with pytest.raises(SchemaError):
        g.add_edge("Branch", s, o)  # Other is not a Point
    with pytest.raises(SchemaError):
        g.add_edge("Nope", s, c)
    with pytest.raises(SchemaError):
        g.add_edge("Branch", s, 99)
    assert g.num_edges == 1


def test_abstract_types_refused(schema):
    g = HostGraph(schema)
    with pytest.raises(SchemaError, match="abstract"):
        g.add_node("Point", P())
    with pytest.raises(SchemaError, match="abstract"):
        g.add_node("Node")
    a = g.add_node("Sing", P())
    b = g.add_node("Bnd", P())
    with pytest.raises(SchemaError, match="abstract"):
        g.add_edge("Link", a, b)
    g.add_edge("SubLink", a, b)
    with pytest.raises(SchemaError):
        g.retype(a, "Point")
    with pytest.raises(SchemaError):
        g.add_node("Unknown")
    assert len(g) == 2


def test_attributes_defaults_required_and_type_checked(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P(1, 2))
    assert dict(g.node_attrs(s)) == {"pos": (1, 2), "valence": 0, "label": "x"}
    with pytest.raises(SchemaError, match="needs attribute 'pos'"):
        g.add_node("Sing", {})
    with pytest.raises(SchemaError, match="need"):
        g.add_node("Other", {})
    with pytest.raises(SchemaError, match="must be int"):
        g.add_node("Sing", {"pos": (0, 0), "valence": "three"})
    with pytest.raises(SchemaError, match="must be int"):
        g.add_node("Sing", {"pos": (0, 0), "valence": True})
    with pytest.raises(SchemaError, match="vec2"):
        g.add_node("Sing", {"pos": (0, 0, 0)})
    with pytest.raises(SchemaError, match="no attribute"):
        g.add_node("Sing", {"pos": (0, 0), "bogus": 1})
    # lists normalise to tuples, int fits float
    t = g.add_node("Sing", {"pos": [3, 4]})
    assert g.get(t, "pos") == (3, 4)
    b = g.add_node("Bnd", P())
    e = g.add_edge("Branch", s, b, {"length": 2})
    assert g.get_edge(e, "length") == 2
    with pytest.raises(SchemaError):
        g.set_edge_attr(e, "length", "long")
    with pytest.raises(SchemaError):
        g.set_node_attr(s, "valence", 1.5)
    with pytest.raises(SchemaError):
        g.set_node_attr(s, "nope", 1)
    g.set_node_attr(s, "valence", 4)
    assert g.get(s, "valence") == 4
    assert len(g) == 3


def test_self_loop_refused(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P())
    with pytest.raises(SchemaError, match="self-loop"):
        g.add_edge("Branch", s, s)
    assert g.num_edges == 0


def test_remove_node_with_edges_refused(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P())
    b = g.add_node("Bnd", P())
    e = g.add_edge("Branch", s, b)
    with pytest.raises(SchemaError, match="still has 1 edge"):
        g.remove_node(s)
    assert g.has_node(s)
    g.remove_edge(e)
    g.remove_node(s)
    assert not g.has_node(s)


def test_rotation_by_id_without_angle(schema):
    g = HostGraph(schema)
    c = g.add_node("Sing", P())
    others = [g.add_node("Bnd", P(i)) for i in range(4)]
    e3 = g.add_edge("Branch", c, others[3], id=30)
    e1 = g.add_edge("Branch", c, others[1], id=10)
    e2 = g.add_edge("Branch", others[2], c, id=20)
    assert g.rotation(c) == [e1, e2, e3]
    assert g.next_around(c, e3) == e1
    assert g.next_around(c, e1, -1) == e3


def test_rotation_by_id_with_edges_added_out_of_id_order(schema):
    g = HostGraph(schema)
    c = g.add_node("Sing", P())
    others = [g.add_node("Bnd", P(i)) for i in range(5)]
    ids = [g.add_edge("Branch", c, others[k], id=i) for k, i in enumerate((40, 10, 50, 20, 60))]
    extra = g.add_edge("Branch", others[0], c)  # from the counter: after every id there
    assert g.rotation(c) == sorted(ids) + [extra] == [10, 20, 40, 50, 60, 61]
    assert g.rotation(others[0]) == [40, 61]


def test_endpoint_types_checked_for_every_pair_of_types(schema):
    g = HostGraph(schema)
    s, b, o = g.add_node("Sing", P()), g.add_node("Bnd", P(1)), g.add_node("Other", {"need": 1})
    g.add_edge("Dual", s, b)
    g.add_edge("Dual", s, g.add_node("Bnd", P(2)))  # the same types again
    with pytest.raises(SchemaError):
        g.add_edge("Dual", b, s)  # the same edge type, the ends' types swapped on a directed edge
    g.retype(b, "Corner")
    with pytest.raises(SchemaError):
        g.add_edge("Branch", s, o)
    g.add_edge("Dual", s, b)  # Corner is a Bnd
    assert g.num_edges == 3


def _angle(g, e, n):
    o = g.other(e, n)
    p, q = g.get(n, "pos"), g.get(o, "pos")
    return math.atan2(q[1] - p[1], q[0] - p[0])


def test_rotation_by_angle_and_refresh(schema):
    g = HostGraph(schema, _angle)
    c = g.add_node("Sing", P())
    # directions: 90deg, 180deg, 0deg, -90deg
    dirs = [(0, 1), (-1, 0), (1, 0), (0, -1)]
    nodes = [g.add_node("Bnd", P(*d)) for d in dirs]
    edges = [g.add_edge("Branch", c, n) for n in nodes]
    # sorted by angle: -90 (edges[3]), 0 (edges[2]), 90 (edges[0]), 180 (edges[1])
    assert g.rotation(c) == [edges[3], edges[2], edges[0], edges[1]]
    m = g.mark()
    snap = g.snapshot()
    g.set_node_attr(nodes[1], "pos", (0.5, -2.0))  # now at about -76deg, after -90
    assert g.rotation(c) == [edges[3], edges[1], edges[2], edges[0]]
    g.rollback(m)
    assert g.snapshot() == snap


def test_a_move_that_keeps_the_order_still_renews_the_keys_later_edges_are_placed_by(schema):
    """A neighbour that moves from 80 to 120 degrees stays between its neighbours at 0 and 180, but
    an edge added afterwards at 100 degrees must come before it, not after (the stale key of 80
    degrees put it after, and a face walk then ran round the wrong side)."""
    g = HostGraph(schema, _angle)
    c = g.add_node("Sing", P())
    east, west = g.add_node("Bnd", P(1.0, 0.0)), g.add_node("Bnd", P(-1.0, 0.0))
    moved = g.add_node("Bnd", P(math.cos(math.radians(80)), math.sin(math.radians(80))))
    e_east, e_west, e_moved = (g.add_edge("Branch", c, n) for n in (east, west, moved))
    g.set_node_attr(moved, "pos", (math.cos(math.radians(120)), math.sin(math.radians(120))))
    assert g.rotation(c) == [e_east, e_moved, e_west]  # the same order as before the move
    late = g.add_edge("Branch", c, g.add_node("Bnd", P(math.cos(math.radians(100)), math.sin(math.radians(100)))))
    assert g.rotation(c) == [e_east, late, e_moved, e_west]


def test_rollback_restores_snapshot_exactly(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P())
    b = g.add_node("Bnd", P(1))
    c = g.add_node("Corner", P(2))
    e1 = g.add_edge("Branch", s, b)
    e2 = g.add_edge("Branch", s, c)
    g.add_edge("Dual", s, c)
    snap = g.snapshot()
    m = g.mark()
    n = g.add_node("Sing", P(5))
    g.add_edge("Branch", n, b)
    g.remove_edge(e1)
    g.remove_edge(e2)
    g.set_node_attr(s, "valence", 7)
    g.retype(c, "Bnd")
    g.add_edge("Branch", s, b, id=100)
    g.add_node("Bnd", P(), id=50)
    g.set_edge_attr(100, "length", 3.0)
    assert g.snapshot() != snap
    g.rollback(m)
    assert g.snapshot() == snap
    assert snap["counters"] == (3, 3)
    # the next ids are the ones the undone changes had used
    assert g.add_node("Bnd", P()) == 3


def test_retype_endpoint_violation_leaves_graph_unchanged(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P())
    c = g.add_node("Corner", P())
    g.add_edge("Dual", s, c)
    snap = g.snapshot()
    with pytest.raises(SchemaError):
        g.retype(c, "Sing")  # Dual needs a Bnd target
    assert g.snapshot() == snap
    assert list(g.of_types(["Corner"])) == [c]
    assert list(g.of_types(["Sing"])) == [s]


def test_transaction_rolls_back_on_exception(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P())
    snap = g.snapshot()
    with pytest.raises(RuntimeError):
        with g.transaction():
            b = g.add_node("Bnd", P())
            g.add_edge("Branch", s, b)
            g.set_node_attr(s, "valence", 3)
            raise RuntimeError("boom")
    assert g.snapshot() == snap
    with g.transaction():
        g.add_node("Bnd", P())
    assert len(g) == 2


def test_ids_explicit_and_duplicates(schema):
    g = HostGraph(schema)
    g.add_node("Sing", P(), id=5)
    with pytest.raises(SchemaError):
        g.add_node("Sing", P(), id=5)
    assert g.add_node("Sing", P()) == 6


def test_degree_by_type_and_networkx_export(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P())
    b = g.add_node("Bnd", P(1))
    c = g.add_node("Corner", P(2))
    g.add_edge("Branch", s, b)
    g.add_edge("Branch", s, c)
    g.add_edge("Dual", s, c)
    assert g.degree(s) == 3
    assert g.degree(s, ["Branch"]) == 2
    assert g.degree(s, ["Dual"]) == 1
    assert g.degree(b, ["Dual"]) == 0
    nxg = g.to_networkx()
    assert nxg.number_of_nodes() == 3 and nxg.number_of_edges() == 3
    assert nxg.nodes[c]["type"] == "Corner"
    assert sorted(d["type"] for _, _, d in nxg.edges(data=True)) == ["Branch", "Branch", "Dual"]


def test_changes_since(schema):
    g = HostGraph(schema)
    s = g.add_node("Sing", P())
    b = g.add_node("Bnd", P(1))
    m = g.mark()
    g.add_edge("Branch", s, b)
    ch = g.changes_since(m)
    assert ch.nodes == {s, b} and ch.types == {"Branch"}


def test_a_dropped_graph_is_freed_without_the_cyclic_collector(schema):
    """Bulk-built graphs hold no reference cycles (their lazy tables refer to them weakly), so a
    graph and its tables go as soon as the last reference does, even with the collector off."""
    import gc
    import weakref

    gc.disable()
    try:
        g = HostGraph(schema)
        g.add_nodes("Bnd", range(4), {"pos": [(float(i), 0.0) for i in range(4)]})
        g.add_edges("Branch", [(0, 1), (1, 2), (2, 3)])
        assert sorted(g.incident(1)) == [0, 1]
        gone = weakref.ref(g)
        del g
        assert gone() is None
    finally:
        gc.enable()
