"""Spatial queries on plan points without scipy: Delaunay triangles and points within a distance.

``vaultgram mesh`` needs a Delaunay triangulation (paper §3.1: the medial axis from the Delaunay
triangulation of the boundary samples) and a few neighbour queries (coinciding samples, points on
features). ``scipy.spatial`` would give both, but importing it costs 0.2-0.3 s (it imports
scipy.sparse, scipy.linalg and scipy.special), most of the command's time on a 10^3-face plan (issue
18). Here instead:

* :func:`delaunay`: GEOS's incremental Delaunay triangulation (``shapely.delaunay_triangles``; shapely
  is imported anyway) of the sites moved by a tiny deterministic amount (GEOS's predicates are in
  floating point), whose triangles come back as coordinates, mapped back to the input's indices
  exactly (GEOS copies the input coordinates), edges illegal for the sites as given flipped, and put
  in a canonical order: counter-clockwise, the lowest index first, triangles sorted.
* :func:`pairs_within`, :func:`close_pairs`, :func:`nearest_within`: a grid hash. Points go into square
  cells at least as wide as the distance ``r``, so the points within ``r`` of a point lie in its cell
  or the eight around it; the cells of the larger set are sorted once, the smaller set's nine
  neighbouring cells looked up by a sorted search, and the candidates' distances checked. The work is
  proportional to the candidates: the points within about ``3 r`` of each other.
"""

from __future__ import annotations

import numpy as np
import shapely

from vaultgram.geometry.arrays import lookup, ranges

__all__ = ["QHULL_FROM", "close_pairs", "delaunay", "incircle", "nearest_within", "pairs_within"]

#: The grid's cells are at least this fraction of the points' extent wide, so that cell indices stay
#: below 2^20 in each direction (an int64 key holds both) however small ``r`` is.
MIN_CELL = 2.0**-20


#: Before GEOS triangulates them, the sites move by this fraction of the plan's size (at most a fifth
#: of the sagitta of the finest arc the closest two sites could sample, :func:`_move`), each in a
#: direction hashed from its index. GEOS's predicates are in floating point: on the samples of a
#: slanted straight side (collinear to round-off) it returned overlapping and flat triangles; moved,
#: no three sites are collinear, or four co-circular, to round-off.
PERTURBATION = 1e-9
#: In-circle determinants above this fraction of their permanent are flipped (:func:`_legalised`):
#: far above round-off (1e-16), below what the move can change.
ILLEGAL = 1e-12
#: From this many sites on, qhull (``scipy.spatial.Delaunay``, imported then only) triangulates the moved
#: sites instead of GEOS: GEOS inserts by x, so sites on one circle cost it quadratic time (a regular
#: n-gon, whole :func:`delaunay`: 8,192 sites 0.12 s against qhull's 0.10 s, 20,000 0.72 s against 0.33 s,
#: 50,000 13.2 s against 2.4 s), while plans at the usual spacing have a few thousand sites. The moved
#: sites have one Delaunay triangulation, so both give the same triangles.
QHULL_FROM = 2**13


