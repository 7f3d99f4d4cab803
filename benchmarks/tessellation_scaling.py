"""Time the tessellation (§5) at about 10^3, 10^4 and 10^5 faces.

Run: ``python benchmarks/tessellation_scaling.py [--sizes 1e3,1e4,1e5] [--repeat N]``. The surface is
examples/quad_with_hole.json meshed at the target length ``sqrt(area / faces)`` and lifted to a dome
``z = rise * (1 - (2x/w - 1)^2) * (1 - (2y/h - 1)^2)`` (tessellation needs a surface and its supports,
not the equilibrium, so form finding is left out), supported on its outer boundary. Each row gives the
faces, the voussoirs and the best-of-N seconds of each step of :func:`vaultgram.pipeline.tessellate`
(refine, keystones by the rulebook, stagger, sizes, solids) and in all, and the time per 10^5 faces
(it should stay flat: the tessellation is linear in faces). Floor: 10^5 faces in under 5 s.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from vaultgram.domain import load_domain
from vaultgram.formfinding.supports import support_vertices
from vaultgram.pipeline import mesh_domain, tessellate
from vaultgram.tessellation.surface import ThrustSurface, surface_from_json

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "quad_with_hole.json"
STEPS = ("refine", "keystones", "stagger", "sizes", "solids")


def dome(faces_wanted: int) -> ThrustSurface:
    """The example meshed to about ``faces_wanted`` faces, lifted to a dome, outer boundary supported."""
    domain = load_domain(EXAMPLE)
    mesh = mesh_domain(domain, target_length=math.sqrt(domain.area / faces_wanted))
    xy = np.asarray(mesh.vertices)[:, :2]
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    u = 2 * (xy - lo) / (hi - lo) - 1
    z = 0.25 * (hi - lo).min() * (1 - u[:, 0] ** 2) * (1 - u[:, 1] ** 2)
    anchors = support_vertices(mesh.vertices, mesh.faces, None, domain)
    return surface_from_json({"vertices": np.column_stack([xy, z]).tolist(),
                              "faces": [list(f) for f in mesh.faces], "anchors": anchors.tolist()})


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="1e3,1e4,1e5")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    head = f"{'faces':>8} {'voussoirs':>9} " + " ".join(f"{s:>9}" for s in STEPS) + f" {'total':>8} {'s/1e5 f':>8}"
    print(head)
    print("-" * len(head))
    for size in (int(float(s)) for s in args.sizes.split(",")):
        surface = dome(size)
        tessellate(surface, thickness=0.1)  # load the rulebook once: not part of the cost per surface
        best = None
        for _ in range(args.repeat):
            timings: dict = {}
            start = time.perf_counter()
            result = tessellate(surface, thickness=0.1, timings=timings)
            total = time.perf_counter() - start
            if best is None or total < best[0]:
                best = (total, timings, result)
        total, timings, result = best
        f = len(surface.faces)
        print(f"{f:>8} {result.layout.n_voussoirs:>9} " + " ".join(f"{timings.get(s, 0.0):>9.3f}" for s in STEPS)
              + f" {total:>8.3f} {total / f * 1e5:>8.3f}", flush=True)


if __name__ == "__main__":
    main()
