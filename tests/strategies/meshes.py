"""Random planar meshes for the property tests of form finding and of the mesh kernel.

* ``perturbed_grids()`` -- ``(vertices, faces)`` of an n x n grid of unit quads (n from 2 to 7,
  :func:`vaultgram.geometry.meshes.grid_mesh`) whose interior vertices are moved at random by up to
  ``amp`` (0 to 0.3) in x and y: the boundary stays the square that supports the vault, while the
  faces become irregular quads (at the largest amplitudes even non-convex ones), so that horizontal
  equilibrium has real work to do, or has to fail with a clear error.
"""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from vaultgram.geometry.meshes import grid_mesh


@st.composite
def perturbed_grids(draw):
    """An n x n unit grid with its interior vertices perturbed: ``(vertices (m, 3), faces)``, z = 0."""
    n = draw(st.integers(2, 7))
    amp = draw(st.floats(0.0, 0.3))
    seed = draw(st.integers(0, 2**31 - 1))
    v, f = grid_mesh(n)
    rng = np.random.default_rng(seed)
    inner = (v[:, 0] > 0) & (v[:, 0] < n) & (v[:, 1] > 0) & (v[:, 1] < n)
    v[inner, :2] += rng.uniform(-amp, amp, (int(inner.sum()), 2))
    return v, f
