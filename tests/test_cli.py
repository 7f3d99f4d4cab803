"""The command line: summaries, outputs, and one-line errors with exit code 2 and nothing written."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from click.testing import CliRunner

from vaultgram.cli import main

from paths import EXAMPLES, REPO

RULES = REPO / "rules" / "topology.vgr"


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_rules_check_prints_summary():
    result = run("rules", "check", RULES)
    assert result.exit_code == 0, result.output
    assert "prune_corner_branch all; rebranch all" in result.output
    assert (
        "patching: cut_neck fixpoint; split_at_boundary_feature(onto_boundary = false) fixpoint; "
        "split_at_boundary_feature fixpoint; "
        "choose { split_quad_at_feature_beside_boundary, split_quad_at_feature_beside_boundary_back, "
        "split_quad_at_feature, keep_quad_at_feature } fixpoint"
    ) in result.output


def test_rules_check_json():
    result = run("rules", "check", "--json", RULES)
    summary = json.loads(result.output)
    assert {"prune_corner_branch", "rebranch", "split_quad_at_feature", "pair_t_junctions"} <= set(summary["rules"])
    assert summary["types"]["nodes"]["Corner"] == "BoundaryVertex"


def test_rules_check_of_the_whole_folder_checks_each_stage_rulebook_with_its_functions():
    files = sorted((REPO / "rules").glob("*.vgr"))
    result = run("rules", "check", *files)
    assert result.exit_code == 0, result.output
    assert result.output.count("ok: ") == 2 and "ok: 1 file(s)" in result.output  # tessellation.vgr alone
    books = json.loads(run("rules", "check", "--json", *files).output)
    assert sorted(books[1]["rules"]) == ["keystone", "keystone_of_fan"]
    assert "Vertex" in books[1]["types"]["nodes"] and "Corner" in books[0]["types"]["nodes"]


def test_rules_run_refuses_the_two_stage_rulebooks_together(tmp_path):
    result = run("rules", "run", RULES, REPO / "rules" / "tessellation.vgr", "--graph",
                 EXAMPLES / "skeleton_quad_with_hole.json", "--strategy", "topology", "--out", tmp_path / "o")
    assert result.exit_code == 2 and "a rulebook of its own" in result.output
    assert not (tmp_path / "o").exists()


def test_rules_check_reports_syntax_error_with_position(tmp_path):
    bad = tmp_path / "bad.vgr"
    bad.write_text("rule r {\n  match { a: A \n")
    result = run("rules", "check", bad)
    assert result.exit_code == 2
    assert f"{bad}:3:1" in result.output and "Traceback" not in result.output


def test_rules_check_reports_type_error_with_hint(tmp_path):
    bad = tmp_path / "bad.vgr"
    bad.write_text(f'include "{REPO / "rules" / "schema.vgr"}"\nrule r {{\n  match {{ s: Singulrity }}\n}}\n')
    result = run("rules", "check", bad)
    assert result.exit_code == 2
    assert f"{bad}:3:11: unknown node type 'Singulrity'" in result.output
    assert "did you mean 'Singularity'" in result.output


def test_rules_run_writes_graph_and_trace(tmp_path):
    result = run("rules", "run", RULES, "--graph", EXAMPLES / "skeleton_quad_with_hole.json",
                 "--strategy", "topology", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    graph = json.loads((tmp_path / "graph.json").read_text())
    types = [e["type"] for e in graph["edges"]]
    assert types.count("Rebranch") == 12 and types.count("Branch") == 4
    trace = json.loads((tmp_path / "trace.json").read_text())
    # 4 prunings, 12 rebranchings and the `leave` of the O-grid's choice point (no disc here)
    assert len(trace) == 17 and [a["rule"] for a in trace].count("leave") == 1


def test_rules_run_unknown_strategy_is_a_clear_error(tmp_path):
    result = run("rules", "run", RULES, "--graph", EXAMPLES / "skeleton_quad_with_hole.json",
                 "--strategy", "nope", "--out", tmp_path / "out")
    assert result.exit_code == 2 and "unknown strategy 'nope'" in result.output
    assert not (tmp_path / "out").exists()


def test_why_not_explains(tmp_path):
    run("rules", "run", RULES, "--graph", EXAMPLES / "skeleton_quad_with_hole.json", "--strategy", "topology",
        "--out", tmp_path)
    result = run("rules", "why-not", RULES, "--graph", tmp_path / "graph.json", "--rule", "rebranch")
    assert result.exit_code == 0
    assert "refused by NAC #1" in result.output


def test_decompose_writes_outputs_deterministically(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    for out in (a, b):
        result = run("decompose", EXAMPLES / "quad_with_hole.json", "--out", out)
        assert result.exit_code == 0, result.output
    assert "12 patches (12 four-sided, 0 three-sided), 4 singularities" in result.output
    for name in ("decomposition.json", "patches.json", "decomposition.png"):
        assert (a / name).read_bytes() == (b / name).read_bytes()
    patches = json.loads((a / "patches.json").read_text())
    assert patches["counts"] == {"3": 0, "4": 12}
    assert all(len(p["sides"]) == p["n_sides"] == 4 for p in patches["patches"])


def test_decompose_bad_domain_exits_2_and_writes_nothing(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"outer": [[0, 0], [10, 0], [0, 10], [10, 10]]}))  # a bow tie
    result = run("decompose", bad, "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert "self-intersect" in result.output and "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


def test_python_dash_m_runs_the_cli(tmp_path):
    done = subprocess.run([sys.executable, "-m", "vaultgram", "rules", "check", str(RULES)],
                          capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0 and "ok:" in done.stdout


def test_design_runs_the_whole_pipeline_deterministically(tmp_path):
    outs = [tmp_path / "a", tmp_path / "b"]
    for out in outs:
        result = run("design", EXAMPLES / "fig6_inner_points.json", "--out", out, "--zmax", "3", "--point-load", "2")
        assert result.exit_code == 0, result.output
    names = ["decomposition.json", "patches.json", "decomposition.png", "mesh.json", "mesh.obj", "mesh.png",
             "form.json", "force.json", "thrust.json", "thrust.obj", "summary.json", "thrust.png",
             "tessellation.json", "voussoirs.obj", "tessellation.png"]
    for name in names:
        assert (outs[0] / name).read_bytes() == (outs[1] / name).read_bytes(), name
    summary = json.loads((outs[0] / "summary.json").read_text())["thrust"]
    assert (
        summary["max_angle_deg"] < 0.5
        and abs(summary["reaction_sum"] - summary["total_load"]) < 1e-9 * summary["total_load"]
    )


def test_design_failing_stage_writes_nothing(tmp_path):
    domain = tmp_path / "d.json"
    domain.write_text(json.dumps({"outer": [[0, 0], [10, 0], [10, 10], [0, 10]],
                                  "supports": {"polylines": [[[20, 20], [30, 20]]]}}))
    result = run("design", domain, "--out", tmp_path / "out")
    assert result.exit_code == 2 and "nothing bears thrust" in result.output
    assert not (tmp_path / "out").exists()


def _tree(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_a_run_that_fails_while_writing_leaves_the_output_folder_untouched(tmp_path, monkeypatch):
    """The decomposition's files are written, then the plot fails: --out keeps what it had, no new file
    and no staging folder is left beside it."""
    from vaultgram.io import plots

    out = tmp_path / "out"
    out.mkdir()
    (out / "decomposition.json").write_text("an older run")
    before = _tree(out)

    def failing_plot(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(plots, "plot_decomposition", failing_plot)
    result = run("decompose", EXAMPLES / "quad_with_hole.json", "--out", out)
    assert result.exit_code != 0
    assert _tree(out) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


def test_an_interrupted_run_writes_nothing_and_a_finished_one_replaces_the_files(tmp_path, monkeypatch):
    from vaultgram.io import outputs

    out = tmp_path / "out"
    real = outputs.write_tessellation

    def interrupted(*args, **kwargs):
        real(*args, **kwargs)
        raise KeyboardInterrupt

    design = run("design", EXAMPLES / "quad_with_hole.json", "--out", tmp_path / "d", "--zmax", 3, "--no-plots")
    assert design.exit_code == 0, design.output
    monkeypatch.setattr(outputs, "write_tessellation", interrupted)
    result = run("tessellate", tmp_path / "d" / "thrust.json", "--out", out)
    assert result.exit_code != 0 and not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d"]
    monkeypatch.setattr(outputs, "write_tessellation", real)
    (tmp_path / "d" / "extra.txt").write_text("kept")
    again = run("tessellate", tmp_path / "d" / "thrust.json", "--out", tmp_path / "d")
    assert again.exit_code == 0, again.output
    assert (tmp_path / "d" / "extra.txt").read_text() == "kept"
    assert json.loads((tmp_path / "d" / "tessellation.json").read_text())["voussoirs"]


@pytest.mark.parametrize("name", ["l_shape", "quad_with_hole", "fig5_boundary_points", "fig6_inner_points",
                                  "fig7_curves", "features_combined", "square_point_loads"])
def test_decompose_trace_replays_to_the_same_decomposition(tmp_path, name):
    """decompose --trace writes trace.json (rule, bindings, created, deleted, retyped, set, choice) and the
    starting graph; rules replay gives the decomposition's graph again, element for element."""
    out = tmp_path / "d"
    run = CliRunner().invoke(main, ["decompose", str(EXAMPLES / f"{name}.json"), "--out", str(out), "--trace",
                                    "--no-plot", "--spacing", "0.03"])
    assert run.exit_code == 0, run.output
    trace = json.loads((out / "trace.json").read_text())
    assert {"rule", "binding", "created_nodes", "deleted_edges", "retyped", "set", "choice"} <= set(trace[0])
    assert sum(1 for r in trace if r.get("edit")) == 1  # the Patch nodes the pipeline adds
    again = CliRunner().invoke(main, ["rules", "replay", str(RULES), "--graph", str(out / "start_graph.json"),
                                      "--trace", str(out / "trace.json"), "--out", str(tmp_path / "r")])
    assert again.exit_code == 0, again.output
    replayed = json.loads((tmp_path / "r" / "graph.json").read_text())
    graph = json.loads((out / "decomposition.json").read_text())
    assert [n["id"] for n in replayed["nodes"]] == [n["id"] for n in graph["nodes"]]
    assert [(e["id"], e["type"], e["source"], e["target"]) for e in replayed["edges"]] == [
        (e["id"], e["type"], e["source"], e["target"]) for e in graph["edges"]]
    assert [{k: v for k, v in n.items()} for n in replayed["nodes"]] == graph["nodes"]


