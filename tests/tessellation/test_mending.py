"""Mending the points where four voussoirs meet (§5): a face moved across a joint lowers the crowding,
never raises it, keeps the voussoirs disks within the size limit and the concavity threshold, and
leaves keystones and boundary points alone."""

import numpy as np
import pytest

from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.tessellation.mending import GROWTH, join_small_pairs, mend_meeting_points
from vaultgram.tessellation.voussoirs import (
    MAX_CONCAVITY,
    face_groups,
    max_corner_angles,
    outlines,
    voussoirs_at_vertices,
)


def _grid(n: int):
    """An n x n grid of unit squares, its edges and its inner vertices."""
    v, f = grid_mesh(n)
    me = mesh_edges(f, len(v))
    inner = np.ones(len(v), dtype=bool)
    inner[me.edges[me.boundary].ravel()] = False
    return v, me, inner


def _crowding(me, removed, inner, n) -> int:
    count = voussoirs_at_vertices(me, face_groups(me, removed), n)
    return int(np.maximum(count[inner] - 3, 0).sum())


def test_a_point_of_four_single_faces_becomes_a_point_of_three():
    v, me, inner = _grid(2)
    removed, moves = mend_meeting_points(v, me, np.zeros(me.n_edges, dtype=bool), inner, np.ones(4), target=1.0)
    assert moves == 1 and removed.sum() == 1 and 4 in me.edges[removed].ravel()
    assert voussoirs_at_vertices(me, face_groups(me, removed), len(v))[4] == 3


@pytest.mark.parametrize("target, max_angle, inner", [(0.6, MAX_CONCAVITY, True), (1.0, 170.0, True),
                                                      (1.0, MAX_CONCAVITY, False)])
def test_no_move_beyond_the_size_the_angle_or_the_boundary(target, max_angle, inner):
    """Two unit squares joined have area 2 (above GROWTH x 0.6) and straight corners of 180 degrees;
    a point on the boundary is not mended (and unit faces are not small at target 1)."""
    v, me, interior = _grid(2)
    interior = interior if inner else np.zeros(len(v), dtype=bool)
    removed, moves = mend_meeting_points(v, me, np.zeros(me.n_edges, dtype=bool), interior, np.ones(4), target,
                                         max_angle)
    assert moves == 0 and not removed.any()


def _bond(me, n: int) -> np.ndarray:
    """Rows of dominoes on an n x n grid, each row in step with the one below: straight joints, so
    every inner vertex on a vertical joint is a point of four."""
    removed = np.zeros(me.n_edges, dtype=bool)
    for row in range(n):
        for col in range(0, n - 1, 2):
            a = row * (n + 1) + col + 1
            e = np.flatnonzero((me.edges[:, 0] == a) & (me.edges[:, 1] == a + n + 1))
            removed[e] = True
    return removed


def test_mending_a_stack_bond_lowers_the_crowding_and_keeps_every_promise():
    n = 6
    v, me, inner = _grid(n)
    start = _bond(me, n)
    area = np.ones(n * n)
    frozen = np.zeros(n * n, dtype=bool)
    frozen[[0, 1]] = True  # the first domino is a keystone
    removed, moves = mend_meeting_points(v, me, start, inner, area, target=2.0, frozen_faces=frozen)
    assert moves > 0
    assert _crowding(me, removed, inner, len(v)) < _crowding(me, start, inner, len(v))
    group = face_groups(me, removed)
    assert np.bincount(group, weights=area).max() <= GROWTH * 2.0
    assert group[0] == group[1] and (group == group[0]).sum() == 2  # the keystone is untouched
    loops = outlines(me, group)
    assert len(loops) == len(np.unique(group))  # every voussoir one disk: one outline loop each
    angle, _ = max_corner_angles(v, loops)
    assert (angle <= MAX_CONCAVITY + 1e-9).all()


