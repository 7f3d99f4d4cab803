"""Hole corners inside a ring patch's side whose cut would end in a skewed fan triangle (issue 12,
item 2): the branch between the ring patch and the triangle goes, and a chord from the fan's pole
(a point feature) to the hole corner splits the two into two quads
(``rules/corners.vgr``'s ``rebranch_hole_side_to_fan_pole``, :mod:`vaultgram.topology.hole_sides`).

Since session 24 Figure 4 does not make these drawings' fan triangles: each is a crescent (its
outline turns back about the point by 100 to 111% of its angle there, :mod:`vaultgram.topology.fans`),
so the shipped rulebook leaves the quad whole and the point a pole of its other triangle. The
mechanism tests below draw the layouts as before (the check off, :func:`crescents_allowed`); what
the plans give with it is :func:`test_with_the_fan_check_the_plans_keep_their_pole_and_mesh`.
"""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.domain import domain_from_dict
from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology import fans, hole_fans, hole_hub, hole_sides, reflex, strips
from vaultgram.topology.corners import boundary_angle, graph_rings
from vaultgram.topology.types import DIAGONAL, PATCH_CORNER

#: Saved random plan 666 (a heptagonal hole, one boundary point feature, a short curve; spacing
#: 0.02): three hole corners lie inside one side of the ring patch round the hole, whose opposite
#: side is a long curved branch with one triangle of the point's fan beyond it; every cut's chord to
#: the point runs within a few degrees of a fan side (main d952b9c: 7 boundary singular vertices, min
#: scaled Jacobian 0.005).
DRAW_666 = {
    "outer": [[8.44032913756092, 0.5244097217112929], [3.6235483660660464, 3.4452717220532962],
              [1.0138051730526023, 8.97505952688488], [-5.281010423046002, 7.962029474625007],
              [-9.590934034542673, 2.830898151656286], [-4.583373988825642, -1.9981698823064398],
              [-2.2266693324805575, -4.476822945325245], [1.4986960392179698, -6.21608249005776],
              [8.04430574713432, -5.9404667364291965]],
    "holes": [[[3.513880688453521, -1.6283482775027731], [2.5849814811963236, -3.557227356631426],
               [0.49776390858007624, -4.033621147213533], [-1.1760546257358677, -2.698795408278419],
               [-1.1760546257358682, -0.5579011467271278], [0.4977639085800756, 0.7769245922079868],
               [2.5849814811963228, 0.30053080162587964]]],
    "points": [[-1.2953279895559258, -4.911637831508374]],
    "curves": [[[-2.55200477861334, 2.789084255379736], [-4.1201252164944595, 3.9605051872325836]]],
}
#: The hole corner of DRAW_666 that takes the chord to the point.
CORNER_666 = DRAW_666["holes"][0][2]
#: Saved random plan 86 (a hexagonal hole, one boundary point feature, a short curve; spacing 0.02):
#: two hole corners inside one side of the ring patch, a fan triangle of 93 degrees beyond whose
#: chords from the branch's feet to the point leave 6-9 degrees one side; the new quads' sides differ
#: by up to 3.66 (main d952b9c: 3 boundary singular vertices, min scaled Jacobian 0.341).
DRAW_86 = {
    "outer": [[5.084140743595536, 0.19088096383133663], [3.261968707599068, 4.420984307096025],
              [-2.3873090733694156, 8.905040115690245], [-4.735277081678834, 2.065265290177627],
              [-4.81753956724404, -2.5469258690821714], [-1.1007816840198248, -5.821813855929963],
              [5.371493976846313, -6.240188023767702]],
    "holes": [[[1.2827566439250484, 2.0523140414355154], [0.6413783219625243, 0.9414142009231541],
               [-0.6413783219625239, 0.9414142009231539], [-1.2827566439250484, 2.0523140414355154],
               [-0.6413783219625248, 3.1632138819478763], [0.6413783219625233, 3.1632138819478772]]],
    "points": [[0.7916002702140434, 6.381813703437926]],
    "curves": [[[-1.8531761125341228, -1.3456390938010869e-26], [-0.8849957773599809, -1.1456992792971836]]],
}
#: The hole corner of DRAW_86 that takes the chord to the point.
CORNER_86 = DRAW_86["holes"][0][5]


@pytest.fixture
def crescents_allowed(monkeypatch):
    """Figure 4 splits whatever fans it leaves (fan_clear always true), as before session 24."""
    monkeypatch.setattr(fans, "fan_parts_seen", lambda outline, at, path: True)


@pytest.mark.parametrize("plan, boundary_singular, min_sj", [(DRAW_86, 0, 0.33), (DRAW_666, 2, 0.29)],
                         ids=["86", "666"])