def test_design_trace_is_written(tmp_path):
    out = tmp_path / "d"
    run = CliRunner().invoke(main, ["design", str(EXAMPLES / "l_shape.json"), "--out", str(out), "--trace",
                                       "--no-plots"])
    assert run.exit_code == 0, run.output
    assert json.loads((out / "trace.json").read_text()) and (out / "start_graph.json").is_file()


STAR = """
schema star { node P { pos: vec2, w: int = 0 }  edge L (P -- P) }
rule explode {
  match { s: P { w: 1 } }
  foreach s -L- m {
    create r: P { pos = lerp(s.pos, m.pos, 0.5) }
    create r -L- m
    create r -L- next(r)
  }
  detach delete s
}
strategy go { explode once }
"""


def star_graph(tmp_path):
    """A centre with 6 neighbours on a circle, their edge ids out of angular order."""
    angles = [0, 3, 1, 4, 2, 5]  # edge k reaches the neighbour at 60 * angles[k] degrees
    nodes = [{"id": 0, "type": "P", "pos": [0.0, 0.0], "w": 1}]
    nodes += [{"id": k + 1, "type": "P", "pos": [float(np.cos(a * np.pi / 3)), float(np.sin(a * np.pi / 3))]}
              for k, a in enumerate(angles)]
    edges = [{"id": k, "type": "L", "source": 0, "target": k + 1} for k in range(6)]
    (tmp_path / "star.vgr").write_text(STAR)
    (tmp_path / "g.json").write_text(json.dumps({"nodes": nodes, "edges": edges}))
    return tmp_path / "star.vgr", tmp_path / "g.json"


