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
corners round the worst vertex could reach at all, given its faces), the shortest edge over the median
edge (``short``: a quad with a vanished side scores well on the scaled Jacobian), the mesh's faces and the best
of ``R`` meshing CPU times (``mesh_domain``, process time: less noisy than wall-clock on a shared
machine, but still note the load beside them). ``--without-optimise`` measures the pipeline without
:func:`vaultgram.meshing.optimise.maximise_min_quality` (the comparison of the issue).

Finer sizes (issue 12 What 4: no fold and a min scaled Jacobian of 0.3 at any size): ``--scale S``
meshes at the default target length divided by ``S`` (about ``S**2`` times the faces: 2 and 4 are
"2x / 4x finer"), ``--faces N`` at ``target_length = sqrt(area / N)`` (``N`` faces asked: the
sessions' "8k / 16k"). Each takes several values, one table per value, e.g.
``pattern_quality.py --repeat 1 --plans shared,examples --scale 2 4 --faces 8000 16000``; ``--plans``
picks the kinds of plan (``shared``, ``examples``, ``rectilinear``, ``smooth``; default all).
"""

from __future__ import annotations

import argparse
import math
import os
import time

from benchpaths import ARCHITECTURE, EXAMPLES

from vaultgram import pipeline
from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.errors import VaultgramError
from vaultgram.meshing.densities import TARGET_FRACTION
from vaultgram.meshing.fans import fan_bounds
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import mesh_domain
from vaultgram.testing.orthogonal import RECTILINEAR_PLANS
from vaultgram.testing.smooth import SMOOTH_PLANS

KINDS = "shared,examples,rectilinear,smooth"


def plans(kinds: str = KINDS) -> dict:
    """The plans by name: shared plans, examples (domain files only), rectilinear and smooth plans
    (``kinds``: which of the four, comma-separated)."""
    out = {}
    for kind, folder in (("shared", ARCHITECTURE), ("examples", EXAMPLES)):
        for path in sorted(folder.glob("*.json")) if kind in kinds else ():
            try:
                out[path.stem] = load_domain(path)
            except VaultgramError:
                continue  # not a domain file (the skeleton example)
    for kind, made in (("rectilinear", RECTILINEAR_PLANS), ("smooth", SMOOTH_PLANS)):
        if kind in kinds:
            out.update({name: domain_from_dict({"name": name, **data}) for name, data in made.items()})
    return out


def target_length(domain, scale: float | None = None, faces: int | None = None) -> float | None:
    """The target edge length of a size: ``sqrt(area / faces)`` for ``faces`` faces asked, else the
    default divided by ``scale``; None (the default) for neither."""
    if faces:
        return math.sqrt(domain.area / faces)
    return TARGET_FRACTION * domain.diagonal / scale if scale else None


def measure(domain, repeat: int, target: float | None = None) -> str:
    """One table row: the mesh's quality and the best meshing time of ``repeat`` runs."""
    best = float("inf")
    for _ in range(repeat):
        start = time.process_time()
        mesh = mesh_domain(domain, target_length=target, allow_folds=True)
        best = min(best, time.process_time() - start)
    s = mesh_stats(mesh, domain)
    return (f"{mesh.info['patches']:5d} {mesh.info['triangle_patches']:4d} {s['interior_singular']:4d} "
            f"{s['boundary_singular']:4d} {s['boundary_feature_singular']:4d} {s['min_scaled_jacobian']:7.3f} "
            f"{s['mean_scaled_jacobian']:7.3f} {s['inverted_faces']:4d} {s['boundary_distance_relative']:8.5f} "
            f"{fan_bounds(mesh.vertices, mesh.faces).min():6.3f} {s['shortest_over_median_edge']:7.4f} "
            f"{len(mesh.faces):7d} {best:7.3f}")


def table(domains: dict, names: list, repeat: int, label: str, scale: float | None, faces: int | None) -> None:
    """One table: every plan (those in ``names``, if any) meshed at one size (``label``)."""
    print(f"size: {label}; load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print(f"{'plan':28s} patch  tri  int  bnd feat  min SJ mean SJ  inv bnd dist    fan   short   faces   cpu s")
    total = 0.0
    for name, domain in domains.items():
        if names and name not in names:
            continue
        try:
            row = measure(domain, repeat, target_length(domain, scale, faces))
        except VaultgramError as exc:
            row = f"error: {str(exc).splitlines()[0][:80]}"
        else:
            total += float(row.split()[-1])
        print(f"{name:28s} {row}", flush=True)
    print(f"total meshing time {total:.2f} s; load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("names", nargs="*", help="plans to measure (default all)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--without-optimise", action="store_true", help="skip the max-min optimisation")
    ap.add_argument("--scale", type=float, nargs="+", default=[], help="the default target length / SCALE")
    ap.add_argument("--faces", type=int, nargs="+", default=[], help="target length sqrt(area / FACES)")
    ap.add_argument("--plans", default=KINDS, help=f"kinds of plan, comma-separated (default {KINDS})")
    args = ap.parse_args()
    if args.without_optimise:
        pipeline.maximise_min_quality = lambda x, *_a, **_k: x
    sizes = [(f"default / {s:g}", s, None) for s in args.scale] + [(f"{n} faces asked", None, n) for n in args.faces]
    domains = plans(args.plans)
    for label, scale, faces in sizes or [("default", None, None)]:
        table(domains, args.names, args.repeat, label, scale, faces)


if __name__ == "__main__":
    main()
