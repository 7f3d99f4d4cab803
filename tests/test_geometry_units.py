"""Geometry stage parts (paper §3.2): edge groups, densities, discrete Coons patches, resampling,
constrained Laplacian smoothing."""

from __future__ import annotations

import json

import numpy as np
import pytest

from vaultgram.domain import load_domain
from vaultgram.errors import VaultgramError
from vaultgram.geometry.meshes import corner_arrays, grid_mesh
from vaultgram.geometry.polylines import project_to_polyline, resample_polyline
from vaultgram.meshing.coons import coons_grid, grid_faces
from vaultgram.meshing.densities import DensitySpec, densities_from_dict, group_counts, load_densities
from vaultgram.meshing.layout import edge_groups
from vaultgram.meshing.quadmesh import SlideConstraint
from vaultgram.meshing.smoothing import laplacian_smooth
from vaultgram.meshing.untangle import untangle
from vaultgram.pipeline import decompose

from paths import ARCHITECTURE, EXAMPLES


@pytest.fixture(scope="module")
def qwh_layout():
    return edge_groups(decompose(load_domain(EXAMPLES / "quad_with_hole.json")))


@pytest.fixture(scope="module")
def pillow_layout():
    path = ARCHITECTURE / "rv_pillow_pattern.json"
    if not path.is_file():
        pytest.skip("shared architecture data not found")
    return edge_groups(decompose(load_domain(path)))


# ---------------------------------------------------------------------------------------------
# Edge groups
# ---------------------------------------------------------------------------------------------


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


def test_pillow_poles_are_the_centre_singularity(pillow_layout):
    lay = pillow_layout
    graph = lay.decomposition.graph
    assert [p.pole is not None for p in lay.patterns] == [True] * 3
    poles = {p.corners[p.pole] for p in lay.patterns}
    assert len(poles) == 1 and graph.node_type(poles.pop()) == "Singularity"
    for pat in lay.patterns:  # the two sides at the pole share a group; the third side is free
        k = pat.pole
        assert lay.group_of[pat.sides[k - 1][0]] == lay.group_of[pat.sides[k][0]]


# ---------------------------------------------------------------------------------------------
# Densities
# ---------------------------------------------------------------------------------------------


def test_counts_follow_target_length(qwh_layout):
    diag = qwh_layout.decomposition.disc.domain.diagonal
    c1 = group_counts(qwh_layout, target_length=0.05 * diag)
    c2 = group_counts(qwh_layout, target_length=0.025 * diag)
    assert (c1 >= 1).all()
    assert np.allclose(c2 / c1, 2, atol=0.5)
    for g, c in zip(qwh_layout.groups, c2):
        assert c == max(1, round(g.mean_length / (0.025 * diag)))
    cmax = group_counts(qwh_layout, DensitySpec(length_mode="max"), target_length=0.025 * diag)
    assert (cmax >= c2).all()


def test_designer_counts_regions_and_minimum(qwh_layout):
    spec = DensitySpec(target_length=100.0, min_count=3, groups={"0": 7, 1: {"length": 0.5}})
    c = group_counts(qwh_layout, spec)
    assert c[0] == 7
    assert c[1] == max(3, round(qwh_layout.groups[1].mean_length / 0.5))
    rest = np.delete(c, [0, 1])  # huge target length: the minimum, or more where a side is curved
    assert rest.min() == 3 and (rest >= 3).all()


def test_curved_boundary_sides_get_enough_subdivisions(qwh_layout):
    """The chord constraint (CHORD_TOLERANCE): a curved boundary side resampled at its group's count
    stays within the tolerance of the domain's ring, even for a huge target length."""
    from vaultgram.geometry.polylines import chord_deviation, resample_polyline
    from vaultgram.meshing.densities import CHORD_TOLERANCE
    from vaultgram.meshing.layout import kept_points, side_anchors

    c = group_counts(qwh_layout, target_length=100.0)
    disc = qwh_layout.decomposition.disc
    keep = kept_points(disc)
    curved = 0
    for side in qwh_layout.sides:
        if side.boundary and len(side.polyline) > 2:
            n = int(c[qwh_layout.group_of[side.id]])
            pts, _ = resample_polyline(side.polyline, n, side_anchors(side, keep))
            assert chord_deviation(side.polyline, pts) <= CHORD_TOLERANCE * disc.domain.diagonal
            curved += chord_deviation(side.polyline, side.polyline[[0, -1]]) > 0
    assert curved > 0  # the hole's sides are curved
    # a region covering the whole domain sets every group
    region = DensitySpec(regions=((np.array([[-1, -1], [11, -1], [11, 11], [-1, 11.0]]), {"count": 5}),))
    assert (group_counts(qwh_layout, region) == 5).all()
    # a region covering nothing changes nothing
    away = DensitySpec(regions=((np.array([[50, 50], [51, 50], [51, 51.0]]), {"count": 5}),))
    assert (group_counts(qwh_layout, away) == group_counts(qwh_layout)).all()


