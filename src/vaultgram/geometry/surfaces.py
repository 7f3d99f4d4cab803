"""Polygon meshes in space: area vectors, normals, best-fit planes, corner angles, closest points.

Faces and loops are vertex-index sequences; every function is vectorised over faces (or loops) and
their corners by flattening them into corner arrays (:func:`vaultgram.geometry.meshes.corner_arrays`),
so costs grow linearly with the mesh. The tessellation (§5) cuts voussoirs from a thrust surface with
these: their normals give the intrados and extrados, their planes the corner angles and the flat
extrados, and closest points keep smoothed vertices on the surface.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.arrays import cross_rows, row_dot, unit_rows
from vaultgram.geometry.meshes import corner_arrays

__all__ = [
    "area_vectors",
    "surface_areas",
    "vertex_normals",
    "loop_planes",
    "loop_corner_angles",
    "triangle_fans",
    "closest_points_on_triangles",
    "project_to_surface",
    "FACE_BLOCK",
]

#: Faces measured at a time by :func:`area_vectors`.
FACE_BLOCK = 1 << 16


def area_vectors(vertices: np.ndarray, faces) -> np.ndarray:
    """Vector area of each polygon (Newell's method): normal times area, for planar or not. Measured
    :data:`FACE_BLOCK` faces at a time, each face's corners summed in order as at once (the same bits):
    a block's temporaries are a few MB of reused memory, where the 4.4 million corners of a 10^6-face
    tessellation at once made 0.5 GB of fresh pages for the kernel to fault in (0.4-1.1 s, mostly
    the kernel's, against 0.2-0.3 s).

    >>> area_vectors(np.array([[0.0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]]), [(0, 1, 2, 3)]).tolist()
    [[0.0, 0.0, 2.0]]
    """
    face, u, v, _ = corner_arrays(faces)
    x = np.asarray(vertices, dtype=float)
    out = np.zeros((len(faces), 3))
    for start in range(0, len(faces), FACE_BLOCK):
        stop = min(start + FACE_BLOCK, len(faces))
        a, b = np.searchsorted(face, [start, stop]).tolist()
        cross = cross_rows(x.take(u[a:b], axis=0), x.take(v[a:b], axis=0))
        for k in range(3):
            out[start:stop, k] = 0.5 * np.bincount(face[a:b] - start, weights=cross[:, k], minlength=stop - start)
    return out


def surface_areas(vertices: np.ndarray, faces) -> np.ndarray:
    """Area of each polygon in space: the length of its vector area (:func:`area_vectors`).

    >>> surface_areas(np.array([[0.0, 0, 0], [2, 0, 0], [2, 1, 1], [0, 1, 1]]), [(0, 1, 2, 3)]).round(4).tolist()
    [2.8284]
    """
    return np.linalg.norm(area_vectors(vertices, faces), axis=1)


def vertex_normals(vertices: np.ndarray, faces) -> np.ndarray:
    """Unit normal at each vertex: the sum of the vector areas of its faces, normalised (area-weighted).

    >>> n = vertex_normals(np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]), [(0, 1, 2)])
    >>> n.round(6).tolist()
    [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]
    """
    face, u, _, _ = corner_arrays(faces)
    a = area_vectors(vertices, faces)
    out = np.zeros((len(vertices), 3))
    for k in range(3):
        out[:, k] = np.bincount(u, weights=a[face, k], minlength=len(vertices))
    return unit_rows(out)


def loop_planes(vertices: np.ndarray, loops, up=None) -> tuple[np.ndarray, np.ndarray]:
    """Best-fit plane of each loop of vertices (least squares): ``(centroids, unit normals)``.

    The normal is the direction of least spread of the loop's vertices, turned to agree with the
    loop's vector area (or with ``up``, an (k, 3) array of reference directions, when given).

    >>> c, n = loop_planes(np.array([[0.0, 0, 1], [2, 0, 1], [2, 2, 1], [0, 2, 1]]), [(0, 1, 2, 3)])
    >>> c.tolist(), n.round(6).tolist()
    ([[1.0, 1.0, 1.0]], [[0.0, 0.0, 1.0]])
    """
    loop, u, _, _ = corner_arrays(loops)
    xu = np.asarray(vertices, dtype=float).take(u, axis=0)  # rows by take: a third of fancy indexing's time
    k = len(loops)
    count = np.bincount(loop, minlength=k).astype(float)
    centroid = np.column_stack([np.bincount(loop, weights=xu[:, j], minlength=k) for j in range(3)])
    centroid /= np.maximum(count, 1.0)[:, None]
    d = xu - centroid.take(loop, axis=0)
    cov = np.zeros((k, 3, 3))
    for i in range(3):
        for j in range(i, 3):
            cov[:, i, j] = cov[:, j, i] = np.bincount(loop, weights=d[:, i] * d[:, j], minlength=k)
    normal = np.linalg.eigh(cov)[1][:, :, 0]
    ref = area_vectors(vertices, loops) if up is None else np.asarray(up, dtype=float)
    normal *= np.where(row_dot(normal, ref) < 0, -1.0, 1.0)[:, None]
    return centroid, normal


def loop_corner_angles(vertices: np.ndarray, loops, normals: np.ndarray) -> np.ndarray:
    """Interior angle (degrees, in (0, 360)) at every corner of every loop, measured in the plane with
    the given normal per loop; loops are counter-clockwise about their normal. Corners in loop order.

    >>> square = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 0]])
    >>> loop_corner_angles(square, [(0, 1, 2, 4, 3)], np.array([[0.0, 0, 1]])).round(3).tolist()
    [90.0, 90.0, 45.0, 270.0, 45.0]
    """
    loop, u, v, w = corner_arrays(loops)
    x = np.asarray(vertices, dtype=float)
    n = np.asarray(normals, dtype=float).take(loop, axis=0)  # rows by take: a third of fancy indexing's time
    xu = x.take(u, axis=0)
    a, b = x.take(v, axis=0) - xu, x.take(w, axis=0) - xu  # towards the next and the previous corner
    a -= row_dot(a, n)[:, None] * n
    b -= row_dot(b, n)[:, None] * n
    turn = np.degrees(np.arctan2(row_dot(cross_rows(a, b), n), row_dot(a, b)))
    return np.where(turn <= 0, turn + 360.0, turn)


def triangle_fans(loops) -> np.ndarray:
    """Triangles ``(loop, corner, next corner)`` fanning each loop from an added centre point.

    Row ``(l, a, b)`` is the triangle (centre of loop ``l``, vertex ``a``, vertex ``b``), oriented as the
    loop; a loop of ``k`` vertices gives ``k`` triangles, so no triangle degenerates at a straight
    corner (as a fan from a corner vertex would).

    >>> triangle_fans([(4, 5, 6)]).tolist()
    [[0, 4, 5], [0, 5, 6], [0, 6, 4]]
    """
    loop, u, v, _ = corner_arrays(loops)
    return np.column_stack([loop, u, v])


def closest_points_on_triangles(points: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The closest point of triangle ``(a[i], b[i], c[i])`` to ``points[i]``, for every row at once.

    The standard region test (Ericson, *Real-Time Collision Detection*, 5.1.5), vectorised.

    >>> p = np.array([[0.2, 0.2, 1.0], [2.0, 2.0, 0.0]])
    >>> a, b, c = (np.tile(q, (2, 1)) for q in ([0.0, 0, 0], [1.0, 0, 0], [0.0, 1, 0]))
    >>> closest_points_on_triangles(p, a, b, c).round(12).tolist()
    [[0.2, 0.2, 0.0], [0.5, 0.5, 0.0]]
    """
    ab, ac, ap = b - a, c - a, points - a
    d1, d2 = (ab * ap).sum(1), (ac * ap).sum(1)
    bp = points - b
    d3, d4 = (ab * bp).sum(1), (ac * bp).sum(1)
    cp = points - c
    d5, d6 = (ab * cp).sum(1), (ac * cp).sum(1)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    denom = va + vb + vc
    denom = np.where(np.abs(denom) > 1e-300, denom, 1e-300)
    v, w = vb / denom, vc / denom  # inside: barycentric coordinates
    out = a + ab * v[:, None] + ac * w[:, None]
    edge_bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
    t = (d4 - d3) / np.where(edge_bc, (d4 - d3) + (d5 - d6), 1.0)
    out = np.where(edge_bc[:, None], b + t[:, None] * (c - b), out)
    edge_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
    t = d2 / np.where(edge_ac, d2 - d6, 1.0)
    out = np.where(edge_ac[:, None], a + t[:, None] * ac, out)
    edge_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
    t = d1 / np.where(edge_ab, d1 - d3, 1.0)
    out = np.where(edge_ab[:, None], a + t[:, None] * ab, out)
    out = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, out)
    out = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, out)
    return np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, out)


