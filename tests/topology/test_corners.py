"""Reflex corners of rectilinear plans (rules/corners.vgr, vaultgram.topology.corners): each reflex
corner gets branches of its own (its sides' extensions to the boundary), and the plan meshes as a
structured grid without any singular vertex, inside or on the boundary."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings

from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology.corners import boundary_angle, chord_feet, ray_hit, rectilinear_rings

from paths import ARCHITECTURE, EXAMPLES
from strategies.domains import RECTILINEAR_PLANS, orthogonal_domains

PLANS = RECTILINEAR_PLANS


def no_singular_vertex(domain) -> None:
    """The plan's patches are all four-sided and its mesh has no singular vertex at all."""
    dec = decompose(domain, 0.02)
    assert {p.n_sides for p in dec.patches} == {4}
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["interior_singular"] == 0, stats["interior_singular_vertices"]
    assert stats["boundary_singular"] == 0, list(zip(stats["boundary_singular_angles"],
                                                     stats["boundary_singular_valences"]))
    assert stats["triangles"] == 0 and stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.9


@pytest.mark.parametrize("name", sorted(PLANS))
def test_rectilinear_plans_mesh_without_singular_vertices(name):
    no_singular_vertex(domain_from_dict({"name": name, **PLANS[name]}))


def test_each_reflex_corner_is_the_corner_of_three_patches():
    """The L's reflex corner (5, 5) has both its chords, to (5, 0) and (0, 5): three rectangles."""
    dec = decompose(domain_from_dict(PLANS["L"]), 0.05)
    corners = sorted(sorted(tuple(np.round(dec.graph.get(c, "pos"), 9)) for c in p.corners) for p in dec.patches)
    assert corners == [[(0, 0), (0, 5), (5, 0), (5, 5)], [(0, 5), (0, 10), (5, 5), (5, 10)],
                       [(5, 0), (5, 5), (10, 0), (10, 5)]]


def test_the_l_shape_example_is_three_rectangles():
    dec = decompose(load_domain(EXAMPLES / "l_shape.json"), 0.02)
    assert len(dec.patches) == 3 and not dec.singularities()


def test_chords_cross_at_regular_interior_vertices():
    """In the courtyard block the chord up from the court's corner (15, 8) crosses the one to the
    right from its corner (9, 12), at (15, 12): the corner of four patches, valence 4."""
    dec = decompose(domain_from_dict(PLANS["courtyard"]), 0.02)
    g = dec.graph
    crossings = [n for n in g.nodes() if g.node_type(n) == "ChordCrossing"]
    assert [tuple(np.round(g.get(n, "pos"), 9)) for n in crossings] == [(15, 12)]
    assert [dec.valence(n) for n in crossings] == [4]


def test_chord_feet_are_where_the_side_extensions_meet_the_boundary():
    feet = sorted(tuple(f) for f in chord_feet([np.array(PLANS["L"]["outer"], dtype=float)]))
    assert feet == [(0.0, 5.0), (5.0, 0.0)]
    assert chord_feet([np.array([[0, 0], [4, 0], [2, 3.0]])]) == []  # not rectilinear: no chords
    # the ray from the inside of a square leaves it on the side it points to
    assert ray_hit([np.array([[0, 0], [4, 0], [4, 4], [0, 4.0]])], np.array([1.0, 1.0]), np.array([0, -1.0])).tolist() \
        == [1.0, 0.0]


def test_plans_with_other_angles_or_features_keep_the_medial_axis():
    """A 100 degree corner, or a point feature, and the chords' rules do not apply."""
    assert not rectilinear_rings([np.array([[0, 0], [10, 0], [10, 5], [5, 5], [5, 10], [-1, 10.0]])])
    with_point = domain_from_dict({**PLANS["L"], "points": [[2.0, 2.0]]})
    dec = decompose(with_point, 0.05)
    assert dec.singularities() and not [n for n in dec.graph.nodes() if dec.graph.node_type(n) == "ChordEnd"]


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(orthogonal_domains())
def test_random_orthogonal_plans_mesh_without_singular_vertices(data):
    """Random polyomino outlines of 8-40 corners with 0-2 rectangular or L-shaped holes."""
    no_singular_vertex(domain_from_dict(data))


