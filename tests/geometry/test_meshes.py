"""The mesh kernel (vaultgram.geometry.meshes): grids, boundary loops, corner arrays, adjacency, errors."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.cli import main
from vaultgram.errors import VaultgramError
from vaultgram.geometry.arrays import pieces
from vaultgram.geometry.meshes import (
    Faces,
    MeshError,
    NonManifoldVertexError,
    adjacency,
    barycentre_operator,
    boundary_adjacency,
    boundary_loops,
    corner_angles,
    corner_arrays,
    corner_vectors,
    grid_index,
    grid_mesh,
    has_twin,
    remove_faces,
    twinned_sides,
)
from vaultgram.geometry.polygons import cross_z, signed_angles, signed_area

SETTINGS = settings(max_examples=30, deadline=None)


@SETTINGS
@given(st.integers(1, 12))
def test_boundary_of_a_grid_is_one_counter_clockwise_loop_of_4n_vertices(n):
    v, f = grid_mesh(n)
    (loop,) = boundary_loops(f)
    assert len(loop) == 4 * n == len(set(loop))
    assert signed_area(v[loop, :2]) == pytest.approx(n * n)
    inside = {grid_index(i, j, n) for i in range(1, n) for j in range(1, n)}
    assert not inside & set(loop)


@SETTINGS
@given(st.integers(3, 10), st.integers(3, 10), st.data())
def test_a_hole_punched_into_a_grid_is_a_second_clockwise_loop(nx, ny, data):
    i = data.draw(st.integers(1, nx - 2))
    j = data.draw(st.integers(1, ny - 2))
    v, f = grid_mesh(nx, ny)
    v2, f2, old = remove_faces(v, f, [j * nx + i])
    assert len(f2) == len(f) - 1 and len(v2) == len(v) and np.array_equal(v2, v[old])
    loops = sorted(boundary_loops(f2), key=len)
    assert [len(lp) for lp in loops] == [4, 2 * (nx + ny)]
    assert signed_area(v2[loops[0], :2]) == pytest.approx(-1.0)


@SETTINGS
@given(st.integers(1, 8), st.integers(1, 8))
def test_corner_arrays_adjacency_and_twins_of_a_grid(nx, ny):
    v, f = grid_mesh(nx, ny)
    face, u, nxt, prv = corner_arrays(f)
    assert len(u) == 4 * nx * ny and (np.bincount(face) == 4).all()
    e1, e2 = corner_vectors(v, u, nxt, prv)
    assert (cross_z(e1, e2) > 0).all()  # every corner of a counter-clockwise grid turns left
    a = adjacency(len(v), f)
    pairs = set(zip(a.rows.tolist(), a.cols.tolist()))
    assert pairs == {(j, i) for i, j in pairs} and a.nnz == len(pairs) == 2 * ((nx + 1) * ny + (ny + 1) * nx)
    assert np.array_equal(np.lexsort((a.cols, a.rows)), np.arange(a.nnz))  # sorted by row, then column
    b = boundary_adjacency(len(v), f)
    assert b.nnz == 2 * 2 * (nx + ny)
    assert (~has_twin(u, nxt)).sum() == 2 * (nx + ny)


def test_grid_sizes_below_one_are_mesh_errors():
    with pytest.raises(MeshError, match="at least one face"):
        grid_mesh(0, 3)
    assert issubclass(MeshError, VaultgramError) and issubclass(MeshError, ValueError)


def test_a_pinched_boundary_vertex_is_named():
    """Two squares sharing only vertex 2: it starts two boundary halfedges."""
    faces = [(0, 1, 2, 3), (2, 4, 5, 6)]
    with pytest.raises(NonManifoldVertexError, match="vertex 2 starts two boundary halfedges") as info:
        boundary_loops(faces)
    assert info.value.vertex == 2
    with pytest.raises(ValueError):  # what boundary_loops raised before: callers catching it still work
        boundary_loops(faces)


def test_a_pinched_mesh_is_one_error_line_on_the_command_line(tmp_path):
    """The supports of formfind walk the boundary loops: a pinched vertex is a user's mistake, reported
    in one line with exit code 2 (it was a ValueError traceback)."""
    path = tmp_path / "pinched.json"
    path.write_text(json.dumps({"vertices": [[0, 0], [1, 0], [1, 1], [0, 1], [2, 1], [2, 2], [1, 2]],
                                "faces": [[0, 1, 2, 3], [2, 4, 5, 6]]}))
    result = CliRunner().invoke(main, ["formfind", str(path), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2 and "vertex 2 starts two boundary halfedges" in result.output
    assert "Traceback" not in result.output


def test_empty_meshes():
    assert boundary_loops([]) == []
    assert all(len(a) == 0 for a in corner_arrays([]))
    assert adjacency(3, []).nnz == 0


@settings(max_examples=60, deadline=None)
@given(st.lists(st.integers(0, 6), max_size=30), st.integers(0, 10 ** 6))
def test_faces_from_flat_arrays_are_the_faces_cut_face_by_face(sizes, seed):
    """Faces.from_flat makes each run of equal-sized faces in one pass; the tuples are the slices of
    the flat vertex array, sizes 0 to 6 mixed in any order."""
    from vaultgram.geometry.meshes import Faces

    lens = np.array(sizes, dtype=np.int64)
    vert = np.random.default_rng(seed).integers(0, 50, int(lens.sum()))
    ends = np.cumsum(lens)
    expected = tuple(tuple(vert[e - k:e].tolist()) for e, k in zip(ends, lens))
    faces = Faces.from_flat(vert, lens)
    assert faces == expected and all(type(v) is int for f in faces for v in f)


@SETTINGS
@given(st.integers(0, 50), st.integers(1, 8))
def test_pieces_cover_the_range_once_in_order(n, size):
    parts = pieces(n, size)
    assert np.array_equal(np.concatenate([np.arange(n)[part] for part in parts] or [[]]), np.arange(n))
    assert all(len(np.arange(n)[part]) == size for part in parts[:-1])


def test_corner_angles_are_the_signed_angles_of_the_corner_vectors():
    """Computed in pieces (a 130 x 130 grid has 67600 corners), jittered so that some corners fold."""
    v, f = grid_mesh(130)
    v[:, :2] += np.random.default_rng(3).uniform(-0.4, 0.4, (len(v), 2))
    _, u, nxt, prv = corner_arrays(f)
    expected = signed_angles(*corner_vectors(v, u, nxt, prv))
    assert np.array_equal(corner_angles(v, u, nxt, prv), expected) and (expected < 0).any()


@SETTINGS
@given(st.lists(st.tuples(st.integers(0, 6), st.integers(0, 6)), max_size=30))
def test_has_twin_finds_every_reversed_halfedge(halfedges):
    """Against a set of the halfedges, with repeats and loops (a loop is its own twin)."""
    u = np.array([a for a, _ in halfedges], dtype=np.int64)
    v = np.array([b for _, b in halfedges], dtype=np.int64)
    present = set(halfedges)
    assert has_twin(u, v).tolist() == [(b, a) in present for a, b in halfedges]
    assert has_twin(u, v, 11).tolist() == has_twin(u, v).tolist()


def test_faces_keep_which_sides_have_a_twin():
    v, f, _ = remove_faces(*grid_mesh(4), drop=[5])
    faces = Faces(f)
    _, u, nxt, _ = corner_arrays(faces)
    assert twinned_sides(faces) is twinned_sides(faces)
    assert np.array_equal(twinned_sides(faces), has_twin(u, nxt)) and np.array_equal(twinned_sides(f), has_twin(u, nxt))
    assert int((~twinned_sides(faces)).sum()) == 16 + 4  # the outer boundary and the hole's


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 12), st.integers(1, 12), st.integers(0, 2**32 - 1), st.sampled_from([1, 2, 3]),
       st.booleans())
def test_the_mean_operator_is_scipys_sparse_product(nx, ny, seed, columns, large):
    """``barycentre_operator``: the means of scipy's ``D^-1 A`` CSR product to round-off (the order of
    the sums differs), on a grid with some faces dropped (vertices of degree 0 to 4), the plain and
    the boundary adjacency, one to three columns; below ``SCIPY_FROM`` vertices by numpy, from it
    (``large``: the bound lowered to 0) by its own CSR matrix."""
    import scipy.sparse as sp

    import vaultgram.geometry.meshes as meshes

    rng = np.random.default_rng(seed)
    v, f = grid_mesh(nx, ny)
    f = [face for face in f if rng.random() > 0.2]
    x = rng.normal(size=(len(v), columns)) * 10.0 ** rng.integers(-3, 4)
    for a in (adjacency(len(v), f), boundary_adjacency(len(v), f)):
        m = sp.coo_matrix((np.ones(a.nnz), (a.rows, a.cols)), shape=(len(v), len(v))).tocsr()
        bound, meshes.SCIPY_FROM = meshes.SCIPY_FROM, 0 if large else meshes.SCIPY_FROM
        try:
            w, deg = barycentre_operator(a)
        finally:
            meshes.SCIPY_FROM = bound
        assert (w.matrix is not None) == large
        assert np.array_equal(deg, np.asarray(m.sum(axis=1)).ravel())
        reference = (sp.diags(1.0 / np.maximum(deg, 1)) @ m) @ x
        assert np.allclose(w @ x, reference, rtol=1e-14, atol=1e-14 * np.abs(x).max())
        assert np.array_equal(w @ x[:, 0], (w @ x)[:, 0])
