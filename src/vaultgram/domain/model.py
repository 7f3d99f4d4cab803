"""The domain of a vault: outer boundary, holes, point and curve features (paper §3.1 and §4).

A :class:`Domain` is the plain, immutable input of the pipeline
``Domain -> Discretisation -> Triangulation -> Skeleton -> ...``. It is read from

* vaultgram JSON (``{"name", "outer", "holes", "points", "curves", "supports"}``, see
  ``domain.schema.json`` next to this module; only ``outer`` is required, extra keys such as
  ``source`` are allowed and ignored),
* GeoJSON (a ``FeatureCollection`` or a single ``Feature``: one ``Polygon`` gives the outer ring and
  the holes, ``Point``/``MultiPoint`` give point features, ``LineString``/``MultiLineString`` give
  curve features),
* DXF (via ezdxf: the closed polyline enclosing all others is the outer ring, the other closed
  polylines are holes, ``POINT`` entities are point features and open polylines / lines are curve
  features).

Every loader normalises the rings (closing vertex dropped, outer ring counter-clockwise, holes
clockwise, so that the domain always lies to the *left* of every ring) and runs
:func:`validate_domain` before returning, so a ``Domain`` that exists is valid. Problems raise
:class:`vaultgram.errors.DomainError` with a message that names the ring or feature and the vertex
index, e.g. ``outer ring: vertices 3 and 4 coincide at (10, 0)``. Vertex indices are those of the
normalised ring: the file's order, reversed when the orientation had to be fixed (vertex 0 stays
vertex 0); messages also give the coordinates.

Tolerance: two vertices closer than ``1e-9`` times the diagonal of the outer ring's bounding box are
"the same point" (:attr:`Domain.tolerance`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterable

import numpy as np
import shapely
from scipy.spatial import cKDTree

from vaultgram.errors import DomainError

__all__ = [
    "Domain",
    "load_domain",
    "domain_from_dict",
    "domain_from_geojson",
    "domain_from_dxf",
    "validate_domain",
    "ring_name",
    "REL_TOL",
]

#: Relative tolerance: vertices closer than ``REL_TOL * bbox diagonal`` coincide.
REL_TOL = 1e-9

#: Point features lying *outside* the domain but closer than ``POINT_SNAP * bbox diagonal`` to its
#: boundary are boundary point features (§4.1) digitised against the true curve rather than against
#: its polyline: they are projected onto the boundary. ``POINT_SNAP`` equals the default
#: discretisation spacing, below which the boundary is not resolved anyway. Farther points are an
#: error.
POINT_SNAP = 0.02


# --------------------------------------------------------------------------------------------
# The dataclass
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Domain:
    """A planar vault domain (paper §3.1 input, with the §4 point and curve features).

    Attributes
    ----------
    name : str
        A label (file stem when the file gives none).
    outer : ndarray (n, 2) float64
        Outer boundary, counter-clockwise, without closing vertex.
    holes : tuple of ndarray (m_i, 2)
        Inner boundaries (openings), each clockwise, without closing vertex.
    points : ndarray (k, 2)
        Point features (§4.1): inside the domain or on its boundary. A point given just outside the
        boundary (closer than ``POINT_SNAP`` times the diagonal) is projected onto it.
    curves : tuple of ndarray (c_i, 2)
        Curve features (§4.2): open polylines inside the domain; only their end points may lie on
        the boundary.
    supports : object or None
        The raw ``supports`` value (validated for shape only): ``None`` means the whole outer
        boundary is supported and holes are open; ``{"rings": ["outer", 0, ...]}`` selects whole
        rings; ``{"polylines": [[[x, y], ...], ...]}`` supports the boundary parts lying on them.
    """

    name: str
    outer: np.ndarray
    holes: tuple = ()
    points: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    curves: tuple = ()
    supports: object | None = None

    @property
    def diagonal(self) -> float:
        """Length of the diagonal of the outer ring's bounding box (the unit of all spacings)."""
        return _bbox_diagonal(self.outer)

    @property
    def tolerance(self) -> float:
        """Absolute coincidence tolerance, ``REL_TOL * diagonal``."""
        return REL_TOL * self.diagonal

    @property
    def rings(self) -> tuple:
        """All rings in the standard order: outer ring first, then the holes."""
        return (self.outer, *self.holes)

    def polygon(self) -> shapely.Polygon:
        """The domain as a shapely polygon (outer shell with holes)."""
        return shapely.Polygon(self.outer, [h for h in self.holes])

    @property
    def area(self) -> float:
        """Area of the domain (outer area minus hole areas)."""
        return float(_signed_area(self.outer) + sum(_signed_area(h) for h in self.holes))

    def __repr__(self) -> str:  # arrays make the default repr unreadable
        return (
            f"Domain(name={self.name!r}, outer={len(self.outer)} vertices, holes={len(self.holes)}, "
            f"points={len(self.points)}, curves={len(self.curves)})"
        )


