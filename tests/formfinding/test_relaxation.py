"""Relaxing openings: unsupported edges bent into compression arches with the prescribed sag."""

from __future__ import annotations

import numpy as np
import pytest
from formfinding.cases import holed_grid

from vaultgram.formfinding.formdiagram import form_diagram
from vaultgram.formfinding.relaxation import relax_openings


def test_hole_gets_an_opening_face_and_is_relaxed():
    v, f, outer = holed_grid()
    form = form_diagram(v, f, supports=outer)
    assert (~form.loaded).sum() == 1
    opening = form.opening_faces[0]
    assert len(opening) == 24
    assert not form.anchors[list(opening)].any()
    relaxed = relax_openings(form, sag=0.1)
    moved = np.linalg.norm(relaxed.xy - form.xy, axis=1)
    on_hole = np.zeros(form.n_vertices, dtype=bool)
    on_hole[list(opening)] = True
    assert moved[~on_hole].max() == 0.0                     # mode "boundary" keeps the pattern
    assert moved[on_hole].max() == pytest.approx(0.1 * 6, rel=1e-3)   # sag x span (side of the square hole)
    # the sides bow away from the hole (arches around it): the opening grows and gets rounder
    centre = np.array([10.0, 10.0])
    d0 = np.linalg.norm(form.xy[list(opening)] - centre, axis=1)
    d1 = np.linalg.norm(relaxed.xy[list(opening)] - centre, axis=1)
    mid_sides = np.isclose(d0, 3.0)
    assert np.all(d1[mid_sides] == pytest.approx(3.6, rel=1e-3))
    assert d1.std() < d0.std()

    def area(p):
        return 0.5 * abs(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]))

    assert area(relaxed.xy[list(opening)]) > area(form.xy[list(opening)])
