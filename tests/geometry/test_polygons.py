"""The polygon kernel (vaultgram.geometry.polygons): signed area, bounding-box diagonal, corner angles."""

from __future__ import annotations

import math

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.geometry.polygons import bbox_diagonal, cross_z, interior_angle, signed_area

from strategies.domains import star_polygons

coordinates = st.floats(-100, 100, allow_nan=False, allow_infinity=False)
points = st.tuples(coordinates, coordinates)
SETTINGS = settings(max_examples=60, deadline=None)


@SETTINGS
@given(star_polygons())
def test_signed_area_is_positive_ccw_and_flips_when_reversed(poly):
    area = signed_area(poly)
    assert area > 0
    # the shoelace terms cancel: their rounding grows with the squared distance from the origin
    assert math.isclose(signed_area(poly[::-1]), -area, rel_tol=1e-12, abs_tol=1e-14 * float(np.abs(poly).max()) ** 2)
    assert math.isclose(area, shapely.Polygon(poly).area, rel_tol=1e-9)


@SETTINGS
@given(st.lists(points, min_size=1, max_size=20), points)
def test_bbox_diagonal_is_translation_invariant_and_bounds_every_distance(pts, shift):
    p = np.array(pts, dtype=float)
    d = bbox_diagonal(p)
    assert math.isclose(bbox_diagonal(p + np.array(shift)), d, rel_tol=1e-9, abs_tol=1e-9)
    assert np.hypot(*(p[:, None, :] - p[None, :, :]).transpose(2, 0, 1)).max() <= d * (1 + 1e-12) + 1e-12
    assert bbox_diagonal(np.zeros((0, 2))) == 0.0


@SETTINGS
@given(st.floats(0.01, 6.27), st.floats(0.0, 6.28), st.floats(0.1, 10.0), st.floats(0.1, 10.0))
def test_interior_angles_either_side_make_a_full_turn(opening, phase, r1, r2):
    """The angle inside at a corner plus the angle on the other side is 360 degrees, and a corner
    opened by ``opening`` radians measures that many degrees."""
    corner = (0.0, 0.0)
    after = (r1 * math.cos(phase), r1 * math.sin(phase))
    before = (r2 * math.cos(phase + opening), r2 * math.sin(phase + opening))
    inside = interior_angle(before, corner, after)
    assert math.isclose(inside, math.degrees(opening), abs_tol=1e-9)
    assert math.isclose(inside + interior_angle(after, corner, before), 360.0, abs_tol=1e-9)


@SETTINGS
@given(st.lists(st.tuples(points, points), min_size=1, max_size=10))
def test_cross_z_is_antisymmetric_and_zero_for_parallel_vectors(pairs):
    a = np.array([p for p, _ in pairs], dtype=float)
    b = np.array([q for _, q in pairs], dtype=float)
    assert np.array_equal(cross_z(a, b), -cross_z(b, a))
    assert np.array_equal(cross_z(a, 2 * a), np.zeros(len(a)))