def delaunay(points, diagonal: float | None = None) -> np.ndarray:
    """The Delaunay triangles (m, 3) of the plan points ``points`` (n, 2): counter-clockwise, each
    starting at its lowest index, sorted. They cover the convex hull of the points (but for flat
    triangles of collinear hull points); of points that coincide exactly, the lowest index is used.
    Where the points leave a choice (co-circular points: a lattice, a regular polygon) the triangles
    are those of the points moved by :data:`PERTURBATION` of ``diagonal`` (the plan's size; default
    the points' extent: :mod:`vaultgram.topology.triangulation` passes the plan's, without its far
    frame); edges illegal by more than :data:`ILLEGAL` for the points as given are flipped.

    Why GEOS's and not qhull's: same speed on plans, without importing scipy (see the module's
    docstring); from :data:`QHULL_FROM` sites on qhull's, since GEOS's insertion order (by x) makes
    points on one circle quadratic.

    >>> delaunay(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.1]])).tolist()
    [[0, 1, 2], [1, 3, 2]]
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    sites = _distinct_rows(pts)
    if len(sites) < 3:
        return np.zeros((0, 3), dtype=np.int64)
    q = pts[sites]
    size = max(float(np.ptp(q, axis=0).max()) if diagonal is None else diagonal, 1e-300)
    tri = _geos(q, sites, PERTURBATION * size)
    closest = float(np.sqrt(((q[tri] - q[np.roll(tri, 1, axis=1)]) ** 2).sum(axis=2).min())) if len(tri) else size
    if 0.2 * closest**2 / size < PERTURBATION * size:  # sites finer than the move: move less
        tri = _geos(q, sites, max(0.2 * closest**2 / size, 1e-13 * size))
    a, b, c = q[tri[:, 0]], q[tri[:, 1]], q[tri[:, 2]]
    turn = np.sign((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    tri = tri[turn != 0]  # flat triangles of collinear hull points
    tri[turn[turn != 0] < 0] = tri[turn[turn != 0] < 0][:, [0, 2, 1]]
    return _canonical(sites[_legalised(q, tri)])


def _geos(q: np.ndarray, sites: np.ndarray, amount: float) -> np.ndarray:
    """GEOS's (or from :data:`QHULL_FROM` sites qhull's) Delaunay triangles of the sites ``q`` moved by
    ``amount`` each, in a direction hashed from its index ``sites``: the triangles' rows of ``q``."""
    angle = 2.0 * np.pi * ((sites.astype(np.uint64) * np.uint64(2654435761)) % np.uint64(2**32)) / 2.0**32
    moved = q + amount * np.column_stack([np.cos(angle), np.sin(angle)])
    if len(moved) >= QHULL_FROM:
        from scipy.spatial import Delaunay  # only for plans sampled this finely: see QHULL_FROM

        return Delaunay(moved).simplices.astype(np.int64)
    parts = shapely.get_parts(shapely.delaunay_triangles(shapely.multipoints(moved)))
    return _indices_of(moved, shapely.get_coordinates(parts).reshape(-1, 4, 2)[:, :3].reshape(-1, 2)).reshape(-1, 3)


def _distinct_rows(pts: np.ndarray) -> np.ndarray:
    """The lowest index of each distinct row of ``pts``, ascending."""
    keys = _complex_rows(pts)
    order = np.argsort(keys, kind="stable")
    first = order[np.concatenate([[True], keys[order][1:] != keys[order][:-1]])] if len(pts) else order
    return np.sort(first)


def _indices_of(pts: np.ndarray, coords: np.ndarray) -> np.ndarray:
    """The index in ``pts`` of each row of ``coords``, all of which are rows of ``pts`` exactly (the
    lowest index where rows repeat): a sorted search on the rows as complex numbers, which sort by
    their first coordinate, then their second."""
    keys, wanted = _complex_rows(pts), _complex_rows(coords)
    order = np.argsort(keys, kind="stable")
    pos = np.minimum(np.searchsorted(keys[order], wanted), len(pts) - 1)
    if not np.array_equal(keys[order][pos], wanted):
        raise ValueError("GEOS returned a Delaunay vertex that is not an input point")
    return order[pos].astype(np.int64)


def _complex_rows(xy: np.ndarray) -> np.ndarray:
    """The rows ``(x, y)`` as the complex numbers ``x + iy``, bit for bit."""
    out = np.empty(len(xy), dtype=np.complex128)
    out.real, out.imag = xy[:, 0], xy[:, 1]
    return out


def _canonical(tri: np.ndarray) -> np.ndarray:
    """Triangles turned (orientation kept) to start at their lowest index, then sorted: an order that
    depends on the triangles only, not on the library's traversal."""
    first = np.argmin(tri, axis=1)
    tri = np.take_along_axis(tri, (first[:, None] + np.arange(3)) % 3, axis=1)
    return tri[np.lexsort((tri[:, 2], tri[:, 1], tri[:, 0]))]


