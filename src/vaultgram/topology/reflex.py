"""Reflex corners of any plan given a patch of their own: the helpers of ``rules/corners.vgr``'s
``reflex_corner_patches`` (issue 12, item 2; paper §3.1 and its conclusion).

The medial axis sends no branch to a reflex corner (§3.1). Where a rebranch arrives there the corner
is the corner of two patches, which share its 225-315 degrees with one face each: valence 3 where its
angle asks for 4 (a boundary singularity, the distortion the paper's conclusion names, after Rigby
[11] and Fogg et al. [10]). On a rectilinear plan the chords of ``rules/corners.vgr`` avoid it; on
any other plan one of the corner's quads is split by a chord from the corner to the middle of one of
its two sides away from the corner (or, where that leaves a narrow angle, at another of :data:`FEET`
along it): a triangle with the corner as its marked pole, and a quad. On a
branch, rebranch or diagonal the chord's far end is a T-junction on the patch beyond, carried across
the layout as a strip of quads (``rules/strips.vgr``) to the boundary or into a triangle
(``split_quad_at_reflex_corner_to_side``, :func:`reflex_chord`); on a boundary side it ends at the
free boundary point nearest the middle (``_to_boundary``, :func:`reflex_foot`). The triangle is
meshed as three quads meeting at an inner point of valence 3 (the mesher splits a triangle whose
marked pole is a boundary point, :mod:`vaultgram.meshing.splits`), so the corner gets one face more
(three: regular), the strip's corners are regular, and the one singular vertex added is the split's
inner point: the index the corner gives up goes inside the plan. A reflex corner inside a patch's
side (the corner of no patch: the corners of a polygonal hole along the ring patch round it) is first
made the corner of two quads by a chord across its quad, a strip too (``cut_quad_at_reflex_corner``,
:func:`reflex_cut`), ending at the first of :data:`FEET` along the opposite edge that leaves no angle
below :data:`MIN_CUT_ANGLE` (the middle where it can; :func:`reflex_point`). Where the strip is one
triangle of a pole's fan that none of them halves evenly enough, a last cut, after the rules' rebranch
to the pole (:mod:`vaultgram.topology.hole_sides`), ends at the foot whose chord bisects the triangle's
angle at the pole (:func:`reflex_bisecting_cut`, :func:`bisecting_foot`).

:func:`reflex_chord` and :func:`reflex_foot` pick, among the corner's quads and their sides, where the
chord runs inside the quad and its strip completes (:func:`~vaultgram.topology.strips.strip_walk`)
without ending in a triangle at a point the split would change (:func:`strip_beyond`), the chord
whose worst angle is widest: the three patch angles at the corner after the split and the chord's two
angles with the side it ends on. Where that worst angle is below :data:`MIN_ANGLE` the corner is left
as it is (a sliver of a patch would cost more in the mesh's worst element than the singularity), but
for fallbacks: at a hole corner, last, the widest chord over every foot down to :data:`HOLE_MIN_ANGLE`
(:func:`hole_chord`: a quad corner that narrow still has a scaled Jacobian above 0.3); on the outer ring,
last, the widest down to 35 degrees in a quad of 135 or more that leaves no patch at the corner past straight
(:data:`~vaultgram.topology.reflex_fallbacks.OUTER_MIN_ANGLE`, jagged outlines).

A spike (:data:`SPIKE`: 315-360 degrees, regular valence 5, the noise of a geographic outline) asks for
four faces: it gets a chord while it is the corner of two patches or of three (the rules'
``patches`` parameter), the second beside the first's triangle, whose angle is then not counted
(:func:`other_angle`). A spike whose quad turns past straight gets that quad's chord even at a
narrower angle (:data:`PAST_STRAIGHT`, :data:`FOLD_MIN_ANGLE`): the mesh would fold there.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Iterator

from vaultgram.geometry.polygons import ccw_degrees, direction, regular_valence
from vaultgram.geometry.polylines import arc_lengths, ray_hit_fraction
from vaultgram.topology.corners import boundary_angle, graph_rings, ring_place
from vaultgram.topology.curve_points import short_side
from vaultgram.topology.patches import half_edge_polyline
from vaultgram.topology.reflex_fallbacks import (
    OUTER_MIN_ANGLE,
    OUTER_POINT_MIN_ANGLE,
    any_point_quads,
    point_quads,
    turns_past_straight,
    wide_quads,
)
from vaultgram.topology.statecache import memo_at, untouched
from vaultgram.topology.strips import (
    READS,
    Walk,
    chord_inside,
    edge_cut,
    patch_across,
    patch_sides,
    side_edge,
    strip_boundary_end,
    strip_point,
    strip_walk,
)
from vaultgram.topology.types import (
    BOUNDARY,
    BOUNDARY_VERTEX,
    CURVE_EXTREMITY,
    CURVE_POINT,
    FEATURE_POINT,
    PATCH_CORNER,
)

__all__ = ["reflex_chord", "reflex_side", "reflex_foot", "reflex_cut", "reflex_cut_index", "reflex_cut_at",
           "reflex_bisecting_cut", "reflex_bisecting_cut_index", "reflex_bisecting_cut_at",
           "reflex_point", "rebranch_to_corner", "MIN_ANGLE", "MIN_CUT_ANGLE", "MAX_POLE_ANGLE", "MAX_RATIO", "FEET",
           "SPIKE", "PAST_STRAIGHT", "FOLD_MIN_ANGLE", "MAX_POLE_RATIO", "MIN_FAN_HALF",
           "HOLE_MAX_RATIO", "HOLE_MIN_ANGLE", "BISECTING_FOOT", "cut_walk",
           # helpers the other corner modules (hole_sides, hole_hub, lone_corners) and the benchmarks share
           "patch_corner", "boundary_ahead", "side_length", "on_side", "fan_end", "strip_fan", "is_feature", "is_pole",
           "halves_fan", "curve_end", "strip_beyond", "bisecting_foot", "hole_chord", "widest_chord", "chord_worst",
           "other_angle", "chord_targets", "chord_angles", "even_group", "choose_cut", "smooth_boundary_side",
           "choose_chord"]

#: The node types at which a strip may not end in a triangle (:func:`strip_beyond`).
KEPT_ENDS = (BOUNDARY_VERTEX, FEATURE_POINT, CURVE_POINT)
#: Degrees: no chord whose worst angle (at the corner or where it meets the side) is narrower.
MIN_ANGLE = 30.0
#: The lengths of the sides a chord joins in one edge group may differ by this factor at most.
MAX_RATIO = 2.5
#: Where along a plan edge a chord may end, as fractions of its length, in the order tried: the middle
#: (where a strip cuts the patches beyond, §4.2) first, then points nearer either end, a quarter of the
#: way in at most (each piece of the edge stays at least a third as long as the other).
FEET = (0.5, 0.45, 0.55, 0.4, 0.6, 0.35, 0.65, 0.3, 0.7, 0.25, 0.75)
#: Degrees: a cut across a quad (a corner inside a side) leaves no angle narrower at the corner or
#: where it meets the opposite side (plan 188 of the saved random plans: a cut meeting the loop round a
#: hexagonal hole at 32 degrees left a quad of scaled Jacobian 0.07 there).
MIN_CUT_ANGLE = 40.0
#: Degrees: where no foot of a hole corner's cut halves a point feature's fan triangle into two of
#: :data:`MIN_CUT_ANGLE` (:func:`halves_fan`), the halves may be this narrow: a fan of five triangles
#: round a point of a straight boundary has 180 / 5 degrees each. The 42 hole corners of the 700 saved
#: random plans whose cut's strip is one fan triangle mostly had no foot leaving 40 either side, but
#: their best at 36-40 (plans 4, 231, 579, 692: 37-38).
MIN_FAN_HALF = 36.0
#: Where none of :data:`FEET` serves a hole corner's cut whose strip is one triangle of a pole's fan, the
#: foot whose chord to the pole bisects the triangle's angle there (:func:`bisecting_foot`: the most
#: even halves any foot gives) may lie this fraction of the edge from either end, nearer than
#: :data:`FEET` reach: a skewed fan triangle's bisector meets its far side off the middle (saved random
#: plans 226 and 691 of the 700 drawn in session 25: 0.27 and 0.81 along, halves of 39 and 45 degrees,
#: where the nearest of :data:`FEET` left 35.8 and 35.1).
BISECTING_FOOT = 0.15
#: Degrees: a corner this wide or wider is a spike (regular valence 5: four faces, two chords).
SPIKE = 315.0
#: Degrees: a quad wider than this at a corner turns past straight there, and its mesh folds at any
#: density (:data:`vaultgram.meshpipeline.LAYOUT_TURN_LIMIT`, the same limit): where no chord of a
#: spike qualifies, such a quad's chords do down to :data:`FOLD_MIN_ANGLE` (jagged outlines: a quad of
#: 197 degrees at a 334 degree spike folded the mesh). Not at corners of 225-315 degrees: on the 700
#: saved random plans that made one fold a mesh (642) but lowered two plans' worst scaled Jacobian (443
#: and 444, a quad of 184 and 195 degrees that smoothing had meshed: 0.27 -> 0.21, 0.38 -> 0.29).
PAST_STRAIGHT = 181.0
#: Degrees: the worst angle a chord that undoes a quad turning past straight may leave.
FOLD_MIN_ANGLE = 10.0
#: The triangle a rebranch moved to a lone corner cuts off has its two sides at the corner (its pole:
#: the rebranch and the patch's other side there) in one edge group: their lengths may differ by this
#: factor at most (:func:`rebranch_to_corner`). A corner's quad between two rebranches has them at
#: 3.0-4.1 on the saved random plans and the shared plans; multiple_lobes' 136 degree corner at 7.5
#: (a 0.65 jog against a 4.9 rebranch) had its triangle's split raise the jog's group and the lobes'
#: with it: 2356 faces for 1080, min scaled Jacobian 0.395 -> 0.336.
MAX_POLE_RATIO = 5.0
#: Where no chord of a hole corner keeps its edge group within :data:`MAX_RATIO`, one within this
#: (:func:`choose_chord`): on the 700 saved random plans the 7 hole corners refused only by the ratio
#: (plans 314, 370, 395, 613, 614) were at 2.5-3.5, and 5 of them take such a chord. Not on the outer
#: ring: there it folded a jagged outline (jagged_1: chords at its 299 and 240 degree corners beside a
#: narrow 320 degree spike) and lowered jagged_2's min scaled Jacobian from 0.198 to 0.077.
HOLE_MAX_RATIO = 3.5
#: Degrees: where no chord of a hole corner qualifies at :data:`MIN_ANGLE` (:data:`MIN_CUT_ANGLE` off the
#: middle), nor within :data:`HOLE_MAX_RATIO`, nor into a fan, the chord whose worst angle is widest over
#: every foot of :data:`FEET` down to this (:func:`hole_chord`): a quad corner of 20 degrees has a scaled
#: Jacobian of sin 20 = 0.34, above the 0.3 the benchmarks count. On the 700 saved random plans main
#: d952b9c left 24 hole corners of two patches whose best chord was at 0-40 degrees; at 25 the fallback
#: took 11 of them, at 20 15 (23-25 and 132 too). Not on the outer ring: lower chord angles there folded
#: jagged_1 (session 21); a hole corner's chord ends inside the plan or on the hole's ring.
HOLE_MIN_ANGLE = 20.0
#: Degrees: the triangle's angle at the corner must allow the three-quad split
#: (:data:`vaultgram.meshing.splits.MAX_SPLIT_ANGLE`).
MAX_POLE_ANGLE = 160.0

_STATE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: {corner: choice}}
_KEPT: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> choose_chord's results (_kept_chord)


def _edge_tangent(graph, edge: int, fraction: float = 0.5) -> float:
    """The direction (radians) of a plan edge at ``fraction`` of its length (where a chord ends)."""
    before, mid, after = edge_cut(graph, edge, fraction)
    ahead = after[0] if len(after) else graph.get(graph.ends(edge)[1], "pos")
    back = before[-1] if len(before) else graph.get(graph.ends(edge)[0], "pos")
    return direction(back, ahead)


def _feet(graph, walk, fractions=FEET, half: float = MIN_CUT_ANGLE) -> Iterator[tuple]:
    """The points of the plan edge a strip enters by (``walk``, :func:`strip_beyond`; none where it is
    None) where a chord may end (``fractions`` of its length, in that order), as ``(fraction, point,
    tangent there)``: where the strip's first chord, from there across the patch beyond, runs inside
    it, and, where the strip is one triangle of a feature's fan (:func:`fan_end`), the chord from
    there to the feature halves its angle into two of at least ``half`` degrees (:func:`halves_fan`).
    A closed strip comes back to the middle, its only foot. Lazily: a cut stops at the first that
    serves."""
    if walk is None:
        return
    edge, found = walk.edges[0], patch_sides(graph, walk.patches[0])
    to = strip_point(graph, walk.edges[1]) if len(walk.edges) > 1 else walk.end_point(graph)
    fan, far = fan_end(graph, walk) or curve_end(graph, walk), strip_fan(graph, walk)
    if far is not None and not halves_fan(far[0], far[1], half):
        return  # a strip of several patches enters its fan triangle at its last edge's foot, whatever the first
    for f in fractions[:1] if walk.end is None else fractions:
        at = edge_cut(graph, edge, f)[1]
        walked = f == 0.5 and fan is None  # the strip's walk ran this chord (a fan's: maybe not, _fan_walk)
        if (walked or chord_inside(found, at, to)) and (fan is None or halves_fan(fan, at, half)):
            yield f, at, _edge_tangent(graph, edge, f)


def fan_end(graph, walk) -> tuple | None:
    """Where the strip ``walk`` is one triangle of a pole's fan, entered by the side opposite the pole
    (:func:`strip_beyond`, :func:`is_pole`): the pole's position, the direction (radians) of the
    triangle's side leaving it and the triangle's angle there (degrees); None otherwise."""
    if walk.end is None or len(walk.patches) != 1 or not is_pole(graph, walk.end):
        return None
    found = patch_sides(graph, walk.patches[0])
    return patch_corner(graph, found, found.corners.index(walk.end)) if len(found.corners) == 3 else None


def curve_end(graph, walk) -> tuple | None:
    """Where the strip ``walk`` is one triangle entered by the side opposite a point inside a curve feature
    that is short of patches on the triangle's side (:func:`~vaultgram.topology.curve_points.short_side`;
    a cut's, :func:`_fan_walk`), that corner as :func:`fan_end` gives a pole's: the chord from a foot to
    it must halve the triangle's angle there into two of :data:`MIN_CUT_ANGLE` (:func:`_feet`); None
    otherwise."""
    if walk.end is None or len(walk.patches) != 1 or not short_side(graph, walk.end, walk.patches[0]):
        return None
    found = patch_sides(graph, walk.patches[0])
    return patch_corner(graph, found, found.corners.index(walk.end)) if len(found.corners) == 3 else None


def strip_fan(graph, walk) -> tuple | None:
    """Where the strip ``walk`` crosses several patches and ends in one triangle of a pole's fan (at its
    corner opposite the strip: :func:`is_pole`), that triangle's fan (as :func:`fan_end`'s) and the point
    where the strip enters it, its entry edge's strip point (``rules/strips.vgr``' ``continue_strip``: the
    edge's foot, :func:`fan_foot` where ``place_fan_foot`` stored it, else the middle): the chord from
    there to the pole halves the triangle, which must leave two of :data:`MIN_FAN_HALF` at least
    (:func:`halves_fan`, :func:`_feet`: plans 23 and 24's wedge of slivers came from such strips halved
    at 20-30 degrees). None otherwise (a strip of one triangle: :func:`fan_end`)."""
    if walk.end is None or len(walk.patches) < 2 or walk.split >= 0 or not is_pole(graph, walk.end):
        return None
    found = patch_sides(graph, walk.patches[-1])
    if len(found.corners) != 3 or walk.end not in found.corners:
        return None
    return patch_corner(graph, found, found.corners.index(walk.end)), strip_point(graph, walk.edges[-1])


def fan_foot(graph, edge: int) -> float:
    """Where a strip should cut the plan edge ``edge`` (``rules/strips.vgr``' ``place_fan_foot`` stores it on
    the edge, :func:`~vaultgram.topology.strips.strip_fraction` reads it): 0.5, but where ``edge`` is the
    side of one triangle of a point feature's fan (:func:`is_feature`) opposite it and the chord from its
    middle to the feature leaves the triangle or leaves a part of its angle there under
    :data:`MIN_FAN_HALF`, the first of :data:`FEET`, then the bisecting foot (:func:`bisecting_foot`), whose
    chord runs inside and halves it into two of :data:`MIN_CUT_ANGLE`, else of :data:`MIN_FAN_HALF`; the
    middle where none does. Saved random plans 256 and 257: a hole corner's chord starts a strip across a
    quad into such a triangle, whose middle chord leaves 11.7 degrees at the feature. Once per state."""
    return _once(graph, _fan_foot, edge)


def _fan_foot(graph, edge: int) -> float:
    """:func:`fan_foot`, worked out (the middle first: most fan sides keep it)."""
    if graph.edge_type(edge) == BOUNDARY:
        return 0.5  # a boundary edge a strip splits (strips.strip_boundary_split): no fan beyond it
    tri = [q for q in sorted({graph.ends(e)[0] for n in graph.ends(edge) for e in graph.incident(n, [PATCH_CORNER])})
           for found in (patch_sides(graph, q),) if found is not None and len(found.corners) == 3
           and any(len(side) == 1 and side[0][0] == edge for side in found.sides)]
    if len(tri) != 1:
        return 0.5
    found = patch_sides(graph, tri[0])
    k = next(i for i, side in enumerate(found.sides) if side[0][0] == edge)
    pole = found.corners[(k + 2) % 3]
    if not is_feature(graph, pole):  # a curve's free end: see benchmarks/README.md, session 28
        return 0.5
    fan = patch_corner(graph, found, (k + 2) % 3)
    middle = edge_cut(graph, edge, 0.5)[1]
    if chord_inside(found, middle, fan[0]) and halves_fan(fan, middle, MIN_FAN_HALF):
        return 0.5
    walk = Walk((tri[0],), (edge,), pole)
    feet = [(f, edge_cut(graph, edge, f)[1]) for f in FEET[1:] + bisecting_foot(graph, walk)]
    ok = [(f, at) for f, at in feet if chord_inside(found, at, fan[0])]
    for least in (MIN_CUT_ANGLE, MIN_FAN_HALF):
        for f, at in ok:
            if halves_fan(fan, at, least):
                return f
    return 0.5


def halves_fan(fan: tuple, at, least: float = MIN_CUT_ANGLE) -> bool:
    """Whether the chord from the point ``at`` to the feature of ``fan`` (:func:`fan_end`) splits the
    triangle's angle there into two of at least ``least`` degrees (:data:`MIN_CUT_ANGLE` unless given,
    :data:`MIN_FAN_HALF` where no foot leaves that): the fan gains a triangle no narrower than a cut may
    leave, or than a fan of five round a point of a straight boundary has (§4.1: the feature stays the
    pole of both).

    >>> halves_fan(((0.0, 0.0), 0.0, 90.0), (1.0, 1.0)), halves_fan(((0.0, 0.0), 0.0, 90.0), (1.0, 0.2))
    (True, False)
    >>> halves_fan(((0.0, 0.0), 0.0, 80.0), (1.0, 0.75)), halves_fan(((0.0, 0.0), 0.0, 80.0), (1.0, 0.75), 36.0)
    (False, True)
    """
    pos, d_out, whole = fan
    first = ccw_degrees(d_out, direction(pos, at))
    return least <= first <= whole - least


def is_feature(graph, n: int) -> bool:
    """Whether the point ``n`` is a point feature (a boundary point feature or an inner one)."""
    return bool(graph.get(n, "feature")) or graph.schema.is_subtype(graph.node_type(n), FEATURE_POINT)


def is_pole(graph, n: int) -> bool:
    """Whether the point ``n`` is a pole of the triangles round it whatever the layout: a point feature
    (§4.1) or a curve's free end (§4.2, Figure 8), so that halving one of its triangles keeps it one.
    A hole corner's cut whose strip is such a triangle at a curve's free end was refused as ending at
    a curve point (10 of the 137 boundary singular vertices of the 700 saved random plans, s21)."""
    return is_feature(graph, n) or graph.node_type(n) == CURVE_EXTREMITY


def _ring_tangent(graph, w: int) -> float:
    """The direction (radians) of the boundary at the boundary point ``w``, between its two
    neighbours along the ring."""
    a, b = (graph.other(e, w) for e in graph.incident(w, [BOUNDARY]))
    return direction(graph.get(a, "pos"), graph.get(b, "pos"))


def boundary_ahead(graph, r: int) -> float:
    """The direction (radians) of the boundary leaving the boundary point ``r`` in ring order (towards
    the next point along its ring, the domain on the left): the side from which the domain's interior
    angle at ``r`` is measured counter-clockwise (:func:`~vaultgram.topology.corners.boundary_angle`)."""
    rings, _ = graph_rings(graph)
    ring, k = ring_place(graph, r)
    return direction(rings[ring][k], rings[ring][(k + 1) % len(rings[ring])])


def chord_angles(graph, found, k: int, j: int, end, tangent: float, other: float) -> tuple[float, float]:
    """For the chord from corner ``k`` of the quad ``found`` to the point ``end`` on its side from
    corner ``k + j`` (``j`` 1 or 2), whose direction there is ``tangent`` (radians): the worst angle
    (degrees: the two parts of the quad's angle at the corner, ``other`` the angle of the corner's
    other patch, the chord's angles with the side) and the angle at the corner of the triangle the
    chord cuts off."""
    pos, d_out, whole = patch_corner(graph, found, k)
    d_chord = direction(pos, end)
    first = ccw_degrees(d_out, d_chord)  # between the leaving side and the chord
    if not 0.0 < first < whole:
        return -1.0, 360.0
    meet = ccw_degrees(tangent, d_chord) % 180.0
    return min(first, whole - first, other, meet, 180.0 - meet), first if j == 1 else whole - first


def chord_targets(graph, patch: int, found, k: int, j: int, fans: float | None = None) -> list[tuple]:
    """Where a chord from corner ``k`` of a quad may end on its side from corner ``k + j``: the feet
    of that side's plan edge where a strip may cut it and carry on (``("edge", edge, point, tangent,
    fraction)``, :func:`_feet`: the middle first), or the free boundary point nearest the middle of a
    boundary side (``("point", node, point, tangent, None)``); only where the chord runs inside the
    quad. A foot off the middle must pass the stricter tests of :func:`chord_worst` (without them
    chords got through at multiple_lobes' notches beside fan-shaped patches, 1600 faces for 1080).
    With ``fans`` (degrees), only the feet of a strip that is one triangle of a point feature's fan,
    which may end at the feature where the foot halves it into two of ``fans`` (:func:`strip_beyond`,
    :func:`_feet`): the others were asked without."""
    r, y = found.corners[k], found.corners[(k + j) % 4]
    pos, edge = graph.get(r, "pos"), side_edge(graph, patch, y)
    if edge >= 0:
        walk = strip_beyond(graph, patch, edge, fans is not None)
        if fans is not None and (walk is None or fan_end(graph, walk) is None and strip_fan(graph, walk) is None):
            return []  # asked without fans already
        return [("edge", edge, at, tangent, f) for f, at, tangent in _feet(graph, walk, half=fans or MIN_CUT_ANGLE)
                if chord_inside(found, pos, at)]
    if fans is not None:
        return []
    w = strip_boundary_end(graph, patch, y)
    if w == y or not chord_inside(found, pos, graph.get(w, "pos")):
        return []
    return [("point", w, graph.get(w, "pos"), _ring_tangent(graph, w), None)]


def choose_chord(graph, r: int) -> tuple | None:
    """The chord from the reflex corner ``r`` (see the module docstring): ``(patch, kind, target,
    side, fraction)``, ``kind`` ``"edge"`` (``target`` the plan edge cut at ``fraction`` of its length)
    or ``"point"`` (a boundary point), ``side`` the corner where the side it ends on starts; or None.
    The widest worst angle wins, at the middle or off it (a foot off the middle only where the middle
    of that side does not qualify): the middle first whenever it qualifies somewhere was tried and left
    more corners singular on the saved random plans (217 for 212) with more plans under 0.3 (309 for
    307), since a corner's middle chord can leave its neighbours along a hole none. Where none
    qualifies at a spike (:data:`SPIKE`) and a quad turns past straight there (wider than
    :data:`PAST_STRAIGHT`: its mesh folds at any density), that quad's chords down to
    :data:`FOLD_MIN_ANGLE`: a narrow angle costs less than a fold. Where none qualifies at a hole
    corner, the chords whose edge group is within :data:`HOLE_MAX_RATIO` rather than
    :data:`MAX_RATIO`; where still none does, the chords whose strip is one triangle of a point
    feature's fan, halved at the feature into two of :data:`MIN_CUT_ANGLE`, then of
    :data:`MIN_FAN_HALF`, as a cut's may be (never before: asked first, such chords took the place of
    the chosen ones at corners already regular, and plans 12, 395 and 444 fell under 0.3, 444 from
    0.381 to 0.076); where still none does at a hole corner, the widest chord down to
    :data:`HOLE_MIN_ANGLE` (:func:`hole_chord`); after the spikes' fallback, on the outer ring, the
    widest chord over every foot down to :data:`~vaultgram.topology.reflex_fallbacks.OUTER_MIN_ANGLE`
    in a quad of 135 degrees or more at the corner that leaves no patch there past straight
    (:func:`~vaultgram.topology.reflex_fallbacks.turns_past_straight`), then the widest chord to a boundary
    point down to :data:`~vaultgram.topology.reflex_fallbacks.OUTER_POINT_MIN_ANGLE` in a quad past straight or
    at a spike (:func:`_outer_chord`)."""
    patches = sorted({graph.ends(e)[0] for e in graph.incident(r, [PATCH_CORNER])})
    found = [patch_sides(graph, p) for p in patches]
    if any(f is None for f in found):
        return None
    angles = [patch_corner(graph, sides, sides.corners.index(r))[2] for sides in found]
    quads = [i for i, sides in enumerate(found) if len(sides.corners) == 4]
    at = (r, patches, found, angles)
    best = widest_chord(graph, at, quads, None)
    if best is None and ring_place(graph, r)[0] > 0:
        best = widest_chord(graph, at, quads, None, HOLE_MAX_RATIO)
    for half in (MIN_CUT_ANGLE, MIN_FAN_HALF):
        if best is None:
            best = widest_chord(graph, at, quads, None, fans=half)
    if best is None and ring_place(graph, r)[0] > 0:
        best = hole_chord(graph, at, quads)
    turned = [i for i in quads if angles[i] > PAST_STRAIGHT] if boundary_angle(graph, r) >= SPIKE else []
    if best is None and turned:
        best = widest_chord(graph, at, turned, FOLD_MIN_ANGLE)
    if best is None and ring_place(graph, r)[0] == 0:  # the outer ring's last fallbacks (reflex_fallbacks)
        best = _outer_chord(graph, at, quads)
    return None if best is None else best[1:]


def _outer_chord(graph, at: tuple, quads: list) -> tuple | None:
    """The outer ring's last fallbacks (:mod:`~vaultgram.topology.reflex_fallbacks`): the widest chord over
    every foot down to :data:`~vaultgram.topology.reflex_fallbacks.OUTER_MIN_ANGLE` in a quad of 135 degrees or
    more (:func:`~vaultgram.topology.reflex_fallbacks.wide_quads`); else the widest chord to a boundary point
    down to :data:`~vaultgram.topology.reflex_fallbacks.OUTER_POINT_MIN_ANGLE` in a quad past straight or at a
    spike (:func:`~vaultgram.topology.reflex_fallbacks.point_quads`); else the same in any quad, its edge group
    within :data:`HOLE_MAX_RATIO` (:func:`~vaultgram.topology.reflex_fallbacks.any_point_quads`); none leaving a
    patch at the corner past straight (:func:`~vaultgram.topology.reflex_fallbacks.turns_past_straight`)."""
    r, _, _, angles = at
    best = widest_chord(graph, at, wide_quads(angles, quads), OUTER_MIN_ANGLE, every_foot=True,
                        keep=lambda i, pole, kind: not turns_past_straight(angles, i, pole, PAST_STRAIGHT))

    def point(i, pole, kind):
        """A chord to a boundary point that leaves no patch at the corner past straight."""
        return kind == "point" and not turns_past_straight(angles, i, pole, PAST_STRAIGHT)

    if best is None:
        turned = point_quads(angles, quads, boundary_angle(graph, r), PAST_STRAIGHT, SPIKE)
        best = widest_chord(graph, at, turned, OUTER_POINT_MIN_ANGLE, every_foot=True, keep=point)
    if best is None:
        best = widest_chord(graph, at, any_point_quads(angles, quads), OUTER_POINT_MIN_ANGLE, HOLE_MAX_RATIO,
                            every_foot=True, keep=point)
    return best


def hole_chord(graph, at: tuple, quads: list) -> tuple | None:
    """The last fallback of a hole corner's chord (:func:`choose_chord`, where no other qualifies): of every
    foot of every side (not the first in :data:`FEET` order that qualifies), the chord whose worst angle
    is widest, down to :data:`HOLE_MIN_ANGLE`, its edge group within :data:`HOLE_MAX_RATIO`. The widest
    foot, not the first: at 20 degrees the first foot of plans 613 and 614 left 0.341 as their worst
    scaled Jacobian, the widest 0.449 (main 0.496, the corner singular); plan 574's rose 0.521 -> 0.539."""
    return widest_chord(graph, at, quads, HOLE_MIN_ANGLE, HOLE_MAX_RATIO, every_foot=True)


