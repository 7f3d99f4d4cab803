"""Form finding by Thrust Network Analysis: ``QuadMesh -> FormDiagram -> ThrustNetwork`` (§5).

The paper (§5, Armadillo Vault) turns the meshed pattern into a form diagram, computes its reciprocal
force diagram and horizontal equilibrium, then vertical equilibrium "to generate the final funicular
geometry". :func:`form_find` chains the stage functions of this package in that order:

1. :func:`vaultgram.formfinding.formdiagram.form_diagram` -- remove fully supported edges, add opening faces;
2. :func:`vaultgram.formfinding.horizontal.relax_openings` -- bend unsupported edges into arches (if any);
3. :func:`vaultgram.formfinding.forcediagram.force_diagram` -- the reciprocal diagram (least squares);
4. :func:`vaultgram.formfinding.horizontal.horizontal` -- parallelise until the max angle < ``tol_deg``;
5. :func:`vaultgram.formfinding.vertical.vertical` -- heights under self-weight and point loads, optionally
   scaled to ``zmax``.

References: P. Block and J. Ochsendorf, "Thrust Network Analysis: a new methodology for
three-dimensional equilibrium", J. IASS 48(3), 2007; M. Rippmann, L. Lachauer and P. Block,
"Interactive vault design", Int. J. Space Structures 27(4), 2012 (RhinoVAULT).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
import time

import numpy as np

from vaultgram.formfinding.forcediagram import ForceDiagram, force_diagram
from vaultgram.formfinding.formdiagram import FormDiagram, form_diagram
from vaultgram.formfinding.horizontal import HorizontalResult, horizontal, relax_openings
from vaultgram.geometry.meshes import write_obj
from vaultgram.formfinding.vertical import VerticalResult, vertical

__all__ = ["ThrustNetwork", "form_find", "format_summary"]


@dataclass(frozen=True, eq=False)
class ThrustNetwork:
    """A thrust network in equilibrium: the output of :func:`form_find`.

    Attributes
    ----------
    vertices : ndarray (n, 3)
        Vertex positions (form-diagram numbering; ``vertex_ids`` maps to the input mesh).
    faces : tuple of tuples
        Loaded faces (openings excluded), in form-diagram numbering.
    edges : ndarray (m, 2)
        Edges of the network.
    q : ndarray (m,)
        Force densities (scaled): axial force / 3D length.
    forces : ndarray (m,)
        Axial compression forces ``q * |edge in 3D|``.
    horizontal_forces : ndarray (m,)
        ``q * |edge in plan|`` (the force-diagram lengths times the scale).
    vertex_ids : ndarray (n,)
        Input-mesh index of each vertex.
    anchors : ndarray (n,) bool
    loads : ndarray (n,)
        Vertical loads (positive downwards).
    reactions : ndarray (n_anchors, 3)
        Support reactions (Rx, Ry, Rz), Rz positive upwards, in the order of ``np.flatnonzero(anchors)``.
    summary : dict
        Max angle deviation, residuals, total load, reaction sum, scale, iterations, timings.
    form, force : FormDiagram, ForceDiagram
        The diagrams after horizontal equilibrium.
    """

    vertices: np.ndarray
    faces: tuple
    edges: np.ndarray
    q: np.ndarray
    forces: np.ndarray
    horizontal_forces: np.ndarray
    vertex_ids: np.ndarray
    anchors: np.ndarray
    loads: np.ndarray
    reactions: np.ndarray
    summary: dict
    form: FormDiagram = field(repr=False)
    force: ForceDiagram = field(repr=False)

    def to_json(self) -> dict:
        """JSON-serialisable description (for ``thrust.json``)."""
        return {
            "vertices": self.vertices.tolist(),
            "vertex_ids": self.vertex_ids.tolist(),
            "faces": [list(f) for f in self.faces],
            "edges": self.edges.tolist(),
            "q": self.q.tolist(),
            "forces": self.forces.tolist(),
            "horizontal_forces": self.horizontal_forces.tolist(),
            "anchors": np.flatnonzero(self.anchors).tolist(),
            "loads": self.loads.tolist(),
            "reactions": self.reactions.tolist(),
            "summary": self.summary,
        }

    def write_obj(self, path: str | Path) -> None:
        """Write the network's loaded faces as a Wavefront OBJ (``thrust.obj``)."""
        write_obj(path, self.vertices, self.faces)

    def summary_text(self) -> str:
        return format_summary(self.summary)


def format_summary(summary: dict) -> str:
    """A few readable lines from a :class:`ThrustNetwork` summary."""
    s = summary
    t = s["timings"]
    return "\n".join([
        f"thrust network: {s['n_vertices']} vertices, {s['n_edges']} edges, {s['n_faces']} loaded faces, "
        f"{s['n_openings']} openings, {s['n_anchors']} supports",
        f"horizontal: max angle deviation {s['max_angle_deg']:.3g} deg after {s['horizontal_iterations']} "
        f"iterations (residual {s['horizontal_residual']:.3g})",
        f"vertical:   residual {s['vertical_residual']:.3g} after {s['vertical_iterations']} iterations; "
        f"scale {s['scale']:.6g}, z max {s['zmax']:.6g}",
        f"loads:      total {s['total_load']:.6g}, reactions {s['reaction_sum']:.6g}",
        "time:       " + ", ".join(f"{k} {v * 1000:.1f} ms" for k, v in t.items()),
    ])


