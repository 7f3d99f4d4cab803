"""Boundary fidelity after smoothing (§3.2; issue 12, What 5: every ring vertex whose angle differs
from 180 degrees by more than 15 is a mesh vertex, and the mesh boundary lies within 0.1% of the
bounding-box diagonal from the domain's).

The densities (:func:`vaultgram.meshing.densities.group_counts`) subdivide every boundary side finely
enough that its resampled polyline stays within the tolerance of the side's curve. Smoothing and the
shape optimisation then let the boundary vertices slide along their polylines (§3.2):

* a patch corner on a bend of the outline (a rebranch's foot at a ring vertex turning by 12 degrees
  or more, not a corner of the domain) slides too, since pinned there it could leave its patches a
  corner of nearly 180 degrees (on multiple_lobes a row of quads of scaled Jacobian 0.23, on the
  Rolex plan 0.22). :func:`place_on_points` then puts the sliding vertex that fits best (of the two
  nearest) on each such ring vertex left bare, and the pipeline optimises the faces again with it
  fixed there;
* a vertex that slides away from a gentler bend leaves its chord cutting across the bend.
  :func:`hold_boundary` puts such bends back: for the ring point that lies farthest from the mesh
  boundary, beyond the tolerance, the nearer sliding vertex of its stretch moves onto it (or as near
  as its faces allow), if that does not lower the worst scaled Jacobian of the mesh. Where no single
  snap helps (every chord of an arc near the tolerance), sweeps along the stretch spread its vertices
  so that the slack of its straighter parts reaches the farthest point.

Both are few (the sides were within the tolerance before smoothing), so the loops run over those
points, not over vertices; the distances are vectorised per stretch.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.meshes import corner_arrays
from vaultgram.geometry.polylines import densified, project_to_polyline, segment_distances
from vaultgram.geometry.spatial import nearest_within, pairs_within
from vaultgram.meshing.quadmesh import SlideConstraint
from vaultgram.meshing.quality import face_scaled_jacobians

__all__ = ["hold_boundary", "place_on_points", "on_points", "stretch_chain", "SAME_POINT"]

#: Two points closer than this fraction of the diagonal are the same point.
SAME_POINT = 1e-9

#: Of the sliding vertices of a stretch, the ones this near to a point (nearest first) are tried on it.
_CANDIDATES = 2
#: A vertex is tried at the points of its polyline and this many steps along each segment, and in a
#: tie where none of those brings the boundary nearer, at this many (the last fraction of a step: the
#: ellipse's gap was 0.5% over the tolerance).
_STEPS = 8
_FINE_STEPS = 64
#: At most this many sweeps of :func:`_balance` along a stretch.
_SWEEPS = 64


def hold_boundary(vertices: np.ndarray, faces, constraints, tol: float) -> np.ndarray:
    """The vertices with the sliding ones moved onto the points of their polylines that the mesh
    boundary strays from by more than ``tol``, where the mesh's worst face does not get worse.

    The gaps of a stretch (each polyline point's distance from the mesh boundary) are measured once
    and then kept up to date incrementally: a snap changes only the gaps of the points near the
    moved vertex (:func:`_snap_bend`). Where several points are farthest (a symmetric plan: the
    stadium's four joins of its half circles and straight sides) no single snap lowers the maximum;
    a snap that brings its own neighbourhood nearer while the maximum stays is taken, and the next
    pass takes the next of the tied points.

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
    around = floor = None
    for c in constraints:
        gaps = _gaps(x, c)
        for _ in range(len(c.vertices)):  # each pass snaps one bend or stops
            k = int(np.argmax(gaps))
            if gaps[k] <= tol:
                break
            if around is None:  # the faces round each vertex, and the mesh's worst face before any snap
                around, floor = _faces_around(faces, len(x)), float(face_scaled_jacobians(x, faces).min())
            if not _snap_bend(x, faces, around, c, k, gaps, floor):
                _balance(x, faces, around, c, gaps, tol, floor)
                break
    return x


def place_on_points(vertices: np.ndarray, faces, constraints, points: np.ndarray, eps: float,
                    folding: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """The vertices with one sliding vertex moved onto each of ``points`` that lies on a stretch's
    polyline with no vertex within ``eps`` of it (of the :data:`_CANDIDATES` nearest that reach it
    without passing a neighbour, the one that leaves the best worst face round it, unless each folds
    one; with ``folding``, even then: for a caller that optimises the faces after it and checks that
    they unfold), and per vertex whether it sits on one of ``points``.

    Example
    -------
    The strip's bottom vertex 1 slid off the ring vertex (1, -0.3) it stood for:

    >>> x = np.array([[0.0, 0.0], [1.4, -0.18], [3.0, 0.0], [3.0, 1.0], [1.0, 1.0], [0.0, 1.0]])
    >>> bottom = SlideConstraint(np.array([1]), np.array([[0.0, 0.0], [1.0, -0.3], [3.0, 0.0]]))
    >>> y, on = place_on_points(x, [(0, 1, 4, 5), (1, 2, 3, 4)], [bottom], np.array([[1.0, -0.3]]), 1e-9)
    >>> y[1].tolist(), np.flatnonzero(on).tolist()
    ([1.0, -0.3], [1])
    """
    x = np.array(vertices, dtype=float)
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    if not len(faces) or not len(points):
        return x, np.zeros(len(x), dtype=bool)
    around = None
    for c in constraints:
        poly = np.asarray(c.polyline, dtype=float)[:, :2]
        on = np.flatnonzero(nearest_within(points, poly, eps)[0] >= 0)
        for k in on[nearest_within(stretch_chain(x, c)[0], poly[on], eps)[0] < 0]:
            around = _faces_around(faces, len(x)) if around is None else around  # once a point is bare
            _place_vertex_on(x, faces, around, c, int(k), folding)
    return x, nearest_within(points, x, eps)[0] >= 0


def on_points(vertices: np.ndarray, points: np.ndarray, values: np.ndarray, eps: float) -> np.ndarray:
    """Per vertex, the value of the point of ``points`` within ``eps`` of it, else 0.

    >>> on_points(np.array([[0.0, 0.0], [1.0, 0.5]]), np.array([[1.0, 0.5], [2.0, 0.0]]), np.array([30.0, 90.0]), 1e-9)
    array([ 0., 30.])
    """
    if not len(points):
        return np.zeros(len(vertices))
    at = nearest_within(points, vertices, eps)[0]
    return np.where(at >= 0, np.asarray(values, dtype=float)[at], 0.0)


def _place_vertex_on(x: np.ndarray, faces, around, c: SlideConstraint, k: int, folding: bool = False) -> None:
    """Move the sliding vertex of ``c`` that :func:`place_on_points` picks onto polyline point ``k``."""
    poly = np.asarray(c.polyline, dtype=float)[:, :2]
    best, who = -np.inf if folding else 0.0, -1
    for v in _nearest(x, c, poly[k]):
        if not np.any(np.all(_reach(x, c, v, poly) == poly[k], axis=1)):
            continue
        ring, old = [faces[f] for f in around(v)], x[v].copy()
        x[v, :2] = poly[k]
        worst = face_scaled_jacobians(x, ring).min()
        x[v] = old
        if worst > best:
            best, who = worst, int(v)
    if who >= 0:
        x[who, :2] = poly[k]


def _snap_bend(x: np.ndarray, faces, around, c: SlideConstraint, k: int, gaps: np.ndarray, floor: float) -> bool:
    """Move one of the sliding vertices of ``c`` nearest to point ``k`` of its polyline, the farthest
    from the mesh boundary, to the point of the polyline within its reach that brings the stretch's
    farthest point nearest or, where none does (other points as far: ties), that leaves the farthest
    of the points it changes nearest, below the maximum; whether one moved, with ``gaps`` (per point
    of the polyline) updated. A position counts only if it leaves the faces round the vertex at least
    as good as they were or as the mesh's worst (``floor``). The positions are the polyline's points
    and :data:`_STEPS` steps along each segment, or in a tie where none of those counts
    :data:`_FINE_STEPS` (not otherwise: on hiroshi_senju_museum a finer snap where none lowered the
    maximum left the optimisation after it a worst face of 0.498 instead of 0.500).

    Incremental: only the points within reach of the vertex plus the largest gap can change
    (:func:`_window`); their distance from the rest of the mesh boundary is measured once per vertex,
    and per trial position only their distance from its two new chords."""
    poly = np.asarray(c.polyline, dtype=float)[:, :2]
    for v in _nearest(x, c, poly[k]):
        ring = [faces[f] for f in around(v)]
        good = min(face_scaled_jacobians(x, ring).min(), floor)
        window = _window(x, c, v, poly, gaps[k])
        for steps, least in ((_STEPS, good), (_FINE_STEPS, face_scaled_jacobians(x, ring).min())):
            where, new = _best_position(x, ring, least, v, _reach(x, c, v, poly, steps), poly, gaps, window)
            if where is not None:
                x[v, :2] = where
                gaps[window[0]] = new
                return True
    return False


def _balance(x: np.ndarray, faces, around, c: SlideConstraint, gaps: np.ndarray, tol: float, floor: float) -> None:
    """Where no single snap lowers the farthest gap (each chord of an arc near the tolerance: a
    shorter chord on one side is a longer one on the other), sweeps along the stretch move each
    sliding vertex whose chords stray by more than half the tolerance to the position within its
    reach that leaves the farthest point of its window (:func:`_window`) nearest: the slack of the
    straight or finer parts at the ends of a run spreads along it, until the stretch is within
    ``tol`` or a sweep moves nothing (at most :data:`_SWEEPS`). Only lowers a window's farthest gap,
    so the stretch's never grows; a position counts as in :func:`_snap_bend` (the faces round the
    vertex no worse than they were or than the mesh's worst, ``floor``); ``gaps`` kept up to date.

    On the stadium the half circles' ten chords each came within 0.93 of the tolerance of the ring,
    and their vertices sliding on the ring's own chords (24 points a half circle) put four points
    0.25% beyond it."""
    poly = np.asarray(c.polyline, dtype=float)[:, :2]
    for _ in range(_SWEEPS):
        moved = False
        for v in _hot_vertices(x, c, poly[gaps > tol / 2]):
            near, ends, rest = _window(x, c, v, poly, gaps.max())
            now = gaps[near].max(initial=0.0)
            q = _reach(x, c, v, poly, _FINE_STEPS)
            changed = np.minimum(rest[:, None], _chord_distances(poly[near], ends, q))
            top = changed.max(axis=0, initial=0.0)
            ring = [faces[f] for f in around(v)]
            good = min(face_scaled_jacobians(x, ring).min(), floor)
            lower = np.flatnonzero(top < now * (1 - 1e-9))
            for i in lower[np.argsort(top[lower], kind="stable")]:
                old = x[v].copy()
                x[v, :2] = q[i]
                if face_scaled_jacobians(x, ring).min() >= good:
                    gaps[near], moved = changed[:, i], True
                    break
                x[v] = old
        if gaps.max() <= tol or not moved:
            return


def _hot_vertices(x: np.ndarray, c: SlideConstraint, points: np.ndarray) -> np.ndarray:
    """The sliding vertices of ``c`` within a chord's length (the stretch's longest) of any of
    ``points``, in the stretch's order: those whose move can change the gaps there."""
    verts = np.asarray(c.vertices, dtype=np.int64)
    chain = stretch_chain(x, c)[0]
    reach = np.hypot(*np.diff(np.vstack([chain, chain[:1]]) if c.closed else chain, axis=0).T).max(initial=0.0)
    return verts[np.unique(pairs_within(points, x[verts, :2], reach)[0])]


def _chord_distances(points: np.ndarray, ends: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Distance from each of ``points`` to the two chords from ``ends[0]`` to a position and on to
    ``ends[1]``, for each of ``positions``: a (points, positions) array."""
    first = segment_distances(points, np.repeat(ends[:1], len(positions), 0), positions)
    return np.minimum(first, segment_distances(points, positions, np.repeat(ends[1:], len(positions), 0)))


def _best_position(x: np.ndarray, ring, good: float, v: int, positions: np.ndarray, poly: np.ndarray,
                   gaps: np.ndarray, window) -> tuple[np.ndarray | None, np.ndarray | None]:
    """Of ``positions`` for vertex ``v``, the one :func:`_snap_bend` takes, if any, and the gaps of the
    points of the ``window`` (:func:`_window`) with ``v`` there. The key of a position is the
    stretch's largest gap and, where that is not lower than now (a tie), the largest of the window's."""
    near, ends, rest = window
    gap, old = gaps.max(), x[v].copy()
    outside = gaps[~near].max(initial=0.0)
    best, where, new = (gap, gap), None, None
    for q in positions:
        changed = np.minimum(rest, _distances(poly[near], np.array([ends[0], q, ends[1]])))
        top = changed.max(initial=0.0)
        key = (max(outside, top), top if max(outside, top) >= gap else 0.0)
        if key < best:
            x[v, :2] = q
            if face_scaled_jacobians(x, ring).min() >= good:
                best, where, new = key, q, changed
            x[v] = old
    return where, new


def _window(x: np.ndarray, c: SlideConstraint, v: int, poly: np.ndarray, gap: float
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points of the polyline whose gap a move of sliding vertex ``v`` within its reach
    (:func:`_reach`) can change, the largest gap being ``gap``; the vertex's two neighbours along the
    stretch; and those points' distances from the mesh boundary without the vertex's two chords.

    A point's gap changes only if its nearest point of the mesh boundary is on one of the chords from
    ``v`` to its neighbours, before or after the move; every point of those chords is within the reach
    of ``v`` (the longer chord), so such a point is within the reach plus its gap of ``v``."""
    chain, ids = stretch_chain(x, c)
    i = int(np.flatnonzero(ids == v)[0])
    ends = chain[[i - 1, (i + 1) % len(chain)]]
    reach = np.hypot(*(ends - x[v, :2]).T).max()
    near = np.hypot(*(poly - x[v, :2]).T) <= (reach + gap) * (1 + 1e-9)
    if c.closed:  # the ring from the next vertex round to the previous one
        pieces = [np.roll(chain, -(i + 1), axis=0)[:-1]]
    else:
        pieces = [chain[:i], chain[i + 1:]]
    rest = np.min([_distances(poly[near], p) for p in pieces], axis=0)
    return near, ends, rest


def _distances(points: np.ndarray, poly: np.ndarray) -> np.ndarray:
    """Distance from each of ``points`` to an open polyline (to its one point if it has one)."""
    return np.hypot(*(project_to_polyline(points, poly) - points).T)


def _nearest(x: np.ndarray, c: SlideConstraint, p: np.ndarray) -> np.ndarray:
    """The :data:`_CANDIDATES` sliding vertices of ``c`` nearest to point ``p``, nearest first."""
    verts = np.asarray(c.vertices, dtype=np.int64)
    return verts[np.argsort(np.hypot(*(x[verts, :2] - p).T), kind="stable")[:_CANDIDATES]]


def _reach(x: np.ndarray, c: SlideConstraint, v: int, poly: np.ndarray, steps: int = _STEPS) -> np.ndarray:
    """The points of the polyline (its vertices and ``steps`` steps along each segment) no farther
    from vertex ``v`` than its neighbours along the stretch: where it may slide without passing them."""
    chain, ids = stretch_chain(x, c)
    i = int(np.flatnonzero(ids == v)[0])
    near = chain[[i - 1, (i + 1) % len(chain)]]
    reach = np.hypot(*(near - x[v, :2]).T).max()
    points = densified(poly, steps, c.closed)
    return points[np.hypot(*(points - x[v, :2]).T) <= reach]


def stretch_chain(x: np.ndarray, c: SlideConstraint) -> tuple[np.ndarray, np.ndarray]:
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
    return np.hypot(*(project_to_polyline(poly, stretch_chain(x, c)[0], c.closed) - poly).T)


def _faces_around(faces, n: int):
    """A function giving the faces at a vertex (from the corner arrays, sorted by vertex once)."""
    face_of, u, _, _ = corner_arrays(faces)
    order = np.argsort(u, kind="stable")
    starts = np.searchsorted(u[order], np.arange(n + 1))
    return lambda v: face_of[order[starts[v]:starts[v + 1]]]
