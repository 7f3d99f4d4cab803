"""Reading a domain: vaultgram JSON, GeoJSON and DXF (§3.1 input).

Every reader normalises the rings (closing vertex dropped, outer ring counter-clockwise, holes
clockwise, so that the domain always lies to the *left* of every ring), projects point features
digitised just outside the boundary onto it, and validates the result
(:func:`~vaultgram.domain.validation.validate_domain`). Errors name the file, then the ring or
feature and the vertex.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, Iterable, NamedTuple

import numpy as np
import shapely

from vaultgram.domain.model import REL_TOL, Domain
from vaultgram.domain.validation import check_finite, validate_domain
from vaultgram.errors import DomainError
from vaultgram.geometry.polygons import bbox_diagonal, signed_area

__all__ = ["load_domain", "domain_from_dict", "domain_from_geojson", "domain_from_dxf", "POINT_SNAP", "GEOJSON_TYPES"]

#: Point features lying *outside* the domain but closer than ``POINT_SNAP * bbox diagonal`` to its
#: boundary are boundary point features (§4.1) digitised against the true curve rather than against
#: its polyline: they are projected onto the boundary. ``POINT_SNAP`` equals the default
#: discretisation spacing, below which the boundary is not resolved anyway. Farther points are an
#: error.
POINT_SNAP = 0.02


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


def _normalise_ring(ring: np.ndarray, what: str, ccw: bool, tol: float) -> np.ndarray:
    """Drop the closing vertex and fix the orientation (outer ccw, holes cw)."""
    check_finite(ring, what)
    if len(ring) >= 2 and np.hypot(*(ring[0] - ring[-1])) <= tol:
        ring = ring[:-1]
    area = signed_area(ring) if len(ring) >= 3 else 0.0
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
        for i, r in enumerate(_non_empty_list(value["rings"], "supports.rings", '"outer" or hole indices')):
            if not (r == "outer" or (isinstance(r, int) and not isinstance(r, bool) and r >= 0)):
                raise DomainError(
                    f'supports.rings[{i}]: expected "outer" or a hole index (integer >= 0), got {r!r}'
                )
        return value
    if keys == {"polylines"}:
        for i, pl in enumerate(_non_empty_list(value["polylines"], "supports.polylines", "polylines")):
            check_finite(_as_coords(pl, f"supports.polylines[{i}]", min_len=2), f"supports.polylines[{i}]")
        return value
    raise DomainError(
        f'supports: expected exactly one of the keys "rings" or "polylines", got {sorted(value)}'
    )


def _non_empty_list(value: Any, what: str, items: str) -> list:
    """``value`` if it is a non-empty list, else an error saying what ``items`` it should hold."""
    if not isinstance(value, list) or not value:
        raise DomainError(f"{what}: expected a non-empty list of {items}")
    return value


def _build(
    name: str,
    outer: np.ndarray,
    holes: Iterable[np.ndarray],
    points: np.ndarray,
    curves: Iterable[np.ndarray],
    supports: Any,
) -> Domain:
    """Normalise raw arrays into a validated Domain."""
    check_finite(outer, "outer ring")
    tol = REL_TOL * bbox_diagonal(outer)
    outer = _normalise_ring(outer, "outer ring", ccw=True, tol=tol)
    holes = tuple(
        _normalise_ring(h, f"hole {i}", ccw=False, tol=tol) for i, h in enumerate(holes)
    )
    points = np.ascontiguousarray(np.asarray(points, dtype=np.float64).reshape(-1, 2))
    curves = tuple(np.ascontiguousarray(np.asarray(c, dtype=np.float64)) for c in curves)
    supports = _normalise_supports(supports)
    points = _snap_points(outer, holes, points, POINT_SNAP * bbox_diagonal(outer))
    for arr in (outer, *holes, points, *curves):
        arr.setflags(write=False)
    dom = Domain(str(name), outer, holes, points, curves, supports)
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


def domain_from_dict(d: Any, source: str = "<dict>") -> Domain:
    """Build a validated :class:`Domain` from a vaultgram-JSON dictionary.

    Only ``outer`` is required; ``name`` defaults to ``source``'s stem, ``holes``, ``points`` and
    ``curves`` to empty lists, ``supports`` to ``None``. Unknown keys (``source``, ...) are ignored.
    Errors are prefixed by ``source``.

    Example
    -------
    >>> d = domain_from_dict({"outer": [[0, 0], [10, 0], [10, 10], [0, 10]], "points": [[2.5, 7.5]]})
    >>> d.name, d.area, d.points.tolist()
    ('domain', 100.0, [[2.5, 7.5]])
    >>> domain_from_dict({"outer": [[0, 0], [10, 0], [10, 0], [0, 10]]}, source="plan.json")
    Traceback (most recent call last):
    ...
    vaultgram.errors.DomainError: plan.json: outer ring: vertices 1 and 2 coincide at (10, 0)
    """
    try:
        return _domain_from_dict(d, source)
    except DomainError as e:
        raise _prefixed(e, source) from None


def _prefixed(e: DomainError, source: str) -> DomainError:
    """The same error, its message starting with the file (or other source) it is about."""
    msg = str(e)
    if source and not msg.startswith(source):
        msg = f"{source}: {msg}"
    return DomainError(msg)


def _default_name(source: str) -> str:
    """A domain's name when its file gives none: the file's stem (``domain`` for other sources)."""
    return Path(source).stem if source and not source.startswith("<") else "domain"


def _list_of(d: dict, key: str, what: str) -> list:
    """The list under an optional key (empty when absent or null), or an error naming ``what`` it holds."""
    value = d.get(key, []) or []
    if not isinstance(value, list):
        raise DomainError(f"{key}: expected a list of {what}, got {type(value).__name__}")
    return value


def _domain_from_dict(d: Any, source: str) -> Domain:
    """:func:`domain_from_dict` without the ``source`` prefix on errors."""
    if not isinstance(d, dict):
        raise DomainError(f"expected a JSON object with an 'outer' key, got {type(d).__name__}")
    if "outer" not in d:
        raise DomainError("missing required key 'outer' (a list of [x, y] pairs)")
    name = d.get("name", _default_name(source))
    if not isinstance(name, str):
        raise DomainError(f"name: expected a string, got {type(name).__name__}")
    outer = _as_coords(d["outer"], "outer ring")
    holes = [_as_coords(h, f"hole {i}") for i, h in enumerate(_list_of(d, "holes", "rings"))]
    pts_raw = _list_of(d, "points", "[x, y] pairs")
    points = np.empty((len(pts_raw), 2))
    for i, p in enumerate(pts_raw):
        points[i] = _as_coords([p], f"point feature {i}")[0]
    curves = [_as_coords(c, f"curve feature {i}") for i, c in enumerate(_list_of(d, "curves", "polylines"))]
    return _build(name, outer, holes, points, curves, d.get("supports"))


# --------------------------------------------------------------------------------------------
# GeoJSON
# --------------------------------------------------------------------------------------------

#: The ``type`` values of a GeoJSON document that :func:`load_domain` reads as GeoJSON.
GEOJSON_TYPES = ("FeatureCollection", "Feature", "Polygon", "MultiPolygon", "GeometryCollection")


def domain_from_geojson(d: Any, source: str = "<geojson>") -> Domain:
    """Build a validated :class:`Domain` from a GeoJSON ``FeatureCollection`` or ``Feature``.

    Exactly one ``Polygon`` (or single-part ``MultiPolygon``) gives the outer ring and holes;
    ``Point``/``MultiPoint`` features give point features, ``LineString``/``MultiLineString``
    features give curve features (in file order). A top-level ``supports`` member is kept.

    Example
    -------
    >>> square = [[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]]
    >>> d = domain_from_geojson({"type": "Feature", "properties": {"name": "plan"},
    ...                          "geometry": {"type": "Polygon", "coordinates": [square]}})
    >>> d.name, len(d.outer), d.area
    ('plan', 4, 100.0)
    """
    try:
        return _domain_from_geojson(d, source)
    except DomainError as e:
        raise _prefixed(e, source) from None


class _GeoJsonParts(NamedTuple):
    """What the features of a GeoJSON document hold, in file order."""

    polygons: list  # (feature index, rings)
    points: list  # [x, y]
    curves: list  # [[x, y], ...]


def _domain_from_geojson(d: Any, source: str) -> Domain:
    """:func:`domain_from_geojson` without the ``source`` prefix on errors; the name comes from the
    document, its properties or the polygon feature's properties, else from ``source``."""
    feats = _geojson_features(d)
    parts = _GeoJsonParts([], [], [])
    for i, f in enumerate(feats):
        if not isinstance(f, dict) or f.get("type") != "Feature":
            raise DomainError(f"features[{i}]: expected a GeoJSON Feature")
        _collect_geometry(f.get("geometry"), i, parts)
    if len(parts.polygons) != 1:
        raise DomainError(f"expected exactly one Polygon feature (the domain), found {len(parts.polygons)}")
    i, rings = parts.polygons[0]
    if not isinstance(rings, list) or not rings:
        raise DomainError(f"features[{i}].geometry.coordinates: expected a list of linear rings")
    name = d.get("name") or _properties(d).get("name")
    name = name or _properties(feats[i]).get("name") or _default_name(source)
    outer = _as_coords(rings[0], "outer ring")
    holes = [_as_coords(r, f"hole {k}") for k, r in enumerate(rings[1:])]
    pts = np.array([_as_coords([p], f"point feature {k}")[0] for k, p in enumerate(parts.points)]).reshape(-1, 2)
    crv = [_as_coords(c, f"curve feature {k}") for k, c in enumerate(parts.curves)]
    return _build(str(name), outer, holes, pts, crv, d.get("supports"))


