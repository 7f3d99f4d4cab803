"""The form diagram (§5): fully supported edges removed, corners dropped, opening faces added."""

from __future__ import annotations

import numpy as np
from formfinding.cases import assert_network_ok

from vaultgram.formfinding.formdiagram import form_diagram
from vaultgram.geometry.meshes import grid_index, grid_mesh
from vaultgram.pipeline import form_find


def test_grid_form_diagram_counts():
    v, f = grid_mesh(10)
    form = form_diagram(v, f)
    assert form.n_vertices == 121 - 4          # corners deleted
    assert form.n_edges == 220 - 40            # supported boundary edges removed
    assert form.n_faces == 100 and form.loaded.all()     # corner quads became triangles
    assert sum(len(fc) == 3 for fc in form.faces) == 4
    assert form.anchors.sum() == 40 - 4
    assert form.C.shape == (180, 117)
    assert np.allclose(form.C @ np.ones(117), 0)
    kept = form_diagram(v, f, update_boundaries=False)
    assert kept.n_vertices == 121 and kept.n_edges == 220 and kept.active.sum() == 180

def test_partially_supported_grid_has_run_openings():
    """Supports on two opposite sides: the two free sides are runs between supports (barrel vault)."""
    v, f = grid_mesh(10)
    sup = [grid_index(0, j, 10) for j in range(11)] + [grid_index(10, j, 10) for j in range(11)]
    form = form_diagram(v, f, supports=sup)
    assert (~form.loaded).sum() == 2
    for op in form.opening_faces:
        assert form.anchors[op[0]] and form.anchors[op[-1]] and not form.anchors[list(op[1:-1])].any()
    tn = form_find(v, f, supports=sup, zmax=3.0, sag=0.1)
    assert_network_ok(tn)
