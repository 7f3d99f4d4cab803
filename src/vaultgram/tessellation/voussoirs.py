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

from vaultgram.geometry.arrays import TIE, distinct, lookup, ranges
from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.geometry.meshes import Faces, corner_arrays
from vaultgram.geometry.surfaces import loop_corner_angles, loop_planes

__all__ = ["face_groups", "outlines", "set_outlines", "member_corners", "max_corner_angles", "without_concavities",
           "voussoirs_at_vertices", "MAX_CONCAVITY"]

#: Default largest corner angle of a voussoir, in degrees (a straight joint through a corner is 180).
MAX_CONCAVITY = 190.0


def face_groups(me: MeshEdges, removed: np.ndarray) -> np.ndarray:
    """Voussoir of each face: faces joined by removed edges, numbered by their smallest face."""
    n = len(me.face_start) - 1
    pairs = me.faces_of[removed & ~me.boundary]
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    first = np.full(label.max() + 1 if n else 0, n, dtype=np.int64)
    np.minimum.at(first, label, np.arange(n))
    rank = np.empty_like(first)
    rank[np.argsort(first, kind="stable")] = np.arange(len(first))
    return rank[label]


def outlines(me: MeshEdges, group: np.ndarray, which: np.ndarray | None = None) -> Faces:
    """The outline of every voussoir (of those in ``which``, sorted, if given), a counter-clockwise
    loop of vertices starting at the start of its smallest boundary side; as
    :class:`~vaultgram.geometry.meshes.Faces` of vertex arrays, their corner arrays made already.

    >>> from vaultgram.geometry.halfedges import mesh_edges
    >>> me = mesh_edges([(0, 1, 4, 3), (1, 2, 5, 4)])
    >>> [loop.tolist() for loop in outlines(me, np.array([0, 0]))]
    [[0, 1, 2, 5, 4, 3]]
    >>> [loop.tolist() for loop in outlines(me, np.array([0, 1]), which=np.array([1]))]
    [[1, 2, 5, 4]]
    """
    n_groups = int(group.max()) + 1 if len(group) else 0
    which = np.arange(n_groups) if which is None else np.asarray(which, dtype=np.int64)
    chosen = np.zeros(n_groups, dtype=bool)
    chosen[which] = True
    face = np.flatnonzero(chosen[group])  # by face, so by (voussoir, face) after a stable sort
    owner = np.searchsorted(which, group[face])
    order = np.argsort(owner, kind="stable")
    loops, _ = set_outlines(me, owner[order], face[order], len(which))
    return loops


def set_outlines(me: MeshEdges, owner: np.ndarray, face: np.ndarray, n_sets: int) -> tuple[Faces, np.ndarray]:
    """The outlines of sets of faces that may overlap: set ``owner[i]`` holds face ``face[i]``, the
    members sorted by set, then by face. Per set, its counter-clockwise outline starting at the start
    of its smallest boundary side (the first loop only, if it has more), and whether that outline is
    the set's one loop and touches itself at no vertex (a disk, if the faces are joined). The outlines
    are :class:`~vaultgram.geometry.meshes.Faces` (as :func:`outlines`).

    >>> from vaultgram.geometry.halfedges import mesh_edges
    >>> me = mesh_edges([(0, 1, 4, 3), (1, 2, 5, 4), (3, 4, 7, 6)])
    >>> loops, one = set_outlines(me, np.array([0, 0, 1, 1]), np.array([0, 1, 1, 2]), 2)
    >>> loops[0].tolist(), one.tolist()  # faces 1 and 2 touch at vertex 4 only
    ([0, 1, 2, 5, 4, 3], [True, False])
    """
    member, corner, across = member_corners(me, owner, face)
    on_outline = np.flatnonzero(across < 0)
    g = owner[member[on_outline]]
    n = int(me.edges.max()) + 1 if len(me.edges) else 0
    key = g * n + me.corner_vertex[corner[on_outline]]
    order = np.argsort(key, kind="stable")
    sorted_key = key[order]
    successor = order[np.searchsorted(sorted_key, g * n + me.corner_next[corner[on_outline]])]
    rank, on_loop = _ranks_from_start(successor, g)
    single = np.bincount(g[~on_loop], minlength=n_sets) == 0
    pinched = g[order[1:][sorted_key[1:] == sorted_key[:-1]]]
    single[pinched] = False
    keep = _loop_order(g, rank, on_loop, n_sets)
    flat = me.corner_vertex[corner[on_outline[keep]]]
    lens = np.bincount(g[keep], minlength=n_sets)
    ends = np.cumsum(lens).tolist()
    loops = [flat[a:b] for a, b in zip([0] + ends[:-1], ends)]  # np.split is ~20x slower here
    return Faces.from_flat(flat, lens, loops), single  # their corners made from flat, not joined again


