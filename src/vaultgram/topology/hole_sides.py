"""Hole corners inside a patch side whose cut would end in a skewed fan triangle: the helpers of
``rules/corners.vgr``'s ``rebranch_hole_side_to_fan_pole`` (issue 12, item 2; paper §3.1 and §4.1).

A reflex corner ``r`` of a hole (225-315 degrees, three faces) that lies inside a side of the ring
patch ``P`` round the hole is first cut across ``P`` (:func:`~vaultgram.topology.reflex.reflex_cut`).
Where ``P``'s opposite side is the side of one triangle ``T`` of a point feature ``F``'s fan opposite
``F`` (the cut's strip ends at ``F``), the cut's last chord splits ``T``'s angle at ``F``; a long
curved branch with a skewed triangle beyond sends the chord from any of its feet within a few degrees
of a fan side, and the cut is refused (on the 700 saved random plans, 32 boundary singular vertices in
19 plans, two to three hole corners in one side of one ring patch). No threshold serves there
(session 21); the layout changes instead: the branch between ``P`` and ``T`` goes, and a chord from
``F`` straight to ``r`` splits the pentagon ``P + T`` into two quads, ``(r, b, c, F)`` and
``(F, d, a, r)`` (``a -> b`` the side of ``P`` with ``r``, ``c -> d`` the branch). ``r`` becomes the
corner of two patches (the chord rules give it its third as at any hole corner of two patches), and
``F``, singular by design (§4.1: the pole of its fan), takes two quads' corners for one triangle's
fan. Only a fallback where the cut is refused; only where the chord runs inside the pentagon, leaves
no angle below :data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE` at ``r``, none below
:data:`MIN_POLE_PART` at ``F``, the pentagon's corners at ``c`` and ``d`` do not turn past straight
(:data:`~vaultgram.topology.reflex.PAST_STRAIGHT`), and each new quad's opposite sides are within
:data:`MAX_GROUP_RATIO` of each other in length. Of several corners inside
one side, the one whose worst angle is widest.
"""

from __future__ import annotations

import math
import weakref

import numpy as np
import shapely

from vaultgram.geometry.polygons import ccw_degrees, direction, regular_valence
from vaultgram.topology import reflex
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.statecache import memo_at
from vaultgram.topology.strips import patch_sides, side_edge
from vaultgram.topology.types import PATCH_CORNER

__all__ = ["fan_rebranch_at", "fan_rebranch_edge", "fan_rebranch_index", "fan_rebranch_pole",
           "fan_rebranch_patch", "MIN_POLE_PART", "MAX_GROUP_RATIO", "register_hole_side_helpers",
           "rebranch_candidate", "inside_corner", "choose_rebranch"]

#: Degrees: the least angle either new quad may have at the fan's pole ``F``.
MIN_POLE_PART = 15.0
#: Each new quad's opposite sides (one edge group, §3.2) may differ in length by this factor at most.
#: On the 700 saved random plans: plans 86-89 (3.66: a long fan side against the hole's side) take the
#: rebranch at 4 and gain one regular hole corner each (min scaled Jacobian up 0.02-0.05); at 5, plan
#: 371 (4.75) took it too, its last boundary singularity gone for min 0.506 -> 0.452.
MAX_GROUP_RATIO = 4.0

_STATE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: {corner: choice}}


def rebranch_candidate(graph, r: int):
    """The ring patch ``P`` (a quad) with the hole corner ``r`` inside its side ``i``, its opposite
    side's plan edge and the triangle of a point feature's fan beyond it whose pole is opposite that
    edge, as ``(patch, i, edge, fan patch, pole, fan)`` (:func:`~vaultgram.topology.reflex.fan_end`);
    None where any is missing or ``r``'s cut qualifies (the rebranch is its fallback)."""
    if reflex.reflex_cut_at(graph, r):
        return None
    at = reflex.on_side(graph, r)
    if at is None or len(patch_sides(graph, at[0]).corners) != 4:
        return None
    patch, i = at
    found = patch_sides(graph, patch)
    edge = side_edge(graph, patch, found.corners[(i + 2) % 4])
    walk = reflex.cut_walk(graph, patch, edge) if edge >= 0 else None
    fan = reflex.fan_end(graph, walk) if walk is not None else None
    if fan is None or not reflex.is_feature(graph, walk.end):
        return None
    return patch, i, edge, walk.patches[0], walk.end, fan


def _score(graph, r: int, cand) -> float | None:
    """The worst angle (degrees) the chord from the pole to ``r`` leaves at ``r`` and at the pole
    (:func:`rebranch_candidate`' ``cand``), or None where a test of the module docstring refuses it."""
    patch, i, _, tri, pole, fan = cand
    found, sides = patch_sides(graph, patch), patch_sides(graph, tri)
    c, d = found.corners[(i + 2) % 4], found.corners[(i + 3) % 4]
    if set(sides.corners) != {c, d, pole}:
        return None
    pos, at = graph.get(r, "pos"), graph.get(pole, "pos")
    step = (np.asarray(at, dtype=float) - np.asarray(pos, dtype=float)) * 1e-6
    chord = shapely.LineString([np.asarray(pos) + step, np.asarray(at) - step])
    if not shapely.contains_properly(shapely.union(found.polygon, sides.polygon), chord):
        return None
    theta = boundary_angle(graph, r)
    first = ccw_degrees(reflex.boundary_ahead(graph, r), direction(pos, at))
    f_pos, f_out, whole = fan
    f_first = ccw_degrees(f_out, direction(f_pos, pos))
    turns = [reflex.patch_corner(graph, found, found.corners.index(n))[2]
             + reflex.patch_corner(graph, sides, sides.corners.index(n))[2] for n in (c, d)]
    if max(turns) > reflex.PAST_STRAIGHT or not _even(graph, found, i, r, pole, sides):
        return None
    worst_r, worst_f = min(first, theta - first), min(f_first, whole - f_first)
    return min(worst_r, worst_f) if worst_r >= reflex.MIN_CUT_ANGLE and worst_f >= MIN_POLE_PART else None


