"""A boundary pole's triangle whose split needs a group that an inner point feature's fan caps: the cap
gives way (issue 12, acceptance 3; splits._boundary_groups). Plan 197 of session 32's 700 random plans:
on main 18d7fb4 one of the last boundary singular vertices of the 700."""

from __future__ import annotations

import numpy as np
import pytest
from layout_probes import assert_the_one_singular_corner, faces_at, node_at

from vaultgram.domain import domain_from_dict
from vaultgram.meshing import splits
from vaultgram.meshing.densities import group_counts, point_load_caps
from vaultgram.meshing.layout import edge_groups
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology.types import PATCH_CORNER

#: Random plan 197 of benchmarks/data/random_plans_700.json.gz (spacing 0.02): a hexagon with a regular
#: hexagonal hole and four point features. The hole's 240 degree corner (0.8, 1.899) is the corner of three
#: patches on main 18d7fb4 too: its to-side chord's triangle (48.4 degrees, its marked pole) and two quads.
#: But the triangle's sides at the pole are in one edge group with the side opposite the inner feature
#: (1, 0)'s 44.1 degree fan triangle, capped at 2 (densities.point_load_caps), and its side opposite the
#: pole has count 3: no split (it needs that count even and under twice 2), a fan of three at the corner,
#: five faces, 1 boundary singular vertex, min scaled Jacobian 0.3207.
DRAW_197 = {
    "outer": [[7.315092285401558, 2.3988893318822706], [2.0524376562129483, 9.787108851308394],
              [-5.104956319292477, 4.57137984759526], [-4.75105186147154, -1.5580456378449945],
              [-2.052437656212954, -9.787108851308393], [5.17469566764812, -4.63382995132144]],
    "holes": [[[1.6002062583648566, 3.2845373232869015], [0.8001031291824285, 1.8987180522480909],
               [-0.800103129182428, 1.8987180522480906], [-1.6002062583648566, 3.2845373232869015],
               [-0.800103129182429, 4.670356594325712], [0.8001031291824272, 4.670356594325713]]],
    "points": [[-1.7479304295663685, 0.3168860067791767], [0.99999, 0.0], [-3.2186999343470744, 5.9459307203106455],
               [-5.011331950404597, 2.949858614850606]],
    "curves": [],
}
SPACING = 0.02
CORNER = (0.8001031291824285, 1.8987180522480909)


def _pole_triangle(layout, r: int):
    """The index and pattern of the triangle whose pole is ``r``."""
    (k,) = [k for k, p in enumerate(layout.patterns) if p.pole is not None and p.corners[p.pole] == r]
    return k, layout.patterns[k]


@pytest.fixture(scope="module")
def laid():
    domain = domain_from_dict(DRAW_197)
    dec = decompose(domain, SPACING)
    return domain, dec, edge_groups(dec)


def test_the_capped_group_is_raised_and_the_triangle_splits(laid):
    """The triangle's pole sides' group is capped at 2 by the feature's fan; raised to 3 (the opposite side
    to 4) the triangle is split into three quads: the corner has three faces (regular). In the mesh no
    boundary singularity (main 1), no inverted face, min scaled Jacobian at least 0.35 (main 0.3207, here
    0.3568: the feature's fan of three, evened)."""
    domain, dec, layout = laid
    r = node_at(dec.graph, CORNER)
    assert dec.graph.degree(r, [PATCH_CORNER]) == 3
    k, pat = _pole_triangle(layout, r)
    m_group = int(layout.group_of[pat.sides[pat.pole][0]])
    assert point_load_caps(layout)[m_group] == 2
    counts = group_counts(layout)
    m, n = (int(counts[layout.group_of[pat.sides[(pat.pole + j) % 3][0]]]) for j in (0, 1))
    assert (m, n) == (3, 4) and k in splits.split_patterns(layout, counts)
    mesh = mesh_decomposition(dec)
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    assert faces_at(mesh, CORNER, 1e-6) == 3
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= 0.35


def test_with_the_cap_kept_the_corner_is_a_fan_of_three(laid, monkeypatch):
    """With no group released from its cap (main 18d7fb4's counts) the pole sides keep 2, the opposite side
    3, the triangle stays a fan of three at the corner: five faces, the one boundary singular vertex (240
    degrees), as on main."""
    monkeypatch.setattr(splits, "_boundary_groups", lambda layout, counts, free: np.zeros(len(free), dtype=bool))
    domain, dec, _ = laid
    r = node_at(dec.graph, CORNER)
    layout = edge_groups(dec)  # a layout of its own: its counts at the default length are remembered
    counts = group_counts(layout)
    k, pat = _pole_triangle(layout, r)
    m, n = (int(counts[layout.group_of[pat.sides[(pat.pole + j) % 3][0]]]) for j in (0, 1))
    assert (m, n) == (2, 3) and k not in splits.split_patterns(layout, counts)
    assert_the_one_singular_corner(domain, dec, CORNER, 5, 240.0)
