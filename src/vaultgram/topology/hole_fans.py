"""Hole corners whose cut would end in a sliver of a point feature's fan: the helpers of
``rules/corners.vgr``'s ``merge_fan_triangles_for_hole_corner`` (issue 12, item 2; paper §3.2 and §4.1).

A reflex corner ``r`` of a hole (225-315 degrees, three faces) inside a side of the ring patch ``P``
round the hole is cut across ``P`` (:func:`~vaultgram.topology.reflex.reflex_cut`). Where ``P``'s
opposite side is the side of one triangle ``T`` of a point feature ``F``'s fan opposite ``F``, the
cut's strip ends at ``F`` and its last chord splits ``T``'s angle there. Where ``T`` is a sliver whose
side opposite ``F`` runs nearly radially from ``F`` (a skeleton branch wrapped round the hole beside
the fan's next side: saved random plan 406, ``T`` 42 degrees at ``F``, 3.2 at its corner on the
skeleton, 9.6 m long), no foot halves it, the rebranch to ``F`` and the hub leave angles far outside
their limits, and ``r`` keeps two faces: a boundary singularity.

``T`` and the triangle ``T'`` of the same fan beyond one of ``T``'s sides at ``F`` together are a quad
``(F, x, s, y)`` (``s`` the other end of their common side, the fan side that goes), the layout
:func:`merge_triangles_at_feature` of ``rules/patching.vgr`` offers round inner features: ``F`` keeps
the two triangles' angles as one quad corner (§4.1: a point feature, singular by design, with one
fan triangle less), ``s`` loses a patch corner. The cut's strip then crosses that quad from ``P``'s
side to the quad's opposite side, ``T'``'s side from ``F`` (on plan 406 the outer boundary, where it
ends at a free point), and ``r`` becomes the corner of two patches; the chords of ``rules/corners.vgr``
give it its third, as at any hole corner of two patches. Only where every angle of the quad is within
:data:`MIN_QUAD_ANGLE` to :data:`MAX_QUAD_ANGLE`, its opposite sides are within
:data:`~vaultgram.topology.reflex.HOLE_MAX_RATIO` of each other in length, the quad's side opposite
``P``'s is on the boundary with a free point for the strip to end at, and the cut qualifies once the
triangles are merged (a foot of :data:`~vaultgram.topology.reflex.FEET` whose chord runs inside
``P``, whose strip's chord runs inside the quad, and that leaves no angle below
:data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE`, as :func:`~vaultgram.topology.reflex.choose_cut`
asks): the merge is made only for a cut that then certainly follows.
"""

from __future__ import annotations

import weakref

import numpy as np
import shapely

from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.topology import reflex
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.hole_sides import inside_corner, rebranch_candidate
from vaultgram.topology.statecache import memo_at
from vaultgram.topology.strips import (
    SPLITTABLE,
    chord_inside,
    edge_cut,
    patch_across,
    patch_sides,
    strip_boundary_end,
    strip_point,
)
from vaultgram.topology.types import BOUNDARY, PATCH_CORNER

__all__ = ["fan_merge_at", "fan_merge_edge", "fan_merge_first", "fan_merge_second", "MIN_QUAD_ANGLE",
           "MAX_QUAD_ANGLE", "register_hole_fan_helpers"]

#: Degrees: no angle of the merged quad narrower (a quad corner of 30 degrees has a scaled Jacobian of
#: 0.5; the hub's limit, :data:`~vaultgram.topology.hole_hub.MIN_HUB_ANGLE`).
MIN_QUAD_ANGLE = 30.0
#: Degrees: no angle of the merged quad wider (a quad corner of 165 degrees has a scaled Jacobian of
#: 0.26; the hub's limit, :data:`~vaultgram.topology.hole_hub.MAX_HUB_ANGLE`).
MAX_QUAD_ANGLE = 165.0

_STATE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: {corner: choice}}


def _marked_pole(graph, patch: int) -> int:
    """The corner a rule marked as the pole of the triangle ``patch``; -1 where none is marked."""
    return next((graph.ends(e)[1] for e in graph.incident(patch, [PATCH_CORNER]) if graph.get_edge(e, "pole")), -1)