def test_density_file(tmp_path, qwh_layout):
    path = tmp_path / "d.json"
    path.write_text(json.dumps({"target_length": 1.0, "groups": {"2": 9},
                                "regions": [{"polygon": [[0, 0], [1, 0], [0, 1]], "length": 0.1}]}))
    spec = load_densities(path)
    assert spec.target_length == 1.0 and spec.groups == {"2": 9} and len(spec.regions) == 1
    assert group_counts(qwh_layout, spec)[2] == 9


@pytest.mark.parametrize(
    "data, message",
    [
        ({"groups": {"x": 3}}, "integer"),
        ({"groups": {"99": 3}}, "groups 0 to"),
        ({"groups": {"0": 0}}, "positive integer"),
        ({"groups": {"0": {"count": 2, "length": 1}}}, "count or a length"),
        ({"regions": [{"polygon": [[0, 0], [1, 1]], "count": 2}]}, "at least 3"),
        ({"target_length": -1}, "positive"),
        ({"colour": "red"}, "unknown key"),
    ],
)
def test_bad_densities_raise_clear_errors(qwh_layout, data, message):
    with pytest.raises(VaultgramError, match=message):
        group_counts(qwh_layout, densities_from_dict(data))


def test_bad_target_length(qwh_layout):
    with pytest.raises(VaultgramError, match="target length"):
        group_counts(qwh_layout, target_length=0.0)


# ---------------------------------------------------------------------------------------------
# Discrete Coons patches and resampling
# ---------------------------------------------------------------------------------------------


def _lin(a, b, n):
    return np.linspace(a, b, n + 1)


def test_coons_reproduces_bilinear_patch():
    c0, c1, c2, c3 = map(np.array, ([0.0, 0.0], [4.0, 0.5], [5.0, 3.0], [-0.5, 2.0]))
    m, n = 5, 3
    grid = coons_grid(_lin(c0, c1, m), _lin(c1, c2, n), _lin(c3, c2, m), _lin(c0, c3, n))
    u = np.linspace(0, 1, m + 1)[:, None, None]
    v = np.linspace(0, 1, n + 1)[None, :, None]
    bilinear = (1 - u) * (1 - v) * c0 + u * (1 - v) * c1 + u * v * c2 + (1 - u) * v * c3
    assert np.allclose(grid, bilinear)


def test_coons_keeps_curved_boundaries_exactly():
    t = np.linspace(0, np.pi, 9)
    bottom = np.column_stack([t, 0.3 * np.sin(t)])
    top = bottom + [0, 2.0]
    left = _lin(bottom[0], top[0], 4)
    right = _lin(bottom[-1], top[-1], 4)
    grid = coons_grid(bottom, right, top, left)
    assert np.array_equal(grid[:, 0], bottom) and np.array_equal(grid[:, -1], top)
    assert np.array_equal(grid[0], left) and np.array_equal(grid[-1], right)
    with pytest.raises(ValueError):
        coons_grid(bottom, right, top[:-1], left)


def test_triangle_pattern_fans_around_pole():
    ids = np.arange(4 * 3).reshape(4, 3)
    ids[0, :] = 0  # column 0 collapsed to the pole
    quads, tris = grid_faces(ids, pole=True)
    assert len(quads) == 2 * 2 and len(tris) == 2  # 3 x 2 cells, the first column triangles
    assert (tris[:, 0] == 0).all() and not np.isin(0, quads)


