"""The force diagram: reciprocal to the form diagram, and the least-squares fits that place it."""

from __future__ import annotations

import numpy as np
from formfinding.cases import holed_grid

from vaultgram.formfinding.forcediagram import force_diagram
from vaultgram.formfinding.formdiagram import form_diagram
from vaultgram.formfinding.horizontal import angle_deviations, horizontal
from vaultgram.geometry.meshes import grid_mesh


def test_reciprocal_counts_and_parallel_edges_on_grid():
    v, f = grid_mesh(8)
    form = form_diagram(v, f)
    force = force_diagram(form)
    assert force.n_vertices == form.n_faces
    assert force.n_edges == form.n_edges
    h = horizontal(form, force)
    ang = angle_deviations(form.edge_vectors()[h.force.form_edge], h.force.edge_vectors())
    assert ang.max() < 1e-6          # stored force diagram is parallel (not perpendicular) to the form
    assert np.all(h.q > 0)

def test_weighted_fit_with_unit_weight_is_the_plain_fit():
    from vaultgram.formfinding.forcediagram import PinnedLaplacian, WeightedFit

    v, f, outer = holed_grid(10, 3, 7)
    form = form_diagram(v, f, supports=outer)
    force = force_diagram(form)
    rng = np.random.default_rng(0)
    t = rng.normal(size=(force.n_edges, 2))
    frame = rng.normal(size=(force.n_edges, 2))
    frame /= np.linalg.norm(frame, axis=1)[:, None]
    x0 = rng.normal(size=(force.n_vertices, 2))
    plain = PinnedLaplacian(force.C, force.pins).solve(t, x0)
    assert np.allclose(WeightedFit(force.C, force.pins, frame, 1.0).solve(t, x0), plain, atol=1e-10)
    # with mu < 1 it minimises the weighted objective: its gradient vanishes at the free vertices
    mu = 0.01
    x = WeightedFit(force.C, force.pins, frame, mu).solve(t, x0)
    assert np.array_equal(x[force.pins], x0[force.pins])
    r = force.C @ x - t
    n = np.column_stack([-frame[:, 1], frame[:, 0]])
    wr = n * (n * r).sum(1)[:, None] + mu * frame * (frame * r).sum(1)[:, None]
    grad = force.C.T @ wr
    free = np.setdiff1d(np.arange(force.n_vertices), force.pins)
    assert np.abs(grad[free]).max() < 1e-9


def test_closing_targets_are_walked_and_others_fitted():
    """Where the form is in equilibrium with the densities (a regular grid, unit densities) the force
    diagram is its exact reciprocal: every force edge equals its target and it agrees with the
    least-squares fit; a grid with one vertex moved has no reciprocal, and the fit is as before."""
    from vaultgram.formfinding.forcediagram import PinnedLaplacian, _walked

    form = form_diagram(*grid_mesh(12))
    force = force_diagram(form)
    target = form.edge_vectors()[force.form_edge]
    assert np.array_equal(force.edge_vectors(), target)                 # integer targets: exact
    assert force.xy[force.pins].tolist() == [[0.0, 0.0]]
    fit = PinnedLaplacian(force.C, force.pins).solve(target, np.zeros_like(force.xy))
    assert np.abs(fit - force.xy).max() < 1e-12 * np.abs(fit).max()
    v, f = grid_mesh(12)
    v[50, :2] += [0.1, 0.05]
    moved = form_diagram(v, f)
    force = force_diagram(moved)
    target = moved.edge_vectors()[force.form_edge]
    assert _walked(force, target) is None
    assert np.array_equal(force.xy, PinnedLaplacian(force.C, force.pins).solve(target, np.zeros_like(force.xy)))


def test_walked_reciprocal_of_a_diagram_in_several_parts():
    """Each connected part of the force diagram is walked from its own pin (one root joined to all)."""
    from vaultgram.formfinding.diagrams import connectivity_matrix
    from vaultgram.formfinding.forcediagram import ForceDiagram, _walked

    edges = np.array([[0, 1], [1, 2], [3, 4]])               # two parts: 0-1-2 and 3-4
    C = connectivity_matrix(edges, 5)
    force = ForceDiagram(xy=np.zeros((5, 2)), edges=edges, form_edge=np.arange(3), C=C)
    target = np.array([[1.0, 0.0], [0.0, 2.0], [-1.0, 1.0]])
    xy = _walked(force, target)
    assert xy.tolist() == [[0.0, 0.0], [1.0, 0.0], [1.0, 2.0], [0.0, 0.0], [-1.0, 1.0]]
    cycle = ForceDiagram(xy=np.zeros((3, 2)), edges=np.array([[0, 1], [1, 2], [2, 0]]), form_edge=np.arange(3),
                         C=connectivity_matrix(np.array([[0, 1], [1, 2], [2, 0]]), 3))
    assert _walked(cycle, np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]])) is not None    # closes
    assert _walked(cycle, np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, -0.9]])) is None        # does not