def _legalised(pts: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Counter-clockwise triangles ``tri`` with Lawson's flips applied until no edge is illegal: the
    vertex across it inside the other triangle's circumcircle by more than :data:`ILLEGAL`
    (:func:`incircle`). Each round flips every illegal edge that is the lowest-numbered illegal edge
    of both its triangles (the flips of a round touch distinct triangles), so a round costs one sort
    of the edges. The moved sites' triangles need none or a few."""
    while len(tri):
        t, u, p, a, b, q = _interior_edges(tri)
        bad = np.flatnonzero(incircle(pts, p, a, b, q) > ILLEGAL)
        if not len(bad):
            return tri
        first = np.full(len(tri), len(t))
        np.minimum.at(first, t[bad], bad)
        np.minimum.at(first, u[bad], bad)
        e = bad[(first[t[bad]] == bad) & (first[u[bad]] == bad)]
        tri = tri.copy()
        tri[t[e]] = np.column_stack([p[e], a[e], q[e]])  # the quad p a q b is counter-clockwise
        tri[u[e]] = np.column_stack([q[e], b[e], p[e]])
    return tri


def _interior_edges(tri: np.ndarray) -> tuple[np.ndarray, ...]:
    """Every edge shared by two triangles, once: the triangles ``t`` and ``u``, ``t`` = (p, a, b)
    counter-clockwise with the edge a -> b, ``u`` holding b -> a across from ``q``."""
    n = int(tri.max()) + 1
    corner = np.arange(3)
    a, b = tri[:, (corner + 1) % 3].ravel(), tri[:, (corner + 2) % 3].ravel()  # the side across each corner
    order = np.argsort(a * n + b, kind="stable")
    pos, found = lookup((a * n + b)[order], b * n + a)
    twin = order[pos]
    keep = np.flatnonzero(found & (np.arange(len(a)) < twin))
    t, u = keep // 3, twin[keep] // 3
    return t, u, tri.ravel()[keep], a[keep], b[keep], tri.ravel()[twin[keep]]


def incircle(pts: np.ndarray, a, b, c, d) -> np.ndarray:
    """The in-circle determinant of points ``a, b, c, d`` (index arrays into ``pts``) over its
    permanent (the sum of its terms' magnitudes): positive where ``d`` lies inside the circle through
    the counter-clockwise ``a, b, c``, negative outside, about 0 (within some 1e-15) on it.

    >>> sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]])
    >>> incircle(sq, np.array([0, 0]), np.array([1, 1]), np.array([2, 2]), np.array([3, 4])).round(6).tolist()
    [0.0, 0.666667]
    """
    ad, bd, cd = pts[a] - pts[d], pts[b] - pts[d], pts[c] - pts[d]
    al, bl, cl = (ad**2).sum(axis=1), (bd**2).sum(axis=1), (cd**2).sum(axis=1)
    terms = np.stack([al * bd[:, 0] * cd[:, 1], -al * cd[:, 0] * bd[:, 1], bl * cd[:, 0] * ad[:, 1],
                      -bl * ad[:, 0] * cd[:, 1], cl * ad[:, 0] * bd[:, 1], -cl * bd[:, 0] * ad[:, 1]])
    return terms.sum(axis=0) / np.maximum(np.abs(terms).sum(axis=0), 1e-300)


def pairs_within(points, queries, r: float) -> tuple[np.ndarray, np.ndarray]:
    """Every pair ``(q, p)`` of a row of ``queries`` and a row of ``points`` (plan coordinates: the
    first two columns) at most ``r`` apart, as two index arrays sorted by ``q`` then ``p``.

    >>> q, p = pairs_within(np.array([[0.0, 0.0], [1.0, 0.0], [5.0, 5.0]]), np.array([[0.5, 0.0], [9.0, 9.0]]), 0.6)
    >>> q.tolist(), p.tolist()
    ([0, 0], [0, 1])
    """
    pts, qs = _plan(points), _plan(queries)
    if not len(pts) or not len(qs) or not r >= 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    swap = len(qs) > len(pts)  # sort the larger set's cells, look the smaller set's up
    many, few = (qs, pts) if swap else (pts, qs)
    keys, stride = _cell_keys(many, few, r)
    order = np.argsort(keys[0], kind="stable")
    sorted_keys = keys[0][order]
    around = (keys[1][:, None] + (np.arange(-1, 2)[:, None] * stride + np.arange(-1, 2)).ravel()).ravel()
    lo, hi = np.searchsorted(sorted_keys, around, "left"), np.searchsorted(sorted_keys, around, "right")
    row, at = ranges(lo, hi - lo)
    a, b = row // 9, order[at]  # a row of the smaller set, a row of the larger
    near = ((few[a] - many[b]) ** 2).sum(axis=1) <= r * r
    q, p = (b[near], a[near]) if swap else (a[near], b[near])
    sort = np.lexsort((p, q))
    return q[sort], p[sort]


def _plan(points) -> np.ndarray:
    """The first two columns of ``points`` as a float array (n, 2)."""
    pts = np.asarray(points, dtype=float)
    return pts.reshape(len(pts), -1)[:, :2] if len(pts) else np.zeros((0, 2))


def _cell_keys(a: np.ndarray, b: np.ndarray, r: float) -> tuple[tuple[np.ndarray, np.ndarray], int]:
    """The grid cell of every row of ``a`` and of ``b`` as one integer ``i * stride + j``, and the
    stride. Cells are slightly wider than ``r`` (so that round-off never puts two points ``r`` apart
    two cells apart) and at least :data:`MIN_CELL` of the extent; ``stride`` leaves a free column
    between rows of cells, so that the neighbours ``j - 1`` and ``j + 1`` never alias another row."""
    both = np.concatenate([a, b])
    lo = both.min(axis=0)
    extent = float((both.max(axis=0) - lo).max())
    size = max(r * (1.0 + 1e-6), extent * MIN_CELL) or 1.0
    cells = [np.floor((x - lo) / size).astype(np.int64) for x in (a, b)]
    stride = int(max(c[:, 1].max() for c in cells)) + 2
    return tuple(c[:, 0] * stride + c[:, 1] for c in cells), stride


def close_pairs(points, r: float) -> np.ndarray:
    """The index pairs ``(i, j)``, ``i < j``, of rows of ``points`` at most ``r`` apart, sorted
    (scipy's ``cKDTree.query_pairs``).

    >>> close_pairs(np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 0.1], [3.0, 0.0]]), 0.2).tolist()
    [[0, 2], [1, 3]]
    """
    i, j = pairs_within(points, points, r)
    keep = i < j
    return np.column_stack([i[keep], j[keep]])


def nearest_within(points, queries, r: float) -> tuple[np.ndarray, np.ndarray]:
    """Per row of ``queries``, the index of the nearest row of ``points`` at most ``r`` away (of
    equally near ones the lowest index) and its distance; -1 and infinity where none is that near.

    >>> i, d = nearest_within(np.array([[0.0, 0.0], [1.0, 0.0]]), np.array([[0.9, 0.0], [0.5, 3.0]]), 0.5)
    >>> i.tolist(), d.round(6).tolist()
    ([1, -1], [0.1, inf])
    """
    qs = _plan(queries)
    q, p = pairs_within(points, qs, r)
    index, dist = np.full(len(qs), -1, dtype=np.int64), np.full(len(qs), np.inf)
    if len(q):
        d = np.sqrt(((_plan(points)[p] - qs[q]) ** 2).sum(axis=1))
        best = np.lexsort((p, d, q))
        first = best[np.concatenate([[True], q[best][1:] != q[best][:-1]])]
        index[q[first]], dist[q[first]] = p[first], d[first]
    return index, dist