def _geojson_features(d: Any) -> list:
    """The features of a GeoJSON document: those of a collection, or the one feature or geometry."""
    if not isinstance(d, dict):
        raise DomainError(f"expected a GeoJSON object, got {type(d).__name__}")
    kind = d.get("type")
    if kind == "FeatureCollection":
        feats = d.get("features")
        if not isinstance(feats, list):
            raise DomainError("features: expected a list of GeoJSON features")
        return feats
    if kind == "Feature":
        return [d]
    if kind in ("Polygon", "MultiPolygon", "GeometryCollection"):
        return [{"type": "Feature", "geometry": d}]
    raise DomainError(f"type: expected 'FeatureCollection' or 'Feature', got {kind!r}")


def _collect_geometry(geom: Any, i: int, parts: _GeoJsonParts) -> None:
    """Add the polygons, points and lines of the geometry of feature ``i`` to ``parts``."""
    if not isinstance(geom, dict):
        raise DomainError(f"features[{i}].geometry: expected a GeoJSON geometry object")
    t, coords = geom.get("type"), geom.get("coordinates")
    if t == "Polygon":
        parts.polygons.append((i, coords))
    elif t == "MultiPolygon":
        parts.polygons.extend((i, part) for part in _multi(coords, i))
    elif t == "Point":
        parts.points.append(coords)
    elif t == "MultiPoint":
        parts.points.extend(_multi(coords, i))
    elif t == "LineString":
        parts.curves.append(coords)
    elif t == "MultiLineString":
        parts.curves.extend(_multi(coords, i))
    elif t == "GeometryCollection":
        for g in _multi(geom.get("geometries"), i, "geometries"):
            _collect_geometry(g, i, parts)
    else:
        raise DomainError(f"features[{i}].geometry.type: unsupported geometry type {t!r}")


