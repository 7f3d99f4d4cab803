"""What a tessellation is judged by (§5), on hand-built layouts whose answers are known."""

import math

import numpy as np
import pytest

from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.meshes import grid_mesh, remove_faces
from vaultgram.tessellation.keystones import CutMesh
from vaultgram.tessellation.metrics import (
    concave_voussoirs,
    euler_characteristic,
    format_summary,
    inner_vertices,
    joint_force_angles,
    joint_tilts,
    meeting_points,
    percentiles,
    spread,
    summarise,
)
from vaultgram.tessellation.model import voussoir_layout
from vaultgram.tessellation.voussoirs import face_groups

UP = np.array([0.0, 0.0, 1.0])


def layout_of(v, faces, group):
    """The voussoir layout of ``faces`` grouped by ``group`` (no keystones)."""
    cut = CutMesh(np.asarray(v, dtype=float), tuple(tuple(f) for f in faces), np.zeros(0, dtype=np.int64),
                  np.arange(len(v)), ())
    return voussoir_layout(cut, mesh_edges(cut.faces, len(v)), np.asarray(group))


# A 4 x 2 grid (faces 0-3 below, 4-7 above; inner vertices (1, 1), (2, 1), (3, 1)) laid as bricks.
STAGGERED = [0, 0, 1, 1, 2, 3, 3, 4]  # every inner vertex joins three voussoirs
ONE_IN_LINE = [0, 0, 1, 2, 3, 4, 4, 5]  # at (3, 1) the joints line up: four voussoirs
SINGLES = list(range(8))  # three points of four


@pytest.mark.parametrize("group, expected", [(STAGGERED, {"3": 3}), (ONE_IN_LINE, {"3": 2, "4": 1}),
                                             (SINGLES, {"4": 3}), ([0] * 8, {})])
def test_meeting_points_count_inner_vertices_by_voussoirs_meeting(group, expected):
    v, f = grid_mesh(4, 2)
    lay = layout_of(v, f, group)
    assert meeting_points(lay, len(v)) == expected
    inner = inner_vertices(lay, len(v))
    assert np.flatnonzero(inner).tolist() == [6, 7, 8]


def test_the_share_of_points_of_three_in_the_summary():
    v, f = grid_mesh(4, 2)
    normals = np.tile(UP, (len(v), 1))
    s = summarise(v, normals, layout_of(v, f, ONE_IN_LINE), 190.0, {}, 0, np.ones(6))
    assert s["meeting_points"] == {"3": 2, "4": 1} and s["meeting_points_of_3"] == pytest.approx(2 / 3)
    assert s["voussoirs"] == 6 and s["joints"] == 8 and s["keystones"] == 0
    s = summarise(v, normals, layout_of(v, f, [0] * 8), 190.0, {}, 0, np.ones(1))
    assert s["meeting_points_of_3"] == 1.0 and s["joints"] == 0


def test_the_summary_reads_as_text():
    v, f = grid_mesh(4, 2)
    s = summarise(v, np.tile(UP, (len(v), 1)), layout_of(v, f, ONE_IN_LINE), 190.0,
                  {"concavity": 1, "taken": 2, "aligned": 3, "moved": 5, "joined": 6, "courses": 4}, 0, np.ones(6))
    text = format_summary({**s, "rhythm": 2, "thickness": 0.3})
    assert "6 voussoirs" in text and "2 where 3 meet, 1 where 4 meet" in text and "66.7% of three" in text
    assert "V - E + F = 1" in text and "4 courses" in text and "faces moved 5, pairs joined 6" in text


