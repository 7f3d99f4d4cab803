"""Thrust surfaces for the tessellation tests: form-found grids and meshed examples."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.geometry.meshes import grid_mesh, remove_faces
from vaultgram.pipeline import form_find
from vaultgram.tessellation.surface import surface_from_network


def grid_vault(n: int, free_side: bool = False, hole: bool = False):
    """An ``n`` x ``n`` grid form-found to a rise of ``n / 4``: supported all round, or on three
    sides (the fourth an arch), maybe with a square opening in the middle."""
    v, f = grid_mesh(n)
    if hole:
        mid = n // 2
        drop = [j * n + i for j in range(mid - 1, mid + 1) for i in range(mid - 1, mid + 1)]
        v, f, _ = remove_faces(v, f, drop)
    supports = None
    if free_side:
        supports = np.flatnonzero((v[:, 0] == 0) | (v[:, 0] == n) | (v[:, 1] == 0))
    return surface_from_network(form_find(v, f, supports, zmax=n / 4.0, relax_mode="all" if free_side else "boundary"))


@pytest.fixture(scope="session")
def arch_grid():
    """A 12 x 12 vault with one free edge (an arch) along y = 12."""
    return grid_vault(12, free_side=True)


@pytest.fixture(scope="session")
def dome_grid():
    """A 10 x 10 vault supported all round."""
    return grid_vault(10)