def _fan_merge(graph, r: int):
    """The merge for the hole corner ``r`` (see the module docstring): ``(common fan side, triangle
    (F, x, s), triangle (F, s, y))``, or None. A fallback where the cut is refused
    (:func:`~vaultgram.topology.hole_sides.rebranch_candidate`: its strip is one fan triangle)."""
    if not inside_corner(graph, r):
        return None
    cand = rebranch_candidate(graph, r)
    if cand is None:
        return None
    patch, i, edge, tri, pole, _ = cand
    sides = patch_sides(graph, tri)
    if _marked_pole(graph, tri) != pole or len(sides.corners) != 3:
        return None
    t = sides.corners.index(pole)
    for k in ((t - 1) % 3, t):  # T's side arriving at the pole, then the one leaving it
        got = _pair(graph, r, patch, edge, tri, k, pole)
        if got is not None:
            return got
    return None


def _pair(graph, r: int, patch: int, edge: int, tri: int, k: int, pole: int):
    """The merge of the fan triangle ``tri`` with the triangle beyond its side ``k`` (a side at the pole)
    where it serves ``r``'s cut across ``patch`` to ``edge``; None otherwise."""
    sides = patch_sides(graph, tri)
    side = sides.sides[k]
    if len(side) != 1 or graph.edge_type(side[0][0]) not in SPLITTABLE:
        return None
    common = side[0][0]
    beyond = patch_across(graph, tri, common)
    other = patch_sides(graph, beyond[0]) if beyond is not None else None
    if other is None or len(other.corners) != 3 or _marked_pole(graph, beyond[0]) != pole:
        return None
    first, second = (tri, beyond[0]) if sides.corners[(k + 1) % 3] == pole else (beyond[0], tri)
    one, two = patch_sides(graph, first), patch_sides(graph, second)
    if one.corners[one.corners.index(pole) - 1] != two.corners[(two.corners.index(pole) + 1) % 3]:
        return None
    if not _quad_fits(graph, one, two, pole):
        return None
    far = two.sides[(two.corners.index(pole) + 2) % 3] if first == tri else one.sides[one.corners.index(pole)]
    polygon = shapely.union(sides.polygon, other.polygon)
    return (common, first, second) if _cut_fits(graph, r, patch, edge, polygon, far, beyond[0]) else None


def _quad_fits(graph, one, two, pole: int) -> bool:
    """Whether the quad ``(F, x, s, y)`` of the triangles ``one`` = ``(F, x, s)`` and ``two`` =
    ``(F, s, y)`` has every angle within :data:`MIN_QUAD_ANGLE` to :data:`MAX_QUAD_ANGLE` and its
    opposite sides within :data:`~vaultgram.topology.reflex.HOLE_MAX_RATIO` of each other in length
    (one edge group each, §3.2)."""
    a, b = one.corners.index(pole), two.corners.index(pole)
    angle = [reflex.patch_corner(graph, one, j)[2] for j in range(3)]
    other = [reflex.patch_corner(graph, two, j)[2] for j in range(3)]
    quad = (angle[a] + other[b], angle[(a + 1) % 3], angle[(a + 2) % 3] + other[(b + 1) % 3], other[(b + 2) % 3])
    if not all(MIN_QUAD_ANGLE <= q <= MAX_QUAD_ANGLE for q in quad):
        return False
    length = [reflex.side_length(graph, one.sides[(a + j) % 3]) for j in range(2)]
    beyond = [reflex.side_length(graph, two.sides[(b + j) % 3]) for j in (1, 2)]
    pairs = ((length[0], beyond[0]), (length[1], beyond[1]))
    return all(min(p) > 0 and max(p) <= reflex.HOLE_MAX_RATIO * min(p) for p in pairs)


