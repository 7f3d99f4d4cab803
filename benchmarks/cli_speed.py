"""Wall time of three short commands (issue 18's fast command line): ``vaultgram --help``, a warm
``vaultgram rules check rules/*.vgr`` and ``vaultgram mesh examples/quad_with_hole.json --out DIR``.

Run: ``python benchmarks/cli_speed.py [--runs 5] [--vaultgram PATH]``. Each command runs once to warm
the caches (the parse and rulebook caches of :mod:`vaultgram.grammar.cache`, the OS's file cache),
then ``--runs`` times under ``/usr/bin/time -f "%e %U %S"``; a row gives the best and the median wall
seconds, the floor, and the median CPU seconds (user + system: what the load changes less).
``--vaultgram`` times another installation's script (a base checkout's). The load average is printed
first: the machine's other work slows everything. Floors: ``--help`` 0.15 s, ``rules check`` 0.25 s,
``mesh`` 0.35 s.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from benchpaths import EXAMPLES, REPO

FLOORS = {"help": 0.15, "rules check": 0.25, "mesh": 0.35}


def commands(out: Path) -> dict[str, list[str]]:
    """The timed command lines (without the script), by name."""
    rules = [str(p) for p in sorted((REPO / "rules").glob("*.vgr"))]
    return {"help": ["--help"], "rules check": ["rules", "check", *rules],
            "mesh": ["mesh", str(EXAMPLES / "quad_with_hole.json"), "--out", str(out)]}


def timed(script: str, args: list[str]) -> tuple[float, float]:
    """The wall and CPU (user + system) seconds of one run, as ``/usr/bin/time`` reports them on its
    last stderr line."""
    proc = subprocess.run(["/usr/bin/time", "-f", "%e %U %S", script, *args], capture_output=True, text=True,
                          cwd=REPO)
    if proc.returncode != 0:
        raise SystemExit(f"{script} {' '.join(args)} failed: {proc.stderr.strip()}")
    wall, user, system = map(float, proc.stderr.strip().splitlines()[-1].split())
    return wall, user + system


def main() -> None:
    """Time each command and print best, median, floor and CPU."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--vaultgram", default=str(Path(sys.executable).with_name("vaultgram")))
    args = parser.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f}; {args.vaultgram}")
    with tempfile.TemporaryDirectory() as tmp:
        for name, argv in commands(Path(tmp) / "out").items():
            timed(args.vaultgram, argv)
            runs = [timed(args.vaultgram, argv) for _ in range(args.runs)]
            walls = [w for w, _ in runs]
            print(f"{name:12s} best {min(walls):.2f} s, median {statistics.median(walls):.2f} s "
                  f"(floor {FLOORS[name]:.2f} s), CPU {statistics.median(c for _, c in runs):.2f} s: "
                  f"{' '.join(f'{w:.2f}' for w in walls)}")


if __name__ == "__main__":
    main()
