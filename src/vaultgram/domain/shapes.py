"""A plan drawn in a CAD program: the shapes of a drawing, each on its layer, given their roles.

The CAD readers (:mod:`vaultgram.domain.dxf`, :mod:`vaultgram.domain.rhino`) reduce a drawing to
:class:`Shape` s -- closed curves (rings), open curves (polylines) and points, each named by its entity
and layer -- and :func:`domain_from_shapes` gives them their roles in the plan (§3.1, §4):

* a shape on a *role layer* (:data:`LAYERS`; names configurable, matched without case, a nested layer
  by the last part of its path) takes that layer's role: ``outer`` one closed curve, the outline;
  ``holes`` closed curves; ``points`` points; ``curves`` open curves; ``supports`` curves whose boundary
  vertices bear thrust (the domain's ``{"polylines": ...}`` supports);
* a shape on any other layer takes its role from its geometry: the largest closed curve is the outline
  (unless the ``outer`` layer has it), the other closed curves are holes, open curves are curve
  features, points are point features.

Nothing is dropped silently: what makes no shape (a TEXT, a HATCH, a mesh...) is named in one
:class:`~vaultgram.errors.VaultgramWarning`, and a shape that cannot be placed is an error naming it and
its layer: a closed curve outside the outline, an open curve on ``outer`` or ``holes``, a closed one on
``curves``, a curve on ``points``, no closed curve at all.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np
import shapely

from vaultgram.domain.build import build_domain
from vaultgram.domain.model import Domain
from vaultgram.errors import DomainError, VaultgramWarning
from vaultgram.geometry.polygons import signed_area

__all__ = ["Shape", "domain_from_shapes", "LAYERS", "ROLES", "warn_unused", "unit_symbol"]

#: The roles a layer can give, and the default layer name of each.
LAYERS = {"outer": "outer", "holes": "holes", "points": "points", "curves": "curves", "supports": "supports"}
ROLES = tuple(LAYERS)


#: Unit names of CAD files (DXF's ``$INSUNITS``, Rhino's ``UnitSystem``) and the symbols a domain records.
UNIT_SYMBOLS = {"millimeters": "mm", "centimeters": "cm", "decimeters": "dm", "meters": "m", "kilometers": "km",
                "inches": "in", "feet": "ft", "yards": "yd", "miles": "mi"}


def unit_symbol(name: str | None) -> str | None:
    """The symbol of a CAD unit name (``"Meters"`` -> ``"m"``), None for none or unitless.

    >>> unit_symbol("Millimeters"), unit_symbol("Unitless"), unit_symbol("Microns")
    ('mm', None, 'microns')
    """
    key = (name or "").lower()
    if key in ("", "none", "unitless", "unset"):
        return None
    return UNIT_SYMBOLS.get(key, key)


@dataclass(frozen=True, eq=False)
class Shape:
    """One drawn element of a plan.

    Attributes
    ----------
    kind : str
        ``"ring"`` (a closed curve, without its closing vertex), ``"open"`` (an open curve) or ``"point"``.
    xy : ndarray (n, 2)
        Its vertices in plan (one row for a point).
    layer : str
        The layer it is on (the last part of a nested layer's path).
    name : str
        The entity it comes from, as messages name it (``"CIRCLE #2F"``).
    """

    kind: str
    xy: np.ndarray
    layer: str
    name: str

    @property
    def where(self) -> str:
        """The shape as a message names it: entity and layer."""
        return f"{self.name} on layer '{self.layer}'"


def warn_unused(source: str, unused: Sequence[str]) -> None:
    """One warning naming every entity of a drawing that makes no shape (nothing is dropped silently)."""
    if unused:
        shown = ", ".join(unused[:10]) + (f" and {len(unused) - 10} more" if len(unused) > 10 else "")
        warnings.warn(VaultgramWarning(f"{source}: {len(unused)} entit{'y' if len(unused) == 1 else 'ies'} "
                                       f"not used (not a point or curve of the plan): {shown}"), stacklevel=3)


def domain_from_shapes(shapes: Sequence[Shape], name: str, source: str, layers: Mapping[str, str] | None = None,
                       units: str | None = None) -> Domain:
    """The validated :class:`Domain` of a drawing's shapes, their roles given by their layers or their
    geometry (see the module's docstring); ``layers`` maps roles to layer names (default :data:`LAYERS`).

    Example
    -------
    >>> square = Shape("ring", np.array([[0, 0], [4, 0], [4, 4], [0, 4]], float), "0", "LWPOLYLINE #1")
    >>> hole = Shape("ring", np.array([[1, 1], [2, 1], [2, 2], [1, 2]], float), "0", "LWPOLYLINE #2")
    >>> wall = Shape("open", np.array([[0, 0], [4, 0]], float), "supports", "LINE #3")
    >>> d = domain_from_shapes([hole, square, wall], "plan", "plan.dxf")
    >>> d.area, len(d.holes), d.supports
    (15.0, 1, {'polylines': [[[0.0, 0.0], [4.0, 0.0]]]})
    >>> domain_from_shapes([wall], "plan", "plan.dxf")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    vaultgram.errors.DomainError: plan.dxf: no closed curve: the outline must be a closed curve (found 1 open ...)
    """
    roles = _layer_roles(layers)
    by_role: dict = {role: [] for role in (*ROLES, None)}
    for s in shapes:
        by_role[roles.get(s.layer.lower())].append(s)
    _check_roles(by_role, source, {v: k for k, v in roles.items()})
    free = by_role[None]
    outer, holes = _outline(by_role["outer"], by_role["holes"], [s for s in free if s.kind == "ring"], shapes,
                            source)
    points = [s.xy[0] for s in by_role["points"] + [s for s in free if s.kind == "point"]]
    curves = [s.xy for s in by_role["curves"] + [s for s in free if s.kind == "open"]]
    supports = _support_polylines(by_role["supports"])
    return build_domain(name, outer.xy, [h.xy for h in holes], np.array(points, dtype=float).reshape(-1, 2),
                        curves, supports, units)


def _layer_roles(layers: Mapping[str, str] | None) -> dict:
    """Lower-case layer name -> role."""
    names = {**LAYERS, **(layers or {})}
    unknown = sorted(set(names) - set(ROLES))
    if unknown:
        raise DomainError(f"unknown layer role(s) {unknown}; the roles are {', '.join(ROLES)}")
    return {str(name).lower(): role for role, name in names.items()}


#: The kinds of shape each role layer may hold, and what it says of the others.
_ALLOWED = {"outer": ({"ring"}, "the outline must be a closed curve"),
            "holes": ({"ring"}, "a hole must be a closed curve"),
            "points": ({"point"}, "the layer holds point features"),
            "curves": ({"open"}, "curve features are open curves"),
            "supports": ({"open", "ring"}, "the layer holds the supported stretches, as curves")}
_KIND_NAMES = {"ring": "closed curve", "open": "open curve", "point": "point"}


def _check_roles(by_role: dict, source: str, layer_of: dict) -> None:
    """Each role layer holds the kinds of shape its role takes (one closed curve on ``outer``)."""
    for role, (kinds, why) in _ALLOWED.items():
        for s in by_role[role]:
            if s.kind not in kinds:
                raise DomainError(f"{source}: {_KIND_NAMES[s.kind]} {s.where}: {why}")
    if len(by_role["outer"]) > 1:
        names = ", ".join(s.name for s in by_role["outer"])
        raise DomainError(f"{source}: layer '{by_role['outer'][0].layer}' holds {len(by_role['outer'])} closed "
                          f"curves ({names}): the outline is one closed curve")


def _outline(outer: list, holes: list, rings: list, shapes: Sequence[Shape], source: str):
    """The outline and the holes: the ``outer`` layer's curve, else the largest closed curve on another
    layer; every other closed curve must lie inside it."""
    if not outer and not rings:
        n_open = sum(s.kind == "open" for s in shapes)
        found = sorted({s.layer for s in shapes})
        on = f", on layer(s) {', '.join(repr(x) for x in found)}" if found else ""
        raise DomainError(f"{source}: no closed curve: the outline must be a closed curve (found {n_open} open "
                          f"curve(s) and {len(shapes) - n_open} point(s){on})")
    if outer:
        shell, others = outer[0], holes + rings
    else:
        k = int(np.argmax([abs(signed_area(s.xy)) for s in rings]))
        shell, others = rings[k], holes + rings[:k] + rings[k + 1:]
    polygon = shapely.Polygon(shell.xy)
    for s in others:
        if not polygon.is_valid or not polygon.covers(shapely.MultiPoint(s.xy)):
            raise DomainError(f"{source}: closed curve {s.where} is not inside the outline {shell.where}: every "
                              "closed curve but the outline is a hole")
    return shell, others


def _support_polylines(shapes: list):
    """The domain's supports from the curves on the ``supports`` layer (closed ones closed again)."""
    if not shapes:
        return None
    lines = [np.vstack([s.xy, s.xy[:1]]) if s.kind == "ring" else s.xy for s in shapes]
    return {"polylines": [line.tolist() for line in lines]}
