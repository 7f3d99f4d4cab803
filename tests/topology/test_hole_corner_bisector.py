"""A hole corner's cut into a skewed fan triangle ends where its chord to the pole bisects the triangle's
angle (issue 12, item 2; reflex.bisecting_foot). A reflex hole corner inside a side of the ring patch
round the hole is cut across that patch; where the cut's strip is one triangle of a point feature's fan,
entered by the side opposite the point, the strip ends at the point, halving the triangle there. On a
skewed triangle the fixed feet (reflex.FEET, 0.25-0.75 of the edge) all leave one half under 36 degrees
(reflex.MIN_FAN_HALF), and the corner kept two faces: the bisecting foot lies between them (draw 226 of
session 25's 700 random plans, 0.27 along) or beyond them (draw 691, 0.81)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from layout_probes import node_at

from vaultgram.domain import domain_from_dict
from vaultgram.geometry.polylines import ray_hit_fraction
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology import hole_fans, hole_hub, hole_rebranch, reflex
from vaultgram.topology.types import DIAGONAL, PATCH_CORNER

#: Draw 226 of the 700 random plans saved in session 25, as saved (spacing 0.03): an octagon with a
#: hexagonal hole and two boundary point features. On main 7aa879d the hole corner (-1.737, 0) kept two
#: faces (min scaled Jacobian 0.299): its cut's strip is the 79 degree triangle of the fan round the
#: point (-5.653, 0.279), and the feet of reflex.FEET split it 43.2 / 35.8 (0.25) or 35.2 / 43.8 (0.3).
DRAW_226 = {
    "outer": [[5.083576648746252, 1.7992344576412174], [4.0749770513472505, 8.539700090705303],
              [-1.7342401315853588, 4.899940971452856], [-5.776949068835382, 2.7566465604486816],
              [-5.541517444581442, -1.9613138195466804], [-3.728926885978923, -7.814502232816141],
              [1.7666171653776344, -4.9914193956477035], [4.831228666700839, -2.3053673709273004]],
    "holes": [[[2.140940794001716, -1.7881570703125582e-181], [1.171375752051814, -1.6793359138998805],
               [-0.7677543318479902, -1.6793359138998807], [-1.737319373797893, -2.374749450378234e-16],
               [-0.7677543318479916, 1.67933591389988], [1.1713757520518124, 1.6793359138998813]]],
    "points": [[-5.088369804930812, -3.4246109228640456], [-5.653306679505675, 0.2789000130421111]],
}

#: Draw 691 (spacing 0.02): a nonagon with a heptagonal hole and three point features, one inside the
#: plan. On main the hole corner (0.878, -0.553) kept two faces (min scaled Jacobian 0.292): its cut's
#: strip is the 89.5 degree triangle of the fan round the inner point (-0.839, 0), whose feet along
#: reflex.FEET leave one half of 5-35 degrees; the bisector meets the far side 0.81 along it.
DRAW_691 = {
    "outer": [[6.366513294051941, 1.529066473727368], [3.357932193726691, 4.538833307448916],
              [-0.3804302153203142, 6.210868595470527], [-4.505903139036946, 4.747381278265598],
              [-5.96149182011542, 0.6786864362111167], [-8.33836485592913, -5.520115173563498],
              [-2.571701500034317, -8.684769239379872], [2.86470774545044, -6.586766702375415],
              [5.626718233070554, -2.8047503069877044]],
    "holes": [[[3.3030035491046568, -1e-05], [2.822768045330844, -0.997229298980018],
               [1.743688663370103, -1.2435221262615133], [0.8783341870468224, -0.5534249594434286],
               [0.8783341870468222, 0.5534049594434285], [1.7436886633701028, 1.2435021262615131],
               [2.8227680453308435, 0.9972092989800182]]],
    "points": [[-0.839383685394937, 4.0], [-0.839383685394937, -1e-12], [1.4521814113646052, 5.39120721067798]],
}

#: (plan, spacing, the hole corner, the fan's pole, min scaled Jacobian floor; main 7aa879d: 0.299, 0.292)
CASES = {
    "draw_226": (DRAW_226, 0.03, (-1.737319373797893, 0.0), (-5.653306679505675, 0.2789000130421111), 0.31),
    "draw_691": (DRAW_691, 0.02, (0.8783341870468224, -0.5534249594434286), (-0.839383685394937, 0.0), 0.33),
}


def _halves(dec, corner: int, pole: int) -> list:
    """The angles at ``pole`` of the triangles at the foot of ``corner``'s cut (the strip point joined
    by diagonals to both): the two halves of the fan triangle the cut's strip ended in."""
    g = dec.graph

    def joined(n):
        return {g.other(e, n) for e in g.incident(n, [DIAGONAL])}

    (foot,) = [m for m in joined(corner) & joined(pole) if g.node_type(m) == "StripPoint"]
    patches = [p for p in dec.patches if pole in p.corners and foot in p.corners]
    assert all(p.n_sides == 3 for p in patches)
    return [p.corner_angles()[list(p.corners).index(pole)] for p in patches]


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_hole_corner_cut_ends_where_it_bisects_a_skewed_fan_triangle(name):
    """The hole corner is the corner of three patches, the pole's two new triangles are within a degree
    of each other and at least reflex.MIN_FAN_HALF there (the bisector's halves: 39.0 and 44.7 degrees),
    every hole corner of 225-315 degrees has three patches: no boundary singularity (main: 1), no
    inverted face, min scaled Jacobian up (0.299 -> 0.320, 0.292 -> 0.340)."""
    plan, spacing, corner, pole, floor = CASES[name]
    domain = domain_from_dict(plan)
    dec = decompose(domain, spacing)
    g = dec.graph
    assert g.degree(node_at(g, corner), [PATCH_CORNER]) == 3
    halves = _halves(dec, node_at(g, corner), node_at(g, pole))
    assert len(halves) == 2 and abs(halves[0] - halves[1]) < 1.0, halves
    assert min(halves) >= reflex.MIN_FAN_HALF, halves
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= floor


