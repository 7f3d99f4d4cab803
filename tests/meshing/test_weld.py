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


def test_the_welded_faces_keep_their_corner_arrays(meshed):
    """The welded mesh's faces are a Faces whose kept corner arrays are those of its tuples (every stage
    after welding reads them instead of flattening the faces again), read-only, and survive a pickle."""
    import pickle

    from vaultgram.geometry.meshes import Faces, corner_arrays

    _, _, _, mesh, _ = meshed("two_holes_five_points")   # quads and the triangles of poles
    assert isinstance(mesh.faces, Faces) and {len(f) for f in mesh.faces} == {3, 4}
    kept, again = corner_arrays(mesh.faces), corner_arrays(list(mesh.faces))
    assert all(np.array_equal(a, b) and not a.flags.writeable for a, b in zip(kept, again))
    back = pickle.loads(pickle.dumps(mesh.faces))
    assert back == mesh.faces and all(np.array_equal(a, b) for a, b in zip(corner_arrays(back), kept))


def test_labels(meshed):
    domain, _, _, mesh, _ = meshed("two_holes_five_points")
    assert mesh.boundary[mesh.fixed & ~mesh.feature].all()
    assert mesh.feature.sum() >= 1 and mesh.pole.sum() >= 1
    assert set(np.unique(mesh.ring[mesh.boundary])) == {0, 1, 2}
    assert (mesh.ring[~mesh.boundary] == -1).all()
    assert len(mesh.groups) == mesh.info["edge_groups"] > 0
