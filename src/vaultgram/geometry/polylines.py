"""Polylines: lengths, arc-length parameters, turning angles, nearest points, resampling.

A polyline is an ``(n, 2)`` (or ``(n, 3)``) float array of points in order; ``closed`` polylines
(rings) join their last point back to the first. Every stage measures and resamples its boundaries,
skeleton branches, patch sides and curve features with these functions, vectorised over points and
segments.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.polygons import cross_z, signed_angles

__all__ = [
    "segment_distances",
    "segment_lengths",
    "arc_lengths",
    "polyline_length",
    "arc_parameters",
    "point_at_length",
    "halfway_point",
    "turning_angles",
    "locate_on_polyline",
    "ray_hit_fraction",
    "project_to_polyline",
    "resample_polyline",
    "chord_deviation",
    "densified",
    "polyline_hausdorff",
    "subdivide_polyline",
    "thinned_dense_runs",
    "straight_spans",
]

_CHUNK = 2_000_000  # above this many points x segments, projections go through a spatial index


def segment_lengths(poly: np.ndarray) -> np.ndarray:
    """Length of each segment ``poly[i] -> poly[i + 1]`` of an open polyline (in the plan).

    >>> segment_lengths(np.array([[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]])).tolist()
    [5.0, 1.0]
    """
    return np.hypot(*np.diff(np.asarray(poly, dtype=float)[:, :2], axis=0).T)


def arc_lengths(poly: np.ndarray) -> np.ndarray:
    """Arc length from the first point to each point of an open polyline.

    >>> arc_lengths(np.array([[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]])).tolist()
    [0.0, 5.0, 6.0]
    """
    return np.concatenate([[0.0], np.cumsum(segment_lengths(poly))])


def polyline_length(poly: np.ndarray) -> float:
    """Total length of an open polyline (0 for fewer than two points).

    >>> polyline_length(np.array([[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]]))
    6.0
    """
    return float(segment_lengths(poly).sum()) if len(poly) > 1 else 0.0


def arc_parameters(poly: np.ndarray) -> np.ndarray:
    """Normalised arc length of each point of a polyline, from 0 to 1 (uniform if it has no length).

    >>> arc_parameters(np.array([[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]])).tolist()
    [0.0, 0.8333333333333334, 1.0]
    """
    s = arc_lengths(poly)
    if s[-1] <= 0:
        return np.linspace(0.0, 1.0, len(poly))
    return s / s[-1]


def point_at_length(poly: np.ndarray, length: float) -> np.ndarray:
    """The point of an open polyline at arc length ``length`` from its start (clamped to its ends).

    >>> point_at_length(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]]), 3.0).tolist()
    [2.0, 1.0]
    """
    s = arc_lengths(poly)
    return np.array([np.interp(length, s, poly[:, 0]), np.interp(length, s, poly[:, 1])])


def halfway_point(poly: np.ndarray) -> np.ndarray:
    """The point halfway along an open polyline.

    >>> halfway_point(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]])).tolist()
    [2.0, 0.0]
    """
    return point_at_length(poly, arc_lengths(poly)[-1] / 2)


def turning_angles(poly: np.ndarray, closed: bool = True) -> np.ndarray:
    """Signed turning angle (degrees) at each vertex of a polyline; positive is a left turn.

    For an open polyline the end points get 0.

    >>> turning_angles(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])).tolist()
    [90.0, 90.0, 90.0, 90.0]
    """
    if closed:
        d_in = poly - np.roll(poly, 1, axis=0)
        d_out = np.roll(poly, -1, axis=0) - poly
    else:
        d_in = np.zeros_like(poly)
        d_out = np.zeros_like(poly)
        d_in[1:-1] = poly[1:-1] - poly[:-2]
        d_out[1:-1] = poly[2:] - poly[1:-1]
    ang = np.degrees(signed_angles(d_in, d_out))
    if not closed and len(poly):
        ang[[0, -1]] = 0.0
    return ang


def _segments(poly: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray]:
    """Start points and vectors of the segments of a polyline."""
    a = np.asarray(poly, dtype=float)
    b = np.roll(a, -1, axis=0) if closed else a[1:]
    a = a if closed else a[:-1]
    return a, b - a


def _closest_on_segments(p: np.ndarray, a: np.ndarray, ab: np.ndarray) -> tuple[np.ndarray, list[np.ndarray]]:
    """For points ``p`` (k, d) and segments ``a + t ab`` (s, d): the parameters ``t`` (k, s) of the
    nearest point of every segment, and those points' coordinates, a (k, s) array per axis.

    Axis by axis on (k, s) arrays rather than on (k, s, d) arrays summed over their last axis: the
    same numbers (:func:`_summed`) in a third of the time at the sizes smoothing projects every
    iteration (25-60 points on 36-64 segments, where numpy's per-call costs dominate)."""
    ab2 = np.maximum(_summed([ab[:, j] * ab[:, j] for j in range(ab.shape[1])]), 1e-300)
    t = np.clip(_summed([(p[:, j, None] - a[:, j]) * ab[:, j] for j in range(ab.shape[1])]) / ab2, 0.0, 1.0)
    return t, [a[:, j] + t * ab[:, j] for j in range(ab.shape[1])]


def segment_distances(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from each of ``points`` (k, 2) to each segment from ``a[j]`` to ``b[j]`` (s, 2), a
    (k, s) array: many candidate chords measured at once.

    >>> segment_distances(np.array([[1.0, 1.0], [3.0, 0.0]]), np.array([[0.0, 0.0]] * 2),
    ...                   np.array([[2.0, 0.0], [0.0, 2.0]])).tolist()
    [[1.0, 1.0], [1.0, 3.0]]
    """
    p, a = np.asarray(points, dtype=float)[:, :2], np.asarray(a, dtype=float)[:, :2]
    _, q = _closest_on_segments(p, a, np.asarray(b, dtype=float)[:, :2] - a)
    return np.hypot(q[0] - p[:, 0, None], q[1] - p[:, 1, None])


def _summed(terms: list[np.ndarray]) -> np.ndarray:
    """``0.0 + terms[0] + terms[1] + ...`` in that order: exactly numpy's sum over an array's last
    axis of that length (up to 7; from 8 numpy sums in pairs), whose result here must not change by a
    bit. The leading +0.0 is numpy's too: -0.0 + -0.0 sums to +0.0 there, and the sign of a zero
    ``t`` would reach a projection onto a point at -0.0.

    >>> _summed([np.array([-0.0, 1.5]), np.array([-0.0, 2.0])]).tolist()
    [0.0, 3.5]
    """
    total = terms[0] + 0.0
    for term in terms[1:]:
        total += term
    return total


def locate_on_polyline(poly: np.ndarray, p: np.ndarray, closed: bool = False) -> tuple[float, int, float]:
    """The segment of a polyline nearest to point ``p``: ``(distance, segment index, t in [0, 1])``.

    >>> locate_on_polyline(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]]), np.array([3.0, 1.5]))
    (1.0, 1, 0.75)
    """
    a, ab = _segments(poly, closed)
    p = np.asarray(p, dtype=float)
    t, q = _closest_on_segments(p[None, :], a, ab)
    d = np.hypot(*(qj[0] - pj for qj, pj in zip(q, p)))
    i = int(np.argmin(d))
    return float(d[i]), i, float(t[0, i])


def ray_hit_fraction(poly: np.ndarray, origin, direction: float) -> float | None:
    """Where the ray from ``origin`` in the direction ``direction`` (radians) first meets an open
    polyline, as a fraction of the polyline's arc length (0 at its start, 1 at its end); None where it
    misses it (or the polyline has no length). A chord from a fan's pole that bisects the fan
    triangle's angle ends here on the triangle's far side (:mod:`vaultgram.topology.reflex`).

    >>> round(ray_hit_fraction(np.array([[0.0, 1.0], [4.0, 1.0]]), (1.0, 0.0), np.pi / 2), 9)
    0.25
    >>> round(ray_hit_fraction(np.array([[0.0, 1.0], [2.0, 1.0], [2.0, 3.0]]), (3.0, 2.0), np.pi), 9)
    0.75
    >>> ray_hit_fraction(np.array([[0.0, 1.0], [4.0, 1.0]]), (1.0, 0.0), -np.pi / 2) is None
    True
    """
    pts = np.asarray(poly, dtype=float)[:, :2]
    s = arc_lengths(pts)
    a, ab = pts[:-1], np.diff(pts, axis=0)
    u = np.array([np.cos(direction), np.sin(direction)])
    det = ab[:, 0] * u[1] - ab[:, 1] * u[0]  # cross(ab, u): zero where the segment runs along the ray
    ok = np.abs(det) > 1e-12 * np.maximum(np.hypot(*ab.T), 1e-300)
    det = np.where(ok, det, 1.0)
    rel = a - np.asarray(origin, dtype=float)
    t = (ab[:, 0] * rel[:, 1] - ab[:, 1] * rel[:, 0]) / det  # along the ray
    w = (u[0] * rel[:, 1] - u[1] * rel[:, 0]) / det  # along the segment, 0 to 1
    hit = ok & (t > 0.0) & (w >= 0.0) & (w <= 1.0)
    if s[-1] <= 0.0 or not hit.any():
        return None
    j = int(np.flatnonzero(hit)[np.argmin(t[hit])])
    return float((s[j] + w[j] * (s[j + 1] - s[j])) / s[-1])


def project_to_polyline(points: np.ndarray, poly: np.ndarray, closed: bool = False) -> np.ndarray:
    """The nearest point of a polyline to each of ``points`` (vectorised over points and segments).

    >>> project_to_polyline(np.array([[1.0, 1.0], [3.0, -1.0]]), np.array([[0.0, 0.0], [2.0, 0.0]])).tolist()
    [[1.0, 0.0], [2.0, 0.0]]
    """
    points = np.asarray(points, dtype=float)
    a, ab = _segments(poly, closed)
    if len(a) == 0:
        return np.repeat(np.asarray(poly, dtype=float)[:1], len(points), axis=0)
    if len(points) * len(a) > _CHUNK:
        return _closest_on_nearest_segments(points, a, ab)
    _, q = _closest_on_segments(points, a, ab)
    best = np.argmin(_summed([(qj - points[:, j, None]) ** 2 for j, qj in enumerate(q)]), axis=1)
    rows = np.arange(len(best))
    return np.stack([qj[rows, best] for qj in q], axis=1)


def _closest_on_nearest_segments(p: np.ndarray, a: np.ndarray, ab: np.ndarray) -> np.ndarray:
    """For many points and segments: the nearest point of the nearest segment to each point, the
    segment found in a spatial index (shapely's STRtree), O((k + s) log s) rather than k x s."""
    import shapely

    tree = shapely.STRtree(shapely.linestrings(np.stack([a, a + ab], axis=1)))
    where = tree.query_nearest(shapely.points(p), all_matches=False)
    seg = np.empty(len(p), dtype=np.int64)
    seg[where[0]] = where[1]
    a, ab = a[seg], ab[seg]
    t = np.clip(((p - a) * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0.0, 1.0)
    return a + t[:, None] * ab


def chord_deviation(poly: np.ndarray, samples: np.ndarray) -> float:
    """Largest distance from a point of ``poly`` to the polyline through ``samples`` (both ordered
    along the same curve): how far a side resampled into ``samples`` strays from the curve.

    >>> chord_deviation(np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]), np.array([[0.0, 0.0], [2.0, 0.0]]))
    1.0
    """
    poly = np.asarray(poly, dtype=float)
    if not len(poly):
        return 0.0
    q = project_to_polyline(poly, samples)
    return float(np.hypot(*(q - poly).T).max())


def _share_counts(lengths: np.ndarray, n: int) -> np.ndarray:
    """``n`` subdivisions shared among pieces in proportion to their lengths, at least one each, by
    rounding the pieces' cumulative ends: the sample at each break is the nearest to where a uniform
    subdivision of the whole polyline would put it, so every sample stays within half a subdivision
    (where no piece is held at its one) of its uniform arc-length place.

    Why cumulative: rounding each piece on its own (largest remainders) lets the errors add up along a
    side split by many kept points (multiple_lobes: 0.79 m outline segments with 1 or 2 edges of 0.47
    m at 10^4 faces, 4-6 at 10^5), so a resolution's boundary vertices drifted up to a whole coarse
    edge (0.50 m) from a finer one's at the same index fraction, and the equal-density relaxation of
    form finding (§5), a function of the supports' spacing in index space, took the drift into the
    vault's heights (3.8% of zmax between 10^4 and 10^5 faces, 3 m from any reflex corner).

    >>> _share_counts(np.array([1.5, 1.5, 1.5, 1.5]), 6).tolist()      # not [2, 2, 1, 1]
    [2, 1, 2, 1]
    """
    share = np.cumsum(lengths / lengths.sum() * n)
    ends = np.floor(share + 0.5).astype(np.int64)
    ends[-1] = n
    k = np.arange(1, len(ends) + 1)
    ends = np.maximum.accumulate(np.maximum(ends, k) - k) + k          # at least one per piece, forwards
    ends = np.minimum(ends, n - (len(ends) - k))                          # room for the pieces after
    return np.diff(np.concatenate([[0], ends]))


def resample_polyline(poly: np.ndarray, n: int, anchors=(), lengths=None) -> tuple[np.ndarray, list[int]]:
    """``n + 1`` points along a polyline, uniform in arc length, hitting the ``anchors`` if possible.

    Parameters
    ----------
    poly : ndarray (k, 2)
    n : int
        Number of subdivisions (>= 1).
    anchors : sequence of int
        Indices of interior points of ``poly`` that should be samples. Honoured when ``n`` leaves at
        least one subdivision per piece between anchors; the counts are shared in proportion to
        the pieces' lengths.
    lengths : ndarray (k - 1,), optional
        The measure of each segment to be uniform in instead of its length (all positive): a
        segment measured longer gets more samples.

    Returns
    -------
    samples : ndarray (n + 1, 2)
        First and last equal ``poly[0]`` and ``poly[-1]``.
    hit : list of int
        For each honoured anchor, its sample index (empty when the anchors were not honoured).

    Example
    -------
    >>> pts, hit = resample_polyline(np.array([[0.0, 0.0], [1.0, 0.0], [4.0, 0.0]]), 4, anchors=[1])
    >>> pts[:, 0].tolist(), hit
    ([0.0, 1.0, 2.0, 3.0, 4.0], [1])
    """
    poly = np.asarray(poly, dtype=float)
    s = arc_lengths(poly) if lengths is None else np.concatenate([[0.0], np.cumsum(lengths)])
    anchors = sorted(int(a) for a in anchors if 0 < a < len(poly) - 1)
    breaks = [0, *anchors, len(poly) - 1]
    lengths = np.diff(s[breaks])
    hit: list[int] = []
    if anchors and n >= len(lengths) and np.all(lengths > 0):
        m = _share_counts(lengths, n)
        targets = np.concatenate(
            [np.linspace(s[a], s[b], k + 1)[:-1] for a, b, k in zip(breaks[:-1], breaks[1:], m)] + [[s[-1]]]
        )
        hit = np.cumsum(m)[:-1].tolist()
    else:
        targets = np.linspace(0.0, s[-1], n + 1)
    out = np.column_stack([np.interp(targets, s, poly[:, 0]), np.interp(targets, s, poly[:, 1])])
    out[0], out[-1] = poly[0], poly[-1]
    for a, h in zip(anchors if hit else (), hit):
        out[h] = poly[a]
    return out, hit


def densified(poly: np.ndarray, samples: int, closed: bool = False) -> np.ndarray:
    """The vertices of a polyline and ``samples - 1`` evenly spaced points inside each segment (also
    the closing one when ``closed``).

    >>> densified(np.array([[0.0, 0.0], [2.0, 0.0]]), 2).tolist()
    [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]
    """
    p = np.asarray(poly, dtype=float)[:, :2]
    if closed and len(p):
        p = np.vstack([p, p[:1]])
    t = np.linspace(0.0, 1.0, samples, endpoint=False)[None, :, None]
    out = np.vstack([(p[:-1, None, :] * (1 - t) + p[1:, None, :] * t).reshape(-1, 2), p[-1:]])
    return out[:-1] if closed and len(p) else out


def polyline_hausdorff(a: np.ndarray, b: np.ndarray, samples: int = 8) -> float:
    """Hausdorff distance between two polylines: the larger of the two directed distances, each the
    largest distance from a point of one (its vertices and ``samples - 1`` points inside each segment)
    to the other polyline.

    >>> polyline_hausdorff(np.array([[0.0, 0.0], [2.0, 0.0]]), np.array([[0.0, 1.0], [2.0, 1.0]]))
    1.0
    """
    import shapely

    la, lb = shapely.LineString(np.asarray(a)[:, :2]), shapely.LineString(np.asarray(b)[:, :2])
    d1 = shapely.distance(shapely.points(densified(a, samples)), lb).max()
    d2 = shapely.distance(shapely.points(densified(b, samples)), la).max()
    return float(max(d1, d2))


def subdivide_polyline(poly: np.ndarray, max_length: float, closed: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Split every segment of a polyline into the fewest equal parts no longer than ``max_length``.

    Every vertex is kept. Returns the points in order (a closed polyline does not repeat its first
    point at the end) and the index of each input vertex among them. A segment whose length is a
    whole multiple of ``max_length`` is not split once more by rounding.

    >>> pts, at = subdivide_polyline(np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 1.0]]), 1.0)
    >>> pts[:, 0].tolist(), at.tolist()
    ([0.0, 1.0, 2.0, 3.0, 3.0], [0, 3, 4])
    """
    start, d = _segments(poly, closed)
    length = np.hypot(d[:, 0], d[:, 1])
    m = np.maximum(1, np.ceil(length / max_length * (1 - 1e-12))).astype(np.int64)
    seg = np.repeat(np.arange(len(start)), m)
    offsets = np.concatenate([[0], np.cumsum(m)])
    t = (np.arange(offsets[-1]) - offsets[seg]) / m[seg]
    out = start[seg] + t[:, None] * d[seg]
    at = offsets[:-1].copy()
    if not closed:
        out = np.concatenate([out, np.asarray(poly, dtype=float)[-1:]])
        at = np.concatenate([at, [len(out) - 1]])
    return out, at


def thinned_dense_runs(ring: np.ndarray, dense: float, tol: float, keep_angle: float) -> np.ndarray:
    """Which vertices of a closed ring to keep when thinning its dense runs: a vertex whose two
    segments are both shorter than ``dense`` and which turns by at most ``keep_angle`` degrees may go
    when the ring without it stays within ``tol`` of the ring (Douglas-Peucker, shapely's
    ``simplify``, over the whole ring; every other vertex stays).

    Why: a boundary given as 10^5 vertices much closer than the sampling spacing would make every
    later stage work on 10^5 points where a few hundred describe the same curve to ``tol``.

    >>> t = 2 * np.pi * np.arange(1000) / 1000  # a regular 1000-gon of radius 1, and a square
    >>> int(thinned_dense_runs(np.column_stack([np.cos(t), np.sin(t)]), 0.05, 1e-4, 15.0).sum())
    256
    >>> thinned_dense_runs(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), 0.05, 1e-4, 15.0).tolist()
    [True, True, True, True]
    """
    ring = np.asarray(ring, dtype=float)[:, :2]
    seg = np.hypot(*(np.roll(ring, -1, axis=0) - ring).T)
    may_go = (seg < dense) & (np.roll(seg, 1) < dense) & (np.abs(turning_angles(ring)) <= keep_angle)
    if not may_go.any():
        return np.ones(len(ring), dtype=bool)
    import shapely

    kept = shapely.get_coordinates(shapely.simplify(shapely.LinearRing(ring), tol, preserve_topology=True))
    keep = ~may_go
    keep[_rows_of(ring, kept)] = True
    return keep


def _rows_of(points: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """The indices of ``rows`` among ``points`` (each row an exact copy of a point; sorted search)."""
    view = np.ascontiguousarray(points).view([("x", float), ("y", float)]).ravel()
    order = np.argsort(view, kind="stable")
    want = np.ascontiguousarray(rows).view([("x", float), ("y", float)]).ravel()
    pos = np.clip(np.searchsorted(view[order], want), 0, len(order) - 1)
    return order[pos][view[order[pos]] == want]


def straight_spans(chain: np.ndarray, poly: np.ndarray, closed: bool = False, rel: float = 1e-9) -> np.ndarray:
    """Per point of ``chain`` (points on the polyline ``poly``, in order along it: a stretch of a mesh
    boundary), whether ``poly`` runs straight from the chain point before it to the one after it: no
    bend of ``poly`` lies strictly between them or at the point, and the three are collinear. Such a
    point may slide along the line through its neighbours while the chain stays on ``poly`` (the
    mean-quality pass of :mod:`vaultgram.meshing.orthogonalise`; issue 12, What 5: the bends a chord
    cuts off are the boundary's distance from the plan). The ends of an open chain are False. A bend
    is a point of ``poly`` farther than ``rel`` times the polyline's extent from the line through its
    two neighbours; bends are placed along the chain by their nearest point on it (shapely).

    >>> poly = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]])
    >>> chain = np.array([[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [1.5, 0.0], [2.0, 1.0], [2.0, 2.0]])
    >>> straight_spans(chain, poly).tolist()
    [False, True, True, False, False, False]
    """
    import shapely

    chain, poly = np.asarray(chain, dtype=float)[:, :2], np.asarray(poly, dtype=float)[:, :2]
    n = len(chain)
    ok = np.ones(n, dtype=bool)
    if not closed:
        ok[[0, -1]] = False
    if n < 3:
        return ok & False
    eps = rel * max(float(np.ptp(poly, axis=0).max()), 1e-300)
    before, after = np.roll(chain, 1, axis=0), np.roll(chain, -1, axis=0)
    ok &= np.abs(cross_z(after - before, chain - before)) <= eps * np.hypot(*(after - before).T)
    bends = _bends(poly, closed, eps)
    if len(bends):
        line = np.vstack([chain, chain[:1]]) if closed else chain
        cum = arc_lengths(line)
        pos = shapely.line_locate_point(shapely.LineString(line), shapely.points(bends))
        seg = np.clip(np.searchsorted(cum, pos, side="right") - 1, 0, len(cum) - 2)
        at = np.where(pos - cum[seg] <= cum[seg + 1] - pos, seg, seg + 1)
        on = np.abs(pos - cum[at]) <= eps  # a bend at a chain point: that point stays
        ok[at[on] % n] = False
        ok[seg[~on] % n] = False  # a bend inside segment k: points k and k + 1 stay
        ok[(seg[~on] + 1) % n] = False
    return ok


def _bends(poly: np.ndarray, closed: bool, eps: float) -> np.ndarray:
    """The points of a polyline farther than ``eps`` from the line through their two neighbours (the
    ends of an open polyline are not bends)."""
    if len(poly) < 3:
        return poly[:0]
    before, after = np.roll(poly, 1, axis=0), np.roll(poly, -1, axis=0)
    chord = np.hypot(*(after - before).T)
    bent = np.abs(cross_z(after - before, poly - before)) > eps * np.maximum(chord, 1e-300)
    if not closed:
        bent[[0, -1]] = False
    return poly[bent]