def test_with_the_fan_check_the_plans_keep_their_pole_and_mesh(plan, boundary_singular, min_sj):
    """Draws 86 and 666 with the shipped rulebook: no chord from a hole corner to the point (no skewed
    fan triangle to take out), the point is still a pole, the mesh has no fold, at most 0 and 2
    boundary singular vertices (2 and 3 with the crescent and the rebranch) and a worst face of at
    least 0.33 and 0.29 (0.36 and 0.29)."""
    domain = domain_from_dict(plan)
    dec = decompose(domain)
    assert not _rebranches(dec.graph)
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["inverted_faces"] == 0 and stats["feature_points_pole"] == stats["feature_points"] == 1
    assert stats["boundary_singular"] <= boundary_singular and stats["min_scaled_jacobian"] >= min_sj


def _node_at(graph, at) -> int:
    (n,) = [n for n in graph.nodes() if graph.node_type(n) != "Patch"
            and np.allclose(graph.get(n, "pos"), at, atol=1e-9)]
    return n


def _rebranches(graph) -> list[tuple[int, int]]:
    """The chords of the layout from a hole corner to a point feature: ``(corner, feature)``."""
    hole = {n for ring in graph_rings(graph)[1][1:] for n in ring}
    return [(r, f) for e in graph.edges() if graph.edge_type(e) == DIAGONAL
            for r, f in (graph.ends(e), graph.ends(e)[::-1]) if r in hole and reflex.is_feature(graph, f)]


def _rebranched(plan: dict, corner) -> tuple:
    """Decompose ``plan``, check that its one hole-corner-to-feature chord joins ``corner`` to the
    plan's first point feature, and mesh it: the layout graph, the corner's node and the mesh's stats."""
    domain = domain_from_dict(plan)
    dec = decompose(domain)
    g = dec.graph
    r, f = _node_at(g, corner), _node_at(g, plan["points"][0])
    assert _rebranches(g) == [(r, f)]
    return g, r, mesh_stats(mesh_decomposition(dec), domain)


def test_a_hole_corner_takes_the_chord_to_the_fan_pole_and_then_its_third_patch(crescents_allowed):
    """Draw 86: the hole corner (0.641, 3.163) is joined to the point feature by a chord and, with the
    chord rules' split after it, is the corner of three patches (main: of none, two faces); 2
    boundary singular vertices (main 3), no fold, min scaled Jacobian at least 0.36 (main 0.341)."""
    g, r, stats = _rebranched(DRAW_86, CORNER_86)
    assert g.degree(r, [PATCH_CORNER]) == 3
    assert stats["inverted_faces"] == 0 and stats["boundary_singular"] <= 2, stats["boundary_singular_angles"]
    assert stats["min_scaled_jacobian"] >= 0.36


def test_the_rebranch_takes_a_skewed_fan_triangle_out_of_the_mesh(crescents_allowed):
    """Draw 666: of three hole corners inside one side, one (0.498, -4.034) is joined to the point
    feature and becomes a patch corner (of two: no chord of its quads qualifies after); the fan
    triangle whose sliver of a face was the mesh's worst is gone: 3 boundary singular vertices (main
    7), no fold, min scaled Jacobian at least 0.29 (main 0.005)."""
    g, r, stats = _rebranched(DRAW_666, CORNER_666)
    assert g.degree(r, [PATCH_CORNER]) == 2
    assert stats["inverted_faces"] == 0 and stats["boundary_singular"] <= 3, stats["boundary_singular_angles"]
    assert stats["min_scaled_jacobian"] >= 0.29


@pytest.mark.parametrize("plan", [DRAW_86, DRAW_666], ids=["86", "666"])
def test_the_chord_to_the_pole_leaves_no_narrow_angle_at_the_corner_or_the_pole(plan, crescents_allowed):
    """Draws 86 and 666: the chord from the hole corner to the point splits the corner's angle (from the
    boundary leaving it, as its interior angle is measured) into two of at least reflex.MIN_CUT_ANGLE,
    and each patch with the chord as a side has at least hole_sides.MIN_POLE_PART degrees at the
    point (the fan triangle's angle there, now two quads' corners)."""
    dec = decompose(domain_from_dict(plan))
    g = dec.graph
    ((r, f),) = _rebranches(g)
    pos, at = g.get(r, "pos"), g.get(f, "pos")
    first = ccw_degrees(reflex.boundary_ahead(g, r), direction(pos, at))
    assert min(first, boundary_angle(g, r) - first) >= reflex.MIN_CUT_ANGLE
    beside = [p for p in dec.patches if r in p.corners and f in p.corners]
    assert len(beside) == 2 and all(p.n_sides in (3, 4) for p in beside)
    for p in beside:
        assert p.corner_angles()[list(p.corners).index(f)] >= hole_sides.MIN_POLE_PART