def widest_chord(graph, at: tuple, quads: list, least: float | None, ratio: float = MAX_RATIO,
                  fans: float | None = None, every_foot: bool = False, keep=None) -> tuple | None:
    """Of the chords from the reflex corner in the quads ``quads`` (indices into ``at``: the corner,
    its patches, their sides and their angles there), the one whose worst angle is widest, as
    ``(worst, patch, kind, target, side, fraction)`` (:func:`choose_chord`); ``least`` and ``ratio`` are
    passed on to :func:`chord_worst`, ``fans`` to :func:`chord_targets`. Of a side's feet the first that
    qualifies, in :data:`FEET` order (the middle first), or with ``every_foot`` the widest of all of
    them (:func:`hole_chord`). With ``keep``, only chords it passes, asked with the quad's index, the
    triangle's angle at the corner and the chord's kind (``"edge"`` or ``"point"``; the outer ring's fallbacks:
    :func:`~vaultgram.topology.reflex_fallbacks.turns_past_straight`). None where none qualifies."""
    r, patches, found, angles = at
    theta = boundary_angle(graph, r)
    best = None
    for i in quads:
        p, sides = patches[i], found[i]
        k = sides.corners.index(r)
        other = other_angle(theta, angles, i)
        for j in (1, 2):
            for kind, target, point, tangent, fraction in chord_targets(graph, p, sides, k, j, fans):
                candidate = (kind, target, point, tangent, fraction)
                worst = chord_worst(graph, p, sides, k, j, candidate, other, least, ratio)
                if worst is not None and keep is not None:
                    pole = chord_angles(graph, sides, k, j, point, tangent, other)[1]
                    worst = worst if keep(i, pole, kind) else None
                if worst is not None:
                    if best is None or worst > best[0]:
                        best = (worst, p, kind, target, sides.corners[(k + j) % 4], fraction)
                    if not every_foot:
                        break
    return best


