"""Reliability measurements of issue 17 (results in benchmarks/README.md, with the machine load).

* ``python benchmarks/reliability.py plans [--count 200] [--plans-file F]`` -- ``mesh`` on a fixed list of
  random valid plans (``vaultgram.testing.domains.vault_domains``: star-shaped non-convex outlines, 0-3
  holes, 0-3 inner and boundary points, 0-2 curves; drawn with a fixed seed): how many give a valid
  mesh (no inverted face), and the refusals grouped by their message. The draws are the same every
  run of the same code, but hypothesis mixes the constants of the loaded local modules into its
  draws, so another version of vaultgram draws other plans: to compare two versions on the same
  plans, the first run saves them to ``--plans-file`` and the second reads them from it. The 700 draws of
  session 32 (main 0a355bf) are kept in the repository: ``--count 700 --plans-file
  benchmarks/data/random_plans_700.json.gz`` (a ``.gz`` file is read and written gzipped).
  With ``--per-plan F`` it also writes one row per plan to F (JSON: index, shortest edge over median
  edge, min scaled Jacobian, boundary singular vertices, inverted faces; ``null`` for a refused plan), to
  see which plans a change moves.
* ``python benchmarks/reliability.py ngon N`` -- seconds to mesh a regular N-gon, per stage.
* ``python benchmarks/reliability.py guard`` -- seconds to refuse ``--target-length 1e-3`` on
  examples/quad_with_hole.json (in-process, after imports, and the whole command).
* ``python benchmarks/reliability.py peak [--target-length L]`` -- peak resident memory of ``vaultgram
  design`` on examples/quad_with_hole.json at about 10^5 faces (a child process, its ru_maxrss).
"""

from __future__ import annotations

import argparse
import collections
import gzip
import json
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
QWH = REPO / "examples" / "quad_with_hole.json"


def random_plans(count: int, seed: int = 17) -> list:
    """``count`` (domain dict, spacing) draws of ``vault_domains``, the same for the same seed."""
    from hypothesis import HealthCheck, given, settings
    from hypothesis import seed as hseed

    from vaultgram.testing.domains import vault_domains

    plans: list = []

    @hseed(seed)
    @settings(max_examples=count, database=None, deadline=None, derandomize=False,
              suppress_health_check=list(HealthCheck))
    @given(vault_domains())
    def draw(plan):
        if len(plans) < count:
            plans.append(plan)

    draw()
    return plans


def saved_plans(count: int, path: Path | None) -> list:
    """The plans in ``path`` (a JSON list of [domain dict, spacing]) if it exists, else ``count`` new
    draws of :func:`random_plans`, saved there when a path is given."""
    if path is not None and path.is_file():
        text = gzip.decompress(path.read_bytes()).decode() if path.suffix == ".gz" else path.read_text()
        return [tuple(plan) for plan in json.loads(text)]
    plans = random_plans(count)
    if path is not None:
        text = json.dumps(plans)
        if path.suffix == ".gz":
            path.write_bytes(gzip.compress(text.encode(), mtime=0))
        else:
            path.write_text(text)
    return plans


#: Shortest edge over median edge: a mesh under one of these has a quad collapsed towards a triangle
#: (the scaled Jacobian does not see it; issue 12, session 26).
SHORT_EDGES = (0.001, 0.01, 0.05)


def mesh_rate(count: int, path: Path | None = None, per_plan: Path | None = None) -> dict:
    """Mesh every plan; count the valid meshes and group the refusals by their message's kind. Of the
    valid meshes: their boundary singularities (by the domain's corners, :func:`mesh_stats`), the plans
    with any, the plans whose worst scaled Jacobian is under 0.1 and under 0.3, and its mean, and the
    plans whose shortest edge is under each of :data:`SHORT_EDGES` of their median edge. With
    ``per_plan``, the row of each plan written there (:func:`_plan_row`)."""
    from vaultgram.domain import domain_from_dict
    from vaultgram.errors import VaultgramError
    from vaultgram.meshing.quality import mesh_stats
    from vaultgram.pipeline import mesh_domain

    stats, rows, refusals = [], [], collections.Counter()
    plans = saved_plans(count, path)
    for index, (data, spacing) in enumerate(plans):
        try:
            domain = domain_from_dict(data)
            stats.append(mesh_stats(mesh_domain(domain, spacing), domain))
            rows.append(_plan_row(index, stats[-1]))
        except VaultgramError as exc:
            refusals[re.sub(r"-?\d[\d.e+-]*", "N", str(exc).split(": ")[-1])[:90]] += 1
            rows.append(None)
    if per_plan is not None:
        per_plan.write_text(json.dumps(rows))
    valid = [s for s in stats if s["inverted_faces"] == 0]
    worst = np.array([s["min_scaled_jacobian"] for s in valid])
    short = np.array([s["shortest_over_median_edge"] for s in valid])
    bnd = [s["boundary_singular"] for s in valid]
    return {"plans": len(plans), "valid": len(valid), "rate": len(valid) / max(len(plans), 1),
            "boundary_singular": sum(bnd), "plans_boundary_singular": sum(b > 0 for b in bnd),
            "min_sj_under_0.1": int((worst < 0.1).sum()), "min_sj_under_0.3": int((worst < 0.3).sum()),
            "mean_min_sj": round(float(worst.mean()), 4) if len(worst) else None,
            "shortest_edge_under": {str(r): int((short < r).sum()) for r in SHORT_EDGES},
            "refusals": refusals.most_common()}


