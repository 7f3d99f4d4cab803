"""Reading a plan from a DXF drawing with ezdxf (§3.1 input).

Every entity a CAD plan draws its boundaries and features with is read through ezdxf's path tools:
``LWPOLYLINE`` (arcs given by bulges flattened), 2D and 3D ``POLYLINE``, ``CIRCLE``, ``ARC``,
``ELLIPSE``, ``SPLINE``, ``LINE`` and ``POINT``; block references (``INSERT``) are exploded, their
entities on layer ``0`` taking the reference's layer. ``LINE`` and ``ARC`` entities that meet end to
end on one layer are joined into one polyline, or one closed curve when the chain closes. Curves are
flattened to 1/1000 of their own extent (the sagitta), so a circle gets about 42 vertices whatever its
size. Layers give the shapes their roles (:mod:`vaultgram.domain.shapes`); ``$INSUNITS`` gives the
domain's units. Every other entity (``TEXT``, ``HATCH``, ``DIMENSION``...) is named in a warning.
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path
from typing import Iterator, Mapping, NamedTuple

import numpy as np

from vaultgram.domain.build import prefixed
from vaultgram.domain.model import Domain
from vaultgram.domain.shapes import Shape, domain_from_shapes, unit_symbol, warn_unused
from vaultgram.errors import DomainError
from vaultgram.geometry.polygons import bbox_diagonal

__all__ = ["domain_from_dxf", "dxf_shapes", "CURVE_TYPES"]

#: The DXF entity types read as curves (through ``ezdxf.path.make_path``).
CURVE_TYPES = ("LWPOLYLINE", "POLYLINE", "CIRCLE", "ARC", "ELLIPSE", "SPLINE", "LINE")
#: Sagitta of the flattening, relative to a curve's own extent.
FLATTENING = 1e-3
#: Cubic Bezier curves a full circle or ellipse is approximated by before flattening (ezdxf's default
#: of 4 puts the vertices up to 2.7e-4 of the radius off the circle; 16 puts them within 1e-7).
CONIC_SEGMENTS = 16


def domain_from_dxf(path: str | Path, layers: Mapping[str, str] | None = None) -> Domain:
    """Read a DXF drawing's modelspace and build a validated :class:`Domain`.

    Parameters
    ----------
    path : str or Path
    layers : dict, optional
        Role -> layer name (default :data:`vaultgram.domain.shapes.LAYERS`: ``outer``, ``holes``,
        ``points``, ``curves``, ``supports``).

    Raises
    ------
    DomainError
        Not a readable DXF file; nothing usable in it; a shape that cannot be placed (named with its
        entity handle and layer). Unused entities are a :class:`~vaultgram.errors.VaultgramWarning`.
    """
    path = Path(path)
    doc = _read(path)
    shapes, unused = dxf_shapes(doc.modelspace())
    warn_unused(str(path), unused)
    if not shapes:
        found = f": only {', '.join(unused[:5])}" if unused else ": the modelspace is empty"
        raise DomainError(f"{path}: nothing usable (no point, line, polyline, circle, arc, ellipse or spline)"
                          f"{found}")
    units = unit_symbol(_unit_name(doc))
    try:
        return domain_from_shapes(shapes, path.stem, str(path), layers, units)
    except DomainError as e:
        raise prefixed(e, str(path)) from None


def _read(path: Path):
    """The ezdxf document of a DXF file, or a DomainError saying why it cannot be read."""
    import ezdxf

    try:
        return ezdxf.readfile(str(path))
    except (IOError, ezdxf.DXFStructureError, ezdxf.DXFError) as e:
        raise DomainError(f"{path}: not a readable DXF file ({e})") from None


def _unit_name(doc) -> str | None:
    """The drawing's ``$INSUNITS`` as a unit name (None when unitless)."""
    from ezdxf import units

    code = int(doc.header.get("$INSUNITS", 0))
    return units.unit_name(code) if code else None


class _Piece(NamedTuple):
    """A LINE or ARC, to be joined with those it meets end to end."""

    xy: np.ndarray
    layer: str
    name: str


def dxf_shapes(layout) -> tuple[list[Shape], list[str]]:
    """The shapes of a DXF layout (modelspace or block) and the names of the entities that make none."""
    shapes: list[Shape] = []
    pieces: list[_Piece] = []
    unused: list[str] = []
    for entity, layer, name in _entities(layout):
        t = entity.dxftype()
        if t == "POINT":
            loc = entity.dxf.location
            shapes.append(Shape("point", np.array([[loc.x, loc.y]]), layer, name))
        elif t in CURVE_TYPES and not (t == "POLYLINE" and not (entity.is_2d_polyline or entity.is_3d_polyline)):
            xy, closed = _curve(entity)
            if len(xy) < (3 if closed else 2):
                unused.append(f"{name} on layer '{layer}' (degenerate)")
            elif t in ("LINE", "ARC"):
                pieces.append(_Piece(xy, layer, name))
            else:
                shapes.append(Shape("ring" if closed else "open", xy, layer, name))
        else:
            unused.append(f"{name} on layer '{layer}'")
    return shapes + _joined(pieces), unused


