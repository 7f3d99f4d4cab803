"""Patches (paper §3.1, Figure 2f): ordered corners, sides joining them, each shared side walked once each way."""

from __future__ import annotations

from collections import Counter

import numpy as np

from vaultgram.domain import load_domain
from vaultgram.engine.embedding import face_index, face_walk, faces
from vaultgram.geometry.polygons import signed_area
from vaultgram.pipeline import decompose
from vaultgram.topology.patches import face_from, face_outline, find_patches, half_edge_polyline, kept_at_node
from vaultgram.topology.types import DIAGONAL, PLAN_EDGES

from paths import EXAMPLES


def test_patches_have_ordered_corners_and_connected_sides():
    dec = decompose(load_domain(EXAMPLES / "quad_with_hole.json"), 0.02)
    g = dec.graph
    for p in dec.patches:
        assert p.area() > 0  # counter-clockwise
        for i, side in enumerate(p.sides):
            assert np.allclose(side[0], g.get(p.corners[i], "pos"))
            assert np.allclose(side[-1], g.get(p.corners[(i + 1) % p.n_sides], "pos"))


def test_shared_sides_are_traversed_once_each_way():
    dec = decompose(load_domain(EXAMPLES / "l_shape.json"), 0.02)
    uses = Counter(he for p in dec.patches for side in p.side_edges for he in side)
    assert max(uses.values()) == 1
    interior_edges = {e for (e, _) in uses if dec.graph.edge_type(e) != "Boundary"}
    for e in interior_edges:
        u, v = dec.graph.ends(e)
        assert uses[(e, u)] == uses[(e, v)] == 1


def test_face_outline_is_the_faces_polylines_kept_by_content():
    dec = decompose(load_domain(EXAMPLES / "quad_with_hole.json"), 0.05)
    g = dec.graph
    all_faces = faces(g, PLAN_EDGES)
    for face in all_faces:
        found = face_outline(g, PLAN_EDGES, face)
        polys = [half_edge_polyline(g, e, u) for e, u in face]
        outline = np.vstack([p[:-1] for p in polys])
        assert all(np.array_equal(a, b) for a, b in zip(found.polylines, polys))
        assert np.array_equal(found.outline, outline)
        assert np.array_equal(found.closed, np.vstack([outline, outline[:1]]))
        assert found.area == signed_area(outline) and found.closed_area == signed_area(found.closed)
        assert not found.outline.flags.writeable and face_outline(g, PLAN_EDGES, face) is found  # shared, read-only
        assert all(np.array_equal(found.outline[k], poly[0]) for k, poly in zip(found.starts, polys))
    bounded = sum(face_outline(g, PLAN_EDGES, f).area > 0 for f in all_faces)
    assert bounded == len(dec.patches) + 1  # + each hole's inside
    # moved geometry is a new outline: a node of a face moved by one unit moves the outline's point
    face = next(f for f in all_faces if face_outline(g, PLAN_EDGES, f).area > 0)
    before = face_outline(g, PLAN_EDGES, face)
    e, u = next((e, u) for e, u in face if not g.edge_attrs(e).get("polyline"))
    mark, (x, y) = g.mark(), g.get(u, "pos")
    g.set_node_attr(u, "pos", (x + 1.0, y))
    after = face_outline(g, PLAN_EDGES, face)
    assert after is not before and np.array_equal(after.outline[face.index((e, u))], [x + 1.0, y])
    g.rollback(mark)
    assert np.array_equal(face_outline(g, PLAN_EDGES, face).outline, before.outline)


def test_find_patches_is_the_same_read_again():
    # the faces cut at their corners are kept across states (issue 13): reading the patches again
    # gives equal, read-only patches
    dec = decompose(load_domain(EXAMPLES / "fig7_curves.json"), 0.05)
    again = find_patches(dec.graph, dec.disc, PLAN_EDGES)
    assert [p.corners for p in again] == [p.corners for p in dec.patches]
    assert [p.side_edges for p in again] == [p.side_edges for p in dec.patches]
    for p, q in zip(again, dec.patches):
        assert all(np.array_equal(a, b) and not a.flags.writeable for a, b in zip(p.sides, q.sides))
    # what is kept with the faces (issue 13) follows a change: a diagonal across a quad makes two
    # triangles, one patch more, the rest as they were; after the rollback the patches are the first
    g, quad = dec.graph, next(p for p in dec.patches if p.n_sides == 4)
    mark = g.mark()
    g.add_edge(DIAGONAL, quad.corners[0], quad.corners[2])
    split = find_patches(g, dec.disc, PLAN_EDGES, strict=False)
    assert len(split) == len(dec.patches) + 1 and sum(p.n_sides == 3 for p in split) == sum(
        p.n_sides == 3 for p in dec.patches) + 2
    g.rollback(mark)
    assert [p.side_edges for p in find_patches(g, dec.disc, PLAN_EDGES)] == [p.side_edges for p in dec.patches]


