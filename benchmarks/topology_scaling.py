"""Time the topology stages (§3.1) on examples/quad_with_hole.json at decreasing spacings.

Run: ``python benchmarks/topology_scaling.py [--repeat N]``. Prints one row per spacing with the
number of points and faces and the best-of-N wall time of each step (discretise, triangulate,
skeleton, typed graph, rules, patches) and of the whole :func:`decompose` call (which also loads and
checks the rulebook). The target for the whole decomposition at spacing 0.005 is < 1 s.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from vaultgram.domain import load_domain
from vaultgram.engine.strategy import Runner
from vaultgram.pipeline import decompose
from vaultgram.topology.decomposition import decomposition_graph
from vaultgram.topology.discretise import discretise
from vaultgram.topology.patches import find_patches
from vaultgram.topology.rulebook import load_vault_rulebook
from vaultgram.topology.skeleton import skeleton
from vaultgram.topology.triangulation import triangulate
from vaultgram.topology.types import PLAN_EDGES

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "quad_with_hole.json"
SPACINGS = (0.05, 0.02, 0.01, 0.005, 0.002)


def best_of(fn, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    domain = load_domain(EXAMPLE)
    book = load_vault_rulebook()
    head = (f"{'spacing':>8} {'points':>7} {'faces':>7} {'sing':>5} {'patches':>7} {'discretise':>11} "
            f"{'triangulate':>12} {'skeleton':>9} {'graph':>7} {'rules':>7} {'patches':>8} {'decompose':>10}")
    print(f"{domain.name}: best of {args.repeat}, seconds")
    print(head)
    print("-" * len(head))
    for s in SPACINGS:
        t_d, disc = best_of(lambda: discretise(domain, s), args.repeat)
        t_t, tri = best_of(lambda: triangulate(disc), args.repeat)
        t_s, sk = best_of(lambda: skeleton(tri), args.repeat)
        t_g, _ = best_of(lambda: decomposition_graph(sk, book), args.repeat)

        def rewrite():
            graph = decomposition_graph(sk, book)
            start = time.perf_counter()
            Runner(book, graph).run("topology")
            return time.perf_counter() - start, graph

        t_r, graph = min(rewrite() for _ in range(args.repeat))
        t_p, patches = best_of(lambda: find_patches(graph, disc, PLAN_EDGES), args.repeat)
        t_all, _ = best_of(lambda: decompose(domain, s), args.repeat)
        print(
            f"{s:>8g} {len(disc.points):>7d} {tri.n_faces:>7d} {len(sk.singularities()):>5d} {len(patches):>7d} "
            f"{t_d:>11.4f} {t_t:>12.4f} {t_s:>9.4f} {t_g:>7.4f} {t_r:>7.4f} {t_p:>8.4f} {t_all:>10.4f}"
        )


if __name__ == "__main__":
    main()
