"""Smoothing the tessellation on the thrust surface (paper §5).

"Between form finding and fabrication, another step of uniform Laplacian smoothing can be done on the
spatial network this time, constrained to the form-found surface." (§5) Each iteration moves every
inner vertex of the voussoir outlines to the mean of its neighbours along the outlines, then back
onto the thrust surface (its closest point); vertices on the boundary of the surface stay.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from vaultgram.geometry.surfaces import project_to_surface

__all__ = ["smooth_on_surface", "fan_triangles"]


def fan_triangles(faces) -> np.ndarray:
    """Each face split into triangles fanning from its first vertex (the surface to project on)."""
    return np.array([(f[0], f[k], f[k + 1]) for f in faces for k in range(1, len(f) - 1)], dtype=np.int64)


def _outline_adjacency(loops, n: int) -> sp.csr_matrix:
    """Row-normalised adjacency of the outline edges (each joint counted once)."""
    pairs = {(min(p, q), max(p, q)) for loop in loops for p, q in zip(loop.tolist(), np.roll(loop, -1).tolist())}
    e = np.array(sorted(pairs), dtype=np.int64).reshape(-1, 2)
    a = sp.coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n)).tocsr()
    a = a + a.T
    deg = np.asarray(a.sum(axis=1)).ravel()
    return sp.diags(1.0 / np.maximum(deg, 1.0)) @ a


def smooth_on_surface(x: np.ndarray, loops, fixed: np.ndarray, surface_vertices: np.ndarray, surface_faces,
                      iterations: int) -> np.ndarray:
    """``iterations`` steps of Laplacian smoothing of the outline vertices ``x``, each projected back
    onto the surface; ``fixed`` vertices stay."""
    x = np.array(x, dtype=float)
    if iterations <= 0:
        return x
    w = _outline_adjacency(loops, len(x))
    tris = fan_triangles(surface_faces)
    free = ~fixed
    for _ in range(iterations):
        y = w @ x
        x[free] = project_to_surface(y[free], surface_vertices, tris)
    return x