def _plan_row(index: int, stats: dict) -> list:
    """A plan's row of ``--per-plan``: index, shortest edge over median edge, min scaled Jacobian,
    boundary singular vertices, inverted faces."""
    return [index, stats["shortest_over_median_edge"], stats["min_scaled_jacobian"], stats["boundary_singular"],
            stats["inverted_faces"]]


def ngon(n: int) -> dict:
    """Seconds per stage to mesh a regular n-gon of radius 10."""
    from vaultgram.domain import domain_from_dict
    from vaultgram.pipeline import mesh_domain
    from vaultgram.topology.rulebook import load_vault_rulebook

    load_vault_rulebook(None)
    t = 2 * np.pi * np.arange(n) / n
    domain = domain_from_dict({"outer": np.column_stack([10 * np.cos(t), 10 * np.sin(t)]).tolist()})
    timings: dict = {}
    start = time.perf_counter()
    mesh = mesh_domain(domain, timings=timings)
    return {"n": n, "seconds": time.perf_counter() - start, "faces": len(mesh.faces),
            "stages": {k: round(v, 2) for k, v in timings.items()}}


def guard() -> dict:
    """Seconds to refuse --target-length 1e-3 on the quad with a hole: the command in-process after
    its imports (a first call loads the rulebook), and the whole command as a process."""
    from click.testing import CliRunner

    from vaultgram.cli import main

    args = ["mesh", str(QWH), "--target-length", "1e-3", "--out", str(Path(tempfile.mkdtemp()) / "o")]
    CliRunner().invoke(main, args)
    start = time.perf_counter()
    result = CliRunner().invoke(main, args)
    inprocess = time.perf_counter() - start
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "vaultgram", *args], capture_output=True)
    return {"in_process": inprocess, "process": time.perf_counter() - start, "message": result.stderr.strip()}


def peak(target_length: float) -> dict:
    """Peak resident memory (MB) and faces of ``vaultgram design`` on the quad with a hole."""
    out = Path(tempfile.mkdtemp()) / "o"
    start = time.perf_counter()
    run = subprocess.run([sys.executable, "-m", "vaultgram", "design", str(QWH), "--out", str(out), "--zmax", "3",
                          "--target-length", str(target_length), "--format", "json"], capture_output=True, text=True)
    seconds = time.perf_counter() - start
    rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    faces = len(json.loads((out / "mesh.json").read_text())["faces"]) if run.returncode == 0 else None
    return {"faces": faces, "peak_mb": round(rss), "seconds": round(seconds, 1), "error": run.stderr[-300:]}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="what", required=True)
    plans = sub.add_parser("plans")
    plans.add_argument("--count", type=int, default=200)
    plans.add_argument("--plans-file", type=Path, default=None,
                       help="JSON of the plans: read if it exists, else the new draws are saved there")
    plans.add_argument("--per-plan", type=Path, default=None,
                       help="also write each plan's row here (JSON: index, shortest edge / median edge, min SJ, "
                            "boundary singular, inverted faces)")
    sub.add_parser("ngon").add_argument("n", type=int)
    sub.add_parser("guard")
    sub.add_parser("peak").add_argument("--target-length", type=float, default=0.0316)
    args = parser.parse_args()
    result = {"plans": lambda: mesh_rate(args.count, args.plans_file, args.per_plan), "ngon": lambda: ngon(args.n),
              "guard": guard, "peak": lambda: peak(args.target_length)}[args.what]()
    print(json.dumps(result, indent=1, default=str))


if __name__ == "__main__":
    main()
