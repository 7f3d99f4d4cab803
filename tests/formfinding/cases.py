"""Meshes and checks shared by the form-finding tests (``from formfinding.cases import ...``)."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.geometry.meshes import boundary_loops, grid_mesh, remove_faces


def holed_grid(n=20, lo=7, hi=13):
    """An n x n grid with the central block of faces [lo, hi) x [lo, hi) removed; outer loop supported."""
    v, f = grid_mesh(n)
    drop = [j * n + i for i in range(lo, hi) for j in range(lo, hi)]
    v2, f2, _ = remove_faces(v, f, drop)
    outer = max(boundary_loops(f2), key=len)
    return v2, f2, outer

def assert_network_ok(tn, tol_deg=0.5):
    s = tn.summary
    assert s["max_angle_deg"] < tol_deg
    assert np.all(tn.q > 0), "compression only"
    assert s["vertical_residual"] < 1e-8 * s["total_load"]
    assert s["reaction_sum"] == pytest.approx(s["total_load"], rel=1e-9)
    assert np.all(np.isfinite(tn.vertices))


def notched_grid(n=10, depth=0.5):
    """An n x n grid on the unit square whose left side is a notch: its middle vertex pushed ``depth``
    inwards, the side two straight lines (a reflex corner of 270 deg at depth 0.5), the columns
    squeezed to fit. Outer loop supported. Equal force densities fold it next to the corner."""
    v, f = grid_mesh(n)
    x, y = v[:, 0] / n, v[:, 1] / n
    x0 = depth * (1 - 2 * np.abs(y - 0.5))
    v[:, 0], v[:, 1] = x0 + (1 - x0) * x, y
    return v, f, max(boundary_loops(f), key=len)
