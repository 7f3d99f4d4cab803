"""A symmetric plan's voussoirs do not follow round-off: ties between mirror edges go the same way on
every machine (:func:`vaultgram.geometry.arrays.steady` and :func:`~vaultgram.geometry.arrays.nearest`),
whose BLAS kernels differ in the last bits of the form finding (an 8 x 8 grid gave 29 voussoirs here and
28 on another machine, 26 to 29 under a relative noise of 1e-15)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vaultgram.geometry.arrays import nearest, steady
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.pipeline import form_find, tessellate
from vaultgram.tessellation.surface import surface_from_network


@pytest.fixture(scope="module")
def grid_surface():
    return surface_from_network(form_find(*grid_mesh(8), zmax=2.0))


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_round_off_leaves_the_voussoirs_of_a_symmetric_vault(grid_surface, seed):
    noise = 1 + 1e-15 * np.random.default_rng(seed).standard_normal(grid_surface.vertices.shape)
    noisy = dataclasses.replace(grid_surface, vertices=grid_surface.vertices * noise)
    a, b = tessellate(grid_surface, thickness=0.2), tessellate(noisy, thickness=0.2)
    assert [loop.tolist() for loop in a.layout.loops] == [loop.tolist() for loop in b.layout.loops]
    assert a.summary["meeting_points"] == b.summary["meeting_points"]


def test_nearest_gives_a_tie_to_the_lowest_index():
    points = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]])
    for eps in (1e-15, -1e-15, 0.0):
        assert nearest(points * (1 + eps * np.arange(4))[:, None], np.zeros((1, 2))).tolist() == [0]
    assert nearest(points, np.array([[0.0, -0.9]])).tolist() == [3]  # a real difference still counts


def test_steady_sums_are_exact():
    """Values on the power-of-two grid add without round-off: a comparison of sums is a tie or not,
    whatever the order of the sum."""
    a = steady(np.random.default_rng(0).random(1000))
    assert a.sum() == a[::-1].sum() == np.sort(a).sum()
    assert np.all(np.abs(a - steady(a * (1 + 1e-15))) == 0)