def _mesh_point_loads(point_loads, n_mesh: int):
    if point_loads is None or isinstance(point_loads, dict):
        return point_loads
    arr = np.asarray(point_loads, dtype=float).ravel()
    if arr.shape != (n_mesh,):
        raise ValueError(f"point_loads has {arr.size} entries; give one per mesh vertex ({n_mesh}) "
                         f"or a dict {{mesh vertex: load}}")
    return {int(i): float(arr[i]) for i in np.flatnonzero(arr)}


def form_find(mesh_vertices, faces, supports=None, *, zmax: float | None = None, scale: float = 1.0,
              thickness=1.0, density: float = 1.0, point_loads=None, tol_deg: float = 0.5,
              alpha: float = 100.0, relax: bool = True, sag: float = 0.1, relax_mode: str = "boundary",
              update_boundaries: bool = True, kmax_horizontal: int = 1000, kmax_vertical: int = 500,
              vertical_tol: float = 1e-12) -> ThrustNetwork:
    """Form-find a funicular vault over a planar mesh by Thrust Network Analysis (§5).

    Parameters
    ----------
    mesh_vertices : array (n, 2) or (n, 3)
    faces : sequence of counter-clockwise vertex-index sequences
    supports : vertex indices or boolean mask; default every boundary vertex
    zmax : float, optional
        Height of the highest vertex; the thrust scale is solved for. Without it ``scale`` is used.
    scale : float
        Thrust scale when ``zmax`` is None (force densities = scale x force/form length ratios).
    thickness, density : self-weight = 3D tributary area x thickness x density
    point_loads : dict {mesh vertex: load} or array (n_mesh,), positive downwards
    tol_deg : float
        Horizontal-equilibrium tolerance on the max angle between form and force edges (degrees).
    alpha : float
        Form weight (percent) in horizontal equilibrium; 100 keeps the form diagram.
    relax, sag, relax_mode
        Relax open edges (:func:`vaultgram.formfinding.horizontal.relax_openings`) before horizontal equilibrium.
    update_boundaries : bool
        See :func:`vaultgram.formfinding.formdiagram.form_diagram`.

    Returns
    -------
    ThrustNetwork

    Raises
    ------
    FormFindingError, HorizontalEquilibriumError, ConvergenceError
        bad input (named), no compression-only solution (edges and angles named), non-convergence.

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> v, f = grid_mesh(6)
    >>> tn = form_find(v, f, zmax=2.0)
    >>> round(float(tn.vertices[:, 2].max()), 9), tn.summary["max_angle_deg"] < 0.5
    (2.0, True)
    """
    timings = {}
    t = time.perf_counter()
    n_mesh = len(mesh_vertices)
    form = form_diagram(mesh_vertices, faces, supports, update_boundaries=update_boundaries)
    timings["form"] = time.perf_counter() - t
    t = time.perf_counter()
    n_open = int((~form.loaded).sum())
    if relax and n_open:
        form = relax_openings(form, sag, mode=relax_mode)
    timings["relax"] = time.perf_counter() - t
    t = time.perf_counter()
    force = force_diagram(form)
    timings["force"] = time.perf_counter() - t
    h: HorizontalResult = horizontal(form, force, alpha=alpha, kmax=kmax_horizontal, tol_deg=tol_deg)
    timings["horizontal"] = h.seconds
    v: VerticalResult = vertical(h.form, h.q, scale=scale, zmax=zmax, thickness=thickness, density=density,
                                 point_loads=_mesh_point_loads(point_loads, n_mesh), kmax=kmax_vertical,
                                 tol=vertical_tol)
    timings["vertical"] = v.seconds
    timings["total"] = sum(timings.values())
    xyz = v.xyz
    vec = h.form.C @ xyz
    l3 = np.linalg.norm(vec, axis=1)
    lh = np.hypot(vec[:, 0], vec[:, 1])
    summary = {
        "n_vertices": h.form.n_vertices,
        "n_edges": h.form.n_edges,
        "n_faces": len(h.form.loaded_faces),
        "n_openings": n_open,
        "n_anchors": int(h.form.anchors.sum()),
        "max_angle_deg": h.max_angle,
        "horizontal_iterations": h.iterations,
        "horizontal_residual": v.residual_xy,
        "vertical_residual": v.residual,
        "vertical_iterations": v.iterations,
        "total_load": v.total_load,
        "reaction_sum": float(v.reactions[:, 2].sum()),
        "scale": v.scale,
        "zmax": float(xyz[:, 2].max()),
        "timings": timings,
    }
    return ThrustNetwork(
        vertices=xyz, faces=h.form.loaded_faces, edges=np.asarray(h.form.edges), q=v.q, forces=v.q * l3,
        horizontal_forces=v.q * lh, vertex_ids=np.asarray(h.form.vertex_ids), anchors=np.asarray(h.form.anchors),
        loads=v.loads, reactions=v.reactions, summary=summary, form=h.form, force=h.force)
