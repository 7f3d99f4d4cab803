"""Engine scaling: search-plan matching vs networkx subgraph monomorphisms, `all`, fixpoint, incremental.

Typed grid-like host graphs (a square grid whose nodes alternate types A and B like a checkerboard,
edges of type E) of about 10^3, 10^4 and 10^5 nodes. For each size:

* find all matches of a 3-node typed path pattern (A -E- B -E- A) with the engine (as a sorted
  table of columns, and as Match objects), and enumerate the same pattern with networkx
  ``GraphMatcher.subgraph_monomorphisms_iter`` (typed node/edge match);
* run a rule with a NAC (mark each A-B pair once with an F edge unless already marked) with ``all``
  and then to ``fixpoint`` (nothing left to do: it measures the full re-check), and a fixpoint that
  applies every match one at a time with incremental re-matching;
* measure one incremental re-match after a single local change (delete one E edge).

Usage: python benchmarks/engine_scaling.py [--sizes 1000 10000 100000] [--no-baseline] [--construction]
[--all-only]

``--all-only`` only runs the NAC rule with ``all`` and prints wall and CPU microseconds per
application (issue 18's floor: under 15 us at 10^5 nodes).

``--construction`` only times building the host graph: in bulk from arrays, one element at a time,
and as a networkx Graph (the issue-18 floor: bulk at most 3x networkx; sizes up to 10^6 are cheap).
Prints a table; never used by tests.
"""

from __future__ import annotations

import argparse
import gc
import math
import time

import networkx as nx
import numpy as np
from networkx.algorithms import isomorphism

from vaultgram.engine.columnar import forget_arrays
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.incremental import MatchSet
from vaultgram.engine.matcher import Matcher
from vaultgram.engine.rulebook import rulebook_from_text
from vaultgram.engine.strategy import Runner

RULES = """
schema bench {
  node A
  node B
  edge E (Node -- Node)
  edge F (A -- B)
}
rule path3 {
  match { a: A  b: B  c: A  a -E- b  b -E- c }
}
rule mark {
  match { a: A  b: B  a -E- b }
  not { a -F- b }
  create a -F- b
}
strategy mark_all { mark all }
strategy mark_fixpoint { mark fixpoint max 1000000 }
"""


def grid(rulebook, n_nodes: int) -> HostGraph:
    side = int(math.isqrt(n_nodes))
    g = HostGraph(rulebook.schema)
    for i in range(side):
        for j in range(side):
            g.add_node("A" if (i + j) % 2 == 0 else "B", id=i * side + j)
    for i in range(side):
        for j in range(side):
            n = i * side + j
            if j + 1 < side:
                g.add_edge("E", n, n + 1)
            if i + 1 < side:
                g.add_edge("E", n, n + side)
    g.forget()
    return g


def grid_arrays(n_nodes: int):
    """The checkerboard grid of :func:`grid` as arrays: A ids, B ids, edge ends (k, 2)."""
    side = int(math.isqrt(n_nodes))
    ids = np.arange(side * side)
    i, j = np.divmod(ids, side)
    ends = np.vstack([np.column_stack([ids[j + 1 < side], ids[j + 1 < side] + 1]),
                      np.column_stack([ids[i + 1 < side], ids[i + 1 < side] + side])])
    return ids[(i + j) % 2 == 0], ids[(i + j) % 2 == 1], ends


