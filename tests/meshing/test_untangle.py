"""Untangling the faces smoothing leaves folded."""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.meshes import corner_arrays, grid_mesh
from vaultgram.meshing.quadmesh import SlideConstraint
from vaultgram.meshing.untangle import untangle


def _min_scaled_jacobian(x, faces):
    _, u, v, p = corner_arrays(faces)
    e1, e2 = x[v, :2] - x[u, :2], x[p, :2] - x[u, :2]
    return float(((e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]) / (np.hypot(*e1.T) * np.hypot(*e2.T))).min())


def test_untangle_repairs_folded_faces_and_leaves_good_meshes_alone():
    """Two interior vertices of a 6 x 6 grid dragged across their neighbours (four inverted faces, a
    fold Laplacian smoothing keeps next to a concave boundary): untangle brings every corner back to
    a positive scaled Jacobian, moves no fixed vertex, keeps the sliding ones on their line, and
    returns a mesh that is already good unchanged."""
    v, f = grid_mesh(6)
    on_boundary = (v[:, 0] % 6 == 0) | (v[:, 1] % 6 == 0)
    bottom = np.flatnonzero((v[:, 1] == 0) & (v[:, 0] > 0) & (v[:, 0] < 6))
    fixed = on_boundary & ~np.isin(np.arange(len(v)), bottom)
    slide = SlideConstraint(bottom, np.array([[0, 0], [6, 0.0]]))
    folded = v.copy()
    folded[8, :2] = [2.6, 1.9]   # vertex (1, 1) pushed past (2, 2)
    folded[9, :2] = [2.4, 0.7]   # vertex (2, 1) pushed past (3, 1)
    assert _min_scaled_jacobian(folded, f) < 0
    out = untangle(folded, f, fixed, [slide])
    assert _min_scaled_jacobian(out, f) > 0
    assert np.array_equal(out[fixed], folded[fixed])
    assert np.allclose(out[bottom, 1], 0)
    assert np.array_equal(untangle(v, f, fixed, [slide]), v)
