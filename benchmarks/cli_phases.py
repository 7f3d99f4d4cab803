"""Where ``vaultgram mesh examples/quad_with_hole.json`` spends its CPU time, phase by phase, in fresh
processes (issue 18's fast command line).

Run: ``python benchmarks/cli_phases.py [--runs 5] [--python PATH]``. Each run is a new interpreter
(``--python``: another installation's, e.g. a base checkout's venv) that does what the command does,
timing each phase with ``time.process_time``: importing click and the command line, numpy, shapely and
orjson, vaultgram's modules, loading the vault rulebook, reading the domain, decomposing (discretise,
triangulate, skeleton, rules), meshing, and supports, files and statistics. Where the command line has
``long_lived`` (session 17), the imports and the rulebook run inside it as the program's own would. A row
gives the minimum and maximum milliseconds over the runs; the load average is printed first. Bytecode:
run once with ``env -u PYTHONDONTWRITEBYTECODE`` first, or every run compiles vaultgram's modules.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile

from benchpaths import EXAMPLES, REPO

#: The phases, timed in one process; prints ``name=ms`` words.
PHASES = """
import contextlib, time
T = time.process_time
marks, last = {}, [T()]
def mark(name):
    now = T(); marks[name] = (now - last[0]) * 1000; last[0] = now
import click, vaultgram.cli as cli; mark("cli")
start = contextlib.nullcontext()
if hasattr(cli, "long_lived"):
    cli._PROCESS["program"] = True
    start = cli.long_lived()
with start:
    import numpy; mark("numpy")
    import shapely, orjson; mark("shapely")
    from vaultgram.domain import load_domain
    from vaultgram.formfinding.supports import support_vertices
    from vaultgram.io.files import output_folder
    from vaultgram.io.outputs import parse_formats, write_drawings, write_mesh_files
    from vaultgram.meshing.quality import mesh_stats
    from vaultgram.meshing.smoothing import DEFAULT_ITERATIONS
    from vaultgram.meshpipeline import decompose, mesh_decomposition
    from vaultgram.topology.rulebook import load_vault_rulebook
    mark("modules")
    load_vault_rulebook(); mark("rulebook")
domain = load_domain(DOMAIN); mark("domain")
dec = decompose(domain, 0.02); mark("decompose")
mesh = mesh_decomposition(dec, None, DEFAULT_ITERATIONS); mark("meshing")
anchors = support_vertices(mesh.vertices, mesh.faces, domain.supports, domain, mesh.origin)
formats = parse_formats(None)
with output_folder(OUT) as stage:
    write_mesh_files(mesh, stage, anchors, plot=False, formats=formats)
    write_drawings(stage, formats, domain.units, mesh=mesh)
mesh_stats(mesh, domain); mark("files")
print(" ".join(f"{k}={v:.1f}" for k, v in marks.items()), f"total={sum(marks.values()):.1f}")
"""
NAMES = {"cli": "click and vaultgram.cli", "numpy": "numpy", "shapely": "shapely and orjson",
         "modules": "vaultgram's modules", "rulebook": "the vault rulebook", "domain": "reading the domain",
         "decompose": "decompose", "meshing": "meshing", "files": "supports, files, stats", "total": "total"}


def one_run(python: str, out: str) -> dict[str, float]:
    """The milliseconds of each phase in one fresh process."""
    code = f"DOMAIN = {str(EXAMPLES / 'quad_with_hole.json')!r}; OUT = {out!r}\n{PHASES}"
    proc = subprocess.run([python, "-c", code], capture_output=True, text=True, cwd=REPO)
    if proc.returncode != 0:
        raise SystemExit(f"{python}: the phases failed: {proc.stderr.strip()}")
    words = proc.stdout.split()[-len(NAMES):]
    return {k: float(v) for k, v in (w.split("=") for w in words)}


def main() -> None:
    """Run the phases ``--runs`` times and print each one's range."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--python", default=sys.executable)
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}; {args.python}")
    with tempfile.TemporaryDirectory() as tmp:
        runs = [one_run(args.python, os.path.join(tmp, f"out{i}")) for i in range(args.runs)]
    for key, name in NAMES.items():
        values = [r[key] for r in runs]
        print(f"{name:24s} {min(values):6.1f} - {max(values):6.1f} ms")


if __name__ == "__main__":
    main()
