"""The patch layout (paper §3.2): atomic sides, patterns and poles, edge groups; and the patch corners
the layout starts from."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.meshing.layout import edge_groups


def test_quad_opposite_sides_share_a_group(qwh_layout):
    lay = qwh_layout
    assert len(lay.patterns) == 12
    for pat in lay.patterns:
        assert pat.pole is None
        g = [int(lay.group_of[s]) for s, _ in pat.sides]
        assert g[0] == g[2] and g[1] == g[3]
    # every side is in exactly one group, and each group is named once
    assert sorted(s for grp in lay.groups for s in grp.sides) == list(range(len(lay.sides)))
    assert lay.n_groups == len(set(lay.group_of.tolist()))


def test_shared_sides_are_stored_once(qwh_layout):
    uses = np.zeros(len(qwh_layout.sides), dtype=int)
    for pat in qwh_layout.patterns:
        for s, rev in pat.sides:
            uses[s] += 1
            side = qwh_layout.sides[s]
            assert uses[s] == 1 or rev  # the second traversal is reversed
            assert (side.boundary and uses[s] == 1) or not side.boundary
    boundary = np.array([s.boundary for s in qwh_layout.sides])
    assert (uses[boundary] == 1).all() and (uses[~boundary] == 2).all()


def test_poles_at_a_singularity_share_their_sides_group(star_layout):
    """rv_star_pattern's three-sided patches: two have their pole at a singularity, two at a reflex
    corner (the triangles of rules/corners.vgr's reflex chords, marked, meshed as three quads); the two
    sides at the pole share an edge group (Figure 3: a quad with one side collapsed), the third is free."""
    lay = star_layout
    graph = lay.decomposition.graph
    fans = [p for p in lay.patterns if p.pole is not None]
    assert sorted(graph.node_type(p.corners[p.pole]) for p in fans) == ["BoundaryVertex"] * 2 + ["Singularity"] * 2
    for pat in fans:
        k = pat.pole
        assert lay.group_of[pat.sides[k - 1][0]] == lay.group_of[pat.sides[k][0]]


def test_pole_of_a_triangle_is_not_on_the_boundary_when_it_can_be_inside():
    """choose_pole: a three-sided patch with an inner corner never puts its pole on the boundary
    (a boundary pole of n triangles is a boundary singularity for n >= 2), unless it is a feature or a
    rule marked it (a reflex corner's triangle, meshed as three quads: rules/corners.vgr)."""
    from vaultgram.domain import load_domain
    from vaultgram.meshing.layout import is_feature_node
    from vaultgram.pipeline import decompose

    from paths import ARCHITECTURE

    path = ARCHITECTURE / "rv_star_pattern.json"
    if not path.is_file():
        pytest.skip(f"{path} not found")
    dec = decompose(load_domain(path))
    lay = edge_groups(dec)
    disc = dec.disc
    on_ring = lambda n: 0 <= n < disc.n_points and disc.ring[n] >= 0  # noqa: E731
    tris = [p for p in lay.patterns if p.pole is not None]
    assert tris
    for pat in tris:
        pole = pat.corners[pat.pole]
        if on_ring(pole) and not is_feature_node(dec, pole) and dec.marked_pole(dec.patches[pat.patch]) != pole:
            assert all(on_ring(c) for c in pat.corners)


# ---------------------------------------------------------------------------------------------
# Patch corners from the topology rules (patching.vgr)
# ---------------------------------------------------------------------------------------------


def test_triangles_at_a_reflex_corner_are_merged():
    """patching.vgr, merge_triangles_at_reflex_corner: the reflex corner (5.57, 5.59) of rv_star was
    the corner of 2 quads and 2 triangles; it is now the corner of 3 patches (regular, valence 4)."""
    from vaultgram.domain import load_domain
    from vaultgram.pipeline import decompose

    from paths import ARCHITECTURE

    path = ARCHITECTURE / "rv_star_pattern.json"
    if not path.is_file():
        pytest.skip(f"{path} not found")
    dec = decompose(load_domain(path))
    steps = {r.step: r.applications for r in dec.reports}
    assert any("merge_triangles_at_reflex_corner" in str(k) for k, v in steps.items() if v)
    g = dec.graph
    for target in ([5.57, 5.59], [5.75, 10.03]):
        node = min((c for p in dec.patches for c in p.corners),
                   key=lambda n: np.hypot(*(np.asarray(g.get(n, "pos")) - target)))
        assert sum(node in p.corners for p in dec.patches) == 3


def test_triangle_with_a_smooth_boundary_corner_becomes_a_quad():
    """patching.vgr, spread_boundary_pole(_back): on rolex two pairs of neighbouring singularities
    rebranch to one point of a hole, (5.33, 8.07) and (8.47, 6.87), each the corner of a triangle and
    of 3 patches; one rebranch of each pair moves to the next free boundary point (forward at the
    first, backward at the second, where the forward point is already a corner), so both points and
    their new neighbours are corners of 2 patches, as a regular point of a smooth stretch."""
    from vaultgram.domain import load_domain
    from vaultgram.pipeline import decompose

    from paths import ARCHITECTURE

    path = ARCHITECTURE / "rolex_learning_centre.json"
    if not path.is_file():
        pytest.skip(f"{path} not found")
    dec = decompose(load_domain(path))
    applied = {str(r.step): r.applications for r in dec.reports}
    assert applied["spread_boundary_pole all"] == applied["spread_boundary_pole_back all"] == 1
    g = dec.graph
    disc = dec.disc
    ring_corners = {c for p in dec.patches for c in p.corners if 0 <= c < disc.n_points and disc.ring[c] >= 0}
    for target in ([5.331, 8.067], [8.466, 6.866]):
        node = min(ring_corners, key=lambda n: np.hypot(*(np.asarray(g.get(n, "pos")) - target)))
        assert np.hypot(*(np.asarray(g.get(node, "pos")) - target)) < 0.01
        assert sum(node in p.corners for p in dec.patches) == 2
    # on the hole's smooth stretches every patch corner is the corner of exactly 2 patches
    hole = disc.ring[min(ring_corners, key=lambda n: np.hypot(*(np.asarray(g.get(n, "pos")) - [5.331, 8.067])))]
    for c in ring_corners:
        if disc.ring[c] == hole and abs(disc.turning[c]) < 30:
            assert sum(c in p.corners for p in dec.patches) == 2
