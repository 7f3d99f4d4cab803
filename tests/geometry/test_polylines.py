"""The polyline kernel (vaultgram.geometry.polylines): resampling, projection, lengths, angles, distances."""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.geometry.polylines import (
    arc_lengths,
    arc_parameters,
    chord_deviation,
    halfway_point,
    locate_on_polyline,
    point_at_length,
    polyline_hausdorff,
    polyline_length,
    project_to_polyline,
    resample_polyline,
    straight_spans,
    turning_angles,
)


def test_resample_hits_anchors_and_ends():
    poly = np.array([[0, 0], [1, 0], [2, 0], [2, 1], [2, 2.0]])
    pts, hit = resample_polyline(poly, 6, anchors=[2])
    assert len(pts) == 7 and hit == [3]
    assert np.allclose(pts[3], [2, 0]) and np.allclose(pts[0], poly[0]) and np.allclose(pts[-1], poly[-1])
    pts, hit = resample_polyline(poly, 1, anchors=[2])  # not enough subdivisions: anchors ignored
    assert hit == [] and len(pts) == 2
    pts, _ = resample_polyline(poly, 4)
    assert np.allclose(np.hypot(*np.diff(pts, axis=0).T), 1.0)


def test_projection_onto_polyline():
    poly = np.array([[0, 0], [2, 0], [2, 2.0]])
    p = np.array([[1, 0.5], [3, 1], [-1, -1], [2.5, 3]])
    assert np.allclose(project_to_polyline(p, poly), [[1, 0], [2, 1], [0, 0], [2, 2]])
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1.0]])
    assert np.allclose(project_to_polyline(np.array([[-0.2, 0.5]]), square, closed=True), [[0, 0.5]])


# ---------------------------------------------------------------------------------------------
# Properties
# ---------------------------------------------------------------------------------------------

coordinates = st.floats(-100, 100, allow_nan=False, allow_infinity=False)
points = st.tuples(coordinates, coordinates)


@st.composite
def polylines(draw, min_size: int = 2, max_size: int = 8):
    """Open polylines of ``min_size`` to ``max_size`` points, consecutive points at least 1e-3 apart."""
    pts = np.array(draw(st.lists(points, min_size=min_size, max_size=max_size)), dtype=float)
    keep = np.concatenate([[True], np.hypot(*np.diff(pts, axis=0).T) > 1e-3])
    pts = pts[keep]
    if len(pts) < 2:
        pts = np.vstack([pts[:1], pts[:1] + [1.0, 0.0]])
    return pts


SETTINGS = settings(max_examples=60, deadline=None)


@SETTINGS
@given(polylines(), st.lists(points, min_size=1, max_size=10), st.booleans())
def test_projection_lies_on_the_polyline_and_is_nearest(poly, pts, closed):
    """Every projected point lies on the polyline, and no farther from its point than the nearest
    vertex (nor than any point of the polyline, measured by shapely)."""
    p = np.array(pts, dtype=float)
    q = project_to_polyline(p, poly, closed=closed)
    line = shapely.LineString(np.vstack([poly, poly[:1]]) if closed else poly)
    scale = 1e-9 * (1.0 + np.abs(poly).max() + np.abs(p).max())
    assert shapely.distance(shapely.points(q), line).max() <= scale
    d = np.hypot(*(q - p).T)
    nearest_vertex = np.hypot(*(p[:, None, :] - poly[None, :, :]).transpose(2, 0, 1)).min(axis=1)
    assert (d <= nearest_vertex + scale).all()
    assert np.allclose(d, shapely.distance(shapely.points(p), line), atol=scale)


@SETTINGS
@given(polylines(), points, st.booleans())
def test_locate_agrees_with_projection(poly, p, closed):
    """locate_on_polyline's distance is the distance to the projected point."""
    p = np.array(p, dtype=float)
    d, i, t = locate_on_polyline(poly, p, closed=closed)
    q = project_to_polyline(p[None, :], poly, closed=closed)[0]
    assert 0.0 <= t <= 1.0 and 0 <= i < (len(poly) if closed else len(poly) - 1)
    assert abs(d - np.hypot(*(q - p))) <= 1e-9 * (1.0 + np.abs(poly).max() + np.abs(p).max())


