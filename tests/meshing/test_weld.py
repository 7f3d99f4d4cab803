"""Welding the Coons patches into one mesh (paper §3.2, Figure 2g): exact welding, vertex labels."""

from __future__ import annotations

import numpy as np


def test_welding_is_exact(meshed):
    _, _, _, mesh, _ = meshed("quad_with_hole")
    used = np.zeros(mesh.n_vertices, dtype=bool)
    used[np.concatenate([np.asarray(f) for f in mesh.faces])] = True
    assert used.all()  # no duplicate or stray vertex
    x = mesh.vertices
    d = np.hypot(*(x[:, None] - x[None]).transpose(2, 0, 1))
    np.fill_diagonal(d, np.inf)
    assert d.min() > 1e-3 * mesh.info["diagonal"]  # no two vertices at one place


def test_labels(meshed):
    domain, _, _, mesh, _ = meshed("two_holes_five_points")
    assert mesh.boundary[mesh.fixed & ~mesh.feature].all()
    assert mesh.feature.sum() >= 1 and mesh.pole.sum() >= 1
    assert set(np.unique(mesh.ring[mesh.boundary])) == {0, 1, 2}
    assert (mesh.ring[~mesh.boundary] == -1).all()
    assert len(mesh.groups) == mesh.info["edge_groups"] > 0
