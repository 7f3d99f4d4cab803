"""Construction order: courses from the supports, zones, names."""

import numpy as np

from vaultgram.pipeline import tessellate
from vaultgram.tessellation.courses import support_zones, voussoir_names


def test_courses_grow_one_voussoir_at_a_time_from_the_supports(arch_grid):
    t = tessellate(arch_grid, thickness=0.3)
    lay, course = t.layout, t.courses
    assert course.min() == 0
    supported = np.zeros(len(t.vertices), dtype=bool)
    supported[: len(arch_grid.supported)] = arch_grid.supported
    resting = np.array([supported[loop].any() for loop in lay.loops])
    assert (course[resting] == 0).all() and (course[~resting] > 0).all()
    pairs = lay.joint_voussoirs()
    assert (np.abs(course[pairs[:, 0]] - course[pairs[:, 1]]) <= 1).all()
    # every voussoir of course c > 0 has a neighbour of course c - 1
    for k in np.flatnonzero(course > 0):
        others = pairs[(pairs == k).any(axis=1)].ravel()
        assert (course[others] == course[k] - 1).any()
    assert len(set(t.names)) == lay.n_voussoirs


def test_support_zones_are_runs_of_supported_vertices():
    edges = np.array([[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0]])
    supported = np.array([True, True, False, True, True, False])
    assert support_zones(edges, supported).tolist() == [0, 0, -1, 1, 1, -1]


def test_names_number_the_voussoirs_of_each_zone_and_course():
    assert voussoir_names(np.array([0, 1, 0, -1]), np.array([1, 1, 1, -1])) == ["B0.1", "B1.1", "B0.2", "X.1"]
