"""Random smooth plans: how many mesh, and how well (issue 12, the O-grid and lone-branch rules).

Run: ``python benchmarks/smooth_plans.py [--count 80] [--seed 1] [--json FILE]``. Draws ``count``
outlines (a fixed seed: the same list every run): an ellipse of aspect 0.4-1 whose radius carries
three random harmonics of up to 15% each, sampled at 12-100 points, and in three draws of ten cut by a
straight wall (a disc cut by a wall, an apse). Meshes each with the defaults and prints one line per
plan (valid, min and mean scaled Jacobian, boundary singularities, inverted faces, or the error) and
a summary: valid meshes (no inverted face), plans below a min scaled Jacobian of 0.3 (issue 12's
floor), the boundary singularities in all and the mean of the worst scaled Jacobians. Such plans
have a skeleton of one singularity or one branch (vaultgram.testing.smooth); run on an older
checkout to compare.
"""

from __future__ import annotations

import argparse
import json
import statistics
from pathlib import Path

import numpy as np

from vaultgram.domain import domain_from_dict
from vaultgram.errors import VaultgramError
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import mesh_domain


def random_outline(rng: np.random.Generator) -> np.ndarray:
    """One outline as described in the module docstring (counter-clockwise)."""
    n = int(rng.integers(12, 100))
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 5 * (1 + sum(rng.uniform(-0.15, 0.15) * np.cos(j * t + rng.uniform(0, 6.28)) for j in range(1, 4)))
    squash = rng.uniform(0.4, 1.0)
    outer = np.column_stack([r * np.cos(t), squash * r * np.sin(t)])
    if rng.uniform() < 0.3:  # cut by a straight wall below the centre
        outer = outer[outer[:, 1] > -rng.uniform(0.3, 0.9) * squash * 5]
    return outer


def measure(k: int, outer: np.ndarray) -> dict:
    """The mesh of one outline at the defaults, measured (or the error)."""
    try:
        domain = domain_from_dict({"name": f"smooth_{k}", "outer": outer.tolist()})
        s = mesh_stats(mesh_domain(domain, allow_folds=True), domain)
    except VaultgramError as e:
        return {"plan": k, "error": str(e)}
    return {"plan": k, "min_sj": round(s["min_scaled_jacobian"], 3), "mean_sj": round(s["mean_scaled_jacobian"], 3),
            "boundary_singular": s["boundary_singular"], "inverted": s["inverted_faces"]}


def summary(rows: list[dict]) -> dict:
    meshed = [r for r in rows if "error" not in r]
    return {"plans": len(rows), "valid": sum(r["inverted"] == 0 for r in meshed),
            "refused": len(rows) - len(meshed), "below_0.3": sum(r["min_sj"] < 0.3 for r in meshed),
            "boundary_singular": sum(r["boundary_singular"] for r in meshed),
            "mean_min_sj": round(statistics.mean(r["min_sj"] for r in meshed), 3) if meshed else None}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=80)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--json", type=Path, help="write the rows and the summary here")
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    rows = [measure(k, random_outline(rng)) for k in range(args.count)]
    for row in rows:
        print(json.dumps(row))
    result = summary(rows)
    print(json.dumps(result, indent=1))
    if args.json:
        args.json.write_text(json.dumps({"rows": rows, "summary": result}, indent=1))


if __name__ == "__main__":
    main()
