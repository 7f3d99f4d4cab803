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


def test_interacting_openings_all_meet_their_sag():
    """Mode "all" moves every vertex, so each opening's sag depends on the others' force densities: the
    search meets every sag together (to 1e-6 of its target), where bisection alone, opening by opening,
    leaves the small hole's sag several times its target: its bracket went stale as the other moved."""
    from vaultgram.formfinding import relaxation
    from vaultgram.geometry.meshes import boundary_loops, grid_mesh, remove_faces

    n = 16
    v, f = grid_mesh(n)
    big = [j * n + i for j in range(5, 11) for i in range(2, 8)]          # a 6 x 6 hole and a 3 x 3 one
    drop = big + [j * n + i for j in range(6, 9) for i in range(9, 12)]
    v, f, _ = remove_faces(v, f, drop)
    form = form_diagram(v, f, supports=max(boundary_loops(f), key=len))
    eo, fo = relaxation.opening_edges(form)
    moving = relaxation._moving_vertices(form, eo, "all")
    arches = [relaxation._arch(form, k, moving) for k in np.flatnonzero(~form.loaded)]
    system = relaxation._ForceDensities(form, moving, eo, fo, 1.0)
    target = 0.1 * np.array([a.span for a in arches])
    logq, xy = relaxation._sag_search(system, arches, 0.1, 60)
    assert len(arches) == 2
    assert np.allclose(relaxation._sags(xy, form.xy, arches), target, rtol=1e-6, atol=0)
    assert np.allclose(relax_openings(form, 0.1, mode="all").xy, xy)
    stale = relaxation._bisect_sag(system, arches, target, 60)
    assert np.max(np.abs(relaxation._sags(system.solve(stale), form.xy, arches) / target - 1)) > 1.0
