"""The last fallback of a reflex corner's chord on the outer ring: the helper
:func:`~vaultgram.topology.reflex.choose_chord` asks where no other chord qualifies (issue 12, acceptance 3:
random non-convex plans with short edges; paper §3.1 and its conclusion).

A reflex corner of 225-315 degrees left the corner of two patches has one face in each: valence 3 where
its angle asks for 4, a boundary singularity. :func:`~vaultgram.topology.reflex.choose_chord` splits one
of its quads by a chord to a foot on a side away from it where the chord's worst angle reaches
:data:`~vaultgram.topology.reflex.MIN_ANGLE` (30) at the side's middle, or
:data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE` (40) at a foot off it. On a jagged outline (geographic
noise: :func:`vaultgram.testing.jagged.jagged_plans`) the corners' quads are long and skewed, their
middle chords narrow, and the chord that qualifies best is at a foot 0.3 of the way from one end with a
worst angle of 35-40 degrees: 6 of the 20 reflex corners with too few faces on main ff28880's four jagged
plans. A hole corner has its fallbacks down to 20 degrees
(:func:`~vaultgram.topology.reflex.hole_chord`); the outer ring had none, since the same fallbacks
there folded jagged_1 and lowered jagged_2's worst scaled Jacobian (benchmarks/README.md, sessions 20-21).

:func:`outer_chord` takes the widest chord over every foot down to :data:`OUTER_MIN_ANGLE` (35 degrees: a
quad corner of 35 degrees has a scaled Jacobian of sin 35 = 0.57), with the edge group within
:data:`~vaultgram.topology.reflex.MAX_RATIO` as for every other outer chord, and never where the corner
keeps a patch turning past straight (:data:`~vaultgram.topology.reflex.PAST_STRAIGHT`): the other patch's
angle and the chord's two parts of its own stay under it. A corner whose other patch already turns past
straight gets a third face it cannot share, and the quad there folds. Measured on the jagged plans and the
700 saved random plans (benchmarks/README.md, session 29): lower limits (30, 25, 20) and the hole's ratio
(3.5) each lowered a jagged plan's worst face below main's (jagged_2 0.198 -> 0.16-0.17 from one 235
degree corner's chord at 33 degrees; jagged_1 0.061 -> 0.027, or a fold, from a 240 degree corner's chord
within 3.5 beside its 299 degree corner of a 187 degree quad).
"""

from __future__ import annotations

from vaultgram.topology import reflex
from vaultgram.topology.corners import boundary_angle, ring_place

__all__ = ["OUTER_MIN_ANGLE", "outer_chord", "turns_past_straight"]

#: Degrees: the worst angle an outer-ring corner's fallback chord may leave (:func:`outer_chord`), at
#: any foot of :data:`~vaultgram.topology.reflex.FEET`: between the middle's 30 and the 40 a foot off
#: the middle needs otherwise. On the four jagged plans 35 took three corners of 227-306 degrees whose
#: best chords were at 35-40 (two of them regular after, the worst faces no lower: jagged_3 0.245 ->
#: 0.277); 30 took a fourth at 33 degrees and jagged_2 fell 0.198 -> 0.161.
OUTER_MIN_ANGLE = 35.0


def turns_past_straight(angles: list, i: int, pole: float) -> bool:
    """Whether a chord that cuts the angle (degrees) of the ``i``-th of a reflex corner's patches
    (``angles``: their angles there) into the triangle's ``pole`` and the rest leaves the corner a patch
    wider than :data:`~vaultgram.topology.reflex.PAST_STRAIGHT`: one of those two parts, or another
    patch's angle, which the chord keeps. Such a patch keeps one face across more than 180 degrees at a
    corner that now has one face more to share out, and its quad folds there (jagged_1's 299 degree
    corner beside a 187 degree quad).

    >>> turns_past_straight([150.0, 140.0], 0, 60.0), turns_past_straight([150.0, 187.0], 0, 60.0)
    (False, True)
    >>> turns_past_straight([200.0, 100.0, 30.0], 0, 15.0)
    True
    """
    rest = [a for m, a in enumerate(angles) if m != i]
    return max([pole, angles[i] - pole, *rest]) > reflex.PAST_STRAIGHT


def outer_chord(graph, at: tuple, quads: list) -> tuple | None:
    """The last fallback of a chord at a corner ``at`` of the outer ring (as
    :func:`~vaultgram.topology.reflex.widest_chord` takes it: the corner, its patches, their sides and
    their angles there; ``quads`` the indices of the quads among them), where
    :func:`~vaultgram.topology.reflex.choose_chord` found none: of every foot of every side of those quads,
    the chord whose worst angle is widest, at least :data:`OUTER_MIN_ANGLE`, its triangle's pole within
    :data:`~vaultgram.topology.reflex.MAX_POLE_ANGLE`, its edge group within
    :data:`~vaultgram.topology.reflex.MAX_RATIO`, leaving no patch at the corner past straight
    (:func:`turns_past_straight`); as ``(worst, patch, kind, target, side, fraction)``, or None (a hole's
    corner too: it has :func:`~vaultgram.topology.reflex.hole_chord`)."""
    r, patches, found, angles = at
    if ring_place(graph, r)[0] != 0:
        return None
    theta = boundary_angle(graph, r)
    best = None
    for i in quads:
        p, sides = patches[i], found[i]
        k = sides.corners.index(r)
        other = reflex.other_angle(theta, angles, i)
        for j in (1, 2):
            for target in reflex.chord_targets(graph, p, sides, k, j):
                worst = reflex.chord_worst(graph, p, sides, k, j, target, other, OUTER_MIN_ANGLE)
                if worst is None or (best is not None and worst <= best[0]):
                    continue
                pole = reflex.chord_angles(graph, sides, k, j, target[2], target[3], other)[1]
                if not turns_past_straight(angles, i, pole):
                    best = (worst, p, target[0], target[1], sides.corners[(k + j) % 4], target[4])
    return best
