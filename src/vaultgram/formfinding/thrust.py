"""The thrust network: the result of form finding by Thrust Network Analysis (§5).

The paper (§5, Armadillo Vault) turns the meshed pattern into a form diagram, computes its reciprocal
force diagram and horizontal equilibrium, then vertical equilibrium "to generate the final funicular
geometry". :func:`vaultgram.pipeline.form_find` chains the stage functions of this package in that
order:

1. :func:`vaultgram.formfinding.formdiagram.form_diagram` -- remove fully supported edges, add opening faces;
2. :func:`vaultgram.formfinding.relaxation.relax_openings` -- bend unsupported edges into arches (if any);
3. :func:`vaultgram.formfinding.forcediagram.force_diagram` -- the reciprocal diagram (least squares);
4. :func:`vaultgram.formfinding.horizontal.horizontal` -- parallelise until the max angle < ``tol_deg``;
5. :func:`vaultgram.formfinding.vertical.vertical` -- heights under self-weight and point loads, optionally
   scaled to ``zmax``;

and :func:`thrust_network` gathers the equilibrium into a :class:`ThrustNetwork`.

References: P. Block and J. Ochsendorf, "Thrust Network Analysis: a new methodology for
three-dimensional equilibrium", J. IASS 48(3), 2007; M. Rippmann, L. Lachauer and P. Block,
"Interactive vault design", Int. J. Space Structures 27(4), 2012 (RhinoVAULT).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from vaultgram.formfinding.forcediagram import ForceDiagram
from vaultgram.formfinding.formdiagram import FormDiagram
from vaultgram.formfinding.horizontal import HorizontalResult
from vaultgram.formfinding.vertical import VerticalResult
from vaultgram.geometry.arrays import json_array
from vaultgram.geometry.frames import NO_ORIGIN, between, to_plan

__all__ = ["ThrustNetwork", "thrust_network", "format_summary"]


@dataclass(frozen=True, eq=False)
class ThrustNetwork:
    """A thrust network in equilibrium: the output of :func:`vaultgram.pipeline.form_find`.

    The heights come from vertical equilibrium, the plan and the force densities from horizontal
    equilibrium; every array is in form-diagram numbering.

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
        Counts, max angle deviation, residuals, total load, reaction sum, scale, iterations.
    form, force : FormDiagram, ForceDiagram
        The diagrams after horizontal equilibrium.
    origin : tuple of float
        Where the frame of the plan coordinates starts in the plan's (the mesh's ``origin``,
        :mod:`vaultgram.geometry.frames`); the force diagram has no place in the plan.
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
    origin: tuple = NO_ORIGIN

    def in_frame(self, origin=NO_ORIGIN) -> "ThrustNetwork":
        """The network and its form diagram in the frame starting at ``origin`` (by default the plan's
        own coordinates, as the files have them; itself when it is in that frame already)."""
        if self.origin == origin:
            return self
        o = between(self.origin, origin)
        return replace(self, vertices=to_plan(self.vertices, o), origin=origin,
                       form=self.form.with_xy(to_plan(self.form.xy, o)))

    def to_json(self, arrays: bool = False) -> dict:
        """JSON-serialisable description (for ``thrust.json``); ``arrays``: numpy arrays and tuples kept
        as they are, for :func:`vaultgram.io.files.write_json` (:func:`~vaultgram.geometry.arrays.json_array`)."""
        names = ("vertices", "vertex_ids", "edges", "q", "forces", "horizontal_forces", "loads", "reactions")
        out = {name: json_array(getattr(self, name), arrays) for name in names}
        return {**out, "faces": list(self.faces) if arrays else [list(f) for f in self.faces],
                "anchors": json_array(np.flatnonzero(self.anchors), arrays), "summary": self.summary}

    def summary_text(self) -> str:
        return format_summary(self.summary)


def format_summary(summary: dict) -> str:
    """A few readable lines from a :class:`ThrustNetwork` summary."""
    s = summary
    return "\n".join([
        f"thrust network: {s['n_vertices']} vertices, {s['n_edges']} edges, {s['n_faces']} loaded faces, "
        f"{s['n_openings']} openings, {s['n_anchors']} supports",
        f"horizontal: max angle deviation {s['max_angle_deg']:.3g} deg after {s['horizontal_iterations']} "
        f"iterations (residual {s['horizontal_residual']:.3g})",
        f"vertical:   residual {s['vertical_residual']:.3g} after {s['vertical_iterations']} iterations; "
        f"scale {s['scale']:.6g}, z max {s['zmax']:.6g}",
        f"loads:      total {s['total_load']:.6g}, reactions {s['reaction_sum']:.6g}",
        *_relaxation_line(s),
    ])


def _relaxation_line(s: dict) -> list[str]:
    """How the openings were relaxed, when the summary says (:func:`vaultgram.pipeline.form_find`)."""
    mode = s.get("relax_mode")
    if mode is None or mode == "none":
        return []
    if s.get("relax_fallback"):
        return [f"relaxed:    every free vertex ('all'): bending only the unsupported boundary failed "
                f"({s['relax_fallback'].split(':')[0]})"]
    return [f"relaxed:    {'the unsupported boundary' if mode == 'boundary' else 'every free vertex'} ('{mode}')"]


def thrust_network(h: HorizontalResult, v: VerticalResult, n_openings: int) -> ThrustNetwork:
    """The thrust network of a horizontal and a vertical equilibrium, with its summary."""
    xyz = v.xyz
    vec = h.form.C @ xyz
    l3 = np.linalg.norm(vec, axis=1)
    lh = np.hypot(vec[:, 0], vec[:, 1])
    summary = {
        "n_vertices": h.form.n_vertices,
        "n_edges": h.form.n_edges,
        "n_faces": len(h.form.loaded_faces),
        "n_openings": n_openings,
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
    }
    return ThrustNetwork(
        vertices=xyz, faces=h.form.loaded_faces, edges=np.asarray(h.form.edges), q=v.q, forces=v.q * l3,
        horizontal_forces=v.q * lh, vertex_ids=np.asarray(h.form.vertex_ids), anchors=np.asarray(h.form.anchors),
        loads=v.loads, reactions=v.reactions, summary=summary, form=h.form, force=h.force)
