"""The outer ring's last fallback for a reflex corner's chord, which
:func:`~vaultgram.topology.reflex.choose_chord` takes where no other chord qualifies (issue 12,
acceptance 3: random non-convex plans with short edges; paper §3.1 and its conclusion).

A reflex corner of 225-315 degrees left the corner of two patches has one face in each: valence 3 where
its angle asks for 4, a boundary singularity. :func:`~vaultgram.topology.reflex.choose_chord` splits one
of its quads by a chord to a foot on a side away from it where the chord's worst angle reaches
:data:`~vaultgram.topology.reflex.MIN_ANGLE` (30) at the side's middle, or
:data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE` (40) at a foot off it. On a jagged outline (geographic
noise: :func:`vaultgram.testing.jagged.jagged_plans`) a corner's quads are long and skewed, their
middle chords narrow, and the best chord is often at a foot 0.3 of the way from one end, with a worst
angle of 35-40 degrees (6 of the 20 reflex corners with too few faces on main ff28880's four jagged
plans). A hole corner has fallbacks down to 20 degrees (:func:`~vaultgram.topology.reflex.hole_chord`);
the outer ring had none, since the same fallbacks there folded jagged_1 and lowered jagged_2's worst
scaled Jacobian (benchmarks/README.md, sessions 20-21).

The outer ring's fallback is the widest chord over every foot down to :data:`OUTER_MIN_ANGLE` (a quad
corner of 35 degrees has a scaled Jacobian of sin 35 = 0.57), its edge group within
:data:`~vaultgram.topology.reflex.MAX_RATIO` as for every other outer chord, in a quad whose angle at the
corner is :data:`OUTER_MIN_QUAD_ANGLE` or more (:func:`wide_quads`), and none that leaves a patch at the
corner turning past straight (:func:`turns_past_straight`). Lower limits and the hole's ratio were
measured and not kept (benchmarks/README.md, session 29): at 30 degrees a 235 degree corner of jagged_2
took a chord at 33 whose strip crossed the plan and its worst face fell 0.198 -> 0.161; within 3.5, a 240
degree corner of jagged_1 took one beside its 299 degree corner of a 187 degree quad and the mesh folded
there, or fell 0.061 -> 0.027.

Where that fallback finds none either, a second one (:func:`point_quads`, session 30): a chord to the free
boundary point nearest the middle of a quad's boundary side (no strip: the quad becomes a triangle and a
quad, and nothing beyond it changes) down to :data:`OUTER_POINT_MIN_ANGLE`, in a quad that turns past
straight at the corner or at a spike. Splitting such a quad undoes a turn the mesh folds at
(:data:`~vaultgram.topology.reflex.PAST_STRAIGHT`), and a spike's third patch keeps the angles of the
other two. On main 28c810b jagged_1's 299 degree corner beside a 187 degree quad (best chord 27.2 degrees,
to a boundary point) and its 334 degree spike of three patches (20.6) take it: boundary singular 7 -> 5,
worst face 0.223 -> 0.302, at that corner. The wider fallbacks measured against it
(benchmarks/README.md, session 30) changed the density across the plan: jagged_3's worst face fell
0.369 -> 0.30-0.36 with any of its chords at 20-38 degrees, wherever they were.

Where neither finds one, a third (:func:`any_point_quads`, session 33): the same chord to a boundary point,
down to :data:`OUTER_POINT_MIN_ANGLE`, in any quad of the corner, its edge group within
:data:`~vaultgram.topology.reflex.HOLE_MAX_RATIO` (3.5). On main 9c0e4b0 four corners of 235-292 degrees of
the jagged plans, each the corner of two quads short of straight, take chords of 20.6-28.6 degrees and
become regular: boundary singular 25 -> 21 (jagged_0 9 -> 8, jagged_2 5 -> 4, jagged_3 7 -> 5). The cost
session 30 measured is there: jagged_3's worst face falls 0.375 -> 0.328, away from the corners (the edge
groups' counts move), above the 0.25 bar. Edge chords too (30 degrees, within 3.5, any quad) made two more
corners regular but re-laid multiple_lobes' notches (8 -> 15 patches, 1080 -> 1704 faces); not kept.

This module imports nothing of :mod:`vaultgram.topology.reflex`, which asks it (its
:func:`~vaultgram.topology.reflex.widest_chord` with :func:`turns_past_straight` as the ``keep`` test).
"""

from __future__ import annotations

__all__ = ["OUTER_MIN_ANGLE", "OUTER_MIN_QUAD_ANGLE", "OUTER_POINT_MIN_ANGLE", "any_point_quads", "point_quads",
           "turns_past_straight", "wide_quads"]

