"""One variant, rebuilt and measured: its decomposition, patches, mesh, metrics and thumbnail.

:func:`evaluate` is a pure function of a :class:`Job` (the domain, the options, the variant's
choices), so it runs the same in this process, in a pool worker or on a Dask worker, and ``vaultgram
replay`` writes byte for byte what ``vaultgram explore`` wrote. The decomposition is rebuilt from the
domain with the variant's choices (:class:`~.program.Scripted`), meshed with the pipeline's own
meshing at the common target length (:func:`vaultgram.pipeline.mesh_decomposition`; folds are
counted, not refused, so every variant can be compared) and measured with
:func:`vaultgram.meshing.quality.mesh_stats` (and, with ``formfind``, form-found). Its files are
returned as bytes, for the caller to write inside its output folder.
"""

from __future__ import annotations

import tempfile
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from vaultgram.domain import Domain
from vaultgram.errors import VaultgramError
from vaultgram.exploration.layout import layout_of
from vaultgram.exploration.program import Scripted
from vaultgram.exploration.thumbnail import thumbnail_svg
from vaultgram.io.outputs import write_decomposition, write_mesh_files
from vaultgram.meshing.layout import choose_pole
from vaultgram.meshing.quality import mesh_stats

FILES = ("decomposition.json", "patches.json", "mesh.json")  # what each variant's folder holds


@dataclass(frozen=True)
class Job:
    """Everything a variant's evaluation depends on (picklable, for process pools and Dask)."""

    variant: int
    answers: tuple
    domain: Domain
    spacing: float
    rules_dir: str | None
    target_length: float | None
    smooth: int
    hash: str  # the search's layout hash, which the rebuilt decomposition must have
    formfind: bool = False  # also form-find the mesh (§5) and measure the thrust network


@dataclass(frozen=True)
class Evaluation:
    """A variant's metrics, its files (name -> bytes) and its thumbnail (SVG text)."""

    variant: int
    metrics: dict
    files: dict
    svg: str


def evaluate(job: Job) -> Evaluation:
    """Rebuild, mesh and measure one variant (see the module docstring)."""
    from vaultgram.meshpipeline import decompose, mesh_decomposition

    dec = decompose(job.domain, job.spacing, job.rules_dir, chooser=Scripted(job.answers))
    layout = layout_of(dec.graph, list(dec.patches))
    if layout.hash != job.hash:  # the search and the rebuild took different paths: a fault, not input
        raise RuntimeError(f"variant {job.variant}: rebuilt layout {layout.hash} differs from the search's {job.hash}")
    mesh = mesh_decomposition(dec, job.target_length, job.smooth, allow_folds=True)
    metrics = {**layout_metrics(dec), **mesh_metrics(mesh, job.domain)}
    if job.formfind:
        metrics.update(formfind_metrics(mesh, job.domain))
    return Evaluation(job.variant, metrics, _files(dec, mesh), thumbnail_svg(dec, mesh))


def layout_metrics(dec) -> dict:
    """Patches by sides, layout singularities by valence (inner corner points not round 4 patches;
    the key is the number of patches), poles (points that are the pole of a triangle patch)."""
    around = Counter(c for p in dec.patches for c in p.corners)
    boundary = {n for n in around if "ring" in dec.graph.node_attrs(n)}
    valence = Counter(k for n, k in around.items() if n not in boundary and k != 4)
    poles = {choose_pole(dec, p) for p in dec.patches if p.n_sides == 3}
    return {
        "patches": len(dec.patches),
        "patches_by_sides": {str(k): sum(p.n_sides == k for p in dec.patches) for k in (3, 4)},
        "singularities": sum(valence.values()),
        "singularities_by_valence": {str(k): valence[k] for k in sorted(valence)},
        "poles": len(poles),
    }


def mesh_metrics(mesh, domain: Domain) -> dict:
    """The mesh's edge groups (density degrees of freedom, §3.2) and quality."""
    stats = mesh_stats(mesh, domain)
    return {
        "edge_groups": int(mesh.info["edge_groups"]),
        "boundary_singularities": int(stats["boundary_singular"]),
        "interior_singular_vertices": int(stats["interior_singular"]),
        "min_scaled_jacobian": round(float(stats["min_scaled_jacobian"]), 6),
        "mean_scaled_jacobian": round(float(stats["mean_scaled_jacobian"]), 6),
        "inverted_faces": int(stats["inverted_faces"]),
        "faces": int(stats["faces"]),
    }


def formfind_metrics(mesh, domain: Domain) -> dict:
    """The form-finding result of the mesh with the domain's supports (:func:`vaultgram.pipeline.
    thrust_of_mesh`): the largest angle deviation between form and force diagram, the largest
    horizontal thrust, the rise; or why there is no compression-only network."""
    from vaultgram.pipeline import thrust_of_mesh

    try:
        network = thrust_of_mesh(mesh, domain.supports, domain)
    except VaultgramError as exc:
        return {"formfind_error": str(exc)}
    return {"angle_deviation_deg": round(float(network.summary["max_angle_deg"]), 6),
            "max_thrust": round(float(np.max(network.horizontal_forces)), 6),
            "zmax": round(float(network.summary["zmax"]), 6)}


def _files(dec, mesh) -> dict:
    """The variant's files, written by the pipeline's own writers, as bytes."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        write_decomposition(dec, out, plot=False)
        write_mesh_files(mesh, out, plot=False, formats=("json",))
        return {name: (out / name).read_bytes() for name in FILES}


def evaluate_or_error(job: Job) -> Evaluation:
    """:func:`evaluate`, with a variant the meshing refuses kept as an evaluation that says why."""
    try:
        return evaluate(job)
    except VaultgramError as exc:
        return Evaluation(job.variant, {"error": str(exc)}, {}, "")