@SETTINGS
@given(st.lists(st.floats(0.05, 5.0), min_size=2, max_size=12), st.floats(1.0, 6.0))
def test_resample_puts_each_anchor_within_half_a_subdivision_of_its_uniform_place(pieces, per_unit):
    """With every piece long enough for one subdivision, the sample at each anchor is the one a uniform
    subdivision of the whole polyline puts nearest to it: the counts follow the cumulative arc length,
    so rounding errors do not add up along a side split by many kept points (issue 18: the boundary
    vertices of two resolutions of a plan then agree to half an edge of the coarser, not a whole one)."""
    s = np.concatenate([[0.0], np.cumsum(pieces)])
    n = max(int(np.ceil(per_unit * s[-1])), int(np.ceil(s[-1] / min(pieces))))
    poly = np.column_stack([s, np.zeros_like(s)])
    pts, hit = resample_polyline(poly, n, anchors=range(1, len(s) - 1))
    assert len(hit) == len(s) - 2
    assert np.all(np.abs(np.array(hit) - n * s[1:-1] / s[-1]) <= 0.5 + 1e-9)


@SETTINGS
@given(polylines(), st.integers(1, 40), st.data())
def test_resample_keeps_its_ends_and_has_n_plus_one_samples(poly, n, data):
    """resample_polyline gives n + 1 points, the first and last exactly the polyline's ends; the anchors
    it reports as hit are samples at the anchor points, and the samples stay on the polyline."""
    anchors = data.draw(st.lists(st.integers(1, max(1, len(poly) - 2)), max_size=3)) if len(poly) > 2 else []
    pts, hit = resample_polyline(poly, n, anchors)
    assert pts.shape == (n + 1, 2)
    assert np.array_equal(pts[0], poly[0]) and np.array_equal(pts[-1], poly[-1])
    for a, h in zip(sorted(set(anchors)), hit):
        assert np.array_equal(pts[h], poly[a])
    assert hit == [] or len(hit) == len(set(anchors))
    assert chord_deviation(pts, poly) <= 1e-9 * (1.0 + np.abs(poly).max())


@SETTINGS
@given(polylines())
def test_lengths_and_parameters(poly):
    """Arc lengths increase from 0 to the polyline's length; parameters run from 0 to 1; the ends are
    at lengths 0 and the total; the halfway point lies on the polyline, at the middle of a segment."""
    s = arc_lengths(poly)
    assert s[0] == 0.0 and (np.diff(s) > 0).all()
    assert np.isclose(s[-1], polyline_length(poly))
    t = arc_parameters(poly)
    assert t[0] == 0.0 and t[-1] == 1.0
    assert np.allclose(point_at_length(poly, 0.0), poly[0]) and np.allclose(point_at_length(poly, s[-1]), poly[-1])
    d, _, _ = locate_on_polyline(poly, halfway_point(poly))
    assert d <= 1e-9 * (1.0 + np.abs(poly).max())
    assert np.allclose(halfway_point(poly[:2]), 0.5 * (poly[0] + poly[1]))


@SETTINGS
@given(st.integers(3, 12), st.floats(0.1, 10.0), st.floats(0.0, 6.3))
def test_turning_angles_of_a_convex_polygon_add_up_to_a_full_turn(n, r, phase):
    t = phase + 2 * np.pi * np.arange(n) / n
    ring = np.column_stack([r * np.cos(t), r * np.sin(t)])
    assert np.isclose(turning_angles(ring).sum(), 360.0)
    assert np.isclose(turning_angles(ring[::-1]).sum(), -360.0)
    open_angles = turning_angles(ring, closed=False)
    assert open_angles[0] == open_angles[-1] == 0.0


@SETTINGS
@given(polylines(), polylines())
def test_hausdorff_is_symmetric_and_zero_on_itself(a, b):
    """The Hausdorff distance is symmetric, at least the distance between the first points' nearest
    counterparts, and (up to rounding) zero from a polyline to itself; so is the chord deviation."""
    scale = 1e-9 * (1.0 + np.abs(a).max())
    assert 0.0 <= polyline_hausdorff(a, a) <= scale
    assert polyline_hausdorff(a, b) == polyline_hausdorff(b, a)
    assert polyline_hausdorff(a, b) >= shapely.distance(shapely.points(a[0]), shapely.LineString(b)) - scale
    assert 0.0 <= chord_deviation(a, a) <= scale


