"""The QuadMesh value through files: JSON and OBJ round trip."""

from __future__ import annotations

import json

import numpy as np

from vaultgram.io.meshfiles import mesh_from_json, mesh_to_json, read_mesh, write_mesh
from vaultgram.meshing.quality import mesh_stats


def test_json_and_obj_round_trip(tmp_path, meshed):
    domain, _, _, mesh, stats = meshed("rv_lips_pattern")
    json_path, obj_path = write_mesh(mesh, tmp_path / "out")
    data = json.loads(json_path.read_text())
    assert len(data["vertices"][0]) == 3 and len(data["faces"]) == mesh.n_faces
    assert {"labels", "edge_groups"} <= set(data)
    back = read_mesh(json_path)
    assert np.allclose(back.vertices, mesh.vertices) and back.faces == mesh.faces
    assert (back.pole == mesh.pole).all() and (back.fixed == mesh.fixed).all()
    assert mesh_stats(back) == {k: v for k, v in stats.items() if not k.startswith("boundary_distance")}
    obj = obj_path.read_text().splitlines()
    assert sum(line.startswith("v ") for line in obj) == mesh.n_vertices
    assert sum(line.startswith("f ") for line in obj) == mesh.n_faces
    assert not list((tmp_path / "out").glob(".*tmp"))
    assert mesh_from_json(mesh_to_json(mesh)).n_faces == mesh.n_faces
