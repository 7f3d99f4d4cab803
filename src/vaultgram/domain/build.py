"""Normalising and validating what a reader found into a :class:`~vaultgram.domain.model.Domain`.

Every reader (:mod:`vaultgram.domain.readers`, :mod:`vaultgram.domain.cad`) ends in
:func:`build_domain`: closing vertices dropped, the outer ring counter-clockwise and the holes
clockwise, point features digitised just outside the boundary projected onto it, the supports'
shape checked, then :func:`~vaultgram.domain.validation.validate_domain`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Iterable

import numpy as np
import shapely

from vaultgram.domain.model import REL_TOL, Domain
from vaultgram.domain.validation import check_finite, validate_domain
from vaultgram.errors import DomainError
from vaultgram.geometry.frames import local_origin, to_local
from vaultgram.geometry.polygons import bbox_diagonal, signed_area
from vaultgram.geometry.text import plan_frame
from vaultgram.limits import MAX_COORDINATE, MAX_OFFSET

__all__ = ["build_domain", "as_coords", "prefixed", "default_name", "POINT_SNAP"]


#: Point features lying *outside* the domain but closer than ``POINT_SNAP * bbox diagonal`` to its
#: boundary are boundary point features (§4.1) digitised against the true curve rather than against
#: its polyline: they are projected onto the boundary. ``POINT_SNAP`` equals the default
#: discretisation spacing, below which the boundary is not resolved anyway. Farther points are an
#: error.
POINT_SNAP = 0.02


def as_coords(value: Any, what: str, min_len: int = 0) -> np.ndarray:
    """Turn a JSON list of ``[x, y]`` pairs into an (n, 2) float array, naming bad entries."""
    if not isinstance(value, (list, tuple)):
        raise DomainError(f"{what}: expected a list of [x, y] pairs, got {type(value).__name__}")
    out = _plain_coords(value)
    if out is not None and len(out) >= min_len:
        return out
    out = np.empty((len(value), 2), dtype=np.float64)
    for i, p in enumerate(value):
        if (
            not isinstance(p, (list, tuple))
            or len(p) < 2
            or not all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in p[:2])
        ):
            raise DomainError(f"{what}, vertex {i}: expected [x, y] with two numbers, got {_short(p)}")
        out[i] = (_coordinate(p[0], what, i), _coordinate(p[1], what, i))
    if len(out) < min_len:
        raise DomainError(f"{what}: expected at least {min_len} vertices, got {len(out)}")
    return out


def _plain_coords(value) -> np.ndarray | None:
    """``value`` as an (n, 2) array when every vertex is a list of two or more plain numbers (JSON
    integers and floats, not bools), finite and at most :data:`~vaultgram.limits.MAX_COORDINATE`;
    None otherwise, and :func:`as_coords` then finds and names the bad vertex one by one. Why: the
    one-by-one check took 4 s on a ring of 10^5 vertices."""
    if not all(type(p) in (list, tuple) and len(p) >= 2 for p in value):
        return None
    xy = [p[:2] for p in value]
    if not {type(c) for p in xy for c in p} <= {int, float}:
        return None
    try:
        out = np.array(xy, dtype=np.float64).reshape(-1, 2)
    except OverflowError:  # an integer beyond the floats
        return None
    if not (np.isfinite(out).all() and (not len(out) or np.abs(out).max() <= MAX_COORDINATE)):
        return None
    return out


def _coordinate(c, what: str, i: int) -> float:
    """A coordinate as a float: finite and at most :data:`~vaultgram.limits.MAX_COORDINATE` in size
    (beyond, squared lengths and areas overflow or lose every digit of the plan's shape)."""
    try:
        x = float(c)
    except OverflowError:
        x = float("inf")
    if not np.isfinite(x):
        raise DomainError(f"{what}, vertex {i}: coordinate is not finite ({_short(c)})")
    if abs(x) > MAX_COORDINATE:
        raise DomainError(f"{what}, vertex {i}: coordinate {x:g} is larger than {MAX_COORDINATE:g} "
                          "(give the plan in other units, or nearer the origin)")
    return x


def _short(value) -> str:
    """``repr`` of a value, cut at 60 characters."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def normalise_ring(ring: np.ndarray, what: str, ccw: bool, tol: float) -> np.ndarray:
    """Drop the closing vertex and fix the orientation (outer ccw, holes cw)."""
    check_finite(ring, what)
    if len(ring) >= 2 and np.hypot(*(ring[0] - ring[-1])) <= tol:
        ring = ring[:-1]
    area = signed_area(ring) if len(ring) >= 3 else 0.0
    if (area < 0) == ccw and area != 0:
        ring = np.roll(ring[::-1], 1, axis=0)  # reversed, but vertex 0 stays vertex 0
    return np.ascontiguousarray(ring, dtype=np.float64)


def normalise_supports(value: Any) -> Any:
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
        for i, r in enumerate(non_empty_list(value["rings"], "supports.rings", '"outer" or hole indices')):
            if not (r == "outer" or (isinstance(r, int) and not isinstance(r, bool) and r >= 0)):
                raise DomainError(
                    f'supports.rings[{i}]: expected "outer" or a hole index (integer >= 0), got {r!r}'
                )
        return value
    if keys == {"polylines"}:
        for i, pl in enumerate(non_empty_list(value["polylines"], "supports.polylines", "polylines")):
            check_finite(as_coords(pl, f"supports.polylines[{i}]", min_len=2), f"supports.polylines[{i}]")
        return value
    raise DomainError(
        f'supports: expected exactly one of the keys "rings" or "polylines", got {sorted(value)}'
    )


def non_empty_list(value: Any, what: str, items: str) -> list:
    """``value`` if it is a non-empty list, else an error saying what ``items`` it should hold."""
    if not isinstance(value, list) or not value:
        raise DomainError(f"{what}: expected a non-empty list of {items}")
    return value


def build_domain(
    name: str,
    outer: np.ndarray,
    holes: Iterable[np.ndarray],
    points: np.ndarray,
    curves: Iterable[np.ndarray],
    supports: Any,
    units: str | None = None,
) -> Domain:
    """Normalise raw arrays into a validated Domain (every reader ends here); a plan far from the
    origin is moved to its local frame (:mod:`vaultgram.geometry.frames`), its messages still naming
    the plan's coordinates."""
    check_finite(outer, "outer ring")
    check_offset(outer)
    origin, diagonal = local_origin(outer), bbox_diagonal(outer)
    with plan_frame(origin, diagonal):
        return _normalised(name, in_frame(outer, origin, diagonal), [in_frame(h, origin, diagonal) for h in holes],
                           in_frame(np.asarray(points, dtype=np.float64).reshape(-1, 2), origin, diagonal),
                           [in_frame(c, origin, diagonal) for c in curves], supports, units, origin)


def in_frame(coords, origin, diagonal: float) -> np.ndarray:
    """``coords`` in the plan's local frame (:func:`~vaultgram.geometry.frames.to_local`), every
    coordinate smaller than double precision's resolution at the plan's size (``eps * diagonal``) made
    zero.

    Such a coordinate carries no geometry: beside a plan of 10 m, -2e-311 and 0 are the same number
    everywhere but at the origin, and the same plan moved by a metre loses the difference. Kept, it
    gives the plan a detail below every tolerance of the method: saved random plan 183 (a hypothesis
    draw) has a hole corner at y = -2.2e-311, and the max-min optimisation slid a boundary vertex to
    (x, 0) beside it, a quad side of 2e-311 whose corners still measured well. Made zero, the plan
    is meshed as wherever else it lies.

    >>> in_frame(np.array([[3.5, -2.2e-311], [1e-17, 4.0]]), (0.0, 0.0), 10.0).tolist()
    [[3.5, 0.0], [0.0, 4.0]]
    """
    local = np.asarray(to_local(coords, origin), dtype=np.float64)
    return np.where(np.abs(local) < np.finfo(np.float64).eps * diagonal, 0.0, local)


def _normalised(name, outer, holes, points, curves, supports, units, origin) -> Domain:
    """The Domain of :func:`build_domain`, its rings and features already in their local frame."""
    tol = REL_TOL * bbox_diagonal(outer)
    outer = normalise_ring(outer, "outer ring", ccw=True, tol=tol)
    holes = tuple(
        normalise_ring(h, f"hole {i}", ccw=False, tol=tol) for i, h in enumerate(holes)
    )
    points = np.ascontiguousarray(points)
    curves = tuple(np.ascontiguousarray(np.asarray(c, dtype=np.float64)) for c in curves)
    supports = normalise_supports(supports)
    points = snap_points(outer, holes, points, POINT_SNAP * bbox_diagonal(outer))
    for arr in (outer, *holes, points, *curves):
        arr.setflags(write=False)
    dom = Domain(str(name), outer, holes, points, curves, supports, units, origin)
    validate_domain(dom)
    return dom


def check_offset(outer: np.ndarray) -> None:
    """Refuse a plan lying so far from the origin, for its size, that double precision keeps too few
    digits of its shape to write it back (more than :data:`~vaultgram.limits.MAX_OFFSET` diagonals
    away); nearer far plans are worked on in a local frame."""
    if len(outer) < 2:
        return
    diagonal = bbox_diagonal(outer)
    far = float(np.abs(outer).max())
    if far > MAX_OFFSET * diagonal:
        lo = outer.min(axis=0)
        raise DomainError(
            f"outer ring: the plan lies at ({lo[0]:g}, {lo[1]:g}), {far / max(diagonal, 1e-300):.3g} times its size "
            f"(diagonal {diagonal:g}) from the origin, beyond {MAX_OFFSET:g}: translate it nearer the origin")


def snap_points(outer, holes, points, snap):
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


def prefixed(e: DomainError, source: str) -> DomainError:
    """The same error, its message starting with the file (or other source) it is about."""
    msg = str(e)
    if source and not msg.startswith(source):
        msg = f"{source}: {msg}"
    return DomainError(msg)


def default_name(source: str) -> str:
    """A domain's name when its file gives none: the file's stem (``domain`` for other sources)."""
    return Path(source).stem if source and not source.startswith("<") else "domain"
