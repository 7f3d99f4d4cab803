"""Shared explorations of the exploration tests (cached per session: each search meshes its variants)."""

from __future__ import annotations

import pytest

from vaultgram.domain import load_domain
from vaultgram.exploration.explore import ExploreOptions, explore

from paths import ARCHITECTURE, EXAMPLES

SPACING = 0.05
INPUTS = {
    "two_holes_five_points": ARCHITECTURE / "two_holes_five_points.json",
    "armadillo_vault_plan": ARCHITECTURE / "armadillo_vault_plan.json",
    "fig5_boundary_points": EXAMPLES / "fig5_boundary_points.json",
    "fig6_inner_points": EXAMPLES / "fig6_inner_points.json",
    "fig7_curves": EXAMPLES / "fig7_curves.json",
    "features_combined": EXAMPLES / "features_combined.json",
}


def domain_of(name: str):
    path = INPUTS[name]
    if not path.is_file():
        pytest.skip(f"{path} not found (the shared data sits beside the checkout)")
    return load_domain(path)


@pytest.fixture(scope="session")
def explorations():
    """name -> Exploration, made on first use (limit 16 states, spacing 0.05, light smoothing)."""
    cache = {}

    def get(name: str):
        if name not in cache:
            cache[name] = explore(domain_of(name), ExploreOptions(spacing=SPACING, limit=16, smooth=5))
        return cache[name]

    return get
