"""Form finding on meshed examples (paper §5): compression only, equilibrium, reactions, zmax."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from vaultgram.cli import main
from vaultgram.domain import load_domain
from vaultgram.formfinding.supports import support_vertices
from vaultgram.pipeline import form_find, mesh_domain

from paths import EXAMPLES

CASES = ["quad_with_hole.json", "l_shape.json", "square_point_loads.json"]


@pytest.fixture(scope="module", params=CASES)
def network(request):
    domain = load_domain(EXAMPLES / request.param)
    mesh = mesh_domain(domain, 0.02)
    supports = support_vertices(mesh.vertices, mesh.faces, domain.supports, domain)
    loads = {int(v): 5.0 for v in np.flatnonzero(mesh.feature)}
    return mesh, form_find(mesh.vertices, mesh.faces, supports, zmax=3.0, point_loads=loads or None)


def test_horizontal_equilibrium_within_tolerance_and_compression_only(network):
    _, tn = network
    assert tn.summary["max_angle_deg"] < 0.5
    assert np.all(tn.q > 0)


def test_vertical_equilibrium_and_reactions(network):
    _, tn = network
    total = tn.summary["total_load"]
    assert tn.summary["vertical_residual"] < 1e-8 * total
    assert abs(tn.reactions[:, 2].sum() - total) < 1e-9 * total
    assert abs(tn.vertices[:, 2].max() - 3.0) < 1e-6
    assert np.all(tn.vertices[~tn.anchors, 2] > 0)  # a vault above its supports


def test_point_features_carry_their_point_loads(network):
    mesh, tn = network
    features = set(np.flatnonzero(mesh.feature).tolist())
    at_features = [k for k, v in enumerate(tn.vertex_ids.tolist()) if v in features]
    selfweight_only = np.delete(tn.loads, at_features)
    for k in at_features:  # the point load on top of the feature vertex's own self-weight
        assert tn.loads[k] > 5.0 > selfweight_only.max()


def test_holes_are_open_by_default():
    domain = load_domain(EXAMPLES / "quad_with_hole.json")
    mesh = mesh_domain(domain, 0.02)
    supports = support_vertices(mesh.vertices, mesh.faces, None, domain)
    radius = np.hypot(*(mesh.vertices[supports] - 5).T)
    assert radius.min() > 4.9  # only the outer square, none on the hole of radius 2


def test_formfind_cli_is_deterministic_and_writes_everything(tmp_path):
    outs = []
    for k in range(2):
        out = tmp_path / f"run{k}"
        result = CliRunner().invoke(main, ["formfind", str(EXAMPLES / "quad_with_hole.json"), "--out", str(out),
                                           "--zmax", "3"])
        assert result.exit_code == 0, result.output
        outs.append(out)
    names = ["form.json", "force.json", "thrust.json", "thrust.obj", "summary.json"]
    for name in names:
        assert (outs[0] / name).read_bytes() == (outs[1] / name).read_bytes()
    summary = json.loads((outs[0] / "summary.json").read_text())
    assert summary["max_angle_deg"] < 0.5 and abs(summary["zmax"] - 3) < 1e-6


def test_formfind_cli_bad_inputs_exit_2_without_output(tmp_path):
    mesh = tmp_path / "mesh.json"
    mesh.write_text(json.dumps({"vertices": [[0, 0], [1, 0], [1, 1]], "faces": [[0, 1, 7]]}))
    result = CliRunner().invoke(main, ["formfind", str(mesh), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2 and "valid vertex indices" in result.output
    supports = tmp_path / "supports.json"
    supports.write_text(json.dumps({"polylines": [[[50, 50], [60, 50]]]}))
    result = CliRunner().invoke(main, ["formfind", str(EXAMPLES / "l_shape.json"), "--out", str(tmp_path / "out"),
                                       "--supports", str(supports)])
    assert result.exit_code == 2 and "nothing bears thrust" in result.output
    assert not (tmp_path / "out").exists()
