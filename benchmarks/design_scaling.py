"""Time ``vaultgram design`` end to end at about 10^4, 10^5 and 10^6 faces, per part of the pipeline.

Run: ``python benchmarks/design_scaling.py [--target-lengths 0.1,0.0316,0.01] [--plan PLAN]``. Each size
runs the command line (``vaultgram design PLAN --out DIR --target-length L``, every default else) in
a child process, smallest first, and reads the seconds of each stage from ``DIR/timings.json``. A row
gives the faces, the wall seconds of the command, its CPU seconds (less swayed than the wall by the
machine's other work, though not free of it), its peak resident memory, and the stages summed by
part of the paper: meshing (§3: discretise to untangle), form finding (§5: supports to vertical),
tessellation (§5: surface to metrics) and the outputs (write, and the figures: the hand-over of each
stage to the figure process and the wait for it), and ``other``, the wall time outside every stage
(start-up and imports, the process's exit). The load
average is printed first: the machine's other work slows everything. Floor (issue 18): 10^6 faces on
examples/quad_with_hole.json under 60 s and 8 GB.

The peak memory is the largest ``ru_maxrss`` of the children so far, which is the current child's
because the sizes grow.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
PLAN = REPO / "examples" / "quad_with_hole.json"
#: The stages of each part, as ``timings.json`` names them (vaultgram.pipeline).
PARTS = {
    "mesh": ("discretise", "triangulate", "skeleton", "rules", "groups", "weld", "smooth", "untangle", "orthogonalise"),
    "formfind": ("supports", "form", "relax", "force", "horizontal", "vertical"),
    "tessellate": ("surface", "refine", "keystones", "stagger", "sizes", "surface_smooth", "solids", "courses",
                   "metrics"),
    "outputs": ("write", "figures"),
}


def run_design(plan: Path, target_length: float) -> dict:
    """One ``vaultgram design`` in a child process: faces, wall seconds, CPU seconds (the child's and
    its figure process's, user and system), peak MB, stage seconds."""
    out = Path(tempfile.mkdtemp()) / "out"
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "vaultgram", "design", str(plan), "--out", str(out),
                           "--target-length", str(target_length)], capture_output=True, text=True)
    wall = time.perf_counter() - start
    if done.returncode != 0:
        raise SystemExit(f"design at --target-length {target_length} failed: {done.stderr.strip()[-300:]}")
    stages = json.loads((out / "timings.json").read_text())
    faces = len(json.loads((out / "mesh.json").read_text())["faces"])
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - used.ru_utime - used.ru_stime
    return {"faces": faces, "wall": wall, "cpu": cpu, "peak_mb": after.ru_maxrss / 1024, "stages": stages}


def parts(stages: dict) -> dict:
    """The stage seconds summed by part (:data:`PARTS`).

    >>> parts({"weld": 1.0, "smooth": 2.0, "form": 0.5, "write": 0.25})
    {'mesh': 3.0, 'formfind': 0.5, 'tessellate': 0.0, 'outputs': 0.25}
    """
    return {part: sum(stages.get(s, 0.0) for s in names) for part, names in PARTS.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--target-lengths", default="0.1,0.0316,0.01",
                        help="comma-separated --target-length values, growing in faces")
    parser.add_argument("--plan", type=Path, default=PLAN)
    parser.add_argument("--stages", action="store_true", help="also print every stage's seconds")
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}  plan {args.plan.name}")
    print(f"{'faces':>9} {'wall s':>8} {'cpu s':>8} {'peak MB':>8} " + " ".join(f"{p:>10}" for p in PARTS)
          + f" {'other':>10}")
    for length in (float(v) for v in args.target_lengths.split(",")):
        row = run_design(args.plan, length)
        # other: the wall time outside every stage (start-up and imports, the process's exit)
        other = row["wall"] - sum(row["stages"].values())
        cells = " ".join(f"{v:10.2f}" for v in [*parts(row["stages"]).values(), other])
        print(f"{row['faces']:9d} {row['wall']:8.1f} {row['cpu']:8.1f} {row['peak_mb']:8.0f} {cells}", flush=True)
        if args.stages:
            print("  " + ", ".join(f"{k} {v:.2f}" for k, v in sorted(row["stages"].items(), key=lambda kv: -kv[1])))


if __name__ == "__main__":
    main()