def test_mending_never_makes_a_point_more_crowded():
    """Call after call, until nothing is left to mend, the total crowding only falls."""
    n = 8
    v, me, inner = _grid(n)
    removed = _bond(me, n)
    before = _crowding(me, removed, inner, len(v))
    while True:
        removed, moves = mend_meeting_points(v, me, removed, inner, np.ones(n * n), target=2.0)
        after = _crowding(me, removed, inner, len(v))
        assert after <= before
        if moves == 0:
            break
        before = after


def test_a_small_voussoir_takes_faces_from_its_larger_neighbour_until_they_are_even():
    """A row of six quads on the boundary (no inner vertex: nothing to mend): voussoir A of two faces of
    area 0.2 beside voussoir B of four of area 1, target 2. A is small (below SMALL x target) and
    takes B's faces one by one while that brings the sizes closer: 0.4 | 4 -> 1.4 | 3 -> 2.4 | 2."""
    v, f = grid_mesh(6, 1)
    me = mesh_edges(f, len(v))
    area = np.array([0.2, 0.2, 1.0, 1.0, 1.0, 1.0])
    removed = (me.faces_of >= 0).all(axis=1)
    removed[np.flatnonzero((me.edges[:, 0] == 2) & (me.edges[:, 1] == 9))] = False  # the joint A | B
    assert np.bincount(face_groups(me, removed), weights=area).tolist() == [0.4, 4.0]
    out, moves = mend_meeting_points(v, me, removed, np.zeros(len(v), dtype=bool), area, target=2.0)
    group = face_groups(me, out)
    assert moves == 2 and group.tolist() == [0, 0, 0, 0, 1, 1]
    assert np.bincount(group, weights=area).tolist() == pytest.approx([2.4, 2.0])


def _joint(me, a, b):
    return np.flatnonzero((me.edges[:, 0] == min(a, b)) & (me.edges[:, 1] == max(a, b)))


@pytest.mark.parametrize("target, joins", [(2.0, 1), (1.2, 0)])
def test_two_small_neighbours_become_one_within_the_size_limit(target, joins):
    """Two unit squares side by side, each below the target: one voussoir of area 2, unless that is
    above UPPER (1.5) times the target."""
    v, f = grid_mesh(2, 1)
    me = mesh_edges(f, len(v))
    out, n = join_small_pairs(v, me, np.zeros(me.n_edges, dtype=bool), np.ones(2), target)
    assert n == joins and out.sum() == joins and out[_joint(me, 1, 4)].all() == bool(joins)


def test_an_l_shaped_union_is_not_made_below_its_reflex_corner():
    """Voussoir A (faces 0 and 1, a row) and B (face 2, above face 0) would make an L with a corner of
    270 degrees at vertex 4: refused at the threshold of 190, made at 275."""
    v, me, _ = _grid(2)
    removed = np.zeros(me.n_edges, dtype=bool)
    removed[_joint(me, 1, 4)] = True
    area = np.ones(4)
    frozen = np.array([False, False, False, True])  # face 3 stays out of it
    for max_angle, joins in [(190.0, 0), (275.0, 1)]:
        out, n = join_small_pairs(v, me, removed, area, 2.1, max_angle, frozen)
        assert n == joins
        assert face_groups(me, out).tolist() == ([0, 0, 1, 2] if joins == 0 else [0, 0, 0, 1])


def test_joining_pairs_never_crowds_a_vertex_and_leaves_keystones_alone():
    n = 6
    v, me, inner = _grid(n)
    none = np.zeros(me.n_edges, dtype=bool)
    frozen = np.zeros(n * n, dtype=bool)
    frozen[7] = True
    out, joins = join_small_pairs(v, me, none, np.ones(n * n), 2.0, frozen_faces=frozen)
    before = voussoirs_at_vertices(me, face_groups(me, none), len(v))
    group = face_groups(me, out)
    after = voussoirs_at_vertices(me, group, len(v))
    assert joins > 0 and (after <= before).all()
    assert (group == group[7]).sum() == 1  # the keystone is still on its own
    assert np.bincount(group).max() == 2  # pairs of unit squares: each at most 1.5 x 2 = 3
