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
  subdivision are never corners, nor (with ``chamfers``, the default) are the vertices of a
  chamfer (:func:`_chamfer_points`): 135 to 150 degree vertices, in a run of such vertices that
  ends at a sharper convex corner; the regular valence makes them smooth points (issue 12). Other
  runs of 135 to 150 degree vertices (:attr:`Discretisation.soft_runs`) are smooth points where the
  caller asks (``smooth_at``; :func:`vaultgram.meshpipeline.decompose` tries them run by run).
* Curve features (§4.2) are open polylines discretised the same way. An end point lying on the
  boundary is inserted into its ring (it becomes a ring point, so the boundary segment it lies on
  is split and stays a triangle edge), and the curve shares that point.
* Point features (§4.1) are added as points. A point on the boundary is inserted into its ring, a
  point on a curve feature into the curve; both then share the existing point.

Everything per point is computed with numpy (``np.repeat`` over segments); Python loops run only
over rings and features.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from vaultgram.domain.model import Domain
from vaultgram.errors import DomainError
from vaultgram.geometry.arrays import distinct
from vaultgram.geometry.polylines import locate_on_polyline, subdivide_polyline, thinned_dense_runs, turning_angles
from vaultgram.geometry.spatial import close_pairs
from vaultgram.limits import SPACING_MAX, SPACING_RANGE
from vaultgram.topology.corners import chord_feet

__all__ = ["Discretisation", "discretise", "SPACING_RANGE"]


