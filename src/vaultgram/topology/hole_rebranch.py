"""Hole corners beside a rebranch's end: the helper of ``rules/corners.vgr``'s
``move_rebranch_to_hole_corner`` (issue 12, item 2; paper §3.1 and §4.1).

A reflex corner ``r`` of a hole (225-315 degrees, three faces) left inside a side of a quad ``P`` by
every cut and fallback of ``rules/corners.vgr`` (its cut's strip ends in a narrow fan triangle that
neither a foot, the rebranch to the fan's pole nor the hub serves) keeps two faces: a boundary
singularity. Where ``r``'s neighbour ``w`` along the ring, one boundary edge away, is the corner of
``P`` where that side ends (or starts) and the end of a rebranch from ``P``'s skeleton vertex ``x``
(a side of both ``P`` and the patch ``Q`` beyond), the rebranch's end moves from ``w`` to
``r``: it still joins ``x`` to the boundary within one boundary edge of where ``x``'s maximal circle
touches it (§3.1). ``r`` becomes the corner of ``P`` and ``Q`` (the chords of ``rules/corners.vgr`` give
it its third patch, as at any hole corner of two patches), ``w`` a point inside ``Q``'s side with the
two faces its straight angle asks for. Only where the moved rebranch runs inside ``P``, leaves
:data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE` to under 180 degrees at ``r`` on either side and at
least :data:`~vaultgram.topology.reflex.MIN_ANGLE` at ``x`` in ``P``, and ``Q``'s angle at ``x`` stays
within :data:`MAX_BEYOND_ANGLE`. On the 700 saved random plans it serves plan 317 only (the 252 degree
corner of a pentagonal hole, 175.6 / 76.4 degrees at it, the rebranch's old end 0.55 away): 1 boundary
singular vertex to 0, min scaled Jacobian 0.349 either way.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.polygons import ccw_degrees, direction, regular_valence
from vaultgram.topology import reflex
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.hole_sides import inside_corner
from vaultgram.topology.strips import chord_inside, patch_sides
from vaultgram.topology.types import PATCH_CORNER

__all__ = ["rebranch_to_hole_corner", "MAX_BEYOND_ANGLE", "register_hole_rebranch_helpers"]

#: Degrees: the widest angle the patch beyond (``Q``) may have at ``x`` once the rebranch has moved
#: (it gains what ``P`` gives up there; a quad corner of 165 degrees has a scaled Jacobian of 0.26).
MAX_BEYOND_ANGLE = 165.0


def rebranch_to_hole_corner(graph, patch: int, other: int, w: int, x: int, r: int) -> bool:
    """Whether the rebranch from the skeleton vertex ``x`` to the boundary point ``w`` (a corner of the
    quad ``patch`` and of the patch ``other`` beyond the rebranch) may move to the hole corner ``r``,
    ``w``'s neighbour along the ring inside ``patch``'s side at ``w`` (see the module docstring)."""
    if not inside_corner(graph, r) or graph.get(w, "feature") or graph.degree(w, [PATCH_CORNER]) != 2:
        return False
    at = reflex.on_side(graph, r)
    found, beyond = patch_sides(graph, patch), patch_sides(graph, other)
    if at is None or at[0] != patch or found is None or beyond is None or len(found.corners) != 4:
        return False
    if regular_valence(boundary_angle(graph, w)) != 3 or x not in found.corners or x not in beyond.corners:
        return False
    i, k = at[1], found.corners.index(x)
    beside = (found.corners[k - 1], found.corners[(k + 1) % 4])
    return w in (found.corners[i], found.corners[(i + 1) % 4]) and w in beside and _fits(graph, found, beyond, k, w, r)


def _fits(graph, found, beyond, k: int, w: int, r: int) -> bool:
    """Whether the rebranch from the corner ``k`` (``x``) of the quad ``found`` moved from its corner ``w``
    to ``r`` runs inside it and leaves no angle below :data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE`
    at ``r`` (either side) and none of 180 or more (either patch would turn there), none below
    :data:`~vaultgram.topology.reflex.MIN_ANGLE` at ``x`` in ``found``, and the patch ``beyond`` (which
    gains the rest of ``x``'s angle) none above :data:`MAX_BEYOND_ANGLE` there."""
    x = found.corners[k]
    pos, to = np.asarray(graph.get(r, "pos"), dtype=float), np.asarray(graph.get(x, "pos"), dtype=float)
    if not chord_inside(found, pos, to):
        return False
    theta, first = boundary_angle(graph, r), ccw_degrees(reflex.boundary_ahead(graph, r), direction(pos, to))
    _, d_out, whole = reflex.patch_corner(graph, found, k)
    at_x = ccw_degrees(d_out, direction(to, pos))  # from the side leaving x to the moved rebranch
    in_patch = at_x if w == found.corners[k - 1] else whole - at_x
    grown = reflex.patch_corner(graph, beyond, beyond.corners.index(x))[2] + whole - in_patch
    parts = (first, theta - first)
    return (min(parts) >= reflex.MIN_CUT_ANGLE and max(parts) < 180.0 and in_patch >= reflex.MIN_ANGLE
            and grown <= MAX_BEYOND_ANGLE)


def register_hole_rebranch_helpers(f) -> None:
    """Register the helper with a function registry (``rules/corners.vgr`` calls it)."""
    f.register("rebranch_to_hole_corner", rebranch_to_hole_corner, ("node", "node", "node", "node", "node"), "bool",
               uses_graph=True, local=False)
