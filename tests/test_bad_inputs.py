"""The generated bad inputs (tests/badinputs.py): every one gives exit code 2, exactly one line on
stderr, no traceback, and writes nothing (no --out, no staging folder). Run in-process, a category
per test, so that the few hundred cases take seconds."""

from __future__ import annotations

import pytest
from badinputs import (
    OUT,
    all_cases,
    density_cases,
    domain_cases,
    dxf_cases,
    geojson_cases,
    graph_cases,
    mesh_cases,
    option_cases,
    support_cases,
)
from click.testing import CliRunner

from vaultgram.cli import main


def _failure(case, tmp_path) -> str | None:
    """Why ``case`` breaks the promise, or None."""
    folder = tmp_path / case.name.replace("/", "_")
    folder.mkdir()
    for name, data in case.files.items():
        (folder / name).write_bytes(data)
    args = [str(folder / "out") if a == OUT else str(folder / a) if a in case.files or a == "absent.json" else a
            for a in case.args]
    result = CliRunner().invoke(main, args)
    lines = result.stderr.strip().splitlines()
    left = sorted(p.name for p in folder.iterdir() if p.name not in case.files)
    if result.exit_code != 2 or len(lines) != 1 or "Traceback" in result.output or left:
        return f"{case.name}: exit {result.exit_code}, stderr {lines[:2]}, left {left}, {result.exception!r}"
    return None


@pytest.mark.parametrize("cases", [domain_cases, option_cases, mesh_cases, geojson_cases, dxf_cases, density_cases,
                                   support_cases, graph_cases], ids=lambda f: f.__name__)
def test_every_bad_input_is_one_line_and_exit_2(tmp_path, cases):
    failures = [f for case in cases() if (f := _failure(case, tmp_path)) is not None]
    assert not failures, "\n".join(failures)


def test_the_suite_has_at_least_300_cases_of_every_kind():
    cases = all_cases()
    kinds = {c.name.split("/")[0] for c in cases}
    assert len(cases) >= 300 and kinds == {"domain", "option", "mesh", "geojson", "dxf", "densities", "supports",
                                           "graph"}
    assert len({c.name for c in cases}) == len(cases)
