"""Reading a domain: vaultgram JSON, GeoJSON, DXF and Rhino .3dm (§3.1 input).

Every reader normalises the rings (closing vertex dropped, outer ring counter-clockwise, holes
clockwise, so that the domain always lies to the *left* of every ring), projects point features
digitised just outside the boundary onto it, and validates the result
(:func:`~vaultgram.domain.validation.validate_domain`). Errors name the file, then the ring or
feature and the vertex.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping, NamedTuple

import numpy as np

from vaultgram.domain.build import POINT_SNAP, as_coords, build_domain, default_name, prefixed
from vaultgram.domain.dxf import domain_from_dxf
from vaultgram.domain.model import Domain
from vaultgram.domain.rhino import domain_from_3dm
from vaultgram.errors import DomainError
from vaultgram.geometry.polygons import signed_area
from vaultgram.io.files import parse_json

__all__ = ["load_domain", "domain_from_dict", "domain_from_geojson", "domain_from_dxf", "domain_from_3dm",
           "POINT_SNAP", "GEOJSON_TYPES", "GEOJSON_ROLES", "FORMATS"]

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
        raise prefixed(e, source) from None


def _list_of(d: dict, key: str, what: str) -> list:
    """The list under an optional key (empty when absent or null), or an error naming ``what`` it holds."""
    value = d.get(key)
    if value is None:
        return []
    if not isinstance(value, list):  # {} is not an empty list
        raise DomainError(f"{key}: expected a list of {what}, got {type(value).__name__}")
    return value


def _domain_from_dict(d: Any, source: str) -> Domain:
    """:func:`domain_from_dict` without the ``source`` prefix on errors."""
    if not isinstance(d, dict):
        raise DomainError(f"expected a JSON object with an 'outer' key, got {type(d).__name__}")
    if "outer" not in d:
        raise DomainError("missing required key 'outer' (a list of [x, y] pairs)")
    name = d.get("name", default_name(source))
    if not isinstance(name, str):
        raise DomainError(f"name: expected a string, got {type(name).__name__}")
    outer = as_coords(d["outer"], "outer ring")
    holes = [as_coords(h, f"hole {i}") for i, h in enumerate(_list_of(d, "holes", "rings"))]
    pts_raw = _list_of(d, "points", "[x, y] pairs")
    points = np.empty((len(pts_raw), 2))
    for i, p in enumerate(pts_raw):
        points[i] = as_coords([p], f"point feature {i}")[0]
    curves = [as_coords(c, f"curve feature {i}") for i, c in enumerate(_list_of(d, "curves", "polylines"))]
    return build_domain(name, outer, holes, points, curves, d.get("supports"))


# --------------------------------------------------------------------------------------------
# GeoJSON
# --------------------------------------------------------------------------------------------

#: The ``type`` values of a GeoJSON document that :func:`load_domain` reads as GeoJSON.
GEOJSON_TYPES = ("FeatureCollection", "Feature", "Polygon", "MultiPolygon", "GeometryCollection")


def domain_from_geojson(d: Any, source: str = "<geojson>") -> Domain:
    """Build a validated :class:`Domain` from a GeoJSON ``FeatureCollection`` or ``Feature``.

    Exactly one ``Polygon`` (or single-part ``MultiPolygon``; more parts are an error naming the
    largest) gives the outer ring and holes; ``Point``/``MultiPoint`` features give point features,
    ``LineString``/``MultiLineString`` features give curve features (in file order). A feature's
    ``role`` property (:data:`GEOJSON_ROLES`) says what it is instead: ``outer`` (the polygon),
    ``hole`` (polygons whose exterior rings are holes), ``point``, ``curve``, ``support`` (lines or
    polygon rings whose boundary vertices bear thrust, the domain's ``{"polylines": ...}``). A
    top-level ``supports`` member is kept.

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
        raise prefixed(e, source) from None


#: The ``role`` property a GeoJSON feature may carry (without one, a feature's role is its geometry's).
GEOJSON_ROLES = ("outer", "hole", "point", "curve", "support")


class _GeoJsonParts(NamedTuple):
    """What the features of a GeoJSON document hold, in file order."""

    polygons: list  # (feature index, rings)
    points: list  # [x, y]
    curves: list  # [[x, y], ...]
    holes: list  # rings of features with the role "hole"
    supports: list  # polylines of features with the role "support"


def _domain_from_geojson(d: Any, source: str) -> Domain:
    """:func:`domain_from_geojson` without the ``source`` prefix on errors; the name comes from the
    document, its properties or the polygon feature's properties, else from ``source``."""
    feats = _geojson_features(d)
    parts = _GeoJsonParts([], [], [], [], [])
    for i, f in enumerate(feats):
        if not isinstance(f, dict) or f.get("type") != "Feature":
            raise DomainError(f"features[{i}]: expected a GeoJSON Feature")
        role = _properties(f).get("role")
        if role is not None and role not in GEOJSON_ROLES:
            raise DomainError(f"features[{i}].properties.role: expected one of {', '.join(GEOJSON_ROLES)}, "
                              f"got {role!r}")
        _collect_geometry(f.get("geometry"), i, parts, role)
    if len(parts.polygons) != 1:
        raise DomainError(f"expected exactly one Polygon feature (the domain), found {len(parts.polygons)}")
    i, rings = parts.polygons[0]
    if not isinstance(rings, list) or not rings:
        raise DomainError(f"features[{i}].geometry.coordinates: expected a list of linear rings")
    name = d.get("name") or _properties(d).get("name")
    name = name or _properties(feats[i]).get("name") or default_name(source)
    outer = as_coords(rings[0], "outer ring")
    holes = [as_coords(r, f"hole {k}") for k, r in enumerate([*rings[1:], *parts.holes])]
    pts = np.array([as_coords([p], f"point feature {k}")[0] for k, p in enumerate(parts.points)]).reshape(-1, 2)
    crv = [as_coords(c, f"curve feature {k}") for k, c in enumerate(parts.curves)]
    return build_domain(str(name), outer, holes, pts, crv, _geojson_supports(d, parts.supports))


def _geojson_supports(d: dict, polylines: list):
    """The document's ``supports``, or the polylines of its features with the role ``support``."""
    if not polylines:
        return d.get("supports")
    if d.get("supports") is not None:
        raise DomainError("supports: given twice, as the document's 'supports' and as features with the role "
                          "'support'; give one")
    return {"polylines": polylines}


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


#: The geometry types each role takes.
_ROLE_TYPES = {"outer": ("Polygon", "MultiPolygon"), "hole": ("Polygon", "MultiPolygon"),
               "point": ("Point", "MultiPoint"), "curve": ("LineString", "MultiLineString"),
               "support": ("LineString", "MultiLineString", "Polygon", "MultiPolygon")}


def _collect_geometry(geom: Any, i: int, parts: _GeoJsonParts, role: str | None = None) -> None:
    """Add the polygons, points and lines of the geometry of feature ``i`` to ``parts``, by its role
    (:data:`GEOJSON_ROLES`) or, without one, by its type."""
    if not isinstance(geom, dict):
        raise DomainError(f"features[{i}].geometry: expected a GeoJSON geometry object")
    t, coords = geom.get("type"), geom.get("coordinates")
    if t == "GeometryCollection":
        for g in _multi(geom.get("geometries"), i, "geometries"):
            _collect_geometry(g, i, parts, role)
        return
    if role is not None and t not in _ROLE_TYPES[role]:
        raise DomainError(f"features[{i}]: a {t} cannot have the role {role!r} "
                          f"(expected {' or '.join(_ROLE_TYPES[role])})")
    polygons = [coords] if t == "Polygon" else _multi(coords, i) if t == "MultiPolygon" else None
    exteriors = [p[0] for p in polygons if isinstance(p, list) and p] if polygons is not None else None
    if role == "hole":
        parts.holes.extend(exteriors)
    elif role == "support":
        parts.supports.extend(exteriors if exteriors is not None else [coords] if t == "LineString"
                              else _multi(coords, i))
    elif polygons is not None:
        parts.polygons.append((i, polygons[0] if t == "Polygon" else _one_polygon(polygons, i)))
    elif t == "Point":
        parts.points.append(coords)
    elif t == "MultiPoint":
        parts.points.extend(_multi(coords, i))
    elif t == "LineString":
        parts.curves.append(coords)
    elif t == "MultiLineString":
        parts.curves.extend(_multi(coords, i))
    else:
        raise DomainError(f"features[{i}].geometry.type: unsupported geometry type {t!r}")


def _one_polygon(polygons: list, i: int) -> list:
    """The one part of a MultiPolygon; more parts are an error naming the largest (the domain is one
    polygon, and the others would be lost)."""
    if len(polygons) == 1:
        return polygons[0]
    if not polygons:
        raise DomainError(f"features[{i}].geometry: a MultiPolygon without parts")
    areas = [abs(signed_area(as_coords(p[0], f"features[{i}] part {k} exterior ring", 3)))
             if isinstance(p, list) and p else 0.0 for k, p in enumerate(polygons)]
    k = int(np.argmax(areas))
    raise DomainError(f"features[{i}].geometry: a MultiPolygon of {len(polygons)} parts: the domain is one polygon; "
                      f"the largest is part {k} (area {areas[k]:.6g}), the other {len(polygons) - 1} would be "
                      "lost: give them as separate plans, or as holes (features with the role 'hole')")


def _multi(parts: Any, i: int, key: str = "coordinates") -> list:
    """The parts of a multi-part geometry of feature ``i`` (none if absent)."""
    if parts is None:
        return []
    if not isinstance(parts, list):
        raise DomainError(f"features[{i}].geometry.{key}: expected a list, got {type(parts).__name__}")
    return parts


def _properties(obj: dict) -> dict:
    """The ``properties`` of a GeoJSON object (empty when absent or null; anything but an object is
    an error)."""
    props = obj.get("properties")
    if props is None:
        return {}
    if not isinstance(props, dict):
        raise DomainError(f"properties: expected an object or null, got {type(props).__name__}")
    return props


# --------------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------------


#: The input formats :func:`load_domain` reads, by name, and the extensions that choose them.
FORMATS = {"json": (".json",), "geojson": (".geojson",), "dxf": (".dxf",), "3dm": (".3dm",)}


def load_domain(path: str | Path, input_format: str | None = None, layers: Mapping[str, str] | None = None,
                spacing: float = 0.02) -> Domain:
    """Load a domain file (vaultgram JSON, GeoJSON, DXF or Rhino .3dm) and validate it.

    The format is ``input_format`` (a key of :data:`FORMATS`), else chosen by extension (``.json``,
    ``.geojson``, ``.dxf``, ``.3dm``) and, for unknown extensions, by content. A JSON document with
    ``"type": "FeatureCollection"`` or ``"Feature"`` is GeoJSON, otherwise vaultgram JSON.

    Parameters
    ----------
    path : str or Path
    input_format : str, optional
        ``"json"`` (vaultgram JSON or GeoJSON, by content), ``"geojson"``, ``"dxf"`` or ``"3dm"``.
    layers : dict, optional
        For DXF and .3dm: role -> layer name (:data:`vaultgram.domain.shapes.LAYERS`).
    spacing : float
        For .3dm: curves are sampled at this spacing (relative to the plan's diagonal).

    Returns
    -------
    Domain

    Raises
    ------
    DomainError
        If the file is missing, empty, malformed (JSON errors give line and column) or describes
        an invalid domain (see :func:`validate_domain`).

    Examples
    --------
    >>> d = load_domain("examples/quad_with_hole.json")
    >>> d
    Domain(name='quad_with_hole', outer=4 vertices, holes=1, points=0, curves=0)
    >>> round(d.area, 4)
    87.4538
    """
    path = Path(path)
    raw = _read_bytes(path)
    kind = _format(path, raw, input_format)
    if kind == "dxf":
        return domain_from_dxf(path, layers)
    if kind == "3dm":
        return domain_from_3dm(path, layers, spacing)
    data = _parse_json(raw, path)
    if isinstance(data, dict) and data.get("type") in GEOJSON_TYPES:
        return domain_from_geojson(data, source=str(path))
    if kind == "geojson":
        raise DomainError(f"{path}: not GeoJSON (expected a 'type' of {', '.join(GEOJSON_TYPES)})")
    return domain_from_dict(data, source=str(path))


def _format(path: Path, raw: bytes, input_format: str | None) -> str:
    """The input format: the one asked for, else by extension, else by content (JSON starts with ``{``,
    a .3dm file with its signature)."""
    if input_format is not None:
        if input_format not in FORMATS:
            raise DomainError(f"unknown input format {input_format!r}; use one of {', '.join(FORMATS)}")
        return input_format
    ext = path.suffix.lower()
    for kind, extensions in FORMATS.items():
        if ext in extensions:
            return kind
    if raw.startswith(b"3D Geometry File Format"):
        return "3dm"
    return "json" if raw.lstrip()[:1] == b"{" else "dxf"


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
    return parse_json(text, path, DomainError)
