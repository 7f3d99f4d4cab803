"""Voussoirs: faces merged across the removed edges, their outlines, no strong concavities (§5), and
how many voussoirs meet at each vertex (their mending is test_mending.py)."""

import math
from collections import Counter

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.meshes import grid_mesh, remove_faces
from vaultgram.geometry.polygons import signed_area
from vaultgram.tessellation.voussoirs import (
    MAX_CONCAVITY,
    face_groups,
    max_corner_angles,
    outlines,
    voussoirs_at_vertices,
    without_concavities,
)


def _edge(me, a, b):
    """The edge between vertices ``a`` and ``b``."""
    return int(np.flatnonzero((me.edges[:, 0] == min(a, b)) & (me.edges[:, 1] == max(a, b)))[0])


def _removed(me, pairs):
    out = np.zeros(me.n_edges, dtype=bool)
    for a, b in pairs:
        out[_edge(me, a, b)] = True
    return out


def _inner(me, n):
    inner = np.ones(n, dtype=bool)
    inner[me.edges[me.boundary].ravel()] = False
    return inner


def _euler(loops) -> int:
    edges = {frozenset(p) for loop in loops for p in zip(loop.tolist(), np.roll(loop, -1).tolist())}
    vertices = {int(v) for loop in loops for v in loop}
    return len(vertices) - len(edges) + len(loops)


# ---------------------------------------------------------------------------------------------
# Groups and outlines
# ---------------------------------------------------------------------------------------------


def test_faces_joined_by_removed_edges_are_one_voussoir_numbered_by_its_smallest_face():
    v, f = grid_mesh(3, 1)  # faces 0 1 2 in a row; vertices 0..3 below, 4..7 above
    me = mesh_edges(f)
    assert face_groups(me, _removed(me, [(2, 6)])).tolist() == [0, 1, 1]
    assert face_groups(me, _removed(me, [(1, 5), (2, 6)])).tolist() == [0, 0, 0]
    assert face_groups(me, np.zeros(me.n_edges, dtype=bool)).tolist() == [0, 1, 2]
    # a removed boundary edge joins nothing
    assert face_groups(me, _removed(me, [(0, 1)])).tolist() == [0, 1, 2]


@st.composite
def grid_matchings(draw):
    """A 5 x 4 grid, maybe with an opening, and removed edges joining faces two by two or along rows
    (voussoirs that are disks)."""
    v, f = grid_mesh(5, 4)
    hole = draw(st.booleans())
    if hole:
        v, f, _ = remove_faces(v, f, [7])  # face (2, 1): an opening
    me = mesh_edges(f)
    inner = np.flatnonzero(~me.boundary)
    order = draw(st.permutations(inner.tolist()))
    bars = draw(st.booleans())  # rows of faces joined along x, or dominoes
    used = np.zeros(len(f), dtype=bool)
    removed = np.zeros(me.n_edges, dtype=bool)
    for e in order[: draw(st.integers(0, len(order)))]:
        a, b = me.faces_of[e]
        horizontal = v[me.edges[e, 0], 0] == v[me.edges[e, 1], 0]  # a vertical edge joins a row
        if bars and horizontal:
            removed[e] = True
        elif not bars and not (used[a] or used[b]):
            removed[e] = True
            used[[a, b]] = True
    return v, f, me, removed, hole


@settings(max_examples=40, deadline=None, derandomize=True)
@given(grid_matchings())
def test_outlines_are_counter_clockwise_loops_of_joints_and_boundary(case):
    v, f, me, removed, hole = case
    group = face_groups(me, removed)
    loops = outlines(me, group)
    assert len(loops) == group.max() + 1
    for k, loop in enumerate(loops):
        assert signed_area(v[loop, :2]) > 0  # counter-clockwise seen from above
        assert signed_area(v[loop, :2]) == pytest.approx((group == k).sum())  # unit faces
        assert len(set(loop.tolist())) == len(loop)
    # every outline side is a boundary edge or an edge between two voussoirs, and a joint is a side of
    # exactly its two voussoirs, run in opposite directions
    sides = Counter((int(p), int(q)) for loop in loops for p, q in zip(loop, np.roll(loop, -1)))
    for (p, q), n in sides.items():
        e = _edge(me, p, q)
        assert n == 1 and not removed[e]
        faces = me.faces_of[e]
        if (faces >= 0).all():
            assert group[faces[0]] != group[faces[1]] and sides[(q, p)] == 1
    joints = [e for e in range(me.n_edges) if (me.faces_of[e] >= 0).all() and len(set(group[me.faces_of[e]])) == 2]
    assert len(sides) == 2 * len(joints) + int(me.boundary.sum())
    assert _euler(loops) == 1 - int(hole)


def test_max_corner_angles_finds_the_reflex_corner_of_an_l():
    x = np.array([[0.0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0], [0, 0, 0.5], [1, 0, 0.5],
                  [1, 1, 0.5], [0, 1, 0.5]])
    angle, vertex = max_corner_angles(x, [np.array([0, 1, 2, 3, 4, 5]), np.array([6, 7, 8, 9])])
    assert angle == pytest.approx([270.0, 90.0])
    assert vertex[0] == 3 and vertex[1] in (6, 7, 8, 9)


