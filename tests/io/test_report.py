"""report.html (vaultgram.io.report): one self-contained page with every figure as well-formed
inline SVG, the parameters, each stage's metrics and times; ``vaultgram report DIR`` rebuilds it;
``--no-report`` and ``--no-plots``; and Chromium shows it (tests/browser.py)."""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET

import pytest
from browser import render
from click.testing import CliRunner

from vaultgram.cli import main
from vaultgram.io.figures import BESIDE, CATALOGUE
from vaultgram.io.report import SECTIONS, STAGES

from paths import EXAMPLES

SMALL = ["--spacing", "0.05", "--target-length", "1.2"]


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """One design of the paper's square with a hole, shared by the module."""
    out = tmp_path_factory.mktemp("report") / "out"
    result = run("design", EXAMPLES / "quad_with_hole.json", "--out", out, *SMALL)
    assert result.exit_code == 0, result.output
    return out


def svgs(page: str) -> list[str]:
    return re.findall(r"<svg\b.*?</svg>", page, flags=re.S)


def test_the_report_has_every_section_and_figure(folder):
    page = (folder / "report.html").read_text()
    for section in SECTIONS:
        assert f"<section id='{section}'>" in page, section
    for spec in CATALOGUE:
        assert f"<figure id='figure-{spec.name}'>" in page, spec.name
        assert (folder / "figures" / f"{spec.name}.png").is_file()
    assert len(svgs(page)) == len(CATALOGUE)
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["parameters"]["spacing"] == 0.05
    assert f"<th>patches</th><td class='n'>{summary['decomposition']['patches']}</td>" in page
    timings = json.loads((folder / "timings.json").read_text())
    assert {"rules", "smooth", "horizontal", "stagger", "write", "figures"} <= set(timings)
    assert set(timings) <= {s for steps in STAGES.values() for s in steps}  # every timed stage in a part
    for name, figure in BESIDE.items():  # the single figures beside the files are those of figures/
        assert (folder / name).read_bytes() == (folder / "figures" / f"{figure}.png").read_bytes()


def test_every_svg_is_well_formed_and_nothing_is_fetched(folder):
    page = (folder / "report.html").read_text()
    for svg in svgs(page):
        assert ET.fromstring(svg).tag.endswith("svg")
    for external in ("<script", "<link", "<img", "src=", "url(http", "@import"):
        assert external not in page, external
    assert set(re.findall(r"href=['\"]([a-z]+):", page)) <= {"data"}  # embedded images only


def test_report_command_rebuilds_the_page_and_refuses_other_folders(folder, tmp_path):
    before = (folder / "report.html").read_bytes()
    (folder / "report.html").unlink()
    result = run("report", folder)
    assert result.exit_code == 0, result.output
    assert (folder / "report.html").read_bytes() == before
    result = run("report", tmp_path)
    assert result.exit_code == 2 and "no summary.json" in result.output and "Traceback" not in result.output
    assert list(tmp_path.iterdir()) == []


def test_no_report_and_no_plots(tmp_path):
    result = run("design", EXAMPLES / "l_shape.json", "--out", tmp_path / "a", *SMALL, "--no-plots", "--no-report")
    assert result.exit_code == 0, result.output
    names = {p.name for p in (tmp_path / "a").iterdir()}
    assert "report.html" not in names and "figures" not in names and not any(n.endswith(".png") for n in names)
    assert "timings.json" in names


def test_chromium_shows_the_report(folder):
    shown = render(folder / "report.html", height=1600)
    assert not shown.is_blank()
    for section in SECTIONS:
        assert f'id="{section}"' in shown.dom
    assert shown.dom.count("<svg") >= len(CATALOGUE)
