"""Polygon meshes in space (vaultgram.geometry.surfaces): vector areas measured by blocks of faces."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.geometry import surfaces
from vaultgram.geometry.surfaces import area_vectors


def newell(x: np.ndarray, faces) -> np.ndarray:
    """Each face's vector area as Newell's sum, corner by corner in order (the reference bits)."""
    out = np.zeros((len(faces), 3))
    for f, face in enumerate(faces):
        total = np.zeros(3)
        for u, v in zip(face, face[1:] + face[:1]):
            a, b = x[u], x[v]
            total = total + np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])
        out[f] = 0.5 * total
    return out


@pytest.mark.parametrize("block", [1, 2, 5, 1 << 16])
def test_vector_areas_by_blocks_are_the_bits_of_each_faces_sum(monkeypatch, block):
    """Triangles, quads, larger faces, an empty face; blocks that end inside runs of faces of one size."""
    monkeypatch.setattr(surfaces, "FACE_BLOCK", block)
    rng = np.random.default_rng(block)
    x = rng.normal(size=(60, 3)) * 10.0 ** rng.integers(-3, 4, (60, 1))
    faces = [tuple(rng.choice(60, size, replace=False).tolist()) for size in rng.integers(3, 8, 23)] + [()]
    assert area_vectors(x, faces).tobytes() == newell(x, faces).tobytes()
