"""Reflex corners of any plan given a patch of their own: the helper of ``rules/patching.vgr``'s
``split_quad_at_reflex_corner_to_side`` (issue 12, item 2).

The medial axis sends no branch to a reflex corner (§3.1). Where a rebranch arrives there the corner
is the corner of two patches, which share its 225-315 degrees with one face each: valence 3 where its
angle asks for 4 (a boundary singularity, the distortion the paper's conclusion names, after Rigby
[11] and Fogg et al. [10]). On a rectilinear plan the chords of ``rules/corners.vgr`` avoid it; on
any other plan one of the corner's quads is split by a chord from the corner to the middle of one of
its two sides away from the corner (a branch, rebranch or diagonal): a triangle with the corner as
its marked pole, and a quad. The chord's far end is a T-junction on the patch beyond, carried across
the layout as a strip of quads (``rules/strips.vgr``) to the boundary or into a triangle. The
triangle is meshed as three quads meeting at an inner point of valence 3 (the mesher splits a
triangle whose marked pole is a boundary point, :mod:`vaultgram.meshing.splits`), so the corner gets
one face more (three: regular), the strip's corners are regular, and the one singular vertex added
is the split's inner point: the index the corner gives up goes inside the plan.

:func:`reflex_chord` picks, among the corner's quads and their sides a strip may cut and complete
across (:func:`~vaultgram.topology.strips.strip_from_curve_end`), the chord whose worst angle is
widest: the three patch angles at the corner after the split and the chord's two angles with the side
it ends on. Where that worst angle is below :data:`MIN_ANGLE` the corner is left as it is (a sliver
of a patch would cost more in the mesh's worst element than the singularity).
"""

from __future__ import annotations

import math
import weakref

from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.patches import half_edge_polyline
from vaultgram.topology.statecache import per_state
from vaultgram.topology.strips import _across, _halves, patch_sides, side_edge, strip_from_curve_end, strip_walk
from vaultgram.topology.types import BOUNDARY_VERTEX, PATCH_CORNER

__all__ = ["reflex_chord", "MIN_ANGLE", "MAX_POLE_ANGLE"]

#: Degrees: no chord whose worst angle (at the corner or where it meets the side) is narrower.
MIN_ANGLE = 20.0
#: Degrees: the triangle's angle at the corner must allow the three-quad split
#: (:data:`vaultgram.meshing.splits.MAX_SPLIT_ANGLE`).
MAX_POLE_ANGLE = 160.0

_STATE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: {corner: choice}}


def _direction(a, b) -> float:
    """The direction (radians) from point ``a`` to point ``b``."""
    return math.atan2(float(b[1]) - float(a[1]), float(b[0]) - float(a[0]))


def _ccw(start: float, end: float) -> float:
    """Degrees turning counter-clockwise from direction ``start`` to ``end``, in [0, 360)."""
    return math.degrees(end - start) % 360.0


def _side_tangent(graph, edge: int) -> float:
    """The direction (radians) of a plan edge at its strip point (the middle, where the chord ends)."""
    before, mid, after = _halves(graph, edge)
    ahead = after[0] if len(after) else graph.get(graph.ends(edge)[1], "pos")
    back = before[-1] if len(before) else graph.get(graph.ends(edge)[0], "pos")
    return _direction(back, ahead)


def _angles(graph, found, k: int, j: int, edge: int, other: float) -> tuple[float, float]:
    """For the chord from corner ``k`` of the quad ``found`` to the middle of ``edge``, its side from
    corner ``k + j`` (``j`` 1 or 2): the worst angle (degrees: the two parts of the quad's angle at
    the corner, ``other`` the angle of the corner's other patch, the chord's angles with the side)
    and the angle at the corner of the triangle the chord cuts off."""
    pos, d_out, whole = _corner(graph, found, k)
    d_chord = _direction(pos, _halves(graph, edge)[1])
    first = _ccw(d_out, d_chord)  # between the leaving side and the chord
    if not 0.0 < first < whole:
        return -1.0, 360.0
    meet = _ccw(_side_tangent(graph, edge), d_chord) % 180.0
    return min(first, whole - first, other, meet, 180.0 - meet), first if j == 1 else whole - first


def _choose(graph, r: int) -> tuple[int, int] | None:
    """The (patch, edge) of the chord from the reflex corner ``r`` (:func:`reflex_chord`), or None."""
    patches = sorted({graph.ends(e)[0] for e in graph.incident(r, [PATCH_CORNER])})
    found = [patch_sides(graph, p) for p in patches]
    if any(f is None for f in found):
        return None
    theta = boundary_angle(graph, r)
    best = None
    for p, sides in zip(patches, found):
        if len(sides.corners) != 4:
            continue
        k = sides.corners.index(r)
        other = theta - _corner(graph, sides, k)[2]
        for j in (1, 2):
            edge = side_edge(graph, p, sides.corners[(k + j) % 4])
            if edge < 0:
                continue
            worst, pole = _angles(graph, sides, k, j, edge, other)
            if worst >= MIN_ANGLE and pole <= MAX_POLE_ANGLE and (best is None or worst > best[0]) \
                    and _strip_ends_well(graph, p, r, edge):
                best = (worst, p, edge)
    return None if best is None else best[1:]


def _strip_ends_well(graph, patch: int, r: int, edge: int) -> bool:
    """Whether the chord from ``r`` to the middle of ``edge`` runs inside the quad and the strip it
    starts in the patch beyond completes (:func:`~vaultgram.topology.strips.strip_from_curve_end`)
    without ending in a triangle at a boundary point: that point would gain a face, a boundary
    singularity (rv_star_pattern's 215 degree vertex, the strip from its 256 degree corner)."""
    if not strip_from_curve_end(graph, patch, r, edge):
        return False
    beyond = _across(graph, patch, edge)
    walk = strip_walk(graph, beyond[0], beyond[1], frozenset([patch]))
    ends = graph.node_type(walk.end) if walk.end is not None else None
    return ends is None or not graph.schema.is_subtype(ends, BOUNDARY_VERTEX) or len(
        patch_sides(graph, walk.patches[-1]).corners) == 4


def _corner(graph, found, k: int) -> tuple[tuple, float, float]:
    """A patch's corner ``k``: its position, the direction (radians) of the side leaving it and the
    patch's interior angle there (degrees), between the first steps of its two sides."""
    pos = graph.get(found.corners[k], "pos")
    e, u = found.sides[k][0]
    out = half_edge_polyline(graph, e, u)[1]  # the first step along the side leaving the corner
    e, u = found.sides[k - 1][-1]
    back = half_edge_polyline(graph, e, u)[-2]  # the last step of the side arriving there, reversed
    d_out = _direction(pos, out)
    return pos, d_out, _ccw(d_out, _direction(pos, back))


def reflex_chord(graph, patch: int, r: int) -> int:
    """The plan edge to whose middle the chord from the reflex corner ``r`` runs in the quad
    ``patch`` (a whole side of it away from ``r``), where this quad and side are the corner's best
    chord (see the module docstring); -1 otherwise. Worked out once per corner and state."""
    memo = per_state(_STATE, graph, lambda g: {})
    if r not in memo:
        memo[r] = _choose(graph, r)
    choice = memo[r]
    return choice[1] if choice is not None and choice[0] == patch else -1
