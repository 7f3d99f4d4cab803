"""Thrust networks end to end: a grid with a hole in compression, outputs, determinism."""

from __future__ import annotations

import json

import numpy as np
import pytest
from formfinding.cases import assert_network_ok, holed_grid

from vaultgram.formfinding.horizontal import angle_deviations
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.io.files import write_obj
from vaultgram.pipeline import form_find


@pytest.mark.parametrize("mode", ["boundary", "all"])
def test_hole_converges_in_compression(mode):
    v, f, outer = holed_grid()
    tn = form_find(v, f, supports=outer, zmax=4.0, relax_mode=mode)
    assert_network_ok(tn)
    assert tn.summary["n_openings"] == 1
    assert abs(tn.vertices[:, 2].max() - 4.0) < 1e-6
    assert tn.force.n_vertices == tn.form.n_faces
    assert tn.force.n_edges == tn.form.n_edges
    ang = angle_deviations(tn.form.edge_vectors()[tn.force.form_edge], tn.force.edge_vectors())
    assert ang.max() < 0.5

def test_outputs_are_json_and_obj(tmp_path):
    v, f = grid_mesh(4)
    tn = form_find(v, f, zmax=1.0)
    for obj in (tn.to_json(), tn.form.to_json(), tn.force.to_json()):
        json.loads(json.dumps(obj))
    path = tmp_path / "thrust.obj"
    write_obj(path, tn.vertices, tn.faces)
    lines = path.read_text().splitlines()
    assert sum(ln.startswith("v ") for ln in lines) == tn.vertices.shape[0]
    assert sum(ln.startswith("f ") for ln in lines) == len(tn.faces)
    write_obj(tmp_path / "form.obj", tn.form.xy, tn.form.loaded_faces)
    assert "max angle deviation" in tn.summary_text()

def test_deterministic():
    v, f, outer = holed_grid(12, 4, 8)
    a = form_find(v, f, supports=outer, zmax=2.0)
    b = form_find(v, f, supports=outer, zmax=2.0)
    for name in ("vertices", "q", "forces", "loads", "reactions", "edges"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert np.array_equal(a.force.xy, b.force.xy)
