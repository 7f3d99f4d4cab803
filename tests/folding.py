"""A plan whose mesh folds at the default settings, for the tests of the fold error (its message,
its figure, the CLI's exit code).

The shipped rulebook meshes both plans below since session 24: Figure 4's split at a point feature
(rules/patching.vgr) leaves no crescent that its fan cannot mesh (``fan_clear``,
:mod:`vaultgram.topology.fans`), which was their fold. No saved random plan folds with it, so the
tests reproduce the folds through the public interface: a rulebook passed with ``--rules``
(``rules_dir``) whose Figure 4 rules split without that check (:func:`rules_without_fan_check`).
"""

from __future__ import annotations

from pathlib import Path

from vaultgram.topology.rulebook import default_rules_dir

#: The conditions of rules/patching.vgr's Figure 4 rules that refuse a split leaving a crescent fan, and
#: how often each occurs: in the match of split_quad_at_feature and keep_quad_at_feature, and in their
#: ``not`` block, which split_quad_at_feature_beside_boundary_back shares (session 26).
FAN_CHECKS = ((" and fan_clear(p, f, o)", 2), ("\n      and fan_clear(q, f, patch_corner(q, (eq.index + 2) % 4))", 3))


def rules_without_fan_check(folder: Path) -> Path:
    """A copy in ``folder/rules`` of the shipped rulebook whose Figure 4 rules split a quad at a
    feature whatever fans it leaves (the rulebook before session 24): the plans below fold with it."""
    out = folder / "rules"
    out.mkdir()
    for path in default_rules_dir().glob("*.vgr"):
        text = path.read_text()
        if path.name == "patching.vgr":
            for check, count in FAN_CHECKS:
                assert text.count(check) == count, check
                text = text.replace(check, "")
        (out / path.name).write_text(text)
    return out


#: The advice :func:`skip_the_fold_advice` puts in the fold error instead of the real one.
SKIPPED_ADVICE = "(the finer meshes not tried in this test)"


def skip_the_fold_advice(monkeypatch) -> None:
    """The fold error without its advice: the finer meshes that :func:`vaultgram.meshpipeline._finer_mesh`
    tries take four fifths of a folding design's time (44 of 59 s on :data:`FOLDING`), and the tests
    of the command line's exit code, its one line and its figure do not read the advice (tested once,
    in tests/meshing/test_quality.py)."""
    monkeypatch.setattr("vaultgram.meshpipeline._finer_mesh", lambda *args: SKIPPED_ADVICE)


#: Draw 74 of benchmarks/reliability.py's plans (saved plan 78 of /work/plans700.json): three points and a
#: curve in an octagon. Without the fan check (:func:`rules_without_fan_check`) the point (0.05, 5.74) is
#: the pole of a crescent between the boundary and a diagonal bent round the curve's skeleton branch, and
#: it folds (39 inverted faces) whatever smoothing, untangling, the optimiser and the three-quad splits do.
#: (The rectangle with two curves that these tests used before
#: meshes since thin fans became three quads, vaultgram.meshing.splits.)
FOLDING = {"outer": [[5.388755136395837, 2.6384309882897248], [2.272610268283502, 6.6329147511377],
                     [-2.33842148645929, 4.776013036590429], [-5.030664895556137, 1.7236375148607566],
                     [-6.297157131259193, -3.0832008678643037], [-2.4261781222834715, -7.081122918773187],
                     [3.4991589610352656, -7.146713674920552], [9.23604221728679, -3.164509897810106]],
           "points": [[3.510862245437796, 1.1791723000490535], [8.274220447064053, -1.7137746762851482],
                      [0.04897158689832004, 5.737436537232383]],
           "curves": [[[-5e-324, 1.1063395951484711], [-1.3568401035271442, 2.0108613012609426]]]}

#: Saved random plan 646 (benchmarks/reliability.py, /work/plans700.json in session 21): five points in a
#: pentagon, two of them 0.03 and 0.2 from others and one on the boundary; without the fan check, at
#: spacing 0.05 the patches between the boundary point (4.33, -1.43) and its neighbours fold, at 0.025
#: the plan meshes.
FOLDING_AT_COARSE_SPACING = {
    "outer": [[4.99600053330489, 0.1999466709331708], [2.202054369628232, 7.829772558014759],
              [-7.2437851099974075, 4.832496393248626], [-5.896499541992104, -4.655409871199035],
              [2.3426145265261717, -6.335685878312445]],
    "points": [[2.9821325206620415, 5.538672294051537e-251], [-1.9470627144108237, 0.03],
               [3.7056973671537774, 3.7235609149270386], [4.33265403161021, -1.433961466378233],
               [-1.776942507732966, -5.49554787475574]]}
