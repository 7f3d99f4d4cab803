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

from vaultgram.geometry.arrays import distinct, lookup, ranges, run_starts
from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.tessellation.sizes import UPPER
from vaultgram.tessellation.voussoirs import (
    MAX_CONCAVITY,
    face_groups,
    max_corner_angles,
    member_corners,
    set_outlines,
    voussoirs_at_vertices,
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

    def take(self, rows: np.ndarray) -> _Moves:
        """The moves ``rows``, in that order."""
        return _Moves(self.gain[rows], self.joint[rows], self.face[rows], self.source[rows], self.target[rows])


@dataclass(frozen=True)
class _State:
    """The voussoirs as they stand in a round: each face's voussoir and the faces in voussoir order
    (``order[start[k]:start[k + 1]]`` are voussoir ``k``'s, by face; a voussoir a move emptied has
    none)."""

    group: np.ndarray
    order: np.ndarray
    start: np.ndarray

    @property
    def n_groups(self) -> int:
        return len(self.start) - 1


@dataclass(frozen=True)
class _Crowding:
    """The corners around each vertex (``around[at[v]:at[v + 1]]``) and how many voussoirs meet at
    each vertex (``count``), kept up to date as faces move (:func:`_recount`): a round's moves
    change the count at the corners of the faces moved only."""

    around: np.ndarray
    at: np.ndarray
    count: np.ndarray

    def corners(self, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The corners around the vertices ``v``: ``(i, corner)`` pairs, by ``i``."""
        row, at = ranges(self.at[v], self.at[v + 1] - self.at[v])
        return row, self.around[at]

    def faces_at(self, me: MeshEdges, group: np.ndarray, v: np.ndarray, ks: list) -> list:
        """How many faces of voussoir ``k[i]`` have a corner at vertex ``v[i]``, for each ``k`` of ``ks``."""
        row, corner = self.corners(v)
        there = group[me.corner_face[corner]]
        return [np.bincount(row, weights=there == k[row], minlength=len(v)).astype(np.int64) for k in ks]


def _corners_of(me: MeshEdges, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The corners of ``faces``: ``(i, corner)`` pairs, by ``i``, each face's in order."""
    return ranges(me.face_start[faces], me.face_start[faces + 1] - me.face_start[faces])


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
    group = face_groups(me, removed)  # kept up to date as faces move (below), not found again each round
    crowding = _crowding(me, group, len(x))
    total = 0
    known = (np.zeros(0, dtype=np.int64), np.zeros(0, dtype=bool))  # feasibility of moves, by key (below)
    for _ in range(ROUNDS):
        state = _state(group)
        moves = _candidates(me, removed, interior, area, target, frozen_faces, state, crowding)
        key = moves.face * len(area) + state.order[state.start[moves.target]]
        good = _feasible_known(x, me, removed, state, moves, max_angle, key, known)
        made, used = _apply(me, removed, state, moves, good, len(x))
        total += len(made)
        if not len(made):
            break
        kept = ~used[moves.source] & ~used[moves.target]
        order = np.argsort(key[kept])
        known = (key[kept][order], good[kept][order])
        # a moved face takes its target's number: both voussoirs stay in one piece (_feasible), so they are
        # still the ones face_groups would find, numbered otherwise (which no choice here depends on)
        group[moves.face[made]] = moves.target[made]
        _recount(me, crowding, group, moves.face[made])
    return removed, total


def _state(group: np.ndarray) -> _State:
    """The voussoirs of the faces' voussoir numbers ``group``."""
    n_groups = int(group.max()) + 1 if len(group) else 0
    start = np.concatenate([[0], np.cumsum(np.bincount(group, minlength=n_groups))])
    return _State(group, np.argsort(group, kind="stable"), start)


def _crowding(me: MeshEdges, group: np.ndarray, n: int) -> _Crowding:
    """The corners around each of the ``n`` vertices, and the voussoirs of ``group`` meeting at each."""
    around = np.argsort(me.corner_vertex, kind="stable")
    at = np.concatenate([[0], np.cumsum(np.bincount(me.corner_vertex, minlength=n))])
    return _Crowding(around, at, voussoirs_at_vertices(me, group, n))


def _recount(me: MeshEdges, crowding: _Crowding, group: np.ndarray, faces: np.ndarray) -> None:
    """Count the voussoirs (of ``group``) meeting at the corners of ``faces`` again."""
    v = distinct(me.corner_vertex[_corners_of(me, faces)[1]])
    row, corner = crowding.corners(v)
    n_groups = max(int(group.max()) + 1, 1)
    crowding.count[v] = np.bincount(distinct(row * n_groups + group[me.corner_face[corner]]) // n_groups,
                                    minlength=len(v))


def _candidates(me: MeshEdges, removed: np.ndarray, interior: np.ndarray, area: np.ndarray, target: float,
                frozen_faces: np.ndarray, state: _State, crowding: _Crowding) -> _Moves:
    """Every move of a face across a joint at a crowded inner vertex that lowers the crowding, and
    every move that evens out a small voussoir without raising it (module docstring), keeping the
    receiving voussoir within :data:`GROWTH` times ``target``."""
    group = state.group
    frozen = np.zeros(state.n_groups, dtype=bool)
    frozen[group[frozen_faces]] = True
    size = np.bincount(group, weights=area, minlength=state.n_groups)
    largest = GROWTH * target
    tiny = size < SMALL * target
    crowded = interior & (crowding.count >= 4)
    faces_in = np.bincount(group, minlength=state.n_groups)
    e = np.flatnonzero(~removed & ~me.boundary)
    ends, sides = me.edges.take(e, axis=0), me.faces_of.take(e, axis=0)
    at_crowded = crowded[ends[:, 0]] | crowded[ends[:, 1]]
    # only moves at a crowded vertex or beside a small voussoir can fit (below): the others go first
    near = np.flatnonzero(at_crowded | tiny[group[sides[:, 0]]] | tiny[group[sides[:, 1]]])
    e, sides, at_crowded = np.repeat(e[near], 2), sides[near], np.repeat(at_crowded[near], 2)
    face, other = sides.ravel(), sides[:, ::-1].ravel()  # both ways
    source, into = group[face], group[other]
    left = size[source] - area[face]
    evens = tiny[into] & (area[face] < size[source] - size[into]) & ((faces_in[source] > 2) | (left <= UPPER * target))
    even_out = (tiny[source] & (faces_in[source] == 1)) | evens  # moves worth making that mend nothing
    fits = ~frozen[source] & ~frozen[into] & (size[into] + area[face] <= largest) & (at_crowded | even_out)
    row = np.flatnonzero(fits)
    gain, ok = _gains(me, state, crowding, interior, face[row], into[row])
    row, gain = row[ok], gain[ok]
    keep = (gain > 0) | ((gain == 0) & even_out[row])
    row, gain = row[keep], gain[keep]
    grown = size[into[row]] + area[face[row]]
    best = np.lexsort((face[row], e[row], grown, -gain))  # most gain, then smallest voussoir made
    row = row[best]
    return _Moves(gain[best], e[row], face[row], source[row], into[row])


def _gains(me: MeshEdges, state: _State, crowding: _Crowding, interior: np.ndarray, face: np.ndarray,
           target: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each move of ``face[i]`` into voussoir ``target[i]``: how much the crowding at the face's
    corners drops, and whether the move is allowed (no inner corner left inside one voussoir). At a
    corner the face's own voussoir leaves if the face was its only face there, and the target
    arrives if it had none."""
    row, corner = _corners_of(me, face)
    v = me.corner_vertex[corner]
    before = crowding.count[v]
    source, into = crowding.faces_at(me, state.group, v, [state.group[face][row], target[row]])
    after = before - (source == 1) + (into == 0)
    inner = interior[v]
    drop = (np.maximum(before - 3, 0) - np.maximum(after - 3, 0)) * inner
    enclosed = np.bincount(row, weights=(after == 1) & inner, minlength=len(face)) > 0
    return np.bincount(row, weights=drop, minlength=len(face)).astype(np.int64), ~enclosed


def _feasible_known(x: np.ndarray, me: MeshEdges, removed: np.ndarray, state: _State, moves: _Moves,
                    max_angle: float, key: np.ndarray, known: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Per move, whether it is feasible (:func:`_feasible`). A move's feasibility depends on its face
    and its two voussoirs only, so it is checked once, for all moves, before any is made, and kept
    for the next rounds while neither voussoir changes: ``key`` names each move by its face and the
    smallest face of its target (the same voussoir while unchanged), ``known`` is the sorted keys
    and the feasibility of the moves checked in earlier rounds between voussoirs unchanged since.
    After the first round most candidates are such moves found infeasible before."""
    pos, found = lookup(known[0], key)
    good = np.zeros(len(moves), dtype=bool)
    good[found] = known[1][pos[found]]
    new = np.flatnonzero(~found)
    good[new] = _feasible(x, me, removed, state, moves.take(new), max_angle)
    return good


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
    owner, at = ranges(state.start[groups], state.start[groups + 1] - state.start[groups])
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


def _apply(me: MeshEdges, removed: np.ndarray, state: _State, moves: _Moves, good: np.ndarray, n_vertices: int
           ) -> tuple[np.ndarray, np.ndarray]:
    """Make the ``good`` (feasible) moves in order (best first), each unless an earlier move made
    shares a voussoir or a vertex with it; returns the moves made, and which voussoirs they changed.
    A move that shares neither with any other good move is made whichever comes first: only the
    others are gone through one by one."""
    i = np.flatnonzero(good)
    source, target = moves.source[i], moves.target[i]
    row, corner = _corners_of(me, moves.face[i])
    v = me.corner_vertex[corner]
    sharing = np.bincount(row, weights=np.bincount(v, minlength=n_vertices)[v] > 1, minlength=len(i)) > 0
    groups = np.bincount(np.concatenate([source, target]), minlength=state.n_groups)
    made = (groups[source] == 1) & (groups[target] == 1) & ~sharing
    used_groups = np.zeros(state.n_groups, dtype=bool)
    used_vertices = np.zeros(n_vertices, dtype=bool)
    for j in np.flatnonzero(~made).tolist():
        src, dst, f = int(source[j]), int(target[j]), int(moves.face[i[j]])
        corners = me.corner_vertex[me.face_start[f]:me.face_start[f + 1]]
        if used_groups[src] or used_groups[dst] or used_vertices[corners].any():
            continue
        used_groups[[src, dst]] = True
        used_vertices[corners] = True
        made[j] = True
    used_groups[source[made]] = used_groups[target[made]] = True
    _move(me, removed, state.group, moves.face[i[made]], target[made])
    return i[made], used_groups


def _move(me: MeshEdges, removed: np.ndarray, group: np.ndarray, face: np.ndarray, target: np.ndarray) -> None:
    """Move each ``face[i]`` into voussoir ``target[i]``: its joints with the target are removed, the
    removed edges tying it to its own voussoir put back. (The moves made in a round share no vertex,
    so no side: they are made at once.)"""
    row, corner = _corners_of(me, face)
    sides = me.corner_edge[corner]
    across = me.other_face(sides, face[row])
    joins = sides[~removed[sides] & (across >= 0) & (group[np.maximum(across, 0)] == target[row])]
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
        state = _state(face_groups(me, removed))
        pairs, joint, pair_of = _small_pairs(me, removed, area, target, frozen_faces, state)
        joined = _join(pairs, _convex_unions(x, me, state, pairs, max_angle))
        removed[joint[joined[pair_of]]] = True
        made = int(joined.sum())
        total += made
        if not made:
            break
    return removed, total


def _small_pairs(me: MeshEdges, removed: np.ndarray, area: np.ndarray, target: float, frozen_faces: np.ndarray,
                 state: _State) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The pairs of neighbouring small voussoirs whose union is within the size limit, smallest union
    first (rows ``(a, b)``, ``a < b``), and the joints between the pairs with the pair of each."""
    group = state.group
    size = np.bincount(group, weights=area, minlength=state.n_groups)
    frozen = np.zeros(state.n_groups, dtype=bool)
    frozen[group[frozen_faces]] = True
    e = np.flatnonzero(~removed & ~me.boundary)
    sides = group[me.faces_of.take(e, axis=0)]
    a, b = np.minimum(sides[:, 0], sides[:, 1]), np.maximum(sides[:, 0], sides[:, 1])
    ok = (size[a] < PAIRED * target) & (size[b] < PAIRED * target) & ~frozen[a] & ~frozen[b]
    ok &= (size[a] + size[b] <= UPPER * target) & (a != b)
    e, a, b = e[ok], a[ok], b[ok]
    order = np.lexsort((b, a, size[a] + size[b]))  # a pair's joints side by side (one union size), by edge
    e, a, b = e[order], a[order], b[order]
    first = run_starts(a * state.n_groups + b)
    return np.column_stack([a[first], b[first]]), e, np.cumsum(first) - 1


def _convex_unions(x: np.ndarray, me: MeshEdges, state: _State, pairs: np.ndarray, max_angle: float) -> np.ndarray:
    """Per pair, whether its union is a disk in one loop without a corner above ``max_angle``."""
    if not len(pairs):
        return np.zeros(0, dtype=bool)
    owner, face = _members(state, pairs.ravel())
    owner //= 2
    order = np.lexsort((face, owner))
    loops, single = set_outlines(me, owner[order], face[order], len(pairs))
    check = np.flatnonzero(single)
    angle = np.full(len(pairs), np.inf)
    angle[check] = max_corner_angles(x, [loops[k] for k in check.tolist()])[0]
    return angle <= max_angle


def _join(pairs: np.ndarray, good: np.ndarray) -> np.ndarray:
    """Which of the ``good`` pairs to join: in order, each voussoir once per round."""
    used: set = set()
    joined = np.zeros(len(pairs), dtype=bool)
    for i, (a, b) in zip(np.flatnonzero(good).tolist(), pairs[good].tolist()):
        if a in used or b in used:
            continue
        used |= {a, b}
        joined[i] = True
    return joined
