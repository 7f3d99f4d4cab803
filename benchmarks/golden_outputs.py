"""Record, or compare against a record, what ``vaultgram design`` writes on every example and plan.

Run: ``python benchmarks/golden_outputs.py record DIR`` before a refactor, then
``python benchmarks/golden_outputs.py compare DIR`` after it: every JSON and OBJ file and the printed
summary must be byte-identical (timings, timings.json and the temporary folder aside; PNG files are left out:
matplotlib embeds its version). Plans where the default fails are run again with
``--relax-mode all``; a plan that fails both ways records its error line, which must not change
either. Extra ``vaultgram design`` options may follow DIR.

Inputs: ``examples/*.json`` (except the graph ``skeleton_*``) and ``../shared/data/architecture``.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from benchpaths import ARCHITECTURE, REPO

KEPT = (".json", ".obj")
TIMED = {"timings.json"}  # the seconds of every stage: differ on every run


def inputs() -> list[Path]:
    """Every bundled example domain and every shared plan, in a fixed order."""
    examples = [p for p in sorted((REPO / "examples").glob("*.json")) if not p.name.startswith("skeleton_")]
    plans = sorted(ARCHITECTURE.glob("*.json")) if ARCHITECTURE.is_dir() else []
    return examples + plans


def run_design(domain: Path, options: list[str]) -> dict:
    """One design run (default relaxation, then ``--relax-mode all``): its exit code, output and files."""
    for extra in ([], ["--relax-mode", "all"]):
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "out"
            # Run beside the input and name it alone: summary.json records the path as given, so a
            # checkout elsewhere (a worktree, a clean clone) records the same bytes.
            cmd = [sys.executable, "-m", "vaultgram", "design", domain.name, "--out", str(out), *options, *extra]
            proc = subprocess.run(cmd, capture_output=True, text=True, cwd=domain.parent)
            files = {p.name: hashlib.sha256(p.read_bytes()).hexdigest()
                     for p in sorted(out.glob("*")) if p.suffix in KEPT and p.name not in TIMED} if out.is_dir() else {}
            if proc.returncode == 0:
                break
    return {"options": extra, "code": proc.returncode, "stdout": proc.stdout, "stderr": proc.stderr.strip(),
            "files": files}


def record(options: list[str]) -> dict:
    """The outcome of every input, keyed by file name."""
    result = {}
    for domain in inputs():
        result[domain.name] = run_design(domain, options)
        print(f"{domain.name}: exit {result[domain.name]['code']}, {len(result[domain.name]['files'])} files",
              flush=True)
    return result


def normalised(stdout: str) -> str:
    """The printed summary or error without what varies from run to run: timings and the output folder."""
    lines = [line for line in stdout.splitlines() if not line.startswith(("time:", "timings:"))]
    return "\n".join(re.sub(r"/\S*/out\b", "OUT", line) for line in lines)


def differences(before: dict, after: dict) -> list[str]:
    """One line per input whose outcome changed, naming what changed (timings and paths aside)."""
    lines = []
    for name in sorted(set(before) | set(after)):
        a, b = before.get(name), after.get(name)
        if a is None or b is None:
            lines.append(f"{name}: only {'after' if a is None else 'before'}")
            continue
        changed = [key for key in ("options", "code") if a[key] != b[key]]
        changed += [key for key in ("stdout", "stderr") if normalised(a[key]) != normalised(b[key])]
        changed += [f"file {f}" for f in sorted(set(a["files"]) | set(b["files"]))
                    if a["files"].get(f) != b["files"].get(f)]
        if changed:
            lines.append(f"{name}: " + ", ".join(changed))
    return lines


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", choices=["record", "compare"])
    parser.add_argument("dir", type=Path)
    args, options = parser.parse_known_args()
    now = record(options)
    if args.mode == "record":
        args.dir.mkdir(parents=True, exist_ok=True)
        (args.dir / "golden.json").write_text(json.dumps(now, indent=1, sort_keys=True))
        return 0
    lines = differences(json.loads((args.dir / "golden.json").read_text()), now)
    print("\n".join(lines) if lines else f"identical: {len(now)} inputs")
    return 1 if lines else 0


if __name__ == "__main__":
    sys.exit(main())
