"""The thrust surface: the form-found network the voussoirs are cut from (paper §5, Figures 12a, 13a).

A :class:`ThrustSurface` is the thrust network's vertices in space, its loaded faces
(counter-clockwise in plan) and which vertices bear thrust. It comes from a
:class:`~vaultgram.formfinding.thrust.ThrustNetwork` or from a ``thrust.json`` file, and is checked on
the way in: every vertex has a finite height, every face is a loop of distinct valid vertices, and
the faces form a manifold, consistently oriented mesh. Problems are a
:class:`~vaultgram.errors.TessellationError` naming the element and its index.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vaultgram.errors import MeshError, TessellationError
from vaultgram.geometry.arrays import sorted_keys
from vaultgram.geometry.frames import NO_ORIGIN, local_origin, to_local
from vaultgram.geometry.halfedges import MeshEdges, mesh_edges
from vaultgram.geometry.meshes import Faces, boundary_loops, corner_arrays

__all__ = ["ThrustSurface", "surface_from_network", "surface_from_json"]


@dataclass(frozen=True, eq=False)
class ThrustSurface:
    """A thrust network as a surface.

    Attributes
    ----------
    vertices : ndarray (n, 3)
    faces : tuple of tuple
        Loaded faces, counter-clockwise in plan.
    supported : ndarray (n,) bool
        Vertices bearing thrust (the supports).
    edges : MeshEdges
        The faces' edges and the faces beside them.
    origin : tuple of float
        Where the frame of the coordinates starts in the plan's (:mod:`vaultgram.geometry.frames`).
    """

    vertices: np.ndarray
    faces: tuple
    supported: np.ndarray
    edges: MeshEdges
    origin: tuple = NO_ORIGIN

    @property
    def holes(self) -> int:
        """Openings: boundary loops beyond the outer one."""
        return max(len(boundary_loops(self.faces)) - 1, 0)


def _checked_vertices(vertices, where: str) -> np.ndarray:
    try:
        x = np.asarray(vertices, dtype=float)
    except (TypeError, ValueError):
        raise TessellationError(f"{where}: vertices must be [x, y, z] points") from None
    if x.ndim != 2 or x.shape[1] != 3:
        raise TessellationError(f"{where}: vertices have no heights: each must be [x, y, z] (a thrust network, "
                                "not a plan mesh; run vaultgram formfind first)")
    bad = np.flatnonzero(~np.isfinite(x).all(axis=1))
    if len(bad):
        raise TessellationError(f"{where}: vertex {int(bad[0])} has a coordinate that is not finite")
    return x


def _checked_faces(faces, n: int, where: str) -> tuple:
    """The faces as tuples of vertex indices, checked one by one (the first bad face named); faces
    that come as :class:`~vaultgram.geometry.meshes.Faces` (a thrust network's) are checked at once
    first (:func:`_valid_faces`), and only looked at one by one if one fails."""
    if isinstance(faces, Faces):
        valid = _valid_faces(faces, n)
        if valid is not None:
            return valid
    out = []
    for k, f in enumerate(faces):
        try:
            f = tuple(int(v) for v in f)
        except (TypeError, ValueError):
            raise TessellationError(f"{where}: face {k} is not a list of vertex indices") from None
        if len(f) < 3:
            raise TessellationError(f"{where}: face {k} has {len(f)} vertices (at least 3)")
        bad = [v for v in f if not 0 <= v < n]
        if bad:
            raise TessellationError(f"{where}: face {k} names vertex {bad[0]}, but there are {n} vertices")
        if len(set(f)) != len(f):
            raise TessellationError(f"{where}: face {k} repeats a vertex")
        out.append(f)
    if not out:
        raise TessellationError(f"{where}: the network has no faces")
    return Faces(out)


def _valid_faces(faces: Faces, n: int) -> Faces | None:
    """``faces`` made again from their corner arrays (tuples of Python ints, as :func:`_checked_faces`
    makes them: at 10^6 faces a fraction of a second instead of some four seconds face by face) if
    there are some and every one has at least three distinct vertices in ``0 .. n - 1``; else None.

    >>> _valid_faces(Faces([(0, 1, 2), (2, 1, 3)]), 4), _valid_faces(Faces([(0, 1, 1)]), 4)
    (((0, 1, 2), (2, 1, 3)), None)
    """
    face, vertex, _, _ = corner_arrays(faces)
    lens = np.bincount(face, minlength=len(faces))
    if not len(faces) or lens.min() < 3 or vertex.min() < 0 or vertex.max() >= n:
        return None
    keys = sorted_keys(face * n + vertex)  # a vertex twice in a face: a key twice
    return Faces.from_flat(vertex, lens) if np.all(keys[1:] != keys[:-1]) else None


def _checked_edges(faces: tuple, n: int, where: str) -> MeshEdges:
    try:
        me = mesh_edges(faces, n)
    except MeshError as exc:
        raise TessellationError(f"{where}: not a consistently oriented manifold mesh: {exc}") from None
    try:
        boundary_loops(faces)
    except MeshError as exc:
        raise TessellationError(f"{where}: not a manifold mesh: {exc}") from None
    return me


def _surface(vertices, faces, supported_ids, where: str, origin=None) -> ThrustSurface:
    """The checked surface; vertices in site coordinates (``origin`` None) are moved to their local frame."""
    x = _checked_vertices(vertices, where)
    if origin is None:
        origin = local_origin(x)
        x = to_local(x, origin)
    faces = _checked_faces(faces, len(x), where)
    me = _checked_edges(faces, len(x), where)
    supported = np.zeros(len(x), dtype=bool)
    ids = np.asarray(supported_ids, dtype=np.int64).ravel()
    if len(ids) and (ids.min() < 0 or ids.max() >= len(x)):
        raise TessellationError(f"{where}: a support names a vertex outside 0..{len(x) - 1}")
    supported[ids] = True
    return ThrustSurface(x, faces, supported, me, origin)


def surface_from_network(network) -> ThrustSurface:
    """The surface of a :class:`~vaultgram.formfinding.thrust.ThrustNetwork`."""
    return _surface(network.vertices, network.faces, np.flatnonzero(network.anchors), "thrust network",
                    network.origin)


def surface_from_json(data, where: str = "thrust") -> ThrustSurface:
    """The surface of a ``thrust.json`` document (``vertices`` with heights, ``faces``, ``anchors``), in
    its local frame when it lies far from the origin."""
    if not isinstance(data, dict) or "vertices" not in data or "faces" not in data:
        raise TessellationError(f"{where}: not a thrust network (needs 'vertices' and 'faces')")
    return _surface(data["vertices"], data["faces"], data.get("anchors", []), where)
