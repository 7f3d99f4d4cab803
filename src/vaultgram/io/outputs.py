"""The files a run writes: one function per stage's outputs, each file written atomically.

JSON is written with sorted keys and no timings, so the same input and options give byte-identical
files (:mod:`vaultgram.io.files`).
"""

from __future__ import annotations

from pathlib import Path

from vaultgram.formfinding.thrust import ThrustNetwork
from vaultgram.io.files import write_json, write_obj, write_obj_objects
from vaultgram.io.meshfiles import write_mesh
from vaultgram.io.plots import plot_decomposition, plot_mesh, plot_tessellation, plot_thrust
from vaultgram.meshing.quadmesh import QuadMesh
from vaultgram.tessellation.model import Tessellation
from vaultgram.topology.decomposition import Decomposition

__all__ = ["write_decomposition", "write_mesh_files", "write_thrust", "write_tessellation"]


def write_decomposition(dec: Decomposition, out: Path, plot: bool = True, trace: bool = False) -> None:
    """``decomposition.json`` (the typed graph), ``patches.json``, if ``plot`` ``decomposition.png`` and, if
    ``trace``, ``trace.json`` (every rule application) and ``start_graph.json`` (the graph before the rules
    and the patch nodes the pipeline added between strategies, as ``vaultgram rules replay`` takes them)."""
    write_json(out / "decomposition.json", dec.to_json())
    write_json(out / "patches.json", dec.patches_json())
    if trace and dec.start_graph is not None:
        write_json(out / "trace.json", dec.trace)
        write_json(out / "start_graph.json", dec.start_graph)
    if plot:
        plot_decomposition(dec, out / "decomposition.png")


def write_mesh_files(mesh: QuadMesh, out: Path, supports=None, plot: bool = True) -> None:
    """``mesh.json`` (with the supported vertices, if given), ``mesh.obj`` and, if ``plot``, ``mesh.png``."""
    write_mesh(mesh, out, supports)
    if plot:
        plot_mesh(mesh, out / "mesh.png")


def write_thrust(network: ThrustNetwork, out: Path, plot: bool = False) -> None:
    """``form.json``, ``force.json``, ``thrust.json``, ``thrust.obj``, ``summary.json`` and, if ``plot``,
    ``thrust.png``."""
    write_json(out / "form.json", network.form.to_json())
    write_json(out / "force.json", network.force.to_json())
    write_json(out / "thrust.json", network.to_json())
    write_obj(out / "thrust.obj", network.vertices, network.faces)
    write_json(out / "summary.json", network.summary)
    if plot:
        plot_thrust(network, out / "thrust.png")


def write_tessellation(tessellation: Tessellation, out: Path, summary: bool = False, plot: bool = True) -> None:
    """``tessellation.json``, ``voussoirs.obj`` (one closed solid ``o voussoir_N`` per voussoir, in the
    order of ``voussoirs``) and, if ``plot``, ``tessellation.png``; with ``summary``, also
    ``summary.json`` (the tessellation's alone)."""
    write_json(out / "tessellation.json", tessellation.to_json())
    solids = tessellation.solids
    objects = [(f"voussoir_{k}", solids.of(k)) for k in range(tessellation.layout.n_voussoirs)]
    write_obj_objects(out / "voussoirs.obj", solids.vertices, objects)
    if summary:
        write_json(out / "summary.json", tessellation.summary)
    if plot:
        plot_tessellation(tessellation, out / "tessellation.png")