def test_projection_through_the_spatial_index_matches_the_brute_force():
    """Many points onto a long ring: the STRtree path gives the same nearest distances as every
    segment tried (the brute force it replaces above _CHUNK points x segments)."""
    from vaultgram.geometry import polylines

    t = np.linspace(0.0, 2 * np.pi, 20001)[:-1]
    ring = np.column_stack([np.cos(t) * (1 + 0.1 * np.sin(7 * t)), np.sin(t)])
    pts = np.random.default_rng(3).normal(size=(200, 2))
    assert len(pts) * len(ring) > polylines._CHUNK
    fast = polylines.project_to_polyline(pts, ring, closed=True)
    a, ab = polylines._segments(ring, True)
    _, q = polylines._closest_on_segments(pts, a, ab)
    slow = np.hypot(*(qj - pts[:, j, None] for j, qj in enumerate(q))).min(axis=1)
    np.testing.assert_allclose(np.hypot(*(fast - pts).T), slow, rtol=0, atol=1e-12)


def _projected_directly(p: np.ndarray, poly: np.ndarray, closed: bool) -> np.ndarray:
    """The nearest points by (k, s, d) arrays summed over their last axis (the form the axis-by-axis
    computation replaced, issue 18)."""
    a = poly if closed else poly[:-1]
    ab = (np.roll(poly, -1, axis=0) if closed else poly[1:]) - a
    t = np.clip(((p[:, None, :] - a) * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0.0, 1.0)
    q = a + t[..., None] * ab
    return q[np.arange(len(p)), np.argmin(((q - p[:, None, :]) ** 2).sum(-1), axis=1)]


@SETTINGS
@given(st.integers(0, 2**32 - 1), st.sampled_from([2, 3]), st.booleans())
def test_projection_is_bit_for_bit_the_direct_sums(seed, dim, closed):
    """Projected axis by axis, the nearest points are the direct formulation's to the last bit,
    signed zeros included (meshes must not change by a bit): points on and off polylines with
    coordinates rounded to a few digits, -0.0, repeated points (zero-length segments)."""
    rng = np.random.default_rng(seed)
    poly = np.round(rng.normal(size=(int(rng.integers(2, 30)), dim)), int(rng.integers(0, 3)))
    pts = np.round(rng.normal(size=(int(rng.integers(1, 20)), dim)), int(rng.integers(0, 3)))
    poly[rng.integers(0, len(poly), 2)] = -0.0
    poly[1] = poly[0]
    pts[: len(pts) // 2] = poly[rng.integers(0, len(poly), len(pts) // 2)]
    assert project_to_polyline(pts, poly, closed).tobytes() == _projected_directly(pts, poly, closed).tobytes()


def test_straight_spans_mark_the_points_between_straight_neighbours():
    """A square ring meshed with a point at every corner and mid-side: the mid-side points slide,
    the corners do not; a chain that cuts a corner with a chord keeps the points whose span holds the
    cut corner; an open chain's ends never slide."""
    square = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])
    chain = np.array([[0, 0], [1, 0], [2, 0], [2, 1], [2, 2], [1, 2], [0, 2], [0, 1.0]])
    assert straight_spans(chain, square, closed=True).tolist() == [False, True] * 4
    cut = np.array([[0.5, 0], [1, 0], [1.5, 0], [2, 0.5], [2, 1.5], [1, 2], [0, 2], [0, 1.0]])
    assert straight_spans(cut, square, closed=True).tolist() == [False, True] + [False] * 6
    line = np.array([[0.0, 0.0], [4.0, 0.0]])
    assert straight_spans(np.array([[0, 0], [1, 0], [3, 0], [4, 0.0]]), line).tolist() == [False, True, True, False]


def test_no_point_of_an_arc_slides():
    """Every point of a polygonal arc is a bend: no chain point on it has a straight span."""
    t = np.linspace(0.0, np.pi, 13)
    arc = np.column_stack([np.cos(t), np.sin(t)])
    assert not straight_spans(arc[::2], arc).any()
