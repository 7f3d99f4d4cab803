"""Validation of domains (vaultgram.domain.validation): one test per geometric error."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.domain import Domain, domain_from_dict, validate_domain
from vaultgram.errors import DomainError

SQUARE = [[0, 0], [10, 0], [10, 10], [0, 10]]
HOLE = [[4, 4], [6, 4], [6, 6], [4, 6]]


def err(d) -> str:
    with pytest.raises(DomainError) as e:
        domain_from_dict(d)
    return str(e.value)


# --- geometric errors ----------------------------------------------------------------------------


def test_too_few_vertices():
    assert "outer ring: needs at least 3 distinct vertices" in err({"outer": [[0, 0], [1, 0], [0, 0]]})


def test_non_finite():
    msg = err({"outer": [[0, 0], [1, 0], [float("nan"), 1]]})
    assert "outer ring, vertex 2" in msg and "not finite" in msg
    msg = err({"outer": SQUARE, "holes": [[[4, 4], [6, 4], [6, float("inf")]]]})
    assert "hole 0, vertex 2" in msg


def test_duplicate_consecutive_vertices():
    msg = err({"outer": [[0, 0], [10, 0], [10, 0], [10, 10], [0, 10]]})
    assert msg.endswith("outer ring: vertices 1 and 2 coincide at (10, 0)")


def test_near_duplicate_non_consecutive_vertices():
    ring = [[0, 0], [10, 0], [5, 5 + 1e-12], [10, 10], [0, 10], [5, 5]]
    msg = err({"outer": ring})
    assert "outer ring: vertices 2 and 5 coincide at (5, 5)" in msg


def test_self_intersection_names_segments():
    bowtie = [[0, 0], [10, 10], [10, 0], [0, 10]]
    msg = err({"outer": bowtie})
    assert "outer ring, vertex 0: ring self-intersects at (5, 5)" in msg
    assert "segments 0-1 and 2-3" in msg
    hole = [[4, 4], [6, 6], [6, 4], [4, 6]]
    assert "hole 0, vertex 0: ring self-intersects at (5, 5)" in err({"outer": SQUARE, "holes": [hole]})


def test_hole_outside():
    msg = err({"outer": SQUARE, "holes": [[[20, 20], [22, 20], [22, 22]]]})
    assert "hole 0, vertex 0: lies outside the outer ring" in msg


def test_hole_touching_outer():
    msg = err({"outer": SQUARE, "holes": [[[0, 4], [2, 4], [2, 6]]]})
    assert "hole 0, vertex" in msg and "touches the outer ring at (0, 4)" in msg


def test_hole_crossing_outer():
    msg = err({"outer": SQUARE, "holes": [[[8, 4], [12, 4], [12, 6], [8, 6]]]})
    assert "hole 0, vertex" in msg and "crosses the outer ring" in msg


def test_holes_overlapping_and_nested():
    h2 = [[5, 5], [7, 5], [7, 7], [5, 7]]
    msg = err({"outer": SQUARE, "holes": [HOLE, h2]})
    assert "hole 1, vertex" in msg and "hole 0" in msg and "overlaps" in msg
    inner = [[4.5, 4.5], [5.5, 4.5], [5.5, 5.5]]
    assert "hole 1, vertex 0: lies inside hole 0" in err({"outer": SQUARE, "holes": [HOLE, inner]})
    touching = [[6, 4], [8, 4], [8, 6]]
    msg = err({"outer": SQUARE, "holes": [HOLE, touching]})
    assert "hole 1, vertex" in msg and "touches hole 0" in msg


def test_point_feature_outside():
    msg = err({"outer": SQUARE, "points": [[5, 5], [15, 5]]})
    assert msg.endswith("point feature 1 at (15, 5) lies outside the domain")


def test_point_feature_in_hole():
    msg = err({"outer": SQUARE, "holes": [HOLE], "points": [[5, 5]]})
    assert msg.endswith("point feature 0 at (5, 5) lies inside hole 0")


def test_point_feature_duplicate():
    assert "point features 0 and 1 coincide" in err({"outer": SQUARE, "points": [[2, 2], [2, 2]]})


def test_curve_leaving_domain():
    msg = err({"outer": SQUARE, "curves": [[[5, 5], [12, 5]]]})
    assert "curve feature 0, vertex 1: leaves the domain" in msg


def test_curve_crossing_hole():
    msg = err({"outer": SQUARE, "holes": [HOLE], "curves": [[[2, 5], [8, 5]]]})
    assert "curve feature 0, vertex 0: crosses hole 0" in msg and "segment 0-1" in msg


def test_curve_touching_boundary_between_its_ends():
    msg = err({"outer": SQUARE, "curves": [[[2, 2], [0, 5], [2, 8]]]})
    assert "curve feature 0, vertex 1: touches the domain boundary at (0, 5)" in msg


def test_curve_may_start_on_boundary():
    d = domain_from_dict({"outer": SQUARE, "holes": [HOLE], "curves": [[[0, 5], [2, 5]], [[4, 5], [3, 5]]]})
    assert len(d.curves) == 2


def test_curve_self_intersection():
    msg = err({"outer": SQUARE, "curves": [[[1, 1], [3, 3], [3, 1], [1, 3]]]})
    assert "curve feature 0, vertex 0: curve self-intersects" in msg


def test_validate_domain_direct():
    d = Domain("x", np.array(SQUARE, float), (), np.array([[20.0, 20.0]]), (), None)
    with pytest.raises(DomainError, match="point feature 0 at \\(20, 20\\) lies outside"):
        validate_domain(d)
