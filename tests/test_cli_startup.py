"""The command line starts light (issue 18): importing it (what `vaultgram --help` does) loads none of
the heavy libraries; each command imports what it needs when it runs, and a warm ``rules check`` reads
its cached result."""

from __future__ import annotations

import os
import subprocess
import sys

from paths import REPO

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


def _rules_check(args, cache, cwd, loaded=("lark", "numpy", "vaultgram.engine.checker")):
    """``vaultgram rules check ARGS`` in a subprocess with this cache folder: its output and which of
    ``loaded`` it imported."""
    code = ("import sys; from vaultgram.cli import main; "
            f"sys.argv = ['vaultgram', 'rules', 'check', *{list(args)!r}]\n"
            "try:\n    main()\nexcept SystemExit:\n    pass\n"
            f"print('LOADED', *(m for m in {loaded!r} if m in sys.modules))")
    env = {**os.environ, "VAULTGRAM_CACHE_DIR": str(cache)}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env, cwd=cwd)
    text, _, modules = out.stdout.rpartition("LOADED")
    return text, modules.split(), out.stderr


def test_a_warm_rules_check_reads_the_cache_and_imports_nothing_heavy(tmp_path):
    files = [str(p) for p in sorted((REPO / "rules").glob("*.vgr"))]
    cold, cold_loaded, _ = _rules_check(files, tmp_path / "cache", REPO)
    warm, warm_loaded, _ = _rules_check(files, tmp_path / "cache", REPO)
    assert cold.startswith("ok: ") and cold_loaded == ["lark", "numpy", "vaultgram.engine.checker"]
    assert warm == cold and warm_loaded == []


def test_an_edited_include_is_checked_again(tmp_path):
    (tmp_path / "schema.vgr").write_text("schema s { node A { w: int = 0 } }\n")
    (tmp_path / "main.vgr").write_text('include "schema.vgr"\nrule bump { match { a: A } set a.w = a.w + 1 }\n')
    _rules_check(["main.vgr"], tmp_path / "cache", tmp_path)
    _, loaded, _ = _rules_check(["main.vgr"], tmp_path / "cache", tmp_path)
    assert loaded == []                                                   # warm
    (tmp_path / "schema.vgr").write_text("schema s { node A { v: int = 0 } }\n")   # w is gone
    out, loaded, err = _rules_check(["main.vgr"], tmp_path / "cache", tmp_path)
    assert "lark" in loaded and out == "" and "main.vgr:2" in err and "w" in err


def test_a_warm_parse_cache_loads_a_rulebook_without_lark(tmp_path):
    code = ("import sys; from vaultgram.engine.rulebook import load_rulebook; "
            f"book = load_rulebook([{str(REPO / 'rules' / 'schema.vgr')!r}]); "
            "print(len(book.schema.node_types), 'lark' in sys.modules)")
    env = {**os.environ, "VAULTGRAM_CACHE_DIR": str(tmp_path)}
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
            for _ in range(2)]
    (types, cold), (types_warm, warm) = (r.stdout.split() for r in runs)
    assert types == types_warm and int(types) > 5 and (cold, warm) == ("True", "False")


def test_the_mesh_command_imports_no_form_finding_tessellation_figures_or_scipy(tmp_path):
    """``vaultgram mesh`` imports what meshing needs: of form finding only the supports (mesh.json
    records them), no tessellation, no figures, none of the libraries only those use, and no scipy at
    all (its import took 0.2-0.3 s of the command's 0.6: the Delaunay triangles and neighbour queries
    are :mod:`vaultgram.geometry.spatial`'s, the smoothing's sparse product numpy's)."""
    code = ("import sys; from vaultgram.cli import main; "
            f"sys.argv = ['vaultgram', 'mesh', {str(REPO / 'examples' / 'quad_with_hole.json')!r}, "
            f"'--out', {str(tmp_path / 'out')!r}]\n"
            "try:\n    main()\nexcept SystemExit:\n    pass\n"
            "print('LOADED', *sorted(sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded = out.stdout.rpartition("LOADED")[2].split()
    assert (tmp_path / "out" / "mesh.json").is_file() and "vaultgram.meshpipeline" in loaded
    heavy = ("vaultgram.tessellation", "vaultgram.io.figures", "vaultgram.io.plots", "vaultgram.pipeline",
             "matplotlib", "cvxopt", "networkx", "scipy")
    unwanted = [m for m in loaded if m.startswith(heavy)
                or (m.startswith("vaultgram.formfinding.") and m != "vaultgram.formfinding.supports")]
    assert unwanted == []
