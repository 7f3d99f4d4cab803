"""Corners of 135 to 225 degrees that are the corner of one patch only (issue 12, item 3: their
regular valence is 3, two faces): ``rules/patching.vgr``'s ``move_rebranch_to_lone_corner`` moves
the rebranch ending at the free smooth point beside such a corner onto it, with the geometry of
:func:`vaultgram.topology.reflex.rebranch_to_corner`; the quad becomes a triangle with its pole at
the corner, meshed as three quads (:mod:`vaultgram.meshing.splits`)."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.meshing.densities import group_counts
from vaultgram.meshing.layout import edge_groups
from vaultgram.meshing.quality import mesh_stats
from vaultgram.meshing.splits import split_patterns
from vaultgram.pipeline import decompose, mesh_decomposition, mesh_domain
from vaultgram.topology.corners import boundary_angle

from paths import ARCHITECTURE


def foot(turns=(47.0, 18.0, 39.0, 22.0, 37.0), step: float = 0.35, length: float = 8.0) -> list:
    """A strip 8 long ending in a rounded foot like the Armadillo's top one: five corners turning by
    ``turns`` degrees (interior angles 133, 162, 141, 158 and 143), ``step`` apart, between two legs
    splayed by 8.5 degrees each (smooth bends)."""
    heading, p = np.radians(8.5), np.array([length, 0.0])
    pts = [[0.0, 0.0], [length, 0.0]]
    p = p + np.array([np.cos(heading), np.sin(heading)])
    pts.append(p.tolist())
    for t in turns:
        heading += np.radians(t)
        p = p + step * np.array([np.cos(heading), np.sin(heading)])
        pts.append(p.tolist())
    return pts + [[0.0, float(p[1])]]


def assert_corner_of_a_quad_and_its_marked_triangle(dec, pos) -> int:
    """The plan point at ``pos`` is the corner of two patches, a quad and a triangle with it as the
    marked pole (a lone corner given its second patch); returns its node."""
    (b,) = [n for n in dec.graph.nodes() if dec.graph.node_type(n) != "Patch"
            and np.allclose(dec.graph.get(n, "pos"), pos, atol=1e-9)]
    at_b = [p for p in dec.patches if b in p.corners]
    assert sorted(p.n_sides for p in at_b) == [3, 4]
    (tri,) = [p for p in at_b if p.n_sides == 3]
    assert dec.marked_pole(tri) == b
    return b


def test_a_lone_143_degree_corner_gets_a_second_patch():
    """The foot's last corner (143 degrees) was the corner of one quad only (valence 2, regular 3)
    on main 0f466b5, the plan's one boundary singularity; the rebranch ending at its neighbour moves
    onto it: the corner of two patches, one of them a triangle with it as the marked pole, split
    into three quads, and no boundary singularity (min scaled Jacobian 0.602 -> 0.718)."""
    outer = foot()
    domain = domain_from_dict({"name": "foot", "outer": outer})
    dec = decompose(domain)
    b = assert_corner_of_a_quad_and_its_marked_triangle(dec, outer[6])
    layout = edge_groups(dec)
    (k,) = [i for i, p in enumerate(layout.patterns) if p.pole is not None and p.corners[p.pole] == b]
    assert k in split_patterns(layout, group_counts(layout))
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= 0.7


def test_no_rebranch_moves_where_it_would_leave_a_sliver():
    """A rebranch moved to a corner would split the patch's angle there into two of at least 30
    degrees (reflex.MIN_ANGLE) or not at all: at every corner of 135-225 degrees that is the
    corner of two patches, one a triangle with its pole there, both angles reach 30 degrees."""
    domain = domain_from_dict({"name": "foot", "outer": foot()})
    dec = decompose(domain)
    moved = [tri for tri in dec.patches if tri.n_sides == 3 and dec.marked_pole(tri) is not None
             and dec.graph.node_type(dec.marked_pole(tri)) == "Corner"]
    assert moved
    for tri in moved:
        pole = dec.marked_pole(tri)
        (quad,) = [p for p in dec.patches if pole in p.corners and p is not tri]
        for patch in (tri, quad):
            assert patch.corner_angles()[list(patch.corners).index(pole)] >= 30.0


#: Draw 268 of the 700 saved random plans (spacing 0.05): corners of 142, 150 and 141 degrees, each
#: the corner of one quad on main 0f466b5; its 141 degree corner's free neighbour comes before it
#: along the ring.
DRAW_268 = {"name": "draw 268", "outer": [[5.934141, 2.637454], [3.425586, 8.906739], [-2.637454, 5.934141],
                                          [-5.22598, 2.009943], [-4.813876, -2.139548], [-3.083416, -8.017078],
                                          [3.109803, -6.996904], [4.666743, -1.794857]],
            "points": [[0.0, -5.667016], [2.07857, 0.0]]}


def test_lone_corners_either_way_round():
    """Draw 268: three boundary singularities on main 0f466b5 (its 142, 150 and 141 degree corners
    with one face each); with move_rebranch_to_lone_corner one is left (141 degrees), which its
    _back twin takes (the rebranch's end before the corner along the ring): none left, the corners
    each the corner of two patches."""
    domain = domain_from_dict(DRAW_268)
    dec = decompose(domain, 0.05)
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    assert stats["inverted_faces"] == 0
    lone = [n for n in dec.graph.nodes() if dec.graph.node_type(n) == "Corner"
            and 135 <= boundary_angle(dec.graph, n) < 225]
    assert len(lone) >= 2  # the 150 degree one is a smooth point (meshpipeline._soft_runs_settled)
    assert all(sum(n in p.corners for p in dec.patches) == 2 for n in lone)


#: Boundary singularities of the shared plans' default meshes (issue 12's acceptance asks for 0 on
#: every one): multiple_lobes keeps the three corners of its right notch (233 and 237 degrees with
#: valence 3, and 136 degrees with valence 2) and the 226 degree notch between its left lobes.
SHARED_BOUNDARY_SINGULAR = {
    "armadillo_vault": 0, "armadillo_vault_plan": 0, "british_museum_map": 0, "hiroshi_senju_museum": 0,
    "mexico_airport": 0, "multiple_lobes": 4, "rolex_learning_centre": 0, "rv_lips_pattern": 0,
    "rv_pillow_pattern": 0, "rv_quad_pattern": 0, "rv_ring_pattern": 0, "rv_star_pattern": 0,
    "two_holes_five_points": 0,
}


@pytest.mark.parametrize("name", sorted(SHARED_BOUNDARY_SINGULAR))
def test_shared_plan_boundary_singularities(name):
    path = ARCHITECTURE / f"{name}.json"
    if not path.is_file():
        pytest.skip(f"{path} not found")
    domain = load_domain(path)
    stats = mesh_stats(mesh_domain(domain), domain)
    assert stats["boundary_singular"] == SHARED_BOUNDARY_SINGULAR[name], stats["boundary_singular_angles"]
    assert stats["inverted_faces"] == 0


#: Draw 34 of the 700 saved random plans (rounded; spacing 0.05): an octagon whose 148 degree corner
#: (the first) was the corner of one quad between two rebranches that end two boundary points away
#: on either side, not at its ring neighbours (main e95b500: its one boundary singularity).
OCTAGON_34 = [[6.635, 2.253], [2.672, 5.42], [-2.201, 6.483], [-5.282, 2.604], [-4.735, -1.608],
              [-2.605, -5.284], [2.253, -6.635], [8.938, -4.407]]


def test_a_lone_corner_two_points_from_the_rebranch_gets_a_second_patch():
    """The rebranch moves to the lone corner from the next patch corner along the ring, over the free
    smooth point between (reflex.smooth_boundary_side): the corner of a quad and of a triangle with
    it as the marked pole, no boundary singularity (main: 1, the 148 degree corner with one face),
    min scaled Jacobian 0.534 -> 0.718."""
    domain = domain_from_dict({"name": "octagon 34", "outer": OCTAGON_34})
    dec = decompose(domain, 0.05)
    assert_corner_of_a_quad_and_its_marked_triangle(dec, OCTAGON_34[0])
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= 0.7


def test_smooth_boundary_side_is_a_boundary_run_of_smooth_free_points():
    """reflex.smooth_boundary_side on every side of every patch of the octagon's decomposition
    before the patching rules' changes matter: true exactly where every half-edge is a boundary
    segment and every point inside the side has an angle of 135 to 225 degrees (no feature)."""
    from vaultgram.geometry.polygons import regular_valence
    from vaultgram.topology.reflex import smooth_boundary_side
    from vaultgram.topology.strips import patch_sides

    domain = domain_from_dict({"name": "octagon 34", "outer": OCTAGON_34})
    g = decompose(domain, 0.05).graph
    results = []
    for p in (n for n in g.nodes() if g.node_type(n) == "Patch"):
        for side in patch_sides(g, p).sides:
            on_boundary = all(g.edge_type(e) == "Boundary" for e, _ in side)
            smooth = all(regular_valence(boundary_angle(g, u)) == 3 for _, u in side[1:]) if on_boundary else False
            assert smooth_boundary_side(g, side) == smooth
            results.append(smooth)
    assert any(results) and not all(results)


def test_no_rebranch_moves_to_a_corner_beside_a_short_jog():
    """multiple_lobes' 136 degree corner: the next rebranch along the ring (1.5 away) would make a
    triangle whose sides at the corner, a 0.65 jog and a 4.9 long rebranch, are one edge group
    (ratio 7.5 > reflex.MAX_POLE_RATIO): its split raised the jog's group and the lobes' with it
    (2356 faces for 1080, min scaled Jacobian 0.336). The corner keeps its one quad."""
    path = ARCHITECTURE / "multiple_lobes.json"
    if not path.is_file():
        pytest.skip(f"{path} not found")
    domain = load_domain(path)
    dec = decompose(domain)
    jog = [n for n in dec.graph.nodes() if dec.graph.node_type(n) == "Corner"
           and 135 <= boundary_angle(dec.graph, n) < 137]
    assert jog and all(sum(n in p.corners for p in dec.patches) == 1 for n in jog)
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["faces"] < 1300 and stats["min_scaled_jacobian"] > 0.39
