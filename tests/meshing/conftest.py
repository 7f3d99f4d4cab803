"""Shared fixtures of the meshing tests: the layouts of two examples, and meshed examples with their
layout, counts and statistics (cached per module)."""

from __future__ import annotations

import pytest

from vaultgram.domain import load_domain
from vaultgram.meshing.densities import group_counts
from vaultgram.meshing.layout import edge_groups
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_domain

from paths import ARCHITECTURE, EXAMPLES


@pytest.fixture(scope="module")
def qwh_layout():
    return edge_groups(decompose(load_domain(EXAMPLES / "quad_with_hole.json")))


@pytest.fixture(scope="module")
def star_layout():
    path = ARCHITECTURE / "rv_star_pattern.json"
    if not path.is_file():
        pytest.skip("shared architecture data not found")
    return edge_groups(decompose(load_domain(path)))


def _path(name):
    p = EXAMPLES / f"{name}.json"
    return p if p.is_file() else ARCHITECTURE / f"{name}.json"


def _cached(make):
    """``get(name, *args)``: ``make(domain, *args)`` for the example or shared plan ``name``, computed
    once (skipped when the shared data is not there)."""
    cache = {}

    def get(name, *args):
        if (name, *args) not in cache:
            path = _path(name)
            if not path.is_file():
                pytest.skip(f"{path} not found")
            cache[(name, *args)] = make(load_domain(path), *args)
        return cache[(name, *args)]

    return get


@pytest.fixture(scope="session")
def cached_examples():
    """:func:`_cached`, for modules that mesh the examples their own way (test_features.py)."""
    return _cached


@pytest.fixture(scope="module")
def meshed():
    """``meshed(name, factor=1.0)``: domain, layout, counts, mesh and statistics at the target length
    ``0.025 * diagonal * factor``."""

    def make(domain, factor=1.0):
        dec = decompose(domain)
        layout = edge_groups(dec)
        target = 0.025 * domain.diagonal * factor
        counts = group_counts(layout, target_length=target)
        mesh = mesh_domain(domain, target_length=target)
        return (domain, layout, counts, mesh, mesh_stats(mesh, domain))

    get = _cached(make)
    return lambda name, factor=1.0: get(name, factor)


@pytest.fixture(scope="session")
def unexplained():
    """:func:`unexplained_boundary_singular`, for the tests."""
    return unexplained_boundary_singular


def unexplained_boundary_singular(stats) -> list:
    """The boundary singularities (by the regular valence of the mesh angle) that are not one of the
    two known gaps of the decomposition on plans that are not rectilinear: a corner turning by 30 to
    45 degrees (interior 135-150 or 210-225: the discretisation's corner, the rule's smooth point)
    with valence 2 or 4, and a reflex corner (225-315) that the medial axis gives no branch
    (valence 3; rules/corners.vgr gives one on rectilinear plans only)."""
    out = []
    for v, a, d in zip(stats["boundary_singular_vertices"], stats["boundary_singular_angles"],
                       stats["boundary_singular_valences"]):
        threshold = (135 <= a < 150 and d == 2) or (210 < a < 225 and d == 4)
        if not (threshold or (225 <= a <= 315 and d == 3)):
            out.append((v, a, d))
    return out
