"""vaultgram explore and replay: the files, byte-identical with 1 or 4 workers and on Dask, replay,
the gallery in a real browser, and bad input."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from browser import render
from click.testing import CliRunner

from vaultgram.cli import main

from paths import EXAMPLES, REPO

DOMAIN = str(EXAMPLES / "fig5_boundary_points.json")
ARGS = ["--spacing", "0.05", "--limit", "6", "--smooth", "5"]


def _explore(out: Path, *extra) -> object:
    return CliRunner().invoke(main, ["explore", DOMAIN, "--out", str(out), *ARGS, *extra])


def _files(out: Path) -> dict:
    """Every file written, as bytes; variants.json without its one timing."""
    files = {str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}
    variants = json.loads(files.pop("variants.json"))
    variants.pop("seconds")
    return {**files, "variants.json": json.dumps(variants, sort_keys=True).encode()}


@pytest.fixture(scope="module")
def explored(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("explore") / "out"
    result = _explore(out)
    assert result.exit_code == 0, result.output
    assert "states visited" in result.output and "distinct variants" in result.output
    return out


def test_explore_writes_the_state_space_the_variants_and_the_gallery(explored):
    space = json.loads((explored / "state_space.json").read_text())
    listing = json.loads((explored / "variants.json").read_text())
    assert set(listing) == {"states_visited", "seconds", "variants"}
    assert listing["states_visited"] == len(space["states"]) == 6
    assert [v["id"] for v in listing["variants"]] == [v["id"] for v in space["variants"]]
    for v in listing["variants"]:
        assert (explored / v["decomposition"]).is_file()
        assert {"patches_by_sides", "singularities_by_valence", "poles", "edge_groups", "boundary_singularities",
                "min_scaled_jacobian", "mean_scaled_jacobian", "score"} <= set(v["metrics"])
    for edge in space["edges"]:
        assert {"from", "to", "rule", "match", "choice"} <= set(edge)
        assert space["states"][edge["to"]]["parent"] == edge["from"]
    assert any(v["pareto"] for v in space["variants"])


def test_replay_rebuilds_a_variant_byte_for_byte(explored, tmp_path):
    space = json.loads((explored / "state_space.json").read_text())
    last = space["variants"][-1]
    result = CliRunner().invoke(main, ["replay", DOMAIN, str(explored / "state_space.json"), "--variant",
                                       str(last["id"]), "--out", str(tmp_path / "r")])
    assert result.exit_code == 0, result.output
    for name in ("decomposition.json", "patches.json", "mesh.json"):
        assert (tmp_path / "r" / name).read_bytes() == (explored / last["folder"] / name).read_bytes()


def test_four_workers_write_the_same_files(explored, tmp_path):
    result = _explore(tmp_path / "w4", "--workers", "4")
    assert result.exit_code == 0, result.output
    assert _files(tmp_path / "w4") == _files(explored)


def test_a_local_dask_cluster_writes_the_same_files(explored, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster:
        result = _explore(tmp_path / "dask", "--scheduler", cluster.scheduler_address)
    assert result.exit_code == 0, result.output
    assert _files(tmp_path / "dask") == _files(explored)


def test_the_gallery_renders_one_thumbnail_per_variant(explored):
    page = render(explored / "index.html", 1000, 900)
    assert not page.is_blank()
    n = len(json.loads((explored / "variants.json").read_text())["variants"])
    assert page.dom.count('class="thumbnail"') == n and page.dom.count('class="card') == n
    assert page.dom.count('class="card pareto"') >= 1


@pytest.mark.parametrize("extra, message", [
    (["--limit", "0"], "--limit must be at least 1"),
    (["--depth", "-1"], "--depth must be at least 0"),
    (["--workers", "0"], "--workers must be at least 1"),
    (["--pareto", "score"], "--pareto takes two metrics"),
    (["--order", "depth"], "Invalid value for '--order'"),
    (["--scheduler", "tcp://127.0.0.1:9"], "cannot reach the Dask scheduler"),
])
def test_bad_options_are_one_line_exit_2_nothing_written(tmp_path, extra, message):
    result = CliRunner().invoke(main, ["explore", DOMAIN, "--out", str(tmp_path / "out"), *ARGS, *extra])
    assert result.exit_code == 2 and message in result.output
    assert len(result.output.strip().splitlines()) == 1 and "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


def test_a_rulebook_without_choice_points_explores_one_variant_and_says_so(tmp_path):
    rules = tmp_path / "rules"
    shutil.copytree(REPO / "rules", rules, ignore=shutil.ignore_patterns("*.py", "__pycache__"))
    for path in rules.glob("*.vgr"):
        path.write_text(path.read_text().replace("  choose {", "  {"))
    result = _explore(tmp_path / "out", "--rules", str(rules))
    assert result.exit_code == 0, result.output
    assert "the rulebook has no choice points" in result.output
    assert len(json.loads((tmp_path / "out" / "variants.json").read_text())["variants"]) == 1


def test_replay_of_a_missing_variant_is_an_error(explored, tmp_path):
    result = CliRunner().invoke(main, ["replay", DOMAIN, str(explored / "state_space.json"), "--variant", "99",
                                       "--out", str(tmp_path / "r")])
    assert result.exit_code == 2 and "no variant 99" in result.output and not (tmp_path / "r").exists()


def test_formfind_adds_the_thrust_network_metrics(tmp_path):
    result = _explore(tmp_path / "ff", "--formfind", "--limit", "2")
    assert result.exit_code == 0, result.output
    for v in json.loads((tmp_path / "ff" / "variants.json").read_text())["variants"]:
        metrics = v["metrics"]
        assert "formfind_error" in metrics or (
            0 <= metrics["angle_deviation_deg"] < 5 and metrics["max_thrust"] > 0 and metrics["zmax"] > 0)
