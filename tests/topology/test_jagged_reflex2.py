"""Reflex corners of jagged outlines left with too few faces, round 2 (issue 12, acceptance 3 / What 2): the
outer ring's second fallback (:func:`vaultgram.topology.reflex_fallbacks.point_quads`, asked by
``reflex._outer_chord`` after the 35 degree fallback): a chord to a boundary point down to 20 degrees, in a
quad that turns past straight at the corner or at a spike.

On main 28c810b jagged_1's 299 degree corner at (5.769, 13.166) was the corner of a 112 and a 187 degree quad
(two faces where 225-315 degrees ask for three; its worst face, 0.223, beside it) and its 334 degree spike at
(5.371, -16.695) the corner of three patches (three faces where 315-360 degrees ask for four); jagged_1 had 7
boundary singular vertices. Their best chords to a boundary point are at 27.2 and 20.6 degrees.
"""

from __future__ import annotations

import pytest
from layout_probes import faces_at, laid_out, node_at

from vaultgram.domain import domain_from_dict
from vaultgram.meshing.quality import mesh_stats
from vaultgram.meshpipeline import decompose
from vaultgram.testing.jagged import jagged_plans
from vaultgram.topology import reflex
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.reflex_fallbacks import OUTER_POINT_MIN_ANGLE, point_quads
from vaultgram.topology.strips import patch_sides
from vaultgram.topology.types import PATCH_CORNER

PLANS = jagged_plans()


@pytest.fixture(scope="module")
def jagged_1():
    """jagged_1 laid out and meshed (:func:`layout_probes.laid_out`), once."""
    return laid_out(PLANS["jagged_1"], 0.02)


def _corner(graph, at) -> tuple:
    """The boundary point at ``at``, its patches, their sides and their angles there (``choose_chord``'s ``at``)."""
    r = node_at(graph, at, 1e-6)
    patches = sorted({graph.ends(e)[0] for e in graph.incident(r, [PATCH_CORNER])})
    found = [patch_sides(graph, p) for p in patches]
    return r, patches, found, [reflex.patch_corner(graph, s, s.corners.index(r))[2] for s in found]


@pytest.mark.parametrize(("corner", "angle", "faces"), [
    ((5.769, 13.166), 298.9, 3),   # 225-315 degrees: three faces, beside a quad of 187 degrees on main
    ((5.371, -16.695), 334.3, 4),  # a spike: four faces, the corner of three patches on main
])
def test_corner_gets_its_regular_faces(jagged_1, corner, angle, faces):
    """The corner is the corner of one patch more than on main and has its angle's regular number of faces
    in the mesh; no patch there turns past straight."""
    _, dec, mesh = jagged_1
    r, patches, _, angles = _corner(dec.graph, corner)
    assert boundary_angle(dec.graph, r) == pytest.approx(angle, abs=0.05)
    assert len(patches) == faces, angles
    assert max(angles) <= reflex.PAST_STRAIGHT, angles
    assert faces_at(mesh, corner, 1e-6) == faces


def test_jagged_1_fewer_boundary_singular_worst_face_higher(jagged_1):
    """jagged_1 has 5 boundary singular vertices (main 7), no inverted face, and its worst face is 0.302
    (main 0.223: the 187 degree quad's corner, now split by the chord)."""
    domain, _, mesh = jagged_1
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] <= 5, stats["boundary_singular_angles"]
    assert stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.29, stats["min_scaled_jacobian"]


@pytest.mark.parametrize(("corner", "angle", "chord"), [((7.165, -16.045), 279.2, False),
                                                      ((-9.154, 19.008), 235.1, True)])
def test_no_point_chord_in_a_quad_short_of_straight(corner, angle, chord, monkeypatch):
    """jagged_3's corners at (7.165, -16.045) (quads of 102 and 177 degrees) and (-9.154, 19.008) (127 and
    108) had chords to a boundary point of 25.5 and 22.8 degrees in states the rules pass through: either
    one taken lowered jagged_3's worst face from 0.369 to 0.32, away from the corner. Neither quad turns
    past straight and neither corner is a spike, so the second fallback refuses both and the corners stay
    the corners of two patches (in the final layout the 22.8 degree chord is still there, refused by the
    quad limit alone; the other corner's quads have none of 20 degrees any more). Since session 33 the
    third fallback (``any_point_quads``) takes both (tests/topology/test_jagged_point_any.py, the bar a
    worst face of 0.25): this test lays jagged_3 out with it off, as on main 9c0e4b0."""
    monkeypatch.setattr(reflex, "any_point_quads", lambda angles, quads: [])
    dec = decompose(domain_from_dict(PLANS["jagged_3"], "jagged_3"), 0.02)
    g = dec.graph
    at = _corner(g, corner)
    r, patches, _, angles = at
    quads = list(range(len(patches)))
    assert boundary_angle(g, r) == pytest.approx(angle, abs=0.05)
    assert len(patches) == 2 and max(angles) < reflex.PAST_STRAIGHT, angles
    assert point_quads(angles, quads, boundary_angle(g, r), reflex.PAST_STRAIGHT, reflex.SPIKE) == []
    best = reflex.widest_chord(g, at, quads, OUTER_POINT_MIN_ANGLE, every_foot=True,
                               keep=lambda i, pole, kind: kind == "point")
    assert (best is not None and best[2] == "point") == chord  # the chord the quad limit alone refuses
    assert reflex.choose_chord(g, r) is None


def test_the_second_fallback_limits():
    """Its angle is the hole corner's last fallback's (a quad corner of sin 20 = 0.34), under the first
    fallback's; it looks at quads past straight, or at every quad of a spike."""
    from vaultgram.topology.reflex_fallbacks import OUTER_MIN_ANGLE

    assert OUTER_POINT_MIN_ANGLE == reflex.HOLE_MIN_ANGLE < OUTER_MIN_ANGLE
    limit, spike = reflex.PAST_STRAIGHT, reflex.SPIKE
    assert point_quads([150.0, 130.0], [0, 1], 280.0, limit, spike) == []
    assert point_quads([95.0, 185.0], [0, 1], 280.0, limit, spike) == [1]
    assert point_quads([140.0, 90.0, 100.0], [0, 2], 330.0, limit, spike) == [0, 2]