@pytest.mark.parametrize("name", sorted(CASES))
def test_without_the_bisecting_foot_the_corner_keeps_two_faces(monkeypatch, name):
    """The fixed feet alone leave the hole corner inside the ring patch's side (main's layout): the
    corner of no patch, one boundary singularity. The hub split after the bisecting cut (session 26,
    hole_hub) and the rebranch moved to the corner after the hub (session 28, hole_rebranch: on draw
    226 the rebranch to the corner's neighbour) are switched off too, and so is the merge of two fan
    triangles after it (session 31, hole_fans: on draw 226 the triangle beyond and its fan neighbour):
    they are the last fallbacks, and would take the corner in its place."""
    monkeypatch.setattr(reflex, "bisecting_foot", lambda graph, walk: ())
    monkeypatch.setattr(hole_hub, "_best_hub", lambda *args: None)
    monkeypatch.setattr(hole_rebranch, "_fits", lambda *args: False)
    monkeypatch.setattr(hole_fans, "_pair", lambda *args: None)
    plan, spacing, corner, _, _ = CASES[name]
    domain = domain_from_dict(plan)
    dec = decompose(domain, spacing)
    assert dec.graph.degree(node_at(dec.graph, corner), [PATCH_CORNER]) == 0
    assert mesh_stats(mesh_decomposition(dec), domain)["boundary_singular"] == 1


def test_the_bisecting_foot_halves_the_fan_triangle_and_keeps_off_the_ends(monkeypatch):
    """reflex.bisecting_foot on a straight far side: a triangle with its pole at the origin and its
    far side from (4, -1) to (4, 3) (50.9 degrees at the pole): the chord to the foot bisects it; a far
    side whose bisector meets it within reflex.BISECTING_FOOT of an end ((4, -0.1) to (4, 30): 0.12
    along) gives no foot."""
    far = [[4.0, -1.0], [4.0, 3.0]]

    def foot_of(side):
        start = math.atan2(side[0][1], side[0][0])
        monkeypatch.setattr(reflex, "fan_end", lambda graph, walk: ((0.0, 0.0), start, _angle(side)))
        monkeypatch.setattr(reflex, "half_edge_polyline", lambda graph, edge, u: np.array(side, dtype=float))
        return reflex.bisecting_foot(_Graph(), _Walk())

    (fraction,) = foot_of(far)
    foot = np.array(far[0]) + fraction * (np.array(far[1]) - np.array(far[0]))
    first = math.degrees(math.atan2(foot[1], foot[0]) - math.atan2(-1.0, 4.0))
    assert first == pytest.approx(_angle(far) / 2.0) and 0.25 < fraction < 0.5
    assert foot_of([[4.0, -0.1], [4.0, 30.0]]) == ()
    assert ray_hit_fraction(np.array(far), (0.0, 0.0), 0.0) == pytest.approx(0.25)


def _angle(side) -> float:
    """The angle (degrees) at the origin between the directions to the two ends of ``side``."""
    (x0, y0), (x1, y1) = side
    return math.degrees(math.atan2(y1, x1) - math.atan2(y0, x0))


class _Walk:
    """A strip of one triangle entered by the plan edge 0 (the fan is patched in)."""

    edges = (0,)


class _Graph:
    """The one graph method reflex.bisecting_foot asks besides the patched helpers."""

    @staticmethod
    def ends(edge):
        return 0, 1
