"""The structure a plan mesh must have before any stage uses it, checked once with a message naming
the face, edge or vertex: faces of distinct vertices, each edge used at most once in each direction
(manifold and consistently oriented: :func:`vaultgram.geometry.halfedges.mesh_edges`), boundary vertices
starting one boundary half-edge each (no pinched vertex: :func:`vaultgram.geometry.meshes.boundary_loops`),
and every face of non-zero area in the plan, all turning the same way (no face flipped over).

>>> from vaultgram.geometry.meshes import grid_mesh
>>> v, f = grid_mesh(2)
>>> check_plan_mesh(v, f)
>>> check_plan_mesh(v, [(0, 1, 4, 3), (4, 5, 8, 7)])
Traceback (most recent call last):
...
vaultgram.errors.NonManifoldVertexError: vertex 4 starts two boundary halfedges (non-manifold boundary vertex)
"""

from __future__ import annotations

import numpy as np

from vaultgram.errors import MeshError
from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.meshes import boundary_loops, face_areas

__all__ = ["check_plan_mesh"]


def check_plan_mesh(vertices, faces, min_sides: int = 3) -> None:
    """Raise :class:`~vaultgram.errors.MeshError` naming the first face, edge or vertex where
    ``faces`` over ``vertices`` (their x and y) are not a manifold, consistently oriented mesh of
    non-degenerate faces with at least ``min_sides`` sides, all counter-clockwise or all clockwise."""
    if not len(faces):
        raise MeshError("the mesh has no faces")
    for k, f in enumerate(faces):
        if len(f) < min_sides:
            raise MeshError(f"face {k} has {len(f)} vertices (at least {min_sides})")
        if len(set(f)) != len(f):
            raise MeshError(f"face {k} repeats a vertex: {list(f)}")
    mesh_edges(faces, len(vertices))
    boundary_loops(faces)
    xy = np.asarray(vertices, dtype=float)[:, :2]
    areas = face_areas(xy, faces)
    scale = float(np.ptp(xy, axis=0) @ np.ptp(xy, axis=0)) if len(xy) else 0.0
    zero = np.flatnonzero(np.abs(areas) <= 1e-14 * scale)
    if len(zero):
        raise MeshError(f"face {int(zero[0])} has zero area in the plan: {list(faces[int(zero[0])])}")
    turn = 1.0 if (areas > 0).sum() >= (areas < 0).sum() else -1.0
    flipped = np.flatnonzero(areas * turn < 0)
    if len(flipped):
        k = int(flipped[0])
        raise MeshError(f"face {k} is flipped over (it turns the other way from the others): {list(faces[k])}")
