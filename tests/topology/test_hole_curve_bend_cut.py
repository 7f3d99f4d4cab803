"""A hole corner whose cut's strip ends in a triangle at a curve's bend that is short of patches on that
side: the strip may end there (issue 12, acceptance 3; reflex.curve_end, curve_points.short_side).
Plan 133 of session 32's 700 random plans (134 is the same plan): on main 18d7fb4 one of the last
boundary singular vertices of the 700."""

from __future__ import annotations

import pytest
from layout_probes import assert_the_one_singular_corner, assert_three_faces_and_regular, node_at

from vaultgram.domain import domain_from_dict
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology import reflex
from vaultgram.topology.curve_points import short_side
from vaultgram.topology.types import PATCH_CORNER

#: Random plan 133 of benchmarks/data/random_plans_700.json.gz (spacing 0.02): a pentagon with a regular
#: hexagonal hole and a V-shaped curve whose bend (-2.659, -2.822) points at the hole. On main 18d7fb4 the
#: hole's 240 degree corner (-0.943, -2.327) lies inside the hole side of the ring patch round the hole's
#: left; the patch's opposite side is a skeleton branch, and beyond it a triangle whose third corner is the
#: curve's bend (166.3 degrees there). Its cut's strip would end at the curve point, refused (a curve is a
#: cut the layout keeps), and no fallback applies (no point feature): 1 boundary singular vertex (two
#: faces), min scaled Jacobian 0.3236.
DRAW_133 = {
    "outer": [[6.64593649789066, 5.888080810575688e-301], [1.7274047311963219, 5.316405103241563],
              [-4.854101966249684, 3.5267115137548393], [-7.774894286575404, -5.648791349942929],
              [2.9257388840480405, -9.004498397508158]],
    "holes": [[[2.1432854127154815, -2.3266634154790062], [1.3716427063577408, -3.663187788180565],
               [-0.17164270635774037, -3.663187788180565], [-0.9432854127154814, -2.3266634154790062],
               [-0.17164270635774137, -0.9901390427774479], [1.3716427063577397, -0.9901390427774468]]],
    "points": [],
    "curves": [[[-4.158587105925516, -2.821635000090599], [-2.658587105925516, -2.821635000090599],
                [-4.163475103717143, -2.2811436307813944]]],
}
SPACING = 0.02
CORNER = (-0.9432854127154814, -2.3266634154790062)
BEND = (-2.658587105925516, -2.821635000090599)


def _angles_at(dec, n: int) -> list[float]:
    """The angles (degrees) of the patches with the corner ``n`` there."""
    return sorted(p.corner_angles()[list(p.corners).index(n)] for p in dec.patches if n in p.corners)


def test_the_cut_ends_at_the_curve_bend_and_the_corner_gets_three_faces():
    """The hole corner is the corner of three patches whose angles sum to its 240 degrees, each 30 to under
    180; the bend is the corner of five patches (four on its 340.2 degree side, as that side asks, one in
    the V), the triangle's 166.3 degrees halved into two of at least 40. In the mesh: no boundary
    singularity (main 1), three faces at the corner, no inverted face, min scaled Jacobian at least 0.32
    (main 0.3236, here 0.3236)."""
    domain = domain_from_dict(DRAW_133)
    dec = decompose(domain, SPACING)
    g = dec.graph
    r, bend = node_at(g, CORNER), node_at(g, BEND)
    assert g.degree(r, [PATCH_CORNER]) == 3
    angles = _angles_at(dec, r)
    assert sum(angles) == pytest.approx(240.0, abs=0.5) and all(30.0 <= a < 180.0 for a in angles), angles
    at_bend = _angles_at(dec, bend)
    assert len(at_bend) == 5 and sum(at_bend) == pytest.approx(360.0, abs=0.5), at_bend
    assert at_bend[0] == pytest.approx(19.8, abs=0.5) and min(at_bend[1:]) >= reflex.MIN_CUT_ANGLE, at_bend
    assert not any(short_side(g, bend, p) for p in {g.ends(e)[0] for e in g.incident(bend, [PATCH_CORNER])})
    assert_three_faces_and_regular(domain, mesh_decomposition(dec), CORNER, 0.32)


def test_without_the_curve_end_the_corner_keeps_two_faces(monkeypatch):
    """With a curve point never short of patches (main 18d7fb4's cut) the corner is the corner of no patch,
    the bend of four (three on its outer side: one short) and the corner the one boundary singular vertex
    (240 degrees, two faces), as on main."""
    monkeypatch.setattr(reflex, "short_side", lambda *args: False)
    domain = domain_from_dict(DRAW_133)
    dec = decompose(domain, SPACING)
    g = dec.graph
    r, bend = node_at(g, CORNER), node_at(g, BEND)
    assert g.degree(r, [PATCH_CORNER]) == 0
    assert len(_angles_at(dec, bend)) == 4
    assert any(short_side(g, bend, p) for p in {g.ends(e)[0] for e in g.incident(bend, [PATCH_CORNER])})
    assert_the_one_singular_corner(domain, dec, CORNER, 2, 240.0)