def other_angle(theta: float, angles: list, i: int) -> float:
    """The angle (degrees) at a reflex corner of interior angle ``theta`` that a chord in its ``i``-th
    patch (``angles``: its patches' angles at the corner) counts besides its own parts: beside two
    patches the other's, the rest of ``theta``; beside more (a spike of 315 to 360 degrees, regular
    valence 5, after its first chord) none (infinite): the others keep their angles whatever the
    chord does, and a narrow one among them (a sliver the skeleton left) must not bar the chord that
    splits the widest patch (jagged outlines: a quad of 196 degrees at a 342 degree spike beside a
    triangle of 10).

    >>> other_angle(270.0, [180.0, 90.0], 0), other_angle(330.0, [150.0, 100.0, 80.0], 0)
    (90.0, inf)
    """
    return theta - angles[i] if len(angles) == 2 else math.inf


def chord_worst(graph, patch: int, found, k: int, j: int, target: tuple, other: float,
                 least: float | None = None, ratio: float = MAX_RATIO) -> float | None:
    """The worst angle of the chord from corner ``k`` of the quad ``patch`` to ``target`` (one of
    :func:`chord_targets`' ``(kind, target, point, tangent, fraction)``) where the chord qualifies, None
    otherwise: its worst angle (:func:`chord_angles`) reaches :data:`MIN_ANGLE` at the middle of an edge or
    on the boundary and :data:`MIN_CUT_ANGLE` at a foot off the middle (as for a cut: a foot off the
    middle is taken only where it leaves no narrow angle), the triangle's pole angle allows its split,
    and the sides the chord puts in one edge group, with the edge's two pieces at a foot off the
    middle, are even (:func:`even_group`, within ``ratio``). ``least``, where given, replaces both
    angle limits."""
    kind, edge, at, tangent, fraction = target
    worst, pole = chord_angles(graph, found, k, j, at, tangent, other)
    if least is None:
        least = MIN_ANGLE if fraction in (0.5, None) else MIN_CUT_ANGLE
    if worst < least or pole > MAX_POLE_ANGLE:
        return None
    return worst if even_group(graph, patch, found, k, j, at, _pieces(graph, kind, edge, fraction), ratio) else None