def _multi(parts: Any, i: int, key: str = "coordinates") -> list:
    """The parts of a multi-part geometry of feature ``i`` (none if absent)."""
    if parts is None:
        return []
    if not isinstance(parts, list):
        raise DomainError(f"features[{i}].geometry.{key}: expected a list, got {type(parts).__name__}")
    return parts


def _properties(obj: dict) -> dict:
    """The ``properties`` of a GeoJSON object (empty when absent or not an object)."""
    props = obj.get("properties")
    return props if isinstance(props, dict) else {}


# --------------------------------------------------------------------------------------------
# DXF
# --------------------------------------------------------------------------------------------


def domain_from_dxf(path: str | Path) -> Domain:
    """Read a DXF drawing (modelspace) with ezdxf and build a validated :class:`Domain`.

    Closed ``LWPOLYLINE``/``POLYLINE`` entities are rings (arc segments given by bulges are
    flattened); the ring whose polygon contains all the others is the outer ring, the others are
    holes. ``POINT`` entities are point features; open polylines and ``LINE`` entities are curve
    features. Other entities are ignored.
    """
    path = Path(path)
    drawing = _read_dxf(path)
    if not drawing.closed:
        raise DomainError(f"{path}: no closed polyline found (the outer boundary must be closed)")
    k = _enclosing_ring(path, drawing.closed)
    holes = [r for m, r in enumerate(drawing.closed) if m != k]
    try:
        return _build(path.stem, drawing.closed[k], holes, np.array(drawing.points).reshape(-1, 2), drawing.open,
                      None)
    except DomainError as e:
        raise _prefixed(e, str(path)) from None


class _DxfDrawing(NamedTuple):
    """The entities of a DXF drawing that make a domain, in file order."""

    closed: list  # closed polylines: vertices (n, 2), without the closing one
    open: list  # open polylines and lines
    points: list  # (x, y) of POINT entities


