"""A hole corner's strip of several patches may end in a pole's fan triangle where its last strip point
halves that triangle (:func:`vaultgram.topology.reflex.fan_foot`, stored on the triangle's side by
``rules/strips.vgr``' ``place_fan_foot`` and read by :func:`~vaultgram.topology.strips.strip_fraction`;
:func:`~vaultgram.topology.reflex.strip_fan`; issue 12 acceptance 3). Main 171d5a0 left the 252 degree
corner of saved random plan 256 (257: the same plan) the corner of two patches with two faces: the chord
to its quad's far side starts a strip across a quad into the fan triangle of the boundary feature
(3.85, 6.83), whose middle chord leaves 11.7 degrees of the triangle's 81 at the feature."""

from __future__ import annotations

import numpy as np
import pytest
from layout_probes import assert_regular_hole_corner, faces_at, laid_out, node_at

from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.meshing.quality import mesh_stats
from vaultgram.topology import reflex
from vaultgram.topology.types import DIAGONAL, PATCH_CORNER

#: Saved random plan 256 of the 700 (spacing 0.04): a nonagon with a pentagonal hole (252 degree
#: corners) and two point features, one on the outer boundary (:data:`POLE`).
DRAW_256 = {
    "outer": [[8.478490664009072, 0.6043145375638308], [6.979248188011332, 6.757915037448342],
              [0.7168808071572327, 6.909900641671641], [-5.052879331711044, 7.469548210688001],
              [-8.864688200359744, 2.5290322157988108], [-5.021491826107172, -2.243795855317247],
              [-3.728797069344071, -7.671292027250948], [1.9360083204556184, -7.720727894716769],
              [5.6442174093722945, -4.089196460837618]],
    "holes": [[[5.533412435073567, 0.0], [4.151439513993406, -1.90212254315547],
               [1.9153603561537287, -1.1755763824374694], [1.9153603561537282, 1.175576382437469],
               [4.151439513993405, 1.9021225431554702]]],
    "points": [[-2.7526470296213195e-23, -4.544258476828885], [3.848064497584282, 6.833907839559991]],
}
SPACING = 0.04
CORNER = (1.9153603561537282, 1.175576382437469)
POLE = (3.848064497584282, 6.833907839559991)


def _run():
    return laid_out(DRAW_256, SPACING)


@pytest.fixture(scope="module")
def fanned():
    return _run()


def test_the_hole_corner_gets_its_third_face(fanned):
    """The 252 degree corner is the corner of three patches with three faces (valence 4, regular): no
    boundary singular vertex is left (main 1), no inverted face, min scaled Jacobian main's 0.322 less 0.01."""
    assert_regular_hole_corner(fanned, CORNER, 252.0, 0.312)


def test_the_strip_halves_the_fan_triangle_evenly(fanned):
    """The strip's last chord runs from a strip point to the feature and splits the fan triangle's 81
    degrees there into two of at least MIN_CUT_ANGLE (40; the bisector: no foot of FEET reaches 40): the
    angles between the feature's consecutive diagonals round it are all at least that."""
    _, dec, _ = fanned
    g = dec.graph
    pole = node_at(g, POLE)
    pos = g.get(pole, "pos")
    ends = [g.other(e, pole) for e in g.incident(pole, [DIAGONAL])]
    assert any(g.node_type(n) == "StripPoint" for n in ends)
    turns = sorted(ccw_degrees(0.0, direction(pos, g.get(n, "pos"))) for n in ends)
    gaps = np.diff(turns)
    assert len(gaps) == 2 and gaps.min() >= reflex.MIN_CUT_ANGLE and gaps.sum() == pytest.approx(81.0, abs=0.5)


def test_with_middle_strip_points_the_corner_keeps_two_faces(monkeypatch):
    """With every fan foot at its edge's middle (main's strip points), the corner is the corner of two
    patches with two faces: main's one boundary singular vertex at 252 degrees."""
    monkeypatch.setattr(reflex, "_fan_foot", lambda graph, edge: 0.5)
    domain, dec, mesh = _run()
    assert dec.graph.degree(node_at(dec.graph, CORNER), [PATCH_CORNER]) == 2
    assert faces_at(mesh, CORNER) == 2
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 1 and stats["boundary_singular_angles"][0] == pytest.approx(252.0)
