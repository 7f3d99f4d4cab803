"""Delaunay triangulation of the domain (paper §3.1): tiling, boundary edges, kinds, Euler."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.errors import DomainError
from vaultgram.topology.discretise import discretise
from vaultgram.topology.triangulation import triangulate

from paths import ARCHITECTURE

PLANS = sorted(ARCHITECTURE.glob("*.json")) if ARCHITECTURE.is_dir() else []
SPACINGS = [0.01, 0.0125, 0.015, 0.0175, 0.02, 0.025, 0.03, 0.035, 0.04, 0.045, 0.05]


def check_triangulation(tri):
    disc, d = tri.disc, tri.disc.domain
    T, P = tri.triangles, tri.points
    # counter-clockwise faces
    a, b, c = P[T[:, 0]], P[T[:, 1]], P[T[:, 2]]
    area = 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    assert (area > 0).all()
    # faces tile the domain
    assert area.sum() == pytest.approx(d.area, rel=1e-9)
    # every boundary segment is a triangle edge, with the triangle on the domain side
    directed = {(int(x), int(y)) for t in T for x, y in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
    for i, j in disc.segments():
        assert (int(i), int(j)) in directed
    # neighbours are symmetric and kinds are neighbour counts
    nb = tri.neighbours
    for t in range(len(T)):
        for k in range(3):
            u = nb[t, k]
            if u >= 0:
                assert t in nb[u]
                assert set(T[t]) - {T[t, k]} <= set(T[u])
    assert (tri.kind == (nb >= 0).sum(axis=1)).all()
    # Euler characteristic of a disc with holes
    V = len(np.unique(T))
    E = len(tri.edges())
    assert V - E + len(T) == 1 - len(d.holes)
    assert V == len(P)  # every sample point is used
    # circumcentres are equidistant from the three vertices
    r = np.stack([np.hypot(*(P[T[:, k]] - tri.circumcentres).T) for k in range(3)], axis=1)
    np.testing.assert_allclose(r, np.repeat(tri.circumradii[:, None], 3, axis=1), rtol=1e-6)


@pytest.mark.parametrize("name", ["quad_with_hole", "l_shape"])
@pytest.mark.parametrize("spacing", SPACINGS)
def test_examples(examples_dir, name, spacing):
    d = load_domain(examples_dir / f"{name}.json")
    check_triangulation(triangulate(discretise(d, spacing)))


@pytest.mark.parametrize("path", PLANS or [None], ids=lambda p: p.stem if p else "absent")
def test_architecture(path):
    if path is None:
        pytest.skip(f"shared architecture data not found at {ARCHITECTURE}")
    d = load_domain(path)
    check_triangulation(triangulate(discretise(d, 0.02)))


def test_cocircular_faces_share_a_cell():
    # an evenly sampled rectangle: many cocircular quadruples, one cell per circle
    d = domain_from_dict({"outer": [[0, 0], [10, 0], [10, 2], [0, 2]]})
    tri = triangulate(discretise(d, 0.02))
    same = tri.cell[:, None] == tri.cell[tri.neighbours]
    dist = np.hypot(*(tri.circumcentres[:, None, :] - tri.circumcentres[tri.neighbours]).transpose(2, 0, 1))
    coincide = (tri.neighbours >= 0) & (dist < 1e-9)
    assert coincide.any()
    assert (same[coincide]).all()
    assert tri.n_cells < tri.n_faces


def test_missing_boundary_segment_is_reported():
    # a narrow slot whose two sides are closer than the spacing: Delaunay misses boundary edges
    outer = [[0, 0], [10, 0], [10, 10], [5.001, 10], [5.001, 1.3], [4.999, 1], [4.999, 10], [0, 10]]
    d = domain_from_dict({"outer": outer})
    with pytest.raises(DomainError, match=r"outer ring, vertex \d+: boundary segment .* smaller spacing"):
        triangulate(discretise(d, 0.05))


def test_curve_features_are_cut():
    d = domain_from_dict({"outer": [[0, 0], [10, 0], [10, 10], [0, 10]], "curves": [[[3, 5], [7, 5]]]})
    tri = triangulate(discretise(d, 0.02))
    c = tri.disc.curves[0]
    cut = {tuple(sorted(e)) for e in zip(c[:-1], c[1:])}
    T = tri.triangles
    for t in range(len(T)):
        for k in range(3):
            e = tuple(sorted((T[t, (k + 1) % 3], T[t, (k + 2) % 3])))
            if e in cut:
                assert tri.neighbours[t, k] == -1
    uncut = triangulate(tri.disc, cut_curves=False)
    assert (uncut.neighbours >= 0).sum() == (tri.neighbours >= 0).sum() + 2 * len(cut)


@given(
    w=st.floats(2, 20), h=st.floats(2, 20), spacing=st.floats(0.01, 0.05),
    hx=st.floats(0.3, 0.7), hy=st.floats(0.3, 0.7), hr=st.floats(0.05, 0.2),
)
@settings(max_examples=25, deadline=None)
def test_rectangle_with_hole_property(w, h, spacing, hx, hy, hr):
    r = hr * min(w, h)
    cx, cy = hx * w, hy * h
    r = min(r, 0.8 * min(cx, w - cx, cy, h - cy))
    ang = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    hole = np.stack([cx + r * np.cos(ang), cy + r * np.sin(ang)], axis=1).tolist()
    d = domain_from_dict({"outer": [[0, 0], [w, 0], [w, h], [0, h]], "holes": [hole]})
    try:
        tri = triangulate(discretise(d, spacing))
    except DomainError as e:  # only allowed failure: the spacing is too coarse for the geometry
        assert "smaller spacing" in str(e)
        return
    check_triangulation(tri)


def _regular_polygon(n, radius=10.0):
    t = 2 * np.pi * np.arange(n) / n
    return radius * np.column_stack([np.cos(t), np.sin(t)])


def _empty_circumcircles(pts, tri, rel=1e-9):
    """No point lies inside a triangle's circumcircle by more than ``rel`` of its radius."""
    from scipy.spatial import cKDTree

    from vaultgram.topology.triangulation import circumcentres

    centre, radius = circumcentres(pts, tri)
    inside = cKDTree(pts).query_ball_point(centre, radius * (1 - rel))
    return all(len(i) == 0 for i in inside)


