"""``report.html``: one self-contained page of a design -- every figure as inline SVG, the
parameters, each stage's metrics and the time each stage took.

The page is made from the files of a finished output folder alone (``summary.json``,
``timings.json``, ``figures/*.svg``), so ``vaultgram report DIR`` rebuilds it exactly as ``vaultgram
design`` wrote it. It needs no network and runs no script: the figures are SVG elements of the page
itself, the style one ``<style>`` block.
"""

from __future__ import annotations

import html
import json
import re
from pathlib import Path

from vaultgram.errors import VaultgramError
from vaultgram.io.files import read_json, write_text

__all__ = ["write_report", "report_html", "SECTIONS", "STAGES"]

#: The page's sections, by id, in order.
SECTIONS = ("parameters", "stages", "topology", "mesh", "thrust", "tessellation", "figures")

#: The stages of the pipeline and the timings (``timings.json`` keys) each is made of.
STAGES = {
    "topology": ("discretise", "triangulate", "skeleton", "rules"),
    "mesh": ("groups", "weld", "smooth", "untangle", "orthogonalise"),
    "form finding": ("supports", "form", "relax", "force", "horizontal", "vertical"),
    "tessellation": ("surface", "refine", "keystones", "stagger", "sizes", "surface_smooth", "solids", "courses",
                     "metrics"),
    "outputs": ("write", "figures", "report"),
}

_STYLE = """
body { font-family: sans-serif; margin: 2em auto; max-width: 1200px; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; }
td, th { border-bottom: 1px solid #ddd; padding: 2px 12px 2px 0; text-align: left; font-size: 14px; }
td.n { text-align: right; font-variant-numeric: tabular-nums; }
figure { margin: 1em 0 2em; } figcaption { font-size: 14px; color: #555; }
figure svg { max-width: 100%; height: auto; }
"""


def write_report(folder: Path, target: Path | None = None) -> Path:
    """Write ``report.html`` of the output ``folder`` (into ``target``, default the folder itself)."""
    path = Path(target or folder) / "report.html"
    write_text(path, report_html(Path(folder)))
    return path


def report_html(folder: Path) -> str:
    """The report page of an output folder (see the module docstring)."""
    summary_path = folder / "summary.json"
    if not summary_path.is_file():
        raise VaultgramError(f"{folder}: no summary.json: not the output folder of `vaultgram design`")
    summary = read_json(summary_path)
    if not isinstance(summary, dict) or "thrust" not in summary:
        raise VaultgramError(f"{summary_path}: not the summary of `vaultgram design` (no 'thrust' section)")
    timings = read_json(folder / "timings.json") if (folder / "timings.json").is_file() else {}
    name = (summary.get("mesh") or {}).get("domain", folder.name)
    body = [f"<h1>{_e(name)}: vaultgram design</h1>",
            _section("parameters", "Parameters", _table(summary.get("parameters") or {})),
            _section("stages", "Stages and times", _stage_table(timings)),
            _section("topology", "Topology: block decomposition", _table(summary.get("decomposition") or {})),
            _section("mesh", "Mesh", _table({**(summary.get("mesh") or {}), **(summary.get("mesh_quality") or {})})),
            _section("thrust", "Thrust network: equilibrium and reactions", _table(summary.get("thrust") or {})),
            _section("tessellation", "Tessellation: voussoirs", _table(summary.get("tessellation") or {})),
            _section("figures", "Figures", "\n".join(_figures(folder)))]
    return ("<!doctype html>\n<html lang='en'><head><meta charset='utf-8'>"
            f"<title>{_e(name)}: vaultgram report</title><style>{_STYLE}</style></head><body>\n"
            + "\n".join(body) + "\n</body></html>\n")


def _e(value) -> str:
    return html.escape(str(value))


def _section(ident: str, title: str, content: str) -> str:
    return f"<section id='{ident}'><h2>{_e(title)}</h2>\n{content}\n</section>"


def _cell(value) -> str:
    """A table cell: numbers right-aligned (floats to 6 significant digits), the rest as JSON text."""
    if isinstance(value, bool) or value is None:
        return f"<td>{_e(value)}</td>"
    if isinstance(value, (int, float)):
        return f"<td class='n'>{value:.6g}</td>" if isinstance(value, float) else f"<td class='n'>{value}</td>"
    text = value if isinstance(value, str) else json.dumps(value)
    return f"<td>{_e(text if len(text) < 300 else text[:300] + ' ...')}</td>"


def _flat(data: dict, prefix: str = "") -> list:
    """(key, value) rows of a nested dict, keys joined by dots."""
    rows = []
    for key in sorted(data):
        value = data[key]
        if isinstance(value, dict) and value and len(value) <= 12:
            rows += _flat(value, f"{prefix}{key}.")
        else:
            rows.append((f"{prefix}{key}", value))
    return rows


def _table(data: dict) -> str:
    if not data:
        return "<p>not computed</p>"
    rows = "".join(f"<tr><th>{_e(k)}</th>{_cell(v)}</tr>" for k, v in _flat(data))
    return f"<table>{rows}</table>"


def _stage_table(timings: dict) -> str:
    """The time of each stage and of its steps (seconds), and the total."""
    if not timings:
        return "<p>no timings (timings.json) in this folder</p>"
    rows = []
    for stage, steps in STAGES.items():
        mine = [(s, timings[s]) for s in steps if s in timings]
        if mine:
            detail = ", ".join(f"{s} {t:.3f}" for s, t in mine)
            rows.append(f"<tr><th>{_e(stage)}</th><td class='n'>{sum(t for _, t in mine):.3f} s</td>"
                        f"<td>{_e(detail)}</td></tr>")
    rows.append(f"<tr><th>total</th><td class='n'>{sum(timings.values()):.3f} s</td><td></td></tr>")
    return f"<table><tr><th>stage</th><th>time</th><th>steps (s)</th></tr>{''.join(rows)}</table>"


def _figures(folder: Path) -> list:
    """Each figure of ``folder/figures`` (in the catalogue's order) as an inline SVG with its caption."""
    from vaultgram.io.figures import CATALOGUE

    out = []
    for spec in CATALOGUE:
        path = folder / "figures" / f"{spec.name}.svg"
        if path.is_file():
            out.append(f"<figure id='figure-{spec.name}'>{_inline(path.read_text())}"
                       f"<figcaption>{_e(spec.caption)}</figcaption></figure>")
    return out or ["<p>no figures (run without --no-plots)</p>"]


def _inline(svg: str) -> str:
    """An SVG file's ``<svg>`` element, without the XML declaration and doctype a page cannot hold."""
    start = svg.find("<svg")
    if start < 0:
        raise VaultgramError("a figure is not SVG (no <svg> element)")
    return re.sub(r"\s+$", "", svg[start:])