def strip_beyond(graph, patch: int, edge: int, fans: bool = False, split: bool = False):
    """The walk of the strip a chord in the quad ``patch`` to the middle of its side ``edge`` starts
    in the patch beyond, where it completes (:func:`~vaultgram.topology.strips.strip_walk`, as for
    Figure 8's split to a side, §4.2) without ending in a triangle at a point the split would
    change: a boundary point gains a face, a boundary singularity (rv_star_pattern's 215 degree
    vertex, the strip from its 256 degree corner); a point feature's fan carries its load (§4.1: a
    random plan's worst quad went from 0.31 to 0.20 there); a curve is a cut the layout keeps
    (§4.2). None otherwise. With ``fans`` (a cut, :func:`choose_cut`), a strip that is one triangle of a
    point feature's fan (:func:`fan_end`) may end at the feature, which stays the pole of both
    halves, where the chord's foot halves the triangle's angle there (:func:`_feet`,
    :func:`halves_fan`): 58 of the 204 boundary singular vertices of the 700 saved random plans
    were hole corners whose cut was refused only by such an end. For the chords of a corner of two
    patches only where no other chord qualifies (:func:`choose_chord`: asked first, it changed the chosen
    chord at corners already regular: plans 12, 395 and 444 fell under 0.3, 444 from 0.381 to
    0.076). A strip of several patches into a fan only where its last strip point halves the fan
    triangle into two of :data:`MIN_FAN_HALF` (:func:`strip_fan`, :func:`fan_foot`; from the middle at
    20-30 degrees, plans 23 and 24 took a wedge of slivers, min SJ 0.455 -> 0.048). With
    ``split`` (a cut, :func:`cut_walk`), the strip may end at the middle of a boundary side that is one
    boundary edge (:func:`~vaultgram.topology.strips.strip_boundary_split`)."""
    beyond = patch_across(graph, patch, edge)
    walk = None if beyond is None else strip_walk(graph, beyond[0], beyond[1], frozenset([patch]), split)
    if walk is None or walk.end is None or len(patch_sides(graph, walk.patches[-1]).corners) == 4:
        return walk
    if fans and (fan_end(graph, walk) is not None or strip_fan(graph, walk) is not None):
        return walk  # a strip of several patches: only where its last chord halves the fan (_feet)
    kind = graph.node_type(walk.end)
    kept = is_feature(graph, walk.end) or any(graph.schema.is_subtype(kind, t) for t in KEPT_ENDS)
    return None if kept else walk


