"""How good the corners round a vertex can be at all, whatever smoothing does: the fan bound.

A pole of a three-sided patch (§3.2, Figure 3) gets one triangle per subdivision of the side opposite
it, so a pole with many triangles has narrow corners however its neighbours are placed: its faces
share the pole's angle in the mesh (360 degrees inside, the domain's corner angle on the boundary).
A corner of angle ``a`` has the scaled Jacobian ``sin(a)`` in a quad and ``min(1, sin(a) 2 / sqrt(3))``
in a triangle (:func:`vaultgram.meshing.quality.face_scaled_jacobians`), so reaching ``s`` at every
corner of the vertex needs ``a >= asin(s)`` per quad corner and ``a >= asin(s sqrt(3) / 2)`` per
triangle corner, and these must fit in the vertex's angle. :func:`fan_bounds` is the largest such
``s``: an upper bound no placement of the other vertices can beat; only fewer faces at the vertex
(another pattern, or a finer split of its angle) can.
"""

from __future__ import annotations

import math

import numpy as np

from vaultgram.geometry.meshes import corner_arrays, corner_vectors
from vaultgram.geometry.polygons import signed_angles

__all__ = ["fan_bounds"]

_BISECTIONS = 50


def fan_bounds(vertices: np.ndarray, faces) -> np.ndarray:
    """Per vertex, the largest scaled Jacobian all its corners could reach together, given its
    number of triangle and quad corners and its angle in the mesh (the sum of its corners' angles);
    1 where that is no limit, ``inf`` at vertices without faces.

    Example
    -------
    A vertex with 24 triangles round it (15 degrees each) can reach ``sin(15) 2 / sqrt(3)``:

    >>> ring = np.column_stack([np.cos(np.arange(24) * np.pi / 12), np.sin(np.arange(24) * np.pi / 12)])
    >>> v = np.vstack([[0.0, 0.0], ring])
    >>> f = [(0, 1 + k, 1 + (k + 1) % 24) for k in range(24)]
    >>> round(float(fan_bounds(v, f)[0]), 4), round(math.sin(math.pi / 12) * 2 / math.sqrt(3), 4)
    (0.2989, 0.2989)
    """
    x = np.asarray(vertices, dtype=float)[:, :2]
    face_of, u, v, p = corner_arrays(faces)
    n = len(x)
    e1, e2 = corner_vectors(x, u, v, p)
    angle = signed_angles(e1, e2)
    theta = np.bincount(u, weights=np.where(angle < 0, angle + 2 * math.pi, angle), minlength=n)
    tri = (np.bincount(face_of, minlength=len(faces)) == 3)[face_of]
    n_tri = np.bincount(u, weights=tri, minlength=n)
    n_quad = np.bincount(u, weights=~tri, minlength=n)
    lo, hi = np.zeros(n), np.ones(n)
    for _ in range(_BISECTIONS):
        s = 0.5 * (lo + hi)
        need = n_tri * np.arcsin(np.minimum(1.0, s * math.sqrt(3.0) / 2)) + n_quad * np.arcsin(s)
        fits = need <= theta
        lo, hi = np.where(fits, s, lo), np.where(fits, hi, s)
    return np.where(n_tri + n_quad > 0, lo, np.inf)