def construction(size: int) -> dict:
    """Seconds to build the grid host graph in bulk from arrays (``add_nodes`` / ``add_edges``, the
    cyclic garbage collector paused), one element at a time (:func:`grid`), and as a networkx Graph
    with a type attribute (acceptance: bulk at most 3x networkx)."""
    rulebook = rulebook_from_text(RULES)
    a, b, ends = grid_arrays(size)

    def bulk():
        g = HostGraph(rulebook.schema)
        g.add_nodes("A", a)
        g.add_nodes("B", b)
        g.add_edges("E", ends)
        return g

    def networkx():
        h = nx.Graph()
        h.add_nodes_from(a.tolist(), type="A")
        h.add_nodes_from(b.tolist(), type="B")
        h.add_edges_from(ends.tolist(), type="E")
        return h

    row = {"nodes": len(a) + len(b), "edges": len(ends)}
    for name, build in (("bulk_s", bulk), ("one_by_one_s", lambda: grid(rulebook, size)), ("networkx_s", networkx)):
        paused = gc.isenabled()
        gc.disable()
        try:
            _, row[name] = timed(build)
        finally:
            if paused:
                gc.enable()
    row["bulk_vs_networkx"] = row["bulk_s"] / row["networkx_s"]
    return row


CYCLE = """
schema cycle { node A  node B  edge E (Node -- Node) }
rule square { match { a: A  b: B  c: A  d: B  a -E- b  b -E- c  c -E- d  d -E- a } }
"""


def bulk_grid(schema, size: int) -> HostGraph:
    """The checkerboard grid, built in bulk from arrays (``add_nodes`` / ``add_edges``)."""
    a, b, ends = grid_arrays(size)
    g = HostGraph(schema)
    g.add_nodes("A", a)
    g.add_nodes("B", b)
    g.add_edges("E", ends)
    return g


def _peak_mb() -> float:
    """This process's peak resident memory so far (MB)."""
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def cycle_engine(size: int) -> dict:
    """The 4-cycle (a square of the checkerboard, A-B-A-B) with the engine: every match as a sorted
    table, then as Match objects; the peak memory of the whole process (graph included)."""
    g, t_build = timed(lambda: bulk_grid(rulebook_from_text(CYCLE).schema, size))
    matcher = Matcher(rulebook_from_text(CYCLE).rules["square"], g)
    table, t_match = timed(matcher.table)
    return {"nodes": len(g), "matches": table.rows, "build_s": t_build, "engine_s": t_match, "peak_mb": _peak_mb()}


def _typed_nx(size: int):
    """The checkerboard grid as a networkx Graph with a ``type`` attribute, and the typed 4-cycle."""
    a, b, ends = grid_arrays(size)
    host = nx.Graph()
    host.add_nodes_from(a.tolist(), type="A")
    host.add_nodes_from(b.tolist(), type="B")
    host.add_edges_from(ends.tolist(), type="E")
    motif = nx.Graph()
    motif.add_nodes_from([("a", {"type": "A"}), ("b", {"type": "B"}), ("c", {"type": "A"}), ("d", {"type": "B"})])
    motif.add_edges_from([(u, v, {"type": "E"}) for u, v in ("ab", "bc", "cd", "da")])
    return host, motif


def cycle_peer(size: int, peer: str) -> dict:
    """The same 4-cycle count with networkx's VF2 (typed monomorphisms) or grandiso (the ``peers``
    extra; it streams its search), and the peak memory."""
    host, motif = _typed_nx(size)
    if peer == "grandiso":
        import grandiso

        search = lambda: sum(1 for _ in grandiso.find_motifs_iter(motif, host))  # noqa: E731
    else:
        same = lambda x, y: x["type"] == y["type"]  # noqa: E731
        matcher = isomorphism.GraphMatcher(host, motif, node_match=same, edge_match=same)
        search = lambda: sum(1 for _ in matcher.subgraph_monomorphisms_iter())  # noqa: E731
    count, seconds = timed(search)
    return {"nodes": host.number_of_nodes(), "matches": count, f"{peer}_s": seconds, "peak_mb": _peak_mb()}


def cycles(sizes, peers, peer_max: int) -> list[dict]:
    """Each size's 4-cycle search in a fresh process per tool (so that peak memory is its own)."""
    import json
    import subprocess
    import sys

    rows = []
    for size in sizes:
        row = {}
        for tool in ["engine", *(p for p in peers if size <= peer_max)]:
            out = subprocess.run([sys.executable, __file__, "--cycle-one", str(size), tool], check=True,
                                 capture_output=True, text=True).stdout
            one = json.loads(out)
            row.setdefault("matches", one["matches"])
            assert one["matches"] == row["matches"], (tool, one["matches"], row["matches"])
            row.update({k: v for k, v in one.items() if k != "peak_mb"}, **{f"{tool}_peak_mb": one["peak_mb"]})
        rows.append(row)
    return rows


