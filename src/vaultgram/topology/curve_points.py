"""Curve points short of patches on one side: where a hole corner's cut may end (issue 12, acceptance 3).

A curve feature is a cut the layout keeps (§4.2), so a strip may not end in a triangle at one of its
points (:func:`~vaultgram.topology.reflex.strip_beyond`): splitting the triangle there gives the point
one patch more. Its two sides are two boundaries of the cut, each with its own angle (a bend of 19.8
degrees inside a V-shaped curve is 340.2 outside), and each side asks for the faces a boundary point
of that angle does (``1 + max(1, round(theta / 90))`` less one, :func:`regular_valence`). Where the
triangle's side of the point has fewer patches than that, one patch more makes it regular there, not
irregular: saved random plans 133 and 134 of session 32's draw, a hexagonal hole's 240 degree corner
whose cut's strip is the triangle beyond a ring patch, 166.3 degrees at the bend of a V-shaped curve
whose outer side had three patches (it asks for four).
"""

from __future__ import annotations

from vaultgram.geometry.polygons import ccw_degrees, direction, regular_valence
from vaultgram.topology.patches import half_edge_polyline
from vaultgram.topology.strips import patch_sides
from vaultgram.topology.types import CURVE, CURVE_POINT, PATCH_CORNER

__all__ = ["short_side"]


def _leaving(graph, n: int, edge: int, pos) -> float:
    """The direction (radians) in which the plan edge ``edge`` leaves the point ``n`` at ``pos``."""
    return direction(pos, half_edge_polyline(graph, edge, n)[1])


def _sector(graph, n: int, pos) -> tuple[float, float] | None:
    """The direction (radians) of the first of the two curve segments at the curve point ``n`` and the
    angle (degrees) counter-clockwise from it to the second: one side of the curve there, the rest of
    360 the other; None unless ``n`` is inside one curve (two curve segments)."""
    curve = list(graph.incident(n, [CURVE]))
    if len(curve) != 2:
        return None
    first = _leaving(graph, n, curve[0], pos)
    return first, ccw_degrees(first, _leaving(graph, n, curve[1], pos))


def short_side(graph, n: int, patch: int) -> bool:
    """Whether the point ``n`` inside a curve feature (a ``CurvePoint``, not a free end) is the corner
    of fewer patches on the side of the curve where the patch ``patch`` lies than that side's angle asks
    faces for (see the module docstring): one patch more there, a strip's end, leaves it no worse."""
    if graph.node_type(n) != CURVE_POINT:
        return False
    pos = graph.get(n, "pos")
    sector = _sector(graph, n, pos)
    if sector is None:
        return False
    first, theta = sector

    def side(q: int) -> bool | None:  # True on the first side, None for a patch not found
        found = patch_sides(graph, q)
        if found is None or n not in found.corners:
            return None
        e, u = found.sides[found.corners.index(n)][0]
        return ccw_degrees(first, _leaving(graph, u, e, pos)) < theta - 1e-9

    patches = sorted({graph.ends(e)[0] for e in graph.incident(n, [PATCH_CORNER])})
    sides = [side(q) for q in patches]
    mine = side(patch)
    if mine is None or any(s is None for s in sides):
        return False
    angle = theta if mine else 360.0 - theta
    return sides.count(mine) < int(regular_valence(angle)) - 1
