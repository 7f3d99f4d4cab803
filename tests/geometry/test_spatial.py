"""Spatial queries without scipy (vaultgram.geometry.spatial): GEOS's Delaunay triangles mapped to the
input's indices, and the grid hash's pairs within a distance, each against its definition or a
brute-force reference."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial import Delaunay

from vaultgram.geometry import spatial
from vaultgram.geometry.spatial import ILLEGAL, close_pairs, delaunay, nearest_within, pairs_within

SETTINGS = settings(max_examples=40, deadline=None)


def _circumcircles(pts: np.ndarray, tri: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Centres and radii of the triangles' circumcircles."""
    a, b, c = pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]]
    d = 2.0 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    bb, cc = ((b - a) ** 2).sum(axis=1), ((c - a) ** 2).sum(axis=1)
    ux = ((c[:, 1] - a[:, 1]) * bb - (b[:, 1] - a[:, 1]) * cc) / d
    uy = ((b[:, 0] - a[:, 0]) * cc - (c[:, 0] - a[:, 0]) * bb) / d
    return a + np.column_stack([ux, uy]), np.hypot(ux, uy)


def _inside_circumcircle(a, b, c, d) -> bool:
    """Whether ``d`` lies inside the circumcircle of the counter-clockwise triangle ``a b c`` by more
    than ``ILLEGAL`` of the in-circle determinant's permanent, in exact rational arithmetic."""
    rows = [(Fraction(p[0]) - Fraction(d[0]), Fraction(p[1]) - Fraction(d[1])) for p in (a, b, c)]
    (ax, ay), (bx, by), (cx, cy) = rows
    al, bl, cl = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    terms = [al * bx * cy, -al * cx * by, bl * cx * ay, -bl * ax * cy, cl * ax * by, -cl * bx * ay]
    return sum(terms) > Fraction(ILLEGAL) * sum(abs(t) for t in terms)


def _check_delaunay(pts: np.ndarray, tri: np.ndarray) -> None:
    """The properties of a Delaunay triangulation of distinct points: counter-clockwise triangles in
    canonical order, no site inside any circumcircle beyond round-off (``ILLEGAL``, checked in
    rationals), the triangles tile the convex hull (their areas sum to its area) and
    Euler's formula on it: ``2 n - 2 - h`` triangles, ``h`` the sites on the hull's boundary."""
    a, b, c = pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]]
    area = 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    assert (area > 0).all()
    assert (tri[:, 0] < tri[:, 1:].min(axis=1)).all() and (np.diff(tri[:, 0]) >= 0).all()
    centre, radius = _circumcircles(pts, tri)
    dist = np.sqrt(((pts[None, :, :] - centre[:, None, :]) ** 2).sum(axis=2))
    for t, k in zip(*np.nonzero(dist < radius[:, None] * (1 + 1e-6))):
        assert k in tri[t] or not _inside_circumcircle(*pts[tri[t]], pts[k])
    hull = shapely.convex_hull(shapely.multipoints(pts))
    assert area.sum() == pytest.approx(hull.area, rel=1e-9)
    on_hull = shapely.dwithin(shapely.points(pts), hull.exterior, 1e-12 * np.ptp(pts, axis=0).max()).sum()
    assert len(tri) == 2 * len(pts) - 2 - on_hull


@st.composite
def sites(draw, far: bool):
    """Distinct plan points in general position: random floats in a box of random size, near the
    origin, or (``far``) up to 10^4 of its sizes away (the stages work near the origin of a local
    frame)."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    n, scale = draw(st.integers(4, 60)), 10.0 ** rng.uniform(-3, 3)
    return scale * (rng.uniform(-1e4, 1e4, size=2) * far + rng.random((n, 2)))


@SETTINGS
@given(sites(far=False))
def test_delaunay_of_points_in_general_position(pts):
    """Every property, and the same triangles as qhull's (unique in general position)."""
    tri = delaunay(pts)
    _check_delaunay(pts, tri)
    assert {tuple(t) for t in np.sort(tri, axis=1)} == {tuple(t) for t in np.sort(Delaunay(pts).simplices, axis=1)}


@SETTINGS
@given(sites(far=True))
def test_delaunay_of_points_far_from_the_origin(pts):
    """Far from the origin (fewer digits left for the shape), still Delaunay to round-off."""
    _check_delaunay(pts, delaunay(pts))


@SETTINGS
@given(st.integers(2, 9), st.integers(2, 9), st.floats(0.01, 100.0))
def test_delaunay_of_a_lattice(nx, ny, step):
    """A lattice: every square's four corners are co-circular, GEOS picks a diagonal each; still
    empty circumcircles (to round-off), the hull tiled, Euler's count."""
    pts = step * np.stack(np.meshgrid(np.arange(nx), np.arange(ny)), axis=-1).reshape(-1, 2).astype(float)
    tri = delaunay(pts)
    _check_delaunay(pts, tri)
    assert np.array_equal(tri, delaunay(pts))  # deterministic


