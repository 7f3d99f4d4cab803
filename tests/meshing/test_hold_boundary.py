"""Putting the boundary back on the plan after smoothing (vaultgram.meshing.fidelity, issue 12 What 5):
a sliding vertex moves onto a bend its chord cut off, never at the cost of the mesh's worst face, and
onto a ring vertex that must be a mesh vertex, the one of the nearest that fits it best."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.geometry.meshes import grid_mesh
from vaultgram.geometry.polylines import chord_deviation, project_to_polyline
from vaultgram.meshing.fidelity import _balance, _faces_around, _gaps, _snap_bend, hold_boundary, place_on_points
from vaultgram.meshing.quadmesh import SlideConstraint
from vaultgram.meshing.quality import face_scaled_jacobians

N = 6  # a 6 x 6 grid of unit squares; its bottom row slides on a bent polyline


def _bent_bottom(depth: float) -> np.ndarray:
    """The bottom side, from (0, 0) to (6, 0), with a bend of ``depth`` down at every x + 0.5."""
    xs = np.arange(0.0, N + 0.01, 0.5)
    return np.column_stack([xs, np.where(np.arange(len(xs)) % 2 == 1, -depth, 0.0)])


def _grid_on(poly: np.ndarray, shift: np.ndarray):
    """The grid with its inner bottom vertices moved by ``shift`` along x and projected onto ``poly``."""
    x, faces = grid_mesh(N)
    x = x[:, :2].copy()
    bottom = np.arange(1, N)
    x[bottom, 0] += shift
    x[bottom] = project_to_polyline(x[bottom], poly)
    return x, faces, SlideConstraint(bottom, poly)


def _chain(x, c):
    return np.vstack([c.polyline[:1], x[c.vertices], c.polyline[-1:]])


BEND = np.array([[0.0, 0.0], [3.0, -0.3], [6.0, 0.0]])
SLID = np.r_[0.0, 0.0, 0.4, 0.0, 0.0]  # vertex 3, at x = 3 over the bend, slid to x = 3.4
ABOVE = N + 1 + 3  # the vertex above it


def test_a_vertex_that_slid_off_a_bend_goes_back_onto_it():
    x, faces, c = _grid_on(BEND, SLID)
    assert chord_deviation(BEND, _chain(x, c)) > 0.05
    y = hold_boundary(x, faces, [c], tol=0.01)
    assert chord_deviation(BEND, _chain(y, c)) == 0.0
    assert y[3].tolist() == [3.0, -0.3]
    assert np.array_equal(np.delete(y, 3, axis=0), np.delete(x, 3, axis=0))  # one vertex moved
    assert face_scaled_jacobians(y, faces).min() > face_scaled_jacobians(x, faces).min()


def test_within_the_tolerance_nothing_moves():
    x, faces, c = _grid_on(BEND, SLID)
    assert np.array_equal(hold_boundary(x, faces, [c], tol=0.1), x)


def test_a_move_that_would_skew_a_face_below_the_worst_is_not_made():
    """With the vertex above leaning right, vertex 3 back on the bend would skew its faces below the
    mesh's worst; its left neighbour slides towards the bend instead, as far as the faces allow."""
    x, faces, c = _grid_on(BEND, SLID)
    x[ABOVE] = [3.5, 0.6]
    before = face_scaled_jacobians(x, faces).min()
    onto = x.copy()
    onto[3] = BEND[1]
    assert face_scaled_jacobians(onto, faces).min() < before
    y = hold_boundary(x, faces, [c], tol=0.01)
    assert y[3].tolist() == x[3].tolist()
    assert face_scaled_jacobians(y, faces).min() >= before
    assert chord_deviation(BEND, _chain(y, c)) < chord_deviation(BEND, _chain(x, c))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-0.45, 0.45), min_size=N - 1, max_size=N - 1), st.floats(0.02, 0.3))
def test_holding_never_lowers_the_worst_face_nor_lets_the_boundary_stray_farther(shift, depth):
    poly = _bent_bottom(depth)
    x, faces, c = _grid_on(poly, np.asarray(shift))
    tol = 0.01
    y = hold_boundary(x, faces, [c], tol)
    assert face_scaled_jacobians(y, faces).min() >= face_scaled_jacobians(x, faces).min() - 1e-12
    assert chord_deviation(poly, _chain(y, c)) <= max(tol, chord_deviation(poly, _chain(x, c))) + 1e-12
    assert np.allclose(project_to_polyline(y[c.vertices], poly), y[c.vertices])  # still on the boundary
    moved = np.flatnonzero(np.any(y != x, axis=1))
    assert set(moved.tolist()) <= set(c.vertices.tolist())


