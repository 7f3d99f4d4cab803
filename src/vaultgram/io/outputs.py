"""The files a run writes: one function per stage's outputs, each file written atomically.

JSON is written with sorted keys and no timings, so the same input and options give byte-identical
files (:mod:`vaultgram.io.files`). ``formats`` (:data:`OUTPUT_FORMATS`) choose the files:

* ``json`` -- ``decomposition.json``, ``patches.json``, ``mesh.json``, ``form.json``, ``force.json``,
  ``thrust.json``, ``tessellation.json``, ``summary.json`` (and the PNG figures);
* ``obj`` -- ``mesh.obj``, ``thrust.obj``, ``voussoirs.obj``;
* ``compas`` -- ``mesh.compas.json``, ``thrust.compas.json`` (COMPAS meshes), ``form.compas.json``
  (a compas_tna ``FormDiagram``), ``voussoirs.compas.json`` (:mod:`vaultgram.io.compasfiles`);
* ``3dm`` -- ``result.3dm``, ``dxf`` -- ``result.dxf``: one layer per stage (:mod:`vaultgram.io.cadfiles`).

Without ``formats`` a writer writes ``json`` and ``obj`` (:data:`DEFAULT_FORMATS`), as it always has.
The figures' modules (:mod:`vaultgram.io.plots`) and the optional formats' are imported where a figure
is drawn or such a file written, and the stages' models only named: ``vaultgram mesh``, which draws
nothing, imports no form finding, tessellation or figures (issue 18).
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import TYPE_CHECKING

from vaultgram import progress
from vaultgram.errors import VaultgramError
from vaultgram.io.files import collector_paused, write_json, write_obj, write_obj_groups, write_text
from vaultgram.io.meshfiles import mesh_to_json

if TYPE_CHECKING:
    from vaultgram.formfinding.thrust import ThrustNetwork
    from vaultgram.meshing.quadmesh import QuadMesh
    from vaultgram.tessellation.model import Tessellation
    from vaultgram.topology.decomposition import Decomposition

__all__ = ["write_decomposition", "write_mesh_files", "write_thrust", "write_tessellation", "write_design",
           "write_drawings", "design_summary", "mesh_quality", "write_design_figures",
           "parse_formats", "OUTPUT_FORMATS", "DEFAULT_FORMATS"]

#: The output formats, and the ones written when none are asked for.
OUTPUT_FORMATS = ("json", "obj", "compas", "3dm", "dxf")
DEFAULT_FORMATS = ("json", "obj")


def parse_formats(text: str | None) -> tuple:
    """The formats of a comma-separated list (:data:`DEFAULT_FORMATS` for None), each checked, and the
    optional packages they need importable, so a run fails before it computes anything.

    >>> parse_formats("json, dxf")
    ('json', 'dxf')
    >>> try:
    ...     parse_formats("json,stl")
    ... except VaultgramError as exc:
    ...     print(exc)
    --format: unknown format 'stl'; use a comma-separated list of json, obj, compas, 3dm, dxf
    """
    if text is None:
        return DEFAULT_FORMATS
    formats = tuple(dict.fromkeys(f.strip().lower() for f in text.split(",") if f.strip()))
    for f in formats:
        if f not in OUTPUT_FORMATS:
            raise VaultgramError(f"--format: unknown format {f!r}; use a comma-separated list of "
                                 f"{', '.join(OUTPUT_FORMATS)}")
    if not formats:
        raise VaultgramError(f"--format: no format given; use a comma-separated list of {', '.join(OUTPUT_FORMATS)}")
    if "compas" in formats:
        from vaultgram.io.compasfiles import require_compas

        require_compas()
    if "3dm" in formats:
        from vaultgram.domain.rhino import rhino3dm_module

        rhino3dm_module("--format 3dm")
    return formats


def write_decomposition(dec: Decomposition, out: Path, plot: bool = True, formats=DEFAULT_FORMATS,
                        trace: bool = False) -> None:
    """``decomposition.json`` (the typed graph), ``patches.json``, if ``plot`` ``decomposition.png`` and, if
    ``trace``, ``trace.json`` (every rule application) and ``start_graph.json`` (the graph before the rules
    and the patch nodes the pipeline added between strategies, as ``vaultgram rules replay`` takes them)."""
    if "json" in formats:
        write_json(out / "decomposition.json", dec.to_json())
        write_json(out / "patches.json", dec.patches_json())
        if plot:
            from vaultgram.io.plots import plot_decomposition

            plot_decomposition(dec, out / "decomposition.png")
    if trace and dec.start_graph is not None:
        write_json(out / "trace.json", dec.trace)
        write_json(out / "start_graph.json", dec.start_graph)


def write_mesh_files(mesh: QuadMesh, out: Path, supports=None, plot: bool = True, formats=DEFAULT_FORMATS) -> None:
    """``mesh.json`` (with the supported vertices, if given), ``mesh.obj``, ``mesh.compas.json`` and, if
    ``plot``, ``mesh.png``, as ``formats`` ask; in the plan's coordinates (:mod:`vaultgram.geometry.frames`)."""
    mesh = mesh.in_frame()
    if "json" in formats:
        write_json(out / "mesh.json", mesh_to_json(mesh, supports, arrays=True))
        if plot:
            from vaultgram.io.plots import plot_mesh

            plot_mesh(mesh, out / "mesh.png")
    if "obj" in formats:
        write_obj(out / "mesh.obj", mesh.vertices, mesh.faces)
    if "compas" in formats:
        _write_compas(out / "mesh.compas.json", mesh, supports)