def networkx_baseline(g: HostGraph) -> tuple[int, float]:
    host = nx.Graph()
    for n in g.nodes():
        host.add_node(n, type=g.node_type(n))
    for e in g.edges():
        host.add_edge(*g.ends(e), type=g.edge_type(e))
    pattern = nx.Graph()
    pattern.add_nodes_from([("a", {"type": "A"}), ("b", {"type": "B"}), ("c", {"type": "A"})])
    pattern.add_edges_from([("a", "b", {"type": "E"}), ("b", "c", {"type": "E"})])
    matcher = isomorphism.GraphMatcher(
        host, pattern, node_match=lambda x, y: x["type"] == y["type"], edge_match=lambda x, y: x["type"] == y["type"]
    )
    start = time.perf_counter()
    count = sum(1 for _ in matcher.subgraph_monomorphisms_iter())
    return count, time.perf_counter() - start


def timed(fn):
    start = time.perf_counter()
    result = fn()
    return result, time.perf_counter() - start


def run(size: int, baseline: bool) -> dict:
    rulebook = rulebook_from_text(RULES)
    g = grid(rulebook, size)
    matcher = Matcher(rulebook.rules["path3"], g)
    def cold():  # all matches, sorted by key, as columns, building the graph's arrays first
        forget_arrays(g)
        return matcher.table()

    table, t_first = timed(cold)
    t_match = min([t_first] + [timed(cold)[1] for _ in range(2)])  # best of 3, arrays rebuilt each time
    t_warm = min(timed(matcher.table)[1] for _ in range(3))  # the same search with the arrays cached
    matches, t_objects = timed(matcher.all)  # the same as a list of Match objects
    row = {"nodes": len(g), "edges": g.num_edges, "matches": table.rows, "engine_s": t_match,
           "warm_s": t_warm, "as_objects_s": t_objects}
    if baseline:
        count, t_nx = networkx_baseline(g)
        assert count == len(matches) == table.rows, (count, len(matches))
        row.update(networkx_s=t_nx, speedup=t_nx / t_match)

    runner = Runner(rulebook, g)
    _, row["all_s"] = timed(lambda: runner.run("mark_all"))
    row["all_applied"] = runner.reports[-1].applications
    row["all_us"] = row["all_s"] / max(row["all_applied"], 1) * 1e6
    _, row["fixpoint_recheck_s"] = timed(lambda: runner.run("mark_fixpoint"))

    g2 = grid(rulebook, size)
    runner2 = Runner(rulebook, g2)
    _, row["fixpoint_s"] = timed(lambda: runner2.run("mark_fixpoint"))
    row["fixpoint_applied"] = runner2.reports[-1].applications

    # one local change, then an incremental re-match of the path pattern
    g3 = grid(rulebook, size)
    mset = MatchSet(Matcher(rulebook.rules["path3"], g3))
    centre = len(g3) // 2 + int(math.isqrt(len(g3))) // 2
    e = next(iter(g3.incident(centre)))
    mark = g3.mark()
    g3.remove_edge(e)
    changes = g3.changes_since(mark)
    times = []
    for _ in range(201):
        start = time.perf_counter()
        mset.update(changes)
        times.append(time.perf_counter() - start)
    row["incremental_ms"] = sorted(times)[100] * 1000  # the median: a garbage-collector pause is not the engine
    fresh = {m.key for m in Matcher(rulebook.rules["path3"], g3).all()}
    assert fresh == set(mset.matches), "incremental match set differs from a full search"
    return row


