"""The face index (engine/embedding.py FaceIndex): faces kept across changes and rollbacks, each equal
to a fresh face walk, walked again only where a change reached it."""

from __future__ import annotations

import math
import random

import pytest

from vaultgram.engine.embedding import face_index, face_walk, faces
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.rulebook import rulebook_from_text

SCHEMA = """
schema s {
  node P { pos: vec2 }
  edge Branch (P -- P)
  edge Dual (P -> P)
}
"""
MAP = {"Branch"}


@pytest.fixture(scope="module")
def schema():
    return rulebook_from_text(SCHEMA).schema


def _angle(g, e, n):
    p, q = g.get(n, "pos"), g.get(g.other(e, n), "pos")
    return math.atan2(q[1] - p[1], q[0] - p[0])


def _grid(schema, n: int = 4) -> tuple[HostGraph, dict]:
    """An n x n grid of unit squares (nodes at integer points), with a Dual edge in every square
    (another type: not part of the map)."""
    g = HostGraph(schema, _angle)
    at = {(i, j): g.add_node("P", {"pos": (float(i), float(j))}) for i in range(n + 1) for j in range(n + 1)}
    for (i, j), u in at.items():
        for di, dj in ((1, 0), (0, 1)):
            if (i + di, j + dj) in at:
                g.add_edge("Branch", u, at[(i + di, j + dj)])
        if (i + 1, j + 1) in at:
            g.add_edge("Dual", u, at[(i + 1, j + 1)])
    g.forget()
    return g, at


def _half_edges(g) -> list:
    return [(e, u) for e in g.edges() if g.edge_type(e) in MAP for u in g.ends(e)]


def _all_equal_to_walks(g, index) -> bool:
    return all(index.face(h) == face_walk(g, MAP, h) for h in _half_edges(g))


def test_faces_are_the_walks_each_walked_once_and_euler_holds(schema):
    g, at = _grid(schema)
    index = face_index(g, MAP)
    assert face_index(g, MAP) is index  # one index per graph and edge types
    assert _all_equal_to_walks(g, index)
    found = faces(g, MAP, walk=lambda graph, types, h: index.face(h))
    assert found == faces(g, MAP)  # the same faces in the same order
    nodes, edges = len(g), len(list(g.of_types(MAP)))
    assert nodes - edges + len(found) == 2 and len(found) == 16 + 1  # Euler: the squares and the outside
    assert index.walks == len(found)  # each face walked once, however many half-edges asked


def test_a_diagonal_walks_only_the_faces_it_splits_and_rollback_only_the_face_it_restores(schema):
    g, at = _grid(schema)
    index = face_index(g, MAP)
    assert _all_equal_to_walks(g, index)
    square = next(h for h in _half_edges(g) if h[1] == at[(1, 1)] and at[(2, 2)] in {u for _, u in index.face(h)})
    index.data(square)["mark"] = "split"
    far = [h for h in _half_edges(g) if at[(3, 3)] in g.ends(h[0])][0]
    index.data(far)["mark"] = "kept"
    walks, mark = index.walks, g.mark()
    d = g.add_edge("Branch", at[(1, 1)], at[(2, 2)])
    g.add_edge("Dual", at[(2, 1)], at[(1, 2)])  # not of the map: changes none of its faces
    assert _all_equal_to_walks(g, index)
    assert index.walks == walks + 2  # the square cut in two triangles, nothing else
    assert len(index.face((d, at[(1, 1)]))) == len(index.face((d, at[(2, 2)]))) == 3
    assert index.data(far) == {"mark": "kept"}  # a face the change did not reach keeps its data
    assert index.data(square) == {}  # the split one is a new face
    g.rollback(mark)
    assert _all_equal_to_walks(g, index)
    assert index.walks == walks + 3  # the square again
    assert index.data(far) == {"mark": "kept"}
    assert len(list(g.of_types(MAP))) == 40  # the grid's edges, no diagonal