# ---------------------------------------------------------------------------------------------
# Concavities
# ---------------------------------------------------------------------------------------------


def _bent_pair(bend_deg: float):
    """Two faces sharing the edge 1-4 whose merged outline bends by ``bend_deg`` along it: its corner at
    vertex 4 is ``180 + bend_deg`` (and at vertex 1 ``180 - bend_deg``)."""
    a = math.tan(math.radians(bend_deg))
    x = np.array([[0.0, 0, 0], [1, 0, 0], [2, a, 0], [0, 1, 0], [1, 1, 0], [2, 1 + a, 0]])
    faces = [(0, 1, 4, 3), (1, 2, 5, 4)]
    return x, faces, mesh_edges(faces)


@pytest.mark.parametrize("bend, max_angle, kept", [(20.0, MAX_CONCAVITY, True), (20.0, 210.0, False),
                                                   (5.0, MAX_CONCAVITY, False), (5.0, 180.0, True)])
def test_an_edge_is_kept_where_removing_it_makes_a_corner_above_the_threshold(bend, max_angle, kept):
    x, faces, me = _bent_pair(bend)
    removed = _removed(me, [(1, 4)])
    angle, vertex = max_corner_angles(x, outlines(me, face_groups(me, removed)))
    assert angle[0] == pytest.approx(180.0 + bend) and vertex[0] == 4
    left, restored = without_concavities(x, me, removed, max_angle)
    assert restored == int(kept) and left[_edge(me, 1, 4)] == (not kept)


def test_a_voussoir_with_a_concave_face_is_taken_apart():
    """The reflex corner (at vertex 6) is a corner of the second face itself: no removed edge meets it,
    so the voussoir becomes its faces again."""
    x = np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0], [1.6, 0.5, 0]])
    faces = [(0, 1, 4, 3), (1, 2, 6, 5, 4)]
    me = mesh_edges(faces)
    removed = _removed(me, [(1, 4)])
    left, restored = without_concavities(x, me, removed)
    assert restored == 1 and not left.any()


def test_without_concavities_only_touches_the_bad_voussoirs():
    """A row of three joined faces and an L of three: the row keeps its removed edges, the L loses the
    two edges at its reflex corner, and no voussoir has a corner above the threshold."""
    x, f = grid_mesh(3, 3)  # vertex (i, j) is 4 j + i, face (i, j) is 3 j + i
    me = mesh_edges(f)
    row = [(1, 5), (2, 6)]  # faces 0 1 2
    ell = [(8, 9), (9, 13)]  # faces 3 6 7, reflex at vertex 9 = (1, 2)
    removed = _removed(me, row + ell)
    assert sorted(np.bincount(face_groups(me, removed)).tolist()) == [1, 1, 1, 3, 3]
    assert max_corner_angles(x, outlines(me, face_groups(me, removed)))[0].max() == pytest.approx(270.0)
    left, restored = without_concavities(x, me, removed)
    assert left[[_edge(me, *p) for p in row]].all()
    assert restored == 2 and not left[[_edge(me, *p) for p in ell]].any()
    angle, _ = max_corner_angles(x, outlines(me, face_groups(me, left)))
    assert angle.max() <= MAX_CONCAVITY


# ---------------------------------------------------------------------------------------------
# Meeting points
# ---------------------------------------------------------------------------------------------


def test_voussoirs_at_vertices_counts_distinct_voussoirs():
    v, f = grid_mesh(2)  # the centre, vertex 4, is a corner of all four faces
    me = mesh_edges(f)
    count = voussoirs_at_vertices(me, face_groups(me, np.zeros(me.n_edges, dtype=bool)), len(v))
    assert count.tolist() == [1, 2, 1, 2, 4, 2, 1, 2, 1]
    count = voussoirs_at_vertices(me, face_groups(me, _removed(me, [(1, 4)])), len(v))
    assert count.tolist() == [1, 1, 1, 2, 3, 2, 1, 2, 1]


def test_an_element_that_no_other_follows_is_off_its_owners_loop():
    """Where an outline touches itself two elements have one successor and one element none: it (and
    the element it then precedes) never reach the start, the same on every call (its predecessor was
    left uninitialised before)."""
    from vaultgram.tessellation.voussoirs import _ranks_from_start

    successor = np.array([1, 2, 0, 4, 3, 4])  # owner 0: 0 -> 1 -> 2 -> 0; owner 1: 3 -> 4 -> 3 and 5 -> 4
    owner = np.array([0, 0, 0, 1, 1, 1])
    for _ in range(3):
        rank, on_loop = _ranks_from_start(successor, owner)
        assert rank[:4].tolist() == [0, 1, 2, 0] and on_loop.tolist() == [True] * 4 + [False] * 2
