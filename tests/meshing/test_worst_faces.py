"""benchmarks/worst_faces.py (issue 12 What 4): the worst face of a mesh and its cause."""

from __future__ import annotations

import sys

import numpy as np
from uncapped import without_point_load_caps

from vaultgram.domain import domain_from_dict
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.pipeline import mesh_domain

from paths import REPO

sys.path[:0] = [str(REPO / "benchmarks"), str(REPO / "tests" / "meshing")]
import worst_faces  # noqa: E402
from test_fans import CURVE_END, CURVE_END_PLAN  # noqa: E402


def test_vertex_angles_of_a_grid():
    """Corners 90, sides 180, inside 360 degrees; 1, 2 and 4 faces."""
    v, f = grid_mesh(3)
    angle, count = worst_faces.vertex_angles(v, f)
    assert np.allclose(angle[[0, 1, 5]], [90, 180, 360]) and count[[0, 1, 5]].tolist() == [1, 2, 4]


def test_curve_turn_is_zero_at_the_ends_and_the_bend_inside():
    x = np.array([[0, 0], [1, 0], [1, 1.0]])
    assert [worst_faces.curve_turn(x, np.array([0, 1, 2]), c) for c in (0, 1, 2)] == [0.0, 90.0, 0.0]


def test_the_worst_face_of_a_curve_end_plan_is_its_free_end_fan(monkeypatch):
    """CURVE_END_PLAN's worst face is a triangle round the curve's free end, under the fan bound there
    (drawn without the point-load caps, as in test_fans)."""
    without_point_load_caps(monkeypatch)
    row = worst_faces.cause(mesh_domain(domain_from_dict(CURVE_END_PLAN), 0.04))
    assert row["cause"] == "triangle: fan at curve free end" and row["sides"] == 3
    assert np.allclose(row["xy"], CURVE_END, atol=1e-4) and row["angle"] > 359.9
    assert 0 < row["sj"] <= row["fan_bound"] < 0.3 and row["worst_at_vertex"]


def test_the_table_counts_the_plans_under_the_floor_by_cause():
    rows = [{"plan": 0, "sj": 0.05, "fan_bound": 0.08, "cause": "a"},
            {"plan": 1, "sj": 0.2, "fan_bound": 0.5, "cause": "a"},
            {"plan": 2, "sj": 0.25, "fan_bound": 1.0, "cause": "b"},
            {"plan": 3, "sj": 0.9, "fan_bound": 1.0, "cause": "b"},
            {"plan": 4, "error": "folds"}]
    text = worst_faces.table(rows, 0.3)
    assert text.splitlines()[0] == "4 valid plans; 3 under 0.3, 1 under 0.1"
    assert "| a | 2 | 1 | 0.125 | 0.290 | 1 |" in text and "| b | 1 | 0 | 0.250 | 1.000 | 0 |" in text
