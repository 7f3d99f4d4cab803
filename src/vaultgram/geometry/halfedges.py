"""The edges of a polygon mesh and the faces on either side of them, as arrays.

Faces are counter-clockwise vertex loops (seen from +z for a plan or a height field). Side ``k`` of
face ``f`` is the half-edge ``faces[f][k] -> faces[f][k + 1]``, with ``f`` on its left. Each
undirected edge ``(a, b)``, ``a < b``, has up to two faces: the one whose side runs ``a -> b`` and the
one whose side runs ``b -> a``; a boundary edge lacks one of them. :func:`mesh_edges` builds this once,
vectorised, for stages that walk meshes by edges and faces (the tessellation's strips, joints and
voussoir outlines).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np

from vaultgram.errors import MeshError
from vaultgram.geometry.meshes import corner_arrays

__all__ = ["MeshEdges", "SortedSides", "corner_edges", "edges_of_sides", "mesh_edges", "repeated_sides",
           "sorted_sides"]


@dataclass(frozen=True, eq=False)
class MeshEdges:
    """Edges of a polygon mesh with their faces.

    Attributes
    ----------
    edges : ndarray (m, 2)
        Undirected edges, ``edges[e, 0] < edges[e, 1]``, sorted.
    corner_face, corner_vertex, corner_next : ndarray (c,)
        Per face corner (in face order, then corner order): its face, its vertex and the next vertex.
    corner_edge : ndarray (c,)
        The edge of the side leaving each corner.
    faces_of : ndarray (m, 2)
        ``[face with the side low -> high, face with the side high -> low]``, -1 where there is none.
    corners_of : ndarray (m, 2)
        The corners whose sides those are (the side leaving the corner), -1 where there is none.
    face_start : ndarray (f + 1,)
        Corners of face ``f`` are ``face_start[f]:face_start[f + 1]``.
    """

    edges: np.ndarray
    corner_face: np.ndarray
    corner_vertex: np.ndarray
    corner_next: np.ndarray
    corner_edge: np.ndarray
    faces_of: np.ndarray
    corners_of: np.ndarray
    face_start: np.ndarray

    @property
    def n_edges(self) -> int:
        return len(self.edges)

    @cached_property
    def boundary(self) -> np.ndarray:
        """Edges with a face on one side only."""
        return (self.faces_of[:, 0] < 0) | (self.faces_of[:, 1] < 0)

    def face_edges(self, f: int) -> np.ndarray:
        """The edges of face ``f``, side by side."""
        return self.corner_edge[self.face_start[f]:self.face_start[f + 1]]

    def other_face(self, e: np.ndarray, f: np.ndarray) -> np.ndarray:
        """The face across edge ``e`` from face ``f`` (-1 on the boundary); vectorised."""
        a, b = self.faces_of[e, 0], self.faces_of[e, 1]
        return np.where(a == f, b, a)

    @cached_property
    def corner_side(self) -> np.ndarray:
        """Per corner, its index in its face (0 for the first corner of every face)."""
        return np.arange(len(self.corner_face)) - self.face_start[self.corner_face]

    @cached_property
    def corner_twin(self) -> np.ndarray:
        """Per corner, the corner whose side runs the other way along the same edge (-1 on the boundary)."""
        c = self.corners_of[self.corner_edge]
        return np.where(c[:, 0] == np.arange(len(c)), c[:, 1], c[:, 0])


def mesh_edges(faces, n_vertices: int | None = None) -> MeshEdges:
    """The edges of ``faces`` and the faces on either side of them.

    Raises :class:`~vaultgram.errors.MeshError` naming the edge and the faces if a half-edge
    is used by two faces (a non-manifold or inconsistently oriented mesh).

    Example
    -------
    >>> me = mesh_edges([(0, 1, 4, 3), (1, 2, 5, 4)])
    >>> me.edges.tolist()
    [[0, 1], [0, 3], [1, 2], [1, 4], [2, 5], [3, 4], [4, 5]]
    >>> me.faces_of[3].tolist(), int(me.boundary.sum())
    ([0, 1], 6)
    """
    face, u, v, _ = corner_arrays(faces)
    lens = np.bincount(face, minlength=len(faces)) if len(faces) else np.zeros(0, dtype=np.int64)
    return corner_edges(face, u, v, lens, n_vertices)


def corner_edges(face: np.ndarray, u: np.ndarray, v: np.ndarray, lens: np.ndarray, n_vertices: int | None = None
                 ) -> MeshEdges:
    """:func:`mesh_edges` of faces given by their corner arrays (corner ``k`` is the side ``u[k] -> v[k]``
    of face ``face[k]``) and their sizes ``lens``: for a step that holds its faces as arrays, not tuples.

    >>> from vaultgram.geometry.meshes import corners_of_flat
    >>> face, u, v, _ = corners_of_flat(np.array([0, 1, 4, 3, 1, 2, 5, 4]), np.array([4, 4]))
    >>> corner_edges(face, u, v, np.array([4, 4])).faces_of[3].tolist()
    [0, 1]
    """
    n = int(max(u.max(), v.max())) + 1 if len(u) else 0
    n = max(n, n_vertices or 0)
    sides = sorted_sides(u, v, n)
    repeated = repeated_sides(sides)
    if len(repeated):
        a, b = repeated[0]
        raise MeshError(f"edge {int(u[a])}-{int(v[a])} is traversed in the same direction by faces "
                        f"{int(face[a])} and {int(face[b])}")
    return edges_of_sides(face, u, v, lens, sides, n)


class SortedSides(NamedTuple):
    """The face sides (corners) sorted by edge, then direction: ``order`` the corners, ``key`` their
    sorted keys ``(lo * n + hi) * 2 + (u > v)``; the two sides of an edge are neighbours."""

    order: np.ndarray
    key: np.ndarray


def sorted_sides(u: np.ndarray, v: np.ndarray, n: int) -> SortedSides:
    """The sides ``u[k] -> v[k]`` sorted by edge then direction, by one stable argsort (timsort: a
    mesh whose faces come in an order near that of their vertices, as grids and meshed patches do,
    sorts several times faster than with quicksort; the order of equal keys is that of the corners).

    >>> s = sorted_sides(np.array([0, 1, 2, 1]), np.array([1, 2, 0, 0]), 3)
    >>> s.order.tolist(), s.key.tolist()
    ([0, 3, 2, 1], [2, 3, 5, 10])
    """
    key = np.minimum(u, v) * n + np.maximum(u, v)
    key *= 2
    key += u > v
    order = np.argsort(key, kind="stable")
    return SortedSides(order, key[order])


def repeated_sides(sides: SortedSides) -> np.ndarray:
    """Pairs of corners ``(a, b)``, ``a`` first, whose sides run the same way along the same edge
    (two faces traversing it in one direction: a non-manifold or inconsistently oriented mesh).

    >>> repeated_sides(sorted_sides(np.array([0, 1, 0]), np.array([1, 0, 1]), 2)).tolist()
    [[0, 2]]
    """
    at = np.flatnonzero(sides.key[1:] == sides.key[:-1])
    return np.stack([sides.order[at], sides.order[at + 1]], axis=1)


def edges_of_sides(face: np.ndarray, u: np.ndarray, v: np.ndarray, lens: np.ndarray, sides: SortedSides,
                   n: int) -> MeshEdges:
    """:class:`MeshEdges` of faces given by their corner arrays (``face``, ``u``, ``v``: corner ``k`` is
    the side ``u[k] -> v[k]`` of face ``face[k]``), their sizes ``lens`` and :func:`sorted_sides`,
    without repeated sides. A side repeated anyway keeps the later corner.

    >>> face, u, v = np.array([0, 0, 0, 1, 1, 1]), np.array([0, 1, 2, 2, 1, 3]), np.array([1, 2, 0, 1, 3, 2])
    >>> me = edges_of_sides(face, u, v, np.array([3, 3]), sorted_sides(u, v, 4), 4)
    >>> me.edges.tolist(), me.faces_of.tolist()
    ([[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]], [[0, -1], [-1, 0], [0, 1], [1, -1], [-1, 1]])
    """
    pair = sides.key >> 1
    first = np.concatenate([[True], pair[1:] != pair[:-1]]) if len(pair) else np.zeros(0, dtype=bool)
    edge = np.cumsum(first) - 1                       # the edge of each sorted side
    corner_edge = np.empty(len(face), dtype=np.int64)
    corner_edge[sides.order] = edge
    keys = pair[first]
    corners_of = np.full((len(keys), 2), -1, dtype=np.int64)
    corners_of[edge, sides.key & 1] = sides.order
    faces_of = np.where(corners_of >= 0, face[corners_of], -1)
    start = np.concatenate([[0], np.cumsum(lens)])
    edges = np.column_stack([keys // n, keys % n]) if n else np.zeros((0, 2), dtype=np.int64)
    return MeshEdges(edges.astype(np.int64), face, u, v, corner_edge, faces_of, corners_of, start)
