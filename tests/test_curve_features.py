"""Curve features (paper §4.2): the cut, the T-junction repair and the extremity poles, by the rules."""

from __future__ import annotations

import shutil
from collections import Counter

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from vaultgram.domain import domain_from_dict
from vaultgram.errors import DomainError
from vaultgram.pipeline import decompose
from vaultgram.topology.functions import curve_side
from vaultgram.topology.rulebook import default_rules_dir

SQUARE = [[0, 0], [10, 0], [10, 10], [0, 10]]


def square_with(*curves):
    return domain_from_dict({"outer": SQUARE, "curves": [list(c) for c in curves]})


def plan_edges_at(dec, n):
    g = dec.graph
    return [e for e in g.incident(n) if g.edge_type(e) in ("Branch", "Rebranch", "Boundary", "Curve", "Diagonal")]


def assert_curve_is_clean(dec):
    """Curve edges follow every curve segment; no skeleton vertex lies on a curve; no T-junction left."""
    g, disc = dec.graph, dec.disc
    for curve in disc.curves:
        for a, b in zip(curve[:-1], curve[1:]):
            assert any(g.other(e, int(a)) == int(b) for e in g.incident(int(a), ["Curve"]))
        for p in curve[1:-1]:
            p = int(p)
            if len(plan_edges_at(dec, p)) > 2 and not g.get(p, "corner"):
                assert curve_side(g, p) == 0, f"T-junction left at curve point {p} {g.get(p, 'pos')}"
    if not disc.curves:
        return
    line = shapely.MultiLineString([disc.points[c] for c in disc.curves])
    for s in dec.singularities():
        assert shapely.distance(shapely.Point(g.get(s, "pos")), line) > 1e-6


def test_slit_makes_triangles_with_poles_at_its_extremities():
    dec = decompose(square_with([[3, 5], [7, 5]]), 0.02)
    g = dec.graph
    assert Counter(p.n_sides for p in dec.patches) == {4: 10, 3: 2}
    ends = [n for n in g.nodes() if g.node_type(n) == "CurveExtremity"]
    assert len(ends) == 2
    for x in ends:  # each extremity is the corner of a triangle (its pole, §4.2)
        assert any(p.n_sides == 3 and x in p.corners for p in dec.patches)
    assert [dec.valence(s) for s in dec.singularities()] == [5, 5, 5, 5]
    assert_curve_is_clean(dec)


def test_curve_attached_to_the_boundary():
    dec = decompose(square_with([[0, 5], [6, 5]]), 0.02)
    g = dec.graph
    (junction,) = [n for n in g.nodes() if g.node_type(n) == "Corner" and np.allclose(g.get(n, "pos"), (0, 5))]
    assert dec.valence(junction) == 3  # two boundary pieces and the curve
    assert {p.n_sides for p in dec.patches} <= {3, 4}
    assert_curve_is_clean(dec)


def test_bent_curve_needs_the_t_junction_repair():
    domain = square_with([[2, 2], [5, 5], [8, 3]])
    dec = decompose(domain, 0.02)
    fired = Counter(step["rule"] for step in dec.trace)
    assert fired["pair_t_junctions"] >= 1 and fired["spread_t_junction"] >= 1
    assert {p.n_sides for p in dec.patches} <= {3, 4}
    assert_curve_is_clean(dec)
    g = dec.graph
    (start,) = [n for n in g.nodes() if g.node_type(n) == "CurveExtremity" and np.allclose(g.get(n, "pos"), (2, 2))]
    assert all(p.n_sides == 3 for p in dec.patches if start in p.corners)  # Figure 8: a pole, no flat corner


def test_rules_drive_the_curve_repair(tmp_path):
    rules = tmp_path / "rules"
    shutil.copytree(default_rules_dir(), rules, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
    text = (rules / "curves.vgr").read_text()
    (rules / "curves.vgr").write_text(text.replace("  pair_t_junctions fixpoint\n", "").replace(
        "  spread_t_junction fixpoint\n", ""))
    with pytest.raises(DomainError, match="5 sides|6 sides"):
        decompose(square_with([[2, 2], [5, 5], [8, 3]]), 0.02, rules_dir=rules)


@st.composite
def squares_with_curves(draw):
    curves = []
    for _ in range(draw(st.integers(1, 2))):
        k = draw(st.integers(2, 3))
        pts = [(draw(st.floats(1.5, 8.5)), draw(st.floats(1.5, 8.5))) for _ in range(k)]
        line = shapely.LineString(pts)
        if line.length < 1.5 or not line.is_simple or any(line.distance(shapely.LineString(c)) < 1.0 for c in curves):
            continue
        curves.append(pts)
    return curves


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(squares_with_curves(), st.sampled_from([0.01, 0.02, 0.03]))
def test_random_curves_decompose_cleanly_or_fail_clearly(curves, spacing):
    assume(curves)
    try:
        dec = decompose(square_with(*curves), spacing)
    except DomainError as exc:
        assert str(exc)
        return
    assert {p.n_sides for p in dec.patches} <= {3, 4}
    assert_curve_is_clean(dec)
    area = sum(p.area() for p in dec.patches)
    assert abs(area - 100.0) < 1e-9 * 100


@pytest.mark.parametrize("name", ["fig5_boundary_points", "fig6_inner_points", "fig7_curves", "features_combined"])
def test_feature_examples_decompose(name):
    from vaultgram.domain import load_domain

    from paths import EXAMPLES

    dec = decompose(load_domain(EXAMPLES / f"{name}.json"), 0.02)
    g = dec.graph
    assert {p.n_sides for p in dec.patches} <= {3, 4}
    assert_curve_is_clean(dec)
    for n in g.nodes():  # every point feature and curve extremity is a corner of a triangle (its pole)
        if g.node_type(n) == "Patch":
            continue
        if g.get(n, "feature") or g.node_type(n) == "CurveExtremity":
            assert any(p.n_sides == 3 and n in p.corners for p in dec.patches), g.get(n, "pos")


def test_curve_tip_inside_a_patch_is_surrounded_by_triangles():
    """A slit whose tips no rebranch reaches (fig7_curves, top): the tip patches are split into triangles."""
    from vaultgram.domain import load_domain

    from paths import EXAMPLES

    dec = decompose(load_domain(EXAMPLES / "fig7_curves.json"), 0.02)
    fired = Counter(step["rule"] for step in dec.trace)
    assert fired["split_around_curve_tip"] >= 2
