"""Reading a plan from a Rhino ``.3dm`` file with rhino3dm (optional extra ``vaultgram[rhino]``).

Points, and curves of every kind (polylines, lines, arcs, circles, ellipses, NURBS and poly curves) of
the model's objects are read: polylines by their vertices, other curves sampled at equal arc lengths
no longer than the discretisation spacing times the plan's diagonal (at least 16 segments a curve).
Layers give the shapes their roles (:mod:`vaultgram.domain.shapes`); the model's unit system gives the
domain's units. Objects of other kinds (meshes, surfaces, text...) are named in a warning.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Mapping

import numpy as np

from vaultgram.domain.build import prefixed
from vaultgram.domain.model import Domain
from vaultgram.domain.shapes import Shape, domain_from_shapes, unit_symbol, warn_unused
from vaultgram.errors import DomainError
from vaultgram.geometry.polygons import bbox_diagonal

__all__ = ["domain_from_3dm", "rhino3dm_module", "MIN_SEGMENTS"]

#: The fewest segments a curve that is not a polyline is sampled with.
MIN_SEGMENTS = 16


def rhino3dm_module(what: str):
    """The ``rhino3dm`` module, or a DomainError saying which extra installs it."""
    try:
        import rhino3dm
    except ImportError:
        raise DomainError(f"{what}: .3dm files need the rhino3dm package: pip install 'vaultgram[rhino]'") from None
    return rhino3dm


def domain_from_3dm(path: str | Path, layers: Mapping[str, str] | None = None, spacing: float = 0.02) -> Domain:
    """Read a Rhino model's points and curves and build a validated :class:`Domain`.

    Parameters
    ----------
    path : str or Path
    layers : dict, optional
        Role -> layer name (default :data:`vaultgram.domain.shapes.LAYERS`).
    spacing : float
        The discretisation spacing (relative to the plan's diagonal): curves are sampled at it.

    Raises
    ------
    DomainError
        rhino3dm missing, not a readable .3dm file, no closed curve, a shape that cannot be placed
        (named by its object index, kind and layer). Unused objects are a warning.
    """
    path = Path(path)
    rhino3dm = rhino3dm_module(str(path))
    model = rhino3dm.File3dm.Read(str(path))
    if model is None:
        raise DomainError(f"{path}: not a readable .3dm file")
    shapes, unused = _shapes(model, rhino3dm, spacing)
    warn_unused(str(path), unused)
    units = unit_symbol(getattr(model.Settings.ModelUnitSystem, "name", None))
    try:
        return domain_from_shapes(shapes, path.stem, str(path), layers, units)
    except DomainError as e:
        raise prefixed(e, str(path)) from None


def _shapes(model, rhino3dm, spacing: float) -> tuple[list[Shape], list[str]]:
    """The shapes of a model's points and curves, and the names of the objects that make none."""
    names = [layer.Name for layer in model.Layers]
    objects = [(k, obj.Geometry, names[obj.Attributes.LayerIndex] if 0 <= obj.Attributes.LayerIndex < len(names)
                else "") for k, obj in enumerate(model.Objects)]
    kept = [(k, g, layer) for k, g, layer in objects if isinstance(g, (rhino3dm.Point, rhino3dm.Curve))]
    unused = [f"object {k} ({type(g).__name__}) on layer '{layer}'" for k, g, layer in objects
              if not isinstance(g, (rhino3dm.Point, rhino3dm.Curve))]
    if not kept:
        return [], unused
    corners = np.array([[(b.Min.X, b.Min.Y), (b.Max.X, b.Max.Y)] for b in (g.GetBoundingBox() for _, g, _ in kept)])
    step = spacing * max(bbox_diagonal(corners.reshape(-1, 2)), 1e-12)
    shapes = []
    for k, g, layer in kept:
        name = f"object {k} ({type(g).__name__})"
        if isinstance(g, rhino3dm.Point):
            shapes.append(Shape("point", np.array([[g.Location.X, g.Location.Y]]), layer, name))
            continue
        xy, closed = _sampled(g, step)
        shapes.append(Shape("ring" if closed else "open", xy, layer, name))
    return shapes, unused


def _sampled(curve, step: float) -> tuple[np.ndarray, bool]:
    """A curve's plan vertices: a polyline's own, else equal arc lengths of at most ``step``; a closed
    curve without its closing vertex."""
    if curve.IsPolyline():
        pl = curve.TryGetPolyline()
        xy = np.array([(pl[i].X, pl[i].Y) for i in range(pl.Count)])
    else:
        dom = curve.Domain
        dense = np.linspace(dom.T0, dom.T1, max(256, 32 * curve.SpanCount) + 1)
        pts = _points(curve, dense)
        cum = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
        n = max(MIN_SEGMENTS, math.ceil(cum[-1] / step))
        xy = _points(curve, np.interp(np.linspace(0.0, cum[-1], n + 1), cum, dense))
    closed = bool(curve.IsClosed)
    if closed and len(xy) > 1 and np.allclose(xy[0], xy[-1], rtol=0, atol=1e-9 * max(bbox_diagonal(xy), 1e-12)):
        xy = xy[:-1]
    return xy, closed


def _points(curve, params: np.ndarray) -> np.ndarray:
    """The plan points of a curve at parameters."""
    return np.array([(p.X, p.Y) for p in (curve.PointAt(float(t)) for t in params)])
