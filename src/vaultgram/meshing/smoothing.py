"""Constrained uniform Laplacian smoothing (paper §3.2, Figure 2h; Botsch et al. [12]).

"A uniform Laplacian smoothing can be applied, which iteratively moves each vertex towards the
barycentre of its neighbouring vertices. Constraints are added to respect the boundaries: vertices at
the boundary corners remain fixed and other vertices lying on the boundaries are projected back on it
after each iteration, to allow them to slide along it. Usually, a small number of iterations is
sufficient to obtain a globally smooth mesh." (§3.2) During smoothing, feature points stay fixed and
curve-feature vertices are projected onto their curve (§4.1, §4.2).

One iteration is one sparse product ``x <- D^-1 A x`` (``A`` the vertex adjacency of the mesh edges,
``D`` the degrees; :class:`vaultgram.geometry.meshes.MeanOperator`), fixed vertices reset, then each
:class:`SlideConstraint`'s vertices projected onto its polyline: the nearest point over all
segments, computed for all vertices of the constraint at once
(:func:`vaultgram.geometry.polylines.project_to_polyline`). No Python loop runs over vertices. Faces
that smoothing leaves folded are repaired by :mod:`vaultgram.meshing.untangle`.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vaultgram import progress
from vaultgram.geometry.arrays import distinct, pieces
from vaultgram.geometry.meshes import (
    MeanOperator,
    MeshError,
    adjacency,
    barycentre_operator,
    boundary_adjacency,
    corner_arrays,
    corner_vectors,
)
from vaultgram.geometry.polygons import cross_z
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
        At least 0 (a negative number raises :class:`~vaultgram.geometry.meshes.MeshError`).
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
        raise MeshError(f"iterations must be >= 0, got {iterations}")
    if iterations == 0 or len(faces) == 0:
        return x
    w, deg = _barycentre_operator(len(x), faces, tangential)
    keep = (np.zeros(len(x), dtype=bool) if fixed is None else np.asarray(fixed, dtype=bool)) | (deg == 0)
    anchor = x[keep]
    corners = _FaceCorners(*corner_arrays(faces), len(faces))
    valid = _valid_faces(x, corners)
    tick = progress.ticker("smooth", iterations)
    for _ in range(iterations):
        tick()
        old, x = x, _laplacian_step(x, w, keep, anchor, constraints)
        if safe:
            valid = _undo_inversions(x, old, valid, corners)
    return x


def _laplacian_step(x: np.ndarray, w: MeanOperator, keep: np.ndarray, anchor: np.ndarray, constraints) -> np.ndarray:
    """One iteration (§3.2): every vertex to the barycentre of its neighbours, the ``keep`` vertices
    back at ``anchor``, the sliding ones projected back onto their polylines."""
    y = w @ x
    y[keep] = anchor
    return slide(y, constraints)


def _barycentre_operator(n: int, faces, tangential: bool) -> tuple[MeanOperator, np.ndarray]:
    """The operator ``D^-1 A`` that moves every vertex to the barycentre of its neighbours, and
    the degrees ``D``. With ``tangential``, a vertex on the mesh boundary averages its two boundary
    neighbours only: it moves along the boundary, so it cannot be dragged onto a corner or across a
    narrow part."""
    a = adjacency(n, faces)
    if tangential:
        b = boundary_adjacency(n, faces)
        a = a.rows_of(b, b.degrees() > 0)
    return barycentre_operator(a)


class _FaceCorners(NamedTuple):
    """The corner arrays of the faces (:func:`vaultgram.geometry.meshes.corner_arrays`) and their number."""

    face_of: np.ndarray
    u: np.ndarray
    v: np.ndarray
    p: np.ndarray
    n_faces: int


def _undo_inversions(x: np.ndarray, old: np.ndarray, valid: np.ndarray, corners: _FaceCorners) -> np.ndarray:
    """Give the vertices of every face valid before the step and inverted after it their ``old``
    positions, in place (repeated, since reverting may invert a neighbour); the faces now valid."""
    now = _valid_faces(x, corners)
    for _ in range(_MAX_REVERTS):
        broken = valid & ~now
        if not broken.any():
            break
        back = distinct(corners.u[broken[corners.face_of]])
        x[back] = old[back]
        now = _valid_faces(x, corners)
    return now


def _valid_faces(x: np.ndarray, corners: _FaceCorners) -> np.ndarray:
    """Faces whose every corner turns counter-clockwise (positive cross product, above a relative
    1e-9 of the squared edge lengths). The corners are tested a cache-sized piece at a time
    (:func:`~vaultgram.geometry.arrays.pieces`): this test of every face at every iteration was
    most of the smoothing's time at 10^6 faces."""
    xy = np.ascontiguousarray(x[:, :2])
    bad = np.zeros(corners.n_faces, dtype=bool)
    for part in pieces(len(corners.u)):
        e1, e2 = corner_vectors(xy, corners.u[part], corners.v[part], corners.p[part])
        scale = e1[:, 0] * e1[:, 0] + e1[:, 1] * e1[:, 1] + (e2[:, 0] * e2[:, 0] + e2[:, 1] * e2[:, 1])
        bad[corners.face_of[part][cross_z(e1, e2) <= 1e-9 * scale]] = True
    return ~bad
