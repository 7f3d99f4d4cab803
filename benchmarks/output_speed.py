"""Time what ``vaultgram design`` spends after the design is computed: writing its data files, its
figures and its report, at about 10^3, 10^4 and 10^5 faces.

Run: ``python benchmarks/output_speed.py [--sizes 1e3,1e4,1e5] [--files-only] [--in-process]``. The
plan is examples/quad_with_hole.json meshed at the target length ``sqrt(area / faces)``; the whole
pipeline runs once per size (:func:`vaultgram.pipeline.design`) with the figures drawn in the
background as ``vaultgram design`` draws them (:class:`vaultgram.io.figures.worker.FigureWorker`;
``--in-process`` draws them after the design instead), then :func:`vaultgram.io.outputs.write_design`
writes into a fresh folder. Each row gives the faces, the seconds of the design, of the data files
(``write``: JSON, OBJ, summary; from 20 000 faces the background process writes the mesh's and the
thrust network's during the design, :data:`vaultgram.io.figures.worker.BACKGROUND_FACES`), of the
figures on the critical path (the wait for the background process, or the drawing), the background
process's CPU seconds, the report, all the outputs together (``outputs``: the run's seconds after the
design, and ``out cpu`` this process's CPU seconds of them, which the load changes less), the
figures' share of the whole run, and whether a second write (no figures, every file in this process)
gave byte-identical data files. The load average is printed first: the machine's other
work slows everything. Floors: 10^5 faces write their outputs in under 2 s; figures under 10% of the
run.
"""

from __future__ import annotations

import argparse
import math
import os
import tempfile
import time
from pathlib import Path

from vaultgram.domain import load_domain
from vaultgram.io.figures.worker import FigureWorker
from vaultgram.io.outputs import DEFAULT_FORMATS, write_design
from vaultgram.pipeline import design

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "quad_with_hole.json"
VARYING = {"timings.json", "report.html"}  # the files that hold the timings


def folder_bytes(folder: Path) -> dict:
    """Every file of ``folder`` but the timed ones, by relative path."""
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name not in VARYING}


def measure(faces_wanted: int, plots: bool, background: bool) -> str:
    """One row: the design and its outputs at about ``faces_wanted`` faces."""
    domain = load_domain(EXAMPLE)
    with tempfile.TemporaryDirectory() as tmp:
        a, b = Path(tmp) / "a", Path(tmp) / "b"
        a.mkdir()
        b.mkdir()
        with FigureWorker(a, DEFAULT_FORMATS) as worker:
            start = time.perf_counter()
            result = design(domain, target_length=math.sqrt(domain.area / faces_wanted), zmax=3.0,
                            on_stage=worker if plots and background else None)
            seconds = time.perf_counter() - start
            start, cpu = time.perf_counter(), time.process_time()
            timings = write_design(result, a, plots=plots, report=plots, figures=worker if background else None)
            outputs, cpu = time.perf_counter() - start, time.process_time() - cpu
        write_design(result, b, plots=False, report=False)
        same = all(folder_bytes(a).get(k) == v for k, v in folder_bytes(b).items())
    figures, report = timings.get("figures", 0.0), outputs - timings["write"] - timings.get("figures", 0.0)
    share = figures / (seconds + outputs)
    return (f"{len(result.mesh.faces):>8} {seconds:>8.2f} {timings['write']:>8.2f} {figures:>8.2f} "
            f"{worker.seconds:>8.2f} {report:>8.2f} {outputs:>8.2f} {cpu:>8.2f} {share:>7.1%} "
            f"{'yes' if same else 'NO':>10}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="1e3,1e4,1e5")
    ap.add_argument("--files-only", action="store_true", help="Write the data files only (no figures, no report).")
    ap.add_argument("--in-process", action="store_true", help="Draw the figures after the design, in this process.")
    args = ap.parse_args()
    print(f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    head = (f"{'faces':>8} {'design':>8} {'write':>8} {'figures':>8} {'fig cpu':>8} {'report':>8} {'outputs':>8} "
            f"{'out cpu':>8} {'fig %':>7} {'identical':>10}")
    print(head)
    print("-" * len(head))
    for size in (int(float(s)) for s in args.sizes.split(",")):
        print(measure(size, not args.files_only, not args.in_process), flush=True)
    print(f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
