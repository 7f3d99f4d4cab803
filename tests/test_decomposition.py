"""Topology finding end to end (paper §3.1): skeleton -> typed graph -> rulebook -> 3/4-sided patches."""

from __future__ import annotations

import json
import shutil
from collections import Counter

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.errors import DomainError, RuleError
from vaultgram.pipeline import decompose
from vaultgram.topology.rulebook import default_rules_dir

from paths import ARCHITECTURE_PLANS, EXAMPLES

SPACINGS = [0.01, 0.0125, 0.015, 0.0175, 0.02, 0.025, 0.03, 0.035, 0.04, 0.045, 0.05]


def tiling_error(dec) -> float:
    """Relative difference between the patches' total area and the discretised domain's area."""
    disc = dec.disc
    rings = [disc.points[r] for r in disc.rings]
    domain = shapely.Polygon(rings[0], rings[1:])
    return abs(sum(p.area() for p in dec.patches) - domain.area) / domain.area


@pytest.mark.parametrize("spacing", SPACINGS)
def test_quad_with_hole_has_twelve_quads_and_four_valence_five_singularities(spacing):
    dec = decompose(load_domain(EXAMPLES / "quad_with_hole.json"), spacing)
    assert [p.n_sides for p in dec.patches] == [4] * 12
    singular = dec.singularities()
    assert len(singular) == 4
    assert [dec.valence(s) for s in singular] == [5, 5, 5, 5]
    for s in singular:  # on the square's diagonals
        x, y = dec.graph.get(s, "pos")
        assert min(abs(x - y), abs(x + y - 10)) < 0.5
    assert tiling_error(dec) < 1e-9


@pytest.mark.parametrize("spacing", [0.01, 0.02, 0.03, 0.05])
def test_l_shape_has_nine_quads_and_one_valence_five_vertex(spacing):
    dec = decompose(load_domain(EXAMPLES / "l_shape.json"), spacing)
    g = dec.graph
    assert [p.n_sides for p in dec.patches] == [4] * 9
    interior = [n for n in g.nodes() if g.node_type(n) in ("Singularity", "LoopVertex")]
    irregular = [dec.valence(n) for n in interior if dec.valence(n) != 4]
    assert irregular == [5]
    # the reflex corner (5, 5) gets no branch of its own: two boundary pieces and one rebranch, the
    # layout of the published implementation (reference/peer_decomposition/Lshape_h0.25.json)
    (reflex,) = [n for n in g.nodes() if g.node_type(n) != "Patch" and np.allclose(g.get(n, "pos"), (5, 5))]
    assert g.node_type(reflex) == "BoundaryVertex" and dec.valence(reflex) == 3
    corners = sorted(tuple(g.get(n, "pos")) for n in g.nodes() if g.node_type(n) == "Corner")
    assert corners == [(0, 0), (0, 10), (5, 10), (10, 0), (10, 5)]
    assert tiling_error(dec) < 1e-9


def test_patches_have_ordered_corners_and_connected_sides():
    dec = decompose(load_domain(EXAMPLES / "quad_with_hole.json"), 0.02)
    g = dec.graph
    for p in dec.patches:
        assert p.area() > 0  # counter-clockwise
        for i, side in enumerate(p.sides):
            assert np.allclose(side[0], g.get(p.corners[i], "pos"))
            assert np.allclose(side[-1], g.get(p.corners[(i + 1) % p.n_sides], "pos"))


def test_shared_sides_are_traversed_once_each_way():
    dec = decompose(load_domain(EXAMPLES / "l_shape.json"), 0.02)
    uses = Counter(he for p in dec.patches for side in p.side_edges for he in side)
    assert max(uses.values()) == 1
    interior_edges = {e for (e, _) in uses if dec.graph.edge_type(e) != "Boundary"}
    for e in interior_edges:
        u, v = dec.graph.ends(e)
        assert uses[(e, u)] == uses[(e, v)] == 1


@pytest.mark.parametrize("path", ARCHITECTURE_PLANS, ids=lambda p: p.stem)
def test_architecture_plans_decompose_into_three_and_four_sided_patches(path):
    dec = decompose(load_domain(path), 0.02)
    assert dec.patches
    assert {p.n_sides for p in dec.patches} <= {3, 4}
    assert tiling_error(dec) < 1e-9


