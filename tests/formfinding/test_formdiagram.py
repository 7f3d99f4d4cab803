"""The form diagram (§5): fully supported edges removed, corners dropped, opening faces added."""

from __future__ import annotations

import numpy as np
from formfinding.cases import assert_network_ok

from vaultgram.formfinding.formdiagram import (
    _bare_vertices,
    _boundary_sides,
    _Corners,
    _kept_edges,
    _lone_sides,
    form_diagram,
)
from vaultgram.geometry.halfedges import edges_of_sides, mesh_edges, sorted_sides
from vaultgram.geometry.meshes import corner_arrays, grid_index, grid_mesh, remove_faces
from vaultgram.pipeline import form_find


def test_grid_form_diagram_counts():
    v, f = grid_mesh(10)
    form = form_diagram(v, f)
    assert form.n_vertices == 121 - 4          # corners deleted
    assert form.n_edges == 220 - 40            # supported boundary edges removed
    assert form.n_faces == 100 and form.loaded.all()     # corner quads became triangles
    assert sum(len(fc) == 3 for fc in form.faces) == 4
    assert form.anchors.sum() == 40 - 4
    assert form.C.shape == (180, 117)
    assert np.allclose(form.C @ np.ones(117), 0)
    kept = form_diagram(v, f, update_boundaries=False)
    assert kept.n_vertices == 121 and kept.n_edges == 220 and kept.active.sum() == 180

def test_partially_supported_grid_has_run_openings():
    """Supports on two opposite sides: the two free sides are runs between supports (barrel vault)."""
    v, f = grid_mesh(10)
    sup = [grid_index(0, j, 10) for j in range(11)] + [grid_index(10, j, 10) for j in range(11)]
    form = form_diagram(v, f, supports=sup)
    assert (~form.loaded).sum() == 2
    for op in form.opening_faces:
        assert form.anchors[op[0]] and form.anchors[op[-1]] and not form.anchors[list(op[1:-1])].any()
    tn = form_find(v, f, supports=sup, zmax=3.0, sag=0.1)
    assert_network_ok(tn)


def _brute_edge_faces(form) -> dict:
    """``{(u, v): [left, right]}`` from the faces as tuples, one dict entry per side (a reference for
    the sorted-sides construction)."""
    out: dict = {}
    for k, face in enumerate(form.faces):
        sides = list(zip(face, face[1:] + face[:1]))
        if not form.loaded[k] and form.anchors[face[0]] and form.anchors[face[-1]] and len(face) > 2 \
                and (face[-1], face[0]) not in {(u, v) for u, v in sides[:-1]}:
            sides = sides[:-1]              # an open opening face: no side on its closing chord
        for a, b in sides:
            out.setdefault((min(a, b), max(a, b)), [-1, -1])[int(a > b)] = k
    return out


def test_edge_faces_match_the_faces_sides_with_holes_and_runs():
    """Every edge's left and right faces (loaded and opening) are the faces whose sides run u -> v
    and v -> u, on a grid with two holes supported on one side only (closed openings and runs)."""
    from vaultgram.geometry.meshes import remove_faces

    v, f, _ = remove_faces(*grid_mesh(9, 7), drop=[2 * 9 + 2, 4 * 9 + 6, 3 * 9 + 6])   # faces j * nx + i
    sup = [k for k in range(len(v)) if v[k, 1] == 0.0]
    form = form_diagram(v, f, supports=sup)
    ref = _brute_edge_faces(form)
    got = {tuple(e): list(lr) for e, lr in zip(form.edges.tolist(), form.edge_faces.tolist())}
    assert got == {e: lr for e, lr in ref.items() if e in got}
    assert len(got) == form.n_edges and (~form.loaded).sum() == 3   # two holes and one run
    assert (form.edge_faces[form.active] >= 0).all()
    # each hole's face has a side on every one of its edges, the run none on its closing chord
    sides = np.bincount(form.edge_faces[form.edge_faces >= form.loaded.sum()], minlength=form.n_faces)
    runs = [bool(form.anchors[o[0]] and form.anchors[o[-1]]) for o in form.opening_faces]
    assert sides[~form.loaded].tolist() == [len(o) - r for o, r in zip(form.opening_faces, runs)]
    assert sum(runs) == 1


def test_dropped_corner_that_turns_a_face_clockwise_is_named():
    """A supported vertex left without edges is dropped from its face; a face that then turns
    clockwise is named with its input index and both vertex lists."""
    import pytest

    from vaultgram.errors import FormFindingError

    v = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [1.0, 0.3], [0.0, 2.0], [1.0, 3.0]])
    f = [(0, 1, 2, 3), (3, 2, 5, 4), (0, 3, 4)]
    with pytest.raises(FormFindingError, match=r"face \d+ \[.*\] becomes \[.*\], which is not counter-clockwise"):
        form_diagram(v, f, supports=[0, 1, 2, 4, 5])


def _corners_of(faces):
    face, vert, nxt, _ = corner_arrays(faces)
    return _Corners(face, vert, nxt, np.bincount(face, minlength=len(faces)), np.arange(len(faces)))


def test_boundary_sides_from_the_sorted_sides_are_those_of_the_edges():
    """A grid with two holes: the sides alone on their edge, in corner order, as the edges' boundary."""
    v, f, _ = remove_faces(*grid_mesh(8), drop=[9, 10, 45])
    mesh = _corners_of(f)
    sides = sorted_sides(mesh.vert, mesh.nxt, len(v))
    edges = edges_of_sides(mesh.face, mesh.vert, mesh.nxt, mesh.lens, sides, len(v))
    lone, boundary = _lone_sides(mesh, sides), _boundary_sides(edges)
    assert all(np.array_equal(a, b) for a, b in zip(lone, boundary)) and len(lone[0]) == 32 + 6 + 4


def test_bare_vertices_are_those_that_keep_no_edge():
    """Against the edges' count of kept edges per vertex, for random supports (fully supported corners
    and inner vertices whose four neighbours are all supported)."""
    v, f = grid_mesh(6)
    mesh, edges = _corners_of(f), mesh_edges(f, len(v))
    for seed in range(20):
        anchors = np.random.default_rng(seed).random(len(v)) < 0.7
        for drop in (True, False):
            _, degree = _kept_edges(edges, anchors, drop)
            assert np.array_equal(_bare_vertices(mesh, anchors, drop), degree == 0)
