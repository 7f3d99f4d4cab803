"""The command line starts light (issue 18): importing it (what `vaultgram --help` does) loads none of
the heavy libraries; each command imports what it needs when it runs, and a warm ``rules check`` reads
its cached result."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

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


def test_the_mesh_command_imports_neither_numpy_ma_nor_importlib_resources(tmp_path):
    """Two imports of some 10 and 4 ms that nothing on the mesh path needs (issue 18): ``numpy.ma``,
    which numpy 2.4's ``np.unique`` without ``return_*`` imports to ask whether its input is masked
    (the path takes :func:`vaultgram.geometry.arrays.distinct`), and ``importlib.resources`` with
    its readers (the shipped rulebook's folder is its package's)."""
    loaded = _mesh_modules(tmp_path, "import sys")
    assert "vaultgram.meshpipeline" in loaded
    assert [m for m in loaded if m == "numpy.ma" or m.startswith("importlib.resources")] == []


def _mesh_modules(tmp_path, setup: str, after: str = "' '.join(sorted(sys.modules))") -> list[str]:
    """``vaultgram mesh`` of quad_with_hole run as the program (its arguments in ``sys.argv``) in a
    subprocess after ``setup``: the words of ``after`` evaluated once it exits."""
    code = (f"{setup}; import sys; from vaultgram.cli import main; "
            f"sys.argv = ['vaultgram', 'mesh', {str(REPO / 'examples' / 'quad_with_hole.json')!r}, "
            f"'--out', {str(tmp_path / 'out')!r}]\n"
            "try:\n    main()\nexcept SystemExit:\n    pass\n"
            f"print('AFTER', {after})")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert (tmp_path / "out" / "mesh.json").is_file()
    return out.stdout.rpartition("AFTER")[2].split()


def test_the_program_freezes_its_start_up_out_of_the_garbage_collector(tmp_path):
    """Run as the program, ``vaultgram mesh`` imports and loads its rulebook with the collector
    paused, then freezes what exists (``gc.freeze``: the modules, classes and the rulebook are not
    walked again by any collection, nor at exit) and collects again."""
    enabled, frozen = _mesh_modules(tmp_path, "import gc", "gc.isenabled(), gc.get_freeze_count() > 10000")
    assert (enabled, frozen) == ("True", "True")


def test_a_caller_of_the_command_line_keeps_its_objects_collectable(tmp_path):
    """Called by other code (click's test runner here, an application), the command line pauses the
    collector during a command's start-up but freezes nothing: the caller's objects stay collectable."""
    import gc

    from click.testing import CliRunner

    from vaultgram.cli import main

    before = gc.get_freeze_count()
    result = CliRunner().invoke(main, ["mesh", str(REPO / "examples" / "quad_with_hole.json"),
                                       "--out", str(tmp_path / "out")])
    assert result.exit_code == 0 and (tmp_path / "out" / "mesh.json").is_file()
    assert gc.isenabled() and gc.get_freeze_count() == before


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="threads counted in /proc (Linux)")
def test_the_program_loads_numpy_with_one_blas_thread(tmp_path, monkeypatch):
    """Run as the program, ``vaultgram mesh`` sets one OpenBLAS thread before numpy loads (its threads
    spin at start-up and the mesh path multiplies no large matrices): the process has no other thread."""
    for name in ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS"):
        monkeypatch.delenv(name, raising=False)
    env, threads = _mesh_modules(tmp_path, "import os",
                                 "os.environ.get('OPENBLAS_NUM_THREADS'), len(os.listdir('/proc/self/task'))")
    assert (env, threads) == ("1", "1")


def test_a_blas_thread_count_the_user_chose_is_kept(tmp_path, monkeypatch):
    """``OPENBLAS_NUM_THREADS`` or ``OMP_NUM_THREADS`` set by the user stays as given."""
    monkeypatch.setenv("OMP_NUM_THREADS", "2")
    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    env, omp = _mesh_modules(tmp_path, "import os",
                             "os.environ.get('OPENBLAS_NUM_THREADS'), os.environ.get('OMP_NUM_THREADS')")
    assert (env, omp) == ("None", "2")


def test_a_caller_of_the_command_line_keeps_its_environment(tmp_path, monkeypatch):
    """Called by other code, the command line leaves the caller's environment as it was."""
    import os

    from click.testing import CliRunner

    from vaultgram.cli import main

    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    result = CliRunner().invoke(main, ["mesh", str(REPO / "examples" / "quad_with_hole.json"),
                                       "--out", str(tmp_path / "out")])
    assert result.exit_code == 0 and "OPENBLAS_NUM_THREADS" not in os.environ
