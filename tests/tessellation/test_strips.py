"""Strips of quads (tessellation.strips): every edge between two quads is a rung of exactly one strip."""

from collections import Counter

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.meshes import grid_mesh, remove_faces
from vaultgram.tessellation.strips import quad_strips, strip_directions, strip_labels


def _sides(faces):
    return [(f[k], f[(k + 1) % len(f)]) for f in faces for k in range(len(f))]


def _inner_rungs(strips):
    """How often each edge joins two consecutive quads of a strip."""
    return Counter(int(r) for s in strips for r in (s.rungs[:-1] if s.cyclic else s.rungs[1:-1]))


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 6), st.integers(1, 6), st.data())
def test_grid_strips_are_its_rows_and_columns(nx, ny, data):
    _, faces = grid_mesh(nx, ny)
    drop = data.draw(st.sets(st.integers(0, nx * ny - 1), max_size=max(nx * ny // 3, 0)))
    if len(drop) == nx * ny:
        return
    v, faces, _ = remove_faces(*grid_mesh(nx, ny), drop)
    me = mesh_edges(faces)
    strips = quad_strips(me, faces)
    # every quad lies on two strips, once in each direction
    assert Counter(int(q) for s in strips for q in s.quads) == Counter({q: 2 for q in range(len(faces))})
    # consecutive quads of a strip share the rung between them; ends are boundary edges
    for s in strips:
        for i in range(1, len(s)):
            assert set(me.faces_of[s.rungs[i]]) == {s.quads[i - 1], s.quads[i]}
        if not s.cyclic:
            assert me.boundary[s.rungs[0]] and me.boundary[s.rungs[-1]]
    inner = np.flatnonzero(~me.boundary)
    assert _inner_rungs(strips) == Counter(inner.tolist())  # each inner edge joins two quads of one strip


def test_a_ring_of_quads_is_one_cyclic_strip():
    n = 8
    faces = [(i, n + i, n + (i + 1) % n, (i + 1) % n) for i in range(n)]
    strips = quad_strips(mesh_edges(faces), faces)
    cyclic = [s for s in strips if s.cyclic]
    assert len(cyclic) == 1 and sorted(cyclic[0].quads.tolist()) == list(range(n))
    assert cyclic[0].rungs[0] == cyclic[0].rungs[-1]
    assert sorted(len(s) for s in strips) == [1] * n + [n]


def test_strips_end_at_faces_that_are_not_quads():
    faces = [(0, 1, 4, 3), (1, 2, 5, 4), (2, 6, 5)]
    strips = quad_strips(mesh_edges(faces), faces)
    assert max(len(s) for s in strips) == 2 and all(2 not in s.quads for s in strips)


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 6), st.integers(1, 6), st.data())
def test_strip_labels_are_the_strips_as_sets(nx, ny, data):
    """Two strip nodes share a label exactly when they lie on the same strip of :func:`quad_strips`
    (grids with holes and a triangle: nodes of faces that are not quads have none)."""
    drop = data.draw(st.sets(st.integers(0, nx * ny - 1), max_size=max(nx * ny // 3, 0)))
    if len(drop) == nx * ny:
        return
    v, faces, _ = remove_faces(*grid_mesh(nx, ny), drop)
    lo, hi = mesh_edges(faces).edges[0]  # the smallest vertex and its right neighbour: a boundary edge
    faces = faces + [(hi, lo, len(v)) if (lo, hi) in set(_sides(faces)) else (lo, hi, len(v))]  # a triangle there
    me = mesh_edges(faces)
    strip = np.full(2 * len(faces), -1)
    for k, s in enumerate(quad_strips(me, faces)):
        strip[2 * s.quads + strip_directions(me, s)] = k
    label = strip_labels(me)
    assert ((label >= 0) == (strip >= 0)).all() and (label[-2:] == -1).all()
    pairs = set(zip(label.tolist(), strip.tolist()))
    assert len(pairs) == len({a for a, _ in pairs}) == len({b for _, b in pairs})  # one to one
