"""Voussoirs: faces of the thrust network merged across the removed edges, with their outlines.

A voussoir is a set of faces joined by removed edges (:mod:`vaultgram.tessellation.stagger`); its
outline is the loop of the edges it shares with no face of its own, counter-clockwise seen from
above. "We do not remove edges when this would result in strong voussoir concavities. Indeed,
L-shaped voussoirs would be more difficult to position correctly and the sharp corners would induce
stress concentrations" (§5): :func:`without_concavities` puts back the removed edges at every
corner above the threshold, measured in the voussoir's best-fit plane, until none is left.
The points where four voussoirs still meet are mended afterwards (:mod:`vaultgram.tessellation.mending`).
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from vaultgram.geometry.arrays import distinct
from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.geometry.surfaces import loop_corner_angles, loop_planes

__all__ = ["face_groups", "outlines", "max_corner_angles", "without_concavities",
           "voussoirs_at_vertices", "MAX_CONCAVITY"]

#: Default largest corner angle of a voussoir, in degrees (a straight joint through a corner is 180).
MAX_CONCAVITY = 190.0


def face_groups(me: MeshEdges, removed: np.ndarray) -> np.ndarray:
    """Voussoir of each face: faces joined by removed edges, numbered by their smallest face."""
    n = len(me.face_start) - 1
    pairs = me.faces_of[removed & (me.faces_of >= 0).all(axis=1)]
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    first = np.full(label.max() + 1 if n else 0, n, dtype=np.int64)
    np.minimum.at(first, label, np.arange(n))
    rank = np.empty_like(first)
    rank[np.argsort(first, kind="stable")] = np.arange(len(first))
    return rank[label]


def outlines(me: MeshEdges, group: np.ndarray) -> list[np.ndarray]:
    """The outline of every voussoir, a counter-clockwise loop of vertices starting at the start of
    its smallest boundary side.

    >>> from vaultgram.geometry.halfedges import mesh_edges
    >>> me = mesh_edges([(0, 1, 4, 3), (1, 2, 5, 4)])
    >>> [loop.tolist() for loop in outlines(me, np.array([0, 0]))]
    [[0, 1, 2, 5, 4, 3]]
    """
    twin = me.corner_twin
    g = group[me.corner_face]
    on_outline = np.flatnonzero((twin < 0) | (group[me.corner_face[np.maximum(twin, 0)]] != g))
    n = int(me.edges.max()) + 1 if len(me.edges) else 0
    key = g[on_outline] * n + me.corner_vertex[on_outline]
    order = np.argsort(key, kind="stable")
    sorted_key = key[order]
    successor = order[np.searchsorted(sorted_key, g[on_outline] * n + me.corner_next[on_outline])]
    owner = g[on_outline]
    rank, on_loop = _ranks_from_start(successor, owner)
    keep = np.lexsort((rank, owner))
    keep = keep[on_loop[keep]]
    vertices = me.corner_vertex[on_outline[keep]]
    count = np.bincount(owner[keep], minlength=int(group.max()) + 1 if len(group) else 0)
    return np.split(vertices, np.cumsum(count)[:-1])


def _ranks_from_start(successor: np.ndarray, owner: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For cycles given by ``successor``, each element's distance along its cycle from the cycle's
    start (the first element of each ``owner``), by pointer jumping; and whether it lies on that
    start's cycle (an owner with more cycles keeps only the first, as a disk has one outline)."""
    m = len(successor)
    pred = np.empty(m, dtype=np.int64)
    pred[successor] = np.arange(m)
    start = np.full(int(owner.max()) + 1 if m else 0, m, dtype=np.int64)
    np.minimum.at(start, owner, np.arange(m))
    pred[start[owner] == np.arange(m)] = -1  # each owner's cycle starts at its first element
    rank = (pred >= 0).astype(np.int64)
    for _ in range(max(1, int(np.ceil(np.log2(max(m, 2))))) + 1):
        live = pred >= 0
        if not live.any():
            break
        rank[live] += rank[pred[live]]
        pred[live] = pred[pred[live]]
    return rank, pred < 0


def max_corner_angles(x: np.ndarray, loops: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Per loop, its largest corner angle in its best-fit plane (degrees) and the vertex there."""
    if not loops:
        return np.zeros(0), np.zeros(0, dtype=np.int64)
    _, normals = loop_planes(x, loops)
    angles = loop_corner_angles(x, loops, normals)
    lens = np.fromiter(map(len, loops), dtype=np.int64, count=len(loops))
    start = np.concatenate([[0], np.cumsum(lens)[:-1]])
    largest = np.maximum.reduceat(angles, start)
    owner = np.repeat(np.arange(len(loops)), lens)
    at = np.flatnonzero(angles == largest[owner])  # the first corner of each loop at its largest angle
    first = at[np.searchsorted(owner[at], np.arange(len(loops)))]
    return largest, np.concatenate(loops)[first]


def without_concavities(x: np.ndarray, me: MeshEdges, removed: np.ndarray, max_angle: float = MAX_CONCAVITY,
                        faces: np.ndarray | None = None) -> tuple[np.ndarray, int]:
    """Put back removed edges at voussoir corners above ``max_angle`` until there are none (among the
    voussoirs of ``faces`` if given); returns the removed edges left and how many were put back. A
    voussoir whose corner is a corner of one of its faces (no removed edge there) is taken apart
    into its faces."""
    removed = removed.copy()
    restored = 0
    while True:
        group = face_groups(me, removed)
        sizes = np.bincount(group)
        loops = outlines(me, group)
        multi = np.flatnonzero(sizes > 1)
        multi = multi if faces is None else np.intersect1d(multi, group[faces])
        angle, vertex = max_corner_angles(x, [loops[k] for k in multi])
        bad = angle > max_angle
        if not bad.any():
            return removed, restored
        bad_group = np.zeros(len(sizes), dtype=bool)
        bad_group[multi[bad]] = True
        bad_vertex = np.zeros(len(x), dtype=bool)
        bad_vertex[vertex[bad]] = True
        owner = group[np.maximum(me.faces_of[:, 0], 0)]
        inside = removed & bad_group[owner]
        back = inside & (bad_vertex[me.edges[:, 0]] | bad_vertex[me.edges[:, 1]])
        stuck = np.setdiff1d(multi[bad], owner[back])  # nothing to put back at the corner itself
        back |= inside & np.isin(owner, stuck)
        restored += int(back.sum())
        removed &= ~back


def voussoirs_at_vertices(me: MeshEdges, group: np.ndarray, n_vertices: int) -> np.ndarray:
    """Per vertex, how many distinct voussoirs meet there."""
    pairs = distinct(group[me.corner_face] * n_vertices + me.corner_vertex)
    return np.bincount(pairs % n_vertices, minlength=n_vertices)
