"""Jagged outlines for the tests of the reflex-corner rules (``rules/corners.vgr``) and the quality
benchmarks (``benchmarks/quality_vs_gmsh.py --plans jagged``).

A circle of radius 20 with a three-lobed wave and random radius noise, sampled at 50 to 110 sorted
random angles: the geographic outlines of issue 12, with short edges (0.1-0.3 against a median of
1.5), convex corners, reflex corners of 225-315 degrees and spikes of 315-360 (regular valence 5,
two chords each). :func:`jagged_plans` draws them reproducibly.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["jagged_plans"]


def jagged_plans(count: int = 4, seed: int = 7) -> dict:
    """``count`` star-shaped outlines of 50-110 vertices with radius noise, named ``jagged_k``, as
    domain dicts (``{"outer": ring}``), drawn from ``seed``.

    >>> plans = jagged_plans(2)
    >>> sorted(plans), [len(p["outer"]) for p in plans.values()]
    (['jagged_0', 'jagged_1'], [107, 88])
    """
    rng = np.random.default_rng(seed)
    plans = {}
    for k in range(count):
        n = int(rng.integers(50, 111))
        t = np.sort(rng.uniform(0, 2 * math.pi, n))
        r = 20 * (1 + 0.25 * np.sin(3 * t + k)) * rng.uniform(0.93, 1.07, n)
        plans[f"jagged_{k}"] = {"outer": np.column_stack([r * np.cos(t), r * np.sin(t)]).round(3).tolist()}
    return plans
