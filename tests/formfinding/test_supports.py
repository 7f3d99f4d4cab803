"""Support specifications resolve to the right mesh vertices (paper §5, issue: supports)."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.domain import domain_from_dict
from vaultgram.errors import FormFindingError
from vaultgram.formfinding.supports import support_vertices
from vaultgram.geometry.meshes import grid_mesh, remove_faces


def grid_with_hole():
    """A 6 x 6 grid of unit quads with the central 2 x 2 faces removed (outer 0..6, hole 2..4)."""
    v, f = grid_mesh(6)
    centre = [j * 6 + i for j in (2, 3) for i in (2, 3)]
    v, f, _ = remove_faces(v, f, centre)
    return v, f


def on_square(xy, lo, hi):
    x, y = xy[:, 0], xy[:, 1]
    inside = (x >= lo - 1e-9) & (x <= hi + 1e-9) & (y >= lo - 1e-9) & (y <= hi + 1e-9)
    edge = np.isclose(x, lo) | np.isclose(x, hi) | np.isclose(y, lo) | np.isclose(y, hi)
    return np.flatnonzero(inside & edge)


def test_default_is_the_outer_boundary_with_holes_open():
    v, f = grid_with_hole()
    assert support_vertices(v, f).tolist() == on_square(v, 0, 6).tolist()


def test_rings_select_outer_and_holes():
    v, f = grid_with_hole()
    domain = domain_from_dict({"outer": [[0, 0], [6, 0], [6, 6], [0, 6]],
                               "holes": [[[2, 2], [4, 2], [4, 4], [2, 4]]]})
    hole = support_vertices(v, f, {"rings": [0]}, domain)
    assert hole.tolist() == on_square(v, 2, 4).tolist()
    both = support_vertices(v, f, {"rings": ["outer", 0]}, domain)
    assert sorted(both.tolist()) == sorted(on_square(v, 0, 6).tolist() + on_square(v, 2, 4).tolist())


def test_polylines_select_boundary_vertices_on_them():
    v, f = grid_with_hole()
    chosen = support_vertices(v, f, {"polylines": [[[0, 0], [6, 0]], [[0, 6], [6, 6]]]})
    assert set(np.round(v[chosen, 1], 9)) == {0.0, 6.0} and len(chosen) == 14


def test_explicit_vertices_and_errors():
    v, f = grid_mesh(3)
    assert support_vertices(v, f, {"vertices": [5, 0, 5]}).tolist() == [0, 5]
    with pytest.raises(FormFindingError, match=r"supports.vertices\[0\]: vertex index 99 is out of range"):
        support_vertices(v, f, {"vertices": [99]})
    with pytest.raises(FormFindingError, match="no mesh vertex lies on them"):
        support_vertices(v, f, {"polylines": [[[10, 10], [11, 10]]]})
    with pytest.raises(FormFindingError, match="needs the domain"):
        support_vertices(v, f, {"rings": ["outer"]})
