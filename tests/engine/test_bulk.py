"""Bulk construction of a host graph (issue 18): the garbage collector is paused while the arrays
are added, and left as it was, also when the addition is refused."""

from __future__ import annotations

import gc
import math

import numpy as np
import pytest

from vaultgram.engine.errors import SchemaError
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.rulebook import rulebook_from_text

SCHEMA = rulebook_from_text("schema s { node A  edge E (A -- A) }").schema


@pytest.mark.parametrize("enabled", [True, False])
def test_bulk_additions_pause_the_collector_and_restore_it(monkeypatch, enabled):
    seen = []
    real = HostGraph._index_edges
    monkeypatch.setattr(HostGraph, "_index_edges", lambda *a: (seen.append(gc.isenabled()), real(*a))[1])
    (gc.enable if enabled else gc.disable)()
    try:
        g = HostGraph(SCHEMA)
        g.add_nodes("A", range(4))
        g.add_edges("E", [(0, 1), (1, 2), (2, 3)])
        assert seen == [False] and gc.isenabled() == enabled
        with pytest.raises(SchemaError):
            g.add_edges("E", [(0, 9)])                      # node 9 does not exist
        assert gc.isenabled() == enabled
        assert sorted(g.incident(1)) == [0, 1] and g.num_edges == 3
    finally:
        gc.enable()


# ------------------------------------------------------------------------------------------------
# The bulk path keeps attributes, types, ends and the type index in arrays until they are used:
# everything a graph built in bulk answers is what the same graph built element by element answers.
# ------------------------------------------------------------------------------------------------

RICH = rulebook_from_text("""
schema r {
  node P { pos: vec2, label: str = "p", size: float = 1.5, flag: bool = false, k: int = -1 }
  node Q : P
  edge L (P -- P) { w: float = 0.0, tag: str = "" }
  edge M (P -> Q)
}
""").schema

POS = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (-1.0, 0.5), (0.5, -1.0), (2.0, 2.0)]
LINKS = [(0, 1), (0, 2), (0, 3), (0, 4), (1, 2), (4, 1)]


def _angle(g, e, n):
    """The direction of edge ``e`` leaving node ``n`` (as :func:`_angles` computes it in bulk)."""
    p, q = g.get(n, "pos"), g.get(g.other(e, n), "pos")
    return math.atan2(q[1] - p[1], q[0] - p[0])


def _angles(ends) -> list:
    return [[_angle_of(POS[u], POS[v]), _angle_of(POS[v], POS[u])] for u, v in ends]


def _angle_of(p, q) -> float:
    return math.atan2(q[1] - p[1], q[0] - p[0])


def one_by_one() -> HostGraph:
    g = HostGraph(RICH, _angle)
    for i, p in enumerate(POS[:5]):
        g.add_node("P", {"pos": p, "label": f"n{i}", "size": i, "flag": i % 2 == 0}, id=i)
    g.add_node("Q", {"pos": POS[5]}, id=5)
    for u, v in LINKS:
        g.add_edge("L", u, v, {"w": u + v / 10})
    g.add_edge("M", 0, 5)
    return g


def in_bulk(angle=_angle, angles=True) -> HostGraph:
    """The graph of :func:`one_by_one` built in bulk; ``angles``: the rotation keys given (else the
    angle function is called for each half-edge)."""
    g = HostGraph(RICH, angle)
    g.add_nodes("P", np.arange(5), {"pos": np.array(POS[:5]), "label": [f"n{i}" for i in range(5)],
                                    "size": np.arange(5), "flag": np.arange(5) % 2 == 0})
    g.add_nodes("Q", [5], {"pos": [POS[5]]})
    g.add_edges("L", LINKS, {"w": [u + v / 10 for u, v in LINKS]}, angles=_angles(LINKS) if angles else None)
    g.add_edges("M", [(0, 5)], angles=_angles([(0, 5)]) if angles else None)
    return g


@pytest.mark.parametrize("angles", [True, False])
def test_a_graph_built_in_bulk_is_the_graph_built_element_by_element(angles):
    one, bulk = one_by_one(), in_bulk(angles=angles)
    assert bulk.node_attrs(3) == one.node_attrs(3) == {"pos": (-1.0, 0.5), "label": "n3", "size": 3.0,
                                                       "flag": False, "k": -1}
    assert type(bulk.get(2, "size")) is float and type(bulk.get(2, "k")) is int and type(bulk.get(2, "flag")) is bool
    assert bulk.values("node", [4, 0, 5], "label") == one.values("node", [4, 0, 5], "label") == ["n4", "n0", "p"]
    assert bulk.values("edge", range(6), "w") == one.values("edge", range(6), "w")
    assert [bulk.rotation(n) for n in range(6)] == [one.rotation(n) for n in range(6)]
    assert bulk.ends(3) == (0, 4) and bulk.edge_type(6) == "M" and bulk.is_directed(6)
    assert (len(bulk), bulk.num_edges, bulk.count(["P", "Q"]), bulk.count(["L"])) == (6, 7, 6, 6)
    assert sorted(bulk.incident(0, ["L"])) == [0, 1, 2, 3] and bulk.degree(1) == 3
    assert all((a == b).all() for a, b in zip(bulk.arrays(), one.arrays()))
    assert bulk.snapshot() == one.snapshot() and bulk.to_json() == one.to_json()