def _distinct_faces(g, walk) -> set:
    """The faces found from every plan half-edge, each as its set of half-edges."""
    half_edges = [(e, u) for e in g.edges() if g.edge_type(e) in PLAN_EDGES for u in g.ends(e)]
    return {frozenset(walk(h)) for h in half_edges}


def test_face_from_is_the_face_walk_kept_by_the_face_index():
    # each plan half-edge's face is what face_walk walks from it, each face walked once;
    # Euler: V - E + F = 2 (connected plan); a diagonal across a patch is one face more, and only
    # the two faces it makes are walked; after the rollback the faces are the old ones again, and
    # only the patch's face is walked again
    dec = decompose(load_domain(EXAMPLES / "quad_with_hole.json"), 0.05)
    g = dec.graph
    index = face_index(g, PLAN_EDGES)
    plan_nodes = {u for e in g.edges() if g.edge_type(e) in PLAN_EDGES for u in g.ends(e)}
    plan_edges = [e for e in g.edges() if g.edge_type(e) in PLAN_EDGES]
    for e in plan_edges:
        for u in g.ends(e):
            assert face_from(g, PLAN_EDGES, (e, u)) == face_walk(g, PLAN_EDGES, (e, u))
    before, walks = _distinct_faces(g, lambda h: face_from(g, PLAN_EDGES, h)), index.walks
    assert len(plan_nodes) - len(plan_edges) + len(before) == 2
    assert faces(g, PLAN_EDGES, walk=face_from) == faces(g, PLAN_EDGES)  # the faces of the plan, in order
    assert index.walks == walks  # none walked again
    patch = dec.patches[0]
    mark = g.mark()
    d = g.add_edge(DIAGONAL, patch.corners[0], patch.corners[2])
    after = _distinct_faces(g, lambda h: face_from(g, PLAN_EDGES, h))
    assert after == _distinct_faces(g, lambda h: face_walk(g, PLAN_EDGES, h)) and len(after) == len(before) + 1
    assert index.walks == walks + 2 and len(after - before) == 2
    assert faces(g, PLAN_EDGES, walk=face_from) == faces(g, PLAN_EDGES) and index.walks == walks + 2
    assert face_from(g, PLAN_EDGES, (d, patch.corners[0])) == face_walk(g, PLAN_EDGES, (d, patch.corners[0]))
    g.rollback(mark)
    assert _distinct_faces(g, lambda h: face_from(g, PLAN_EDGES, h)) == before and index.walks == walks + 3


def test_kept_at_node_searches_again_only_when_a_face_it_read_or_the_node_changes():
    # kept_at_node (issue 13) gives its search's result while the faces it read are the same and
    # unchanged: not after a node of one of them moves or a plan edge is drawn at the node, again
    # equal to the search after a rollback
    dec = decompose(load_domain(EXAMPLES / "quad_with_hole.json"), 0.05)
    g = dec.graph
    patch = dec.patches[0]
    x = patch.corners[0]
    near = {u for e in g.rotation(x) if g.edge_type(e) in PLAN_EDGES for _, u in face_walk(g, PLAN_EDGES, (e, x))}
    far = next(p for p in dec.patches if not {u for side in p.side_edges for _, u in side} & near)
    searches = []

    def find(look):  # the outline areas of the faces at x, in rotation order
        searches.append(1)
        out = []
        for e in g.rotation(x):
            if g.edge_type(e) in PLAN_EDGES:
                look((e, x))
                out.append(round(face_outline(g, PLAN_EDGES, face_from(g, PLAN_EDGES, (e, x))).area, 9))
        return tuple(out)

    def kept():
        return kept_at_node(g, PLAN_EDGES, x, "areas", find)

    first = kept()
    mark = g.mark()
    assert kept() == first and len(searches) == 1
    g.add_edge(DIAGONAL, far.corners[0], far.corners[2])  # a patch away from x split
    assert kept() == first and len(searches) == 1
    u = next(u for u in sorted(near) if u != x and g.degree(u, PLAN_EDGES) == 2)
    (px, py) = g.get(u, "pos")
    g.set_node_attr(u, "pos", (px + 0.01, py))  # a node of a face at x moved
    moved = kept()
    assert len(searches) == 2 and moved == find(lambda h: None)  # searched again: what a search gives
    g.add_edge(DIAGONAL, patch.corners[0], patch.corners[2])  # a plan edge at x: one face more there
    assert len(kept()) == len(first) + 1 and len(searches) == 4
    g.rollback(mark)
    assert kept() == first and len(searches) == 5
