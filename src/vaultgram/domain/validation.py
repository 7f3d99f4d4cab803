"""Validation of a domain: valid rings and features (§3.1, §4), and features against the spacing.

:func:`validate_domain` checks what every domain must satisfy; every loader runs it, so a
:class:`~vaultgram.domain.model.Domain` that exists is valid. :func:`check_feature_spacing` checks
what depends on the discretisation spacing chosen for it: features far enough apart and from the
boundary. Every problem is a :class:`~vaultgram.errors.DomainError` naming the ring or feature, the
vertex index and the coordinates.
"""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from vaultgram.domain.model import Domain, ring_name
from vaultgram.errors import DomainError
from vaultgram.geometry.polygons import signed_area
from vaultgram.geometry.polylines import locate_on_polyline
from vaultgram.geometry.text import fmt_point

__all__ = ["validate_domain", "check_feature_spacing", "FEATURE_CLEARANCE"]

def check_finite(arr: np.ndarray, what: str) -> None:
    bad = ~np.isfinite(arr).all(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DomainError(f"{what}, vertex {i}: coordinate is not finite {fmt_point(arr[i], 10)}")


def _check_duplicates(pts: np.ndarray, what: str, tol: float) -> None:
    """No two vertices of one ring / curve within ``tol`` (consecutive or not)."""
    pairs = cKDTree(pts).query_pairs(r=max(tol, 0.0), output_type="ndarray")
    if len(pairs):
        pairs = np.sort(pairs, axis=1)
        i, j = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))[0]]
        raise DomainError(f"{what}: vertices {i} and {j} coincide at {fmt_point(pts[i], 10)}")


def _segments(pts: np.ndarray, closed: bool) -> np.ndarray:
    nxt = np.roll(pts, -1, axis=0) if closed else pts[1:]
    a = pts if closed else pts[:-1]
    return shapely.linestrings(np.stack([a, nxt], axis=1))


def _check_simple(pts: np.ndarray, what: str, closed: bool, tol: float) -> None:
    """No two segments of a ring / curve intersect, except consecutive ones at their shared vertex."""
    n = len(pts)
    nseg = n if closed else n - 1
    idx = np.arange(nseg)
    nxt = (idx + 1) % n
    # consecutive segments folding back on themselves (a spike): collinear and opposite directions
    d = pts[nxt] - pts[idx]
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
        raise DomainError(
            f"{what}, vertex {j}: ring self-intersects at {fmt_point(pts[j], 10)} "
            f"(segments {i}-{j} and {j}-{(j + 1) % n} fold back onto each other)"
            if closed
            else f"{what}, vertex {j}: curve self-intersects at {fmt_point(pts[j], 10)} "
            f"(segments {i}-{j} and {j}-{j + 1} fold back onto each other)"
        )
    segs = _segments(pts, closed)
    tree = shapely.STRtree(segs)
    a, b = tree.query(segs, predicate="intersects")
    keep = a < b
    a, b = a[keep], b[keep]
    adjacent = (b == a + 1) | (closed & (a == 0) & (b == nseg - 1))
    a, b = a[~adjacent], b[~adjacent]
    if len(a):
        order = np.lexsort((b, a))
        i, j = int(a[order[0]]), int(b[order[0]])
        where = shapely.intersection(segs[i], segs[j])
        p = np.asarray(shapely.get_coordinates(where))[0]
        kind = "ring" if closed else "curve"
        raise DomainError(
            f"{what}, vertex {i}: {kind} self-intersects at {fmt_point(p, 10)} "
            f"(segments {i}-{(i + 1) % n} and {j}-{(j + 1) % n} intersect)"
        )


def _first_vertex(ring: np.ndarray, mask: np.ndarray) -> int:
    idx = np.flatnonzero(mask)
    return int(idx[0]) if len(idx) else 0


def _touch_point(g1, g2) -> np.ndarray:
    inter = shapely.intersection(g1, g2)
    return np.asarray(shapely.get_coordinates(inter))[0]


