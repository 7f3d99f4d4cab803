"""How faithfully a mesh's boundary follows the domain's (issue 12, What 5).

Two measures, both relative to the bounding-box diagonal of the domain's outer ring:

* :func:`boundary_deviation`: the distance between the mesh boundary and the domain's rings, both
  ways (:func:`boundary_distance`): from the mesh's boundary vertices and the midpoints of its
  boundary edges (where a chord strays farthest) to the rings, and from the rings' vertices and the
  midpoints of their edges (where a chord cuts a bend off) to the mesh boundary;
* :func:`missed_vertices`: the ring vertices turning by more than an angle (15 degrees: those whose
  interior angle differs from 180 by more) that no mesh boundary vertex sits on.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.meshes import boundary_halfedges
from vaultgram.geometry.polygons import bbox_diagonal
from vaultgram.geometry.polylines import turning_angles
from vaultgram.geometry.spatial import nearest_within

__all__ = ["boundary_distance", "boundary_deviation", "missed_vertices"]


def _rings_lines(rings):
    import shapely

    return shapely.MultiLineString([np.vstack([r, r[:1]]) for r in (np.asarray(r, dtype=float)[:, :2] for r in rings)])


def boundary_distance(vertices: np.ndarray, faces, rings) -> float:
    """The larger of the two directed distances between the mesh boundary and the rings, each
    measured at the vertices and edge midpoints of one to the lines of the other (``inf`` for a mesh
    without boundary).

    >>> square = [np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])]
    >>> x = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 1.0]])  # the corner (0, 2) cut off
    >>> round(boundary_distance(x, [(0, 1, 2, 3)], square), 4)  # 2 / sqrt(5), from (0, 2) to the chord
    0.8944
    """
    import shapely

    xy = np.asarray(vertices, dtype=float)[:, :2]
    u, v = boundary_halfedges(faces)
    if not len(u):
        return float("inf")
    rings = [np.asarray(r, dtype=float)[:, :2] for r in rings]
    mesh_lines = shapely.multilinestrings(shapely.linestrings(np.stack([xy[u], xy[v]], axis=1)))
    probes = np.vstack([xy[u], 0.5 * (xy[u] + xy[v])])
    ring_probes = np.vstack([*rings, *[0.5 * (r + np.roll(r, -1, axis=0)) for r in rings]])
    out = shapely.distance(shapely.points(probes), _rings_lines(rings)).max()
    return float(max(out, shapely.distance(shapely.points(ring_probes), mesh_lines).max()))


def boundary_deviation(vertices: np.ndarray, faces, rings) -> float:
    """:func:`boundary_distance` over the outer ring's bounding-box diagonal.

    >>> square = [np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])]
    >>> x = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [1.0, 0.1]])
    >>> float(round(boundary_deviation(x, [(0, 4, 1, 2, 3)], square) * np.hypot(2, 2), 6))  # vertex 4: 0.1 in
    0.1
    """
    return boundary_distance(vertices, faces, rings) / bbox_diagonal(np.asarray(rings[0])[:, :2])


def missed_vertices(vertices: np.ndarray, boundary: np.ndarray, rings, angle: float = 15.0,
                    tol: float = 1e-9) -> list[tuple[int, int]]:
    """``(ring, vertex)`` of every ring vertex turning by more than ``angle`` degrees with no mesh
    boundary vertex within ``tol`` diagonals of it.

    >>> square = [np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])]
    >>> x = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.1, 1.9]])
    >>> missed_vertices(x, np.ones(4, bool), square)
    [(0, 3)]
    """
    on_boundary = np.asarray(vertices, dtype=float)[np.asarray(boundary, dtype=bool), :2]
    limit = tol * bbox_diagonal(np.asarray(rings[0])[:, :2])
    out = []
    for r, ring in enumerate(rings):
        ring = np.asarray(ring, dtype=float)[:, :2]
        sharp = np.flatnonzero(np.abs(turning_angles(ring)) > angle)
        out += [(r, int(i)) for i in sharp[nearest_within(on_boundary, ring[sharp], limit)[0] < 0]]
    return out
