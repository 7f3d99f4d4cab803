"""Jagged outlines (issue 12: geographic outlines of 50-110 vertices with short edges, reflex corners
and spikes of 315-360 degrees): the spikes' chords and the chords that undo a quad turning past
straight at a reflex corner (``rules/corners.vgr``, :mod:`vaultgram.topology.reflex`).

On main d7b8402 jagged_1 failed with "the mesh folds" (a quad of 197 degrees at its 334 degree spike),
jagged_0 had a worst scaled Jacobian of 0.035, and spikes were left the corner of two patches.
"""

from __future__ import annotations

import pytest

from vaultgram.domain import domain_from_dict
from vaultgram.meshing.quality import mesh_stats
from vaultgram.meshpipeline import decompose
from vaultgram.pipeline import mesh_domain
from vaultgram.testing.jagged import jagged_plans
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.reflex import PAST_STRAIGHT, other_angle
from vaultgram.topology.types import PATCH_CORNER

PLANS = jagged_plans()


def _domain(name: str):
    """The jagged plan ``name`` as a domain."""
    return domain_from_dict(PLANS[name], name)


def _corner_patches(dec, lowest: float) -> list[tuple[float, int]]:
    """``(angle, number of patches)`` of every boundary vertex of ``dec`` of interior angle ``lowest``
    degrees or more."""
    g = dec.graph
    return [(boundary_angle(g, n), g.degree(n, [PATCH_CORNER])) for n in g.nodes()
            if g.schema.is_subtype(g.node_type(n), "BoundaryVertex") and boundary_angle(g, n) >= lowest]


@pytest.mark.parametrize("name", sorted(PLANS))
def test_every_spike_gets_a_chord(name):
    """A spike of 315-360 degrees (regular valence 5: four faces) is the corner of three patches or
    more (main: one spike of two on jagged_0, three on jagged_1, one on jagged_2); on jagged_0, 2 and 3
    every spike is the corner of four or more (its second chord: main had spikes of three on 0 and 3)."""
    spikes = _corner_patches(decompose(_domain(name)), 315.0)
    assert spikes and min(count for _, count in spikes) >= 3, spikes
    if name != "jagged_1":
        assert min(count for _, count in spikes) >= 4, spikes


def test_no_quad_turns_past_straight_at_a_spike_of_two_patches():
    """jagged_1's 334 degree spike at (5.371, -16.695) was the corner of two quads, one turning by
    197 degrees (a fold at any density): now it is the corner of three patches, none wider there
    than ``PAST_STRAIGHT``; two patch corners of the layout are wider than that (main: six, four of
    them at spikes)."""
    dec = decompose(_domain("jagged_1"))
    wide = [(round(float(a), 1), c) for p in dec.patches for c, a in zip(p.corners, p.corner_angles())
            if a > PAST_STRAIGHT]
    assert len(wide) <= 2, wide
    g = dec.graph
    spike = min((n for n in g.nodes() if g.schema.is_subtype(g.node_type(n), "BoundaryVertex")),
                key=lambda n: sum((a - b) ** 2 for a, b in zip(g.get(n, "pos"), (5.371, -16.695))))
    assert all(c != spike for _, c in wide)
    assert g.degree(spike, [PATCH_CORNER]) >= 3


def test_jagged_1_meshes_without_folding():
    """The plan main refused with "the mesh folds" meshes, with no inverted face, a worst scaled
    Jacobian above 0.05 and at most 5 boundary singularities (gmsh's QuadQS fails on it; 9 until session
    30's second outer fallback). The worst face (0.061 then) was a sliver at (5.48, 12.6) whose short sides
    were 0.008 and 0.025 of the median edge;
    its 0.124 before the max-min optimisation kept sides against their opposite sides was bought with a
    side of 0.0004 of it (a triangle in all but name)."""
    domain = _domain("jagged_1")
    stats = mesh_stats(mesh_domain(domain), domain)
    assert stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.05, stats["min_scaled_jacobian"]
    assert stats["shortest_over_median_edge"] > 0.003
    assert stats["boundary_singular"] <= 5, stats["boundary_singular_angles"]


def test_jagged_0_worst_element():
    """jagged_0's worst scaled Jacobian was 0.035 (a sliver quad at its 343 degree spike, the corner of
    two patches): now above 0.2, and no more boundary singularities than main's 13."""
    domain = _domain("jagged_0")
    stats = mesh_stats(mesh_domain(domain), domain)
    assert stats["min_scaled_jacobian"] > 0.2, stats["min_scaled_jacobian"]
    assert stats["boundary_singular"] <= 12, stats["boundary_singular_angles"]


def test_other_angle_counts_the_rest_beside_two_patches_only():
    """Beside two patches a chord counts the other's angle (the rest of the corner's); beside three
    (a spike after its first chord) none, so a sliver the skeleton left does not bar the chord."""
    assert other_angle(300.0, [190.0, 110.0], 0) == pytest.approx(110.0)
    assert other_angle(300.0, [190.0, 110.0], 1) == pytest.approx(190.0)
    assert other_angle(342.0, [136.0, 196.0, 10.0], 1) == float("inf")


def test_fold_at_a_plain_corner_names_the_corner_not_a_feature():
    """Where a patch turns past straight at a plain corner of the plan (no point or curve feature),
    the fold error names the corner's angle and the layout, not a feature or curve to move (main
    advised moving "the feature or curve there" where there is none). Saved random plan 642 (a hole's
    300 degree corner) folded so until session 23 (its layout now gives the corner three patches under
    180 degrees: tests/topology/test_layout_folds.py), so the advice is asked of its corner directly."""
    from vaultgram.meshing.quality import _turn_advice

    domain = domain_from_dict({
        "outer": [[9.47084251771326, 9.470842517713261e-09], [-9.470842721412436e-09, 9.47084251771326],
                  [-9.78412900810179, -9.784128619434026e-09], [9.470841561568737e-09, -9.47084251771326]],
        "holes": [[[2.697527427539362, 3.2844947809168623], [0.9012362862303192, 2.247405606939146],
                   [0.9012362862303184, 4.321583954894578]]],
        "curves": [[[-5.746083091077161, 0.16638200309940565], [-2.753095985915797, -0.03862577318675223]]]})
    dec = decompose(domain, 0.02)
    g = dec.graph
    (tip,) = {c for p in dec.patches for c in p.corners
              if max(abs(a - b) for a, b in zip(g.get(c, "pos"), (2.697527427539362, 3.2844947809168623))) < 1e-9}
    advice = _turn_advice(dec, tip)
    assert advice == "the layout leaves this 300 degree corner of the plan too few patches: soften or move the corner"
    assert "move the feature or curve" not in advice