def ring_name(ring: int) -> str:
    """Human name of ring ``ring`` in the standard order (0 = outer, 1.. = hole ring-1)."""
    return "outer ring" if ring == 0 else f"hole {ring - 1}"


# --------------------------------------------------------------------------------------------
# Small geometric helpers
# --------------------------------------------------------------------------------------------


def _fmt(x: float) -> str:
    return f"{float(x):.10g}"


def _pt(p) -> str:
    return f"({_fmt(p[0])}, {_fmt(p[1])})"


def _bbox_diagonal(pts: np.ndarray) -> float:
    if len(pts) == 0:
        return 0.0
    return float(np.hypot(*(pts.max(axis=0) - pts.min(axis=0))))


def _signed_area(ring: np.ndarray) -> float:
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


# --------------------------------------------------------------------------------------------
# Parsing raw coordinates
# --------------------------------------------------------------------------------------------


def _as_coords(value: Any, what: str, min_len: int = 0) -> np.ndarray:
    """Turn a JSON list of ``[x, y]`` pairs into an (n, 2) float array, naming bad entries."""
    if not isinstance(value, (list, tuple)):
        raise DomainError(f"{what}: expected a list of [x, y] pairs, got {type(value).__name__}")
    out = np.empty((len(value), 2), dtype=np.float64)
    for i, p in enumerate(value):
        if (
            not isinstance(p, (list, tuple))
            or len(p) < 2
            or not all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in p[:2])
        ):
            raise DomainError(f"{what}, vertex {i}: expected [x, y] with two numbers, got {p!r}")
        out[i] = (float(p[0]), float(p[1]))
    if len(out) < min_len:
        raise DomainError(f"{what}: expected at least {min_len} vertices, got {len(out)}")
    return out


