"""Laplacian smoothing of the tessellation on the thrust surface (§5): vertices stay on the surface, the
boundary stays, the network gets more regular, no voussoir gets a corner above the concavity
threshold."""

import numpy as np
import pytest

from vaultgram.geometry.meshes import grid_mesh
from vaultgram.geometry.surfaces import area_vectors, project_to_surface
from vaultgram.pipeline import tessellate
from vaultgram.tessellation.smoothing import fan_triangles, smooth_on_surface
from vaultgram.tessellation.solids import solid_volumes


def _distance_to(surface, points):
    return np.linalg.norm(project_to_surface(points, surface.vertices, fan_triangles(surface.faces)) - points, axis=1)


def _laplacian_residual(x, faces, free) -> float:
    """Mean distance of the free vertices from the mean of their neighbours along the faces' edges."""
    nbrs = [set() for _ in range(len(x))]
    for face in faces:
        for p, q in zip(list(face), list(face[1:]) + [face[0]]):
            nbrs[p].add(q)
            nbrs[q].add(p)
    return float(np.mean([np.linalg.norm(x[list(nbrs[v])].mean(axis=0) - x[v]) for v in np.flatnonzero(free)]))


def test_fan_triangles_cover_each_face():
    x = np.array([[0.0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 2, 0], [0, 1, 0]])
    faces = [(0, 1, 2, 3, 4), (0, 1, 2)]
    tris = fan_triangles(faces)
    assert tris.tolist() == [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 1, 2]]
    a = np.linalg.norm(area_vectors(x, tris.tolist()), axis=1)
    assert a[:3].sum() == pytest.approx(np.linalg.norm(area_vectors(x, faces[:1])))


def test_no_iterations_change_nothing():
    v, f = grid_mesh(2)
    loops = [np.array(q) for q in f]
    out = smooth_on_surface(v, f, loops, np.zeros(len(v), dtype=bool), v, f, 0)
    assert np.array_equal(out, v) and out is not v


def test_a_vertex_moves_to_the_mean_of_its_distinct_neighbours():
    """Vertex 1 of two squares side by side has neighbours 0, 2 and 4 (the edge 1-4 is a side of both
    faces but counts once); on a flat surface one step puts it at their mean."""
    v, f = grid_mesh(2, 1)  # vertices 0 1 2 below, 3 4 5 above
    x = v.copy()
    x[1] = [1.3, 0.4, 0.0]
    fixed = np.ones(len(v), dtype=bool)
    fixed[1] = False
    out = smooth_on_surface(x, f, [np.array(q) for q in f], fixed, v, f, 1)
    assert np.allclose(out[1], (v[0] + v[2] + v[4]) / 3)
    assert np.array_equal(out[fixed], x[fixed])


def test_a_point_off_the_surface_is_put_back_on_it():
    v, f = grid_mesh(4)
    x = v.copy()
    x[12, 2] = 0.7  # the centre, lifted
    fixed = np.ones(len(v), dtype=bool)
    fixed[12] = False
    out = smooth_on_surface(x, f, [np.array(q) for q in f], fixed, v, f, 1)
    assert out[12].tolist() == pytest.approx([2.0, 2.0, 0.0])


@pytest.fixture(scope="module")
def smoothed(arch_grid):
    return {n: tessellate(arch_grid, thickness=0.3, surface_smooth=n) for n in (0, 5)}


def test_smoothed_vertices_stay_on_the_thrust_surface(arch_grid, smoothed):
    t = smoothed[5]
    size = np.ptp(arch_grid.vertices, axis=0).max()
    assert _distance_to(arch_grid, t.vertices).max() < 1e-9 * size
    assert not np.allclose(t.vertices, smoothed[0].vertices)


def test_the_boundary_and_the_supports_stay(arch_grid, smoothed):
    t0, t5 = smoothed[0], smoothed[5]
    me = t5.layout.edges
    fixed = np.zeros(len(t5.vertices), dtype=bool)
    fixed[me.edges[me.boundary].ravel()] = True
    fixed[: len(arch_grid.supported)] |= arch_grid.supported
    assert np.array_equal(t5.vertices[fixed], t0.vertices[fixed])
    moved = np.linalg.norm(t5.vertices - t0.vertices, axis=1) > 1e-9
    assert moved.any() and not moved[fixed].any()


def test_smoothing_makes_the_network_more_regular(arch_grid, smoothed):
    t0, t5 = smoothed[0], smoothed[5]
    free = np.linalg.norm(t5.vertices - t0.vertices, axis=1) > 1e-9
    before = _laplacian_residual(t0.vertices, t0.layout.mesh.faces, free)
    after = _laplacian_residual(t5.vertices, t5.layout.mesh.faces, free)
    assert after < 0.95 * before  # (on a curved surface the residual keeps its part along the normal)
    # the topology, and so the bond, is the same; the solids are still valid
    assert t5.summary["meeting_points"] == t0.summary["meeting_points"]
    assert t5.summary["euler_characteristic"] == t0.summary["euler_characteristic"]
    assert (solid_volumes(t5.solids, t5.layout.n_voussoirs) > 0).all()
    assert t5.summary["joint_tilt_deg"]["p95"] <= 3.5


def test_smoothing_undoes_a_perturbation_along_the_surface(dome_grid):
    t = tessellate(dome_grid, thickness=0.3)
    me = t.layout.edges
    fixed = np.zeros(len(t.vertices), dtype=bool)
    fixed[me.edges[me.boundary].ravel()] = True
    fixed[: len(dome_grid.supported)] |= dome_grid.supported
    rng = np.random.default_rng(1)
    jitter = t.vertices + np.where(fixed[:, None], 0.0, rng.uniform(-0.2, 0.2, t.vertices.shape))
    tris = fan_triangles(dome_grid.faces)
    jitter = np.where(fixed[:, None], jitter, project_to_surface(jitter, dome_grid.vertices, tris))
    faces = t.layout.mesh.faces
    out = smooth_on_surface(jitter, faces, t.layout.loops, fixed, dome_grid.vertices, dome_grid.faces, 10,
                            max_angle=359.0)  # the jitter itself may fold voussoirs: smoothing, unguarded
    assert _laplacian_residual(out, faces, ~fixed) < 0.5 * _laplacian_residual(jitter, faces, ~fixed)
    assert _distance_to(dome_grid, out).max() < 1e-9 * np.ptp(dome_grid.vertices, axis=0).max()
    assert np.array_equal(out[fixed], t.vertices[fixed])


def test_no_step_makes_a_voussoir_concave():
    """An L of three unit squares, one voussoir, on a flat surface, its inner corner (vertex 4) pushed
    out to (1.2, 1.2): a corner of about 256 degrees. Smoothing pulls it back to (1, 1), 270 degrees;
    with the threshold at 260 that step is undone, without the guard (359) it is made."""
    v, f = grid_mesh(2)
    faces = [f[0], f[1], f[2]]  # three of the four squares: vertex 4 is the L's inner corner
    loop = np.array([0, 1, 2, 5, 4, 7, 6, 3])  # the L's outline, counter-clockwise
    x = v.copy()
    x[4, :2] = [1.2, 1.2]
    fixed = np.ones(len(v), dtype=bool)
    fixed[4] = False
    guarded = smooth_on_surface(x, faces, [loop], fixed, v, f, 3, max_angle=260.0)
    free = smooth_on_surface(x, faces, [loop], fixed, v, f, 3, max_angle=359.0)
    assert np.array_equal(guarded, x) and free[4].tolist() == pytest.approx([1.0, 1.0, 0.0])
