"""Even voussoir sizes (§5): the voussoirs the bond left too large get an edge back or are cut in two."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.geometry.surfaces import area_vectors
from vaultgram.pipeline import tessellate
from vaultgram.tessellation.sizes import (
    OVERSIZED,
    UPPER,
    _halving_edges,
    _side_area,
    split_large_quads,
    unmerge_large,
)
from vaultgram.tessellation.voussoirs import face_groups, voussoirs_at_vertices


def columns(xs, ny):
    """A planar grid with the vertical lines at ``xs`` and ``ny`` unit rows (face ``(i, j)`` is
    ``j * (len(xs) - 1) + i``)."""
    v, f = grid_mesh(len(xs) - 1, ny)
    v[:, 0] = np.asarray(xs, dtype=float)[v[:, 0].astype(int)]
    return v, f


def _edge(me, a, b):
    return int(np.flatnonzero((me.edges[:, 0] == min(a, b)) & (me.edges[:, 1] == max(a, b)))[0])


def _inner(me, n):
    inner = np.ones(n, dtype=bool)
    inner[me.edges[me.boundary].ravel()] = False
    return inner


def _areas(x, faces):
    return np.linalg.norm(area_vectors(x, faces), axis=1)


# ---------------------------------------------------------------------------------------------
# Unmerging
# ---------------------------------------------------------------------------------------------


def test_a_large_voussoir_gets_back_the_edge_that_halves_it():
    v, f = grid_mesh(4, 1)  # faces 0..3 in a row; vertex (i, j) is 5 j + i
    me = mesh_edges(f)
    removed = np.zeros(me.n_edges, dtype=bool)
    removed[[_edge(me, i, i + 5) for i in (1, 2, 3)]] = True
    left, restored = unmerge_large(me, removed, _inner(me, len(v)), np.ones(4), 1.0, len(v))
    assert restored == 1 and not left[_edge(me, 2, 7)]
    assert face_groups(me, left).tolist() == [0, 0, 1, 1]
    # by area, not by count: faces of areas 1 1 2 split 1 1 | 2
    left, _ = unmerge_large(me, removed, _inner(me, len(v)), np.array([1.0, 1.0, 2.0, 0.1]), 1.0, len(v))
    assert face_groups(me, left).tolist() == [0, 0, 1, 1]
    left, _ = unmerge_large(me, removed, _inner(me, len(v)), np.array([2.0, 1.0, 1.0, 0.1]), 1.0, len(v))
    assert face_groups(me, left).tolist() == [0, 1, 1, 1]


def test_voussoirs_within_the_upper_bound_are_left_alone():
    v, f = grid_mesh(2, 1)
    me = mesh_edges(f)
    removed = np.zeros(me.n_edges, dtype=bool)
    removed[_edge(me, 1, 4)] = True
    area = np.ones(2)
    assert unmerge_large(me, removed, _inner(me, len(v)), area, 2.0 / UPPER, len(v))[1] == 0
    assert unmerge_large(me, removed, _inner(me, len(v)), area, 0.99 * 2.0 / UPPER, len(v))[1] == 1


@pytest.mark.parametrize("top_joined, target, restored", [(False, 2.0, 0), (True, 2.0, 1), (False, 1.0, 1)])
def test_no_edge_comes_back_where_it_would_make_a_point_of_four(top_joined, target, restored):
    """A row of four joined under four faces: its middle edge ends at the inner vertex (2, 1), where the
    row and the two faces above it meet (three voussoirs); giving it back would make four, unless the
    two faces above are one voussoir, or the row is more than OVERSIZED times the target."""
    v, f = grid_mesh(4, 2)  # vertex (i, j) is 5 j + i
    me = mesh_edges(f)
    removed = np.zeros(me.n_edges, dtype=bool)
    removed[[_edge(me, i, i + 5) for i in (1, 2, 3)]] = True
    removed[_edge(me, 7, 12)] = top_joined  # faces 5 and 6, above the middle
    inner = _inner(me, len(v))
    before = voussoirs_at_vertices(me, face_groups(me, removed), len(v))
    left, n = unmerge_large(me, removed, inner, np.ones(8), target, len(v))
    assert n == restored
    after = voussoirs_at_vertices(me, face_groups(me, left), len(v))
    most = 4 if target * OVERSIZED < 4 else 3
    assert after[inner].max() <= max(most, before[inner].max())


def test_unmerging_a_bond_makes_points_of_four_only_at_oversized_voussoirs(arch_grid):
    t = tessellate(arch_grid, thickness=0.3)
    me, group = t.layout.edges, t.layout.group
    x = t.vertices
    removed = (me.faces_of >= 0).all(axis=1) & (group[me.faces_of[:, 0]] == group[me.faces_of[:, 1]])
    area = _areas(x, t.layout.mesh.faces)
    inner = _inner(me, len(x))
    size = np.bincount(group, weights=area)
    target = float(np.median(size)) / 2  # most voussoirs are now too large
    left, restored = unmerge_large(me, removed, inner, area, target, len(x))
    assert 0 < restored <= (size > UPPER * target).sum()
    back = removed & ~left
    changed = np.unique(group[me.faces_of[back, 0]])
    assert (size[changed] > UPPER * target).all()  # only the large ones, one edge each
    assert len(changed) == restored
    before = voussoirs_at_vertices(me, group, len(x))
    after = voussoirs_at_vertices(me, face_groups(me, left), len(x))
    oversized = back & (size[group[me.faces_of[:, 0]]] > OVERSIZED * target)
    new_fours = np.flatnonzero(inner & (after >= 4) & (before < 4))
    assert set(new_fours.tolist()) <= set(me.edges[oversized].ravel().tolist())


# ---------------------------------------------------------------------------------------------
# Cutting single quads
# ---------------------------------------------------------------------------------------------


def test_a_large_single_quad_is_cut_between_the_midpoints_of_its_long_sides():
    """The middle column is 3 wide: its lower quad (alone, area 3) is cut in two at x = 2.5; the upper
    one belongs to a voussoir of two faces and stays. The midpoint of the side between them becomes a
    corner of the upper face, a point of three voussoirs."""
    v, f = columns([0, 1, 4, 5], 2)  # faces 0 1 2 below, 3 4 5 above
    group = np.array([0, 1, 2, 3, 3, 4])
    x, faces, new_group, halved, cuts = split_large_quads(v, f, group, 1.0)
    assert cuts == 1 and len(faces) == len(f) + 1 and len(x) == len(v) + 2
    assert sorted(map(tuple, halved.tolist())) == [(1, 2), (5, 6)]
    assert np.allclose(x[len(v):], [v[list(p)].mean(axis=0) for p in halved])
    assert sorted(x[len(v):, :2].tolist()) == [[2.5, 0.0], [2.5, 1.0]]
    area = _areas(x, faces)
    assert len(faces[1]) == 4 and len(faces[-1]) == 4 and area[1] == pytest.approx(1.5) == area[-1]
    assert new_group[-1] == group.max() + 1 and new_group[1] == group[1]
    assert area.sum() == pytest.approx(_areas(v, f).sum())
    assert len(faces[4]) == 5  # the face above, with the midpoint in its lower side
    me = mesh_edges(faces, len(x))  # still a conforming, oriented mesh
    count = voussoirs_at_vertices(me, new_group, len(x))
    mid_inner = int(np.flatnonzero(np.isclose(x[:, 1], 1.0) & np.isclose(x[:, 0], 2.5))[0])
    mid_boundary = int(np.flatnonzero(np.isclose(x[:, 1], 0.0) & np.isclose(x[:, 0], 2.5))[0])
    assert count[mid_inner] == 3 and count[mid_boundary] == 2


def test_quads_within_the_bound_or_in_larger_voussoirs_are_not_cut():
    v, f = columns([0, 1, 4, 5], 1)
    x, faces, group, halved, cuts = split_large_quads(v, f, np.array([0, 1, 2]), 3.0 / UPPER)
    assert cuts == 0 and x is v and len(halved) == 0
    x, faces, group, halved, cuts = split_large_quads(v, f, np.array([0, 0, 1]), 1.0)
    assert cuts == 0


def test_every_large_single_quad_is_halved_once_sharing_midpoints_with_its_neighbours():
    """Two columns of three 3 x 1 quads, every face alone: six cuts, four midpoints per column (the
    quads of a column share their long sides), voussoirs no larger than half the largest quad."""
    v, f = columns([0, 1, 4, 5, 6, 9], 3)
    x, faces, new_group, halved, cuts = split_large_quads(v, f, np.arange(len(f)), 1.0)
    assert cuts == 6 and len(faces) == len(f) + 6 and len(x) == len(v) + 8 == len(v) + len(halved)
    size = np.bincount(new_group, weights=_areas(x, faces))
    assert len(size) == len(f) + 6 and size.max() == pytest.approx(1.5)
    mesh_edges(faces, len(x))  # conforming and oriented


@settings(max_examples=60, deadline=None)
@given(st.lists(st.booleans(), min_size=24, max_size=24), st.lists(st.integers(1, 30), min_size=16, max_size=16))
def test_the_halving_edge_of_every_voussoir_is_the_most_even_split_edge_by_edge(removed_bits, areas):
    """Subtree sums over each voussoir's tree of faces (and the walk for voussoirs with a cycle) pick
    the edge that a walk over each edge's two sides picks (whole areas: ties are exact)."""
    v, f = grid_mesh(4)
    me = mesh_edges(f, len(v))
    inner_edges = np.flatnonzero((me.faces_of >= 0).all(axis=1))
    removed = np.zeros(me.n_edges, dtype=bool)
    removed[inner_edges[np.array(removed_bits)]] = True
    area = np.array(areas, dtype=float)
    group = face_groups(me, removed)
    size = np.bincount(group, weights=area)
    large = np.bincount(group) > 1
    expected = []
    for k in np.flatnonzero(large).tolist():
        inside = np.flatnonzero(removed & (group[np.maximum(me.faces_of[:, 0], 0)] == k))
        gaps = {e: abs(size[k] - 2 * _side_area(me, inside, area, e)) for e in inside.tolist()}
        expected.append((k, min(gaps, key=lambda e: (gaps[e], e))))
    assert _halving_edges(me, removed, group, area, size, large) == expected


def test_a_voussoir_around_a_vertex_is_split_by_the_walk():
    """Four faces joined all round their common vertex close a cycle of removed edges: no edge of the
    cycle splits them, so the edge chosen leads to the fifth face."""
    v, f = grid_mesh(3, 2)  # faces 0 1 2 / 3 4 5; faces 0, 1, 3, 4 meet at vertex 5
    me = mesh_edges(f, len(v))
    removed = np.zeros(me.n_edges, dtype=bool)
    for a, b in ((1, 5), (4, 5), (5, 6), (5, 9), (2, 6)):  # the four around vertex 5, and 1-2
        removed[_edge(me, a, b)] = True
    group = face_groups(me, removed)
    area = np.ones(6)
    size = np.bincount(group, weights=area)
    (k, e), = _halving_edges(me, removed, group, area, size, np.bincount(group) > 1)
    assert sorted(me.faces_of[e].tolist()) == [1, 2]