#: :attr:`Discretisation.ring` of curve-feature points and of point features off rings and curves.
RING_CURVE = -1
RING_POINT = -2
#: Ring vertices whose both segments are shorter than ``DENSE_RUN * h`` form dense runs (a finely
#: sampled arc, a regular polygon of 10^5 sides), thinned to within ``THINNING_TOLERANCE * h`` of the
#: ring before sampling; vertices turning by more than ``BOUNDARY_FIDELITY_ANGLE`` degrees always stay
#: (issue 12: they are mesh vertices). No shared plan or example has such a run at the paper's spacings
#: (their shortest edges are above 0.04 h), so their samples are unchanged.
DENSE_RUN = 0.02
THINNING_TOLERANCE = 1e-3
BOUNDARY_FIDELITY_ANGLE = 15.0
#: A ring vertex turning towards the domain by more than this many degrees (an interior angle under
#: 135) is a convex corner by the regular valence (:func:`_chamfer_points`).
CONVEX_TURN = 45.0
#: Ring vertices turning by less than this many degrees are points on a straight stretch (a feature
#: point or a chord's foot inserted there), not a chamfer's neighbour.
STRAIGHT_TURN = 1e-6
#: Turning angles closer than this (degrees) are equal: a regular octagon's corners, 45 degrees each up
#: to rounding, are all alike (none is sharper, so none is a chamfer's).
ANGLE_TOLERANCE = 1e-6


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
    chamfers : bool
        Whether chamfers were made smooth points (:func:`discretise`'s argument).
    smoothed : ndarray (m,) int
        The chamfer points and those at ``smooth_at``: they turn by more than ``corner_angle`` but are
        no corners (a curve's end on one is a corner all the same).
    smooth_at : ndarray (k, 2) float
        The points asked smooth besides the chamfers (:func:`discretise`'s argument).
    soft_runs : tuple of ndarray
        Every run of ring vertices turning towards the domain by ``corner_angle`` to
        :data:`CONVEX_TURN` degrees (interior angles of 135 to 150), consecutive along their ring
        (points on a straight stretch aside), as point indices; smoothed or not.
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
    chamfers: bool = True
    smoothed: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    smooth_at: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    soft_runs: tuple = ()

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


def discretise(domain: Domain, spacing: float = 0.02, corner_angle: float = 30.0, chamfers: bool = True,
               smooth_at=()) -> Discretisation:
    """Sample the boundaries and features of ``domain`` (paper §3.1; features §4).

    Feature points on the boundary or on a curve are inserted into it; the rings and curves are
    subdivided to the spacing, curves sharing their boundary end points; coincident feature points
    are merged; corners are decided by angle (see the module docstring).

    Parameters
    ----------
    domain : Domain
        A validated domain.
    spacing : float
        Maximal distance between consecutive boundary points as a fraction of the bounding-box
        diagonal; the paper recommends 0.01 to 0.05 (:data:`SPACING_RANGE`). Must lie in
        ``(0, 0.2]``.
    corner_angle : float
        A ring vertex turning by more than this many degrees is a corner (convex or reflex), but a
        chamfer's.
    chamfers : bool
        Make the vertices of chamfers smooth points (:func:`_chamfer_points`), not corners.
    smooth_at : array_like (k, 2)
        Points (in the domain's coordinates) where a ring vertex of 135 to 150 degrees is a smooth
        point too, chamfer or not (within the domain's tolerance; other points there are ignored).

    Returns
    -------
    Discretisation

    Raises
    ------
    DomainError
        If ``spacing`` or ``corner_angle`` is out of range.

    Example
    -------
    >>> from vaultgram.domain import load_domain
    >>> disc = discretise(load_domain("examples/l_shape.json"), 0.05)  # with its chords' two feet
    >>> disc
    Discretisation('l_shape', spacing=0.05, 64 points, 6 corners)
    >>> disc.corner_kind[disc.is_corner].tolist()  # the reflex corner of the L at (5, 5)
    [1, 1, 1, -1, 1, 1]
    """
    spacing, corner_angle = _checked_parameters(spacing, corner_angle)
    h, tol = spacing * domain.diagonal, domain.tolerance
    placed = _insert_features(domain, tol)
    rings, ring_members, ring_vertices = _sample_rings(placed.rings, placed.inserted, h)
    n_ring_points = sum(len(part.points) for part in rings)
    curves, curve_members, curve_vertices = _sample_curves(placed, ring_vertices, h, n_ring_points)
    n_line_points = n_ring_points + sum(len(part.points) for part in curves)
    feature, isolated = _point_features(domain.points, placed.points, ring_vertices, curve_vertices, n_line_points)
    samples = _Samples.concatenate(rings + curves + isolated)
    samples, curve_members, feature = _merge_coincident_features(samples, curve_members, feature, n_ring_points,
                                                                 tol)
    smooth_at = np.asarray(smooth_at, dtype=float).reshape(-1, 2)
    smoothed = _chamfer_points(samples, corner_angle) if chamfers else np.zeros(len(samples.ring), dtype=bool)
    smoothed |= _soft_at(samples, corner_angle, smooth_at, tol)
    is_corner, corner_kind = _corners(samples, curve_members, corner_angle, smoothed)
    for a in (*samples, is_corner, corner_kind, feature):
        a.setflags(write=False)
    return Discretisation(
        domain, spacing, h, samples.points, samples.ring, samples.index, is_corner, corner_kind, samples.turning,
        samples.is_vertex, rings=tuple(ring_members), curves=tuple(curve_members), feature_points=feature,
        chamfers=chamfers, smoothed=np.flatnonzero(smoothed & ~is_corner), smooth_at=smooth_at,
        soft_runs=_soft_runs(samples, corner_angle),
    )


def _checked_parameters(spacing, corner_angle) -> tuple[float, float]:
    """The spacing and corner angle as numbers in their ranges, or a :class:`DomainError`."""
    try:
        spacing, corner_angle = float(spacing), float(corner_angle)
    except (TypeError, ValueError):
        raise DomainError(f"spacing {spacing!r} and corner_angle {corner_angle!r} must be numbers") from None
    if not (0.0 < spacing <= SPACING_MAX) or not np.isfinite(spacing):
        raise DomainError(
            f"spacing {spacing:g} is out of range: it is a fraction of the bounding-box diagonal "
            f"and must lie in (0, {SPACING_MAX}] (useful values {SPACING_RANGE[0]} to {SPACING_RANGE[1]})"
        )
    if not (0.0 <= corner_angle < 180.0):
        raise DomainError(f"corner_angle {corner_angle:g} must lie in [0, 180) degrees")
    return spacing, corner_angle


# --------------------------------------------------------------------------------------------
# Feature points on rings and curves (§4.1, §4.2)
# --------------------------------------------------------------------------------------------


class _Insert(NamedTuple):
    """A point to insert into a polyline: on segment ``seg`` at parameter ``t``."""

    seg: int
    t: float
    p: np.ndarray


class _At(NamedTuple):
    """Where a feature point lies: the vertex ``vertex`` of ring or curve ``owner`` after insertion."""

    on_ring: bool
    owner: int
    vertex: int


class _Placed(NamedTuple):
    """The rings and curves with the feature points that lie on them inserted as vertices."""

    rings: list  # of (n, 2) arrays
    inserted: list  # for each ring, the vertices inserted into it (kept by the thinning of dense runs)
    curves: list
    curve_ends: list  # for each curve, an _At or None for its first and for its last point
    points: list  # for each point feature, an _At or None (a point off every ring and curve)


def _insert_features(domain: Domain, tol: float) -> _Placed:
    """Insert the curve ends lying on a ring into it, the feet of the reflex corners' chords of a
    rectilinear plan (:func:`vaultgram.topology.corners.chord_feet`), then the point features lying
    on a ring or on a curve (§4: they share the point there)."""
    rings = [np.asarray(r) for r in domain.rings]
    curves = [np.asarray(c) for c in domain.curves]
    ring_inserts: list[list[_Insert]] = [[] for _ in rings]
    curve_inserts: list[list[_Insert]] = [[] for _ in curves]
    end_refs = [[_queue(ring_inserts, True, _on_rings(rings, curve[end], tol), curve[end])
                 for end in (0, len(curve) - 1)] for curve in curves]
    point_refs = []
    for foot in chord_feet(rings) if not (len(domain.points) or len(domain.curves)) else ():  # corners.vgr
        _queue(ring_inserts, True, _on_rings(rings, foot, tol), foot)
    for p in domain.points:
        ref = _queue(ring_inserts, True, _on_rings(rings, p, tol), p)
        if ref is None:
            ref = _queue(curve_inserts, False, _on_curves(curves, p, tol), p)
        point_refs.append(ref)
    ring_hits = [_insert(r, ins, tol) for r, ins in zip(rings, ring_inserts)]
    curve_hits = [_insert(c, ins, tol) for c, ins in zip(curves, curve_inserts)]
    hits = {True: [at for _, at in ring_hits], False: [at for _, at in curve_hits]}
    return _Placed([r for r, _ in ring_hits], [at for _, at in ring_hits], [c for c, _ in curve_hits],
                   [[_resolved(ref, hits) for ref in refs] for refs in end_refs],
                   [_resolved(ref, hits) for ref in point_refs])


def _on_rings(rings: list, p: np.ndarray, tol: float) -> tuple[int, int, float] | None:
    """``(ring, segment, t)`` of the ring nearest to ``p`` if it lies on one (within ``tol``)."""
    best = None
    for r, ring in enumerate(rings):
        d, seg, t = locate_on_polyline(ring, p, closed=True)
        if d <= tol and (best is None or d < best[0]):
            best = (d, r, seg, t)
    return None if best is None else best[1:]


def _on_curves(curves: list, p: np.ndarray, tol: float) -> tuple[int, int, float] | None:
    """``(curve, segment, t)`` of the first curve ``p`` lies on (within ``tol``)."""
    for c, curve in enumerate(curves):
        d, seg, t = locate_on_polyline(curve, p, closed=False)
        if d <= tol:
            return c, seg, t
    return None


def _queue(inserts: list, on_ring: bool, hit, p: np.ndarray) -> _At | None:
    """Queue ``p`` for insertion into a ring or curve where ``hit`` says (``(owner, segment, t)``);
    its reference holds the position in the owner's queue until :func:`_insert` says the vertex."""
    if hit is None:
        return None
    owner, seg, t = hit
    inserts[owner].append(_Insert(seg, t, p.copy()))
    return _At(on_ring, owner, len(inserts[owner]) - 1)


def _resolved(ref: _At | None, hits: dict) -> _At | None:
    """A queued point's reference with its vertex after insertion (``hits[on_ring][owner][k]``)."""
    return None if ref is None else ref._replace(vertex=hits[ref.on_ring][ref.owner][ref.vertex])


def _insert(poly: np.ndarray, inserts: list, tol: float) -> tuple[np.ndarray, list[int]]:
    """Insert points into a polyline; return the new polyline and each insert's vertex index.

    A point within ``tol`` of a vertex of its segment is that vertex; the others are inserted in
    order along their segments.
    """
    n = len(poly)
    if not inserts:
        return poly, []
    resolved = []  # ("v", vertex) or ("n", index into new)
    new = []
    for ins in inserts:
        nxt = (ins.seg + 1) % n
        if np.hypot(*(poly[ins.seg] - ins.p)) <= tol:
            resolved.append(("v", ins.seg))
        elif np.hypot(*(poly[nxt] - ins.p)) <= tol:
            resolved.append(("v", nxt))
        else:
            resolved.append(("n", len(new)))
            new.append(ins)
    if not new:
        return poly, [r[1] for r in resolved]
    order = sorted(range(len(new)), key=lambda i: (new[i].seg, new[i].t))
    rows, kinds = [], []
    j = 0
    for v in range(n):
        rows.append(poly[v])
        kinds.append(("v", v))
        while j < len(order) and new[order[j]].seg == v:
            rows.append(new[order[j]].p)
            kinds.append(("n", order[j]))
            j += 1
    pos = {k: i for i, k in enumerate(kinds)}
    return np.array(rows), [pos[r] for r in resolved]


# --------------------------------------------------------------------------------------------
# Sampling (§3.1)
# --------------------------------------------------------------------------------------------


class _Samples(NamedTuple):
    """Sample points with their per-point labels (see :class:`Discretisation`)."""

    points: np.ndarray
    ring: np.ndarray
    index: np.ndarray
    turning: np.ndarray
    is_vertex: np.ndarray

    @classmethod
    def concatenate(cls, parts: list) -> _Samples:
        """The samples of several rings, curves and points, one after the other."""
        return cls(*(np.concatenate(column) for column in zip(*parts)))

    def subset(self, keep: np.ndarray) -> _Samples:
        """The samples where the mask ``keep`` is true."""
        return _Samples(*(column[keep] for column in self))


def _subdivided(poly: np.ndarray, h: float, closed: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A ring or curve split to the spacing ``h``: its points, the positions of its input vertices,
    the turning angle at each point (0 between input vertices) and the mask of input vertices."""
    out, at = subdivide_polyline(poly, h, closed=closed)
    turning = np.zeros(len(out))
    turning[at] = turning_angles(poly, closed=closed)
    is_vertex = np.zeros(len(out), dtype=bool)
    is_vertex[at] = True
    return out, at, turning, is_vertex


def _sample_rings(rings: list, inserted: list, h: float
                  ) -> tuple[list[_Samples], list[np.ndarray], list[np.ndarray]]:
    """Every ring, thinned where its vertices are much denser than the spacing
    (:func:`vaultgram.geometry.polylines.thinned_dense_runs`; inserted feature points stay),
    subdivided to the spacing, numbered in order from 0.

    Returns the samples of each ring, the point indices of each ring, and the point index of each
    ring vertex (-1 for a vertex the thinning dropped).
    """
    samples, members, vertices = [], [], []
    offset = 0
    for r, (ring, keep_also) in enumerate(zip(rings, inserted)):
        keep = thinned_dense_runs(ring, h * DENSE_RUN, h * THINNING_TOLERANCE, BOUNDARY_FIDELITY_ANGLE)
        keep[list(keep_also)] = True
        out, at, turning, is_vertex = _subdivided(ring[keep], h, closed=True)
        samples.append(_Samples(out, np.full(len(out), r, dtype=np.int64), np.arange(len(out)), turning, is_vertex))
        members.append(np.arange(offset, offset + len(out)))
        vertex = np.full(len(ring), -1, dtype=np.int64)
        vertex[keep] = at + offset
        vertices.append(vertex)
        offset += len(out)
    return samples, members, vertices


def _sample_curves(placed: _Placed, ring_vertices: list, h: float, offset: int
                   ) -> tuple[list[_Samples], list[np.ndarray], list[np.ndarray]]:
    """Every curve subdivided to the spacing and numbered from ``offset``, an end point on a ring
    being that ring's point (§4.2).

    Returns the samples of each curve (without the ring points), the point indices of each curve,
    and the point index of each curve vertex.
    """
    samples, members, vertices = [], [], []
    for curve, ends in zip(placed.curves, placed.curve_ends):
        out, at, turning, is_vertex = _subdivided(curve, h, closed=False)
        glob = np.arange(offset, offset + len(out))
        keep = np.ones(len(out), dtype=bool)
        for end, on_ring in zip((0, len(out) - 1), ends):
            if on_ring is not None:
                glob[end] = ring_vertices[on_ring.owner][on_ring.vertex]
                keep[end] = False
        n_kept = int(keep.sum())
        glob[keep] = np.arange(offset, offset + n_kept)
        samples.append(_Samples(out[keep], np.full(n_kept, RING_CURVE, dtype=np.int64), np.flatnonzero(keep),
                                turning[keep], is_vertex[keep]))
        members.append(glob)
        vertices.append(glob[at])
        offset += n_kept
    return samples, members, vertices


def _point_features(points: np.ndarray, where: list, ring_vertices: list, curve_vertices: list, offset: int
                    ) -> tuple[np.ndarray, list[_Samples]]:
    """The point index of each point feature (§4.1): its ring or curve point (``where`` it lies, see
    :class:`_Placed`), or a point of its own, numbered from ``offset``. Returns the indices and the
    samples of the points of their own."""
    feature = np.empty(len(points), dtype=np.int64)
    own = []
    for i, (p, at) in enumerate(zip(points, where)):
        if at is None:
            feature[i] = offset + len(own)
            own.append(p)
        else:
            feature[i] = (ring_vertices if at.on_ring else curve_vertices)[at.owner][at.vertex]
    if not own:
        return feature, []
    k = len(own)
    return feature, [_Samples(np.array(own), np.full(k, RING_POINT, dtype=np.int64), np.zeros(k, dtype=np.int64),
                              np.zeros(k), np.ones(k, dtype=bool))]


def _merge_coincident_features(samples: _Samples, curves: list, feature: np.ndarray, n_ring_points: int,
                               tol: float) -> tuple[_Samples, list, np.ndarray]:
    """Merge curve and point features coinciding with another feature point (two curves sharing an
    end point, a point feature at a curve's end), so that the Delaunay sites are distinct."""
    n = len(samples.points)
    if n <= n_ring_points:
        return samples, curves, feature
    remap = np.arange(n)
    pairs = close_pairs(samples.points, tol)
    if len(pairs):
        pairs = pairs[pairs[:, 1] >= n_ring_points]
        for a, b in pairs[np.lexsort((pairs[:, 0], pairs[:, 1]))]:
            remap[b] = remap[a] if remap[a] == a else remap[remap[a]]
    keep = remap == np.arange(n)
    if keep.all():
        return samples, curves, feature
    final = (np.cumsum(keep) - 1)[remap]
    return samples.subset(keep), [final[c] for c in curves], final[feature]


def _chamfer_points(samples: _Samples, corner_angle: float) -> np.ndarray:
    """The ring vertices of chamfers: vertices turning towards the domain by ``corner_angle`` to
    :data:`CONVEX_TURN` degrees (interior angles of 135 to 150 degrees) in a run of such vertices
    (consecutive along the ring, points on a straight stretch aside) that ends next to a sharper
    convex corner: a plan's corner cut off by one or more short walls (the two 135 degree vertices
    of a rectangle's cut corner) or eased by a softer bend next to it. The regular valence makes
    each one a smooth boundary point with two faces (issue 12: "a 150 degree corner is a smooth
    boundary point, not a patch corner"); as a patch corner it would be the corner of one quad of
    135-150 degrees, a boundary singularity. Runs that end at no sharper corner (a rounded tip, a
    polygon of soft corners only, which the O-grid rules take) stay corners.

    >>> ring = np.zeros(7, dtype=int)
    >>> turning = np.array([90.0, 40.0, 0.0, 40.0, 20.0, 40.0, 20.0])  # a chamfer of two; a lone 140
    >>> samples = _Samples(np.zeros((7, 2)), ring, np.arange(7), turning, np.ones(7, bool))
    >>> np.flatnonzero(_chamfer_points(samples, 30.0)).tolist()
    [1, 3]
    """
    at, soft = _soft_vertices(samples, corner_angle)
    turning, ring = samples.turning[at], samples.ring[at]
    out = np.zeros(len(samples.ring), dtype=bool)
    for r in distinct(ring[soft]):
        on = ring == r
        out[at[on]] = _anchored_runs(soft[on], turning[on] > CONVEX_TURN + ANGLE_TOLERANCE)
    return out


def _soft_vertices(samples: _Samples, corner_angle: float) -> tuple[np.ndarray, np.ndarray]:
    """The ring vertices that turn (points on a straight stretch aside), in ring order, and which
    of them turn towards the domain by ``corner_angle`` to :data:`CONVEX_TURN` degrees (interior
    angles of 135 to 150: regular with two faces, issue 12)."""
    at = np.flatnonzero((samples.ring >= 0) & samples.is_vertex & (np.abs(samples.turning) > STRAIGHT_TURN))
    turning = samples.turning[at]
    return at, (turning > corner_angle) & (turning <= CONVEX_TURN + ANGLE_TOLERANCE)


def _soft_at(samples: _Samples, corner_angle: float, points: np.ndarray, tol: float) -> np.ndarray:
    """The mask of the 135 to 150 degree ring vertices (:func:`_soft_vertices`) within ``tol`` of
    one of ``points``."""
    at, soft = _soft_vertices(samples, corner_angle)
    out = np.zeros(len(samples.ring), dtype=bool)
    if len(points):
        at = at[soft]
        near = np.hypot(*(samples.points[at][:, None, :] - points[None, :, :]).transpose(2, 0, 1)) <= tol
        out[at[near.any(axis=1)]] = True
    return out


def _soft_runs(samples: _Samples, corner_angle: float) -> tuple:
    """The runs of 135 to 150 degree ring vertices (:attr:`Discretisation.soft_runs`), ring by ring,
    each as its point indices in ring order from the run's first vertex; not a ring whose every
    corner is such (alike corners, as :func:`_chamfer_points` leaves them: the O-grid's plan, whose
    ring of patches has them on its sides already).

    >>> ring = np.array([0] * 7 + [1] * 3)
    >>> turning = np.array([40.0, 90.0, 40.0, 35.0, 0.0, 20.0, 40.0, 40.0, 40.0, 40.0])
    >>> samples = _Samples(np.zeros((10, 2)), ring, np.arange(10), turning, np.ones(10, bool))
    >>> [run.tolist() for run in _soft_runs(samples, 30.0)]  # one run wraps round; ring 1 all soft
    [[2, 3], [6, 0]]
    """
    at, soft = _soft_vertices(samples, corner_angle)
    runs = []
    for r in distinct(samples.ring[at][soft]):
        on = samples.ring[at] == r
        if not soft[on].all():
            runs += [at[on][run] for run in _closed_runs(soft[on])]
    return tuple(runs)


def _closed_runs(mask: np.ndarray) -> list:
    """The runs of consecutive true entries of a closed sequence with a false entry, as index arrays
    in order (a run across the end continues at the start).

    >>> [run.tolist() for run in _closed_runs(np.array([1, 0, 1, 1, 0, 1], bool))]
    [[2, 3], [5, 0]]
    """
    n = len(mask)
    shift = int(np.flatnonzero(~mask)[0]) + 1  # the sequence from just after a false entry
    order = np.roll(np.arange(n), -shift)
    rolled = mask[order]
    starts = np.flatnonzero(rolled & ~np.concatenate([[False], rolled[:-1]]))
    ends = np.flatnonzero(rolled & ~np.concatenate([rolled[1:], [False]])) + 1
    return [order[a:b] for a, b in zip(starts, ends)]


def _anchored_runs(soft: np.ndarray, sharp: np.ndarray) -> np.ndarray:
    """In a closed sequence, the ``soft`` entries whose run of consecutive soft entries has a
    ``sharp`` entry just before or just after it (cyclically); none if every entry is soft.

    >>> _anchored_runs(np.array([0, 1, 1, 0, 1, 0, 1], bool), np.array([1, 0, 0, 0, 0, 0, 0], bool)).tolist()
    [False, True, True, False, False, False, True]
    """
    n = len(soft)
    if soft.all():
        return np.zeros(n, dtype=bool)
    k = np.arange(n)
    hard = np.flatnonzero(~soft)
    before = np.maximum.accumulate(np.where(soft, -1, k))
    before = np.where(before < 0, hard[-1], before)
    after = np.minimum.accumulate(np.where(soft, n, k)[::-1])[::-1]
    after = np.where(after >= n, hard[0], after)
    return soft & (sharp[before] | sharp[after])


def _corners(samples: _Samples, curves: list, corner_angle: float, smoothed: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray]:
    """Ring points turning by more than ``corner_angle`` are corners (but those ``smoothed``, a
    chamfer's), convex (1) when the ring turns towards the domain, reflex (-1) otherwise. Curve
    features cut the domain (§4.2): where a curve meets a ring, and where a curve turns sharply, the
    regions on either side see a convex corner."""
    ring, turning = samples.ring, samples.turning
    is_corner = (ring >= 0) & (np.abs(turning) > corner_angle) & ~smoothed
    corner_kind = np.zeros(len(ring), dtype=np.int8)
    corner_kind[is_corner & (turning > 0)] = 1
    corner_kind[is_corner & (turning < 0)] = -1
    sharp = (ring == RING_CURVE) & (np.abs(turning) > corner_angle)
    ends = np.array([i for c in curves for i in (c[0], c[-1]) if ring[i] >= 0], dtype=np.int64)
    for cut in (np.flatnonzero(sharp), ends):
        is_corner[cut] = True
        corner_kind[cut] = 1
    return is_corner, corner_kind
