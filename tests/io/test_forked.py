"""Data files written by several processes at once (vaultgram.io.forked, as write_design does from
FORK_FACES faces on) are the same files, byte for byte, as written one after the other; a failure in
a child is raised in the parent."""

from __future__ import annotations

import pytest

from vaultgram.domain import load_domain
from vaultgram.io import outputs
from vaultgram.io.forked import run_all
from vaultgram.pipeline import design

from paths import EXAMPLES


def files(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != "timings.json"}


def test_forked_writes_are_the_sequential_files(tmp_path, monkeypatch):
    result = design(load_domain(EXAMPLES / "l_shape.json"), spacing=0.05)
    outputs.write_design(result, tmp_path / "seq", plots=False, report=False)
    monkeypatch.setattr(outputs, "FORK_FACES", 0)
    outputs.write_design(result, tmp_path / "par", plots=False, report=False)
    seq, par = files(tmp_path / "seq"), files(tmp_path / "par")
    assert set(seq) >= {"summary.json", "mesh.json", "thrust.json", "tessellation.json", "voussoirs.obj"}
    assert seq == par


def test_a_failing_child_is_raised_here(tmp_path):
    def fails():
        raise OSError(28, "No space left on device", str(tmp_path / "x"))

    with pytest.raises(OSError, match="No space left"):
        run_all([fails, lambda: None])