def test_a_node_moved_empties_the_data_of_its_faces_only(schema):
    g, at = _grid(schema)
    index = face_index(g, MAP)
    here = [h for h in _half_edges(g) if h[1] == at[(2, 2)]]
    elsewhere = [h for h in _half_edges(g) if at[(2, 2)] not in {u for _, u in face_walk(g, MAP, h)}]
    for h in here + elsewhere:
        index.data(h)[h] = "outline"  # the data of a face: one entry per half-edge asked
    mark = g.mark()
    g.set_node_attr(at[(2, 2)], "pos", (2.2, 1.9))  # its rotation stays; its four squares change shape
    assert all(h not in index.data(h) for h in here)
    assert all(index.data(h)[h] == "outline" for h in elsewhere)
    assert _all_equal_to_walks(g, index)
    g.rollback(mark)
    assert all(h not in index.data(h) for h in here)  # the undo moves it again
    assert _all_equal_to_walks(g, index)


def test_random_changes_and_rollbacks_keep_every_face_equal_to_its_walk(schema):
    # a random sequence of diagonals added, edges removed, nodes moved, Dual edges added, rollbacks
    # and one forget: after each, every half-edge's face from the index is the fresh walk
    rng = random.Random(7)
    g, at = _grid(schema, 5)
    index = face_index(g, MAP)
    marks, asked = [], 0
    for step in range(120):
        what = rng.random()
        nodes = sorted(at.values())
        if what < 0.3:
            (i, j) = rng.choice([k for k in at if k[0] < 5 and k[1] < 5])
            u, v = (at[(i, j)], at[(i + 1, j + 1)]) if rng.random() < 0.5 else (at[(i + 1, j)], at[(i, j + 1)])
            if not any(g.other(e, u) == v for e in g.incident(u, MAP)):
                marks.append(g.mark())
                g.add_edge("Branch", u, v)
        elif what < 0.45:
            edges = sorted(g.of_types(MAP))
            marks.append(g.mark())
            g.remove_edge(rng.choice(edges))
        elif what < 0.6:
            n = rng.choice(nodes)
            x, y = g.get(n, "pos")
            marks.append(g.mark())
            g.set_node_attr(n, "pos", (x + rng.uniform(-0.2, 0.2), y + rng.uniform(-0.2, 0.2)))
        elif what < 0.7:
            marks.append(g.mark())
            g.add_edge("Dual", *rng.sample(nodes, 2))
        elif what < 0.97 and marks:
            g.rollback(marks.pop(rng.randrange(len(marks))))
            marks = [m for m in marks if m <= g.mark()]
        else:
            g.forget()
            marks = []
        if step % 3 == 0 or what >= 0.7:
            assert _all_equal_to_walks(g, index), step
            asked += len(_half_edges(g))
    assert _all_equal_to_walks(g, index)
    assert index.walks < asked / 10  # kept, not walked anew for every question


def test_node_data_is_kept_until_the_node_or_the_map_edges_at_it_change(schema):
    g, at = _grid(schema)
    index = face_index(g, MAP)
    centre, corner, far = at[(2, 2)], at[(0, 0)], at[(4, 4)]
    for n in (centre, corner, far):
        index.node_data(n)["degree"] = g.degree(n, MAP)
    mark = g.mark()
    g.add_edge("Dual", centre, at[(0, 4)])  # not of the map
    g.add_edge("Branch", corner, at[(1, 1)])  # a map edge at the corner
    assert index.node_data(centre) == {"degree": 4} and index.node_data(far) == {"degree": 2}
    assert index.node_data(corner) == {}  # its map degree changed: worked out again
    index.node_data(corner)["degree"] = g.degree(corner, MAP)
    assert index.node_data(corner)["degree"] == 3
    g.set_node_attr(far, "pos", (4.0, 4.1))
    assert index.node_data(far) == {} and index.node_data(centre) == {"degree": 4}
    g.rollback(mark)
    assert index.node_data(corner) == {} and index.node_data(centre) == {"degree": 4}  # undone: again
    late = g.add_node("P", {"pos": (9.0, 9.0)})
    index.node_data(late)["degree"] = 0
    g.rollback(mark)
    again = g.add_node("P", {"pos": (-9.0, -9.0)})  # the same id for another node
    assert again == late and index.node_data(again) == {}