def test_a_ring_vertex_left_bare_gets_the_vertex_that_fits_it_best():
    x, faces, c = _grid_on(BEND, SLID)  # vertex 3 slid off the bend (3, -0.3) to x = 3.4
    y, on = place_on_points(x, faces, [c], BEND[1:2], 1e-9)
    assert y[3].tolist() == [3.0, -0.3] and np.flatnonzero(on).tolist() == [3]
    assert np.array_equal(np.delete(y, 3, axis=0), np.delete(x, 3, axis=0))


def test_of_the_two_nearest_the_one_whose_faces_stay_better_goes():
    """Vertex 3 slid to x = 3.4; vertex 2 is the nearer to the bend at x = 3 once it slides to 2.8,
    but its faces would be squeezed against vertex 3's: vertex 3 goes back."""
    x, faces, c = _grid_on(BEND, np.r_[0.0, 0.8, 0.4, 0.0, 0.0])
    assert np.hypot(*(x[2] - BEND[1])) < np.hypot(*(x[3] - BEND[1]))
    y, on = place_on_points(x, faces, [c], BEND[1:2], 1e-9)
    assert y[3].tolist() == [3.0, -0.3] and y[2].tolist() == x[2].tolist()


def test_a_point_every_candidate_folds_a_face_to_reach_gets_one_only_with_folding():
    """Two quads over a bent bottom side whose vertex 1 slid off the bend (1, -0.3); the interior
    vertex 4 at (1.4, -0.1) is so low that vertex 1 on the bend folds the right quad. Without
    ``folding`` the point stays bare; with it the vertex goes there, for the pipeline to optimise the
    faces and keep it only if they unfold (meshpipeline._held_to_the_plan)."""
    faces = [(0, 1, 4, 5), (1, 2, 3, 4)]
    x = np.array([[0.0, 0.0], [1.4, -0.18], [3.0, 0.0], [3.0, 1.0], [1.4, -0.1], [0.0, 1.0]])
    bottom = SlideConstraint(np.array([1]), np.array([[0.0, 0.0], [1.0, -0.3], [3.0, 0.0]]))
    assert face_scaled_jacobians(x, faces).min() > 0.7
    y, on = place_on_points(x, faces, [bottom], np.array([[1.0, -0.3]]), 1e-9)
    assert np.array_equal(y, x) and not on.any()
    y, on = place_on_points(x, faces, [bottom], np.array([[1.0, -0.3]]), 1e-9, folding=True)
    assert y[1].tolist() == [1.0, -0.3] and np.flatnonzero(on).tolist() == [1]
    assert face_scaled_jacobians(y, faces)[1] < 0 < face_scaled_jacobians(y, faces)[0]


def test_a_point_a_vertex_sits_on_moves_nothing():
    x, faces, c = _grid_on(BEND, np.zeros(N - 1))
    x[3] = BEND[1]
    y, on = place_on_points(x, faces, [c], BEND[1:2], 1e-9)
    assert np.array_equal(y, x) and np.flatnonzero(on).tolist() == [3]


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-0.45, 0.45), min_size=N - 1, max_size=N - 1), st.floats(0.02, 0.3))
def test_every_bend_left_bare_gets_a_vertex_without_folding_a_face(shift, depth):
    poly = _bent_bottom(depth)
    x, faces, c = _grid_on(poly, np.asarray(shift))
    bends = poly[1:-1:2]  # the bends at x + 0.5, each between two vertices' starting places
    y, on = place_on_points(x, faces, [c], bends, 1e-9)
    assert face_scaled_jacobians(y, faces).min() > 0 or face_scaled_jacobians(x, faces).min() <= 0
    assert np.allclose(project_to_polyline(y[c.vertices], poly), y[c.vertices])
    hit = [np.any(np.all(y[c.vertices] == b, axis=1)) for b in bends]
    assert on[c.vertices].sum() == sum(hit)


TWIN = np.array([[-3.0, -3.0], [-1.0, -3.3], [3.0, -3.0], [3.0, 3.0], [1.0, 3.3], [-3.0, 3.0]])  # p -> -p


def _twin_grid():
    """A 6 x 6 grid about the origin whose boundary slides on the closed polyline :data:`TWIN`, a square
    with a bend on its bottom side and the same bend turned by 180 degrees on its top; the vertices at
    x = -1 and x = 1 over the bends slid away by 0.4, point-symmetrically too: the two bends are the
    stretch's farthest points, tied to the last bit (-p is exact, so are the distances)."""
    x, faces = grid_mesh(N, origin=(-3.0, -3.0))
    x = x[:, :2].copy()
    ring = np.r_[0:N + 1, (N + 1) * np.arange(2, N + 2) - 1, (N + 1) * N + np.arange(N - 1, -1, -1),
                 (N + 1) * np.arange(N - 1, 0, -1)]  # counter-clockwise from (-3, -3)
    bottom, top = ring[:N + 1], ring[2 * N:3 * N + 1]
    x[bottom[2], 0] += 0.4
    x[bottom] = project_to_polyline(x[bottom], TWIN[:3])
    x[top] = -x[bottom]
    return x, faces, SlideConstraint(ring, TWIN, closed=True)


