"""Validation of a domain: valid rings and features (§3.1, §4), and features against the spacing.

:func:`validate_domain` checks what every domain must satisfy; every loader runs it, so a
:class:`~vaultgram.domain.model.Domain` that exists is valid. :func:`check_feature_spacing` checks
what depends on the discretisation spacing chosen for it: features far enough apart and from the
boundary. Every problem is a :class:`~vaultgram.errors.DomainError` naming the ring or feature, the
vertex index and the coordinates.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import shapely

from vaultgram.domain.model import Domain, ring_name
from vaultgram.errors import DomainError
from vaultgram.geometry.polygons import signed_area
from vaultgram.geometry.polylines import locate_on_polyline
from vaultgram.geometry.spatial import close_pairs
from vaultgram.geometry.text import fmt_point

__all__ = ["validate_domain", "check_feature_spacing", "check_finite", "FEATURE_CLEARANCE"]

#: Features (§4) must be at least this many discretisation spacings ``h = spacing * diagonal`` from
#: the boundary and from each other: closer, the Delaunay triangulation has no room for the skeleton
#: between them and the patches in the gap degenerate.
FEATURE_CLEARANCE = 1.0


# --------------------------------------------------------------------------------------------
# validate_domain: what every domain must satisfy
# --------------------------------------------------------------------------------------------


def validate_domain(domain: Domain) -> None:
    """Check that ``domain`` is a valid vault domain; raise :class:`DomainError` naming the problem.

    Checks, in order: at least 3 distinct vertices per ring, finite coordinates, no duplicate or
    near-duplicate vertices in a ring (tolerance :attr:`Domain.tolerance`, consecutive or not),
    simple rings (no self-intersection, the two segments are named), non-zero area, holes strictly
    inside the outer ring and disjoint from each other (no touching), point features inside the
    domain or on its boundary (not outside, not inside a hole, not duplicated), curve features
    simple and inside the domain, touching the boundary only at their end points.

    Example
    -------
    >>> bowtie = Domain("bowtie", np.array([[0.0, 0.0], [10.0, 10.0], [10.0, 0.0], [0.0, 10.0]]))
    >>> validate_domain(bowtie)
    Traceback (most recent call last):
    ...
    vaultgram.errors.DomainError: outer ring, vertex 0: ring self-intersects at (5, 5) (segments 0-1 and 2-3 intersect)
    """
    tol = domain.tolerance
    for r, ring in enumerate(domain.rings):
        _check_ring(ring, ring_name(r), tol, domain.diagonal)
    shapes = _Shapes.of(domain)
    _check_holes_inside_outer(domain.holes, shapes)
    _check_holes_apart(domain.holes, shapes, tol * domain.diagonal)
    _check_point_features(domain.points, shapes, tol)
    lines = [_check_curve_feature(f"curve feature {c}", curve, shapes, tol) for c, curve in enumerate(domain.curves)]
    _check_curves_apart(domain.curves, lines, tol)


class _Shapes(NamedTuple):
    """The shapely geometry of a domain whose rings are each valid, for the checks between them."""

    outer: shapely.Polygon  # the outer ring alone (prepared)
    outer_line: shapely.LinearRing
    holes: list  # one Polygon per hole
    hole_lines: list  # one LinearRing per hole
    domain: shapely.Polygon  # the outer ring with its holes (prepared)
    boundary: shapely.Geometry  # every ring

    @classmethod
    def of(cls, domain: Domain) -> _Shapes:
        """The shapes of ``domain`` (its rings already checked one by one)."""
        outer = shapely.Polygon(domain.outer)
        shapely.prepare(outer)
        poly = domain.polygon()
        shapely.prepare(poly)
        return cls(outer, shapely.LinearRing(domain.outer), [shapely.Polygon(h) for h in domain.holes],
                   [shapely.LinearRing(h) for h in domain.holes], poly, poly.boundary)


def check_finite(arr: np.ndarray, what: str) -> None:
    """Raise a :class:`DomainError` naming the first vertex of ``arr`` with a coordinate that is not finite."""
    i = _first_not_finite(arr)
    if i is not None:
        raise DomainError(f"{what}, vertex {i}: coordinate is not finite {fmt_point(arr[i], 10)}")


def _first_not_finite(arr: np.ndarray) -> int | None:
    """Index of the first point of ``arr`` with a coordinate that is not finite, or None."""
    bad = np.flatnonzero(~np.isfinite(arr).all(axis=1))
    return int(bad[0]) if len(bad) else None


def _check_ring(ring: np.ndarray, what: str, tol: float, diagonal: float) -> None:
    """One ring: finite, at least 3 distinct vertices, simple, with an area."""
    _check_polyline(ring, what, closed=True, tol=tol)
    if abs(signed_area(ring)) <= tol * diagonal:
        raise DomainError(f"{what}, vertex 0: ring has zero area")


def _check_polyline(pts: np.ndarray, what: str, closed: bool, tol: float) -> None:
    """A ring (``closed``) or a curve feature: pairs of finite coordinates, enough vertices, none
    repeated, no self-intersection."""
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise DomainError(f"{what}: expected a list of [x, y] pairs")
    check_finite(pts, what)
    least = 3 if closed else 2
    if len(pts) < least:
        raise DomainError(f"{what}: needs at least {least} distinct vertices, got {len(pts)}")
    _check_duplicates(pts, what, tol)
    _check_no_spike(pts, what, closed)
    _check_no_crossing(pts, what, closed)


def _close_pairs(pts: np.ndarray, r: float) -> np.ndarray:
    """The index pairs (i < j) of points within ``r`` of each other (a grid hash,
    :func:`vaultgram.geometry.spatial.close_pairs`)."""
    return close_pairs(pts, r)


def _check_duplicates(pts: np.ndarray, what: str, tol: float) -> None:
    """No two vertices of one ring / curve within ``tol`` (consecutive or not)."""
    pairs = _close_pairs(pts, max(tol, 0.0))
    if len(pairs):
        pairs = np.sort(pairs, axis=1)
        i, j = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))[0]]
        raise DomainError(f"{what}: vertices {i} and {j} coincide at {fmt_point(pts[i], 10)}")


def _segments(pts: np.ndarray, closed: bool) -> np.ndarray:
    """The segments of a ring (``closed``) or an open polyline as shapely line strings."""
    nxt = np.roll(pts, -1, axis=0) if closed else pts[1:]
    a = pts if closed else pts[:-1]
    return shapely.linestrings(np.stack([a, nxt], axis=1))


def _check_no_spike(pts: np.ndarray, what: str, closed: bool) -> None:
    """No two consecutive segments fold back onto each other (collinear, opposite directions)."""
    n = len(pts)
    idx = np.arange(n if closed else n - 1)
    d = pts[(idx + 1) % n] - pts[idx]
    d_next = np.roll(d, -1, axis=0)
    cross = d[:, 0] * d_next[:, 1] - d[:, 1] * d_next[:, 0]
    dot = (d * d_next).sum(axis=1)
    length = np.hypot(d[:, 0], d[:, 1]) * np.hypot(d_next[:, 0], d_next[:, 1])
    spike = (np.abs(cross) <= 1e-12 * length) & (dot < 0)
    if not closed:
        spike[-1] = False
    if spike.any():
        i = int(np.flatnonzero(spike)[0])
        j = (i + 1) % n
        kind, after = ("ring", (j + 1) % n) if closed else ("curve", j + 1)
        raise DomainError(
            f"{what}, vertex {j}: {kind} self-intersects at {fmt_point(pts[j], 10)} "
            f"(segments {i}-{j} and {j}-{after} fold back onto each other)"
        )


def _check_no_crossing(pts: np.ndarray, what: str, closed: bool) -> None:
    """No two segments intersect, except consecutive ones at their shared vertex."""
    n = len(pts)
    nseg = n if closed else n - 1
    segs = _segments(pts, closed)
    a, b = shapely.STRtree(segs).query(segs, predicate="intersects")
    keep = a < b
    a, b = a[keep], b[keep]
    adjacent = (b == a + 1) | (closed & (a == 0) & (b == nseg - 1))
    a, b = a[~adjacent], b[~adjacent]
    if len(a):
        order = np.lexsort((b, a))
        i, j = int(a[order[0]]), int(b[order[0]])
        p = _touch_point(segs[i], segs[j])
        kind = "ring" if closed else "curve"
        raise DomainError(
            f"{what}, vertex {i}: {kind} self-intersects at {fmt_point(p, 10)} "
            f"(segments {i}-{(i + 1) % n} and {j}-{(j + 1) % n} intersect)"
        )


def _touch_point(g1, g2) -> np.ndarray:
    """The first point where two geometries meet."""
    return np.asarray(shapely.get_coordinates(shapely.intersection(g1, g2)))[0]


def _check_holes_inside_outer(holes: tuple, shapes: _Shapes) -> None:
    """Every hole strictly inside the outer ring: not touching it, not crossing it, not outside it."""
    for k, (h, hp, hl) in enumerate(zip(holes, shapes.holes, shapes.hole_lines)):
        what = f"hole {k}"
        if shapely.intersects(hl, shapes.outer_line):
            p = _touch_point(hl, shapes.outer_line)
            i = locate_on_polyline(h, p, closed=True)[1]
            verb = "touches" if shapely.covered_by(hp, shapes.outer) else "crosses"
            raise DomainError(
                f"{what}, vertex {i}: {verb} the outer ring at {fmt_point(p, 10)} "
                f"(segment {i}-{(i + 1) % len(h)})"
            )
        outside = np.flatnonzero(~shapely.contains_xy(shapes.outer, h[:, 0], h[:, 1]))
        if len(outside):
            i = int(outside[0])
            raise DomainError(f"{what}, vertex {i}: lies outside the outer ring at {fmt_point(h[i], 10)}")


def _check_holes_apart(holes: tuple, shapes: _Shapes, area_tol: float) -> None:
    """No two holes overlap, touch, or lie one inside the other."""
    polys, lines = shapes.holes, shapes.hole_lines
    for k in range(len(polys)):
        for m in range(k + 1, len(polys)):
            hk, hm = holes[k], holes[m]
            if not shapely.intersects(polys[k], polys[m]):
                continue
            if shapely.intersects(lines[k], lines[m]):
                p = _touch_point(lines[k], lines[m])
                i = locate_on_polyline(hm, p, closed=True)[1]
                overlap = shapely.area(shapely.intersection(polys[k], polys[m]))
                verb = "overlaps" if overlap > area_tol else "touches"
                raise DomainError(
                    f"hole {m}, vertex {i}: {verb} hole {k} at {fmt_point(p, 10)} "
                    f"(segment {i}-{(i + 1) % len(hm)})"
                )
            if shapely.contains(polys[k], polys[m]):
                raise DomainError(f"hole {m}, vertex 0: lies inside hole {k} at {fmt_point(hm[0], 10)}")
            raise DomainError(f"hole {k}, vertex 0: lies inside hole {m} at {fmt_point(hk[0], 10)}")


def _check_point_features(pts: np.ndarray, shapes: _Shapes, tol: float) -> None:
    """Point features (§4.1): finite, inside the domain or on its boundary, not in a hole, distinct."""
    if not len(pts):
        return
    i = _first_not_finite(pts)
    if i is not None:
        raise DomainError(f"point feature {i}: coordinate is not finite {fmt_point(pts[i], 10)}")
    on_boundary = shapely.distance(shapely.points(pts), shapes.boundary) <= tol
    inside = shapely.contains_xy(shapes.domain, pts[:, 0], pts[:, 1]) | on_boundary
    if not inside.all():
        i = int(np.flatnonzero(~inside)[0])
        p = pts[i]
        for k, hp in enumerate(shapes.holes):
            if shapely.contains_xy(hp, p[0], p[1]):
                raise DomainError(f"point feature {i} at {fmt_point(p, 10)} lies inside hole {k}")
        raise DomainError(f"point feature {i} at {fmt_point(p, 10)} lies outside the domain")
    pairs = _close_pairs(pts, tol)
    if len(pairs):
        i, j = np.sort(pairs, axis=1)[0]
        raise DomainError(f"point features {i} and {j} coincide at {fmt_point(pts[i], 10)}")


def _check_curve_feature(what: str, curve: np.ndarray, shapes: _Shapes, tol: float) -> shapely.LineString:
    """A curve feature (§4.2): a simple polyline inside the domain, on the boundary only at its ends.

    Returns its line string, for :func:`_check_curves_apart`.
    """
    _check_polyline(curve, what, closed=False, tol=tol)
    on_boundary = shapely.distance(shapely.points(curve), shapes.boundary) <= tol
    segs = _segments(curve, closed=False)
    _check_curve_inside(what, curve, segs, on_boundary, shapes)
    _check_curve_off_boundary(what, curve, segs, on_boundary, shapes.boundary, tol)
    return shapely.LineString(curve)


def _check_curve_inside(what: str, curve: np.ndarray, segs: np.ndarray, on_boundary: np.ndarray,
                        shapes: _Shapes) -> None:
    """Every vertex inside the domain or on its boundary, and no segment leaving it or crossing a hole."""
    inside = shapely.contains_xy(shapes.domain, curve[:, 0], curve[:, 1]) | on_boundary
    if not inside.all():
        i = int(np.flatnonzero(~inside)[0])
        _raise_curve_outside(what, i, curve[i], shapes.holes)
    covered = shapely.covered_by(segs, shapes.domain)
    if not covered.all():
        i = int(np.flatnonzero(~covered)[0])
        outside = shapely.difference(segs[i], shapes.domain)
        p = np.asarray(shapely.get_coordinates(shapely.point_on_surface(outside)))[0]
        _raise_curve_outside(what, i, p, shapes.holes, segment=(i, i + 1))


def _raise_curve_outside(what, i, p, hole_polys, segment=None):
    """The error for a curve feature outside the domain at ``p``: in a hole, or beyond the outer ring."""
    seg = f" (segment {segment[0]}-{segment[1]})" if segment else ""
    for k, hp in enumerate(hole_polys):
        if shapely.intersects(hp, shapely.Point(p)):
            raise DomainError(f"{what}, vertex {i}: crosses hole {k} at {fmt_point(p, 10)}{seg}")
    raise DomainError(f"{what}, vertex {i}: leaves the domain at {fmt_point(p, 10)}{seg}")


def _check_curve_off_boundary(what: str, curve: np.ndarray, segs: np.ndarray, on_boundary: np.ndarray,
                              boundary, tol: float) -> None:
    """Only the end points of a curve feature may lie on the boundary: no other vertex, no segment."""
    interior_touch = on_boundary.copy()
    interior_touch[[0, -1]] = False
    if interior_touch.any():
        i = int(np.flatnonzero(interior_touch)[0])
        raise DomainError(
            f"{what}, vertex {i}: touches the domain boundary at {fmt_point(curve[i], 10)} "
            "(only the end points of a curve feature may lie on the boundary)"
        )
    inter = shapely.get_coordinates(shapely.intersection(shapely.LineString(curve), boundary))
    if len(inter):
        dd = _distance_to_nearest(inter, curve[[0, -1]])
        if (dd > tol).any():
            p = inter[int(np.argmax(dd))]
            i = int(np.argmin(shapely.distance(segs, shapely.Point(p))))
            raise DomainError(
                f"{what}, vertex {i}: touches the domain boundary at {fmt_point(p, 10)} "
                f"(segment {i}-{i + 1}; only the end points may lie on the boundary)"
            )


def _distance_to_nearest(points: np.ndarray, others: np.ndarray) -> np.ndarray:
    """For each of ``points``, its distance to the nearest of a few ``others``."""
    return np.min(np.hypot(*(points[:, None, :] - others[None, :, :]).transpose(2, 0, 1)), axis=1)


def _check_curves_apart(curves: tuple, lines: list, tol: float) -> None:
    """Curve features meet at most at one shared end point; they never cross."""
    for a in range(len(lines)):
        for b in range(a + 1, len(lines)):
            if not shapely.intersects(lines[a], lines[b]):
                continue
            inter = shapely.get_coordinates(shapely.intersection(lines[a], lines[b]))
            dd = _distance_to_nearest(inter, np.concatenate([curves[a][[0, -1]], curves[b][[0, -1]]]))
            if (dd > tol).any() or len(inter) > 1:
                p = inter[int(np.argmax(dd))]
                i = int(np.argmin(shapely.distance(_segments(curves[b], False), shapely.Point(p))))
                raise DomainError(
                    f"curve feature {b}, vertex {i}: crosses curve feature {a} at {fmt_point(p, 10)}"
                )


# --------------------------------------------------------------------------------------------
# check_feature_spacing: what depends on the discretisation spacing
# --------------------------------------------------------------------------------------------


def check_feature_spacing(domain: Domain, spacing: float, clearance: float = FEATURE_CLEARANCE) -> None:
    """Raise a :class:`DomainError` if a feature is too close to the boundary or to another feature
    for the discretisation spacing (§3.1, §4).

    Inner point features and curve features must be at least ``clearance * h`` (``h = spacing *
    diagonal``) from the domain's boundary and from each other. What touches on purpose is not
    measured: boundary point features; a curve's end on the boundary (the curve is measured outside a
    disc of radius ``2 h`` around it, so that a curve leaving the boundary at 30 degrees or more
    passes); a point feature on a curve; curves sharing an end point (likewise, outside ``2 h``).

    Raises
    ------
    DomainError
        Naming the features, where they are closest, the distance and the spacing.

    Example
    -------
    >>> from vaultgram.domain import load_domain
    >>> fig6 = load_domain("examples/fig6_inner_points.json")
    >>> check_feature_spacing(fig6, 0.02)  # room enough: no error
    >>> check_feature_spacing(fig6, 0.2)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    vaultgram.errors.DomainError: point feature 0 at (1.5, 5) is 1.5 from the boundary (closest at ...), less than ...
    """
    boundary = domain.polygon().boundary
    features = _spaced_features(domain, boundary)
    gap = _Clearance(spacing, domain.diagonal, clearance)
    for f in features:
        gap.check(f.name, gap.trimmed(f.geom, f.ends), "the boundary", boundary)
    ends = [e for f in features for e in f.ends]
    tol = domain.tolerance
    for k, f in enumerate(features):
        for g in features[k + 1:]:
            if _point_on_curve(f.geom, g.geom, tol):
                continue  # a point feature on a curve is a point of the curve
            shared = _shared_ends(f.geom, g.geom, ends, tol)
            gap.check(g.name, gap.trimmed(g.geom, shared), f.name, gap.trimmed(f.geom, shared))


class _Spaced(NamedTuple):
    """A feature measured by :func:`check_feature_spacing`: its name in messages, its geometry, and
    the end points where it touches the boundary on purpose."""

    name: str
    geom: shapely.Geometry
    ends: list


def _spaced_features(domain: Domain, boundary) -> list[_Spaced]:
    """The inner point features (boundary point features touch on purpose), then every curve feature
    with its end points on the boundary."""
    tol = domain.tolerance
    out = []
    for i, p in enumerate(np.asarray(domain.points, dtype=float).reshape(-1, 2)):
        if shapely.distance(shapely.Point(p), boundary) > tol:
            out.append(_Spaced(f"point feature {i} at {fmt_point(p)}", shapely.Point(p), []))
    for c, curve in enumerate(domain.curves):
        curve = np.asarray(curve, dtype=float)
        ends = [e for e in (curve[0], curve[-1]) if shapely.distance(shapely.Point(e), boundary) <= tol]
        out.append(_Spaced(f"curve feature {c}", shapely.LineString(curve), [shapely.Point(e) for e in ends]))
    return out


def _point_on_curve(a, b, tol: float) -> bool:
    """Whether one of two features is a point lying on the other, a curve."""
    kinds = (isinstance(a, shapely.Point), isinstance(b, shapely.Point))
    lines = (isinstance(a, shapely.LineString), isinstance(b, shapely.LineString))
    return ((kinds[0] and lines[1]) or (kinds[1] and lines[0])) and shapely.distance(a, b) <= tol


def _shared_ends(a, b, ends: list, tol: float) -> list:
    """Where two features touch on purpose: boundary end points on both, and where two curves meet."""
    shared = [e for e in ends if shapely.distance(e, a) <= tol and shapely.distance(e, b) <= tol]
    if isinstance(a, shapely.LineString) and isinstance(b, shapely.LineString):
        shared += [shapely.Point(q) for q in shapely.get_coordinates(shapely.intersection(a, b))]
    return shared


class _Clearance(NamedTuple):
    """The clearance features need for a spacing: ``clearance * h``, ``h = spacing * diagonal``."""

    spacing: float
    diagonal: float
    clearance: float

    @property
    def h(self) -> float:
        """The absolute spacing."""
        return self.spacing * self.diagonal

    def trimmed(self, geom, around: list):
        """``geom`` outside discs of radius ``2 h`` around the points where it touches on purpose."""
        if not around:
            return geom
        return shapely.difference(geom, shapely.union_all([e.buffer(2 * self.h) for e in around]))

    def check(self, name: str, geom, other_name: str, other) -> None:
        """Raise if ``geom`` (called ``name``) is closer than the clearance to ``other``."""
        if geom.is_empty or other.is_empty:
            return
        need = self.clearance * self.h
        d = shapely.distance(geom, other)
        if d < need:
            a, b = shapely.get_coordinates(shapely.shortest_line(geom, other))
            raise DomainError(
                f"{name} is {d:.4g} from {other_name} (closest at {fmt_point(a)} and {fmt_point(b)}), less than the "
                f"spacing {need:.4g} (spacing {self.spacing:g} of the diagonal {self.diagonal:.4g}): move it, or "
                f"mesh with a spacing below {d / (self.clearance * self.diagonal):.3g}"
            )
