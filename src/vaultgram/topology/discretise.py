"""Discretisation of the domain's boundaries and features into points (paper §3.1, first paragraph).

"The input boundary curves are discretised into a set of points. The discretisation spacing is set
as a percentage of the length of the diagonal of the bounding box, with values between 1% to 5%
usually providing good results." (§3.1). The points are the sites of the Delaunay triangulation
(:mod:`vaultgram.topology.triangulation`) from which the topological skeleton is built.

Method
------
* Each ring (outer ring, then the holes) is a closed polyline whose every vertex is kept: the input
  files are dense polylines (already discretised curves), so every vertex is a boundary point.
  Each segment is split into ``ceil(length / h)`` equal parts, with ``h = spacing * diagonal``, so
  consecutive points are at most ``h`` apart.
* Corners are decided by angle: an input vertex is a *corner* when its turning angle exceeds
  ``corner_angle`` degrees; it is *convex* when the ring turns towards the domain (left, since the
  domain lies left of every normalised ring) and *reflex* otherwise. Points added by the
  subdivision are never corners.
* Curve features (§4.2) are open polylines discretised the same way. An end point lying on the
  boundary is inserted into its ring (it becomes a ring point, so the boundary segment it lies on
  is split and stays a triangle edge), and the curve shares that point.
* Point features (§4.1) are added as points. A point on the boundary is inserted into its ring, a
  point on a curve feature into the curve; both then share the existing point.

Everything per point is computed with numpy (``np.repeat`` over segments); Python loops run only
over rings and features.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from vaultgram.domain.model import Domain
from vaultgram.errors import DomainError
from vaultgram.geometry.polylines import locate_on_polyline, turning_angles

__all__ = ["Discretisation", "discretise", "SPACING_RANGE"]

#: The documented useful range of the relative spacing (paper §3.1: "between 1% to 5%").
SPACING_RANGE = (0.01, 0.05)
#: Spacings outside ``(0, SPACING_MAX]`` are rejected.
SPACING_MAX = 0.2

RING_CURVE = -1
RING_POINT = -2


@dataclass(frozen=True, eq=False)
class Discretisation:
    """Sample points of a domain (paper §3.1), with per-point labels.

    Attributes
    ----------
    domain : Domain
        The discretised domain.
    spacing : float
        Relative spacing (fraction of the bounding-box diagonal).
    h : float
        Absolute maximal distance between consecutive points, ``spacing * domain.diagonal``.
    points : ndarray (N, 2)
        All points: ring points (outer ring first, then holes in order), then curve-feature points
        not on a ring, then point features not on a ring or curve.
    ring : ndarray (N,) int
        0 for the outer ring, ``1 + k`` for hole ``k``, -1 for curve-feature points, -2 for point
        features. A feature point lying on a ring or curve carries that ring's/curve's label; use
        :attr:`feature_points` to find every feature point.
    index : ndarray (N,) int
        Position of the point along its ring or curve (0 for isolated point features).
    is_corner : ndarray (N,) bool
        Ring vertices whose turning angle exceeds ``corner_angle``; also the ring points where a
        curve feature ends and the curve vertices turning by more than ``corner_angle`` (the curve
        cuts the domain, so the regions on its sides see convex corners there).
    corner_kind : ndarray (N,) int8
        0 none, 1 convex corner, -1 reflex corner.
    turning : ndarray (N,) float
        Signed turning angle in degrees at ring/curve vertices (positive: towards the domain, i.e.
        convex); 0 at subdivision points and isolated points.
    is_input_vertex : ndarray (N,) bool
        True for vertices of the input polylines (and inserted feature points), False for points
        added by the subdivision.
    rings : tuple of ndarray
        For each ring (outer ccw, then holes cw), the indices of its points in order.
    curves : tuple of ndarray
        For each curve feature, the indices of its points in order (end points on the boundary are
        ring points: ``ring[curves[c][0]] >= 0``; other end points are the §4.2 "curve feature
        extremities").
    feature_points : ndarray (k,) int
        Index of the point of each point feature, in the domain's order.
    """

    domain: Domain
    spacing: float
    h: float
    points: np.ndarray
    ring: np.ndarray
    index: np.ndarray
    is_corner: np.ndarray
    corner_kind: np.ndarray
    turning: np.ndarray
    is_input_vertex: np.ndarray
    rings: tuple
    curves: tuple
    feature_points: np.ndarray

    @property
    def n_points(self) -> int:
        return len(self.points)

    def segments(self) -> np.ndarray:
        """All boundary segments as (S, 2) point indices, each directed with the domain on its left."""
        parts = [np.stack([r, np.roll(r, -1)], axis=1) for r in self.rings]
        return np.concatenate(parts) if parts else np.zeros((0, 2), dtype=np.int64)

    def curve_segments(self) -> np.ndarray:
        """All curve-feature segments as (S, 2) point indices."""
        parts = [np.stack([c[:-1], c[1:]], axis=1) for c in self.curves]
        return np.concatenate(parts) if parts else np.zeros((0, 2), dtype=np.int64)

    def __repr__(self) -> str:
        return (
            f"Discretisation({self.domain.name!r}, spacing={self.spacing}, {len(self.points)} points, "
            f"{int(self.is_corner.sum())} corners)"
        )


def _resample(poly: np.ndarray, h: float, closed: bool):
    """Split every segment into equal parts no longer than ``h``.

    Returns the new points, the index of each input vertex in the output, and a mask of input
    vertices.
    """
    if closed:
        nxt = np.roll(poly, -1, axis=0)
        start = poly
    else:
        nxt = poly[1:]
        start = poly[:-1]
    d = nxt - start
    length = np.hypot(d[:, 0], d[:, 1])
    m = np.maximum(1, np.ceil(length / h * (1 - 1e-12))).astype(np.int64)
    seg = np.repeat(np.arange(len(start)), m)
    offsets = np.concatenate([[0], np.cumsum(m)])
    k = np.arange(offsets[-1]) - offsets[seg]
    t = k / m[seg]
    out = start[seg] + t[:, None] * d[seg]
    vertex_pos = offsets[:-1].copy()
    if not closed:
        out = np.concatenate([out, poly[-1:]])
        vertex_pos = np.concatenate([vertex_pos, [len(out) - 1]])
    is_vertex = np.zeros(len(out), dtype=bool)
    is_vertex[vertex_pos] = True
    return out, vertex_pos, is_vertex


def _insert(poly: np.ndarray, inserts: list, tol: float, closed: bool):
    """Insert points (seg, t, p) into a polyline; return new polyline and each insert's vertex index."""
    n = len(poly)
    if not inserts:
        return poly, []
    # keys: a point at t ~ 0 or ~ 1 reuses the vertex
    resolved = []
    new = []
    for seg, t, p in inserts:
        nxt = (seg + 1) % n
        if np.hypot(*(poly[seg] - p)) <= tol:
            resolved.append(("v", seg))
        elif np.hypot(*(poly[nxt] - p)) <= tol:
            resolved.append(("v", nxt))
        else:
            resolved.append(("n", len(new)))
            new.append((seg, t, p))
    if not new:
        return poly, [r[1] for r in resolved]
    order = sorted(range(len(new)), key=lambda i: (new[i][0], new[i][1]))
    # build the merged vertex list
    rows, kinds = [], []
    j = 0
    for v in range(n):
        rows.append(poly[v])
        kinds.append(("v", v))
        while j < len(order) and new[order[j]][0] == v:
            rows.append(new[order[j]][2])
            kinds.append(("n", order[j]))
            j += 1
    pos = {k: i for i, k in enumerate(kinds)}
    return np.array(rows), [pos[r] for r in resolved]


def discretise(domain: Domain, spacing: float = 0.02, corner_angle: float = 30.0) -> Discretisation:
    """Sample the boundaries and features of ``domain`` (paper §3.1; features §4).

    Parameters
    ----------
    domain : Domain
        A validated domain.
    spacing : float
        Maximal distance between consecutive boundary points as a fraction of the bounding-box
        diagonal; the paper recommends 0.01 to 0.05 (:data:`SPACING_RANGE`). Must lie in
        ``(0, 0.2]``.
    corner_angle : float
        A ring vertex turning by more than this many degrees is a corner (convex or reflex).

    Returns
    -------
    Discretisation

    Raises
    ------
    DomainError
        If ``spacing`` or ``corner_angle`` is out of range.
    """
    spacing = float(spacing)
    if not (0.0 < spacing <= SPACING_MAX) or not np.isfinite(spacing):
        raise DomainError(
            f"spacing {spacing:g} is out of range: it is a fraction of the bounding-box diagonal "
            f"and must lie in (0, {SPACING_MAX}] (useful values {SPACING_RANGE[0]} to {SPACING_RANGE[1]})"
        )
    if not (0.0 <= corner_angle < 180.0):
        raise DomainError(f"corner_angle {corner_angle:g} must lie in [0, 180) degrees")
    diag = domain.diagonal
    h = spacing * diag
    tol = domain.tolerance

    rings = [np.asarray(r) for r in domain.rings]
    curves = [np.asarray(c) for c in domain.curves]
    ring_inserts: list[list] = [[] for _ in rings]
    curve_inserts: list[list] = [[] for _ in curves]
    # who refers to an inserted vertex: ("ring", r, k-th insert) / ("curve", c, k-th insert)
    curve_end_ref: dict = {}
    point_ref: dict = {}

    def on_ring(p):
        best = None
        for r, ring in enumerate(rings):
            d, seg, t = locate_on_polyline(ring, p, closed=True)
            if d <= tol and (best is None or d < best[0]):
                best = (d, r, seg, t)
        return best

    for c, curve in enumerate(curves):
        for end in (0, len(curve) - 1):
            hit = on_ring(curve[end])
            if hit is not None:
                _, r, seg, t = hit
                curve_end_ref[(c, end)] = (r, len(ring_inserts[r]))
                ring_inserts[r].append((seg, t, curve[end].copy()))
    for i, p in enumerate(domain.points):
        hit = on_ring(p)
        if hit is not None:
            _, r, seg, t = hit
            point_ref[i] = ("ring", r, len(ring_inserts[r]))
            ring_inserts[r].append((seg, t, p.copy()))
            continue
        for c, curve in enumerate(curves):
            d, seg, t = locate_on_polyline(curve, p, closed=False)
            if d <= tol:
                point_ref[i] = ("curve", c, len(curve_inserts[c]))
                curve_inserts[c].append((seg, t, p.copy()))
                break

    ring_ins_idx = []
    for r in range(len(rings)):
        rings[r], idx = _insert(rings[r], ring_inserts[r], tol, closed=True)
        ring_ins_idx.append(idx)
    curve_ins_idx = []
    for c in range(len(curves)):
        curves[c], idx = _insert(curves[c], curve_inserts[c], tol, closed=False)
        curve_ins_idx.append(idx)

    pts, ring_lab, index, turning, is_vertex, ring_idx = [], [], [], [], [], []
    offset = 0
    ring_vertex_global = []
    for r, ring in enumerate(rings):
        out, vpos, isv = _resample(ring, h, closed=True)
        ang = np.zeros(len(out))
        ang[vpos] = turning_angles(ring, closed=True)
        pts.append(out)
        ring_lab.append(np.full(len(out), r, dtype=np.int64))
        index.append(np.arange(len(out)))
        turning.append(ang)
        is_vertex.append(isv)
        ring_idx.append(np.arange(offset, offset + len(out)))
        ring_vertex_global.append(vpos + offset)
        offset += len(out)
    n_ring_points = offset

    curve_idx = []
    curve_vertex_global = []
    for c, curve in enumerate(curves):
        out, vpos, isv = _resample(curve, h, closed=False)
        ang = np.zeros(len(out))
        ang[vpos] = turning_angles(curve, closed=False)
        glob = np.arange(offset, offset + len(out))
        keep = np.ones(len(out), dtype=bool)
        for end_v, end_o in ((0, 0), (len(domain.curves[c]) - 1, len(out) - 1)):
            ref = curve_end_ref.get((c, end_v))
            if ref is not None:
                r, k = ref
                glob[end_o] = ring_vertex_global[r][ring_ins_idx[r][k]]
                keep[end_o] = False
        # renumber the kept points consecutively
        glob[keep] = np.arange(offset, offset + int(keep.sum()))
        pts.append(out[keep])
        ring_lab.append(np.full(int(keep.sum()), RING_CURVE, dtype=np.int64))
        index.append(np.flatnonzero(keep))
        turning.append(ang[keep])
        is_vertex.append(isv[keep])
        curve_idx.append(glob)
        curve_vertex_global.append(glob[vpos])
        offset += int(keep.sum())

    feature = np.empty(len(domain.points), dtype=np.int64)
    iso = []
    for i, p in enumerate(domain.points):
        ref = point_ref.get(i)
        if ref is None:
            feature[i] = offset + len(iso)
            iso.append(p)
        elif ref[0] == "ring":
            _, r, k = ref
            feature[i] = ring_vertex_global[r][ring_ins_idx[r][k]]
        else:
            _, c, k = ref
            feature[i] = curve_vertex_global[c][curve_ins_idx[c][k]]
    if iso:
        pts.append(np.array(iso))
        ring_lab.append(np.full(len(iso), RING_POINT, dtype=np.int64))
        index.append(np.zeros(len(iso), dtype=np.int64))
        turning.append(np.zeros(len(iso)))
        is_vertex.append(np.ones(len(iso), dtype=bool))

    points = np.concatenate(pts)
    ring_arr = np.concatenate(ring_lab)
    index_arr = np.concatenate(index).astype(np.int64)
    turning_arr = np.concatenate(turning)
    is_vertex_arr = np.concatenate(is_vertex)

    # curve / point features coinciding with another feature point (e.g. two curves sharing an end
    # point, a point feature at a curve's end): merge them so that the Delaunay sites are distinct.
    if len(points) > n_ring_points:
        remap = np.arange(len(points))
        pairs = cKDTree(points).query_pairs(r=tol, output_type="ndarray")
        if len(pairs):
            pairs = np.sort(pairs, axis=1)
            pairs = pairs[pairs[:, 1] >= n_ring_points]
            for a, b in pairs[np.lexsort((pairs[:, 0], pairs[:, 1]))]:
                remap[b] = remap[a] if remap[a] == a else remap[remap[a]]
        if (remap != np.arange(len(points))).any():
            keep = remap == np.arange(len(points))
            new_id = np.cumsum(keep) - 1
            final = new_id[remap]
            points, ring_arr, index_arr = points[keep], ring_arr[keep], index_arr[keep]
            turning_arr, is_vertex_arr = turning_arr[keep], is_vertex_arr[keep]
            curve_idx = [final[c] for c in curve_idx]
            feature = final[feature]

    n = len(points)
    is_ring = ring_arr >= 0
    is_corner = is_ring & (np.abs(turning_arr) > corner_angle)
    corner_kind = np.zeros(n, dtype=np.int8)
    corner_kind[is_corner & (turning_arr > 0)] = 1
    corner_kind[is_corner & (turning_arr < 0)] = -1
    # Curve features cut the domain (§4.2): where a curve meets a ring, and where a curve turns
    # sharply, the regions on either side see a convex corner.
    on_curve = ring_arr == RING_CURVE
    sharp = on_curve & (np.abs(turning_arr) > corner_angle)
    ends = np.array([i for c in curve_idx for i in (c[0], c[-1]) if ring_arr[i] >= 0], dtype=np.int64)
    for cut in (np.flatnonzero(sharp), ends):
        is_corner[cut] = True
        corner_kind[cut] = 1

    arrays = [points, ring_arr, index_arr, is_corner, corner_kind, turning_arr, is_vertex_arr, feature]
    for a in arrays:
        a.setflags(write=False)
    return Discretisation(
        domain=domain,
        spacing=spacing,
        h=h,
        points=points,
        ring=ring_arr,
        index=index_arr,
        is_corner=is_corner,
        corner_kind=corner_kind,
        turning=turning_arr,
        is_input_vertex=is_vertex_arr,
        rings=tuple(ring_idx),
        curves=tuple(curve_idx),
        feature_points=feature,
    )