def _check_finite(arr: np.ndarray, what: str) -> None:
    bad = ~np.isfinite(arr).all(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DomainError(f"{what}, vertex {i}: coordinate is not finite {_pt(arr[i])}")


def _normalise_ring(ring: np.ndarray, what: str, ccw: bool, tol: float) -> np.ndarray:
    """Drop the closing vertex and fix the orientation (outer ccw, holes cw)."""
    _check_finite(ring, what)
    if len(ring) >= 2 and np.hypot(*(ring[0] - ring[-1])) <= tol:
        ring = ring[:-1]
    area = _signed_area(ring) if len(ring) >= 3 else 0.0
    if (area < 0) == ccw and area != 0:
        ring = np.roll(ring[::-1], 1, axis=0)  # reversed, but vertex 0 stays vertex 0
    return np.ascontiguousarray(ring, dtype=np.float64)


def _normalise_supports(value: Any) -> Any:
    """Check the shape of ``supports`` (semantics are applied later in the pipeline)."""
    if value is None:
        return None
    if not isinstance(value, dict):
        raise DomainError(
            'supports: expected null, {"rings": [...]} or {"polylines": [...]}, '
            f"got {type(value).__name__}"
        )
    keys = set(value) - {"comment"}
    if keys == {"rings"}:
        rings = value["rings"]
        if not isinstance(rings, list) or not rings:
            raise DomainError('supports.rings: expected a non-empty list of "outer" or hole indices')
        for i, r in enumerate(rings):
            if not (r == "outer" or (isinstance(r, int) and not isinstance(r, bool) and r >= 0)):
                raise DomainError(
                    f'supports.rings[{i}]: expected "outer" or a hole index (integer >= 0), got {r!r}'
                )
        return value
    if keys == {"polylines"}:
        pls = value["polylines"]
        if not isinstance(pls, list) or not pls:
            raise DomainError("supports.polylines: expected a non-empty list of polylines")
        for i, pl in enumerate(pls):
            arr = _as_coords(pl, f"supports.polylines[{i}]", min_len=2)
            _check_finite(arr, f"supports.polylines[{i}]")
        return value
    raise DomainError(
        f'supports: expected exactly one of the keys "rings" or "polylines", got {sorted(value)}'
    )


def _build(
    name: str,
    outer: np.ndarray,
    holes: Iterable[np.ndarray],
    points: np.ndarray,
    curves: Iterable[np.ndarray],
    supports: Any,
) -> Domain:
    """Normalise raw arrays into a validated Domain."""
    _check_finite(outer, "outer ring")
    tol = REL_TOL * _bbox_diagonal(outer)
    outer = _normalise_ring(outer, "outer ring", ccw=True, tol=tol)
    holes = tuple(
        _normalise_ring(h, f"hole {i}", ccw=False, tol=tol) for i, h in enumerate(holes)
    )
    points = np.ascontiguousarray(np.asarray(points, dtype=np.float64).reshape(-1, 2))
    curves = tuple(np.ascontiguousarray(np.asarray(c, dtype=np.float64)) for c in curves)
    supports = _normalise_supports(supports)
    points = _snap_points(outer, holes, points, POINT_SNAP * _bbox_diagonal(outer))
    dom = Domain(str(name), outer, holes, points, curves, supports)
    for ring in dom.rings:
        ring.setflags(write=False)
    dom.points.setflags(write=False)
    for c in dom.curves:
        c.setflags(write=False)
    validate_domain(dom)
    return dom


def _snap_points(outer, holes, points, snap):
    """Project point features lying just outside the domain (within ``snap``) onto its boundary."""
    if len(points) == 0 or not np.isfinite(points).all() or len(outer) < 3:
        return points
    try:
        poly = shapely.Polygon(outer, list(holes))
        boundary = poly.boundary
        geoms = shapely.points(points)
        d = shapely.distance(geoms, boundary)
        near = (~shapely.contains_xy(poly, points[:, 0], points[:, 1])) & (d <= snap) & (d > 0)
    except (shapely.errors.GEOSException, ValueError):  # invalid rings: validation reports them
        return points
    if not near.any():
        return points
    points = points.copy()
    lines = shapely.shortest_line(geoms[near], boundary)
    points[near] = shapely.get_coordinates(lines).reshape(-1, 2, 2)[:, 1]
    return points


# --------------------------------------------------------------------------------------------
# Validation
# --------------------------------------------------------------------------------------------


def _check_duplicates(pts: np.ndarray, what: str, tol: float) -> None:
    """No two vertices of one ring / curve within ``tol`` (consecutive or not)."""
    pairs = cKDTree(pts).query_pairs(r=max(tol, 0.0), output_type="ndarray")
    if len(pairs):
        pairs = np.sort(pairs, axis=1)
        i, j = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))[0]]
        raise DomainError(f"{what}: vertices {i} and {j} coincide at {_pt(pts[i])}")


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
            f"{what}, vertex {j}: ring self-intersects at {_pt(pts[j])} "
            f"(segments {i}-{j} and {j}-{(j + 1) % n} fold back onto each other)"
            if closed
            else f"{what}, vertex {j}: curve self-intersects at {_pt(pts[j])} "
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
            f"{what}, vertex {i}: {kind} self-intersects at {_pt(p)} "
            f"(segments {i}-{(i + 1) % n} and {j}-{(j + 1) % n} intersect)"
        )


def _first_vertex(ring: np.ndarray, mask: np.ndarray) -> int:
    idx = np.flatnonzero(mask)
    return int(idx[0]) if len(idx) else 0