def test_many_cocircular_points_triangulate_as_given():
    """A regular 1500-gon: one co-circular group of 1498 faces, triangulated as given (GEOS inserts the
    points without merging facets); every triangle a Delaunay one, the same triangles every time, and
    together the polygon's area."""
    from vaultgram.geometry.polygons import triangle_areas
    from vaultgram.topology import triangulation as t

    pts = _regular_polygon(1500)
    tri, area, _ = t._delaunay(pts)
    assert len(tri) == 1498 and _empty_circumcircles(pts, tri)
    assert np.array_equal(tri, t._delaunay(pts)[0]) and (triangle_areas(pts, tri) > 0).all()
    assert np.isclose(area.sum(), 0.5 * 1500 * 100 * np.sin(2 * np.pi / 1500))


def test_a_regular_polygon_of_many_sides_triangulates_and_tiles():
    """The domain of a 3000-gon: every boundary segment recovered, the faces tile it (triangulate checks)."""
    disc = discretise(domain_from_dict({"outer": _regular_polygon(3000).tolist()}), 0.02)
    tri = triangulate(disc)
    assert tri.n_faces == 2998


def test_a_missing_boundary_segment_is_recovered_by_local_refinement():
    """The slot of the test above: the midpoints of the missing segments become ring vertices until
    every boundary segment is an edge; the plan's shape is unchanged, the new vertices lie on it."""
    import shapely

    from vaultgram.topology.recovery import triangulate_recovering

    outer = [[0, 0], [10, 0], [10, 10], [5.001, 10], [5.001, 1.3], [4.999, 1], [4.999, 10], [0, 10]]
    d = domain_from_dict({"outer": outer})
    tri = triangulate_recovering(discretise(d, 0.05))
    refined = tri.disc.domain
    assert len(refined.outer) > len(d.outer)
    assert shapely.Polygon(refined.outer).symmetric_difference(shapely.Polygon(d.outer)).area < 1e-9
    assert np.isclose(tri.areas.sum(), d.area)
    with pytest.raises(DomainError, match="not an edge of the Delaunay triangulation"):
        triangulate_recovering(discretise(d, 0.05), rounds=0)


def test_a_plan_that_needs_no_refinement_keeps_its_triangulation(examples_dir):
    from vaultgram.topology.recovery import triangulate_recovering

    disc = discretise(load_domain(examples_dir / "fig7_curves.json"), 0.03)
    tri = triangulate_recovering(disc)
    assert tri.disc is disc and np.array_equal(tri.triangles, triangulate(disc).triangles)


@given(st.lists(st.lists(st.integers(0, 40), min_size=3, max_size=3, unique=True), max_size=30),
       st.sampled_from([np.int32, np.int64]))
def test_undirected_edges_are_each_triangle_side_once_sorted(rows, dtype):
    """The triangles' sides as (min, max) pairs, each once, in lexicographic order, in the triangles'
    integer type (the keys ``min * n + max`` the function sorts stand for exactly these pairs)."""
    from vaultgram.topology.triangulation import _undirected_edges

    tri = np.array(rows, dtype=dtype).reshape(-1, 3)
    edges = _undirected_edges(tri)
    sides = sorted({tuple(sorted((int(t[i]), int(t[(i + 1) % 3])))) for t in tri for i in range(3)})
    assert edges.dtype == dtype and edges.shape == (len(sides), 2)
    assert [tuple(e) for e in edges.tolist()] == sides
