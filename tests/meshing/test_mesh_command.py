"""The meshing commands of the CLI: vaultgram mesh and vaultgram stats, and their one-line errors."""

from __future__ import annotations

import json

from click.testing import CliRunner

from vaultgram.cli import main

from paths import EXAMPLES


def test_cli_mesh_and_stats(tmp_path):
    runner = CliRunner()
    domain = str(EXAMPLES / "quad_with_hole.json")
    out = tmp_path / "m"
    res = runner.invoke(main, ["mesh", domain, "--out", str(out), "--target-length", "0.6", "--smooth", "5"])
    assert res.exit_code == 0, res.output
    assert (out / "mesh.json").is_file() and (out / "mesh.obj").is_file()
    res = runner.invoke(main, ["stats", str(out / "mesh.json"), "--domain", domain, "--json"])
    assert res.exit_code == 0, res.output
    stats = json.loads(res.output)
    assert stats["boundary_singular"] == 0 and stats["interior_singular"] == 4 and stats["triangles"] == 0
    res = runner.invoke(main, ["stats", str(out / "mesh.json")])
    assert res.exit_code == 0 and "min_scaled_jacobian" in res.output
    dens = tmp_path / "d.json"
    dens.write_text(json.dumps({"groups": {"0": 3, "1": 4}}))
    res = runner.invoke(main, ["mesh", domain, "--out", str(out), "--densities", str(dens)])
    assert res.exit_code == 0, res.output
    assert [g["count"] for g in json.loads((out / "mesh.json").read_text())["edge_groups"]][:2] == [3, 4]


def test_cli_errors_are_one_line(tmp_path):
    runner = CliRunner()
    dens = tmp_path / "d.json"
    dens.write_text('{"groups": {"0": -2}}')
    res = runner.invoke(main, ["mesh", str(EXAMPLES / "l_shape.json"), "--out", str(tmp_path),
                               "--densities", str(dens)])
    assert res.exit_code == 2 and "positive integer" in res.output and "Traceback" not in res.output
    bad = tmp_path / "bad.json"
    bad.write_text('{"vertices": [[0, 0]], "faces": [[0, 1, 2]]}')
    res = runner.invoke(main, ["stats", str(bad)])
    assert res.exit_code == 2 and "faces" in res.output
