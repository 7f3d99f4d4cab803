"""Traces: the record of every rule application, as JSON, replayable to the same graph.

A trace lists, for each application, the rule, its parameter values, the binding of its pattern
variables, the ids it created and deleted, the nodes it retyped (``[node, old type, new type]``),
the attributes it set (``[kind, id, attribute, value]``) and, at a ``choose`` step, the option the
chooser took (``choice``, its index among the options; None elsewhere). Between strategies the host
application may add elements of its own (:meth:`Trace.record_edit`: ``{"rule": null, "edit":
{"nodes": [...], "edges": [...]}}``). :func:`replay` applies the same rules at the same bindings,
and the same edits, to a copy of the starting graph and checks that every application creates the
same ids, so a replayed graph is identical (same ids, attributes and rotations) to the traced one.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

from .errors import RewriteError, TraceError
from .graph import HostGraph
from .matcher import Matcher
from .rewriter import Application, apply_rule


@dataclass
class Edit:
    """Elements the host application added between strategies, as graph JSON (ids included)."""

    nodes: list[dict]
    edges: list[dict]


@dataclass
class Trace:
    """An ordered list of applications (and of the host's edits between strategies, by position)."""

    applications: list[Application] = field(default_factory=list)
    edits: list[tuple[int, Edit]] = field(default_factory=list)  # (applications before it, edit)

    def __len__(self) -> int:
        return len(self.applications)

    def record(self, app: Application) -> None:
        self.applications.append(app)

    def record_edit(self, nodes: list[dict], edges: list[dict]) -> None:
        """Record elements the host added to the graph (not by a rule), for replay."""
        self.edits.append((len(self.applications), Edit(nodes, edges)))

    def to_json(self) -> list[dict]:
        out = []
        edits = list(self.edits)
        for i, app in enumerate(self.applications):
            while edits and edits[0][0] == i:
                out.append({"rule": None, "edit": asdict(edits.pop(0)[1])})
            out.append(_application_json(app))
        out.extend({"rule": None, "edit": asdict(edit)} for _, edit in edits)
        return out


def _application_json(app: Application) -> dict:
    """An application as a trace record: its fields but ``mark``, the lists and dicts copied
    (their items are ids, names and attribute values, which the graph keeps immutable), the
    parameters' tuples as lists. What ``dataclasses.asdict`` gives, without copying every point
    of every polyline set (exploration records the applications of every state, issue 13)."""
    return {"rule": app.rule, "params": {k: _plain(v) for k, v in app.params.items()}, "binding": dict(app.binding),
            "created_nodes": list(app.created_nodes), "created_edges": list(app.created_edges),
            "deleted_nodes": list(app.deleted_nodes), "deleted_edges": list(app.deleted_edges),
            "retyped": [list(r) for r in app.retyped], "set": [list(x) for x in app.set], "choice": app.choice}


def _plain(value):
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    return value


def load_trace(path: str | Path) -> list[dict]:
    """The records of a trace written as JSON (``Trace.to_json``), for :func:`replay`."""
    try:
        return json.loads(Path(path).read_text())
    except (OSError, json.JSONDecodeError) as exc:
        raise TraceError(f"{path}: cannot read trace: {exc}") from None


def replay(records: list[dict], rulebook, graph: HostGraph) -> Trace:
    """Re-apply traced applications to ``graph`` (which must be the traced run's starting graph)."""
    trace = Trace()
    for i, rec in enumerate(records):
        if rec.get("edit") is not None:
            _apply_edit(graph, rec["edit"], i)
            trace.record_edit(rec["edit"]["nodes"], rec["edit"]["edges"])
            continue
        rule = rulebook.rules.get(rec["rule"])
        if rule is None:
            raise RewriteError(f"trace step {i}: unknown rule '{rec['rule']}'")
        params = {k: tuple(v) if isinstance(v, list) else v for k, v in rec["params"].items()}
        matcher = Matcher(rule, graph, params)
        binding = {k: int(v) for k, v in rec["binding"].items()}
        if not matcher.check(binding):
            raise RewriteError(f"trace step {i}: rule {rule.name} does not match at {binding}")
        app = apply_rule(rule, graph, binding, matcher.values)
        app.params = dict(rec["params"])
        if (app.created_nodes, app.created_edges) != (rec["created_nodes"], rec["created_edges"]):
            raise RewriteError(
                f"trace step {i}: rule {rule.name} created nodes {app.created_nodes} and edges "
                f"{app.created_edges}, the trace says {rec['created_nodes']} and {rec['created_edges']}"
            )
        trace.record(app)
    return trace


def _apply_edit(graph: HostGraph, edit: dict, step: int) -> None:
    """Add a recorded edit's nodes and edges (with their ids) to ``graph``."""
    try:
        for item in edit["nodes"]:
            graph.add_node(item["type"], {k: v for k, v in item.items() if k not in ("id", "type")}, item["id"])
        for item in edit["edges"]:
            attrs = {k: v for k, v in item.items() if k not in ("id", "type", "source", "target")}
            graph.add_edge(item["type"], item["source"], item["target"], attrs, item["id"])
    except (KeyError, TypeError) as exc:
        raise TraceError(f"trace step {step}: malformed edit: {exc!r}") from None
