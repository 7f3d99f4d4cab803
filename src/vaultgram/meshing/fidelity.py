"""Boundary fidelity after smoothing (§3.2; issue 12, What 5: the mesh boundary within 0.1% of the
bounding-box diagonal from the domain's).

The densities (:func:`vaultgram.meshing.densities.group_counts`) subdivide every boundary side finely
enough that its resampled polyline stays within the tolerance of the side's curve. Smoothing and the
shape optimisation then let the boundary vertices slide along their polylines (§3.2), and a vertex
that slides away from a bend of the curve leaves its chord cutting across the bend. :func:`hold_boundary`
puts such bends back: for the ring point that lies farthest from the mesh boundary, beyond the
tolerance, the nearer sliding vertex of its stretch moves onto it, if that does not lower the worst
scaled Jacobian of the mesh. Bends are few (the sides were within the tolerance before smoothing), so
the loop runs over bends, not vertices; its distances are vectorised per stretch.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.meshes import corner_arrays
from vaultgram.geometry.polylines import densified, project_to_polyline
from vaultgram.meshing.quadmesh import SlideConstraint
from vaultgram.meshing.quality import face_scaled_jacobians

__all__ = ["hold_boundary"]

#: Of the sliding vertices of a stretch, the ones this near to a bend (nearest first) are tried on it.
_CANDIDATES = 2
#: A vertex is tried at the points of its polyline and this many steps along each segment.
_STEPS = 8


def hold_boundary(vertices: np.ndarray, faces, constraints, tol: float) -> np.ndarray:
    """The vertices with the sliding ones moved onto the points of their polylines that the mesh
    boundary strays from by more than ``tol``, where the mesh's worst face does not get worse.

    Example
    -------
    A 2 x 1 strip whose bottom vertex 1 slid off the bend (1, -0.3) of its polyline:

    >>> x = np.array([[0.0, 0.0], [1.4, -0.18], [3.0, 0.0], [3.0, 1.0], [1.0, 1.0], [0.0, 1.0]])
    >>> bottom = SlideConstraint(np.array([1]), np.array([[0.0, 0.0], [1.0, -0.3], [3.0, 0.0]]))
    >>> hold_boundary(x, [(0, 1, 4, 5), (1, 2, 3, 4)], [bottom], tol=0.01)[1].tolist()
    [1.0, -0.3]
    """
    x = np.array(vertices, dtype=float)
    if not len(faces):
        return x
    around = _faces_around(faces, len(x))
    floor = float(face_scaled_jacobians(x, faces).min())
    for c in constraints:
        for _ in range(len(c.vertices)):  # each pass snaps one bend or stops
            if not _snap_worst_bend(x, faces, around, c, tol, floor):
                break
    return x


def _snap_worst_bend(x: np.ndarray, faces, around, c: SlideConstraint, tol: float, floor: float) -> bool:
    """Move one of the sliding vertices of ``c`` nearest to the point of its polyline farthest from
    the mesh boundary (if that is beyond ``tol``) to the point of the polyline, within its reach, that
    brings the stretch's farthest point nearest; whether one moved. A position counts only if it
    leaves the faces round the vertex at least as good as they were or as the mesh's worst
    (``floor``)."""
    poly = np.asarray(c.polyline, dtype=float)[:, :2]
    gaps = _gaps(x, c)
    k = int(np.argmax(gaps))
    if gaps[k] <= tol:
        return False
    verts = np.asarray(c.vertices, dtype=np.int64)
    for v in verts[np.argsort(np.hypot(*(x[verts, :2] - poly[k]).T), kind="stable")[:_CANDIDATES]]:
        ring = [faces[f] for f in around(v)]
        old, good = x[v].copy(), min(face_scaled_jacobians(x, ring).min(), floor)
        best, where = gaps[k], None
        for q in _reach(x, c, v, poly):
            x[v, :2] = q
            far = _gaps(x, c).max()
            if far < best and face_scaled_jacobians(x, ring).min() >= good:
                best, where = far, q
        x[v] = old
        if where is not None:
            x[v, :2] = where
            return True
    return False


def _reach(x: np.ndarray, c: SlideConstraint, v: int, poly: np.ndarray) -> np.ndarray:
    """The points of the polyline (its vertices and :data:`_STEPS` steps along each segment) no farther
    from vertex ``v`` than its neighbours along the stretch: where it may slide without passing them."""
    chain, ids = _chain(x, c)
    i = int(np.flatnonzero(ids == v)[0])
    near = chain[[i - 1, (i + 1) % len(chain)]]
    reach = np.hypot(*(near - x[v, :2]).T).max()
    points = densified(poly, _STEPS, c.closed)
    return points[np.hypot(*(points - x[v, :2]).T) <= reach]


def _chain(x: np.ndarray, c: SlideConstraint) -> tuple[np.ndarray, np.ndarray]:
    """The mesh boundary along a stretch, in the order of its polyline: points and vertex ids (-1 for
    the fixed vertices at the polyline's ends of an open stretch)."""
    poly = np.asarray(c.polyline, dtype=float)[:, :2]
    ids = np.asarray(c.vertices, dtype=np.int64)
    if c.closed:
        return x[ids, :2], ids
    if len(ids) > 1 and np.hypot(*(x[ids[-1], :2] - poly[0])) < np.hypot(*(x[ids[0], :2] - poly[0])):
        ids = ids[::-1]  # a curve's stretch may run against its polyline
    return np.vstack([poly[:1], x[ids, :2], poly[-1:]]), np.r_[-1, ids, -1]


def _gaps(x: np.ndarray, c: SlideConstraint) -> np.ndarray:
    """Distance from each point of the stretch's polyline to the mesh boundary along it."""
    poly = np.asarray(c.polyline, dtype=float)[:, :2]
    return np.hypot(*(project_to_polyline(poly, _chain(x, c)[0], c.closed) - poly).T)


def _faces_around(faces, n: int):
    """A function giving the faces at a vertex (from the corner arrays, sorted by vertex once)."""
    face_of, u, _, _ = corner_arrays(faces)
    order = np.argsort(u, kind="stable")
    starts = np.searchsorted(u[order], np.arange(n + 1))
    return lambda v: face_of[order[starts[v]:starts[v + 1]]]