def test_rules_run_orders_edges_by_position(tmp_path):
    """With node positions the rotation follows the geometry: the ring built by foreach/next joins
    angular neighbours (in edge-id order it would cross itself)."""
    rules, graph = star_graph(tmp_path)
    result = run("rules", "run", rules, "--graph", graph, "--strategy", "go", "--out", tmp_path / "out")
    assert result.exit_code == 0, result.output
    out = json.loads((tmp_path / "out" / "graph.json").read_text())
    pos = {n["id"]: np.array(n["pos"]) for n in out["nodes"]}
    ring = [(e["source"], e["target"]) for e in out["edges"] if e["source"] > 6 and e["target"] > 6]
    assert len(ring) == 6
    for u, v in ring:  # neighbours on the ring of radius 0.5: 60 degrees apart
        assert np.linalg.norm(pos[u] - pos[v]) == pytest.approx(0.5, rel=1e-9)


def test_rules_matches_lists_every_match(tmp_path):
    rules, graph = star_graph(tmp_path)
    result = run("rules", "matches", rules, "--graph", graph, "--rule", "explode", "--json")
    assert result.exit_code == 0, result.output
    assert json.loads(result.output) == [{"s": 0}]
    text = run("rules", "matches", rules, "--graph", graph, "--rule", "explode").output
    assert text.splitlines() == ["0: s=0", "1 match(es) of explode"]


