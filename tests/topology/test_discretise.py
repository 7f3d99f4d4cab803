"""Boundary discretisation (paper §3.1, first paragraph)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.errors import DomainError
from vaultgram.topology.discretise import discretise

L_SHAPE = [[0, 0], [10, 0], [10, 5], [5, 5], [5, 10], [0, 10]]
SKEWED_L = [[0, 0], [10, 0], [10, 5], [5, 5], [4, 10], [0, 10]]  # not rectilinear: no chord feet added


@pytest.fixture(scope="module")
def lshape():
    return domain_from_dict({"outer": L_SHAPE})


@given(spacing=st.floats(0.01, 0.05))
@settings(max_examples=25, deadline=None)
def test_spacing_bound_and_vertices_kept(spacing):
    d = domain_from_dict({"outer": SKEWED_L})
    disc = discretise(d, spacing)
    ring = disc.points[disc.rings[0]]
    gaps = np.hypot(*(np.roll(ring, -1, axis=0) - ring).T)
    assert gaps.max() <= spacing * d.diagonal * (1 + 1e-9)
    # each input segment is split into equal parts
    for a, b in zip(SKEWED_L, SKEWED_L[1:] + SKEWED_L[:1]):
        seg_len = np.hypot(b[0] - a[0], b[1] - a[1])
        m = int(np.ceil(seg_len / (spacing * d.diagonal) - 1e-9))
        ab, ap = np.subtract(b, a), ring - a
        cross = ab[0] * ap[:, 1] - ab[1] * ap[:, 0]
        t = ap @ ab / seg_len**2
        on = (np.abs(cross) < 1e-9) & (t > -1e-12) & (t < 1 + 1e-12)
        assert on.sum() == m + 1
    # every input vertex is a point, in order
    np.testing.assert_allclose(disc.points[disc.is_input_vertex], d.outer)


def test_a_rectilinear_plan_is_sampled_at_its_chord_feet(lshape):
    """The reflex corner's side extensions meet the boundary at (5, 0) and (0, 5): ring points there
    (rules/corners.vgr draws the chords to them), and the segments on either side split evenly."""
    disc = discretise(lshape, 0.03)
    ring = disc.points[disc.rings[0]]
    for foot in ([5, 0], [0, 5]):
        assert np.isclose(np.hypot(*(ring - foot).T), 0).sum() == 1
    gaps = np.hypot(*(np.roll(ring, -1, axis=0) - ring).T)
    assert np.allclose(gaps, gaps[0]) and gaps.max() <= 0.03 * lshape.diagonal


def test_corners_by_angle(lshape):
    disc = discretise(lshape, 0.02)
    corners = disc.points[disc.is_corner]
    assert len(corners) == 6
    kinds = {tuple(p): k for p, k in zip(disc.points[disc.is_corner], disc.corner_kind[disc.is_corner])}
    assert kinds[(5.0, 5.0)] == -1
    assert sum(k == 1 for k in kinds.values()) == 5
    assert (disc.corner_kind[~disc.is_corner] == 0).all()


def test_dense_curve_has_no_corners(examples_dir):
    d = load_domain(examples_dir / "quad_with_hole.json")
    disc = discretise(d, 0.01)
    hole = disc.rings[1]
    assert not disc.is_corner[hole].any()  # 64-gon turns by 5.6 degrees per vertex
    assert disc.is_corner[disc.rings[0]].sum() == 4
    assert (disc.ring[hole] == 1).all() and (disc.index[hole] == np.arange(len(hole))).all()
    # hole clockwise
    p = disc.points[hole]
    assert np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]) < 0


def test_features_are_labelled_and_inserted():
    d = domain_from_dict(
        {
            "outer": [[0, 0], [10, 0], [10, 10], [0, 10]],
            "points": [[2.5, 7.5], [10, 3.3], [3, 5]],
            "curves": [[[0, 5], [4, 5]]],
        }
    )
    disc = discretise(d, 0.02)
    fp = disc.feature_points
    assert disc.ring[fp[0]] == -2
    assert disc.ring[fp[1]] == 0  # boundary point feature inserted into the outer ring
    np.testing.assert_allclose(disc.points[fp[1]], [10, 3.3])
    assert disc.ring[fp[2]] == -1  # on the curve feature
    c = disc.curves[0]
    assert disc.ring[c[0]] == 0  # starts on the boundary: shares a ring point
    assert (disc.ring[c[1:]] == -1).all()
    np.testing.assert_allclose(disc.points[c[0]], [0, 5])
    assert len(np.unique(disc.points.round(12), axis=0)) == len(disc.points)
    gaps = np.hypot(*np.diff(disc.points[c], axis=0).T)
    assert gaps.max() <= 0.02 * d.diagonal * (1 + 1e-9)


@pytest.mark.parametrize("bad", [0, -0.01, 0.25, float("nan")])
def test_spacing_out_of_range(lshape, bad):
    with pytest.raises(DomainError, match="spacing"):
        discretise(lshape, bad)