def validate_domain(domain: Domain) -> None:
    """Check that ``domain`` is a valid vault domain; raise :class:`DomainError` naming the problem.

    Checks, in order: at least 3 distinct vertices per ring, finite coordinates, no duplicate or
    near-duplicate vertices in a ring (tolerance :attr:`Domain.tolerance`, consecutive or not),
    simple rings (no self-intersection, the two segments are named), non-zero area, holes strictly
    inside the outer ring and disjoint from each other (no touching), point features inside the
    domain or on its boundary (not outside, not inside a hole, not duplicated), curve features
    simple and inside the domain, touching the boundary only at their end points.
    """
    tol = domain.tolerance
    rings = domain.rings
    for r, ring in enumerate(rings):
        what = ring_name(r)
        check_finite(ring, what)
        if len(ring) < 3:
            raise DomainError(f"{what}: needs at least 3 distinct vertices, got {len(ring)}")
        _check_duplicates(ring, what, tol)
        _check_simple(ring, what, closed=True, tol=tol)
        if abs(signed_area(ring)) <= tol * domain.diagonal:
            raise DomainError(f"{what}, vertex 0: ring has zero area")

    outer_poly = shapely.Polygon(domain.outer)
    outer_line = shapely.LinearRing(domain.outer)
    hole_polys = [shapely.Polygon(h) for h in domain.holes]
    hole_lines = [shapely.LinearRing(h) for h in domain.holes]
    shapely.prepare(outer_poly)

    for k, (h, hp, hl) in enumerate(zip(domain.holes, hole_polys, hole_lines)):
        what = f"hole {k}"
        if shapely.intersects(hl, outer_line):
            p = _touch_point(hl, outer_line)
            i = locate_on_polyline(h, p, closed=True)[1]
            verb = "touches" if shapely.covered_by(hp, outer_poly) else "crosses"
            raise DomainError(
                f"{what}, vertex {i}: {verb} the outer ring at {fmt_point(p, 10)} "
                f"(segment {i}-{(i + 1) % len(h)})"
            )
        inside = shapely.contains_xy(outer_poly, h[:, 0], h[:, 1])
        if not inside.all():
            i = _first_vertex(h, ~inside)
            raise DomainError(f"{what}, vertex {i}: lies outside the outer ring at {fmt_point(h[i], 10)}")
    for k in range(len(hole_polys)):
        for m in range(k + 1, len(hole_polys)):
            hk, hm = domain.holes[k], domain.holes[m]
            if not shapely.intersects(hole_polys[k], hole_polys[m]):
                continue
            if shapely.intersects(hole_lines[k], hole_lines[m]):
                p = _touch_point(hole_lines[k], hole_lines[m])
                i = locate_on_polyline(hm, p, closed=True)[1]
                overlap = shapely.area(shapely.intersection(hole_polys[k], hole_polys[m]))
                verb = "overlaps" if overlap > tol * domain.diagonal else "touches"
                raise DomainError(
                    f"hole {m}, vertex {i}: {verb} hole {k} at {fmt_point(p, 10)} "
                    f"(segment {i}-{(i + 1) % len(hm)})"
                )
            if shapely.contains(hole_polys[k], hole_polys[m]):
                raise DomainError(f"hole {m}, vertex 0: lies inside hole {k} at {fmt_point(hm[0], 10)}")
            raise DomainError(f"hole {k}, vertex 0: lies inside hole {m} at {fmt_point(hk[0], 10)}")

    poly = domain.polygon()
    shapely.prepare(poly)
    boundary = poly.boundary

    # point features ------------------------------------------------------------------------
    pts = domain.points
    if len(pts):
        _check_finite_feature(pts)
        dist = shapely.distance(shapely.points(pts), boundary)
        on_boundary = dist <= tol
        inside = shapely.contains_xy(poly, pts[:, 0], pts[:, 1]) | on_boundary
        if not inside.all():
            i = int(np.flatnonzero(~inside)[0])
            p = pts[i]
            for k, hp in enumerate(hole_polys):
                if shapely.contains_xy(hp, p[0], p[1]):
                    raise DomainError(f"point feature {i} at {fmt_point(p, 10)} lies inside hole {k}")
            raise DomainError(f"point feature {i} at {fmt_point(p, 10)} lies outside the domain")
        pairs = cKDTree(pts).query_pairs(r=tol, output_type="ndarray")
        if len(pairs):
            i, j = np.sort(pairs, axis=1)[0]
            raise DomainError(f"point features {i} and {j} coincide at {fmt_point(pts[i], 10)}")

    # curve features ------------------------------------------------------------------------
    lines = []
    for c, curve in enumerate(domain.curves):
        what = f"curve feature {c}"
        if curve.ndim != 2 or curve.shape[1] != 2:
            raise DomainError(f"{what}: expected a list of [x, y] pairs")
        check_finite(curve, what)
        if len(curve) < 2:
            raise DomainError(f"{what}: needs at least 2 distinct vertices, got {len(curve)}")
        _check_duplicates(curve, what, tol)
        _check_simple(curve, what, closed=False, tol=tol)
        # every vertex inside the domain or on the boundary
        d = shapely.distance(shapely.points(curve), boundary)
        on_b = d <= tol
        inside = shapely.contains_xy(poly, curve[:, 0], curve[:, 1]) | on_b
        segs = _segments(curve, closed=False)
        if not inside.all():
            i = int(np.flatnonzero(~inside)[0])
            _raise_curve_outside(what, i, curve[i], hole_polys)
        # no segment may leave the domain or cross a hole
        covered = shapely.covered_by(segs, poly)
        if not covered.all():
            i = int(np.flatnonzero(~covered)[0])
            outside = shapely.difference(segs[i], poly)
            p = np.asarray(shapely.get_coordinates(shapely.point_on_surface(outside)))[0]
            _raise_curve_outside(what, i, p, hole_polys, segment=(i, i + 1))
        # interior vertices may not touch the boundary; nor may segments apart from end points
        interior_touch = on_b.copy()
        interior_touch[[0, -1]] = False
        if interior_touch.any():
            i = int(np.flatnonzero(interior_touch)[0])
            raise DomainError(
                f"{what}, vertex {i}: touches the domain boundary at {fmt_point(curve[i], 10)} "
                "(only the end points of a curve feature may lie on the boundary)"
            )
        line = shapely.LineString(curve)
        inter = shapely.get_coordinates(shapely.intersection(line, boundary))
        if len(inter):
            ends = curve[[0, -1]]
            dd = np.min(np.hypot(*(inter[:, None, :] - ends[None, :, :]).transpose(2, 0, 1)), axis=1)
            if (dd > tol).any():
                p = inter[int(np.argmax(dd))]
                i = int(np.argmin(shapely.distance(segs, shapely.Point(p))))
                raise DomainError(
                    f"{what}, vertex {i}: touches the domain boundary at {fmt_point(p, 10)} "
                    f"(segment {i}-{i + 1}; only the end points may lie on the boundary)"
                )
        lines.append(line)
    for a in range(len(lines)):
        for b in range(a + 1, len(lines)):
            if not shapely.intersects(lines[a], lines[b]):
                continue
            inter = shapely.get_coordinates(shapely.intersection(lines[a], lines[b]))
            ends = np.concatenate([domain.curves[a][[0, -1]], domain.curves[b][[0, -1]]])
            dd = np.min(np.hypot(*(inter[:, None, :] - ends[None, :, :]).transpose(2, 0, 1)), axis=1)
            if (dd > tol).any() or len(inter) > 1:
                p = inter[int(np.argmax(dd))]
                i = int(np.argmin(shapely.distance(_segments(domain.curves[b], False), shapely.Point(p))))
                raise DomainError(
                    f"curve feature {b}, vertex {i}: crosses curve feature {a} at {fmt_point(p, 10)}"
                )


