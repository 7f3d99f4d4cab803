"""Discrete Coons patches (paper §3.2, Figure 3; Coons [14]).

"In the case of a four-sided patch, the four corners and edges are bilinearly interpolated to
generate a proper quad mesh filling the patch. In the case of a three-sided pattern with a pole,
discrete Coons patches can be applied by inserting a zero-length edge at the pole." (§3.2)

A patch with corners ``c0, c1, c2, c3`` (counter-clockwise) is given by its boundary samples:
``bottom`` from ``c0`` to ``c1`` and ``top`` from ``c3`` to ``c2`` (``m + 1`` points each), ``left``
from ``c0`` to ``c3`` and ``right`` from ``c1`` to ``c2`` (``n + 1`` points each). The bilinearly
blended Coons surface evaluated at the grid ``(u_i, v_j)`` is

    P(i, j) = (1 - v) bottom[i] + v top[i] + (1 - u) left[j] + u right[j]
              - [(1 - u)(1 - v) c0 + u (1 - v) c1 + (1 - u) v c3 + u v c2],

which reproduces the four boundary polylines exactly. ``u_i`` is the normalised arc length along
``bottom`` and ``top`` (averaged), ``v_j`` along ``left`` and ``right``, so uneven boundary samples
give an interior that follows them. A triangle with a pole is the same with ``left`` collapsed to
the pole: the first column of cells become triangles fanning around the pole.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.meshes import MeshError
from vaultgram.geometry.polylines import arc_parameters

__all__ = ["coons_grid", "grid_faces", "grid_worst_corner"]


def coons_grid(bottom: np.ndarray, right: np.ndarray, top: np.ndarray, left: np.ndarray) -> np.ndarray:
    """Grid points of a discrete Coons patch (see the module docstring).

    Parameters
    ----------
    bottom, top : ndarray (m + 1, d)
        From ``c0`` to ``c1`` and from ``c3`` to ``c2``.
    left, right : ndarray (n + 1, d)
        From ``c0`` to ``c3`` and from ``c1`` to ``c2``; ``left`` may be all one point (a pole).

    Returns
    -------
    ndarray (m + 1, n + 1, d)
        ``grid[i, j]``; the boundary rows and columns equal the inputs exactly.

    Raises
    ------
    MeshError
        if opposite sides have different numbers of samples.

    Example
    -------
    >>> import numpy as np
    >>> b = np.array([[0, 0], [1, 0], [2, 0.]]); t = b + [0, 1]
    >>> l = np.array([[0, 0], [0, 1.]]); r = l + [2, 0]
    >>> coons_grid(b, r, t, l)[1, 1].tolist()
    [1.0, 1.0]
    """
    bottom, right, top, left = (np.asarray(a, dtype=float) for a in (bottom, right, top, left))
    if len(bottom) != len(top) or len(left) != len(right):
        raise MeshError(
            f"opposite sides need equal sample counts: {len(bottom)} vs {len(top)}, {len(left)} vs {len(right)}"
        )
    u = 0.5 * (arc_parameters(bottom) + arc_parameters(top))[:, None, None]
    v = 0.5 * (arc_parameters(left) + arc_parameters(right))[None, :, None]
    c0, c1, c2, c3 = bottom[0], bottom[-1], top[-1], top[0]
    grid = (
        (1 - v) * bottom[:, None, :] + v * top[:, None, :]
        + (1 - u) * left[None, :, :] + u * right[None, :, :]
        - ((1 - u) * (1 - v) * c0 + u * (1 - v) * c1 + (1 - u) * v * c3 + u * v * c2)
    )
    grid[:, 0], grid[:, -1], grid[0, :], grid[-1, :] = bottom, top, left, right
    return grid


def grid_faces(ids: np.ndarray, pole: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Faces of a structured grid of vertex ids, counter-clockwise.

    Parameters
    ----------
    ids : ndarray (m + 1, n + 1) int
        Vertex id of grid point ``(i, j)``; ``i`` runs along ``bottom`` and ``j`` along ``left``.
    pole : bool
        If True, column ``i = 0`` is one vertex (the pole): its cells become triangles.

    Returns
    -------
    quads : ndarray (q, 4)
    triangles : ndarray (t, 3)

    Example
    -------
    >>> ids = np.array([[0, 0], [1, 2], [3, 4]])  # column i = 0 is the pole 0
    >>> [f.tolist() for f in grid_faces(ids, pole=True)]
    [[[1, 3, 4, 2]], [[0, 1, 2]]]
    """
    a, b = ids[:-1, :-1], ids[1:, :-1]
    c, d = ids[1:, 1:], ids[:-1, 1:]
    quads = np.stack([a, b, c, d], axis=-1)
    if not pole:
        return quads.reshape(-1, 4), np.zeros((0, 3), dtype=ids.dtype)
    tris = np.stack([a[0], b[0], c[0]], axis=-1)
    return quads[1:].reshape(-1, 4), tris


def grid_worst_corner(grid: np.ndarray) -> float:
    """The smallest scaled Jacobian (the sine of the corner angle, <= 0 where a cell is inverted or a
    side has no length) over the corners of a quad grid's cells, counter-clockwise cells as
    :func:`grid_faces` makes them: the structured grid's own form of the mesh quality of issue 12,
    computed with slices, so that a patch's Coons grid can be judged before it is welded
    (:mod:`vaultgram.meshing.weld` resamples the sides of patches whose grid is sheared).

    >>> g = np.array([[[0, 0], [0, 1.]], [[1, 0], [2, 1.]]])  # one cell, its corner at (1, 0) 135 degrees
    >>> round(grid_worst_corner(g), 4)
    0.7071
    """
    g = np.asarray(grid, dtype=float)[..., :2]
    ring = (g[:-1, :-1], g[1:, :-1], g[1:, 1:], g[:-1, 1:])  # a cell's corners, counter-clockwise
    worst = np.inf
    for k in range(4):
        e1, e2 = ring[(k + 1) % 4] - ring[k], ring[k - 1] - ring[k]
        norm = np.hypot(e1[..., 0], e1[..., 1]) * np.hypot(e2[..., 0], e2[..., 1])
        cross = e1[..., 0] * e2[..., 1] - e1[..., 1] * e2[..., 0]
        sj = np.where(norm > 0, cross / np.where(norm > 0, norm, 1.0), -1.0)
        worst = min(worst, float(sj.min())) if sj.size else worst
    return worst
