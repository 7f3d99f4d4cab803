"""Constrained uniform Laplacian smoothing (paper §3.2, Figure 2h)."""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.meshes import grid_mesh
from vaultgram.meshing.quadmesh import SlideConstraint
from vaultgram.meshing.smoothing import laplacian_smooth


def test_smoothing_keeps_fixed_and_slides_on_boundary():
    v, f = grid_mesh(6)
    rng = np.random.default_rng(1)
    inner = (v[:, 0] > 0) & (v[:, 0] < 6) & (v[:, 1] > 0) & (v[:, 1] < 6)
    noisy = v.copy()
    noisy[inner, :2] += rng.uniform(-0.3, 0.3, (inner.sum(), 2))
    bottom = np.flatnonzero((v[:, 1] == 0) & (v[:, 0] > 0) & (v[:, 0] < 6))
    noisy[bottom, 0] += rng.uniform(-0.3, 0.3, len(bottom))
    corners = np.isin(np.arange(len(v)), [0, 6, 42, 48])
    fixed = corners | ((~inner) & ~np.isin(np.arange(len(v)), bottom))
    c = SlideConstraint(bottom, np.array([[0, 0], [6, 0.0]]))
    out = laplacian_smooth(noisy, f, 200, fixed, [c])
    assert np.array_equal(out[fixed], noisy[fixed])
    assert np.allclose(out[bottom, 1], 0)  # stayed on the boundary
    assert np.allclose(out[:, :2], v[:, :2], atol=1e-3)  # the grid is the fixed point