def _check_finite_feature(pts: np.ndarray) -> None:
    bad = ~np.isfinite(pts).all(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DomainError(f"point feature {i}: coordinate is not finite {fmt_point(pts[i], 10)}")


def _raise_curve_outside(what, i, p, hole_polys, segment=None):
    seg = f" (segment {segment[0]}-{segment[1]})" if segment else ""
    for k, hp in enumerate(hole_polys):
        if shapely.intersects(hp, shapely.Point(p)):
            raise DomainError(f"{what}, vertex {i}: crosses hole {k} at {fmt_point(p, 10)}{seg}")
    raise DomainError(f"{what}, vertex {i}: leaves the domain at {fmt_point(p, 10)}{seg}")


#: Features (§4) must be at least this many discretisation spacings ``h = spacing * diagonal`` from
#: the boundary and from each other: closer, the Delaunay triangulation has no room for the skeleton
#: between them and the patches in the gap degenerate.
FEATURE_CLEARANCE = 1.0


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
    """
    diag = domain.diagonal
    h = spacing * diag
    tol = 1e-9 * diag
    need = clearance * h
    boundary = domain.polygon().boundary
    items = []  # (name, geometry measured against others)
    for i, p in enumerate(np.asarray(domain.points, dtype=float).reshape(-1, 2)):
        if shapely.distance(shapely.Point(p), boundary) > tol:
            items.append((f"point feature {i} at {fmt_point(p)}", shapely.Point(p), ()))
    for c, curve in enumerate(domain.curves):
        curve = np.asarray(curve, dtype=float)
        ends = [e for e in (curve[0], curve[-1]) if shapely.distance(shapely.Point(e), boundary) <= tol]
        items.append((f"curve feature {c}", shapely.LineString(curve), [shapely.Point(e) for e in ends]))
    ends_all = [e for _, _, es in items for e in es]

    def trimmed(geom, around):
        if not around:
            return geom
        return shapely.difference(geom, shapely.union_all([e.buffer(2 * h) for e in around]))

    def check(name, geom, other_name, other):
        if geom.is_empty or other.is_empty:
            return
        d = shapely.distance(geom, other)
        if d < need:
            a, b = shapely.get_coordinates(shapely.shortest_line(geom, other))
            raise DomainError(
                f"{name} is {d:.4g} from {other_name} (closest at {fmt_point(a)} and {fmt_point(b)}), less than the "
                f"spacing {need:.4g} (spacing {spacing:g} of the diagonal {diag:.4g}): move it, or mesh with "
                f"a spacing below {d / (clearance * diag):.3g}"
            )

    for name, geom, ends in items:
        check(name, trimmed(geom, ends), "the boundary", boundary)
    for k, (name, geom, ends) in enumerate(items):
        for name2, geom2, ends2 in items[k + 1:]:
            if isinstance(geom, shapely.Point) and isinstance(geom2, shapely.LineString) \
                    and shapely.distance(geom, geom2) <= tol:
                continue  # a point feature on a curve is a point of the curve
            if isinstance(geom2, shapely.Point) and isinstance(geom, shapely.LineString) \
                    and shapely.distance(geom2, geom) <= tol:
                continue
            shared = [e for e in ends_all if shapely.distance(e, geom) <= tol and shapely.distance(e, geom2) <= tol]
            if isinstance(geom, shapely.LineString) and isinstance(geom2, shapely.LineString):
                shared += [shapely.Point(q) for q in shapely.get_coordinates(shapely.intersection(geom, geom2))]
            check(name2, trimmed(geom2, shared), name, trimmed(geom, shared))