def test_tied_farthest_points_are_snapped_one_after_the_other():
    """Neither snap alone brings the stretch's farthest point nearer (its mirror image stays as far):
    the first is taken because it brings the points it changes nearer while the maximum stays, then
    the second (before, neither was, and the boundary stayed 0.06 off the bends)."""
    x, faces, c = _twin_grid()
    gaps = _gaps(x, c)
    assert gaps[1] == gaps[4] == gaps.max() > 0.05
    y = hold_boundary(x, faces, [c], tol=0.01)
    assert y[2].tolist() == [-1.0, -3.3] and y[N * (N + 1) + 4].tolist() == [1.0, 3.3]
    assert _gaps(y, c).max() == 0.0
    assert face_scaled_jacobians(y, faces).min() >= face_scaled_jacobians(x, faces).min()


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-0.45, 0.45), min_size=N - 1, max_size=N - 1), st.floats(0.02, 0.3))
def test_a_snap_updates_the_gaps_it_changes_and_only_those(shift, depth):
    """The gaps kept up to date snap by snap (:func:`_snap_bend` measures only the points near the
    moved vertex) are the gaps measured afresh over the whole stretch."""
    poly = _bent_bottom(depth)
    x, faces, c = _grid_on(poly, np.asarray(shift))
    gaps = _gaps(x, c)
    floor = face_scaled_jacobians(x, faces).min()
    if _snap_bend(x, faces, _faces_around(faces, len(x)), c, int(np.argmax(gaps)), gaps, floor):
        assert np.allclose(gaps, _gaps(x, c), rtol=0, atol=1e-12)
    else:
        assert np.array_equal(gaps, _gaps(x, c))


def _grid_on_arc(radius: float, points: int, shift=None):
    """The grid with its bottom row on a circular arc from (0, 0) to (6, 0) bulging down, drawn as a
    polyline of ``points`` points: vertices sliding on its chords sit inside the circle."""
    t = np.linspace(-1, 1, points) * np.arcsin(3 / radius)
    arc = np.column_stack([3 + radius * np.sin(t), radius * np.cos(t[0]) - radius * np.cos(t)])
    return _grid_on(arc, np.zeros(N - 1) if shift is None else np.asarray(shift))


def test_chords_all_near_the_tolerance_are_balanced_along_the_arc():
    """An arc of radius 6 drawn with 9 points, its five vertices evenly spaced: with a tolerance 10%
    under the farthest gap, the sweeps spread the vertices along the arc until every point is within
    it (the stadium's half circles: four points 0.25% beyond, no single snap bringing them nearer),
    keeping the gaps up to date, the vertices on the arc and the worst face."""
    x, faces, c = _grid_on_arc(6.0, 9)
    gaps = _gaps(x, c)
    tol, floor = 0.9 * gaps.max(), face_scaled_jacobians(x, faces).min()
    y = x.copy()
    _balance(y, faces, _faces_around(faces, len(x)), c, gaps, tol, floor)
    assert gaps.max() <= tol and np.allclose(gaps, _gaps(y, c), rtol=0, atol=1e-12)
    assert np.allclose(project_to_polyline(y[c.vertices], c.polyline), y[c.vertices])
    assert face_scaled_jacobians(y, faces).min() >= floor


@settings(max_examples=30, deadline=None)
@given(st.floats(3.5, 20.0), st.integers(4, 16), st.lists(st.floats(-0.3, 0.3), min_size=N - 1, max_size=N - 1),
       st.floats(0.5, 1.0))
def test_balancing_never_lets_the_boundary_stray_farther_nor_lowers_the_worst_face(radius, points, shift, share):
    x, faces, c = _grid_on_arc(radius, points, shift)
    gaps = _gaps(x, c)
    before, floor = gaps.max(), face_scaled_jacobians(x, faces).min()
    y = x.copy()
    _balance(y, faces, _faces_around(faces, len(x)), c, gaps, share * before, floor)
    assert gaps.max() <= before + 1e-12 and np.allclose(gaps, _gaps(y, c), rtol=0, atol=1e-12)
    assert face_scaled_jacobians(y, faces).min() >= min(floor, face_scaled_jacobians(x, faces).min()) - 1e-12
    assert np.allclose(project_to_polyline(y[c.vertices], c.polyline), y[c.vertices])
