"""Discrete Coons patches (paper §3.2, Figure 3): bilinear interpolation, exact boundaries, the
triangle pattern fanning around its pole."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.meshing.coons import coons_grid, grid_faces, grid_worst_corner
from vaultgram.meshing.quality import face_scaled_jacobians


def _lin(a, b, n):
    return np.linspace(a, b, n + 1)


def test_coons_reproduces_bilinear_patch():
    c0, c1, c2, c3 = map(np.array, ([0.0, 0.0], [4.0, 0.5], [5.0, 3.0], [-0.5, 2.0]))
    m, n = 5, 3
    grid = coons_grid(_lin(c0, c1, m), _lin(c1, c2, n), _lin(c3, c2, m), _lin(c0, c3, n))
    u = np.linspace(0, 1, m + 1)[:, None, None]
    v = np.linspace(0, 1, n + 1)[None, :, None]
    bilinear = (1 - u) * (1 - v) * c0 + u * (1 - v) * c1 + u * v * c2 + (1 - u) * v * c3
    assert np.allclose(grid, bilinear)


def test_coons_keeps_curved_boundaries_exactly():
    t = np.linspace(0, np.pi, 9)
    bottom = np.column_stack([t, 0.3 * np.sin(t)])
    top = bottom + [0, 2.0]
    left = _lin(bottom[0], top[0], 4)
    right = _lin(bottom[-1], top[-1], 4)
    grid = coons_grid(bottom, right, top, left)
    assert np.array_equal(grid[:, 0], bottom) and np.array_equal(grid[:, -1], top)
    assert np.array_equal(grid[0], left) and np.array_equal(grid[-1], right)
    with pytest.raises(ValueError):
        coons_grid(bottom, right, top[:-1], left)


def test_triangle_pattern_fans_around_pole():
    ids = np.arange(4 * 3).reshape(4, 3)
    ids[0, :] = 0  # column 0 collapsed to the pole
    quads, tris = grid_faces(ids, pole=True)
    assert len(quads) == 2 * 2 and len(tris) == 2  # 3 x 2 cells, the first column triangles
    assert (tris[:, 0] == 0).all() and not np.isin(0, quads)


def test_grid_worst_corner_is_the_worst_face_of_the_grids_quads():
    """grid_worst_corner (the structured form weld judges a patch's grid by) agrees with the mesh
    quality's face_scaled_jacobians on jittered grids, folded cells included, and is -1 on a cell
    with a side of no length."""
    rng = np.random.default_rng(7)
    folded = 0
    for _ in range(100):
        m, n = rng.integers(2, 7, size=2)
        grid = np.stack(np.meshgrid(np.arange(m + 1.0), np.arange(n + 1.0), indexing="ij"), -1)
        grid += 0.35 * rng.normal(size=grid.shape)
        quads, _ = grid_faces(np.arange((m + 1) * (n + 1)).reshape(m + 1, n + 1))
        expected = face_scaled_jacobians(grid.reshape(-1, 2), quads).min()
        assert grid_worst_corner(grid) == pytest.approx(expected, abs=1e-12)
        folded += expected <= 0
    assert folded > 0  # the draws include inverted cells
    flat = np.array([[[0.0, 0.0], [0.0, 1.0]], [[0.0, 0.0], [1.0, 1.0]]])
    assert grid_worst_corner(flat) == -1.0
