"""Layouts drawn as before session 27's sliver split at curve ends, for the tests of mechanisms those
layouts showed then.

Since session 27 the default step ``split_quad_at_curve_end_to_side(sliver = 30)`` (rules/strips.vgr,
run in curves.vgr's ``curve_patching``) splits fig7_curves' quads at the curve end (1, 1) to the middle
of the skeleton branch bending round it, where split_quad_at_curve_end's diagonal left a 17.1 degree
sliver. The fan at that end is then no longer the 147 degree pole some tests measure a mechanism on;
those tests draw fig7 with a copy of the rules without that step.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from vaultgram.topology.rulebook import default_rules_dir

#: The step of curve_patching (rules/curves.vgr) that splits a curve end's sliver quads to the side.
SLIVER_STEP = ("  { split_quad_at_curve_end_to_side(sliver = 30), absorb_strip_point, continue_strip, "
               "end_strip_at_boundary,\n    split_strip_patch, end_strip_in_triangle } fixpoint\n")


def rules_with_diagonals_at_curve_ends(folder: Path) -> Path:
    """A copy of the default rules in ``folder`` / "rules" without the sliver step: every quad at a
    curve's free end takes split_quad_at_curve_end's diagonal (or is kept) as before session 27."""
    rules = folder / "rules"
    shutil.copytree(default_rules_dir(), rules, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
    text = (rules / "curves.vgr").read_text()
    if SLIVER_STEP not in text:
        raise AssertionError("the sliver step is not in rules/curves.vgr as tests/diagonal_at_curve_ends.py has it")
    (rules / "curves.vgr").write_text(text.replace(SLIVER_STEP, ""))
    return rules
