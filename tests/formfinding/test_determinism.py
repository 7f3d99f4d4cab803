"""Form finding gives the same bits whatever ran before it in the process.

A helper once saw a rise of multiple_lobes converge when its test ran after the rest of its file
and not when it ran alone, on a mesh with the same hashes: form finding depending on process state.
These tests run one form finding, then other plans (and a change of the sparse solver's
process-wide settings), then the same form finding again, and compare every array bit for bit.
"""

from __future__ import annotations

import numpy as np
import pytest
from cvxopt import cholmod

from vaultgram.domain import load_domain
from vaultgram.geometry.meshes import grid_mesh, remove_faces
from vaultgram.pipeline import form_find, mesh_domain, thrust_of_mesh

from paths import EXAMPLES


def _bits(tn) -> list[bytes]:
    """Every array of a thrust network that form finding computes, as bytes."""
    return [np.ascontiguousarray(a).tobytes() for a in (tn.vertices, tn.q, tn.force.xy, tn.form.xy)]


def _holed_grid():
    """A 12 x 12 grid with a 4 x 4 hole: auto relaxes the hole's edges (a bisection on its sag)."""
    v, f, _ = remove_faces(*grid_mesh(12), drop=[12 * j + i for j in range(4, 8) for i in range(4, 8)])
    return v, f


@pytest.mark.parametrize("relax_mode", ["auto", "all"])
def test_the_same_form_finding_after_other_plans_gives_the_same_bits(relax_mode):
    v, f = _holed_grid()
    first = form_find(v, f, zmax=2.0, relax_mode=relax_mode)
    domain = load_domain(EXAMPLES / "l_shape.json")
    thrust_of_mesh(mesh_domain(domain), domain.supports, domain)  # another plan, its own rises
    form_find(*grid_mesh(9), zmax=1.0)
    again = form_find(v, f, zmax=2.0, relax_mode=relax_mode)
    assert first.summary["relax_mode"] == again.summary["relax_mode"]
    assert _bits(first) == _bits(again)


def test_cholmod_settings_changed_by_other_code_do_not_change_the_result():
    """cvxopt keeps CHOLMOD's settings in one process-wide dict; an LDL^T (``supernodal = 0``) set by
    other code must not reach form finding, and the dict is left as that code set it."""
    v, f = _holed_grid()
    first = form_find(v, f, zmax=2.0, relax_mode="all")
    saved = dict(cholmod.options)
    try:
        cholmod.options.update({"supernodal": 0, "postorder": False})
        again = form_find(v, f, zmax=2.0, relax_mode="all")
        assert cholmod.options["supernodal"] == 0 and cholmod.options["postorder"] is False
    finally:
        cholmod.options.clear()
        cholmod.options.update(saved)
    assert _bits(first) == _bits(again)