def write_thrust(network: ThrustNetwork, out: Path, plot: bool = False, formats=DEFAULT_FORMATS) -> None:
    """``form.json``, ``force.json``, ``thrust.json``, ``summary.json`` and, if ``plot``, ``thrust.png``;
    ``thrust.obj``; ``thrust.compas.json`` and ``form.compas.json``, as ``formats`` ask; in the plan's
    coordinates."""
    network = network.in_frame()
    if "json" in formats:
        write_json(out / "form.json", network.form.to_json(arrays=True))
        write_json(out / "force.json", network.force.to_json(arrays=True))
        write_json(out / "thrust.json", network.to_json(arrays=True))
    if "obj" in formats:
        write_obj(out / "thrust.obj", network.vertices, network.faces)
    if "json" in formats:
        write_json(out / "summary.json", network.summary)
        if plot:
            from vaultgram.io.plots import plot_thrust

            plot_thrust(network, out / "thrust.png")
    if "compas" in formats:
        from vaultgram.io.compasfiles import compas_json, to_formdiagram

        _write_compas(out / "thrust.compas.json", network)
        write_text(out / "form.compas.json", compas_json(to_formdiagram(network)))


def write_tessellation(tessellation: Tessellation, out: Path, summary: bool = False, plot: bool = True,
                       formats=DEFAULT_FORMATS) -> None:
    """``tessellation.json``, ``voussoirs.obj`` (one closed solid ``o voussoir_N`` per voussoir, in the
    order of ``voussoirs``), ``voussoirs.compas.json`` and, if ``plot``, ``tessellation.png``; with
    ``summary``, also ``summary.json`` (the tessellation's alone); as ``formats`` ask; in the plan's
    coordinates."""
    if "json" in formats:
        write_json(out / "tessellation.json", tessellation.to_json(arrays=True))
    tessellation = tessellation.in_frame()  # after the JSON: its areas are measured in the local frame
    if "obj" in formats:
        solids = tessellation.solids
        write_obj_groups(out / "voussoirs.obj", solids.vertices, solids.triangles, solids.owner, "voussoir_")
    if "json" in formats:
        if summary:
            write_json(out / "summary.json", tessellation.summary)
        if plot:
            from vaultgram.io.plots import plot_tessellation

            plot_tessellation(tessellation, out / "tessellation.png")
    if "compas" in formats:
        _write_compas(out / "voussoirs.compas.json", tessellation)


def _write_compas(path: Path, item, supports=None) -> None:
    from vaultgram.io.compasfiles import compas_json, to_compas_mesh

    write_text(path, compas_json(to_compas_mesh(item, supports)))