def cut_walk(graph, patch: int, edge: int):
    """The walk of the strip a hole corner's cut across the quad ``patch`` to its side ``edge`` starts
    (:func:`strip_beyond` with ``fans`` and ``split``), or where that is refused only because the chord from the
    middle of ``edge`` to the corner opposite it in the triangle beyond leaves the triangle (a curved
    side), that triangle as a one-patch walk (:func:`_fan_walk`): the cut's feet off the middle may
    run inside it (:func:`_feet` checks each)."""
    walk = strip_beyond(graph, patch, edge, fans=True, split=True)
    return walk if walk is not None else _fan_walk(graph, patch, edge)


def _fan_walk(graph, patch: int, edge: int) -> Walk | None:
    """The one triangle beyond the side ``edge`` of the quad ``patch``, as a walk ending at its corner
    opposite ``edge``, where that corner is a pole (:func:`is_pole`: a point feature or a curve's free
    end, which stays the pole of both halves) or a point inside a curve short of patches on the
    triangle's side (:func:`curve_end`); None otherwise. For a cut whose strip walk
    (:func:`~vaultgram.topology.strips.strip_walk`, from the middle) is refused there: on the 700 saved
    random plans, hole corners of plans 579 and 665 whose chord from the middle of a curved branch to
    the point feature leaves the fan triangle, while chords from feet at 0.6-0.7 of it run inside; on
    session 32's draw, plans 133 and 134, whose strip ends at a curve's bend (a curve point, refused by
    :func:`strip_beyond`) that had three patches on its 340 degree side."""
    beyond = patch_across(graph, patch, edge)
    found = patch_sides(graph, beyond[0]) if beyond is not None else None
    if found is None or len(found.corners) != 3:
        return None
    end = found.corners[(beyond[1] + 2) % 3]
    kept = is_pole(graph, end) or short_side(graph, end, beyond[0])
    return Walk((beyond[0],), (edge,), end) if kept else None


