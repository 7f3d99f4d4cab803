"""Time the exploration of topology variants (issue 13): the search and the de-duplication.

Run: ``python benchmarks/explore.py [--spacing S] [--limit N] [--depth D] [--order breadth|best]``.
Two inputs: the quad with a hole (examples/quad_with_hole.json) plus two boundary point features
and one curve feature, and ``../shared/data/architecture/two_holes_five_points.json``. For each,
one row: states visited, distinct variants, invalid states, hashes, exact checks and collisions, the search's states per
second (hash only: no meshing; also per second of this process's CPU time, steadier on a shared
machine), and the time per state and per variant (search alone, then with the
evaluation of every variant: rebuild, mesh, metrics, one process).

Then the de-duplication alone at a 100-node layout (the Rolex Learning Center plan, 122 corner
points): per state, making the layout, hashing it and the exact check against an
isomorphic copy (the worst case: every state a duplicate), in wall-clock and in this process's CPU
time (steadier on a shared machine), beside one networkx VF2 check with the
refined colours as labels (the fallback when refinement leaves colours shared; plain VF2 with the
type labels alone did not finish in 10 minutes on this 570-node layout graph).
Floors (issue 13): >= 200 states/s hash only; de-duplication < 1 ms per state at 100-node layouts.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path

import numpy as np
from benchpaths import ARCHITECTURE, EXAMPLES

from vaultgram.domain import load_domain
from vaultgram.exploration.explore import ExploreOptions, explore
from vaultgram.exploration.layout import PatchLayout, _vf2, layout_of, same_layout
from vaultgram.exploration.search import search
from vaultgram.pipeline import decompose
from vaultgram.topology.decomposition import decomposition_graph
from vaultgram.topology.rulebook import load_vault_rulebook

QUAD = EXAMPLES / "quad_with_hole.json"
TWO_HOLES = ARCHITECTURE / "two_holes_five_points.json"
ROLEX = ARCHITECTURE / "rolex_learning_centre.json"


def featured_quad() -> Path:
    """The quad with a hole with two boundary point features and one curve feature, as a file."""
    data = json.loads(QUAD.read_text())
    data.update(name="quad_with_hole_features", points=[[5.0, 0.0], [10.0, 5.0]], curves=[[[5.0, 7.5], [5.0, 9.0]]])
    path = Path(tempfile.mkdtemp()) / "quad_with_hole_features.json"
    path.write_text(json.dumps(data))
    return path


def search_row(path: Path, spacing: float, limit: int, depth: int, order: str) -> dict:
    """One input's search (hash only) and full exploration, timed."""
    domain = load_domain(path)
    book = load_vault_rulebook()
    sk = decompose(domain, spacing).skeleton
    graph, cpu = decomposition_graph(sk, book), time.process_time()
    result = search(book, graph, sk.triangulation.disc, limit, depth, order=order)
    cpu = time.process_time() - cpu
    start = time.perf_counter()
    explore(domain, ExploreOptions(spacing=spacing, limit=limit, depth=depth, order=order))
    full = time.perf_counter() - start
    n, v = len(result.states), len(result.variants)
    invalid = sum(s.invalid is not None for s in result.states)
    return {"input": domain.name, "order": order, "states": n, "variants": v, "invalid": invalid,
            "hashes": result.hashes, "exact_checks": result.exact_checks, "collisions": result.collisions,
            "states_per_s": round(n / result.seconds, 1), "states_per_cpu_s": round(n / cpu, 1),
            "ms_per_state": round(1000 * result.seconds / n, 1),
            "ms_per_variant": round(1000 * result.seconds / v, 1), "explore_s": round(full, 2),
            "explore_ms_per_variant": round(1000 * full / v, 1)}


def shuffled(layout: PatchLayout, seed: int = 0) -> PatchLayout:
    """An isomorphic copy: points and darts renumbered."""
    rng = np.random.default_rng(seed)
    points, darts = rng.permutation(layout.size()), rng.permutation(len(layout.dart_point))
    new_of_dart = np.empty_like(darts)
    new_of_dart[darts] = np.arange(len(darts))
    labels = [None] * layout.size()
    for old, new in enumerate(points):
        labels[new] = layout.point_labels[old]
    return PatchLayout(tuple(labels), layout.patch_sides, points[layout.dart_point[darts]], layout.dart_patch[darts],
                       new_of_dart[layout.dart_next[darts]], layout.dart_pole[darts])


def dedup_row(repeat: int = 200) -> dict:
    """The de-duplication cost per state at about 100 layout nodes (module docstring): the Rolex
    Learning Center plan at spacing 0.02 (122 corner points)."""
    dec = decompose(load_domain(ROLEX), 0.02)
    base = layout_of(dec.graph, list(dec.patches))
    copies = [shuffled(base, k) for k in range(repeat)]
    for copy in copies:
        copy.hash, copy.certificate  # the earlier variant's hash and certificate are known already
    start, cpu = time.perf_counter(), time.process_time()
    for copy in copies:
        fresh = layout_of(dec.graph, list(dec.patches))
        assert fresh.hash == copy.hash and same_layout(copy, fresh)
    per_state, cpu_per_state = (time.perf_counter() - start) / repeat, (time.process_time() - cpu) / repeat
    start = time.perf_counter()
    assert _vf2(base, copies[0])  # the fallback for layouts that refinement leaves with shared colours
    vf2 = time.perf_counter() - start
    return {"input": dec.disc.domain.name, "layout_nodes": base.size(), "darts": len(base.dart_point),
            "dedup_ms_per_state": round(1000 * per_state, 3), "dedup_cpu_ms_per_state": round(1000 * cpu_per_state, 3),
            "coloured_vf2_ms": round(1000 * vf2, 1)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spacing", type=float, default=0.05)
    parser.add_argument("--limit", type=int, default=60)
    parser.add_argument("--depth", type=int, default=8)
    parser.add_argument("--order", choices=["breadth", "best"], default="breadth")
    args = parser.parse_args()
    inputs = [featured_quad()] + ([TWO_HOLES] if TWO_HOLES.is_file() else [])
    for path in inputs:
        print(json.dumps(search_row(path, args.spacing, args.limit, args.depth, args.order)))
    if ROLEX.is_file():
        print(json.dumps(dedup_row()))


if __name__ == "__main__":
    main()
