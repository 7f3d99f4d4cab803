"""Figure 4's split of a quad at a point feature whose far corner lies on the boundary, where the boundary
side at that corner is the one arriving from the feature's neighbour (issue 12; rules/patching.vgr,
split_quad_at_feature_beside_boundary_back). split_quad_at_feature_beside_boundary draws the diagonal
to the boundary point after the far corner, along the side leaving it; where that side is a rebranch
and the boundary side arrives at the corner, no rule drew it to the point before, and
split_quad_at_feature drew it to the far corner itself: a rebranch's end on a straight stretch, the
corner of three patches (three faces at 180 degrees): the two outer boundary singular vertices of the
700 random plans saved in session 25 (plans 399 and 664, main b86dd39)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from vaultgram.domain import domain_from_dict
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology.rulebook import default_rules_dir
from vaultgram.topology.types import PATCH_CORNER

#: Saved random plan 664 (spacing 0.02): a quadrilateral with three boundary point features. On main
#: b86dd39 Figure 4's diagonal from the feature (2.947, 3.203) ran to (-2.5, 2.5), the end of a rebranch
#: on the straight side from (0, 5) to (-5, 0): 1 boundary singular vertex, min scaled Jacobian 0.163.
DRAW_664 = {
    "outer": [[8.200043777905584, 0.0], [3.061616997868383e-16, 5.0], [-5.0, 6.123233995736766e-16],
              [-1.5063236048220365e-15, -8.200043777905584]],
    "points": [[2.1570530097449487, -6.042990768160635], [-2.9999999999999996, 2.0000000000000004],
               [2.9473278668637244, 3.2028584561919757]],
}

#: Saved random plan 399 (spacing 0.04): a hexagon with three point features and a curve. On main the
#: same at a rebranch's end on the side from (-0.685, -9.286) to (6.344, -4.314): 1 boundary singular
#: vertex, min scaled Jacobian 0.318.
DRAW_399 = {
    "outer": [[6.728449061042926, 3.250146403581485], [0.42557471924558454, 5.771300607658235],
              [-5.357054245046767, 3.6430219333085674], [-7.653829328804786, -3.6971470900584507],
              [-0.6847659725176364, -9.286243036946356], [6.344332052503569, -4.314412317335293]],
    "points": [[1.9228879091492619, 0.55], [-6.609400369689113, -0.35929953719113783],
               [-3.156417705975768, -7.304011282211809]],
    "curves": [[[-3.563879994205502, 0.43884478030230945], [-2.1752372515697402, 1.0060055452755492],
                [-0.06360591264881954, 2.8869308075448377]]],
}

#: (plan, spacing, min scaled Jacobian floor; main b86dd39: 0.163, 0.318)
CASES = {"draw_664": (DRAW_664, 0.02, 0.28), "draw_399": (DRAW_399, 0.04, 0.31)}


def _rules_without_the_back_split(folder: Path) -> Path:
    """A copy of the shipped rulebook whose Figure 4 choice has no split to the point before the far
    corner (the rulebook of main b86dd39)."""
    out = folder / "rules"
    out.mkdir()
    for path in default_rules_dir().glob("*.vgr"):
        text = path.read_text()
        if path.name == "patching.vgr":
            old = "split_quad_at_feature_beside_boundary, split_quad_at_feature_beside_boundary_back,"
            assert text.count(old) == 1
            text = text.replace(old, "split_quad_at_feature_beside_boundary,")
        (out / path.name).write_text(text)
    return out


@pytest.mark.parametrize("name", sorted(CASES))
def test_figure_4_diagonal_goes_to_the_point_before_a_far_corner_on_the_boundary(name):
    """No boundary point of the outer ring is the corner of three patches at 180 degrees: no boundary
    singularity (main 1), every free boundary point of a straight stretch with at most two patches,
    the features poles, no inverted face, min scaled Jacobian at least the floor (664: 0.163 -> 0.28)."""
    plan, spacing, floor = CASES[name]
    domain = domain_from_dict(plan)
    dec = decompose(domain, spacing)
    g = dec.graph
    straight = [n for n in g.nodes() if g.node_type(n) == "BoundaryVertex" and not g.get(n, "feature")]
    assert straight and all(g.degree(n, [PATCH_CORNER]) <= 2 for n in straight)
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    assert stats["feature_points_pole"] == len(plan["points"])
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= floor


@pytest.mark.parametrize("name", sorted(CASES))
def test_without_the_back_split_a_straight_boundary_point_has_three_faces(tmp_path, name):
    """With main's Figure 4 choice (no split to the point before the far corner), the diagonal ends at
    the rebranch's end: one boundary vertex at 180 degrees with three faces (main's 1)."""
    plan, spacing, _ = CASES[name]
    domain = domain_from_dict(plan)
    dec = decompose(domain, spacing, rules_dir=_rules_without_the_back_split(tmp_path))
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["boundary_singular"] == 1
    assert np.allclose(stats["boundary_singular_angles"], [180.0])
    assert stats["boundary_singular_valences"] == [4] and stats["boundary_singular_regular_valences"] == [3]
