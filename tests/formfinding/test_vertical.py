"""Vertical equilibrium (TNA step 2): heights, thrust scale and reactions."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.formfinding.formdiagram import form_diagram
from vaultgram.formfinding.vertical import vertical
from vaultgram.geometry.meshes import grid_mesh


def test_vertical_reactions_and_thickness():
    v, f = grid_mesh(6)
    form = form_diagram(v, f)
    q = np.ones(form.n_edges)
    thin = vertical(form, q, thickness=0.5, zmax=2.0)
    thick = vertical(form, q, thickness=1.0, zmax=2.0)
    assert thick.scale == pytest.approx(2 * thin.scale, rel=1e-9)     # same shape, twice the thrust
    assert np.allclose(thick.z, thin.z, atol=1e-9)
    assert thick.reactions[:, 2].sum() == pytest.approx(thick.total_load, rel=1e-12)
    assert np.all(thick.reactions[:, 2] > 0)
    # horizontal reactions of a symmetric vault cancel
    assert np.abs(thick.reactions[:, :2].sum(axis=0)).max() < 1e-9


def test_accelerated_loads_reach_the_plain_fixed_point():
    """Self-weight heights with Anderson-mixed loads equal those of the plain fixed-point iteration
    (heights -> 3D tributary areas -> heights, written out here with scipy's sparse solver) to 1e-10
    relative, in fewer solves, and the loads of the result balance its heights."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import spsolve

    from vaultgram.formfinding.loads import tributary_areas

    form = form_diagram(*grid_mesh(8))
    q = np.ones(form.n_edges)
    res = vertical(form, q, scale=3.0)            # a rise of 1.66 on a span of 8
    K = (form.C.T @ sp.diags(3.0 * q) @ form.C).tocsc()[form.free][:, form.free]
    xyz = np.column_stack([form.xy, np.zeros(form.n_vertices)])
    for plain in range(1, 100):
        z = spsolve(K, tributary_areas(xyz, form.loaded_faces)[form.free])
        change = np.abs(z - xyz[form.free, 2]).max()
        xyz[form.free, 2] = z
        if change < 1e-14 * np.abs(z).max():
            break
    assert np.abs(res.z - xyz[:, 2]).max() < 1e-10 * np.abs(xyz[:, 2]).max()
    assert res.iterations < plain
    p = tributary_areas(res.xyz, form.loaded_faces)
    assert np.abs((K @ res.z[form.free]) - p[form.free]).max() < 1e-10 * p.sum()
