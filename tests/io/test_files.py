"""Output folders: complete or untouched, whatever goes wrong (a folder in the way, no permission,
--out below a file, SIGINT or SIGTERM at any moment of a run), and one line with exit code 2."""

from __future__ import annotations

import os
import random
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.cli import main
from vaultgram.errors import VaultgramError
from vaultgram.io import files
from vaultgram.io.files import freed_memory_kept, output_folder, write_text

from paths import EXAMPLES

DOMAIN = EXAMPLES / "quad_with_hole.json"


def _mesh(out):
    return CliRunner().invoke(main, ["mesh", str(DOMAIN), "--out", str(out), "--target-length", "2"])


def _one_error_line(result, *words):
    lines = result.stderr.strip().splitlines() if hasattr(result, "stderr") else result.output.strip().splitlines()
    assert result.exit_code == 2 and len(lines) == 1 and lines[0].startswith("error:"), result.output
    assert all(w in lines[0] for w in words), lines[0]


def _listing(folder):
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*"))


def test_out_below_a_file_is_one_line(tmp_path):
    (tmp_path / "plan").write_text("not a folder")
    result = _mesh(tmp_path / "plan" / "out")
    _one_error_line(result, "below a file", "plan")
    assert _listing(tmp_path) == ["plan"]


def test_a_folder_where_a_file_goes_leaves_out_untouched(tmp_path):
    (tmp_path / "out" / "mesh.json").mkdir(parents=True)
    (tmp_path / "out" / "mesh.obj").write_text("older")
    result = _mesh(tmp_path / "out")
    _one_error_line(result, "mesh.json", "folder is in the way")
    assert _listing(tmp_path) == ["out", "out/mesh.json", "out/mesh.obj"]
    assert (tmp_path / "out" / "mesh.obj").read_text() == "older"


def test_no_permission_is_one_line_naming_the_file(tmp_path, monkeypatch):
    """(As root the permission bits do not stop a write: the refusal is simulated where it happens.)"""
    def refused(src, dst):
        raise PermissionError(13, "Permission denied", str(dst))

    monkeypatch.setattr(files.os, "replace", refused)
    result = _mesh(tmp_path / "out")
    _one_error_line(result, "Permission denied", "mesh")
    assert "out" not in os.listdir(tmp_path) or not os.listdir(tmp_path / "out")
    assert not [p for p in os.listdir(tmp_path) if p.startswith(".")]


def test_an_unwritable_parent_is_one_line(tmp_path, monkeypatch):
    def refused(*args, **kwargs):
        raise PermissionError(13, "Permission denied", str(tmp_path))

    monkeypatch.setattr(files.tempfile, "mkdtemp", refused)
    with pytest.raises(VaultgramError, match="Permission denied"):
        with output_folder(tmp_path / "out"):
            pass


def test_a_staged_folder_replaces_a_folder_of_its_name(tmp_path):
    (tmp_path / "out" / "figures").mkdir(parents=True)
    (tmp_path / "out" / "figures" / "old.png").write_text("old")
    with output_folder(tmp_path / "out") as stage:
        write_text(stage / "figures" / "new.png", "new")
    assert _listing(tmp_path) == ["out", "out/figures", "out/figures/new.png"]


_DESIGN = ["design", str(DOMAIN), "--zmax", "3", "--target-length", "1.5", "--no-plots", "--no-report"]
#: What a rerun writes differently: the times of its stages.
_TIMED = {"timings.json"}


def _contents(folder) -> dict:
    """Every file below ``folder`` (by relative path) and its bytes, the timings left out."""
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name not in _TIMED}


#: ``python -m vaultgram``, once the interpreter has started: a signal sent before then is Python's to
#: report (with a traceback), not the program's.
_STARTED = "import runpy, sys; print(flush=True); runpy.run_module('vaultgram', run_name='__main__', alter_sys=True)"


