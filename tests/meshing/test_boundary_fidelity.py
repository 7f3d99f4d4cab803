"""Boundary fidelity on every shared plan and example (issue 12, What 5): each ring vertex whose
angle differs from 180 degrees by more than 15 is a mesh vertex, and the mesh boundary lies within
0.1% of the bounding-box diagonal of the domain's boundary, both ways: the mesh boundary from the
rings (it strayed up to 0.25% before) and the rings from the mesh boundary (a chord that a sliding
vertex left across a bend cut up to 0.137% off multiple_lobes before vaultgram.meshing.fidelity)."""

from __future__ import annotations

import pytest

from vaultgram.domain import load_domain
from vaultgram.errors import VaultgramError
from vaultgram.geometry.fidelity import boundary_deviation, missed_vertices
from vaultgram.pipeline import mesh_domain

from paths import ARCHITECTURE_PLANS, EXAMPLES

PLANS = ARCHITECTURE_PLANS + sorted(EXAMPLES.glob("*.json"))  # the shared plans where they are beside the checkout


def _plan(path):
    try:
        return load_domain(path)
    except VaultgramError:  # a file of another kind (a skeleton example)
        pytest.skip(f"{path.name} is not a plan")


@pytest.mark.parametrize("path", PLANS, ids=lambda p: p.stem)
def test_the_mesh_boundary_keeps_sharp_vertices_and_follows_the_plan(path):
    domain = _plan(path)
    mesh = mesh_domain(domain)
    assert missed_vertices(mesh.vertices, mesh.boundary, domain.rings) == []
    assert boundary_deviation(mesh.vertices, mesh.faces, domain.rings) <= 0.001
