"""A hole corner whose cut would end in a sliver of a point feature's fan: the sliver and the fan triangle
beside it become one quad, and the cut crosses it to the boundary (issue 12, item 2; hole_fans). Plan 406
of the 700 random plans saved in session 25: on main 8763e05 one of the last two boundary singular
vertices of the 700."""

from __future__ import annotations

import pytest
from layout_probes import assert_the_one_singular_corner, assert_three_faces_and_regular, node_at

from vaultgram.domain import domain_from_dict
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology import hole_fans
from vaultgram.topology.types import PATCH_CORNER

#: Saved random plan 406 (spacing 0.04): a hexagon with a pentagonal hole and three point features. On
#: main 8763e05 the hole's 252 degree corner (-1.516, 1.102) lies in the middle of the 4.41 long hole side
#: of the ring patch round the hole's left; the patch's opposite side is a skeleton branch wrapped round
#: the hole (9.6 long), and beyond it the triangle of the fan round the boundary feature (-4.130, -3.562)
#: is a sliver (42.0 degrees there, 3.2 at the skeleton vertex (1.111, 4.641)) that no foot halves; the
#: hub is far outside its limits: 1 boundary singular vertex, min scaled Jacobian 0.304.
DRAW_406 = {
    "outer": [[5.276444649579077, 1.552137835351077], [2.352784598546396, 9.719280047042727],
              [-4.015995679749851, 3.8254554140699057], [-5.276511762953571, -1.5521575776614243],
              [-1.8356621546573, -7.58306330460293], [7.240751127961012, -6.897211255495321]],
    "holes": [[[1.8744582567667432, 2.240961604328103e-250], [0.5792394565873624, -1.7827157396212652],
               [-1.5164685849707338, -1.1017789193653498], [-1.5164685849707342, 1.1017789193653493],
               [0.5792394565873621, 1.7827157396212654]]],
    "points": [[3.9607976266143705, 5.227351830612319], [-4.129561893521481, -3.562459486641926],
               [-0.5355880621117435, 7.046309526359876]],
}
SPACING = 0.04
CORNER = (-1.5164685849707342, 1.1017789193653493)
FEATURE = (-4.129561893521481, -3.562459486641926)


def _patches_at(dec, n: int) -> list:
    """``(number of sides, angle at n, whether n is the marked pole)`` of each patch with the corner ``n``."""
    out = []
    for p in dec.patches:
        if n in p.corners:
            k = list(p.corners).index(n)
            out.append((len(p.corners), p.corner_angles()[k], dec.marked_pole(p) == n))
    return sorted(out)


def test_the_fan_triangles_merge_and_the_cut_crosses_to_the_boundary():
    """The hole corner is the corner of three patches whose angles there sum to its 252 degrees, each 30 to
    under 180; the feature is the corner of one quad, with the two merged triangles' angles (41.5 + 42.0)
    as one corner of 30-165 degrees, and the pole of its two other fan triangles (its 180 degrees shared).
    In the mesh: no boundary singularity (main 1), three faces at the corner, no inverted face, min scaled
    Jacobian at least 0.339 (main 0.304, with the merge 0.344)."""
    domain = domain_from_dict(DRAW_406)
    dec = decompose(domain, SPACING)
    g = dec.graph
    r, f = node_at(g, CORNER), node_at(g, FEATURE)
    assert g.degree(r, [PATCH_CORNER]) == 3
    angles = [a for _, a, _ in _patches_at(dec, r)]
    assert sum(angles) == pytest.approx(252.0, abs=0.5) and all(30.0 <= a < 180.0 for a in angles), angles
    at_feature = _patches_at(dec, f)
    quads = [a for n, a, _ in at_feature if n == 4]
    assert len(quads) == 1 and quads[0] == pytest.approx(83.5, abs=1.0), at_feature
    assert hole_fans.MIN_QUAD_ANGLE <= quads[0] <= hole_fans.MAX_QUAD_ANGLE
    assert [pole for n, _, pole in at_feature if n == 3] == [True, True], at_feature
    assert sum(a for _, a, _ in at_feature) == pytest.approx(180.0, abs=0.5)
    assert_three_faces_and_regular(domain, mesh_decomposition(dec), CORNER, 0.339)


def test_without_the_merge_the_corner_keeps_two_faces(monkeypatch):
    """With the merge refused (main's layout) the hole corner is the corner of no patch, the feature the
    pole of four fan triangles, and the corner the one boundary singular vertex (two faces), as on main."""
    monkeypatch.setattr(hole_fans, "_pair", lambda *args: None)
    domain = domain_from_dict(DRAW_406)
    dec = decompose(domain, SPACING)
    g = dec.graph
    r, f = node_at(g, CORNER), node_at(g, FEATURE)
    assert g.degree(r, [PATCH_CORNER]) == 0
    assert [(n, pole) for n, _, pole in _patches_at(dec, f)] == [(3, True)] * 4
    assert_the_one_singular_corner(domain, dec, CORNER, 2, 252.0)
