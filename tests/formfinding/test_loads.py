"""Loads: self-weight from 3D tributary areas, and point loads."""

from __future__ import annotations

import numpy as np
import pytest
from formfinding.cases import assert_network_ok

from vaultgram.formfinding.loads import TributaryAreas, tributary_areas
from vaultgram.geometry.meshes import grid_index, grid_mesh
from vaultgram.pipeline import form_find


def test_tributary_areas_sum_to_face_areas():
    rng = np.random.default_rng(3)
    v, f = grid_mesh(5)
    xyz = v.copy()
    xyz[:, 2] = rng.uniform(0, 2, len(v))
    a = tributary_areas(xyz, f)
    total = 0.0
    for face in f:
        p = xyz[list(face)]
        c = p.mean(axis=0)
        for i in range(len(face)):
            total += 0.5 * np.linalg.norm(np.cross(p[i] - c, p[(i + 1) % len(face)] - c))
    assert a.sum() == pytest.approx(total, rel=1e-12)

def test_areas_over_a_fixed_plan_are_the_3d_areas():
    """The heights-only areas of vertical equilibrium agree with the 3D areas at every height field,
    on quads and triangles (a grid with one face split), and are the plan areas at z = 0."""
    rng = np.random.default_rng(5)
    v, f = grid_mesh(6)
    f = [(f[0][0], f[0][1], f[0][2]), (f[0][0], f[0][2], f[0][3]), *f[1:]]
    areas = TributaryAreas.from_faces(f, len(v))
    over = areas.over_plan(v[:, :2])
    for _ in range(3):
        xyz = v.copy()
        xyz[:, 2] = rng.uniform(-1, 3, len(v))
        assert np.allclose(over(xyz[:, 2]), areas(xyz), rtol=1e-13, atol=1e-15)
    assert over(np.zeros(len(v))).sum() == pytest.approx(36.0, rel=1e-13)


def test_grid_form_find_with_point_loads():
    v, f = grid_mesh(10)
    centre = grid_index(5, 5, 10)
    tn = form_find(v, f, zmax=3.0, point_loads={centre: 10.0})
    assert_network_ok(tn)
    plain = form_find(v, f, zmax=3.0)
    selfweight = tributary_areas(tn.vertices, tn.faces).sum()
    assert tn.summary["total_load"] == pytest.approx(selfweight + 10.0, rel=1e-12)   # point load counted
    assert tn.summary["scale"] > plain.summary["scale"]      # more load, more thrust for the same rise
    k = int(np.flatnonzero(tn.vertex_ids == centre)[0])
    assert tn.loads[k] > plain.loads[k] + 9.99