def _nearest_segment(ring: np.ndarray, p: np.ndarray) -> int:
    """Index i of the ring segment i-(i+1) closest to point p."""
    a = ring
    b = np.roll(ring, -1, axis=0)
    ab = b - a
    t = np.clip(((p - a) * ab).sum(1) / np.maximum((ab * ab).sum(1), 1e-300), 0, 1)
    d = np.hypot(*(a + t[:, None] * ab - p).T)
    return int(np.argmin(d))


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
        _check_finite(ring, what)
        if len(ring) < 3:
            raise DomainError(f"{what}: needs at least 3 distinct vertices, got {len(ring)}")
        _check_duplicates(ring, what, tol)
        _check_simple(ring, what, closed=True, tol=tol)
        if abs(_signed_area(ring)) <= tol * domain.diagonal:
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
            i = _nearest_segment(h, p)
            verb = "touches" if shapely.covered_by(hp, outer_poly) else "crosses"
            raise DomainError(
                f"{what}, vertex {i}: {verb} the outer ring at {_pt(p)} "
                f"(segment {i}-{(i + 1) % len(h)})"
            )
        inside = shapely.contains_xy(outer_poly, h[:, 0], h[:, 1])
        if not inside.all():
            i = _first_vertex(h, ~inside)
            raise DomainError(f"{what}, vertex {i}: lies outside the outer ring at {_pt(h[i])}")
    for k in range(len(hole_polys)):
        for m in range(k + 1, len(hole_polys)):
            hk, hm = domain.holes[k], domain.holes[m]
            if not shapely.intersects(hole_polys[k], hole_polys[m]):
                continue
            if shapely.intersects(hole_lines[k], hole_lines[m]):
                p = _touch_point(hole_lines[k], hole_lines[m])
                i = _nearest_segment(hm, p)
                overlap = shapely.area(shapely.intersection(hole_polys[k], hole_polys[m]))
                verb = "overlaps" if overlap > tol * domain.diagonal else "touches"
                raise DomainError(
                    f"hole {m}, vertex {i}: {verb} hole {k} at {_pt(p)} "
                    f"(segment {i}-{(i + 1) % len(hm)})"
                )
            if shapely.contains(hole_polys[k], hole_polys[m]):
                raise DomainError(f"hole {m}, vertex 0: lies inside hole {k} at {_pt(hm[0])}")
            raise DomainError(f"hole {k}, vertex 0: lies inside hole {m} at {_pt(hk[0])}")

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
                    raise DomainError(f"point feature {i} at {_pt(p)} lies inside hole {k}")
            raise DomainError(f"point feature {i} at {_pt(p)} lies outside the domain")
        pairs = cKDTree(pts).query_pairs(r=tol, output_type="ndarray")
        if len(pairs):
            i, j = np.sort(pairs, axis=1)[0]
            raise DomainError(f"point features {i} and {j} coincide at {_pt(pts[i])}")

    # curve features ------------------------------------------------------------------------
    lines = []
    for c, curve in enumerate(domain.curves):
        what = f"curve feature {c}"
        if curve.ndim != 2 or curve.shape[1] != 2:
            raise DomainError(f"{what}: expected a list of [x, y] pairs")
        _check_finite(curve, what)
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
                f"{what}, vertex {i}: touches the domain boundary at {_pt(curve[i])} "
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
                    f"{what}, vertex {i}: touches the domain boundary at {_pt(p)} "
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
                    f"curve feature {b}, vertex {i}: crosses curve feature {a} at {_pt(p)}"
                )


