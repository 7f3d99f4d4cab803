"""Figure 4's split at a point feature leaves no crescent fan (issue 12, session 24;
:mod:`vaultgram.topology.fans`, ``fan_clear`` in rules/patching.vgr's split_quad_at_feature and
keep_quad_at_feature): saved random plan 78 (tests/folding.py's FOLDING) folded in a fan triangle
its pole does not see; two_holes_five_points' boundary point at a 58.5 degree corner keeps its fan
(a slight turn back of its concave sides is no crescent)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology import fans

from folding import FOLDING, rules_without_fan_check
from paths import ARCHITECTURE

#: Plan 78's boundary point feature, the pole of the crescent without the check.
POLE_78 = FOLDING["points"][2]
#: two_holes_five_points' boundary point feature at a 58.5 degree corner (concave arcs either side).
SHARP_CORNER = (1.009, 8.13)


def _fan_outlines(dec) -> list[tuple]:
    """Each three-sided patch with a marked pole: (pole position, the outline from the point after
    the pole to the point before it)."""
    out = []
    for patch in dec.patches:
        pole = dec.marked_pole(patch)
        if patch.n_sides == 3 and pole is not None:
            k = list(patch.corners).index(pole)
            sides = [patch.sides[(k + i) % 3] for i in range(3)]
            outline = np.concatenate([sides[0][1:], sides[1][1:], sides[2][1:-1]])
            out.append((dec.graph.get(pole, "pos"), outline))
    return out


def _hidden_shares(dec) -> list[float]:
    """Per fan triangle, its outline's deepest turn back about the pole over the pole's angle."""
    return [hidden / whole for hidden, whole in (fans.hidden_turn(o, p) for p, o in _fan_outlines(dec))]


def test_hidden_turn_is_nil_for_a_convex_fan_and_the_depth_of_a_wrap():
    """A convex polygon turns back nowhere about any vertex; a square with a notch hides the notch's
    depth (45 - 14.0 degrees) whichever way it is turned; the whole turn is the pole's angle."""
    hexagon = [(math.cos(a), math.sin(a)) for a in np.radians(np.arange(0, 360, 60))]
    hidden, whole = fans.hidden_turn(hexagon[1:], hexagon[0])
    assert hidden == 0.0 and math.degrees(whole) == pytest.approx(120.0)
    notched = np.array([(2, 0), (2, 2), (1.6, 0.4), (0.5, 2)], dtype=float)
    for turn in np.radians([0.0, 100.0, 250.0]):
        rotation = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])
        hidden, whole = fans.hidden_turn(notched @ rotation.T, (0.0, 0.0))
        assert math.degrees(hidden) == pytest.approx(45.0 - math.degrees(math.atan2(0.4, 1.6)))
        assert math.degrees(whole) == pytest.approx(math.degrees(math.atan2(2, 0.5)))


def test_a_crescent_is_refused_and_a_sagging_side_is_not():
    """A triangle of about 60 degrees at the pole whose first side sags into it (leaving the pole 5.4
    degrees above its chord, which the pole then sees from behind) is meshed as a fan; an outline
    that wraps back by 42 of its 71 degrees (a hook) is not; nor is one turning a full turn."""
    t = np.linspace(0.0, 1.0, 20)[1:]
    sag = np.column_stack([t, 0.03 * np.sin(np.pi * t)])
    sagging = np.vstack([sag, [(0.5, math.sqrt(3) / 2)]])
    hidden, whole = fans.hidden_turn(sagging, (0.0, 0.0))
    assert 0 < hidden < fans.HIDDEN_SHARE * whole and fans.seen_from_pole(sagging, (0.0, 0.0))
    hook = np.vstack([sag, [(1.5, math.sqrt(3) / 2), (1.2, 1.5), (0.3, 0.05), (0.2, 0.8)]])
    hidden, whole = fans.hidden_turn(hook, (0.0, 0.0))
    assert hidden > fans.HIDDEN_SHARE * whole and not fans.seen_from_pole(hook, (0.0, 0.0))
    turns, radii = np.radians(np.arange(10, 400, 10)), np.linspace(1, 2, 39)
    spiral = np.column_stack([radii * np.cos(turns), radii * np.sin(turns)])
    assert not fans.seen_from_pole(spiral, (0.0, 0.0)) and fans.seen_from_pole(spiral[:-4], (0.0, 0.0))


def test_plan_78_has_no_crescent_fan_and_meshes(tmp_path):
    """Plan 78: without the check the boundary point (0.05, 5.74) is the pole of a crescent (its
    outline turns back by more than its angle at the pole); with it, every fan triangle turns back
    by at most HIDDEN_SHARE of its pole's angle, the point is still a pole, and the plan meshes with
    no inverted face (tests/meshing/test_quality.py: it folds without the check)."""
    domain = domain_from_dict(FOLDING)
    assert max(_hidden_shares(decompose(domain, rules_dir=rules_without_fan_check(tmp_path)))) > 1.0
    dec = decompose(domain)
    assert max(_hidden_shares(dec)) <= fans.HIDDEN_SHARE
    assert any(np.allclose(pole, POLE_78) for pole, _ in _fan_outlines(dec))
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["inverted_faces"] == 0 and stats["feature_points_pole"] == stats["feature_points"] == 3


def test_the_check_refuses_78s_crescent_and_clears_the_sharp_corners_fan(monkeypatch):
    """What fan_clear answers in the rules: for plan 78's quad at (0.05, 5.74) (its diagonal bent round
    the curve's branch) False; for two_holes_five_points' quad at its 58.5 degree corner (straight
    diagonal, both halves hiding 1.2 degrees behind the concave arcs) True, and that corner is the
    pole of two fan triangles."""
    asked = []
    seen = fans.fan_parts_seen

    def spy(outline, at, path):
        asked.append((tuple(np.round(outline[0], 3)), len(path), seen(outline, at, path)))
        return asked[-1][2]

    monkeypatch.setattr(fans, "fan_parts_seen", spy)
    decompose(domain_from_dict(FOLDING))
    assert (tuple(np.round(POLE_78, 3)), 3, False) in asked
    asked.clear()
    dec = decompose(load_domain(ARCHITECTURE / "two_holes_five_points.json"))
    assert (SHARP_CORNER, 2, True) in asked
    poles = [pole for pole, _ in _fan_outlines(dec) if np.allclose(pole, SHARP_CORNER, atol=5e-3)]
    assert len(poles) == 2
