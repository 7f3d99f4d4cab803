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