def _check_finite_feature(pts: np.ndarray) -> None:
    bad = ~np.isfinite(pts).all(axis=1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise DomainError(f"point feature {i}: coordinate is not finite {_pt(pts[i])}")


def _raise_curve_outside(what, i, p, hole_polys, segment=None):
    seg = f" (segment {segment[0]}-{segment[1]})" if segment else ""
    for k, hp in enumerate(hole_polys):
        if shapely.intersects(hp, shapely.Point(p)):
            raise DomainError(f"{what}, vertex {i}: crosses hole {k} at {_pt(p)}{seg}")
    raise DomainError(f"{what}, vertex {i}: leaves the domain at {_pt(p)}{seg}")


# --------------------------------------------------------------------------------------------
# Loaders
# --------------------------------------------------------------------------------------------


def domain_from_dict(d: Any, source: str = "<dict>") -> Domain:
    """Build a validated :class:`Domain` from a vaultgram-JSON dictionary.

    Only ``outer`` is required; ``name`` defaults to ``source``'s stem, ``holes``, ``points`` and
    ``curves`` to empty lists, ``supports`` to ``None``. Unknown keys (``source``, ...) are ignored.
    Errors are prefixed by ``source``.
    """
    try:
        return _domain_from_dict(d, source)
    except DomainError as e:
        raise _prefixed(e, source) from None


def _prefixed(e: DomainError, source: str) -> DomainError:
    msg = str(e)
    if source and not msg.startswith(source):
        msg = f"{source}: {msg}"
    return DomainError(msg)


def _domain_from_dict(d: Any, source: str) -> Domain:
    if not isinstance(d, dict):
        raise DomainError(f"expected a JSON object with an 'outer' key, got {type(d).__name__}")
    if "outer" not in d:
        raise DomainError("missing required key 'outer' (a list of [x, y] pairs)")
    name = d.get("name", Path(source).stem if source and not source.startswith("<") else "domain")
    if not isinstance(name, str):
        raise DomainError(f"name: expected a string, got {type(name).__name__}")
    outer = _as_coords(d["outer"], "outer ring")
    holes_raw = d.get("holes", []) or []
    if not isinstance(holes_raw, list):
        raise DomainError(f"holes: expected a list of rings, got {type(holes_raw).__name__}")
    holes = [_as_coords(h, f"hole {i}") for i, h in enumerate(holes_raw)]
    pts_raw = d.get("points", []) or []
    if not isinstance(pts_raw, list):
        raise DomainError(f"points: expected a list of [x, y] pairs, got {type(pts_raw).__name__}")
    points = np.empty((len(pts_raw), 2))
    for i, p in enumerate(pts_raw):
        points[i] = _as_coords([p], f"point feature {i}")[0]
    curves_raw = d.get("curves", []) or []
    if not isinstance(curves_raw, list):
        raise DomainError(f"curves: expected a list of polylines, got {type(curves_raw).__name__}")
    curves = [_as_coords(c, f"curve feature {i}") for i, c in enumerate(curves_raw)]
    return _build(name, outer, holes, points, curves, d.get("supports"))


def domain_from_geojson(d: Any, source: str = "<geojson>") -> Domain:
    """Build a validated :class:`Domain` from a GeoJSON ``FeatureCollection`` or ``Feature``.

    Exactly one ``Polygon`` (or single-part ``MultiPolygon``) gives the outer ring and holes;
    ``Point``/``MultiPoint`` features give point features, ``LineString``/``MultiLineString``
    features give curve features (in file order). A top-level ``supports`` member is kept.
    """
    try:
        return _domain_from_geojson(d, source)
    except DomainError as e:
        raise _prefixed(e, source) from None


def _domain_from_geojson(d: Any, source: str) -> Domain:
    kind = d.get("type")
    if kind == "FeatureCollection":
        feats = d.get("features")
        if not isinstance(feats, list):
            raise DomainError("features: expected a list of GeoJSON features")
    elif kind == "Feature":
        feats = [d]
    elif kind in ("Polygon", "MultiPolygon", "GeometryCollection"):
        feats = [{"type": "Feature", "geometry": d}]
    else:
        raise DomainError(f"type: expected 'FeatureCollection' or 'Feature', got {kind!r}")
    polygons, points, curves = [], [], []

    def add(geom: Any, i: int) -> None:
        if not isinstance(geom, dict):
            raise DomainError(f"features[{i}].geometry: expected a GeoJSON geometry object")
        t, coords = geom.get("type"), geom.get("coordinates")
        if t == "Polygon":
            polygons.append((i, coords))
        elif t == "MultiPolygon":
            for part in coords or []:
                polygons.append((i, part))
        elif t == "Point":
            points.append(coords)
        elif t == "MultiPoint":
            points.extend(coords or [])
        elif t == "LineString":
            curves.append(coords)
        elif t == "MultiLineString":
            curves.extend(coords or [])
        elif t == "GeometryCollection":
            for g in geom.get("geometries", []):
                add(g, i)
        else:
            raise DomainError(f"features[{i}].geometry.type: unsupported geometry type {t!r}")

    for i, f in enumerate(feats):
        if not isinstance(f, dict) or f.get("type") != "Feature":
            raise DomainError(f"features[{i}]: expected a GeoJSON Feature")
        add(f.get("geometry"), i)
    if len(polygons) != 1:
        raise DomainError(f"expected exactly one Polygon feature (the domain), found {len(polygons)}")
    i, rings = polygons[0]
    if not isinstance(rings, list) or not rings:
        raise DomainError(f"features[{i}].geometry.coordinates: expected a list of linear rings")
    name = d.get("name") or (d.get("properties") or {}).get("name")
    if not name:
        props = feats[i].get("properties") or {}
        name = props.get("name") or (Path(source).stem if not source.startswith("<") else "domain")
    outer = _as_coords(rings[0], "outer ring")
    holes = [_as_coords(r, f"hole {k}") for k, r in enumerate(rings[1:])]
    pts = np.array([_as_coords([p], f"point feature {k}")[0] for k, p in enumerate(points)]).reshape(-1, 2)
    crv = [_as_coords(c, f"curve feature {k}") for k, c in enumerate(curves)]
    return _build(str(name), outer, holes, pts, crv, d.get("supports"))


def domain_from_dxf(path: str | Path) -> Domain:
    """Read a DXF drawing (modelspace) with ezdxf and build a validated :class:`Domain`.

    Closed ``LWPOLYLINE``/``POLYLINE`` entities are rings (arc segments given by bulges are
    flattened); the ring whose polygon contains all the others is the outer ring, the others are
    holes. ``POINT`` entities are point features; open polylines and ``LINE`` entities are curve
    features. Other entities are ignored.
    """
    path = Path(path)
    try:
        import ezdxf
        from ezdxf import path as ezpath
    except ImportError as e:  # pragma: no cover - dependency declared in pyproject
        raise DomainError(f"{path}: reading DXF needs the 'ezdxf' package ({e})") from None
    try:
        doc = ezdxf.readfile(str(path))
    except (IOError, ezdxf.DXFStructureError, ezdxf.DXFError) as e:
        raise DomainError(f"{path}: not a readable DXF file ({e})") from None
    closed, open_, pts = [], [], []
    for e in doc.modelspace():
        t = e.dxftype()
        if t in ("LWPOLYLINE", "POLYLINE"):
            if t == "POLYLINE" and not (e.is_2d_polyline or e.is_3d_polyline):
                continue
            p = ezpath.make_path(e)
            verts = np.array([(v.x, v.y) for v in p.control_vertices()]) if not p.has_curves else None
            if verts is None:
                ext = np.array([(v.x, v.y) for v in p.control_vertices()])
                dist = 1e-3 * max(_bbox_diagonal(ext), 1e-12)
                verts = np.array([(v.x, v.y) for v in p.flattening(distance=dist)])
            is_closed = bool(e.is_closed) or (
                len(verts) > 2 and np.allclose(verts[0], verts[-1], rtol=0, atol=1e-12)
            )
            if is_closed and len(verts) > 1 and np.allclose(verts[0], verts[-1], rtol=0, atol=0):
                verts = verts[:-1]
            (closed if is_closed else open_).append(verts)
        elif t == "LINE":
            open_.append(np.array([(e.dxf.start.x, e.dxf.start.y), (e.dxf.end.x, e.dxf.end.y)]))
        elif t == "POINT":
            pts.append((e.dxf.location.x, e.dxf.location.y))
    if not closed:
        raise DomainError(f"{path}: no closed polyline found (the outer boundary must be closed)")
    areas = [abs(_signed_area(r)) if len(r) >= 3 else 0.0 for r in closed]
    k = int(np.argmax(areas))
    outer_poly = shapely.Polygon(closed[k]) if len(closed[k]) >= 3 else None
    for m, r in enumerate(closed):
        if m != k and (outer_poly is None or not outer_poly.is_valid or not outer_poly.covers(shapely.MultiPoint(r))):
            raise DomainError(
                f"{path}: closed polyline {m} is not enclosed by the largest closed polyline "
                f"{k}; exactly one closed polyline must enclose all others"
            )
    holes = [r for m, r in enumerate(closed) if m != k]
    try:
        return _build(path.stem, closed[k], holes, np.array(pts).reshape(-1, 2), open_, None)
    except DomainError as e:
        raise _prefixed(e, str(path)) from None


def load_domain(path: str | Path) -> Domain:
    """Load a domain file (vaultgram JSON, GeoJSON or DXF) and validate it.

    The format is chosen by extension (``.json``, ``.geojson``, ``.dxf``) and, for unknown
    extensions, by content. A JSON document with ``"type": "FeatureCollection"`` or
    ``"Feature"`` is GeoJSON, otherwise vaultgram JSON.

    Raises
    ------
    DomainError
        If the file is missing, empty, malformed (JSON errors give line and column) or describes
        an invalid domain (see :func:`validate_domain`).
    """
    path = Path(path)
    if not path.is_file():
        raise DomainError(f"{path}: file not found")
    raw = path.read_bytes()
    if not raw.strip():
        raise DomainError(f"{path}: file is empty")
    ext = path.suffix.lower()
    head = raw.lstrip()[:1]
    if ext == ".dxf" or (ext not in (".json", ".geojson") and head != b"{"):
        return domain_from_dxf(path)
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise DomainError(f"{path}: not UTF-8 text ({e.reason} at byte {e.start})") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise DomainError(f"{path}:{e.lineno}:{e.colno}: invalid JSON: {e.msg}") from None
    if isinstance(data, dict) and data.get("type") in (
        "FeatureCollection",
        "Feature",
        "Polygon",
        "MultiPolygon",
        "GeometryCollection",
    ):
        return domain_from_geojson(data, source=str(path))
    return domain_from_dict(data, source=str(path))