def _read_dxf(path: Path) -> _DxfDrawing:
    """The polylines, lines and points of the modelspace of a DXF file."""
    try:
        import ezdxf
        from ezdxf import path as ezpath
    except ImportError as e:  # pragma: no cover - dependency declared in pyproject
        raise DomainError(f"{path}: reading DXF needs the 'ezdxf' package ({e})") from None
    try:
        doc = ezdxf.readfile(str(path))
    except (IOError, ezdxf.DXFStructureError, ezdxf.DXFError) as e:
        raise DomainError(f"{path}: not a readable DXF file ({e})") from None
    drawing = _DxfDrawing([], [], [])
    for e in doc.modelspace():
        t = e.dxftype()
        if t in ("LWPOLYLINE", "POLYLINE"):
            if t == "POLYLINE" and not (e.is_2d_polyline or e.is_3d_polyline):
                continue
            verts, is_closed = _polyline_vertices(e, ezpath)
            (drawing.closed if is_closed else drawing.open).append(verts)
        elif t == "LINE":
            drawing.open.append(np.array([(e.dxf.start.x, e.dxf.start.y), (e.dxf.end.x, e.dxf.end.y)]))
        elif t == "POINT":
            drawing.points.append((e.dxf.location.x, e.dxf.location.y))
    return drawing


def _polyline_vertices(entity, ezpath) -> tuple[np.ndarray, bool]:
    """The plan vertices of a DXF polyline (arcs flattened to 1/1000 of its extent) and whether it
    is closed (by its flag, or by ending where it starts); a closed one loses its closing vertex."""
    p = ezpath.make_path(entity)
    verts = np.array([(v.x, v.y) for v in p.control_vertices()])
    if p.has_curves:
        dist = 1e-3 * max(bbox_diagonal(verts), 1e-12)
        verts = np.array([(v.x, v.y) for v in p.flattening(distance=dist)])
    is_closed = bool(entity.is_closed) or (
        len(verts) > 2 and np.allclose(verts[0], verts[-1], rtol=0, atol=1e-12)
    )
    if is_closed and len(verts) > 1 and np.allclose(verts[0], verts[-1], rtol=0, atol=0):
        verts = verts[:-1]
    return verts, is_closed


def _enclosing_ring(path: Path, closed: list) -> int:
    """The index of the closed polyline of largest area, which must enclose every other one."""
    areas = [abs(signed_area(r)) if len(r) >= 3 else 0.0 for r in closed]
    k = int(np.argmax(areas))
    outer_poly = shapely.Polygon(closed[k]) if len(closed[k]) >= 3 else None
    for m, r in enumerate(closed):
        if m != k and (outer_poly is None or not outer_poly.is_valid or not outer_poly.covers(shapely.MultiPoint(r))):
            raise DomainError(
                f"{path}: closed polyline {m} is not enclosed by the largest closed polyline "
                f"{k}; exactly one closed polyline must enclose all others"
            )
    return k


# --------------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------------


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

    Example
    -------
    >>> d = load_domain("examples/quad_with_hole.json")
    >>> d
    Domain(name='quad_with_hole', outer=4 vertices, holes=1, points=0, curves=0)
    >>> round(d.area, 4)
    87.4538
    """
    path = Path(path)
    raw = _read_bytes(path)
    ext = path.suffix.lower()
    if ext == ".dxf" or (ext not in (".json", ".geojson") and raw.lstrip()[:1] != b"{"):
        return domain_from_dxf(path)
    data = _parse_json(raw, path)
    if isinstance(data, dict) and data.get("type") in GEOJSON_TYPES:
        return domain_from_geojson(data, source=str(path))
    return domain_from_dict(data, source=str(path))


def _read_bytes(path: Path) -> bytes:
    """The bytes of a domain file that exists and is not empty."""
    if not path.is_file():
        raise DomainError(f"{path}: file not found")
    try:
        raw = path.read_bytes()
    except OSError as e:
        raise DomainError(f"{path}: cannot read: {e.strerror}") from None
    if not raw.strip():
        raise DomainError(f"{path}: file is empty")
    return raw


def _parse_json(raw: bytes, path: Path) -> Any:
    """The JSON document in ``raw`` (UTF-8, with or without a byte-order mark), errors naming the place.

    Not :func:`vaultgram.io.files.read_json`: a domain file may start with a byte-order mark, and a
    file that is not UTF-8 must be a :class:`DomainError` too.
    """
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise DomainError(f"{path}: not UTF-8 text ({e.reason} at byte {e.start})") from None
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        raise DomainError(f"{path}:{e.lineno}:{e.colno}: invalid JSON: {e.msg}") from None
