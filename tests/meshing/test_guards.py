"""Resource guards: the size of a mesh known from its counts, refused before it is made; option bounds."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from vaultgram.cli import main
from vaultgram.domain import load_domain
from vaultgram.errors import VaultgramError
from vaultgram.limits import MAX_COUNT, MAX_FACES
from vaultgram.meshing.densities import DensitySpec, densities_from_dict, group_counts
from vaultgram.meshing.guards import check_mesh_size, estimate_mesh
from vaultgram.meshing.layout import edge_groups
from vaultgram.meshing.weld import weld
from vaultgram.pipeline import decompose

from paths import EXAMPLES

QWH = EXAMPLES / "quad_with_hole.json"


@pytest.mark.parametrize("name", ["fig6_inner_points", "features_combined"])
def test_the_estimate_is_the_number_of_faces_welded(name):
    """Exact for quads and for the triangle patches of poles (both examples have some)."""
    layout = edge_groups(decompose(load_domain(EXAMPLES / f"{name}.json"), 0.03))
    assert any(p.pole is not None for p in layout.patterns)
    for counts in (group_counts(layout), group_counts(layout, DensitySpec(min_count=5))):
        assert estimate_mesh(layout, counts).faces == len(weld(layout, counts).faces)


def test_the_estimate_grows_with_the_square_of_the_density(qwh_layout):
    base = estimate_mesh(qwh_layout, group_counts(qwh_layout, target_length=0.5)).faces
    finer = estimate_mesh(qwh_layout, group_counts(qwh_layout, target_length=0.25)).faces
    assert 3.5 < finer / base < 4.5


def test_too_many_faces_are_refused_with_the_estimate_and_the_limit(qwh_layout):
    with pytest.raises(VaultgramError, match=r"about 1\.0\de\+08 faces \(about \d+ GB of memory\).*2000000"):
        group_counts(qwh_layout, target_length=1e-3, max_faces=MAX_FACES)
    counts = group_counts(qwh_layout, target_length=0.1)
    with pytest.raises(VaultgramError, match="more than the limit of 1000 faces"):
        check_mesh_size(qwh_layout, counts, 1000)
    assert check_mesh_size(qwh_layout, counts, 10**6).faces == estimate_mesh(qwh_layout, counts).faces


def test_a_vanishing_target_length_is_refused_not_overflowed(qwh_layout):
    with pytest.raises(VaultgramError, match="faces"):
        group_counts(qwh_layout, target_length=1e-300, max_faces=MAX_FACES)


def test_density_file_counts_are_bounded():
    with pytest.raises(VaultgramError, match=f"min_count 1000000 is more than the limit of {MAX_COUNT}"):
        densities_from_dict({"min_count": 1_000_000})
    with pytest.raises(VaultgramError, match="group 2: count 200000 is more than"):
        densities_from_dict({"groups": {"2": 200_000}})
    with pytest.raises(VaultgramError, match="min_count must be a positive integer"):
        densities_from_dict({"min_count": True})


def _invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.mark.parametrize("args, words", [
    (["--target-length", "1e-3"], ["1.02e+08 faces", "--max-faces"]),
    (["--target-length", "0.2", "--max-faces", "100"], ["more than the limit of 100 faces"]),
    (["--spacing", "1e-5"], ["--spacing", "outside 0.01 to 0.05", "--any-spacing"]),
    (["--spacing", "0.3", "--any-spacing"], ["outside 0 to 0.2"]),
    (["--spacing", "nan"], ["--spacing", "not a finite number"]),
    (["--target-length", "inf"], ["--target-length", "not a finite number"]),
    (["--smooth", "100000"], ["--smooth", "0<=x<=1000"]),
    (["--smooth", "-1"], ["--smooth"]),
])
def test_mesh_options_out_of_bounds_are_one_line(tmp_path, args, words):
    result = _invoke("mesh", QWH, "--out", tmp_path / "out", *args)
    lines = result.output.strip().splitlines()
    assert result.exit_code == 2 and len(lines) == 1, result.output
    assert all(w in lines[0] for w in words), lines[0]
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("option", ["--zmax", "--thickness", "--density", "--point-load", "--tol-deg", "--sag",
                                    "--max-concavity"])
@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_every_float_option_of_design_is_finite(tmp_path, option, value):
    result = _invoke("design", QWH, "--out", tmp_path / "out", option, value)
    assert result.exit_code == 2 and len(result.output.strip().splitlines()) == 1, result.output
    assert option in result.output


def test_any_spacing_allows_a_spacing_outside_the_usual_range(tmp_path):
    result = _invoke("decompose", QWH, "--out", tmp_path / "out", "--spacing", "0.08", "--any-spacing", "--no-plot")
    assert result.exit_code == 0, result.output
    patches = json.loads((tmp_path / "out" / "patches.json").read_text())
    assert patches["counts"]["4"] + patches["counts"]["3"] > 0
    assert np.isclose(json.loads((tmp_path / "out" / "decomposition.json").read_text())["spacing"], 0.08)
