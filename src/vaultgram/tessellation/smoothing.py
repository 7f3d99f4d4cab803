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

from vaultgram.geometry.meshes import adjacency, barycentre_operator, corner_arrays
from vaultgram.geometry.surfaces import project_to_surface
from vaultgram.tessellation.voussoirs import MAX_CONCAVITY, max_corner_angles

__all__ = ["smooth_on_surface", "fan_triangles"]


def fan_triangles(faces) -> np.ndarray:
    """Each face split into triangles fanning from its first vertex (the surface to project on).

    >>> fan_triangles([(0, 1, 2, 3), (3, 2, 4)]).tolist()
    [[0, 1, 2], [0, 2, 3], [3, 2, 4]]
    """
    face, u, v, _ = corner_arrays(faces)
    start = np.searchsorted(face, face)  # each corner's face's first corner
    side = np.arange(len(face)) - start
    size = np.bincount(face, minlength=len(faces))[face]
    inner = (side >= 1) & (side <= size - 2)
    return np.column_stack([u[start[inner]], u[inner], v[inner]]).astype(np.int64)


def smooth_on_surface(x: np.ndarray, faces, loops, fixed: np.ndarray, surface_vertices: np.ndarray,
                      surface_faces, iterations: int, max_angle: float = MAX_CONCAVITY) -> np.ndarray:
    """``iterations`` steps of Laplacian smoothing of the network ``faces`` at ``x``, each projected
    back onto the surface; ``fixed`` vertices stay, and no voussoir (``loops``) gets a corner above
    ``max_angle`` (nor a larger one than it had)."""
    x = np.array(x, dtype=float)
    if iterations <= 0:
        return x
    w, _ = barycentre_operator(adjacency(len(x), faces))
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
