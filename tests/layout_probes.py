"""Probes the layout and mesh tests share: the decomposition's node at a point, the mesh faces at a
polygon corner (a corner's face count is its valence on the boundary less one, issue 12)."""

from __future__ import annotations

import numpy as np


def node_at(graph, at, tol: float = 1e-9) -> int:
    """The one non-patch node of the decomposition ``graph`` within ``tol`` of the point ``at``."""
    (n,) = [n for n in graph.nodes()
            if graph.node_type(n) != "Patch" and np.allclose(graph.get(n, "pos"), at, atol=tol)]
    return n


def faces_at(mesh, at, tol: float = 1e-9) -> int:
    """The number of faces at the mesh vertex nearest ``at``, which lies within ``tol`` of it (a fixed
    polygon corner)."""
    x = np.asarray(mesh.vertices, dtype=float)[:, :2]
    v = int(np.hypot(*(x - np.asarray(at)).T).argmin())
    assert np.hypot(*(x[v] - np.asarray(at))) < tol
    return sum(v in face for face in mesh.faces)
