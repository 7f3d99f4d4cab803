"""Patches (paper §3.1, Figure 2f): ordered corners, sides joining them, each shared side walked once each way."""

from __future__ import annotations

from collections import Counter

import numpy as np

from vaultgram.domain import load_domain
from vaultgram.pipeline import decompose

from paths import EXAMPLES


def test_patches_have_ordered_corners_and_connected_sides():
    dec = decompose(load_domain(EXAMPLES / "quad_with_hole.json"), 0.02)
    g = dec.graph
    for p in dec.patches:
        assert p.area() > 0  # counter-clockwise
        for i, side in enumerate(p.sides):
            assert np.allclose(side[0], g.get(p.corners[i], "pos"))
            assert np.allclose(side[-1], g.get(p.corners[(i + 1) % p.n_sides], "pos"))


def test_shared_sides_are_traversed_once_each_way():
    dec = decompose(load_domain(EXAMPLES / "l_shape.json"), 0.02)
    uses = Counter(he for p in dec.patches for side in p.side_edges for he in side)
    assert max(uses.values()) == 1
    interior_edges = {e for (e, _) in uses if dec.graph.edge_type(e) != "Boundary"}
    for e in interior_edges:
        u, v = dec.graph.ends(e)
        assert uses[(e, u)] == uses[(e, v)] == 1