def test_rules_drive_the_result(tmp_path):
    """A rulebook copy without pruning keeps the corner branches: each corner patch splits in two."""
    rules = tmp_path / "rules"
    shutil.copytree(default_rules_dir(), rules, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
    text = (rules / "topology.vgr").read_text()
    (rules / "topology.vgr").write_text(text.replace("  prune_corner_branch all\n", ""))
    domain = load_domain(EXAMPLES / "quad_with_hole.json")
    pruned, unpruned = decompose(domain, 0.02), decompose(domain, 0.02, rules_dir=rules)

    def corner_branches(dec):
        g = dec.graph
        return [e for e in g.edges() if g.edge_type(e) == "Branch" and "Corner" in {g.node_type(n) for n in g.ends(e)}]

    assert corner_branches(pruned) == [] and len(corner_branches(unpruned)) == 4
    assert Counter(p.n_sides for p in pruned.patches) == {4: 12}
    assert Counter(p.n_sides for p in unpruned.patches) == {4: 8, 3: 8}
    assert [unpruned.valence(s) for s in unpruned.singularities()] == [6, 6, 6, 6]


def test_decomposition_is_deterministic():
    domain = load_domain(EXAMPLES / "quad_with_hole.json")
    a, b = decompose(domain, 0.02), decompose(domain, 0.02)
    assert a.to_json() == b.to_json() and a.patches_json() == b.patches_json()


@st.composite
def polygons_with_holes(draw):
    """A random star-shaped outer ring with 0 to 3 random convex-ish holes placed inside it."""
    n = draw(st.integers(4, 9))
    radii = draw(st.lists(st.floats(6.0, 10.0), min_size=n, max_size=n))
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False) + draw(st.floats(0, 0.3))
    outer = np.c_[np.cos(angles) * radii, np.sin(angles) * radii]
    holes = []
    for _ in range(draw(st.integers(0, 3))):
        cx, cy = draw(st.floats(-4, 4)), draw(st.floats(-4, 4))
        r = draw(st.floats(0.4, 1.5))
        k = draw(st.integers(3, 12))
        t = np.linspace(0, 2 * np.pi, k, endpoint=False)
        hole = np.c_[cx + r * np.cos(t), cy + r * np.sin(t)]
        poly = shapely.Polygon(hole)
        if shapely.Polygon(outer).buffer(-0.5).contains(poly) and all(
            shapely.Polygon(h).distance(poly) > 0.5 for h in holes
        ):
            holes.append(hole)
    return {"name": "random", "outer": outer.tolist(), "holes": [h.tolist() for h in holes]}


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(polygons_with_holes(), st.floats(0.01, 0.05))
def test_random_domains_decompose_or_fail_clearly(data, spacing):
    domain = domain_from_dict(data)
    try:
        dec = decompose(domain, spacing)
    except DomainError as exc:
        assert str(exc)  # a documented, clear error
        return
    assert {p.n_sides for p in dec.patches} <= {3, 4}
    assert all(p.area() > 0 for p in dec.patches)
    assert tiling_error(dec) < 1e-9


def test_rulebook_without_pipeline_types_is_a_clear_error(tmp_path):
    (tmp_path / "topology.vgr").write_text("schema s { node Point { pos: vec2 } }\n")
    with pytest.raises(RuleError, match="lacks the type"):  # a fault of the rulebook, not of the domain
        decompose(load_domain(EXAMPLES / "l_shape.json"), 0.02, rules_dir=tmp_path)


def test_boundary_point_features_split_their_quads_into_triangles():
    """Paper Figure 4/5: a quad with a corner labelled as a feature point is split by the diagonal."""
    data = json.loads((EXAMPLES / "quad_with_hole.json").read_text())
    data["points"] = [[0, 0], [10, 0], [10, 10], [0, 10]]
    dec = decompose(domain_from_dict(data), 0.02)
    g = dec.graph
    assert Counter(p.n_sides for p in dec.patches) == {4: 8, 3: 8}
    features = [n for n in g.nodes() if g.node_type(n) == "Corner"]
    assert len(features) == 4 and all(g.get(n, "feature") for n in features)
    for f in features:
        (diagonal,) = g.incident(f, ["Diagonal"])
        assert g.node_type(g.other(diagonal, f)) == "Singularity"
        triangles = [p for p in dec.patches if f in p.corners]
        assert [p.n_sides for p in triangles] == [3, 3]
    assert len(dec.patch_nodes()) == len(dec.patches)
    assert tiling_error(dec) < 1e-9


def test_inner_point_feature_gets_a_fan_of_triangles():
    """Paper Figure 6 (and the published decomposition square10_point_2.5_7.5): 8 quads, 4 triangles."""
    dec = decompose(domain_from_dict({"outer": [[0, 0], [10, 0], [10, 10], [0, 10]], "points": [[2.5, 7.5]]}), 0.02)
    g = dec.graph
    (feature,) = [n for n in g.nodes() if g.node_type(n) == "FeaturePoint"]
    assert Counter(p.n_sides for p in dec.patches) == {4: 8, 3: 4}
    fan = [p for p in dec.patches if feature in p.corners]
    assert len(fan) == 4 and all(p.n_sides == 3 for p in fan)
    assert [dec.valence(s) for s in dec.singularities()] == [5, 5, 5, 5]


def test_close_singularities_are_merged_by_the_rules():
    """A near-square kite: the discretisation splits the centre junction in two, 0.03 apart; the rule
    merge_close_singularities makes it one valence-4 junction of four quads."""
    dec = decompose(domain_from_dict({"outer": [[10, 0], [0, 10], [-11.25, 0], [0, -11.25]]}), 0.02)
    assert len(dec.skeleton.singularities()) == 2
    assert [dec.valence(s) for s in dec.singularities()] == [4]
    assert Counter(p.n_sides for p in dec.patches) == {4: 4}
    assert Counter(step["rule"] for step in dec.trace)["merge_close_singularities"] == 1
