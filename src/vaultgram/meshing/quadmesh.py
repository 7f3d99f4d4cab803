"""The quad mesh: vertices, faces and the labels that smoothing and the later stages need (§3.2).

A :class:`QuadMesh` is what welding the Coons patches gives (:func:`vaultgram.meshing.weld.weld`)
and what smoothing improves: quads, and triangles at poles, counter-clockwise, with per-vertex
labels (boundary, corners, features, curves, poles) and the :class:`SlideConstraint` s along which
boundary and curve vertices slide (:func:`slide`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from vaultgram.geometry.frames import NO_ORIGIN, between, to_plan
from vaultgram.geometry.meshes import Faces
from vaultgram.geometry.polylines import project_to_polyline

__all__ = ["QuadMesh", "SlideConstraint", "slide"]


@dataclass(frozen=True, eq=False)
class SlideConstraint:
    """Vertices that must stay on a polyline (a stretch of boundary between fixed vertices)."""

    vertices: np.ndarray
    polyline: np.ndarray
    closed: bool = False


@dataclass(frozen=True, eq=False)
class QuadMesh:
    """A welded quad mesh with the labels smoothing and the later stages need.

    Attributes
    ----------
    vertices : ndarray (n, 2)
    faces : Faces (a tuple of tuples)
        Quads ``(i, j, k, l)`` and, at poles, triangles ``(pole, j, k)``, counter-clockwise; they keep
        their corner arrays (:class:`vaultgram.geometry.meshes.Faces`), flattened once for every stage.
    face_patch : ndarray (f,) int
        Patch id of each face.
    boundary : ndarray (n,) bool
        Vertex on a ring of the domain.
    ring : ndarray (n,) int
        Ring of a boundary vertex (0 outer, ``1 + k`` hole ``k``), -1 inside.
    corner : ndarray (n,) int8
        1 at a convex corner of the domain, -1 at a reflex corner, 0 elsewhere.
    turning : ndarray (n,) float
        Turning angle of the domain (degrees, positive convex) at boundary vertices lying on a ring
        point of the discretisation; 0 elsewhere.
    fixed : ndarray (n,) bool
        Vertices smoothing does not move: domain corners and feature points.
    pole : ndarray (n,) bool
        Poles of three-sided patches.
    feature : ndarray (n,) bool
        Point features (§4.1), inner and on the boundary; curve extremities are in ``extremity``.
    node : ndarray (n,) int
        The decomposition-graph node a vertex stands for (patch corners), else -1.
    singular : ndarray (n,) bool
        Vertices at skeleton nodes of the decomposition (singularities and loop cuts).
    groups : tuple of dict
        The edge groups: ``{"id", "count", "sides", "mean_length", "max_length"}``.
    constraints : tuple of SlideConstraint
        Boundary and curve stretches between fixed vertices, along which their vertices slide.
    info : dict
        Free-form facts about the run (timings per stage, counts).
    curve : ndarray (n,) int
        The curve feature a vertex lies on (§4.2), else -1 (empty: no curve labels).
    extremity : ndarray (n,) bool
        Curve feature extremities off the boundary (§4.2; also ``feature`` and ``fixed``).
    curves : tuple of ndarray
        For each curve feature, its mesh vertices in order along it: a chain of mesh edges.
    curve_lines : tuple of ndarray (k, 2)
        For each curve feature, its polyline (the discretised input curve).
    origin : tuple of float
        Where the frame of the coordinates starts in the plan's (the domain's ``origin``,
        :mod:`vaultgram.geometry.frames`): the files add it back.
    """

    vertices: np.ndarray
    faces: Faces
    face_patch: np.ndarray
    boundary: np.ndarray
    ring: np.ndarray
    corner: np.ndarray
    turning: np.ndarray
    fixed: np.ndarray
    pole: np.ndarray
    feature: np.ndarray
    node: np.ndarray
    singular: np.ndarray
    groups: tuple = ()
    constraints: tuple = ()
    info: dict = field(default_factory=dict)
    curve: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    extremity: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    curves: tuple = ()
    curve_lines: tuple = ()
    origin: tuple = NO_ORIGIN

    def in_frame(self, origin=NO_ORIGIN) -> "QuadMesh":
        """The mesh in the frame starting at ``origin`` (by default the plan's own coordinates, as the
        files have them; itself when it is in that frame already)."""
        if self.origin == origin:
            return self
        o = between(self.origin, origin)
        return replace(self, vertices=to_plan(self.vertices, o), origin=origin,
                       constraints=tuple(replace(c, polyline=to_plan(c.polyline, o)) for c in self.constraints),
                       curve_lines=tuple(to_plan(c, o) for c in self.curve_lines))

    @property
    def n_vertices(self) -> int:
        return len(self.vertices)

    @property
    def n_faces(self) -> int:
        return len(self.faces)

    def curve_labels(self) -> tuple[np.ndarray, np.ndarray]:
        """``(curve, extremity)`` as full per-vertex arrays (-1 / False where the mesh has no labels)."""
        n = len(self.vertices)
        curve = np.asarray(self.curve, dtype=np.int64) if len(self.curve) == n else np.full(n, -1, dtype=np.int64)
        ext = np.asarray(self.extremity, dtype=bool) if len(self.extremity) == n else np.zeros(n, dtype=bool)
        return curve, ext

    def labels_json(self) -> dict:
        """Per-vertex labels as JSON lists of vertex indices."""
        return {
            "boundary": np.flatnonzero(self.boundary).tolist(),
            "corner": np.flatnonzero(self.corner > 0).tolist(),
            "reflex_corner": np.flatnonzero(self.corner < 0).tolist(),
            "fixed": np.flatnonzero(self.fixed).tolist(),
            "pole": np.flatnonzero(self.pole).tolist(),
            "feature": np.flatnonzero(self.feature).tolist(),
            "curve": np.flatnonzero(self.curve_labels()[0] >= 0).tolist(),
            "curve_extremity": np.flatnonzero(self.curve_labels()[1]).tolist(),
            "singular_node": np.flatnonzero(self.singular).tolist(),
        }


def slide(x: np.ndarray, constraints) -> np.ndarray:
    """Project the vertices of every constraint back onto its polyline, in place (§3.2: "other
    vertices lying on the boundaries are projected back on it after each iteration").

    >>> x = np.array([[0.5, 0.2], [1.0, 1.0]])
    >>> slide(x, [SlideConstraint(np.array([0]), np.array([[0.0, 0.0], [2.0, 0.0]]))])[0].tolist()
    [0.5, 0.0]
    """
    for c in constraints:
        x[c.vertices, :2] = project_to_polyline(x[c.vertices, :2], c.polyline, c.closed)
    return x