def side_length(graph, side) -> float:
    """The length of a patch side (its half-edges' polylines)."""
    return sum(float(arc_lengths(half_edge_polyline(graph, e, u))[-1]) for e, u in side)


def _pieces(graph, kind: str, target: int, fraction: float | None) -> tuple:
    """The lengths of the two pieces a chord's foot off the middle (``fraction`` of the plan edge
    ``target``) cuts that edge into; none for a foot at the middle or on the boundary."""
    if kind != "edge" or fraction == 0.5:
        return ()
    length = float(arc_lengths(half_edge_polyline(graph, target, graph.ends(target)[0]))[-1])
    return fraction * length, (1.0 - fraction) * length


def even_group(graph, patch: int, found, k: int, j: int, end, pieces: tuple = (),
                ratio: float = MAX_RATIO) -> bool:
    """Whether the chord from corner ``k`` to ``end`` leaves its edge group even, its lengths within
    ``ratio`` (:data:`MAX_RATIO` unless given; and the two ``pieces`` of the edge it cuts off the
    middle, :func:`_pieces`, too: at :data:`MAX_RATIO` the feet a quarter of the way in, 1 : 3, are
    refused): the triangle's two
    sides at the corner (its pole) are one group (Figure 3, §3.2), and the side along the quad's
    side from the corner is in one group with the opposite side of the patch beyond it. Where these
    lengths differ by more than :data:`MAX_RATIO`, the count the longest needs over-refines the
    shortest: multiple_lobes' notch corners sit at fan-shaped patches (a side of 0.7 opposite one of
    4.7), and chords of 5.7 beside them doubled the mesh (2338 faces for 1110) with slivers of
    0.05 x 0.17 that made the tessellation refine to 7150 voussoirs from 974."""
    side = found.sides[k] if j == 1 else found.sides[k - 1]
    lengths = [math.dist(graph.get(found.corners[k], "pos"), end), side_length(graph, side)]
    if pieces and max(pieces) > ratio * min(pieces):
        return False
    if len(side) == 1:
        beyond = patch_across(graph, patch, side[0][0])
        sides = patch_sides(graph, beyond[0]) if beyond else None
        if sides is not None and len(sides.corners) == 4:
            lengths.append(side_length(graph, sides.sides[(beyond[1] + 2) % 4]))
    return max(lengths) <= ratio * min(lengths)


def patch_corner(graph, found, k: int) -> tuple[tuple, float, float]:
    """A patch's corner ``k``: its position, the direction (radians) of the side leaving it and the
    patch's interior angle there (degrees), between the first steps of its two sides."""
    pos = graph.get(found.corners[k], "pos")
    e, u = found.sides[k][0]
    out = half_edge_polyline(graph, e, u)[1]  # the first step along the side leaving the corner
    e, u = found.sides[k - 1][-1]
    back = half_edge_polyline(graph, e, u)[-2]  # the last step of the side arriving there, reversed
    d_out = direction(pos, out)
    return pos, d_out, ccw_degrees(d_out, direction(pos, back))


def _once(graph, work, r: int):
    """``work(graph, r)`` (:func:`choose_chord` or :func:`choose_cut`), worked out once per corner and state of
    the graph; :func:`choose_chord`'s kept beyond, while the patches it read are untouched (:func:`_kept_chord`)."""
    return memo_at(_STATE, graph, (work, r), lambda: _kept_chord(graph, r) if work is choose_chord else work(graph, r))


def _kept_chord(graph, r: int):
    """:func:`choose_chord`, kept while no change of the graph touches what it read
    (:class:`~vaultgram.topology.statecache.Untouched`): ``r``'s place among the rings and its angle (the
    key), ``r`` and its patch corner edges, and every patch whose sides it asked for
    (:data:`~vaultgram.topology.strips.READS`: the patches at ``r``, those its strips cross, those beyond
    a side), with every node round them, whose positions, types, attributes and edges (their polylines and
    feet) it reads. Every rule application makes a new state of the graph, and the rules whose conditions
    ask for the chord of every reflex corner re-match the whole graph after each (the jagged outlines:
    1,588 chords worked out for one plan, issue 18): a strip carried across the layout changes a few
    patches, and the corners whose patches and strips it left alone keep their chord."""
    key = (r, ring_place(graph, r)[0], boundary_angle(graph, r))
    return untouched(_KEPT, graph).get(graph, key, lambda: _footprinted(graph, r))