def write_design(result, out: Path, formats=DEFAULT_FORMATS, trace: bool = False, plots: bool = True,
                 report: bool = True, parameters: dict | None = None, figures=None) -> dict:
    """Every file of a whole design (:class:`vaultgram.pipeline.Design`), as ``formats`` ask: each stage's,
    ``summary.json`` (one section per stage, and the ``parameters`` given), the drawings and the rules'
    trace if ``trace``; then, with ``plots`` the figures of every stage (:mod:`vaultgram.io.figures`:
    drawn here, or waited for from ``figures``, the :class:`~vaultgram.io.figures.worker.FigureWorker`
    that drew them in the background while the stages ran and these files were written) and with
    ``report`` ``report.html`` (:mod:`vaultgram.io.report`); ``timings.json`` has the seconds of every
    stage, these included (the one file that differs between reruns, with the report that shows it).
    Returns the timings."""
    timings = dict(result.timings)
    background = figures.files if figures is not None else ()  # written by the figure process
    with progress.timed(timings, "write"), collector_paused():
        write_decomposition(result.decomposition, out, plot=False, formats=formats, trace=trace)
        if "mesh" not in background:
            write_mesh_files(result.mesh, out, result.supports, plot=False, formats=formats)
        if "network" not in background:
            write_thrust(result.network, out, plot=False, formats=formats)
        if result.tessellation is not None:
            write_tessellation(result.tessellation, out, plot=False, formats=formats)
        write_drawings(out, formats, result.domain.units, decomposition=result.decomposition, mesh=result.mesh,
                       network=result.network, tessellation=result.tessellation)
    if figures is not None and figures.handover:  # the stages pickled to the figure process, during the design
        timings["figures"] = figures.handover
    if plots and "json" in formats:
        with progress.timed(timings, "figures"), collector_paused():
            write_design_figures(result, out, figures)
    elif background:
        figures.finish()  # the data files it writes
    if "json" in formats:  # after the figure process: its thrust.json wrote the network's summary.json
        with progress.timed(timings, "write"):
            quality = figures.mesh_quality if background else None
            write_json(out / "summary.json", design_summary(result, parameters, quality))
    write_json(out / "timings.json", timings)
    if report and "json" in formats:
        from vaultgram.io.report import write_report

        write_report(out)
    return timings


def design_summary(result, parameters: dict | None = None, quality: dict | None = None) -> dict:
    """``summary.json`` of a design: each stage's summary (:meth:`vaultgram.pipeline.Design.summary`), the
    decomposition's counts, the mesh's ``quality`` (:func:`mesh_quality`, worked out here if not given)
    and the ``parameters`` of the run."""
    dec = result.decomposition
    counts = dec.patches_json()["counts"]
    summary = {**result.summary(),
               "decomposition": {"patches": len(dec.patches), "four_sided": counts["4"], "three_sided": counts["3"],
                                 "singularities": len(dec.singularities()),
                                 "rule_applications": sum(r.applications for r in dec.reports)},
               "mesh_quality": quality if quality is not None else mesh_quality(result.mesh, result.domain)}
    if parameters is not None:
        summary["parameters"] = parameters
    return summary


def mesh_quality(mesh: QuadMesh, domain) -> dict:
    """The mesh's quality for ``summary.json``: :func:`vaultgram.meshing.quality.mesh_stats` without its
    vertex lists."""
    from vaultgram.meshing.quality import mesh_stats

    return {k: v for k, v in mesh_stats(mesh, domain).items() if not isinstance(v, (list, tuple, dict))}


def write_design_figures(result, out: Path, worker=None) -> None:
    """Every stage's figure in ``figures/`` as PNG and SVG (drawn now, or the ``worker``'s, waited
    for), and the PNG figures beside the files (``decomposition.png``, ``mesh.png``, ``thrust.png``,
    ``tessellation.png``: copies of four of them)."""
    from vaultgram.io.figures import BESIDE, Stages, write_figures

    if worker is not None:
        written = set(worker.finish())
    else:
        written = {spec.name for spec in write_figures(Stages.of(result), out)}
    for name, figure in BESIDE.items():
        if figure in written:  # the same figure, not drawn twice
            shutil.copyfile(out / "figures" / f"{figure}.png", out / name)


def write_drawings(out: Path, formats, units: str | None = None, **stages) -> None:
    """``result.3dm`` and ``result.dxf``, as ``formats`` ask: the ``stages`` given (``decomposition``,
    ``mesh``, ``network``, ``tessellation``) on one layer each (:func:`vaultgram.io.cadfiles.drawing`)."""
    if "3dm" not in formats and "dxf" not in formats:
        return
    from vaultgram.io.cadfiles import drawing, write_3dm, write_dxf

    layers = drawing(**stages)
    if "3dm" in formats:
        write_3dm(out / "result.3dm", layers, units)
    if "dxf" in formats:
        write_dxf(out / "result.dxf", layers, units)
