"""Hole corners inside a side of a triangle whose pole is an end of that side: the helpers of
``rules/corners.vgr``'s ``cut_triangle_at_hole_corner`` (issue 12, item 2; paper §3.2, Figure 3).

A reflex corner ``r`` of a hole (225-315 degrees, three faces) inside a patch side gets two faces
from it, one short. Inside a quad's side it is cut across the quad (:func:`~vaultgram.topology.reflex.
reflex_cut`); inside a side of a triangle it had no move. The triangles round a hole are mostly the
split a neighbouring hole corner took (``split_quad_at_reflex_corner_to_side``): its pole is that
corner, an end of ``r``'s side, marked and meshed as three quads round an inner point. Saved random
plans 688 and 689 (one plan): a 231.4 degree corner almost halfway along the hole side of such a
triangle (corners 167, 112, 118, pole 118), the last of their hole corners left singular.

Figure 3 reads a triangle as a quad whose side at the pole has collapsed to a point: the triangle
``(a, b, o)`` with its pole at ``b``, ``r`` inside ``a -> b``, is the quad ``(a, b, b', o)``, whose
side opposite ``a -> b`` is the pole's other side ``b -> o``. The cut of a quad's side applies: a chord
from ``r`` to a foot ``m`` on ``b -> o`` leaves the quad ``(a, r, m, o)`` and the triangle ``(r, b, m)``,
still with its pole at ``b`` (the collapsed side: its two sides there, ``b -> r`` and ``b -> m``, are
one edge group, §3.2). ``r`` becomes the corner of two patches, and the chords of ``rules/corners.vgr``
give it its third from the quad, as at any hole corner of two patches; ``m`` is a T-junction carried
on as a strip, as a quad cut's (:func:`~vaultgram.topology.reflex.cut_walk`). Mirrored where the pole
is at ``a`` (the foot on ``o -> a``). A triangle whose pole is its corner opposite ``r`` (an inner
point's fan) has no such side: a chord to the pole gives ``r`` two triangles, two faces.

The foot is the first of :data:`~vaultgram.topology.reflex.FEET` where the chord runs inside the
triangle, the strip's first chord inside the patch beyond, and the chord leaves no angle below
:data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE` at ``r`` or with the edge it meets (a quad cut's
limits) and leaves neither new patch turning past straight there, and where the new patches' edge groups
are even (:data:`MAX_RATIO`).
"""

from __future__ import annotations

import math
import weakref

from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.topology import reflex
from vaultgram.topology.corners import boundary_angle, ring_place
from vaultgram.topology.statecache import memo_at
from vaultgram.topology.strips import chord_inside, edge_cut, patch_sides, side_edge, strip_point
from vaultgram.topology.types import PATCH_CORNER

__all__ = ["triangle_cut_at", "triangle_cut", "triangle_cut_index", "triangle_cut_point", "MAX_RATIO",
           "register_hole_triangle_helpers"]

#: The sides the cut puts in one edge group (the new triangle's two sides at its pole; the quad's
#: opposite sides) may differ in length by this factor at most: a hole corner's chords' limit
#: (:data:`~vaultgram.topology.reflex.HOLE_MAX_RATIO`).
MAX_RATIO = reflex.HOLE_MAX_RATIO

_STATE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: {corner: choice}}


def _pole(graph, patch: int) -> int:
    """The corner a rule marked as the pole of the triangle ``patch``; -1 where none is marked."""
    return next((graph.ends(e)[1] for e in graph.incident(patch, [PATCH_CORNER]) if graph.get_edge(e, "pole")), -1)


def _triangle_cut(graph, r: int) -> tuple | None:
    """The cut of the hole corner ``r`` inside a triangle's side (see the module docstring):
    ``(triangle, index of the side holding r, plan edge cut, fraction, position of the foot)``, or
    None."""
    at = reflex.on_side(graph, r)
    if at is None or ring_place(graph, r)[0] == 0:
        return None
    patch, i = at
    found = patch_sides(graph, patch)
    if len(found.corners) != 3:
        return None
    pole = _pole(graph, patch)
    a, b, o = (found.corners[(i + j) % 3] for j in range(3))
    if pole not in (a, b):
        return None
    edge = side_edge(graph, patch, b if pole == b else o)  # the pole's other side
    walk = reflex.cut_walk(graph, patch, edge) if edge >= 0 else None
    if walk is None:
        return None
    for fraction in reflex.FEET[:1] if walk.end is None else reflex.FEET:
        foot = edge_cut(graph, edge, fraction)[1]
        if _foot_fits(graph, r, found, walk, edge, fraction, foot) and _even(graph, r, found, i, pole, foot):
            return patch, i, edge, fraction, (float(foot[0]), float(foot[1]))
    return None