def test_without_the_rebranch_the_corner_stays_inside_a_side(monkeypatch, crescents_allowed):
    """Draw 666 with the rebranch turned off (hole_sides.choose_rebranch refuses every corner): the corner is
    the corner of no patch, as on main, and no chord joins a hole corner to the point. The cut to the
    bisecting foot (reflex.bisecting_foot, session 25), the fallback after the rebranch, is off too:
    it would cut the corner (the corner of two patches, 7 boundary singular vertices and a worst face
    of 0.014 where the rebranch gives 3 and 0.301), and so is the hub split after it (hole_hub,
    session 26)."""
    monkeypatch.setattr(hole_sides, "choose_rebranch", lambda graph, r: None)
    monkeypatch.setattr(reflex, "bisecting_foot", lambda graph, walk: ())
    monkeypatch.setattr(hole_hub, "_best_hub", lambda *args: None)
    g = decompose(domain_from_dict(DRAW_666)).graph
    assert g.degree(_node_at(g, CORNER_666), [PATCH_CORNER]) == 0 and not _rebranches(g)



#: Saved random plan 665 (666's outline and hole, two boundary point features; spacing 0.02): the
#: cuts of the hole corners (2.585, -3.557) and (-1.176, -2.699) run to a curved branch with one
#: triangle of the point (-1.012, -5.044)'s fan beyond; the chord from the branch's middle to the
#: point leaves the triangle, so the strip walk refused the cut whatever its foot (main d952b9c: 3
#: boundary singular vertices, min scaled Jacobian 0.301).
DRAW_665 = {
    "outer": DRAW_666["outer"],
    "holes": DRAW_666["holes"],
    "points": [[-1.011735208765991, -5.044038657090011], [8.272444227521358, -2.216224364125512]],
    "curves": DRAW_666["curves"],
}


def test_a_cut_may_end_in_a_fan_triangle_whose_middle_chord_leaves_it(crescents_allowed):
    """Draw 665: the cut of the hole corner (-1.176, -2.699) takes a foot off the middle of the
    curved branch, whose chord to the point runs inside the fan triangle (reflex.cut_walk): the corner
    is the corner of two patches or more (main d952b9c: of none; with the hole chords' last fallback,
    reflex.hole_chord, it takes its third and the hole corner beside it keeps two); 2 boundary
    singular vertices (main 3), no fold, min scaled Jacobian at least 0.3 (main 0.301)."""
    domain = domain_from_dict(DRAW_665)
    dec = decompose(domain)
    assert dec.graph.degree(_node_at(dec.graph, DRAW_665["holes"][0][3]), [PATCH_CORNER]) >= 2
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["inverted_faces"] == 0 and stats["boundary_singular"] <= 2, stats["boundary_singular_angles"]
    assert stats["min_scaled_jacobian"] >= 0.3


def test_the_fan_walk_is_the_triangle_beyond_whose_middle_chord_leaves_it(monkeypatch, crescents_allowed):
    """Draw 665's hole corner (2.585, -3.557), still inside a side: the strip walk from the middle of
    the side opposite refuses it (reflex.strip_beyond is None), reflex.cut_walk gives the one triangle
    beyond, ending at the point feature opposite the side, and the chord from the middle to the point
    leaves that triangle while one from a foot of reflex.FEET runs inside it. The merge of that triangle
    with its fan neighbour (session 31, hole_fans, the cuts' last fallback) is off: with crescents
    allowed it takes the corner, which is then inside no side."""
    monkeypatch.setattr(hole_fans, "_pair", lambda *args: None)
    g = decompose(domain_from_dict(DRAW_665)).graph
    r, f = _node_at(g, DRAW_665["holes"][0][1]), _node_at(g, DRAW_665["points"][0])
    patch, i = reflex.on_side(g, r)
    found = strips.patch_sides(g, patch)
    edge = strips.side_edge(g, patch, found.corners[(i + 2) % 4])
    assert reflex.strip_beyond(g, patch, edge, fans=True) is None
    walk = reflex.cut_walk(g, patch, edge)
    triangle = strips.patch_sides(g, walk.patches[0])
    assert walk.edges == (edge,) and walk.end == f and len(triangle.corners) == 3
    inside = [strips.chord_inside(triangle, strips.edge_cut(g, edge, t)[1], g.get(f, "pos")) for t in reflex.FEET]
    assert not inside[0] and any(inside)