def _even(graph, found, i: int, r: int, pole: int, sides) -> bool:
    """Whether the opposite sides of each new quad, ``(r, b, c, F)`` and ``(F, d, a, r)``, are within
    :data:`MAX_GROUP_RATIO` of each other in length (one edge group each,
    §3.2: the longer's count would over-refine the shorter)."""
    side = found.sides[i]
    k = next(j for j, (_, u) in enumerate(side) if u == r)
    a_r, r_b = reflex.side_length(graph, side[:k]), reflex.side_length(graph, side[k:])
    b_c, d_a = (reflex.side_length(graph, found.sides[(i + j) % 4]) for j in (1, 3))
    c, d = found.corners[(i + 2) % 4], found.corners[(i + 3) % 4]
    tri = sides.corners.index(pole)
    f_d = reflex.side_length(graph, sides.sides[tri])
    c_f = reflex.side_length(graph, sides.sides[tri - 1])
    if (sides.corners[(tri + 1) % 3], sides.corners[tri - 1]) != (d, c):
        return False
    chord = math.dist(graph.get(r, "pos"), graph.get(pole, "pos"))
    pairs = ((r_b, c_f), (b_c, chord), (f_d, a_r), (d_a, chord))
    return all(max(p) <= MAX_GROUP_RATIO * min(p) for p in pairs)


def choose_rebranch(graph, r: int):
    """The rebranch for the hole corner ``r`` (:func:`rebranch_candidate`), where ``r`` is, of the hole
    corners inside the same side that it could serve, the one whose worst angle is widest (ties:
    the lower node id, for determinism); None otherwise."""
    cand = rebranch_candidate(graph, r)
    if cand is None:
        return None
    patch, i = cand[:2]
    scores = []
    for _, u in patch_sides(graph, patch).sides[i][1:]:
        other = cand if u == r else inside_corner(graph, u) and rebranch_candidate(graph, u)
        score = _score(graph, u, other) if other and other[:3] == cand[:3] else None
        if score is not None:
            scores.append((-score, u))
    return cand if scores and min(scores)[1] == r else None


def inside_corner(graph, u: int) -> bool:
    """Whether the boundary point ``u`` is a hole corner the rebranch may serve: no feature, the
    corner of no patch, regular valence 4 by its angle (225-315 degrees)."""
    return (not graph.get(u, "feature") and graph.degree(u, [PATCH_CORNER]) == 0
            and regular_valence(boundary_angle(graph, u)) == 4)


def _once(graph, r: int):
    """:func:`choose_rebranch`, worked out once per corner and state of the graph."""
    return memo_at(_STATE, graph, r, lambda: choose_rebranch(graph, r) if inside_corner(graph, r) else None)


def fan_rebranch_at(graph, r: int) -> bool:
    """Whether the hole corner ``r`` takes the chord to a fan's pole (see the module docstring)."""
    return _once(graph, r) is not None


def fan_rebranch_edge(graph, patch: int, r: int) -> int:
    """The plan edge (the branch between the ring patch ``patch`` and the fan triangle) that the
    rebranch of the hole corner ``r`` removes; -1 where ``r`` takes none in ``patch``."""
    got = _once(graph, r)
    return got[2] if got is not None and got[0] == patch else -1


def fan_rebranch_index(graph, patch: int, r: int) -> int:
    """The index of the side of ``patch`` inside which ``r`` lies, where it takes the rebranch; -1
    otherwise."""
    got = _once(graph, r)
    return got[1] if got is not None and got[0] == patch else -1


def fan_rebranch_patch(graph, patch: int, r: int) -> int:
    """The fan triangle's Patch node merged with ``patch`` by ``r``'s rebranch; ``patch`` otherwise."""
    got = _once(graph, r)
    return got[3] if got is not None and got[0] == patch else patch


def fan_rebranch_pole(graph, patch: int, r: int) -> int:
    """The point feature (the fan's pole) the rebranch of ``r`` joins it to; ``r`` otherwise."""
    got = _once(graph, r)
    return got[4] if got is not None and got[0] == patch else r


def register_hole_side_helpers(f) -> None:
    """Register the helpers with a function registry (``rules/corners.vgr`` calls them)."""
    f.register("fan_rebranch_at", fan_rebranch_at, ("node",), "bool", uses_graph=True, local=False)
    for name, fn, returns in (("fan_rebranch_edge", fan_rebranch_edge, "edge"),
                              ("fan_rebranch_index", fan_rebranch_index, "int"),
                              ("fan_rebranch_patch", fan_rebranch_patch, "node"),
                              ("fan_rebranch_pole", fan_rebranch_pole, "node")):
        f.register(name, fn, ("node", "node"), returns, uses_graph=True, local=False)