def test_why_not_lists_reasons_with_values(tmp_path):
    rules, graph = star_graph(tmp_path)
    (tmp_path / "far.vgr").write_text(STAR + """
rule far { match { s: P { w: 1 }  m: P  s -L- m } where distance(s.pos, m.pos) > 2 delete s }""")
    result = run("rules", "why-not", tmp_path / "far.vgr", "--graph", graph, "--rule", "far", "--limit", "4")
    assert result.exit_code == 0, result.output
    lines = result.output.splitlines()
    assert "4 nearest partial match(es)" in lines[0] and len(lines) == 5
    assert all("condition `distance(s.pos, m.pos) > 2` is false" in ln and "distance(s.pos, m.pos) = 1" in ln
               and "s.pos = (0, 0)" in ln for ln in lines[1:])


@pytest.mark.parametrize("each", [False, True])
def test_trace_command_draws_each_step(tmp_path, each):
    from vaultgram.domain import load_domain
    from vaultgram.io.traceview import trace_frames
    from vaultgram.pipeline import decompose

    out = tmp_path / "t"
    args = ["trace", EXAMPLES / "fig5_boundary_points.json", "--out", out, "--spacing", "0.04"]
    result = run(*args, *(["--each"] if each else []))
    assert result.exit_code == 0, result.output
    dec = decompose(load_domain(EXAMPLES / "fig5_boundary_points.json"), 0.04, trace=True)
    frames = trace_frames(dec, each)
    applications = sum(r.applications for r in dec.reports)
    assert len(frames) == (applications if each else sum(1 for r in dec.reports if r.applications))
    assert sum(1 for _, records in frames for r in records if r.get("edit") is None) == applications
    assert len(list(out.glob("step_*.png"))) == len(frames) and (out / "start.png").is_file()
    page = (out / "index.html").read_text()
    assert page.count("step_") == len(frames) and all(json.dumps(c)[1:-1] in page for c, _ in frames)
