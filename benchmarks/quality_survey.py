"""Survey the acceptance properties of §3.2 and §4 on many random domains.

Run: ``python benchmarks/quality_survey.py [--count N] [--seed S] [--kind convex|features|both]``.
Draws domains like the property tests do (``convex``: perturbed regular polygons, maybe with a round
hole; ``features``: a rectangle, maybe with a round hole, with 0-3 inner point features, 0-2 point
features on its sides and 0-2 curve features), meshes each at the default settings and sorts the outcome into

* ``ok`` -- every acceptance property holds;
* ``error`` -- a clear :class:`~vaultgram.errors.VaultgramError` (a feature too close for the
  spacing, a curve leaving the domain, a patch that is not 3- or 4-sided, a mesh that folds...);
  ``--errors`` prints how many of each kind;
* defects: ``folded`` (a face with scaled Jacobian <= 1e-3: inverted faces are a MeshFoldError, so
  these are the nearly degenerate ones), ``boundary singular`` (more boundary
  singularities than the index theorem forces: for these domains, none), ``feature not pole``,
  ``curve singular`` (a singular vertex inside a curve feature), ``extremity not pole``.

Prints the counts and, for each defect, the seed and index of the domain so it can be replayed
(``--show K``). Takes about a second per domain.
"""

from __future__ import annotations

import argparse
import json
import math
from collections import Counter

import numpy as np

from vaultgram.domain import domain_from_dict
from vaultgram.errors import VaultgramError
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import mesh_domain

DEGENERATE = 1e-3


def convex_domain(rng: np.random.Generator) -> dict:
    """A polygon of 4-7 corners at radius 10 +- 15%, maybe with a circular hole near the centre."""
    n = int(rng.integers(4, 8))
    t = rng.uniform(0, 2 * math.pi / n) + 2 * math.pi * np.arange(n) / n
    radii = 10 * rng.uniform(0.85, 1.15, n)
    data = {"outer": np.column_stack([radii * np.cos(t), radii * np.sin(t)]).tolist()}
    if rng.random() < 0.5:
        s = np.linspace(0, 2 * math.pi, 40, endpoint=False)
        c, r = rng.uniform(-1.5, 1.5, 2), rng.uniform(1.5, 3.5)
        data["holes"] = [(c + r * np.column_stack([np.cos(s), np.sin(s)])).tolist()]
    return data


def feature_domain(rng: np.random.Generator) -> dict:
    """A w x h rectangle, maybe with a round hole, with 0-3 inner points, 0-2 points on its sides and
    0-2 curves of 1-2 pieces."""
    w, h = rng.uniform(6, 14, 2)
    data = {"outer": [[0, 0], [w, 0], [w, h], [0, h]], "points": [], "curves": []}
    if rng.random() < 0.5:
        t = np.linspace(0, 2 * np.pi, 24, endpoint=False)[::-1]
        r = 0.15 * min(w, h)
        data["holes"] = [np.column_stack([w / 2 + r * np.cos(t), h / 2 + r * np.sin(t)]).tolist()]
    for _ in range(int(rng.integers(0, 4))):
        data["points"].append([rng.uniform(0.05, 0.95) * w, rng.uniform(0.05, 0.95) * h])
    for _ in range(int(rng.integers(0, 3))):  # on the outer boundary, away from its corners
        t = rng.uniform(0.05, 0.95)
        data["points"].append([[t * w, 0], [w, t * h], [t * w, h], [0, t * h]][int(rng.integers(0, 4))])
    for _ in range(int(rng.integers(0, 3))):
        pts = [np.array([rng.uniform(0.1, 0.9) * w, rng.uniform(0.1, 0.9) * h])]
        for _ in range(int(rng.integers(1, 3))):
            a, length = rng.uniform(0, 2 * np.pi), rng.uniform(0.1, 0.3) * min(w, h)
            pts.append(pts[-1] + length * np.array([np.cos(a), np.sin(a)]))
        data["curves"].append(np.array(pts).tolist())
    return data


def defects(stats: dict) -> list[str]:
    """The acceptance properties a mesh of these domains fails (none forces a boundary singularity)."""
    out = []
    if not stats["min_scaled_jacobian"] > DEGENERATE:
        out.append("folded")
    if stats["boundary_singular"]:
        out.append("boundary singular")
    if stats.get("feature_points_pole", 0) != stats.get("feature_points", 0):
        out.append("feature not pole")
    if stats.get("curve_interior_singular", 0):
        out.append("curve singular")
    if stats.get("curve_extremities_pole", 0) != stats.get("curve_extremities", 0):
        out.append("extremity not pole")
    return out


def error_kind(outcome: str) -> str:
    """A short name for the kind of error in an ``error: ...`` outcome."""
    for words, kind in ((("leaves the domain", "crosses", "inside hole"), "invalid domain"),
                        (("from the boundary", "from point feature", "from curve feature"), "too close"),
                        (("sides",), "patch not 3-4 sided"), (("mesh folds",), "mesh folds")):
        if any(w in outcome for w in words):
            return kind
    return "other"


def survey(kind: str, count: int, seed: int):
    """Yield ``(index, data, outcome list)`` for ``count`` domains of ``kind`` drawn from ``seed``."""
    rng = np.random.default_rng(seed)
    draw = convex_domain if kind == "convex" else feature_domain
    for k in range(count):
        data = draw(rng)
        try:
            domain = domain_from_dict(data)
            mesh = mesh_domain(domain)
        except VaultgramError as exc:
            yield k, data, [f"error: {str(exc).splitlines()[0][:90]}"]
            continue
        found = defects(mesh_stats(mesh, domain))
        yield k, data, found or ["ok"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=100)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--kind", choices=["convex", "features", "both"], default="both")
    ap.add_argument("--show", type=int, default=None, help="print domain K as JSON and stop")
    ap.add_argument("--errors", action="store_true", help="also count the errors by kind")
    args = ap.parse_args()
    kinds = ["convex", "features"] if args.kind == "both" else [args.kind]
    for kind in kinds:
        if args.show is not None:
            for k, data, _ in survey(kind, args.show + 1, args.seed):
                if k == args.show:
                    print(json.dumps(data))
            return
        tally, errors = Counter(), Counter()
        for k, _, outcome in survey(kind, args.count, args.seed):
            for o in outcome:
                tally["error" if o.startswith("error") else o] += 1
                if o.startswith("error"):
                    errors[error_kind(o)] += 1
            if outcome != ["ok"] and not outcome[0].startswith("error"):
                print(f"  {kind} seed {args.seed} #{k}: {', '.join(outcome)}")
        print(f"{kind}: {args.count} domains -> " + ", ".join(f"{v} {k}" for k, v in sorted(tally.items())))
        if args.errors and errors:
            print("  errors: " + ", ".join(f"{v} {k}" for k, v in sorted(errors.items())))


if __name__ == "__main__":
    main()
