"""A skeleton that is one branch between two corners (rule ``cut_lone_branch`` of rules/topology.vgr,
vaultgram.topology.lone_branch): a half disc, a lens, a D-shaped apse. Before, the branch left two
faces of two corners each and ``decompose`` refused the plan; now four quads, the two cut points of
the branch their only singular vertices (valence 3), none on the boundary."""

from __future__ import annotations

import math

import numpy as np
import pytest
from degenerate import assert_quads_round, nodes_of
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.domain import domain_from_dict
from vaultgram.pipeline import decompose
from vaultgram.testing.smooth import SMOOTH_PLANS, apse, lens
from vaultgram.topology.lone_branch import branch_cut, branch_piece


def cuts(dec) -> list[int]:
    return nodes_of(dec, "BranchCut")


def assert_cut_in_three(domain, min_quality: float = 0.3) -> None:
    """Four four-sided patches round two BranchCut nodes (the middle third of the branch and a
    rebranch to each side; :func:`assert_quads_round`)."""
    assert len(cuts(assert_quads_round(domain, "BranchCut", 4, min_quality=min_quality))) == 2


@pytest.mark.parametrize("plan", [SMOOTH_PLANS["half_disc"], SMOOTH_PLANS["apse"], SMOOTH_PLANS["lens"],
                                  {"outer": lens(1.0)}], ids=["half-disc", "apse", "lens", "fat-lens"])
def test_plans_whose_skeleton_is_one_branch_are_four_quads(plan):
    assert_cut_in_three(domain_from_dict({"name": "plan", **plan}), min_quality=0.7)


def test_the_cut_points_lie_on_the_branch_at_its_thirds_and_touch_both_sides():
    """On the half disc of radius 5 the medial axis is the parabola x = (25 - y^2) / 10: the cut points
    lie on it (within the discretisation), symmetric about the x axis, and each is linked to a point
    of the wall (x = 0) and one of the arc, both about as far from it as its distance to the wall."""
    dec = decompose(domain_from_dict({"name": "half-disc", "outer": apse()}), 0.03)
    g = dec.graph
    pos = np.array([g.get(n, "pos") for n in cuts(dec)])
    assert np.allclose(pos[:, 0], (25 - pos[:, 1] ** 2) / 10, atol=0.1)
    assert np.isclose(pos[0, 1], -pos[1, 1], atol=0.1) and np.isclose(pos[0, 0], pos[1, 0], atol=0.1)
    for n, p in zip(cuts(dec), pos):
        feet = np.array([g.get(g.other(e, n), "pos") for e in g.incident(n, ["Rebranch"])])
        on_wall = np.isclose(feet[:, 0], 0)
        assert on_wall.sum() == 1
        assert np.allclose(np.hypot(*(feet - p).T), p[0], rtol=0.08)


def test_branch_piece_is_the_part_between_two_fractions_of_the_length():
    """The helper behind the kept third, on a branch of the half disc: the piece between a third and
    two thirds of the length has a third of the length and starts and ends at the cut points."""
    dec = decompose(domain_from_dict({"name": "half-disc", "outer": apse()}), 0.03)
    g = dec.graph
    b = next(e for e in g.incident(cuts(dec)[0], ["Branch"]))
    whole = np.array(branch_piece(g, b, 0.0, 1.0))
    third = np.array(branch_piece(g, b, 1 / 3, 2 / 3))
    assert np.isclose(np.hypot(*np.diff(third, axis=0).T).sum(), np.hypot(*np.diff(whole, axis=0).T).sum() / 3)
    assert np.allclose([third[0], third[-1]], [branch_cut(g, b, 1 / 3), branch_cut(g, b, 2 / 3)])
    assert np.allclose([whole[0], whole[-1]], [g.get(n, "pos") for n in g.ends(b)])


@settings(max_examples=12, deadline=None)
@given(depth=st.one_of(st.just(0.0), st.floats(0.5, 8.0)), radius=st.floats(0.5, 40.0), turn=st.floats(0, 2 * math.pi),
       x=st.floats(-100, 100), y=st.floats(-100, 100), n=st.integers(16, 64))
def test_apses_of_any_depth_size_and_place_are_four_quads(depth, radius, turn, x, y, n):
    """A half circle in front of a straight wall, from a half disc (depth 0) to a deep apse (depth
    1.6 r: a long straight run on either side before the arc)."""
    assert_cut_in_three(domain_from_dict({"name": "apse", "outer": apse(depth * radius / 5, radius, n, turn, (x, y))}))


@pytest.mark.parametrize("extra", [{"points": [[2.0, 0.5]]}, {"curves": [[[1.0, -1.0], [2.0, 1.0]]]}],
                         ids=["point-feature", "curve"])
def test_a_plan_with_features_inside_is_not_cut_this_way(extra):
    """A feature inside changes the skeleton (a curve cuts it in pieces whose sides are not the ring
    alone): the rule asks featureless_plan() and leaves such a plan to the other rules."""
    dec = decompose(domain_from_dict({"name": "half-disc", "outer": apse(), **extra}), 0.03)
    assert not cuts(dec)
