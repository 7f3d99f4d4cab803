"""The report's acceptance: ``vaultgram design`` on every example and on the shared Armadillo plan,
then each ``report.html`` opened in headless Chromium (tests/browser.py): every section there, every
figure there as PNG and as inline SVG, the screenshot not blank.

Run: ``python benchmarks/report_acceptance.py [OUT]`` (default a temporary folder). One row per plan:
its faces, the seconds of the design and of its figures, the report's size, and ``ok`` or what is
missing. Plans where the default fails are run again with ``--relax-mode all`` (as golden_outputs.py).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

from benchpaths import ARCHITECTURE, REPO

sys.path.insert(0, str(REPO / "tests"))

from browser import render  # noqa: E402

from vaultgram.io.figures import CATALOGUE  # noqa: E402
from vaultgram.io.report import SECTIONS  # noqa: E402

ARMADILLO = ARCHITECTURE / "armadillo_vault.json"


def plans() -> list[Path]:
    """Every bundled example domain (not the graph skeleton_*) and the Armadillo plan."""
    found = sorted(p for p in (REPO / "examples").glob("*.json") if not p.name.startswith("skeleton_"))
    return found + ([ARMADILLO] if ARMADILLO.is_file() else [])


def check(out: Path) -> list[str]:
    """What the report of ``out`` lacks (empty: nothing)."""
    shown = render(out / "report.html", height=1600)
    missing = [f"section {s}" for s in SECTIONS if f'id="{s}"' not in shown.dom]
    missing += [f"figure {s.name}" for s in CATALOGUE
                if f'id="figure-{s.name}"' not in shown.dom or not (out / "figures" / f"{s.name}.png").is_file()]
    return missing + (["blank screenshot"] if shown.is_blank() else [])


def main() -> None:
    root = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp())
    print(f"{'plan':<24} {'faces':>7} {'design s':>9} {'figures s':>9} {'report MB':>9}  result")
    for plan in plans():
        out = root / plan.stem
        for extra in ([], ["--relax-mode", "all"]):
            proc = subprocess.run([sys.executable, "-m", "vaultgram", "design", str(plan), "--out", str(out), *extra],
                                  capture_output=True, text=True)
            if proc.returncode == 0:
                break
        if proc.returncode != 0:
            print(f"{plan.stem:<24} {'':>7} {'':>9} {'':>9} {'':>9}  design failed: {proc.stderr.strip()[-120:]}")
            continue
        timings = json.loads((out / "timings.json").read_text())
        faces = json.loads((out / "summary.json").read_text())["mesh_quality"]["faces"]
        missing = check(out)
        design = sum(v for k, v in timings.items() if k not in ("write", "figures"))
        print(f"{plan.stem:<24} {faces:>7} {design:>9.2f} {timings.get('figures', 0):>9.2f} "
              f"{(out / 'report.html').stat().st_size / 1e6:>9.2f}  {'ok' if not missing else ', '.join(missing)}",
              flush=True)


if __name__ == "__main__":
    main()