def _footprinted(graph, r: int) -> tuple:
    """:func:`choose_chord` and its footprint (:func:`_kept_chord`); None for the footprint where a Patch
    node's sides were not found (the faces it walked are not named: kept for this state only)."""
    read: list = []
    READS.append(read)
    try:
        choice = choose_chord(graph, r)
    finally:
        READS.pop()
    if any(found is None for _, found in read):
        return choice, None
    nodes = {r}
    for patch, found in read:
        nodes.add(patch)
        nodes.update(u for side in found.sides for _, u in side)
    return choice, nodes


def reflex_chord(graph, patch: int, r: int) -> int:
    """The plan edge to whose middle the chord from the reflex corner ``r`` runs in the quad
    ``patch`` (a whole side of it away from ``r``; a strip carries it on beyond), where this is the
    corner's best chord (see the module docstring); -1 otherwise."""
    choice = _once(graph, choose_chord, r)
    return choice[2] if choice is not None and choice[:2] == (patch, "edge") else -1


def reflex_side(graph, patch: int, r: int) -> int:
    """The corner of the quad ``patch`` where the side starts on which the chord from the reflex
    corner ``r`` ends, where this is the corner's best chord; ``r`` itself otherwise."""
    choice = _once(graph, choose_chord, r)
    return choice[3] if choice is not None and choice[0] == patch else r


def reflex_foot(graph, patch: int, r: int) -> int:
    """The boundary point (on a side of the quad ``patch`` away from ``r``) where the chord from the
    reflex corner ``r`` ends, where this is the corner's best chord; ``r`` itself otherwise."""
    choice = _once(graph, choose_chord, r)
    return choice[2] if choice is not None and choice[:2] == (patch, "point") else r


def on_side(graph, r: int) -> tuple[int, int] | None:
    """The Patch node with the boundary point ``r`` inside one of its sides, and that side's index:
    found from the first patch corner before ``r`` along its ring (a patch's boundary side runs in
    ring order, the domain on its left); None where ``r`` is a patch's corner or none is found."""
    if graph.degree(r, [PATCH_CORNER]):
        return None
    _, nodes = graph_rings(graph)
    ring, k = ring_place(graph, r)
    ids = nodes[ring]
    a = next((ids[k - j] for j in range(1, len(ids)) if graph.degree(ids[k - j], [PATCH_CORNER])), None)
    for q in sorted({graph.ends(e)[0] for e in graph.incident(a, [PATCH_CORNER])} if a is not None else ()):
        found = patch_sides(graph, q)
        if found is None or a not in found.corners:
            continue
        i = found.corners.index(a)
        if any(u == r for _, u in found.sides[i]):
            return q, i
    return None


def choose_cut(graph, r: int) -> tuple | None:
    """The chord across the quad on whose side the reflex corner ``r`` lies (:func:`reflex_cut`):
    ``(patch, side index, edge, fraction)``, or None. It ends at the first of the opposite edge's
    feet (:func:`_feet`: the middle where it can) where it runs inside the quad and leaves no angle
    below :data:`MIN_CUT_ANGLE` (:func:`_cut_foot`): a corner of a ring patch round a hole lies
    anywhere along the hole's side, and a chord to the middle of the loop beyond may run along it.
    Where the strip is one triangle of a point feature's fan and no foot halves it into two of
    :data:`MIN_CUT_ANGLE` degrees, the feet that halve it into two of :data:`MIN_FAN_HALF`."""
    across = _cut_across(graph, r)
    if across is None:
        return None
    patch, i, found, edge, walk = across
    fans = walk is not None and (fan_end(graph, walk) or strip_fan(graph, walk))
    halves = (MIN_CUT_ANGLE, MIN_FAN_HALF) if fans else (MIN_CUT_ANGLE,)
    for half in halves:
        fraction = _cut_foot(graph, r, found, _feet(graph, walk, half=half))
        if fraction is not None:
            return patch, i, edge, fraction
    return None


def _cut_across(graph, r: int) -> tuple | None:
    """Where a cut from the reflex corner ``r`` inside a quad's side may run: ``(patch, side index, its
    sides, the plan edge opposite, the walk of the strip a cut to it starts)`` (:func:`cut_walk`, None
    where it does not complete); None where ``r`` lies inside no quad's side or the opposite side is
    not one plan edge a strip may cut."""
    at = on_side(graph, r)
    if at is None or len(patch_sides(graph, at[0]).corners) != 4:
        return None
    patch, i = at
    found = patch_sides(graph, patch)
    edge = side_edge(graph, patch, found.corners[(i + 2) % 4])
    return None if edge < 0 else (patch, i, found, edge, cut_walk(graph, patch, edge))


def _bisecting_cut(graph, r: int) -> tuple | None:
    """The cut of the reflex corner ``r`` (as :func:`choose_cut`'s) whose strip is one triangle of a pole's
    fan, ending at the foot whose chord to the pole bisects the triangle's angle there
    (:func:`bisecting_foot`), where :func:`choose_cut` has none: the halves reach :data:`MIN_FAN_HALF`, the
    chords run inside, the cut leaves no angle below :data:`MIN_CUT_ANGLE` (:func:`_cut_foot`). For
    ``rules/corners.vgr``'s last cut, after the rebranch to the fan's pole (which takes a skewed fan
    triangle out of the layout where it qualifies: with Figure 4's crescents allowed, the bisecting
    cut taken first left draw 666 of session 23's plans 7 boundary singular vertices and a worst face
    of 0.014, the rebranch 3 and 0.301)."""
    across = _cut_across(graph, r)
    if across is None or across[4] is None or fan_end(graph, across[4]) is None or _once(graph, choose_cut, r):
        return None
    patch, i, found, edge, walk = across
    fraction = _cut_foot(graph, r, found, _feet(graph, walk, bisecting_foot(graph, walk), MIN_FAN_HALF))
    return None if fraction is None else (patch, i, edge, fraction)


def bisecting_foot(graph, walk) -> tuple:
    """Where the chord from the pole of the fan triangle ``walk`` ends (:func:`fan_end`: a strip of one
    triangle, entered by the side opposite the pole) bisects the triangle's angle at the pole: the
    fraction of the entry edge's length there, as a one-foot tuple for :func:`_feet`, where it lies at
    least :data:`BISECTING_FOOT` from either end; empty otherwise. The most even halves any foot of that
    edge gives the fan (§4.1: the pole stays the pole of both), found where :data:`FEET`' fixed
    fractions miss them on a skewed triangle."""
    pos, d_out, whole = fan_end(graph, walk)
    edge = walk.edges[0]
    fraction = ray_hit_fraction(half_edge_polyline(graph, edge, graph.ends(edge)[0]), pos,
                                d_out + math.radians(whole / 2.0))
    return (fraction,) if fraction is not None and BISECTING_FOOT <= fraction <= 1.0 - BISECTING_FOOT else ()