def member_corners(me: MeshEdges, owner: np.ndarray, face: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The corners of the members of face sets (set ``owner[i]`` holds face ``face[i]``, sorted by set,
    then by face): per corner, its member, its index in ``me``, and the member of the same set across
    the corner's side (-1 if the face there is not in the set, or there is none).

    >>> from vaultgram.geometry.halfedges import mesh_edges
    >>> me = mesh_edges([(0, 1, 4, 3), (1, 2, 5, 4)])
    >>> [a.tolist() for a in member_corners(me, np.array([0, 0]), np.array([0, 1]))]
    [[0, 0, 0, 0, 1, 1, 1, 1], [0, 1, 2, 3, 4, 5, 6, 7], [-1, 1, -1, -1, -1, -1, -1, 0]]
    """
    member, corner = ranges(me.face_start[face], me.face_start[face + 1] - me.face_start[face])
    if not len(face):
        return member, corner, member.copy()
    twin = me.corner_twin[corner]
    n_faces = len(me.face_start) - 1
    beyond = me.corner_face[np.maximum(twin, 0)]
    if np.bincount(face, minlength=n_faces).max() == 1:  # each face in one set (the voussoirs): a map finds it
        at = np.full(n_faces, -1, dtype=np.int64)
        at[face] = np.arange(len(face))
        pos = at[beyond]
        found = (pos >= 0) & (owner[np.maximum(pos, 0)] == owner[member])
    else:
        pos, found = lookup(owner * n_faces + face, owner[member] * n_faces + beyond)  # keys sorted, as the members
    return member, corner, np.where((twin >= 0) & found, pos, -1)


def _loop_order(owner: np.ndarray, rank: np.ndarray, on_loop: np.ndarray, n_sets: int) -> np.ndarray:
    """The elements on their owner's loop (``on_loop``), by owner, then by ``rank`` along the loop.
    Where the ranks on each loop are 0 to its length - 1 (``owner`` sorted), an element's place is its
    loop's start in the output plus its rank: a scatter, where the lexsort takes some six times as long
    on the 3M outline corners of a 10^6-face tessellation. An outline touching itself may break that (a
    corner there has no predecessor): then the lexsort sorts them all, as before."""
    at = np.flatnonzero(on_loop)
    length = np.bincount(owner[at], minlength=n_sets)
    place = (np.cumsum(length) - length)[owner[at]] + rank[at]
    if not ((rank[at] < length[owner[at]]).all() and (np.bincount(place, minlength=len(at)) == 1).all()):
        keep = np.lexsort((rank, owner))
        return keep[on_loop[keep]]
    keep = np.empty(len(at), dtype=np.int64)
    keep[place] = at
    return keep


def _ranks_from_start(successor: np.ndarray, owner: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For cycles given by ``successor``, each element's distance along its cycle from the cycle's
    start (the first element of each ``owner``), by pointer jumping; and whether it lies on that
    start's cycle (an owner with more cycles keeps only the first, as a disk has one outline)."""
    m = len(successor)
    pred = np.arange(m, dtype=np.int64)  # one that no element precedes (an outline touching itself) is its
    pred[successor] = np.arange(m)  # own: it never reaches a start, so it is off the start's cycle
    start = np.full(int(owner.max()) + 1 if m else 0, m, dtype=np.int64)
    np.minimum.at(start, owner, np.arange(m))
    pred[start[owner] == np.arange(m)] = -1  # each owner's cycle starts at its first element
    rank = (pred >= 0).astype(np.int64)
    live = np.flatnonzero(pred >= 0)  # the elements not yet joined to a start: few after some steps
    for _ in range(max(1, int(np.ceil(np.log2(max(m, 2))))) + 1):
        if not len(live):
            break
        up = pred[live]
        rank[live] += rank[up]
        pred[live] = pred[up]
        live = live[pred[live] >= 0]
    return rank, pred < 0


def max_corner_angles(x: np.ndarray, loops: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Per loop, its largest corner angle in its best-fit plane (degrees) and the vertex there."""
    if not loops:
        return np.zeros(0), np.zeros(0, dtype=np.int64)
    loops = loops if isinstance(loops, Faces) else Faces(loops)  # flattened once for planes and angles
    _, normals = loop_planes(x, loops)
    angles = loop_corner_angles(x, loops, normals)
    owner, vertex, _, _ = corner_arrays(loops)
    start = np.concatenate([[0], np.cumsum(np.bincount(owner, minlength=len(loops)))[:-1]])
    largest = np.maximum.reduceat(angles, start)
    at = np.flatnonzero(angles >= largest[owner] - TIE * 180.0)  # each loop's first corner at its largest angle
    first = at[np.searchsorted(owner[at], np.arange(len(loops)))]
    return largest, vertex[first]


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
        multi = np.flatnonzero(sizes > 1)
        if faces is not None:  # a mask, not np.intersect1d (0.4 s of hashing for 10^5 faces of a 10^6 mesh)
            asked = np.zeros(len(sizes), dtype=bool)
            asked[group[faces]] = True
            multi = multi[asked[multi]]
        angle, vertex = max_corner_angles(x, outlines(me, group, multi))
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
        faces = np.flatnonzero(bad_group[group])  # the others are as they were: without a strong corner


def voussoirs_at_vertices(me: MeshEdges, group: np.ndarray, n_vertices: int) -> np.ndarray:
    """Per vertex, how many distinct voussoirs meet there."""
    pairs = distinct(group[me.corner_face] * n_vertices + me.corner_vertex)
    return np.bincount(pairs % n_vertices, minlength=n_vertices)