def test_delaunay_of_a_regular_polygon_of_many_sides():
    """1,500 co-circular points: one diagonal set (the moved points'), 1,498 triangles, all with the
    polygon's circumcircle."""
    t = 2 * np.pi * np.arange(1500) / 1500
    pts = 10.0 * np.column_stack([np.cos(t), np.sin(t)])
    tri = delaunay(pts)
    assert len(tri) == 1498
    centre, radius = _circumcircles(pts, tri)
    assert np.allclose(centre, 0.0, atol=1e-6) and np.allclose(radius, 10.0)


@pytest.mark.parametrize("kind", ["polygon", "lattice", "random"])
def test_delaunay_is_the_same_whichever_library_triangulates(kind, monkeypatch):
    """Below QHULL_FROM sites GEOS triangulates, from it qhull: the moved sites have one Delaunay
    triangulation, so both give the same triangles, also where the points as given leave a choice."""
    if kind == "polygon":
        t = 2 * np.pi * np.arange(600) / 600
        pts = np.column_stack([np.cos(t), np.sin(t)])
    elif kind == "lattice":
        pts = np.stack(np.meshgrid(np.arange(25.0), np.arange(20.0)), axis=-1).reshape(-1, 2)
    else:
        pts = np.random.default_rng(3).random((700, 2))
    by_geos = delaunay(pts)
    monkeypatch.setattr(spatial, "QHULL_FROM", 3)
    assert np.array_equal(delaunay(pts), by_geos)


def test_delaunay_of_repeated_and_too_few_points():
    """Exact repeats: the lowest index stands for them; fewer than three sites or all on a line: none."""
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 0.0], [1.0, 1.2], [0.0, 1.0]])
    tri = delaunay(pts)
    assert len(tri) == 2 and set(tri.ravel().tolist()) == {0, 1, 2, 4}
    _check_delaunay(pts[[0, 1, 2, 4]], np.searchsorted([0, 1, 2, 4], tri))
    assert delaunay(pts[:2]).shape == (0, 3)
    assert delaunay(np.column_stack([np.arange(5.0), 2.0 * np.arange(5.0)])).shape == (0, 3)


def _brute_pairs(pts: np.ndarray, qs: np.ndarray, r: float) -> set:
    """Every (query, point) pair at most ``r`` apart, by all distances."""
    d2 = ((qs[:, None, :] - pts[None, :, :]) ** 2).sum(axis=2)
    return set(zip(*(a.tolist() for a in np.nonzero(d2 <= r * r))))


@st.composite
def point_sets(draw):
    """Two sets of plan points of random sizes (either larger), clustered or spread, with exact repeats
    and points on cell borders, and a distance from 0 to beyond their extent."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    n, m = draw(st.integers(0, 80)), draw(st.integers(0, 80))
    grid = draw(st.booleans())  # on a lattice: many equal distances, points on the cells' borders
    pts = rng.integers(0, 6, size=(n, 2)) * 0.25 if grid else rng.random((n, 2)) ** 3
    qs = rng.integers(0, 6, size=(m, 2)) * 0.25 if grid else rng.random((m, 2)) ** 3
    if n and m and draw(st.booleans()):
        qs[: m // 2] = pts[rng.integers(0, n, size=m // 2)]
    r = draw(st.sampled_from([0.0, 1e-9, 0.01, 0.1, 0.25, 0.5, 2.0]))
    return pts, qs, r


@SETTINGS
@given(point_sets())
def test_pairs_within_is_the_brute_force_set(sets):
    pts, qs, r = sets
    q, p = pairs_within(pts, qs, r)
    assert set(zip(q.tolist(), p.tolist())) == _brute_pairs(pts, qs, r) and len(q) == len(set(zip(q, p)))
    assert np.array_equal(np.lexsort((p, q)), np.arange(len(q)))  # sorted by query, then point


@SETTINGS
@given(point_sets())
def test_close_pairs_is_the_brute_force_set(sets):
    pts, _, r = sets
    pairs = close_pairs(pts, r)
    assert {tuple(x) for x in pairs.tolist()} == {(i, j) for i, j in _brute_pairs(pts, pts, r) if i < j}
    assert pairs.shape == (len(pairs), 2)


@SETTINGS
@given(point_sets())
def test_nearest_within_is_the_nearest_lowest_index(sets):
    pts, qs, r = sets
    index, dist = nearest_within(pts, qs, r)
    for k, q in enumerate(qs):
        d = np.sqrt(((pts - q) ** 2).sum(axis=1))
        near = np.flatnonzero(d <= r)
        if not len(near):
            assert index[k] == -1 and dist[k] == np.inf
            continue
        assert dist[k] == d[near].min() and index[k] == near[d[near] == d[near].min()].min()


def test_queries_take_the_plan_columns_and_tiny_distances():
    """3-d rows are plan points (the first two columns); a distance far below the extent still finds
    coinciding points (the cells are at least 2^-20 of the extent)."""
    pts = np.array([[0.0, 0.0, 5.0], [1e6, 1e6, 0.0], [3.0, 4.0, 1.0]])
    q, p = pairs_within(pts, np.array([[3.0, 4.0 + 1e-12, -7.0]]), 1e-9)
    assert q.tolist() == [0] and p.tolist() == [2]