def _foot_fits(graph, r: int, found, walk, edge: int, fraction: float, foot) -> bool:
    """Whether the chord from ``r`` to ``foot`` (``fraction`` along ``edge``) runs inside the triangle
    ``found``, the strip's first chord from there runs inside the patch beyond (a fan triangle's
    halved into two of :data:`~vaultgram.topology.reflex.MIN_FAN_HALF`), and the chord leaves no angle
    below :data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE` at ``r`` (from the boundary leaving it, as
    its angle is measured) or with the edge it meets, and neither new patch turns past straight at ``r``
    (:data:`~vaultgram.topology.reflex.PAST_STRAIGHT`: the triangle's corner there stays one, and the quad's
    need not wait for the chord that gives ``r`` its third patch; plans 688/689: 73.1 and 158.3)."""
    pos = graph.get(r, "pos")
    if not chord_inside(found, pos, foot):
        return False
    beyond = patch_sides(graph, walk.patches[0])
    to = strip_point(graph, walk.edges[1]) if len(walk.edges) > 1 else walk.end_point(graph)
    fan, curve = reflex.fan_end(graph, walk), reflex.curve_end(graph, walk)
    if not chord_inside(beyond, foot, to) or fan is not None and not reflex.halves_fan(fan, foot, reflex.MIN_FAN_HALF):
        return False
    if curve is not None and not reflex.halves_fan(curve, foot):
        return False
    before, _, after = edge_cut(graph, edge, fraction)
    ahead = after[0] if len(after) else graph.get(graph.ends(edge)[1], "pos")
    back = before[-1] if len(before) else graph.get(graph.ends(edge)[0], "pos")
    d_chord = direction(pos, foot)
    first = ccw_degrees(reflex.boundary_ahead(graph, r), d_chord)
    meet = ccw_degrees(direction(back, ahead), d_chord) % 180.0
    rest = boundary_angle(graph, r) - first
    return min(first, rest, meet, 180.0 - meet) >= reflex.MIN_CUT_ANGLE and max(first, rest) < reflex.PAST_STRAIGHT


def _even(graph, r: int, found, i: int, pole: int, foot) -> bool:
    """Whether the new triangle's sides at the pole, and the new quad's opposite sides, are within
    :data:`MAX_RATIO` of each other in length (one edge group each, §3.2)."""
    side = found.sides[i]
    k = next(j for j, (_, u) in enumerate(side) if u == r)
    a_r, r_b = reflex.side_length(graph, side[:k]), reflex.side_length(graph, side[k:])
    chord = math.dist(graph.get(r, "pos"), foot)
    ahead = pole == found.corners[(i + 1) % 3]  # triangle (r, b, m) and quad (a, r, m, o); else (a, r, m), (r, b, o, m)
    far, other = (found.sides[(i + 1) % 3], found.sides[(i + 2) % 3])[::1 if ahead else -1]
    to_m = math.dist(graph.get(pole, "pos"), foot)  # along the pole's other side (straight enough for a ratio)
    rest = reflex.side_length(graph, far) - to_m
    pairs = ((r_b, to_m), (a_r, rest), (chord, reflex.side_length(graph, other))) if ahead else \
        ((a_r, to_m), (r_b, rest), (chord, reflex.side_length(graph, other)))
    return all(min(p) > 0 and max(p) <= MAX_RATIO * min(p) for p in pairs)


def _once(graph, r: int):
    """:func:`_triangle_cut`, worked out once per corner and state of the graph."""
    return memo_at(_STATE, graph, r, lambda: _triangle_cut(graph, r))


def triangle_cut_at(graph, r: int) -> bool:
    """Whether the hole corner ``r`` takes a cut across the triangle on whose side it lies."""
    return _once(graph, r) is not None


def triangle_cut_index(graph, patch: int, r: int) -> int:
    """The index of the side of the triangle ``patch`` inside which ``r`` lies, where it takes the
    cut there; -1 otherwise."""
    got = _once(graph, r)
    return got[1] if got is not None and got[0] == patch else -1


def triangle_cut(graph, patch: int, r: int) -> int:
    """The plan edge (the pole's other side of the triangle ``patch``) that ``r``'s cut ends on; -1
    where ``r`` takes none in ``patch``."""
    got = _once(graph, r)
    return got[2] if got is not None and got[0] == patch else -1


def triangle_cut_point(graph, patch: int, r: int) -> tuple[float, float]:
    """Where ``r``'s cut across the triangle ``patch`` ends (``r``'s position where there is none)."""
    got = _once(graph, r)
    if got is None or got[0] != patch:
        pos = graph.get(r, "pos")
        return float(pos[0]), float(pos[1])
    return got[4]


def register_hole_triangle_helpers(f) -> None:
    """Register the helpers with a function registry (``rules/corners.vgr`` calls them)."""
    f.register("triangle_cut_at", triangle_cut_at, ("node",), "bool", uses_graph=True, local=False)
    for name, fn, returns in (("triangle_cut_index", triangle_cut_index, "int"), ("triangle_cut", triangle_cut, "edge"),
                              ("triangle_cut_point", triangle_cut_point, "vec2")):
        f.register(name, fn, ("node", "node"), returns, uses_graph=True, local=False)