def neck_plan(width: float, length: float) -> dict:
    """A rectangular room, a passage ``width`` wide and ``length`` long, and a trapezoidal hall: not
    rectilinear, so the medial axis stays, and its branch through the passage meets four reflex corners."""
    x0, x1, y0, y1 = 3.0, 3.0 + length, 2 - width / 2, 2 + width / 2
    return {"outer": [[0, 0], [x0, 0], [x0, y0], [x1, y0], [x1, -1], [9, -2], [9, 6], [x1, 5], [x1, y1], [x0, y1],
                      [x0, 4], [0, 4]]}


@pytest.mark.parametrize("width, length", [(0.4, 0.3), (0.5, 1.0), (0.3, 2.0)])
def test_a_neck_is_one_quad_between_its_four_reflex_corners(width, length):
    """rules/patching.vgr, cut_neck: the branch through the passage goes, two chords across its ends
    make it one quad whose corners are the four reflex corners, each then the corner of three patches
    (valence 4, regular at 270 degrees; 4 boundary singularities and a worst scaled Jacobian of 0.16
    to 0.19 before)."""
    domain = domain_from_dict(neck_plan(width, length))
    dec = decompose(domain)
    x0, x1, y0, y1 = 3.0, 3.0 + length, 2 - width / 2, 2 + width / 2
    reflex = sorted([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
    patches = [sorted(tuple(np.round(dec.graph.get(c, "pos"), 9)) for c in p.corners) for p in dec.patches]
    assert reflex in patches
    assert [sum(r in p for p in patches) for r in reflex] == [3, 3, 3, 3]
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_vertices"]
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= 0.3


def test_the_hiroshi_senju_museum_doorway_has_no_boundary_singularity():
    """The plan's doorway (4.3-4.6, 10.4-10.8) between a room and the hall: its four reflex corners
    had valence 3."""
    path = ARCHITECTURE / "hiroshi_senju_museum.json"
    if not path.exists():
        pytest.skip("shared plans absent")
    domain = load_domain(path)
    stats = mesh_stats(mesh_decomposition(decompose(domain)), domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_vertices"]


def test_a_neck_between_two_rooms_whose_skeleton_ends_in_them_stays():
    """Two round rooms joined by a corridor (radii jittered by 3%): the skeleton vertex at either
    end of the corridor's branch has only that branch and two rebranches, so cut_neck leaves it (it
    would be the corner of a room's patch wrapped round it; 47 folded faces where base had 3). The
    only diagonals are split_lone_corner_quad's (s24-corners): from a room's lone 135-225 degree corner
    to the skeleton vertex opposite it (main b7eedca had none, and its mesh folded: 5 inverted faces;
    with them none)."""
    t = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    r = 3 * (1 + 0.03 * np.random.default_rng(1).standard_normal(24))
    rooms = [shapely.Polygon(np.c_[x + r * np.cos(t), k * r * np.sin(t)]) for x, k in ((0, 0.8), (8, 1.0))]
    plan = shapely.set_precision(shapely.union_all([*rooms, shapely.box(0, -0.5, 8, 0.5)]), 1e-6)
    domain = domain_from_dict({"outer": np.asarray(plan.exterior.coords)[:-1].tolist()})
    dec = decompose(domain)
    assert [step.applications for step in dec.reports if step.step.startswith("cut_neck")] == [0]
    g = dec.graph
    for e in (e for e in g.edges() if g.edge_type(e) == "Diagonal"):
        corner, skeleton = sorted(g.ends(e), key=lambda n: not g.schema.is_subtype(g.node_type(n), "BoundaryVertex"))
        assert g.schema.is_subtype(g.node_type(corner), "BoundaryVertex")
        assert g.schema.is_subtype(g.node_type(skeleton), "SkeletonVertex")
        assert 135 <= boundary_angle(g, corner) < 225
    assert mesh_stats(mesh_decomposition(dec), domain)["inverted_faces"] == 0


@pytest.mark.parametrize("width, length", [(1.0, 0.2), (1.5, 0.5)])
def test_a_wide_doorway_whose_corners_are_regular_stays(width, length):
    """A doorway as wide as it is deep or wider: the medial axis already gives two of its reflex
    corners three patches, and cut_neck, which would give them four, leaves it (2 boundary
    singularities where there were none)."""
    domain = domain_from_dict(neck_plan(width, length))
    stats = mesh_stats(mesh_decomposition(decompose(domain)), domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_vertices"]
