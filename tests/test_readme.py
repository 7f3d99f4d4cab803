"""The README stays true: its Python examples run and say what it claims, its commands exist."""

from __future__ import annotations

import contextlib
import io
import re

import pytest
from click.testing import CliRunner

from vaultgram.cli import main

from paths import REPO

README = (REPO / "README.md").read_text()
PYTHON_BLOCKS = re.findall(r"```python\n(.*?)```", README, flags=re.S)
SHELL = "".join(re.findall(r"```sh\n(.*?)```", README, flags=re.S))
RULES_COMMANDS = "check|run|why-not|matches|test|replay"
COMMANDS = sorted(set(re.findall(rf"^vaultgram (\w+(?: (?:{RULES_COMMANDS}))?)", SHELL, flags=re.M)))


def run_block(code: str, folder, monkeypatch) -> str:
    """Run one README example in ``folder`` (beside links to the examples and rules) and return what it printed."""
    for name in ("examples", "rules"):
        (folder / name).symlink_to(REPO / name)
    monkeypatch.chdir(folder)
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(compile(code, "README.md", "exec"), {})
    return printed.getvalue()


def test_the_readme_has_the_pipeline_the_api_and_the_engine_examples():
    assert len(PYTHON_BLOCKS) == 3 and "..." not in "".join(PYTHON_BLOCKS)


def test_the_pipeline_example_runs_every_stage_and_writes_the_voussoirs(tmp_path, monkeypatch):
    printed = run_block(PYTHON_BLOCKS[0], tmp_path, monkeypatch)
    patches, quads, _, voussoirs = re.match(
        r"(\d+) patches, (\d+) quads, ([\d.]+) deg, (\d+) voussoirs", printed
    ).groups()
    assert int(patches) == 12 and int(quads) > 500 and 0 < int(voussoirs) < int(quads)
    assert {p.name for p in (tmp_path / "out").iterdir()} == {"tessellation.json", "voussoirs.obj", "tessellation.png"}


def test_the_api_example_designs_and_saves_a_dxf(tmp_path, monkeypatch):
    printed = run_block(PYTHON_BLOCKS[1], tmp_path, monkeypatch)
    faces, voussoirs = map(int, re.match(r"(\d+) faces, (\d+) voussoirs", printed).groups())
    assert 0 < voussoirs < faces
    names = {p.name for p in (tmp_path / "out").iterdir()}
    assert {"result.dxf", "thrust.json", "tessellation.json"} <= names and "thrust.obj" not in names


def test_the_engine_example_prunes_the_corner_branch(tmp_path, monkeypatch):
    printed = run_block(PYTHON_BLOCKS[2], tmp_path, monkeypatch)
    assert printed.startswith("0 {'rule': 'prune_corner_branch'")


def test_the_usage_lists_every_command():
    assert {c.split()[0] for c in COMMANDS} == set(main.commands)


@pytest.mark.parametrize("command", COMMANDS)
def test_every_command_in_the_usage_exists(command):
    result = CliRunner().invoke(main, [*command.split(), "--help"])
    assert result.exit_code == 0, result.output
