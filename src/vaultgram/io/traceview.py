"""``vaultgram trace``: figures of the decomposition graph as the rules rewrite it, and an HTML page
stepping through them.

The decomposition's trace (``trace.json``) is replayed from its starting graph; after each strategy
step that applied something (or, with ``each``, after each application) the graph is drawn with the
elements the step matched in red and those it created in green (:func:`plot_graph`).
"""

from __future__ import annotations

import html
import json
from dataclasses import dataclass, field
from pathlib import Path

from vaultgram.engine.graph import HostGraph
from vaultgram.engine.trace import replay
from vaultgram.io.files import write_text
from vaultgram.io.plots import plot_graph
from vaultgram.topology.decomposition import Decomposition, edge_angle

__all__ = ["Frame", "trace_frames", "write_trace_view"]


@dataclass
class Frame:
    """One figure: its caption, the trace records it covers, and what they matched and created."""

    caption: str
    records: list = field(default_factory=list)
    matched: tuple = ((), ())  # node ids, edge ids
    created: tuple = ((), ())


def trace_frames(dec: Decomposition, each: bool = False) -> list[tuple[str, list]]:
    """The trace cut into (caption, records): one piece per strategy step that applied something, or
    per application with ``each``; the pipeline's edits go with the piece after them."""
    records = list(dec.trace)
    pieces: list[tuple[str, list]] = []
    for report in (r for r in dec.reports if r.applications):
        taken: list = []
        applied = 0
        while applied < report.applications:
            taken.append(records.pop(0))
            applied += taken[-1].get("edit") is None
        if each:
            pending: list = []
            for rec in taken:
                pending.append(rec)
                if rec.get("edit") is None:
                    pieces.append((f"{report.step}: {rec['rule']} at {rec['binding']}", pending))
                    pending = []
        else:
            pieces.append((f"{report.step}: {report.applications} application(s)", taken))
    return pieces


def _split(rulebook, records) -> Frame:
    """What the applications among ``records`` matched and created, as node and edge ids."""
    frame = Frame("", records)
    matched_nodes, matched_edges, created_nodes, created_edges = [], [], [], []
    for rec in records:
        if rec.get("edit") is not None:
            continue
        node_vars = rulebook.rules[rec["rule"]].pattern.nodes
        matched_nodes += [i for v, i in rec["binding"].items() if v in node_vars]
        matched_edges += [i for v, i in rec["binding"].items() if v not in node_vars]
        created_nodes += rec["created_nodes"]
        created_edges += rec["created_edges"]
    frame.matched, frame.created = (matched_nodes, matched_edges), (created_nodes, created_edges)
    return frame


def write_trace_view(dec: Decomposition, rulebook, out: Path, each: bool = False) -> int:
    """Write ``step_NNN.png`` per frame, ``start.png`` and ``index.html`` to ``out``; return the
    number of frames. ``dec`` must have been made with ``trace=True`` (its ``start_graph``)."""
    graph = HostGraph.from_json(dec.start_graph, rulebook.schema, angle=edge_angle)
    plot_graph(graph, out / "start.png", title="before the rules")
    frames = []
    for k, (caption, records) in enumerate(trace_frames(dec, each)):
        replay(records, rulebook, graph)
        frame = _split(rulebook, records)
        frame.caption = caption
        plot_graph(graph, out / f"step_{k:03d}.png", *frame.matched, caption, frame.created)
        frames.append(frame)
    write_text(out / "index.html", _page(dec.disc.domain.name, [f.caption for f in frames]))
    return len(frames)


_SCRIPT = """
let k = 0; const img = document.getElementById('frame'), cap = document.getElementById('caption');
function show(i) { k = Math.max(0, Math.min(frames.length - 1, i)); img.src = frames[k][0];
  cap.textContent = (k + 1) + ' / ' + frames.length + ': ' + frames[k][1]; }
document.addEventListener('keydown', e => { if (e.key === 'ArrowRight') show(k + 1);
  if (e.key === 'ArrowLeft') show(k - 1); });
show(0);
"""


def _page(name: str, captions: list[str]) -> str:
    """A self-contained page stepping through the figures (buttons, or the arrow keys)."""
    frames = [("start.png", "before the rules")] + [(f"step_{k:03d}.png", c) for k, c in enumerate(captions)]
    items = ", ".join(f"[{_js(src)}, {_js(text)}]" for src, text in frames)
    return (f"<!doctype html>\n<html><head><meta charset='utf-8'><title>{html.escape(name)}: rule trace</title>"
            "</head><body>\n"
            f"<h1>{html.escape(name)}: what the rules did</h1>\n"
            "<p><button onclick='show(k - 1)'>previous</button> <button onclick='show(k + 1)'>next</button> "
            "<span id='caption'></span></p>\n<img id='frame' alt='graph' style='max-width: 100%'>\n"
            "<p>Red: what the step matched; green: what it created.</p>\n"
            f"<script>const frames = [{items}];{_SCRIPT}</script>\n</body></html>\n")


def _js(text: str) -> str:
    """A JavaScript string literal (JSON's quoting, with '<' escaped for an HTML script block)."""
    return json.dumps(text).replace("<", "\\u003c")
