"""The error figure (vaultgram.io.figures.errorplot): a design that fails on a geometric problem
(here a mesh that folds) writes DIR/error.png alone, a valid PNG that shows the place, and says so in
its one line; beside a folder that holds a result it writes DIR.error.png and leaves the result as it was."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from vaultgram.cli import main

from folding import FOLDING, SKIPPED_ADVICE, rules_without_fan_check, skip_the_fold_advice


def design(plan, out, *options):
    return CliRunner().invoke(main, ["design", str(plan), "--out", str(out), "--quiet", *options])


def red_pixels(png) -> int:
    """How many pixels of the PNG are the error's red (matplotlib's tab:red, #d62728)."""
    from matplotlib.image import imread

    rgb = (imread(png)[..., :3] * 255).round()
    return int((np.abs(rgb - [214, 39, 40]).sum(axis=-1) < 30).sum())


def failed_design(tmp_path, plan_data: dict, name: str, *options):
    """``design`` of ``plan_data`` (written to ``tmp_path/name``) into ``tmp_path/out``: it fails with
    one line ending with the error figure's path, and the folder holds that figure alone (``options``:
    more of design's options). Returns the line, the plan's path and the folder."""
    plan = tmp_path / name
    plan.write_text(json.dumps(plan_data))
    out = tmp_path / "out"
    result = design(plan, out, *options)
    assert result.exit_code == 2 and "Traceback" not in result.output
    (line,) = result.output.strip().splitlines()
    assert line.endswith(f"(drawn in {out / 'error.png'})")
    assert [p.name for p in out.iterdir()] == ["error.png"]
    return line, plan, out


def test_a_fold_draws_error_png_and_writes_nothing_else(tmp_path, tmp_path_factory, monkeypatch):
    skip_the_fold_advice(monkeypatch)
    rules = ("--rules", str(rules_without_fan_check(tmp_path_factory.mktemp("book"))))  # tests/folding.py
    line, plan, out = failed_design(tmp_path, FOLDING, "folding.json", *rules)
    assert "the mesh folds" in line and SKIPPED_ADVICE in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["folding.json", "out"]  # no staging folder left
    png = (out / "error.png").read_bytes()
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    assert red_pixels(out / "error.png") > 20  # the folded faces and their marks, not a blank figure
    first = png
    design(plan, out, *rules)  # again: the same figure, still alone
    assert [p.name for p in out.iterdir()] == ["error.png"] and (out / "error.png").read_bytes() == first


def test_beside_a_finished_result_the_figure_goes_next_to_it(tmp_path, tmp_path_factory, monkeypatch):
    skip_the_fold_advice(monkeypatch)
    rules = ("--rules", str(rules_without_fan_check(tmp_path_factory.mktemp("book"))))  # tests/folding.py
    plan = tmp_path / "folding.json"
    plan.write_text(json.dumps(FOLDING))
    out = tmp_path / "out"
    out.mkdir()
    (out / "summary.json").write_text("{}")  # a previous result
    result = design(plan, out, *rules)
    assert result.exit_code == 2 and f"(drawn in {tmp_path / 'out.error.png'})" in result.output
    assert [p.name for p in out.iterdir()] == ["summary.json"] and (out / "summary.json").read_text() == "{}"
    assert red_pixels(tmp_path / "out.error.png") > 20


#: A long strip held at one short end only: relaxing its open sides collapses form-diagram edges.
HELD_AT_ONE_END = {"outer": [[0, 0], [10, 0], [10, 1], [0, 1]], "supports": {"polylines": [[[0, 0], [0, 1]]]}}


def test_a_failed_relaxation_is_drawn_too(tmp_path):
    """A form-finding failure that knows its edges (here: relaxing a strip held at one end folds its
    faces, or collapses its edges) draws them in plan."""
    line, _, out = failed_design(tmp_path, HELD_AT_ONE_END, "strip.json")
    assert "folded" in line or "collapsed" in line
    assert red_pixels(out / "error.png") > 20


def test_form_finding_errors_carry_the_plan_segments_of_their_edges():
    """The places of a horizontal-equilibrium failure are the flipped edges' segments in plan."""
    from vaultgram.errors import HorizontalEquilibriumError
    from vaultgram.formfinding.formdiagram import form_diagram
    from vaultgram.formfinding.horizontal import horizontal
    from vaultgram.geometry.meshes import grid_mesh

    v, f = grid_mesh(3, 1)
    form = form_diagram(v, f, supports=[0])
    with pytest.raises(HorizontalEquilibriumError) as info:
        horizontal(form)
    edges, segments = info.value.edges, np.asarray(info.value.places)
    assert len(edges) > 0 and segments.shape == (len(edges), 2, 2)
    assert np.array_equal(segments, form.xy[form.edges[edges]])
