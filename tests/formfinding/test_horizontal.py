"""Horizontal equilibrium (TNA step 1): parallelisation with the alpha blend, weighting and acceleration."""

from __future__ import annotations

import numpy as np
from formfinding.cases import holed_grid

from vaultgram.formfinding.formdiagram import form_diagram
from vaultgram.formfinding.horizontal import horizontal
from vaultgram.formfinding.relaxation import relax_openings
from vaultgram.geometry.meshes import grid_mesh


def test_alpha_blend_moves_both_diagrams():
    v, f = grid_mesh(6)
    rng = np.random.default_rng(1)
    inner = (v[:, 0] > 0) & (v[:, 0] < 6) & (v[:, 1] > 0) & (v[:, 1] < 6)
    v[inner, :2] += rng.uniform(-0.2, 0.2, (inner.sum(), 2))
    form = form_diagram(v, f)
    h = horizontal(form, alpha=50)
    assert h.max_angle < 0.5 and h.converged
    assert not np.allclose(h.form.xy, form.xy)
    assert np.allclose(h.form.xy[form.fixed], form.xy[form.fixed])   # anchors stay

def test_weighted_accelerated_iteration_keeps_the_guarantees_in_fewer_iterations():
    """Default (mu = 0.01, Anderson 5) and the plain compas_tna update reach the same stopping test."""
    v, f, outer = holed_grid(24, 8, 16)
    v[:, :2] += 0.02 * np.sin(v[:, [1, 0]])         # break the symmetry
    form = relax_openings(form_diagram(v, f, supports=outer), 0.1)
    fast = horizontal(form)
    plain = horizontal(form, length_weight=1.0, anderson=0)   # stalls here; the LP rescue finishes it
    assert fast.method == "parallelisation"
    for h in (fast, plain):
        assert h.converged and h.max_angle < 0.5
        assert np.all(h.q[form.active] > 0)
    assert fast.iterations < plain.iterations
    assert np.array_equal(fast.form.xy, form.xy)           # alpha = 100 keeps the plan
