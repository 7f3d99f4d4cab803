"""Traces: the record of every rule application, as JSON, replayable to the same graph.

A trace lists, for each application, the rule, its parameter values, the binding of its pattern
variables and the ids it created and deleted. :func:`replay` applies the same rules at the same
bindings to a copy of the starting graph and checks that every application creates the same ids,
so a replayed graph is identical (same ids, attributes and rotations) to the traced one.
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
class Trace:
    """An ordered list of applications."""

    applications: list[Application] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.applications)

    def record(self, app: Application) -> None:
        self.applications.append(app)

    def to_json(self) -> list[dict]:
        out = []
        for app in self.applications:
            d = asdict(app)
            d.pop("mark")
            d["params"] = {k: _plain(v) for k, v in d["params"].items()}
            out.append(d)
        return out


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