def test_resample_hits_anchors_and_ends():
    poly = np.array([[0, 0], [1, 0], [2, 0], [2, 1], [2, 2.0]])
    pts, hit = resample_polyline(poly, 6, anchors=[2])
    assert len(pts) == 7 and hit == [3]
    assert np.allclose(pts[3], [2, 0]) and np.allclose(pts[0], poly[0]) and np.allclose(pts[-1], poly[-1])
    pts, hit = resample_polyline(poly, 1, anchors=[2])  # not enough subdivisions: anchors ignored
    assert hit == [] and len(pts) == 2
    pts, _ = resample_polyline(poly, 4)
    assert np.allclose(np.hypot(*np.diff(pts, axis=0).T), 1.0)


# ---------------------------------------------------------------------------------------------
# Smoothing
# ---------------------------------------------------------------------------------------------


def test_projection_onto_polyline():
    poly = np.array([[0, 0], [2, 0], [2, 2.0]])
    p = np.array([[1, 0.5], [3, 1], [-1, -1], [2.5, 3]])
    assert np.allclose(project_to_polyline(p, poly), [[1, 0], [2, 1], [0, 0], [2, 2]])
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1.0]])
    assert np.allclose(project_to_polyline(np.array([[-0.2, 0.5]]), square, closed=True), [[0, 0.5]])


def test_smoothing_keeps_fixed_and_slides_on_boundary():
    v, f = grid_mesh(6)
    rng = np.random.default_rng(1)
    inner = (v[:, 0] > 0) & (v[:, 0] < 6) & (v[:, 1] > 0) & (v[:, 1] < 6)
    noisy = v.copy()
    noisy[inner, :2] += rng.uniform(-0.3, 0.3, (inner.sum(), 2))
    bottom = np.flatnonzero((v[:, 1] == 0) & (v[:, 0] > 0) & (v[:, 0] < 6))
    noisy[bottom, 0] += rng.uniform(-0.3, 0.3, len(bottom))
    corners = np.isin(np.arange(len(v)), [0, 6, 42, 48])
    fixed = corners | ((~inner) & ~np.isin(np.arange(len(v)), bottom))
    c = SlideConstraint(bottom, np.array([[0, 0], [6, 0.0]]))
    out = laplacian_smooth(noisy, f, 200, fixed, [c])
    assert np.array_equal(out[fixed], noisy[fixed])
    assert np.allclose(out[bottom, 1], 0)  # stayed on the boundary
    assert np.allclose(out[:, :2], v[:, :2], atol=1e-3)  # the grid is the fixed point


def _min_scaled_jacobian(x, faces):
    _, u, v, p = corner_arrays(faces)
    e1, e2 = x[v, :2] - x[u, :2], x[p, :2] - x[u, :2]
    return float(((e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]) / (np.hypot(*e1.T) * np.hypot(*e2.T))).min())


def test_untangle_repairs_folded_faces_and_leaves_good_meshes_alone():
    """Two interior vertices of a 6 x 6 grid dragged across their neighbours (four inverted faces, a
    fold Laplacian smoothing keeps next to a concave boundary): untangle brings every corner back to
    a positive scaled Jacobian, moves no fixed vertex, keeps the sliding ones on their line, and
    returns a mesh that is already good unchanged."""
    v, f = grid_mesh(6)
    on_boundary = (v[:, 0] % 6 == 0) | (v[:, 1] % 6 == 0)
    bottom = np.flatnonzero((v[:, 1] == 0) & (v[:, 0] > 0) & (v[:, 0] < 6))
    fixed = on_boundary & ~np.isin(np.arange(len(v)), bottom)
    slide = SlideConstraint(bottom, np.array([[0, 0], [6, 0.0]]))
    folded = v.copy()
    folded[8, :2] = [2.6, 1.9]   # vertex (1, 1) pushed past (2, 2)
    folded[9, :2] = [2.4, 0.7]   # vertex (2, 1) pushed past (3, 1)
    assert _min_scaled_jacobian(folded, f) < 0
    out = untangle(folded, f, fixed, [slide])
    assert _min_scaled_jacobian(out, f) > 0
    assert np.array_equal(out[fixed], folded[fixed])
    assert np.allclose(out[bottom, 1], 0)
    assert np.array_equal(untangle(v, f, fixed, [slide]), v)


def test_pole_of_a_triangle_is_not_on_the_boundary_when_it_can_be_inside():
    """choose_pole: a three-sided patch with an inner corner never puts its pole on the boundary
    (a boundary pole of n triangles is a boundary singularity for n >= 2), unless it is a feature."""
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
        if on_ring(pole) and not is_feature_node(dec, pole):
            assert all(on_ring(c) for c in pat.corners)


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
