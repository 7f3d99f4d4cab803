"""Progress on stderr (vaultgram.progress): every stage of a design reported as it starts and ends,
in order, a bar for the smoothing and horizontal-equilibrium loops, and silence when stderr is not a
terminal or with --quiet."""

from __future__ import annotations

import io
import re

from click.testing import CliRunner

from vaultgram import progress
from vaultgram.cli import main
from vaultgram.domain import load_domain
from vaultgram.pipeline import design

from paths import EXAMPLES


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_every_stage_starts_and_ends_in_order_with_bars_for_the_loops():
    out = Terminal()
    with progress.reporting(True, out):
        result = design(load_domain(EXAMPLES / "l_shape.json"), spacing=0.05, tessellation=None)
    text = out.getvalue()
    lines = [ln for ln in re.split(r"[\r\n]", text) if ln.startswith("vaultgram: ") and ln.endswith(("...", " s"))]
    expected = []
    for stage, seconds in result.timings.items():
        expected += [f"vaultgram: {stage} ...", f"vaultgram: {stage} done in"]
    assert [ln if ln.endswith("...") else ln.rsplit(" ", 2)[0] for ln in lines] == expected
    for loop in ("smooth", "horizontal"):
        assert re.search(rf"vaultgram: {loop}: +\d+%\|", text), loop  # tqdm's bar


def test_silent_unless_a_terminal_asks():
    out = io.StringIO()  # not a terminal
    with progress.reporting(True, out):
        progress.started("x")
        progress.ticker("x", 10)()
    quiet = Terminal()
    with progress.reporting(False, quiet):
        progress.started("x")
    assert out.getvalue() == quiet.getvalue() == ""
    progress.started("outside any reporting block")  # no reporter: nothing, no error


def test_design_command_prints_no_progress_off_a_terminal_and_takes_quiet(tmp_path):
    result = CliRunner().invoke(main, ["design", str(EXAMPLES / "l_shape.json"), "--out", str(tmp_path / "a"),
                                       "--spacing", "0.05", "--no-plots", "--quiet"])
    assert result.exit_code == 0, result.output
    assert "vaultgram: " not in result.output
