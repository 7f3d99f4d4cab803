"""Smoothing the tessellation on the thrust surface (paper §5).

"Between form finding and fabrication, another step of uniform Laplacian smoothing can be done on the
spatial network this time, constrained to the form-found surface." (§5) Each iteration moves every
free vertex of the network (the faces' edges, joints and the edges inside voussoirs alike) to the
mean of its neighbours, then back onto the thrust surface (its closest point); vertices on the
boundary of the surface and on supports stay. A step must not give a voussoir a corner above the
concavity threshold (or, for one that had such a corner, a larger one): the vertices of every
voussoir that a step makes too concave go back, until none is.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from vaultgram.geometry.surfaces import project_to_surface
from vaultgram.tessellation.voussoirs import MAX_CONCAVITY, max_corner_angles

__all__ = ["smooth_on_surface", "fan_triangles"]


def fan_triangles(faces) -> np.ndarray:
    """Each face split into triangles fanning from its first vertex (the surface to project on)."""
    return np.array([(f[0], f[k], f[k + 1]) for f in faces for k in range(1, len(f) - 1)], dtype=np.int64)


def _edge_adjacency(faces, n: int) -> sp.csr_matrix:
    """Row-normalised adjacency of the faces' edges (each edge counted once)."""
    pairs = {(min(p, q), max(p, q)) for f in faces for p, q in zip(f, list(f[1:]) + [f[0]])}
    e = np.array(sorted(pairs), dtype=np.int64).reshape(-1, 2)
    a = sp.coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n)).tocsr()
    a = a + a.T
    deg = np.asarray(a.sum(axis=1)).ravel()
    return sp.diags(1.0 / np.maximum(deg, 1.0)) @ a


def smooth_on_surface(x: np.ndarray, faces, loops, fixed: np.ndarray, surface_vertices: np.ndarray,
                      surface_faces, iterations: int, max_angle: float = MAX_CONCAVITY) -> np.ndarray:
    """``iterations`` steps of Laplacian smoothing of the network ``faces`` at ``x``, each projected
    back onto the surface; ``fixed`` vertices stay, and no voussoir (``loops``) gets a corner above
    ``max_angle`` (nor a larger one than it had)."""
    x = np.array(x, dtype=float)
    if iterations <= 0:
        return x
    w = _edge_adjacency(faces, len(x))
    tris = fan_triangles(surface_faces)
    free = ~fixed
    allowed = np.maximum(max_corner_angles(x, list(loops))[0], max_angle) + 1e-9
    for _ in range(iterations):
        y = x.copy()
        y[free] = project_to_surface((w @ x)[free], surface_vertices, tris)
        x = _within_concavity(x, y, list(loops), allowed)
    return x


def _within_concavity(old: np.ndarray, new: np.ndarray, loops: list, allowed: np.ndarray) -> np.ndarray:
    """``new`` with the vertices of every voussoir whose largest corner exceeds ``allowed`` put back
    to ``old``, until none does (at worst all of them: ``old`` itself)."""
    while True:
        bad = np.flatnonzero(max_corner_angles(new, loops)[0] > allowed)
        if not len(bad):
            return new
        back = np.concatenate([loops[k] for k in bad])
        new[back] = old[back]