#: Degrees: the worst angle an outer-ring corner's fallback chord may leave, at any foot of
#: :data:`~vaultgram.topology.reflex.FEET`: between the 30 a chord to a side's middle needs and the 40 a
#: foot off the middle needs otherwise. On the four jagged plans 35 made two corners of 227 and 306
#: degrees regular (best chords at 35.4 and 37.3) and no worst face lower (jagged_3 0.245 -> 0.277);
#: 30 took a third corner's chord at 33 degrees and jagged_2 fell 0.198 -> 0.161.
OUTER_MIN_ANGLE = 35.0
#: Degrees: the fallback splits only a quad this wide or wider at the corner (:func:`wide_quads`), whose
#: split leaves the quad part at least 100 degrees beside the triangle's 35 or more. In a narrower quad
#: the two parts are both narrow: multiple_lobes' notch corners (quads of 106 and 114 degrees beside
#: fan-shaped patches, best chords at 39 and 35) took such chords and its mesh went from 1080 faces to
#: 1209-1600, its worst face from 0.407 to 0.365-0.380 (two boundary singular vertices fewer). The jagged
#: corners the fallback makes regular split quads of 137-162 degrees.
OUTER_MIN_QUAD_ANGLE = 135.0
#: Degrees: the worst angle of the second fallback's chord to a boundary point (:func:`point_quads`), as a
#: hole corner's last fallback (:data:`~vaultgram.topology.reflex.HOLE_MIN_ANGLE`): a quad corner of 20 degrees
#: has a scaled Jacobian of sin 20 = 0.34. jagged_1's two corners that take it are at 27.2 and 20.6.
OUTER_POINT_MIN_ANGLE = 20.0


def turns_past_straight(angles: list, i: int, pole: float, limit: float) -> bool:
    """Whether a chord that cuts the angle (degrees) of the ``i``-th of a reflex corner's patches
    (``angles``: their angles there) into the triangle's ``pole`` and the rest leaves the corner a patch
    wider than ``limit`` (:data:`~vaultgram.topology.reflex.PAST_STRAIGHT`): one of those two parts, or
    another patch's angle, which the chord keeps. Such a patch keeps one face across more than 180
    degrees at a corner with one face more to share out, and its quad folds there (jagged_1's 299
    degree corner beside a 187 degree quad).

    >>> turns_past_straight([150.0, 140.0], 0, 60.0, 181.0), turns_past_straight([150.0, 187.0], 0, 60.0, 181.0)
    (False, True)
    >>> turns_past_straight([200.0, 100.0, 30.0], 0, 15.0, 181.0)
    True
    """
    rest = [a for m, a in enumerate(angles) if m != i]
    return max([pole, angles[i] - pole, *rest]) > limit


def wide_quads(angles: list, quads: list) -> list:
    """The indices among ``quads`` of the reflex corner's patches (``angles``: their angles there,
    degrees) that are at least :data:`OUTER_MIN_QUAD_ANGLE` wide at the corner: the quads the outer
    ring's fallback may split.

    >>> wide_quads([105.7, 127.0], [0, 1]), wide_quads([89.9, 137.5], [0, 1]), wide_quads([161.7, 144.3], [1])
    ([], [1], [1])
    """
    return [i for i in quads if angles[i] >= OUTER_MIN_QUAD_ANGLE]


def point_quads(angles: list, quads: list, theta: float, past: float, spike: float) -> list:
    """The indices among ``quads`` of the reflex corner's patches (``angles``: their angles there,
    degrees; ``theta``: the corner's interior angle) whose chords to a boundary point the outer ring's
    second fallback may take: a quad wider than ``past`` (:data:`~vaultgram.topology.reflex.PAST_STRAIGHT`)
    at the corner, whose mesh would turn past straight there, or any quad at a spike (``theta`` of
    ``spike``, :data:`~vaultgram.topology.reflex.SPIKE`, or more: four faces asked, and the chord in its third
    patch leaves the other two as they are). Not any quad at a 225-315 degree corner: jagged_3's two such
    chords (25.5 and 22.8 degrees, in quads of 177 and 108) each lowered its worst face from 0.369 to 0.32,
    away from the corner (the edge groups' counts moved).

    >>> point_quads([111.9, 187.1], [0, 1], 298.9, 181.0, 315.0)
    [1]
    >>> point_quads([137.0, 83.2, 114.1], [0, 2], 334.3, 181.0, 315.0)
    [0, 2]
    >>> point_quads([102.2, 177.1], [0, 1], 279.2, 181.0, 315.0)
    []
    """
    return [i for i in quads if angles[i] > past or theta >= spike]


def any_point_quads(angles: list, quads: list) -> list:
    """The indices among ``quads`` of the reflex corner's patches (``angles``: their angles there, degrees)
    whose chords to a boundary point the outer ring's third fallback may take: every quad (session 33; the
    second fallback's limits, :func:`point_quads`, were what spared jagged_3's worst face). Its own function
    so that a test can switch the fallback off.

    >>> any_point_quads([102.2, 177.1], [0, 1])
    [0, 1]
    """
    return list(quads)