def mark_all(size: int, repeats: int = 3) -> dict:
    """``mark all`` alone on fresh grids (best of ``repeats``): wall and CPU microseconds per
    application (issue 18's floor: under 15 us per application at 10^5 nodes)."""
    rulebook = rulebook_from_text(RULES)
    best = None
    for _ in range(repeats):
        runner = Runner(rulebook, grid(rulebook, size))
        cpu = time.process_time()
        _, wall = timed(lambda: runner.run("mark_all"))
        cpu = time.process_time() - cpu
        applied = runner.reports[-1].applications
        row = {"nodes": len(runner.graph), "applied": applied, "all_s": wall,
               "wall_us": wall / applied * 1e6, "cpu_us": cpu / applied * 1e6}
        best = row if best is None or row["cpu_us"] < best["cpu_us"] else best
    return best


def print_cycles(rows: list[dict]) -> None:
    """The 4-cycle table, with the time growth of the engine from one size to the next (issue 18's
    floor: at most 11x from 10^5 to 10^6 nodes, peak memory at most 2 GB)."""
    cols = ["nodes", "matches", "build_s", "engine_s", "growth", "engine_peak_mb", "networkx_s",
            "networkx_peak_mb", "grandiso_s", "grandiso_peak_mb"]
    print(" ".join(f"{c:>16}" for c in cols))
    for prev, row in zip([None, *rows], rows):
        row["growth"] = row["engine_s"] / prev["engine_s"] if prev else float("nan")
        print(" ".join(f"{row.get(c, float('nan')):>16.4g}" if isinstance(row.get(c, 0.0), float)
                       else f"{row[c]:>16}" for c in cols), flush=True)


def print_table(cols, rows, width: int) -> None:
    """One line of column names, then one per row as it comes (floats to 4 digits, a missing value as nan)."""
    print(" ".join(f"{c:>{width}}" for c in cols))
    for row in rows:
        print(" ".join(f"{row.get(c, float('nan')):>{width}.4g}" if isinstance(row.get(c, 0.0), float)
                       else f"{row[c]:>{width}}" for c in cols), flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1_000, 10_000, 100_000])
    parser.add_argument("--no-baseline", action="store_true", help="skip the networkx baseline")
    parser.add_argument("--construction", action="store_true",
                        help="only time building the host graph (bulk, one by one, networkx); 10^6 nodes take ~1 min")
    parser.add_argument("--cycles", action="store_true",
                        help="only the 4-cycle: engine (time, peak memory) beside the --peers; sizes up to 10^6")
    parser.add_argument("--peers", nargs="*", default=["networkx", "grandiso"],
                        help="with --cycles: networkx and/or grandiso (pip install 'vaultgram[peers]')")
    parser.add_argument("--peer-max", type=int, default=100_000,
                        help="with --cycles: run the peers only up to this many nodes (they take minutes beyond)")
    parser.add_argument("--all-only", action="store_true",
                        help="only the rule with a NAC applied with all, per application (best of 3 fresh grids)")
    parser.add_argument("--cycle-one", nargs=2, metavar=("SIZE", "TOOL"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.cycle_one:
        import json

        size, tool = int(args.cycle_one[0]), args.cycle_one[1]
        print(json.dumps(cycle_engine(size) if tool == "engine" else cycle_peer(size, tool)))
        return
    if args.cycles:
        print_cycles(cycles(args.sizes, args.peers, args.peer_max))
        return
    if args.all_only:
        print_table(["nodes", "applied", "all_s", "wall_us", "cpu_us"], map(mark_all, args.sizes), 12)
        return
    if args.construction:
        print_table(["nodes", "edges", "bulk_s", "one_by_one_s", "networkx_s", "bulk_vs_networkx"],
                    map(construction, args.sizes), 16)
        return
    print_table(["nodes", "edges", "matches", "engine_s", "warm_s", "as_objects_s", "networkx_s", "speedup", "all_s",
                 "all_applied", "all_us", "fixpoint_recheck_s", "fixpoint_s", "fixpoint_applied", "incremental_ms"],
                (run(size, not args.no_baseline) for size in args.sizes), 18)


if __name__ == "__main__":
    main()
