"""Time the geometry stages (§3.2) at about 10^3, 10^4 and 10^5 faces.

Run: ``python benchmarks/mesh_scaling.py [--repeat N] [--sizes 1e3,1e4,1e5]``. Domains:
examples/quad_with_hole.json and a square with three circular holes. For each target face count the
target edge length is ``sqrt(area / faces)``; each row gives the faces obtained and the best-of-N
time of each stage: decompose (§3.1: discretise, triangulate, skeleton, rules), edge groups and
counts, discrete Coons patches and welding, smoothing (default iterations), untangling (of the faces
left nearly degenerate), and the whole
:func:`vaultgram.pipeline.mesh_domain` call. Also printed: smoothing time per 10^5 faces (it should stay
flat: smoothing is linear in faces), and the mesh's minimum scaled Jacobian.
Floor: 10^5 faces in under 5 s end to end.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.meshing.quality import mesh_stats
from vaultgram.meshing.smoothing import DEFAULT_ITERATIONS
from vaultgram.pipeline import mesh_domain

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "quad_with_hole.json"


def three_holes():
    """A 12 x 8 rectangle with three circular openings."""
    t = np.linspace(0, 2 * np.pi, 48, endpoint=False)
    circle = np.column_stack([np.cos(t), np.sin(t)])
    holes = [(c + 1.2 * circle).tolist() for c in ([3.0, 4.0], [6.0, 4.0], [9.0, 4.0])]
    return domain_from_dict({"name": "three_holes", "outer": [[0, 0], [12, 0], [12, 8], [0, 8]], "holes": holes})


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--sizes", default="1e3,1e4,1e5")
    args = ap.parse_args()
    sizes = [int(float(s)) for s in args.sizes.split(",")]
    domains = [load_domain(EXAMPLE), three_holes()]
    print(f"smoothing iterations: {DEFAULT_ITERATIONS}")
    header = f"{'domain':14s} {'target':>8s} {'faces':>8s} {'decomp':>7s} {'groups':>7s} {'weld':>7s} " \
             f"{'smooth':>7s} {'untang':>7s} {'total':>7s} {'smooth/1e5f':>11s} {'min SJ':>7s}"
    print(header)
    for domain in domains:
        for n in sizes:
            target = math.sqrt(domain.area / n)
            best = None
            for _ in range(args.repeat):
                timings: dict = {}
                t0 = time.perf_counter()
                mesh = mesh_domain(domain, target_length=target, timings=timings)
                total = time.perf_counter() - t0
                if best is None or total < best[0]:
                    best = (total, mesh, timings)
            total, mesh, s = best
            f = mesh.n_faces
            decomp = sum(s[k] for k in ("discretise", "triangulate", "skeleton", "rules"))
            print(f"{domain.name:14s} {target:8.4f} {f:8d} {decomp:7.3f} {s['groups']:7.3f} {s['weld']:7.3f} "
                  f"{s['smooth']:7.3f} {s['untangle']:7.3f} {total:7.3f} {s['smooth'] / f * 1e5:11.3f} "
                  f"{mesh_stats(mesh)['min_scaled_jacobian']:7.3f}")


if __name__ == "__main__":
    main()
