"""Pattern quality and meshing time on real and rectilinear plans (the issue "pattern quality on
real plans").

Run: ``python benchmarks/pattern_quality.py [--repeat R] [NAME ...]``. Meshes every shared plan
(``../shared/data/architecture/*.json`` beside the repository, when present), every example and the
rectilinear plans of :data:`vaultgram.testing.orthogonal.RECTILINEAR_PLANS` and the plans of a
degenerate skeleton of :data:`vaultgram.testing.smooth.SMOOTH_PLANS` at the default settings,
and prints per plan: patches (triangles among them), interior and boundary singular vertices (the
boundary ones by the regular valence of their angle, boundary point features apart), min and mean
scaled Jacobian, inverted faces, the boundary's distance from the domain's (relative to the
diagonal), the fan bound (:func:`vaultgram.meshing.fans.fan_bounds`: the best scaled Jacobian the
corners round the worst vertex could reach at all, given its faces) and the best of ``R`` meshing
CPU times (``mesh_domain``, process time: less noisy than wall-clock on a shared machine, but still
note the load beside them). ``--without-optimise`` measures the pipeline without
:func:`vaultgram.meshing.optimise.maximise_min_quality` (the comparison of the issue).
"""

from __future__ import annotations

import argparse
import os
import time

from benchpaths import ARCHITECTURE, EXAMPLES

from vaultgram import pipeline
from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.errors import VaultgramError
from vaultgram.meshing.fans import fan_bounds
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import mesh_domain
from vaultgram.testing.orthogonal import RECTILINEAR_PLANS
from vaultgram.testing.smooth import SMOOTH_PLANS


def plans() -> dict:
    """The plans by name: shared plans, examples (domain files only), rectilinear plans."""
    out = {}
    for path in sorted(ARCHITECTURE.glob("*.json")) + sorted(EXAMPLES.glob("*.json")):
        try:
            out[path.stem] = load_domain(path)
        except VaultgramError:
            continue  # not a domain file (the skeleton example)
    for made in (RECTILINEAR_PLANS, SMOOTH_PLANS):
        out.update({name: domain_from_dict({"name": name, **data}) for name, data in made.items()})
    return out


def measure(domain, repeat: int) -> str:
    """One table row: the mesh's quality and the best meshing time of ``repeat`` runs."""
    best = float("inf")
    for _ in range(repeat):
        start = time.process_time()
        mesh = mesh_domain(domain, allow_folds=True)
        best = min(best, time.process_time() - start)
    s = mesh_stats(mesh, domain)
    return (f"{mesh.info['patches']:5d} {mesh.info['triangle_patches']:4d} {s['interior_singular']:4d} "
            f"{s['boundary_singular']:4d} {s['boundary_feature_singular']:4d} {s['min_scaled_jacobian']:7.3f} "
            f"{s['mean_scaled_jacobian']:7.3f} {s['inverted_faces']:4d} {s['boundary_distance_relative']:8.5f} "
            f"{fan_bounds(mesh.vertices, mesh.faces).min():6.3f} {best:7.3f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("names", nargs="*", help="plans to measure (default all)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--without-optimise", action="store_true", help="skip the max-min optimisation")
    args = ap.parse_args()
    if args.without_optimise:
        pipeline.maximise_min_quality = lambda x, *_a, **_k: x
    print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print(f"{'plan':28s} patch  tri  int  bnd feat  min SJ mean SJ  inv bnd dist  fan  cpu s")
    total = 0.0
    for name, domain in plans().items():
        if args.names and name not in args.names:
            continue
        try:
            row = measure(domain, args.repeat)
        except VaultgramError as exc:
            row = f"error: {str(exc).splitlines()[0][:80]}"
        else:
            total += float(row.split()[-1])
        print(f"{name:28s} {row}", flush=True)
    print(f"total meshing time {total:.2f} s; load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
