"""Mending the points where four or more voussoirs meet (paper §5).

"Having many voussoirs coming to the same point makes the assembly task more difficult" (§5): in a
staggered bond every inner meeting point joins three voussoirs. The bond still leaves points of four
where its courses meet at a seam (two strips running different ways), where an edge had to be kept
against a concavity, or where a large voussoir was given an edge back. Such a point is mended by
moving one face across one of its joints: the joint is removed, so the face joins the voussoir on the
other side, and the removed edges tying the face to the rest of its own voussoir are put back.

A move is made when it lowers the *crowding* at the face's corners (the sum, over inner vertices,
of the voussoirs meeting there minus three), or when it evens out a small voussoir and the crowding
does not grow ("shape and size uniformity between the voussoirs is preferred", §5: a small voussoir
of one face joins its neighbour, a small one of several faces takes a face from a larger neighbour,
bringing the two sizes closer), and when it keeps both voussoirs within the size limit and
without a corner above the concavity threshold, leaves each voussoir a disk in one piece around no
vertex of its own, and touches no keystone. Moves that share no voussoir and no vertex are made
together, in rounds, best first.

Last, neighbouring voussoirs that are both small are joined in pairs (:func:`join_small_pairs`), so
that short courses (between seams, keystones and the boundary) still give voussoirs of about the
target size; a join only ever lowers the number of voussoirs at a vertex.

Example: four single quads around a vertex; moving one of them into its neighbour leaves three
(and the small single faces left may join a neighbour too).

>>> from vaultgram.geometry.halfedges import mesh_edges
>>> from vaultgram.geometry.meshes import grid_mesh
>>> from vaultgram.tessellation.voussoirs import voussoirs_at_vertices
>>> v, f = grid_mesh(2)
>>> me = mesh_edges(f, len(v))
>>> inner = np.zeros(len(v), dtype=bool); inner[4] = True
>>> removed, moves = mend_meeting_points(v, me, np.zeros(len(me.edges), dtype=bool), inner,
...                                      np.ones(4), target=1.0)
>>> moves, int(voussoirs_at_vertices(me, face_groups(me, removed), len(v))[4])
(1, 3)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from vaultgram.geometry.arrays import distinct, run_starts, sorted_keys
from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.tessellation.sizes import UPPER
from vaultgram.tessellation.voussoirs import (
    MAX_CONCAVITY,
    face_groups,
    max_corner_angles,
    member_corners,
    set_outlines,
)

__all__ = ["mend_meeting_points", "join_small_pairs", "ROUNDS"]

#: At most this many rounds of moves.
ROUNDS = 6
#: A move may grow a voussoir to at most this many times the target area (the bond's, about
#: ``rhythm`` faces): a little larger voussoirs are a better price than points of four.
GROWTH = 3.0
#: A voussoir smaller than this many times the target evens out with a neighbour even where that
#: mends no meeting point (it makes none worse): one of a single face joins the neighbour, one of
#: several faces takes a face from a larger neighbour (small faces near features make small voussoirs).
SMALL = 0.9


#: Two neighbouring voussoirs each smaller than this many times the target become one (where the
#: union is at most :data:`~vaultgram.tessellation.sizes.UPPER` times the target, a disk, and
#: without a corner above the concavity threshold): two courses' short voussoirs stacked.
PAIRED = 1.0


@dataclass(frozen=True)
class _Moves:
    """Candidate moves, best first: move ``i`` takes ``face[i]`` across ``joint[i]`` from voussoir
    ``source[i]`` into voussoir ``target[i]``, lowering the crowding by ``gain[i]``."""

    gain: np.ndarray
    joint: np.ndarray
    face: np.ndarray
    source: np.ndarray
    target: np.ndarray

    def __len__(self) -> int:
        return len(self.face)


@dataclass(frozen=True)
class _State:
    """The voussoirs as they stand in a round: each face's voussoir, the faces in voussoir order
    (``order[start[k]:start[k + 1]]`` are voussoir ``k``'s), the voussoirs meeting at each vertex,
    and the sorted keys ``vertex * n_groups + voussoir`` of every face corner (to count a voussoir's
    faces at a vertex)."""

    group: np.ndarray
    order: np.ndarray
    start: np.ndarray
    count: np.ndarray
    keys: np.ndarray

    @property
    def n_groups(self) -> int:
        return len(self.start) - 1

    def members(self, k: int) -> list:
        """The faces of voussoir ``k``."""
        return self.order[self.start[k]:self.start[k + 1]].tolist()

    def faces_at(self, v: np.ndarray, k: np.ndarray) -> np.ndarray:
        """How many faces of voussoir ``k[i]`` have a corner at vertex ``v[i]``."""
        key = v * self.n_groups + k
        return np.searchsorted(self.keys, key, side="right") - np.searchsorted(self.keys, key, side="left")


def mend_meeting_points(x: np.ndarray, me: MeshEdges, removed: np.ndarray, interior: np.ndarray,
                        area: np.ndarray, target: float, max_angle: float = MAX_CONCAVITY,
                        frozen_faces: np.ndarray | None = None) -> tuple[np.ndarray, int]:
    """Move faces across joints until no point of four or more voussoirs can be mended, and join the
    small single faces to a neighbour (see the module docstring); ``interior`` marks the inner
    vertices, ``area`` the faces' areas, ``target`` the voussoir area aimed at, ``frozen_faces`` the
    faces that never move or take a face (the keystones). Returns the removed edges and the number
    of moves."""
    removed = removed.copy()
    frozen_faces = np.zeros(len(area), dtype=bool) if frozen_faces is None else frozen_faces
    total = 0
    for _ in range(ROUNDS):
        state = _state(me, removed, len(x))
        moves = _candidates(me, removed, interior, area, target, frozen_faces, state)
        made = _apply(x, me, removed, state, moves, max_angle)
        total += made
        if not made:
            break
    return removed, total


def _state(me: MeshEdges, removed: np.ndarray, n: int) -> _State:
    group = face_groups(me, removed)
    order = np.argsort(group, kind="stable")
    n_groups = int(group.max()) + 1 if len(group) else 0
    start = np.searchsorted(group[order], np.arange(n_groups + 1))
    keys = sorted_keys(me.corner_vertex * n_groups + group[me.corner_face])
    count = np.bincount(keys[run_starts(keys)] // max(n_groups, 1), minlength=n)  # the voussoirs at each vertex
    return _State(group, order, start, count, keys)


def _candidates(me: MeshEdges, removed: np.ndarray, interior: np.ndarray, area: np.ndarray, target: float,
                frozen_faces: np.ndarray, state: _State) -> list:
    """Every move of a face across a joint at a crowded inner vertex that lowers the crowding, and
    every move that evens out a small voussoir without raising it (module docstring), keeping the
    receiving voussoir within :data:`GROWTH` times ``target``."""
    group = state.group
    frozen = np.zeros(state.n_groups, dtype=bool)
    frozen[group[frozen_faces]] = True
    size = np.bincount(group, weights=area, minlength=state.n_groups)
    largest = GROWTH * target
    tiny = size < SMALL * target
    crowded = interior & (state.count >= 4)
    joint = ~removed & ~me.boundary
    faces_in = np.bincount(group, minlength=state.n_groups)
    e = np.flatnonzero(joint)
    at_crowded = np.repeat(crowded[me.edges[e, 0]] | crowded[me.edges[e, 1]], 2)
    e, face, other = np.repeat(e, 2), me.faces_of[e].ravel(), me.faces_of[e, ::-1].ravel()  # both ways
    source, into = group[face], group[other]
    # only moves at a crowded vertex or beside a small voussoir can fit (below): the others go first
    near = np.flatnonzero(at_crowded | tiny[source] | tiny[into])
    e, face, source, into, at_crowded = e[near], face[near], source[near], into[near], at_crowded[near]
    left = size[source] - area[face]
    evens = tiny[into] & (area[face] < size[source] - size[into]) & ((faces_in[source] > 2) | (left <= UPPER * target))
    even_out = (tiny[source] & (faces_in[source] == 1)) | evens  # moves worth making that mend nothing
    fits = ~frozen[source] & ~frozen[into] & (size[into] + area[face] <= largest) & (at_crowded | even_out)
    row = np.flatnonzero(fits)
    gain, ok = _gains(me, state, interior, face[row], into[row])
    row, gain = row[ok], gain[ok]
    keep = (gain > 0) | ((gain == 0) & even_out[row])
    row, gain = row[keep], gain[keep]
    grown = size[into[row]] + area[face[row]]
    best = np.lexsort((face[row], e[row], grown, -gain))  # most gain, then smallest voussoir made
    row = row[best]
    return _Moves(gain[best], e[row], face[row], source[row], into[row])


def _gains(me: MeshEdges, state: _State, interior: np.ndarray, face: np.ndarray, target: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray]:
    """For each move of ``face[i]`` into voussoir ``target[i]``: how much the crowding at the face's
    corners drops, and whether the move is allowed (no inner corner left inside one voussoir). At a
    corner the face's own voussoir leaves if the face was its only face there, and the target
    arrives if it had none."""
    lens = me.face_start[face + 1] - me.face_start[face]
    row = np.repeat(np.arange(len(face)), lens)
    first = np.repeat(np.cumsum(lens) - lens, lens)
    v = me.corner_vertex[np.repeat(me.face_start[face], lens) + np.arange(int(lens.sum())) - first]
    source, into = state.group[face][row], target[row]
    before = state.count[v]
    after = before - (state.faces_at(v, source) == 1) + (state.faces_at(v, into) == 0)
    inner = interior[v]
    drop = (np.maximum(before - 3, 0) - np.maximum(after - 3, 0)) * inner
    enclosed = np.bincount(row, weights=(after == 1) & inner, minlength=len(face)) > 0
    return np.bincount(row, weights=drop, minlength=len(face)).astype(np.int64), ~enclosed


def _feasible(x: np.ndarray, me: MeshEdges, removed: np.ndarray, state: _State, moves: _Moves,
              max_angle: float) -> np.ndarray:
    """Per move, whether both its voussoirs stay disks in one piece without a corner above
    ``max_angle``: set ``i`` is the target of move ``i`` grown by its face, set ``len(moves) + i``
    the source without it (the face's own voussoir, if that was all of it)."""
    m = len(moves)
    t_owner, t_face = _members(state, moves.target)
    s_owner, s_face = _members(state, moves.source)
    rest = s_face != moves.face[s_owner]
    owner = np.concatenate([t_owner, np.arange(m), s_owner[rest] + m])
    face = np.concatenate([t_face, moves.face, s_face[rest]])
    order = np.lexsort((face, owner))
    owner, face = owner[order], face[order]
    loops, single = set_outlines(me, owner, face, 2 * m)
    empty = np.bincount(owner, minlength=2 * m) == 0
    joined = np.ones(2 * m, dtype=bool)  # the move itself joins the face to its target
    shrunk = owner >= m
    joined[m:] = _joined(me, removed, owner[shrunk] - m, face[shrunk], m)
    ok = (single & joined) | empty
    check = np.flatnonzero(ok & ~empty)
    angle = np.zeros(2 * m)
    angle[check] = max_corner_angles(x, [loops[k] for k in check.tolist()])[0]
    ok &= angle <= max_angle
    return ok[:m] & ok[m:]


def _members(state: _State, groups: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The faces of voussoir ``groups[i]`` for every ``i``: ``(i, face)`` pairs, by ``i`` then by face."""
    count = state.start[groups + 1] - state.start[groups]
    owner = np.repeat(np.arange(len(groups)), count)
    at = np.repeat(state.start[groups] - np.cumsum(count) + count, count) + np.arange(int(count.sum()))
    return owner, state.order[at]


def _joined(me: MeshEdges, removed: np.ndarray, owner: np.ndarray, face: np.ndarray, n_sets: int) -> np.ndarray:
    """Per face set (as in :func:`~vaultgram.tessellation.voussoirs.set_outlines`), whether its faces
    are joined into one piece by the removed edges among them."""
    member, corner, across = member_corners(me, owner, face)
    link = (across >= 0) & removed[me.corner_edge[corner]]
    graph = coo_matrix((np.ones(int(link.sum())), (member[link], across[link])), shape=(len(face), len(face)))
    n_labels, label = connected_components(graph, directed=False)
    pieces = np.bincount(distinct(owner * n_labels + label) // max(n_labels, 1), minlength=n_sets)
    return pieces <= 1


def _apply(x: np.ndarray, me: MeshEdges, removed: np.ndarray, state: _State, moves: _Moves, max_angle: float) -> int:
    """Make the feasible moves in order (best first), each unless an earlier move made shares a
    voussoir or a vertex with it; returns how many. (A move's feasibility depends on its two
    voussoirs only, so it is checked once, for all moves, before any is made.)"""
    good = _feasible(x, me, removed, state, moves, max_angle)
    used_groups = np.zeros(state.n_groups, dtype=bool)
    used_vertices = np.zeros(len(x), dtype=bool)
    made = 0
    for i in np.flatnonzero(good).tolist():
        src, dst, f = int(moves.source[i]), int(moves.target[i]), int(moves.face[i])
        corners = me.corner_vertex[me.face_start[f]:me.face_start[f + 1]]
        if used_groups[src] or used_groups[dst] or used_vertices[corners].any():
            continue
        used_groups[[src, dst]] = True
        used_vertices[corners] = True
        _move(me, removed, state.group, f, dst)
        made += 1
    return made


def _move(me: MeshEdges, removed: np.ndarray, group: np.ndarray, face: int, target: int) -> None:
    """Move ``face`` into voussoir ``target``: its joints with the target are removed, the removed
    edges tying it to its own voussoir put back. (No move made in the round touches its sides.)"""
    sides = me.face_edges(face)
    across = me.other_face(sides, face)
    joins = sides[~removed[sides] & (across >= 0) & (group[np.maximum(across, 0)] == target)]
    removed[sides[removed[sides]]] = False
    removed[joins] = True


def join_small_pairs(x: np.ndarray, me: MeshEdges, removed: np.ndarray, area: np.ndarray, target: float,
                     max_angle: float = MAX_CONCAVITY, frozen_faces: np.ndarray | None = None
                     ) -> tuple[np.ndarray, int]:
    """Join neighbouring voussoirs smaller than :data:`PAIRED` times ``target`` in pairs, smallest
    unions first ("shape and size uniformity between the voussoirs is preferred", §5). A join
    takes a voussoir away from the vertices of the joints removed, so no meeting point gets more
    crowded. Returns the removed edges and the number of pairs joined."""
    removed = removed.copy()
    frozen_faces = np.zeros(len(area), dtype=bool) if frozen_faces is None else frozen_faces
    total = 0
    for _ in range(ROUNDS):
        state = _state(me, removed, len(x))
        pairs, joints = _small_pairs(me, removed, area, target, frozen_faces, state)
        made = _join(removed, _convex_unions(x, me, state, pairs, max_angle), joints)
        total += made
        if not made:
            break
    return removed, total


def _small_pairs(me: MeshEdges, removed: np.ndarray, area: np.ndarray, target: float, frozen_faces: np.ndarray,
                 state: _State) -> tuple[list, dict]:
    """The pairs of neighbouring small voussoirs whose union is within the size limit, smallest union
    first, and the joints between each pair."""
    group = state.group
    size = np.bincount(group, weights=area, minlength=state.n_groups)
    frozen = np.zeros(state.n_groups, dtype=bool)
    frozen[group[frozen_faces]] = True
    e = np.flatnonzero(~removed & ~me.boundary)
    a, b = np.sort(group[me.faces_of[e]], axis=1).T
    ok = (size[a] < PAIRED * target) & (size[b] < PAIRED * target) & ~frozen[a] & ~frozen[b]
    ok &= (size[a] + size[b] <= UPPER * target) & (a != b)
    e, a, b = e[ok], a[ok], b[ok]
    order = np.lexsort((b, a, size[a] + size[b]))
    joints: dict = {}
    for edge, pair in zip(e[order].tolist(), zip(a[order].tolist(), b[order].tolist())):
        joints.setdefault(pair, []).append(edge)
    return list(joints), joints


def _convex_unions(x: np.ndarray, me: MeshEdges, state: _State, pairs: list, max_angle: float) -> list:
    """The pairs whose union is a disk in one loop without a corner above ``max_angle``."""
    if not pairs:
        return []
    owner, face = _members(state, np.array(pairs, dtype=np.int64).ravel())
    owner //= 2
    order = np.lexsort((face, owner))
    loops, single = set_outlines(me, owner[order], face[order], len(pairs))
    check = np.flatnonzero(single)
    angle = np.full(len(pairs), np.inf)
    angle[check] = max_corner_angles(x, [loops[k] for k in check.tolist()])[0]
    return [p for p, good in zip(pairs, (angle <= max_angle).tolist()) if good]


def _join(removed: np.ndarray, pairs: list, joints: dict) -> int:
    """Join the pairs in order, each voussoir once per round; returns how many."""
    used: set = set()
    made = 0
    for a, b in pairs:
        if a in used or b in used:
            continue
        used |= {a, b}
        removed[joints[(a, b)]] = True
        made += 1
    return made