def test_the_typed_structure_of_a_graph_built_in_bulk_is_read_as_it_is_used():
    g = in_bulk()
    node_type, edge_type, ends, typed = g.incidence
    assert (node_type[5], edge_type[6], ends[4], typed[2]) == ("Q", "M", (1, 2), {"L": {1, 4}})
    assert g.has_node(4) and not g.has_node(6) and g.has_edge(6) and not g.has_edge(7)
    assert not g.has_node(-1) and not g.has_node("4") and not g.has_edge(None)
    with pytest.raises(KeyError):
        g.ends(7)
    with pytest.raises(KeyError):
        g.node_type(9)
    assert sorted(g.of_types(["P"])) == [0, 1, 2, 3, 4] and list(g.of_types(["M"])) == [6]


def test_numbers_still_in_their_bulk_columns_are_read_there_and_the_others_one_by_one():
    g = in_bulk(angle=None)
    g.set_node_attr(1, "size", 7)                           # now a dictionary of its own
    ids = np.array([0, 1, 2, 5])
    held = {int(i): v for at, column in g.bulk_numbers("node", ids, "size") for i, v in zip(ids[at], column)}
    assert held == {0: 0.0, 2: 2.0}                         # node 5's default is not an array of numbers
    assert g.values("node", [0, 1, 2, 5], "size") == [0.0, 7, 2.0, 1.5]
    assert list(g.bulk_numbers("node", np.array([0, 1]), "label")) == []  # strings: not numbers


def test_changes_to_elements_added_in_bulk_and_never_used_are_undone_exactly():
    one, bulk = one_by_one(), in_bulk()
    before = one.snapshot()
    mark = bulk.mark()
    bulk.set_node_attr(3, "pos", (3.0, 3.0))               # moves: the rotation at 0 changes
    bulk.set_edge_attr(5, "tag", "x")
    bulk.retype(2, "Q")
    bulk.remove_edge(3)
    for e in list(bulk.incident(4)):
        bulk.remove_edge(e)
    bulk.remove_node(4)
    assert not bulk.has_node(4) and not bulk.has_edge(5) and bulk.count(["P"]) == 3 and len(bulk) == 5
    assert bulk.changes_since(mark).nodes == {0, 1, 2, 3, 4} and bulk.changes_since(mark).types >= {"P", "Q", "L"}
    assert bulk.values("node", [0, 1], "label") == ["n0", "n1"]
    bulk.rollback(mark)
    assert bulk.snapshot() == before


def test_undoing_a_bulk_addition_and_adding_again():
    g = HostGraph(RICH)
    g.add_nodes("P", [3, 1], {"pos": [(0.0, 0.0), (1.0, 0.0)]})
    mark = g.mark()
    g.add_nodes("P", [0, 2], {"pos": [(2.0, 0.0), (3.0, 0.0)], "k": [5, 6]})
    g.add_edges("L", [(0, 1), (2, 3)])
    g.rollback(mark)
    assert g.nodes() == [1, 3] and g.num_edges == 0 and not g.has_node(0)
    with pytest.raises(KeyError):
        g.node_attrs(2)
    g.add_nodes("Q", [2, 0], {"pos": [(4.0, 0.0), (5.0, 0.0)]})
    g.add_edges("M", [(1, 2)])
    assert g.node_attrs(2) == {"pos": (4.0, 0.0), "label": "p", "size": 1.5, "flag": False, "k": -1}
    assert g.node_type(0) == "Q" and g.ends(0) == (1, 2) and g.edges() == [0]


@pytest.mark.parametrize("ids", [[1, 1], [-1], [0], range(0, 1)])
def test_bulk_node_ids_must_be_new_distinct_and_non_negative(ids):
    g = in_bulk()
    before = g.snapshot()
    with pytest.raises(SchemaError, match="new, distinct and non-negative"):
        g.add_nodes("P", ids, {"pos": [(0.0, 0.0)] * len(ids)})
    assert g.snapshot() == before


def test_bulk_edges_are_checked_once_per_pair_of_end_types():
    g = in_bulk()
    with pytest.raises(SchemaError, match=r"cannot join node 1 \(P\) and node 2 \(P\)"):
        g.add_edges("M", [(0, 5), (1, 2), (3, 4)])
    assert g.num_edges == 7
