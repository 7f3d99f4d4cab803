"""Voussoir solids: each voussoir between its intrados and extrados (paper §5, Figure 13b).

The thrust surface is the vault's mid-surface. Every vertex of the tessellation is offset by
``-thickness / 2`` (intrados) and ``+thickness / 2`` (extrados) along the surface's vertex normal;
a voussoir's solid is its outline on both offsets, joined by one face per outline edge. Because the
offset points belong to the vertex, not to the voussoir, two neighbouring voussoirs share their
joint faces exactly: no gap, no overlap. Every face is split into triangles, the same way from both
sides (a joint quad by the diagonal from its smaller vertex's intrados point; the top and bottom by
a fan from the outline's centre), so each solid is a closed, outward-oriented triangle mesh.

With ``flat_extrados`` each voussoir's top is the best-fit plane of its extrados points instead (as
the built vault's stones are cut); the top points then lie on the vertex normals where they cross
that plane, and neighbours meet on the same lines, at their own heights.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vaultgram.geometry.arrays import row_dot
from vaultgram.geometry.meshes import corner_arrays
from vaultgram.geometry.surfaces import loop_planes

__all__ = ["Solids", "voussoir_solids", "solid_volumes"]

#: Triangles per block in :func:`solid_volumes`.
VOLUME_ROWS = 1 << 16


@dataclass(frozen=True, eq=False)
class Solids:
    """The voussoirs as closed triangle meshes over one vertex array.

    Attributes
    ----------
    vertices : ndarray (p, 3)
        Intrados points ``[0, n)``, extrados points ``[n, 2n)`` (vertex ``i`` at ``i`` and ``n + i``),
        then per voussoir its bottom and top centres, then (flat extrados) its own top points.
    triangles : ndarray (t, 3)
        Outward-oriented.
    owner : ndarray (t,)
        The voussoir of each triangle (solids are listed voussoir by voussoir).
    joint : ndarray (t,) bool
        Triangles on joint faces (shared with a neighbour when the extrados is not flat).
    """

    vertices: np.ndarray
    triangles: np.ndarray
    owner: np.ndarray
    joint: np.ndarray

    def of(self, k: int) -> np.ndarray:
        """The triangles of voussoir ``k``."""
        lo, hi = np.searchsorted(self.owner, [k, k + 1])
        return self.triangles[lo:hi]


def _offsets(x: np.ndarray, normals: np.ndarray, thickness: float) -> np.ndarray:
    return np.vstack([x - 0.5 * thickness * normals, x + 0.5 * thickness * normals])


def _flat_tops(x: np.ndarray, normals: np.ndarray, loops, thickness: float, base: int):
    """Per voussoir corner, its top point on the voussoir's best-fit extrados plane; and their ids."""
    top = x + 0.5 * thickness * normals
    centre, plane = loop_planes(top, loops, up=np.tile([0.0, 0.0, 1.0], (len(loops), 1)))
    loop, u, _, _ = corner_arrays(loops)
    n, c = normals[u], centre[loop]
    along = row_dot(plane[loop], n)
    s = row_dot(c - top[u], plane[loop]) / np.where(np.abs(along) > 1e-9, along, 1e-9)
    return top[u] + s[:, None] * n, base + np.arange(len(u))


def voussoir_solids(x: np.ndarray, normals: np.ndarray, loops, thickness: float,
                    flat_extrados: bool = False) -> Solids:
    """The solid of every voussoir outline (counter-clockwise loops of vertex indices into ``x``)."""
    n = len(x)
    points = [_offsets(x, normals, thickness)]
    loop, u, v, _ = corner_arrays(loops)
    k = len(loops)
    count = np.bincount(loop, minlength=k)[:, None]
    bottom, top = points[0].take(u, axis=0), points[0].take(n + u, axis=0)  # rows by take: the same values
    bottom_c = np.column_stack([np.bincount(loop, weights=bottom[:, j], minlength=k) for j in range(3)]) / count
    top_c = np.column_stack([np.bincount(loop, weights=top[:, j], minlength=k) for j in range(3)]) / count
    cb, ct = 2 * n + np.arange(k), 2 * n + k + np.arange(k)
    points += [bottom_c, top_c]
    top_u = n + u
    if flat_extrados:
        flat, top_u = _flat_tops(x, normals, loops, thickness, 2 * n + 2 * k)
        points.append(flat)
        ct_points = np.column_stack([np.bincount(loop, weights=flat[:, j], minlength=k) for j in range(3)]) / count
        points[2] = ct_points
    top_v = np.empty_like(top_u)  # the top point of the next corner, in the same voussoir
    nxt = np.arange(len(u)) + 1
    start = np.concatenate([[0], np.cumsum(count.ravel())[:-1]])
    last = start + count.ravel() - 1
    nxt[last] = start
    top_v[:] = top_u[nxt]
    return _triangles(np.vstack(points), loop, u, v, top_u, top_v, cb, ct)


def _triangles(points, loop, u, v, top_u, top_v, cb, ct) -> Solids:
    """Bottom fan (reversed), top fan, and two triangles per joint face, voussoir by voussoir."""
    bottom = np.column_stack([cb[loop], v, u])
    top = np.column_stack([ct[loop], top_u, top_v])
    low = u < v  # split every joint quad by the diagonal from its smaller vertex's intrados point
    side_a = np.where(low[:, None], np.column_stack([u, v, top_v]), np.column_stack([u, v, top_u]))
    side_b = np.where(low[:, None], np.column_stack([u, top_v, top_u]), np.column_stack([v, top_v, top_u]))
    tris = np.stack([bottom, top, side_a, side_b], axis=1)  # per corner: 4 triangles
    # the corners come voussoir by voussoir (corner_arrays), so the triangles do too
    return Solids(points, tris.reshape(-1, 3), np.repeat(loop, 4), np.tile([False, False, True, True], len(loop)))


def solid_volumes(solids: Solids, n_voussoirs: int) -> np.ndarray:
    """Volume of every solid (divergence theorem): positive when closed and outward-oriented. The
    triangles are taken :data:`VOLUME_ROWS` at a time, each block's corners gathered column by column
    (contiguous, not the strided columns of gathered rows: the same products). At once, the 10^7
    triangles of a 10^6-face design took 1.3 GB of temporaries, more than the rest of the
    tessellation held, and most of the time went to the kernel providing those pages; a block's
    stay in the cache."""
    columns = [np.ascontiguousarray(solids.vertices[:, j]) for j in range(3)]
    six = np.empty(len(solids.triangles))
    for lo in range(0, len(six), VOLUME_ROWS):
        block = solids.triangles[lo:lo + VOLUME_ROWS]
        a, b, c = ([column.take(block[:, k]) for column in columns] for k in range(3))
        six[lo:lo + len(block)] = (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2])
                                   + a[2] * (b[0] * c[1] - b[1] * c[0]))
    return np.bincount(solids.owner, weights=six, minlength=n_voussoirs) / 6.0