def bricks(nx: int, ny: int) -> np.ndarray:
    """Voussoirs of two faces of an ``nx`` x ``ny`` grid (``nx`` even), staggered from row to row."""
    group, k = [], 0
    for j in range(ny):
        row = [0] + [1 + (i - 1) // 2 for i in range(1, nx)] if j % 2 else [i // 2 for i in range(nx)]
        group += [k + r for r in row]
        k += max(row) + 1
    return np.array(group)


def test_euler_characteristic_is_one_minus_the_openings():
    v, f = grid_mesh(6, 3)
    assert euler_characteristic(layout_of(v, f, np.arange(len(f)))) == 1
    assert euler_characteristic(layout_of(v, f, bricks(6, 3))) == 1
    for drop, openings in [([7], 1), ([7, 10], 2)]:
        w, g, _ = remove_faces(v, f, drop)
        assert euler_characteristic(layout_of(w, g, np.arange(len(g)))) == 1 - openings
        me = mesh_edges(g)
        rows = face_groups(me, np.isclose(w[me.edges[:, 0], 0], w[me.edges[:, 1], 0]))  # bars along x
        assert euler_characteristic(layout_of(w, g, rows)) == 1 - openings


def test_spread_is_min_mean_max_and_the_coefficient_of_variation():
    values = np.array([1.0, 2.0, 3.0, 6.0])
    s = spread(values)
    assert (s["min"], s["mean"], s["max"]) == (1.0, 3.0, 6.0)
    assert s["cv"] == pytest.approx(math.sqrt(((1 - 3) ** 2 + 1 + 0 + 9) / 4) / 3)  # population std / mean
    assert spread(10 * values)["cv"] == pytest.approx(s["cv"])
    assert spread(np.full(5, 2.5))["cv"] == 0.0
    assert spread(np.zeros(0)) == {"min": 0.0, "mean": 0.0, "max": 0.0, "cv": 0.0}


def test_percentiles_are_the_median_and_the_95th():
    assert percentiles(np.arange(101.0)) == {"median": 50.0, "p95": 95.0}
    assert percentiles(np.zeros(0)) == {"median": 0.0, "p95": 0.0}


def test_joints_normal_to_a_plane_are_not_tilted():
    v, f = grid_mesh(4, 3)
    lay = layout_of(v, f, np.arange(len(f)))
    assert np.allclose(joint_tilts(v, np.tile(UP, (len(v), 1)), lay), 0.0)


def test_a_joint_tilts_by_the_angle_of_the_normals_across_it():
    """Normals leaning by 10 degrees towards +x: joints along y (across the lean) tilt by 10 degrees,
    joints along x (in the lean's plane) not at all."""
    v, f = grid_mesh(4, 3)
    lay = layout_of(v, f, np.arange(len(f)))
    t = math.radians(10.0)
    tilt = joint_tilts(v, np.tile([math.sin(t), 0.0, math.cos(t)], (len(v), 1)), lay)
    d = v[lay.edges.edges[lay.joints, 1]] - v[lay.edges.edges[lay.joints, 0]]
    along_y = np.abs(d[:, 1]) > 0.5
    assert np.allclose(tilt[along_y], 10.0) and np.allclose(tilt[~along_y], 0.0)


def test_joints_of_a_rectangular_grid_are_along_or_across_the_force_flow():
    """On a grid (flat or a cylinder) the edges crossing a joint are normal to it: angle 0."""
    v, f = grid_mesh(6, 4)
    cylinder = v.copy()
    cylinder[:, 2] = np.sqrt(40.0 - (v[:, 0] - 3.0) ** 2)  # a barrel vault along y
    for x in (v, cylinder):
        lay = layout_of(x, f, bricks(6, 4))
        angles, regular = joint_force_angles(x, lay)
        assert len(angles) == len(lay.joints) and np.allclose(angles, 0.0, atol=1e-6)
        assert regular.any()


def test_on_a_sheared_grid_every_joint_is_off_the_flow_by_the_shear():
    theta = 20.0
    v, f = grid_mesh(5, 4)
    v[:, 0] += math.tan(math.radians(theta)) * v[:, 1]
    lay = layout_of(v, f, np.arange(len(f)))
    angles, _ = joint_force_angles(v, lay)
    assert np.allclose(angles, theta)


def test_regular_joints_join_two_four_valent_inner_vertices_between_quads():
    v, f = grid_mesh(4, 2)
    lay = layout_of(v, f, STAGGERED)
    _, regular = joint_force_angles(v, lay)
    ends = lay.edges.edges[lay.joints[regular]]
    assert sorted(map(tuple, ends.tolist())) == [(6, 7), (7, 8)]  # the middle line, not at the boundary


def test_a_concave_voussoir_is_counted_with_its_largest_corner():
    v, f = grid_mesh(2)  # an L of three faces 0 1 3 and face 2 alone
    lay = layout_of(v, f, [0, 0, 1, 0])
    assert concave_voussoirs(v, lay, 190.0) == (1, pytest.approx(270.0))
    assert concave_voussoirs(v, lay, 275.0) == (0, pytest.approx(270.0))
    assert concave_voussoirs(v, layout_of(v, f, [0, 0, 1, 1]), 190.0) == (0, pytest.approx(180.0))
