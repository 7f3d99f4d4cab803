"""Mesh quality: statistics without labels, and a folded mesh as an error naming where."""

from __future__ import annotations

import dataclasses
import json

import pytest
from click.testing import CliRunner

from vaultgram.cli import main
from vaultgram.domain import domain_from_dict
from vaultgram.errors import VaultgramError
from vaultgram.io.meshfiles import mesh_from_json
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import mesh_domain

from folding import FOLDING, FOLDING_AT_COARSE_SPACING, rules_without_fan_check, skip_the_fold_advice


def test_stats_without_labels_use_mesh_topology():
    v = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0]]
    stats = mesh_stats(mesh_from_json({"vertices": v, "faces": [[0, 1, 4, 3], [1, 2, 5, 4]]}))
    assert stats["quads"] == 2 and stats["interior_singular"] == 0
    assert stats["boundary_singular"] == 0  # the corners' angles in the mesh (90 degrees) ask for one face
    assert stats["boundary_singular_angles"] == [] and stats["boundary_singular_valences"] == []
    # the left quad split into two triangles from the corner (0, 0): two faces at 90 degrees there,
    # three at 180 degrees at (1, 1)
    split = mesh_stats(mesh_from_json({"vertices": v, "faces": [[0, 1, 4], [0, 4, 3], [1, 2, 5, 4]]}))
    assert split["boundary_singular_vertices"] == [0, 4] and split["boundary_singular_angles"] == [90.0, 180.0]
    assert split["boundary_singular_valences"] == [3, 4] and split["boundary_singular_regular_valences"] == [2, 3]
    assert stats["min_scaled_jacobian"] == pytest.approx(1.0)
    assert stats["min_angle"] == pytest.approx(90.0) and stats["max_angle"] == pytest.approx(90.0)
    with pytest.raises(VaultgramError, match="edge 4-1 is traversed in the same direction by faces 0 and 1"):
        mesh_from_json({"vertices": v, "faces": [[0, 3, 4, 1], [1, 2, 5, 4]]})  # the reader refuses it
    mesh = mesh_from_json({"vertices": v, "faces": [[0, 1, 4, 3], [1, 2, 5, 4]]})
    flipped = mesh_stats(dataclasses.replace(mesh, faces=[(0, 3, 4, 1), (1, 2, 5, 4)]))
    assert flipped["inverted_faces"] == 1 and not flipped["oriented"]


def test_shortest_over_median_edge_sees_a_side_the_scaled_jacobian_does_not(tmp_path):
    """Two unit quads side by side, the right one's far side shrunk to 1 mm: its corners still score
    0.7 and more (the scaled Jacobian sees directions), the edge ratio shows the vanished side; the
    CLI's stats print it."""
    v = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0], [1, 1, 0], [2, 0.001, 0]]
    data = {"vertices": v, "faces": [[0, 1, 4, 3], [1, 2, 5, 4]]}
    stats = mesh_stats(mesh_from_json(data))
    assert stats["min_scaled_jacobian"] > 0.7
    assert stats["shortest_over_median_edge"] == pytest.approx(0.001)
    square = mesh_stats(mesh_from_json({**data, "vertices": v[:5] + [[2, 1, 0]]}))
    assert square["shortest_over_median_edge"] == pytest.approx(1.0)
    (tmp_path / "mesh.json").write_text(json.dumps(data))
    out = CliRunner().invoke(main, ["stats", str(tmp_path / "mesh.json")]).output
    assert [line.split()[1] for line in out.splitlines() if line.startswith("shortest_over_median_edge")] == ["0.001"]


def test_a_folded_mesh_is_an_error_naming_where(tmp_path, monkeypatch):
    """A mesh with inverted faces after smoothing and untangling is not returned: MeshFoldError says
    where (the worst face and its patch's corners); with allow_folds the mesh comes back, folded.
    The CLI fails with one line and exit code 2, writing nothing, unless --allow-folds. (The plan
    folds with a rulebook whose Figure 4 split leaves a crescent fan: tests/folding.py.)"""
    from vaultgram.errors import MeshFoldError

    domain, rules = domain_from_dict(FOLDING), rules_without_fan_check(tmp_path)
    with pytest.raises(MeshFoldError, match=r"the mesh folds: \d+ inverted face\(s\), the worst near \(-0\.") as info:
        mesh_domain(domain, rules_dir=rules)
    assert "patch with corners" in str(info.value)
    # neither a finer mesh nor a finer spacing unfolds it: the advice is to move the features
    assert "neither --target-length 0.26 nor --spacing 0.01 unfolds it: move the features" in str(info.value)
    folded = mesh_domain(domain, rules_dir=rules, allow_folds=True)
    assert mesh_stats(folded, domain)["inverted_faces"] > 0
    skip_the_fold_advice(monkeypatch)  # the command line's exit code and output, not the advice again
    path = tmp_path / "folding.json"
    path.write_text(json.dumps(FOLDING))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["mesh", str(path), "--out", str(out), "--rules", str(rules)])
    assert result.exit_code == 2 and "the mesh folds" in result.output and "Traceback" not in result.output
    assert not out.exists() or not any(out.iterdir())
    result = CliRunner().invoke(main, ["mesh", str(path), "--out", str(out), "--rules", str(rules), "--allow-folds"])
    assert result.exit_code == 0 and "warning:" in result.output and (out / "mesh.json").is_file()


def test_a_fold_that_a_finer_spacing_unfolds_says_which(tmp_path):
    """Issue 12's Acceptance: a random plan that folds gets a clear error naming the narrow place and
    the spacing it needs. At spacing 0.05 the patches round the boundary point (4.33, -1.43) fold
    (with the rulebook without the fan check, tests/folding.py); half the target length does not
    unfold them, half the spacing does, and the error says so; meshed at that spacing the plan has no
    inverted face."""
    from vaultgram.errors import MeshFoldError

    domain, rules = domain_from_dict(FOLDING_AT_COARSE_SPACING), rules_without_fan_check(tmp_path)
    with pytest.raises(MeshFoldError, match=r"this close together: mesh with --spacing 0\.025 or less \(") as info:
        mesh_domain(domain, 0.05, rules_dir=rules)
    assert "the worst near (4.2" in str(info.value)
    assert mesh_stats(mesh_domain(domain, 0.025, rules_dir=rules))["inverted_faces"] == 0