def _cut_foot(graph, r: int, found, feet) -> float | None:
    """The fraction of the first of ``feet`` (:func:`_feet`) where the cut from the reflex corner ``r``
    across the quad ``found`` runs inside it and leaves no angle below :data:`MIN_CUT_ANGLE` at ``r``
    (from the boundary leaving ``r``, measured as its interior angle is, and the rest) or with the
    edge it meets; None where none does."""
    pos, ahead, theta = graph.get(r, "pos"), boundary_ahead(graph, r), boundary_angle(graph, r)
    for fraction, foot, tangent in feet:
        d_chord = direction(pos, foot)
        first = ccw_degrees(ahead, d_chord)  # between the boundary leaving r and the chord
        meet = ccw_degrees(tangent, d_chord) % 180.0
        if min(first, theta - first, meet, 180.0 - meet) >= MIN_CUT_ANGLE and chord_inside(found, pos, foot):
            return fraction
    return None


def _cut_part(graph, find, patch: int, r: int, part: int) -> int:
    """Item ``part`` of the cut that ``find`` (:func:`choose_cut` or :func:`_bisecting_cut`) gives the reflex
    corner ``r`` (1: the index of the quad's side holding ``r``, 2: the plan edge cut), where that cut
    lies in the quad ``patch``; -1 otherwise."""
    cut = _once(graph, find, r)
    return cut[part] if cut is not None and cut[0] == patch else -1


def reflex_cut(graph, patch: int, r: int) -> int:
    """Where the reflex corner ``r`` lies inside a side of the quad ``patch`` (the corner of no patch:
    two faces where its angle asks for three), the plan edge opposite that side, to whose middle a
    chord from ``r`` runs, carried on beyond as a strip; -1 where there is none (the chord would
    leave the quad, its strip would not complete, an angle would be below :data:`MIN_ANGLE`)."""
    return _cut_part(graph, choose_cut, patch, r, 2)


def reflex_cut_index(graph, patch: int, r: int) -> int:
    """The index of the side of the quad ``patch`` inside which the reflex corner ``r`` lies, where
    :func:`reflex_cut` has a chord for it; -1 otherwise."""
    return _cut_part(graph, choose_cut, patch, r, 1)


def reflex_cut_at(graph, r: int) -> bool:
    """Whether :func:`reflex_cut` has a chord for the reflex corner ``r`` in some quad."""
    return _once(graph, choose_cut, r) is not None


def reflex_bisecting_cut(graph, patch: int, r: int) -> int:
    """As :func:`reflex_cut`, for the cut whose chord to a fan's pole bisects the fan triangle
    (:func:`_bisecting_cut`): the plan edge it cuts in the quad ``patch``; -1 where there is none."""
    return _cut_part(graph, _bisecting_cut, patch, r, 2)


def reflex_bisecting_cut_index(graph, patch: int, r: int) -> int:
    """The index of the side of the quad ``patch`` inside which ``r`` lies, where
    :func:`reflex_bisecting_cut` has a cut for it; -1 otherwise."""
    return _cut_part(graph, _bisecting_cut, patch, r, 1)


def reflex_bisecting_cut_at(graph, r: int) -> bool:
    """Whether :func:`reflex_bisecting_cut` has a cut for the reflex corner ``r`` in some quad."""
    return _once(graph, _bisecting_cut, r) is not None


def _foot_of(graph, patch: int, r: int) -> tuple[int, float]:
    """The plan edge where the chord from the reflex corner ``r`` in the quad ``patch`` ends and the
    fraction of its length there: the cut's where ``r`` lies inside a side (:func:`reflex_cut`, or
    :func:`reflex_bisecting_cut`), else the chord's (:func:`reflex_chord`). Asked only where one of them matched."""
    if not graph.degree(r, [PATCH_CORNER]):
        cut = _once(graph, choose_cut, r) or _once(graph, _bisecting_cut, r)
        return cut[2], cut[3]
    choice = _once(graph, choose_chord, r)
    return choice[2], choice[4]


def reflex_point(graph, patch: int, r: int) -> tuple[float, float]:
    """Where the chord from the reflex corner ``r`` in the quad ``patch`` meets the plan edge it cuts
    (the new corner, a strip point: :func:`reflex_cut` or :func:`reflex_chord` chose it)."""
    edge, fraction = _foot_of(graph, patch, r)
    foot = edge_cut(graph, edge, fraction)[1]
    return float(foot[0]), float(foot[1])


def smooth_boundary_side(graph, side) -> bool:
    """Whether a patch side (its half-edges ``(edge, start)``) runs along the boundary and every point
    inside it is a free smooth point (no feature, regular valence 3 by its angle: 135-225 degrees), so
    that the side may become part of the patch beyond's boundary side unchanged (two faces at each
    point, as now)."""
    if any(graph.edge_type(e) != BOUNDARY for e, _ in side):
        return False
    inner = [u for _, u in side[1:]]
    return all(not graph.get(u, "feature") and regular_valence(boundary_angle(graph, u)) == 3 for u in inner)


def rebranch_to_corner(graph, patch: int, b: int, c: int, x: int) -> bool:
    """Whether a rebranch from the skeleton vertex ``x`` to the corner ``b`` of the quad ``patch`` (a
    corner of 135 to 225 degrees, its one patch's only; ``c`` the patch's corner next to it along the
    ring where the rebranch ends now: ``rules/patching.vgr``, ``move_rebranch_to_lone_corner``) runs
    straight inside the patch and splits its angle at ``b`` into two of at least :data:`MIN_ANGLE`
    degrees: the one on ``c``'s side (the patch beyond gets that) and the triangle's, at most
    :data:`MAX_POLE_ANGLE` (its pole, meshed as three quads). The same limits as a reflex corner's
    chord (:func:`choose_chord`), for the same reason: a sliver beside ``b`` would cost more than its
    boundary singularity (issue 12, item 3). The patch's side from ``b`` to ``c`` must be a run of
    free smooth boundary points (:func:`smooth_boundary_side`: it joins the patch beyond's side, and
    each point keeps its two faces) and the triangle's sides at ``b`` within :data:`MAX_POLE_RATIO`."""
    found = patch_sides(graph, patch)
    if found is None or len(found.corners) != 4 or b not in found.corners:
        return False
    k = found.corners.index(b)
    forward = c == found.corners[(k + 1) % 4]
    to_c, to_a = (found.sides[k], found.sides[k - 1]) if forward else (found.sides[k - 1], found.sides[k])
    pos, d_out, whole = patch_corner(graph, found, k)
    to = graph.get(x, "pos")
    pole_sides = math.dist(pos, to), side_length(graph, to_a)
    if not smooth_boundary_side(graph, to_c) or max(pole_sides) > MAX_POLE_RATIO * min(pole_sides):
        return False
    first = ccw_degrees(d_out, direction(pos, to))  # between the side leaving b and the rebranch
    triangle = whole - first if forward else first
    return (MIN_ANGLE <= first <= whole - MIN_ANGLE and triangle <= MAX_POLE_ANGLE
            and chord_inside(found, pos, to))