def _entities(layout, insert: str = "", layer0: str = "") -> Iterator[tuple]:
    """(entity, layer, name) of every entity of a layout, block references exploded (recursively)."""
    for e in layout:
        layer = e.dxf.get("layer", "0")
        if insert and layer == "0":
            layer = layer0  # a block's entities on layer 0 are drawn on the reference's layer
        name = f"{e.dxftype()} #{e.dxf.handle}" if not insert else f"{e.dxftype()} in {insert}"
        if e.dxftype() == "INSERT":
            block = f"block '{e.dxf.name}' ({name if not insert else insert})"
            yield from _entities(e.virtual_entities(), block, layer)
        else:
            yield e, layer, name


def _curve(entity) -> tuple[np.ndarray, bool]:
    """The plan vertices of a curve entity (curved parts flattened) and whether it is closed (by its
    flag, or by ending where it starts); a closed one loses its closing vertex."""
    from ezdxf import path as ezpath

    conic = entity.dxftype() in ("CIRCLE", "ARC", "ELLIPSE")
    p = ezpath.make_path(entity, segments=CONIC_SEGMENTS) if conic else ezpath.make_path(entity)
    verts = np.array([(v.x, v.y) for v in p.control_vertices()]).reshape(-1, 2)
    if len(verts) == 0:
        return verts, False
    extent = max(bbox_diagonal(verts), 1e-12)
    if p.has_curves:
        verts = np.array([(v.x, v.y) for v in p.flattening(distance=FLATTENING * extent)])
    flag = entity.dxftype() in ("LWPOLYLINE", "POLYLINE") and bool(entity.is_closed)
    ends_meet = len(verts) > 2 and np.allclose(verts[0], verts[-1], rtol=0, atol=1e-9 * extent)
    if ends_meet:
        verts = verts[:-1]
    return verts, flag or ends_meet


def _joined(pieces: list[_Piece]) -> list[Shape]:
    """LINE and ARC entities joined end to end on each layer: chains through points where exactly two
    pieces meet; a chain that comes back to its start is a closed curve."""
    if not pieces:
        return []
    tol = 1e-9 * bbox_diagonal(np.vstack([p.xy for p in pieces]))
    out = []
    for layer in dict.fromkeys(p.layer for p in pieces):
        out += _chains([p for p in pieces if p.layer == layer], tol)
    return out


def _chains(pieces: list[_Piece], tol: float) -> list[Shape]:
    """The chains of pieces of one layer, in the order of their first piece."""
    ends = [(_key(p.xy[0], tol), _key(p.xy[-1], tol)) for p in pieces]
    at = defaultdict(list)
    for i, (a, b) in enumerate(ends):
        at[a].append(i)
        at[b].append(i)
    used = [False] * len(pieces)
    out = []
    for i, piece in enumerate(pieces):
        if used[i]:
            continue
        used[i] = True
        ahead, last = _walk(ends[i][1], pieces, ends, at, used)
        behind, first = _walk(ends[i][0], pieces, ends, at, used)
        xy = np.vstack([*[b[::-1] for b in behind[::-1]], piece.xy, *ahead])
        members = 1 + len(ahead) + len(behind)
        closed = members > 1 and first == last and len(at[first]) == 2
        name = piece.name if members == 1 else f"{piece.name} and {members - 1} joined LINE/ARC"
        out.append(Shape("ring" if closed else "open", xy[:-1] if closed else xy, piece.layer, name))
    return out


def _walk(node, pieces, ends, at, used) -> tuple[list, tuple]:
    """The vertices (each without its first) of the unused pieces that continue a chain from ``node``
    while exactly two pieces meet there, and the node where it stops."""
    out = []
    while len(at[node]) == 2:
        nxt = [j for j in at[node] if not used[j]]
        if not nxt:
            break
        j = nxt[0]
        used[j] = True
        forward = ends[j][0] == node
        xy = pieces[j].xy if forward else pieces[j].xy[::-1]
        out.append(xy[1:])
        node = ends[j][1] if forward else ends[j][0]
    return out, node


def _key(xy: np.ndarray, tol: float) -> tuple:
    """A point's key for joining: its coordinates on a grid of the joining tolerance."""
    return tuple(np.round(np.asarray(xy) / max(tol, 1e-300)).astype(np.int64).tolist())
