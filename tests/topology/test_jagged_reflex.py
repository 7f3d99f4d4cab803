"""Reflex corners of jagged outlines left with too few faces (issue 12, acceptance 3): the outer ring's
last fallback chord (:mod:`vaultgram.topology.reflex_fallbacks`, asked by
:func:`vaultgram.topology.reflex.choose_chord`), at any foot down to 35 degrees where no other chord
qualifies, and never beside a patch that turns past straight.

On main ff28880 jagged_2's 227 degree corner at (-6.372, -20.873) and jagged_3's 306 degree corner at
(11.145, 12.955) were the corners of two quads (two faces, valence 3 where 225-315 degrees ask for 4):
their widest chords, at a foot 0.3 of the way along, had worst angles of 35.4 and 37.3 degrees, under
the 40 a foot off the middle needs. jagged_2 had 9 boundary singular vertices, jagged_3 9.
"""

from __future__ import annotations

import json
import math

import pytest
from layout_probes import faces_at, laid_out, node_at

from vaultgram.domain import domain_from_dict
from vaultgram.meshing.quality import mesh_stats
from vaultgram.meshpipeline import decompose
from vaultgram.testing.jagged import jagged_plans
from vaultgram.topology import reflex
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.reflex_fallbacks import OUTER_MIN_ANGLE, OUTER_MIN_QUAD_ANGLE, turns_past_straight, wide_quads
from vaultgram.topology.strips import patch_sides
from vaultgram.topology.types import PATCH_CORNER

from paths import ARCHITECTURE

PLANS = jagged_plans()


@pytest.fixture(scope="module")
def laid():
    """jagged_2 and jagged_3 laid out and meshed (:func:`layout_probes.laid_out`), once."""
    return {name: laid_out(PLANS[name], 0.02) for name in ("jagged_2", "jagged_3")}


@pytest.mark.parametrize(("name", "corner", "angle"), [
    ("jagged_2", (-6.372, -20.873), 227.36),
    ("jagged_3", (11.145, 12.955), 306.0),
])
def test_fallback_corner_is_regular(laid, name, corner, angle):
    """The corner is now the corner of three patches (a chord split one of its quads) and has three
    faces in the mesh: valence 4, regular for its angle (main: two patches, two faces)."""
    _, dec, mesh = laid[name]
    r = node_at(dec.graph, corner, 1e-6)
    assert boundary_angle(dec.graph, r) == pytest.approx(angle, abs=0.01)
    assert dec.graph.degree(r, [PATCH_CORNER]) == 3
    assert faces_at(mesh, corner, 1e-6) == 3


@pytest.mark.parametrize(("name", "most", "least"), [("jagged_2", 8, 0.198), ("jagged_3", 8, 0.27)])
def test_fewer_boundary_singular_worst_face_no_lower(laid, name, most, least):
    """jagged_2 and jagged_3 have one boundary singular vertex fewer than on main (9 each), no inverted
    face, and a worst scaled Jacobian no lower than main's (0.198 and 0.2445; now 0.198 and 0.277)."""
    domain, _, mesh = laid[name]
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] <= most, stats["boundary_singular_angles"]
    assert stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] >= least, stats["min_scaled_jacobian"]


def test_no_fallback_beside_a_patch_past_straight(monkeypatch):
    """jagged_1's 299 degree corner at (5.769, 13.166) is the corner of a 112 and a 187 degree quad: no
    chord in the 112 degree quad may be taken (the 187 degree one would keep one face across more than
    180 degrees at a corner with one face more: the fold main's sessions 20-21 saw), and the 187 degree
    quad has none of 35 degrees, so the 35 degree fallback leaves the corner as it is. The layout is laid
    out without the second fallback (``point_quads``, session 30), which splits the 187 degree quad by a
    chord to a boundary point instead (tests/topology/test_jagged_reflex2.py), nor the third
    (``any_point_quads``, session 33), which would take the same chord in any quad."""
    monkeypatch.setattr(reflex, "point_quads", lambda *args: [])
    monkeypatch.setattr(reflex, "any_point_quads", lambda *args: [])
    dec = decompose(domain_from_dict(PLANS["jagged_1"], "jagged_1"))
    g = dec.graph
    r = node_at(g, (5.769, 13.166), 1e-6)
    patches = sorted({g.ends(e)[0] for e in g.incident(r, [PATCH_CORNER])})
    found = [patch_sides(g, p) for p in patches]
    angles = [reflex.patch_corner(g, s, s.corners.index(r))[2] for s in found]
    assert len(patches) == 2 and max(angles) > reflex.PAST_STRAIGHT, angles
    narrow = [i for i, a in enumerate(angles) if a < reflex.PAST_STRAIGHT]
    limit = reflex.PAST_STRAIGHT
    assert all(turns_past_straight(angles, i, pole, limit) for i in narrow for pole in (30.0, 60.0, 80.0))
    assert reflex.widest_chord(g, (r, patches, found, angles), list(range(len(patches))), OUTER_MIN_ANGLE,
                               every_foot=True, keep=lambda i, pole, kind: i not in narrow) is None
    assert reflex.choose_chord(g, r) is None
    monkeypatch.undo()
    turned = patches[angles.index(max(angles))]
    assert reflex.choose_chord(g, r)[:2] == (turned, "point")


def test_fallback_limits():
    """The fallback's angle lies between the middle's limit and a foot off the middle's; its turn test
    counts the other patches' angles and both parts of the split one."""
    assert reflex.MIN_ANGLE < OUTER_MIN_ANGLE < reflex.MIN_CUT_ANGLE
    limit = reflex.PAST_STRAIGHT
    assert not turns_past_straight([150.0, 120.0], 0, 75.0, limit)
    assert turns_past_straight([150.0, 120.0, 190.0], 1, 60.0, limit)
    assert turns_past_straight([200.0, 90.0], 0, 10.0, limit)


def test_no_fallback_in_a_narrow_quad_at_multiple_lobes_notches():
    """multiple_lobes' notch corners at (20.178, 14.056) and (10.054, 15.967) (the corners of two quads of
    106/127 and 114/111 degrees) have chords of 39 and 35 degrees in their 106 and 114 degree quads: taken,
    the mesh went from 1080 faces to 1209-1600 and its worst face from 0.407 to 0.365-0.380. The fallback
    splits only quads of ``OUTER_MIN_QUAD_ANGLE`` (135) or more, so the layout stays main's: 8 patches,
    both corners the corners of two."""
    path = ARCHITECTURE / "multiple_lobes.json"
    if not path.is_file():
        pytest.skip("the shared plans are not beside the repository")
    plan = json.loads(path.read_text())
    dec = decompose(domain_from_dict(plan))
    g = dec.graph
    assert len(dec.patches) == 8
    for corner in ((20.178, 14.056), (10.054, 15.967)):
        r = min((n for n in g.nodes() if g.schema.is_subtype(g.node_type(n), "BoundaryVertex")),
                key=lambda n: math.dist(g.get(n, "pos"), corner))
        assert math.dist(g.get(r, "pos"), corner) < 1e-3
        patches = sorted({g.ends(e)[0] for e in g.incident(r, [PATCH_CORNER])})
        angles = [reflex.patch_corner(g, s, s.corners.index(r))[2] for s in (patch_sides(g, p) for p in patches)]
        assert len(patches) == 2 and max(angles) < OUTER_MIN_QUAD_ANGLE, angles
        assert wide_quads(angles, [0, 1]) == []
        assert reflex.choose_chord(g, r) is None
