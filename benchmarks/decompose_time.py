"""Decomposition and meshing CPU per plan, with digests of what they make (issue 18: lean, fast runs;
issue 12's meshing-time floor).

Run: ``python benchmarks/decompose_time.py [--plans jagged,shared,examples] [--repeat R] [--json OUT]
[--compare OLD.json] [NAME ...]``. For each plan, :func:`vaultgram.pipeline.mesh_domain`'s work in its
two parts, each timed in process time (less noisy than wall-clock on a shared machine; note the load
beside the numbers): ``decompose`` (§3.1, §4: the rules' rewriting, whose rematching calls the rule
helpers) and the meshing of the decomposition (§3.2-§3.3), the best of ``R`` runs each; the faces of
the mesh, and SHA-256 digests of the decomposition's graph (``decomposition.json``'s content) and of
the mesh (vertices, faces, their patches). A cache of the rule helpers must leave both digests as they
were: ``--compare`` prints the CPU before and after per plan and whether the digests are the same.
``--check-chords`` compares every reflex corner's chord the rules ask for (kept while the patches it read
are untouched, :func:`vaultgram.topology.reflex._kept_chord`) with one worked out afresh, and prints how
many were asked, worked out and different (after a change of what ``choose_chord`` reads: its footprint
must name it; CPU times are then not comparable).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import sys
import time

import numpy as np
from benchpaths import ARCHITECTURE, EXAMPLES

from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.meshpipeline import check_feature_spacing, decompose, domain_frame, mesh_or_advise
from vaultgram.testing.jagged import jagged_plans


def plans(kinds: list[str]) -> dict:
    """The plans by name: ``jagged`` (:func:`vaultgram.testing.jagged.jagged_plans`), ``shared`` (the
    shared architecture data) and ``examples`` (the skeleton-only example aside)."""
    out = {}
    if "jagged" in kinds:
        out.update({name: domain_from_dict(data, name) for name, data in jagged_plans().items()})
    if "shared" in kinds and ARCHITECTURE.is_dir():
        out.update({p.stem: load_domain(p) for p in sorted(ARCHITECTURE.glob("*.json"))})
    if "examples" in kinds:
        out.update({p.stem: load_domain(p) for p in sorted(EXAMPLES.glob("*.json"))
                    if not p.stem.startswith("skeleton_")})
    return out


def digest(data) -> str:
    """A short SHA-256 digest of ``data``: JSON-like values (keys sorted) or numpy arrays."""
    h = hashlib.sha256()
    for item in data:
        if isinstance(item, np.ndarray):
            h.update(str(item.dtype).encode() + str(item.shape).encode() + np.ascontiguousarray(item).tobytes())
        else:
            h.update(json.dumps(item, sort_keys=True, default=str).encode())
    return h.hexdigest()[:16]


def check_chords() -> dict:
    """Make every kept chord be compared with a fresh one (``--check-chords``); the counts, updated as the
    rules ask (:func:`vaultgram.testing.chords.chord_checks`)."""
    from collections import Counter

    from vaultgram.testing.chords import chord_checks
    from vaultgram.topology import reflex

    counts = Counter({"asked": 0, "worked out": 0, "differ": 0})
    reflex.choose_chord, reflex._kept_chord = chord_checks(counts)
    return counts


def measure(domain, repeat: int) -> dict:
    """``mesh_domain(domain)``'s two parts, best CPU of ``repeat`` runs each, the first run's total (the
    rule helpers' caches by content are then empty, as in a fresh process: the CLI's case) and the
    digests."""
    runs = []
    for _ in range(repeat):
        start = time.process_time()
        with domain_frame(domain):
            check_feature_spacing(domain, 0.02)
        dec = decompose(domain)
        middle = time.process_time()
        mesh = mesh_or_advise(dec)
        end = time.process_time()
        runs.append((round(middle - start, 3), round(end - middle, 3)))
    faces = [list(map(int, f)) for f in mesh.faces]
    return {"decompose": min(d for d, _ in runs), "mesh": min(m for _, m in runs), "first": round(sum(runs[0]), 3),
            "runs": runs, "faces": len(faces),
            "decomposition": digest([dec.to_json()]),
            "mesh_digest": digest([np.asarray(mesh.vertices, dtype=float), faces,
                                   np.asarray(mesh.face_patch)])}


def compare(old: dict, new: dict) -> int:
    """Print the CPU before and after per plan and whether the digests match; the number of plans
    whose decomposition or mesh differs."""
    print(f"{'plan':28s} {'dec before':>10s} {'after':>7s} {'x':>5s} {'total before':>12s} {'after':>7s} "
          f"{'x':>5s}  same")
    changed = 0
    sums = [0.0, 0.0, 0.0, 0.0]
    for name in sorted(set(old) & set(new)):
        a, b = old[name], new[name]
        same = a["decomposition"] == b["decomposition"] and a["mesh_digest"] == b["mesh_digest"]
        changed += not same
        ta, tb = a["decompose"] + a["mesh"], b["decompose"] + b["mesh"]
        for k, v in enumerate((a["decompose"], b["decompose"], ta, tb)):
            sums[k] += v
        print(f"{name:28s} {a['decompose']:10.2f} {b['decompose']:7.2f} {b['decompose'] / a['decompose']:5.2f} "
              f"{ta:12.2f} {tb:7.2f} {tb / ta:5.2f}  {'yes' if same else 'NO'}")
    print(f"{'all':28s} {sums[0]:10.2f} {sums[1]:7.2f} {sums[1] / sums[0]:5.2f} {sums[2]:12.2f} {sums[3]:7.2f} "
          f"{sums[3] / sums[2]:5.2f}  {changed} changed")
    return changed


def _bad_arguments(args, found: dict) -> str | None:
    """What is wrong with the command line, in one line, or None: an unknown plan kind or name, or a
    ``--compare`` file that does not exist."""
    kinds = set(args.plans.split(",")) - {"jagged", "shared", "examples"}
    if kinds:
        return f"--plans: unknown kind(s) {', '.join(sorted(kinds))} (jagged, shared, examples)"
    names = set(args.names) - set(found)
    if names:
        return f"unknown plan(s) {', '.join(sorted(names))} in --plans {args.plans}"
    if args.compare and not os.path.isfile(args.compare):
        return f"--compare: no file {args.compare}"
    return None


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="only these plans")
    parser.add_argument("--plans", default="jagged,shared,examples")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--json", help="write the rows here")
    parser.add_argument("--compare", help="rows of an earlier run to compare with")
    parser.add_argument("--check-chords", action="store_true", help="compare each kept chord with a fresh one")
    args = parser.parse_args(argv)
    found = plans(args.plans.split(","))
    problem = _bad_arguments(args, found)
    if problem:
        print(f"decompose_time.py: {problem}", file=sys.stderr)
        return 2
    chords = check_chords() if args.check_chords else None
    rows = {}
    print(f"load average {os.getloadavg()[0]:.1f}", flush=True)
    for name, domain in found.items():
        if args.names and name not in args.names:
            continue
        rows[name] = measure(domain, args.repeat)
        r = rows[name]
        print(f"{name:28s} decompose {r['decompose']:6.2f} s  mesh {r['mesh']:6.2f} s  faces {r['faces']:6d}  "
              f"first {r['first']:6.2f} s  {r['decomposition']} {r['mesh_digest']}", flush=True)
    print(f"load average {os.getloadavg()[0]:.1f}")
    if chords is not None:
        print(f"chords: {dict(chords)}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    if args.compare:
        with open(args.compare) as f:
            return 1 if compare(json.load(f), rows) else 0
    return 1 if chords is not None and chords["differ"] else 0


if __name__ == "__main__":
    sys.exit(main())