def _cut_fits(graph, r: int, patch: int, edge: int, polygon, far, beyond: int) -> bool:
    """Whether ``r``'s cut across ``patch`` to ``edge`` qualifies once the triangles are merged into
    ``polygon``: the quad's side ``far`` opposite ``edge`` (the side of the triangle ``beyond``) is on the
    boundary with a free point for the strip's end (:func:`~vaultgram.topology.strips.strip_boundary_end`),
    the strip's chord from ``edge``'s strip point runs inside the quad, and a foot of
    :data:`~vaultgram.topology.reflex.FEET` passes (:func:`_foot_fits`)."""
    if any(graph.edge_type(e) != BOUNDARY for e, _ in far):
        return False
    start = far[0][1]
    end = strip_boundary_end(graph, beyond, start)
    if end == start:
        return False
    to = graph.get(end, "pos")
    if not _inside(polygon, strip_point(graph, edge), to):
        return False
    found = patch_sides(graph, patch)
    return any(_foot_fits(graph, r, found, edge, f, polygon, to) for f in reflex.FEET)


def _foot_fits(graph, r: int, found, edge: int, fraction: float, polygon, to) -> bool:
    """Whether the cut from ``r`` to ``fraction`` along ``edge`` runs inside the quad ``found``, its
    strip's chord from there to ``to`` runs inside the merged quad ``polygon``, and it leaves no angle
    below :data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE` at ``r`` (from the boundary leaving it, and
    the rest) or with ``edge`` (:func:`~vaultgram.topology.reflex.choose_cut`'s tests)."""
    before, foot, after = edge_cut(graph, edge, fraction)
    pos = graph.get(r, "pos")
    if not chord_inside(found, pos, foot) or not _inside(polygon, foot, to):
        return False
    ahead = after[0] if len(after) else graph.get(graph.ends(edge)[1], "pos")
    back = before[-1] if len(before) else graph.get(graph.ends(edge)[0], "pos")
    d_chord = direction(pos, foot)
    first = ccw_degrees(reflex.boundary_ahead(graph, r), d_chord)
    meet = ccw_degrees(direction(back, ahead), d_chord) % 180.0
    return min(first, boundary_angle(graph, r) - first, meet, 180.0 - meet) >= reflex.MIN_CUT_ANGLE


def _inside(polygon, a, b) -> bool:
    """Whether the straight chord from ``a`` to ``b`` runs inside ``polygon``, touching its outline only
    at its ends."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    step = (b - a) * 1e-6
    return bool(shapely.contains_properly(polygon, shapely.LineString([a + step, b - step])))


def _once(graph, r: int):
    """:func:`_fan_merge`, worked out once per corner and state of the graph."""
    return memo_at(_STATE, graph, r, lambda: _fan_merge(graph, r))


def fan_merge_at(graph, r: int) -> bool:
    """Whether the hole corner ``r`` takes the merge of two fan triangles (see the module docstring)."""
    return _once(graph, r) is not None


def fan_merge_edge(graph, r: int) -> int:
    """The fan side that ``r``'s merge removes; -1 where ``r`` takes none."""
    got = _once(graph, r)
    return -1 if got is None else got[0]


def fan_merge_first(graph, r: int) -> int:
    """The merged triangle ``(F, x, s)`` (its corners counter-clockwise from the pole ``F``); ``r`` where
    ``r`` takes no merge."""
    got = _once(graph, r)
    return r if got is None else got[1]


def fan_merge_second(graph, r: int) -> int:
    """The merged triangle ``(F, s, y)``; ``r`` where ``r`` takes no merge."""
    got = _once(graph, r)
    return r if got is None else got[2]


def register_hole_fan_helpers(f) -> None:
    """Register the helpers with a function registry (``rules/corners.vgr`` calls them)."""
    f.register("fan_merge_at", fan_merge_at, ("node",), "bool", uses_graph=True, local=False)
    for name, fn, returns in (("fan_merge_edge", fan_merge_edge, "edge"), ("fan_merge_first", fan_merge_first, "node"),
                              ("fan_merge_second", fan_merge_second, "node")):
        f.register(name, fn, ("node",), returns, uses_graph=True, local=False)