def _design(out):
    """A ``design`` run in a process of its own, returned once the interpreter has started."""
    proc = subprocess.Popen([sys.executable, "-c", _STARTED, *_DESIGN, "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    proc.stdout.readline()
    return proc


def _wait_for_stage(proc, parent, deadline):
    """Until the run starts writing (its staging folder appears) or ends."""
    while proc.poll() is None and time.monotonic() < deadline:
        if any(p.name.startswith(".") for p in parent.iterdir()):
            return
        time.sleep(0.005)


def test_sigterm_in_the_block_removes_the_staging_folder(tmp_path):
    with pytest.raises(SystemExit) as exit_info:
        with output_folder(tmp_path / "out") as stage:
            write_text(stage / "a.txt", "a")
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(1)  # the handler runs at the next bytecode
    assert exit_info.value.code == 128 + signal.SIGTERM
    assert _listing(tmp_path) == []
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL


def test_design_interrupted_at_random_points_leaves_out_absent_or_complete(tmp_path):
    """Three runs of ``design`` side by side, sent SIGINT or SIGTERM at a random moment: two at any
    point of the run, one once it has started writing (its staging folder is there) plus up to 0.5 s.
    Each --out is then absent or byte-identical to an uninterrupted run's, and no staging folder is left."""
    rng = random.Random(17)
    cases = [(signal.SIGINT, False), (signal.SIGTERM, False), (rng.choice([signal.SIGINT, signal.SIGTERM]), True)]
    folders = [tmp_path / f"run{k}" for k in range(len(cases))]
    for folder in folders:
        folder.mkdir()
    procs = [_design(folder / "out") for folder in folders]
    start = time.monotonic()
    for proc, folder, (signum, writing) in zip(procs, folders, cases):
        if writing:
            _wait_for_stage(proc, folder, start + 60)
            time.sleep(rng.uniform(0.0, 0.5))
        else:
            time.sleep(max(0.0, start + rng.uniform(0.3, 5.0) - time.monotonic()))
        proc.send_signal(signum)
    for proc in procs:
        proc.wait(timeout=120)
    reference = tmp_path / "reference"
    assert CliRunner().invoke(main, _DESIGN + ["--out", str(reference)]).exit_code == 0
    expected = _contents(reference)
    for proc, folder in zip(procs, folders):
        assert not [p.name for p in folder.iterdir() if p.name != "out"], "a staging folder was left"
        out = folder / "out"
        if out.exists():
            assert _contents(out) == expected
        assert "Traceback" not in proc.stderr.read()



def test_an_interrupt_after_the_command_ended_exits_130_without_a_traceback(monkeypatch):
    """A Ctrl-C that lands once click has returned (the folder is complete) ends the run with the
    shell's code for an interrupt, not with a KeyboardInterrupt traceback."""
    import click

    def interrupted(*_args, **_kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(click.Group, "main", interrupted)
    with pytest.raises(SystemExit) as exit_info:
        main(["--help"])
    assert exit_info.value.code == 130


@pytest.mark.parametrize("signalled, code", [(KeyboardInterrupt(), 1), (SystemExit(143), 143)])
def test_a_signal_inside_an_extensions_import_ends_the_run_as_the_signal_does(monkeypatch, capsys, signalled, code):
    """A SIGINT or SIGTERM that lands while a C extension initialises (cvxopt's BLAS module, imported
    by ``design`` lazily) reaches the program as a SystemError caused by the signal's exception: the run
    ends with the signal's exit code (click's abort for an interrupt), without a traceback; any other
    SystemError is not hidden."""
    import click

    def import_interrupted(*_args, **_kwargs):
        try:
            raise signalled
        except BaseException as exc:
            raise SystemError("initialization of blas raised unreported exception") from exc

    monkeypatch.setattr(click.Group, "main", import_interrupted)
    with pytest.raises(SystemExit) as exit_info:
        main(["--help"])
    assert exit_info.value.code == code
    assert "Traceback" not in capsys.readouterr().err

    def broken(*_args, **_kwargs):
        raise SystemError("a real bug")

    monkeypatch.setattr(click.Group, "main", broken)
    with pytest.raises(SystemError, match="a real bug"):
        main(["--help"])


def test_freed_memory_kept_leaves_results_alone_and_gives_memory_back():
    """Inside the block large arrays are made, freed and made again; the values are those made
    outside it, also when the block raises (the allocator's settings are restored either way)."""
    rng = np.random.default_rng(0)
    x = rng.normal(size=(10**6, 3))
    expected = np.cross(x, x[::-1]).sum(axis=0)
    with freed_memory_kept():
        for _ in range(3):
            got = np.cross(x, x[::-1]).sum(axis=0)
    assert np.array_equal(got, expected)
    with pytest.raises(ValueError), freed_memory_kept():
        raise ValueError("inside")
    assert np.array_equal(np.cross(x, x[::-1]).sum(axis=0), expected)


JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers(-2**63, 2**63 - 1) | st.floats() | st.text(max_size=4),
    lambda inner: (st.lists(inner, max_size=7) | st.tuples(inner, inner)
                   | st.dictionaries(st.text(max_size=3), inner, max_size=5)
                   | st.dictionaries(st.integers(-5, 5), inner, max_size=3)),
    max_leaves=40)


@settings(max_examples=150, deadline=None)
@given(JSON_VALUES, st.integers(1, 3))
def test_json_written_in_pieces_is_orjsons_text(data, items):
    """Keys of any characters (sorted by code point, as orjson sorts them), other keys than strings,
    lists cut into pieces of ``items``: the bytes of orjson's text of the whole."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(files, "JSON_ITEMS", items)
        assert b"".join(files._json_pieces(data)) == files._dumps(data)
        assert b"".join(files._json_pieces({"k": data, "é": [data] * 4})) == files._dumps({"k": data, "é": [data] * 4})


def test_json_of_arrays_written_in_pieces_is_orjsons_text(monkeypatch):
    """Arrays orjson takes whole and those it takes as lists (not contiguous, of other types), a fragment."""
    import orjson

    monkeypatch.setattr(files, "JSON_ITEMS", 2)
    x = np.arange(15.0).reshape(5, 3) / 7
    data = {"x": x, "t": x.T, "i": np.arange(5), "b": np.array([True, False, True]), "e": np.zeros((0, 3)),
            "f": orjson.Fragment(b'[{"a":1}]'), "nan": np.array([np.nan, 1.0, np.inf]), "o": [np.arange(3)] * 5,
            "u": np.array([1, 2, 3], dtype=np.uint16), "s": np.float64(2.5)}
    assert b"".join(files._json_pieces(data)) == files._dumps(data)
