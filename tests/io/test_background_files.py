"""The figure process also writes the mesh's and the thrust network's data files (and the mesh's
quality) while the later stages run (vaultgram.io.figures.worker): the same bytes as written in one
process, and a file it cannot write is the run's error."""

from __future__ import annotations

import pytest

from vaultgram.domain import load_domain
from vaultgram.io.figures.worker import BACKGROUND, FigureWorker
from vaultgram.io.outputs import DEFAULT_FORMATS, write_design
from vaultgram.pipeline import design

from paths import EXAMPLES

SMALL = dict(spacing=0.05, tessellation=None)


def _design(out, **worker):
    """An L-shaped design with its figures (and here its files, from any size) drawn in the background."""
    with FigureWorker(out, DEFAULT_FORMATS, **worker) as figures:
        result = design(load_domain(EXAMPLES / "l_shape.json"), on_stage=figures, **SMALL)
        files = figures.files
        write_design(result, out, report=False, figures=figures)
    return result, files


def test_the_figure_process_writes_the_same_data_files(tmp_path):
    result, files = _design(tmp_path / "a", from_faces=0)
    assert files == BACKGROUND
    write_design(result, tmp_path / "b", plots=False, report=False)
    here = sorted(p.name for p in (tmp_path / "b").iterdir() if p.name != "timings.json")
    assert {"mesh.json", "mesh.obj", "thrust.json", "thrust.obj", "form.json", "summary.json"} <= set(here)
    for name in here:
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name


def test_small_meshes_keep_their_files_in_the_run(tmp_path):
    assert _design(tmp_path / "a")[1] == ()
    assert (tmp_path / "a" / "mesh.json").is_file()


def test_a_data_file_the_figure_process_cannot_write_is_an_os_error(tmp_path):
    (tmp_path / "a" / "thrust.obj").mkdir(parents=True)  # a folder where the file goes
    with pytest.raises(OSError):
        _design(tmp_path / "a", from_faces=0)


def test_the_tessellation_figures_need_neither_its_solids_nor_its_cut_mesh(tmp_path):
    """The tessellation reaches the figure process without its solids and its layout's cut mesh and
    edge tables (worker._drawn): its figures are the bytes drawn in one process from all of it."""
    from vaultgram.io.figures import Stages, write_figures
    from vaultgram.io.figures.worker import _drawn

    with FigureWorker(tmp_path / "a") as figures:
        result = design(load_domain(EXAMPLES / "l_shape.json"), spacing=0.05, on_stage=figures)
        figures.finish()
    sent = _drawn("tessellation", result.tessellation)
    assert sent.solids is None and sent.layout.mesh is None and sent.layout.edges is None
    assert sent.layout.n_voussoirs == result.tessellation.layout.n_voussoirs > 0
    names = [s.name for s in write_figures(Stages.of(result), tmp_path / "b")]
    assert {"tessellation_plan", "tessellation_3d"} <= set(names)
    for name in ("tessellation_plan", "tessellation_3d"):
        for suffix in ("png", "svg"):
            path = f"figures/{name}.{suffix}"
            assert (tmp_path / "a" / path).read_bytes() == (tmp_path / "b" / path).read_bytes(), path