def project_to_surface(points: np.ndarray, vertices: np.ndarray, triangles: np.ndarray, candidates: int = 8
                       ) -> np.ndarray:
    """The closest point of a triangulated surface to each of ``points``.

    Each point is tested against the ``candidates`` triangles with the nearest centroids (a k-d tree
    query), so a point near the surface lands on it exactly; cost ``O(points x candidates)``.

    >>> v = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    >>> project_to_surface(np.array([[0.25, 0.5, 0.3]]), v, np.array([[0, 1, 2], [0, 2, 3]])).tolist()
    [[0.25, 0.5, 0.0]]
    """
    from scipy.spatial import cKDTree  # only the tessellation's smoothing projects: not with the module (issue 18)

    points = np.asarray(points, dtype=float)
    tri = np.asarray(vertices, dtype=float)[np.asarray(triangles, dtype=np.int64)]
    k = min(candidates, len(tri))
    _, near = cKDTree(tri.mean(axis=1)).query(points, k=k)
    near = np.asarray(near).reshape(len(points), k)
    rows = np.repeat(np.arange(len(points)), k)
    cand = near.ravel()
    q = closest_points_on_triangles(points[rows], tri[cand, 0], tri[cand, 1], tri[cand, 2]).reshape(-1, k, 3)
    best = np.argmin(((q - points[:, None, :]) ** 2).sum(axis=2), axis=1)
    return q[np.arange(len(points)), best]
