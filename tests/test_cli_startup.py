"""The command line starts light (issue 18): importing it (what `vaultgram --help` does) loads none of
the heavy libraries; each command imports what it needs when it runs."""

from __future__ import annotations

import subprocess
import sys

HEAVY = ("numpy", "scipy", "networkx", "shapely", "lark", "matplotlib")


def test_importing_the_cli_imports_nothing_heavy():
    code = ("import sys, vaultgram.cli; "
            f"print(' '.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_help_runs_without_them():
    code = ("import sys; from vaultgram.cli import main; "
            "sys.argv = ['vaultgram', '--help']\n"
            "try:\n    main()\nexcept SystemExit:\n    pass\n"
            f"print('LOADED', ' '.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "design" in out.stdout
    assert out.stdout.strip().endswith("LOADED")
