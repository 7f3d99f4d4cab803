"""Constrained uniform Laplacian smoothing (paper §3.2, Figure 2h; Botsch et al. [12]).

"A uniform Laplacian smoothing can be applied, which iteratively moves each vertex towards the
barycentre of its neighbouring vertices. Constraints are added to respect the boundaries: vertices at
the boundary corners remain fixed and other vertices lying on the boundaries are projected back on it
after each iteration, to allow them to slide along it. Usually, a small number of iterations is
sufficient to obtain a globally smooth mesh." (§3.2) During smoothing, feature points stay fixed and
curve-feature vertices are projected onto their curve (§4.1, §4.2).

One iteration is one sparse matrix product ``x <- D^-1 A x`` (``A`` the vertex adjacency of the mesh
edges, ``D`` the degrees), fixed vertices reset, then each :class:`SlideConstraint`'s vertices
projected onto its polyline: the nearest point over all segments, computed for all vertices of the
constraint at once (:func:`vaultgram.geometry.polylines.project_to_polyline`). No Python loop runs
over vertices. Faces that smoothing leaves folded are repaired by :mod:`vaultgram.meshing.untangle`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from vaultgram.geometry.meshes import adjacency, boundary_adjacency, corner_arrays
from vaultgram.meshing.quadmesh import slide

__all__ = ["laplacian_smooth", "DEFAULT_ITERATIONS"]

#: Default number of iterations: smooths the seams between patches visibly without drifting far from
#: the Coons layout (the global shape of the layout comes from the patches, not from smoothing).
DEFAULT_ITERATIONS = 20

_MAX_REVERTS = 8


def laplacian_smooth(
    vertices: np.ndarray,
    faces,
    iterations: int = DEFAULT_ITERATIONS,
    fixed: np.ndarray | None = None,
    constraints=(),
    tangential: bool = True,
    safe: bool = True,
) -> np.ndarray:
    """Constrained uniform Laplacian smoothing.

    Parameters
    ----------
    vertices : ndarray (n, 2) or (n, 3)
    faces : list of index sequences
    iterations : int
    fixed : ndarray (n,) bool, optional
        Vertices that never move (domain corners, feature points).
    constraints : sequence of SlideConstraint
        ``(vertices, polyline, closed)``: after each iteration these vertices are projected back
        onto the polyline (boundary stretches, curve features).
    tangential : bool
        If True (default), a vertex of the mesh boundary moves to the midpoint of its two boundary
        neighbours (then is projected), instead of the barycentre of all its neighbours: the full
        barycentre drags boundary vertices next to acute corners onto the corner.
    safe : bool
        If True (default), a step that would invert a face valid before it is undone for that
        face's vertices: near reflex corners the barycentre can lie outside the domain.

    Returns
    -------
    ndarray
        New vertex positions (the input is not modified).

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> v, f = grid_mesh(2)
    >>> v[4, :2] += 0.3
    >>> boundary = np.ones(9, bool); boundary[4] = False
    >>> laplacian_smooth(v, f, 1, fixed=boundary)[4, :2].tolist()
    [1.0, 1.0]
    """
    x = np.array(vertices, dtype=float)
    if iterations < 0:
        raise ValueError(f"iterations must be >= 0, got {iterations}")
    if iterations == 0 or len(faces) == 0:
        return x
    n = len(x)
    a = adjacency(n, faces)
    if tangential:
        # a vertex on the mesh boundary averages its two boundary neighbours only: it moves along
        # the boundary, so it cannot be dragged onto a corner or across a narrow part
        b = boundary_adjacency(n, faces)
        on_b = np.asarray(b.sum(axis=1)).ravel() > 0
        a = sp.diags((~on_b).astype(float)) @ a + sp.diags(on_b.astype(float)) @ b
    deg = np.asarray(a.sum(axis=1)).ravel()
    w = sp.diags(1.0 / np.maximum(deg, 1)) @ a
    keep = np.asarray(fixed, dtype=bool) if fixed is not None else np.zeros(n, dtype=bool)
    keep = keep | (deg == 0)
    anchor = x[keep]
    face_of, u, v, p = corner_arrays(faces)
    valid = _valid_faces(x, face_of, u, v, p, len(faces))
    for _ in range(iterations):
        old = x
        x = w @ old
        x[keep] = anchor
        slide(x, constraints)
        if safe:
            # a face valid before the step and inverted after it: its vertices keep their old
            # positions (repeated, since reverting may invert a neighbour)
            for _ in range(_MAX_REVERTS):
                now = _valid_faces(x, face_of, u, v, p, len(faces))
                broken = valid & ~now
                if not broken.any():
                    break
                back = np.unique(u[broken[face_of]])
                x[back] = old[back]
            valid = _valid_faces(x, face_of, u, v, p, len(faces))
    return x


def _valid_faces(x, face_of, u, v, p, n_faces) -> np.ndarray:
    """Faces whose every corner turns counter-clockwise (positive cross product)."""
    e1, e2 = x[v, :2] - x[u, :2], x[p, :2] - x[u, :2]
    cross = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    scale = (e1 * e1).sum(1) + (e2 * e2).sum(1)
    bad = np.zeros(n_faces, dtype=bool)
    bad[face_of[cross <= 1e-9 * scale]] = True
    return ~bad


