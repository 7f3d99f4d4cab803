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

from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.tessellation.sizes import UPPER
from vaultgram.tessellation.voussoirs import MAX_CONCAVITY, face_groups, max_corner_angles, voussoirs_at_vertices

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
class _Move:
    """One face moved across one joint into voussoir ``target`` (:func:`_move` makes it)."""

    gain: int
    area: float
    joint: int
    face: int
    source: int
    target: int


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
    keys = np.sort(me.corner_vertex * n_groups + group[me.corner_face])
    return _State(group, order, start, voussoirs_at_vertices(me, group, n), keys)


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
    joint = ~removed & (me.faces_of >= 0).all(axis=1)
    faces_in = np.bincount(group, minlength=state.n_groups)
    e = np.flatnonzero(joint)
    at_crowded = np.repeat(crowded[me.edges[e, 0]] | crowded[me.edges[e, 1]], 2)
    e, face, other = np.repeat(e, 2), me.faces_of[e].ravel(), me.faces_of[e, ::-1].ravel()  # both ways
    source, into = group[face], group[other]
    left = size[source] - area[face]
    evens = tiny[into] & (area[face] < size[source] - size[into]) & ((faces_in[source] > 2) | (left <= UPPER * target))
    even_out = (tiny[source] & (faces_in[source] == 1)) | evens  # moves worth making that mend nothing
    fits = ~frozen[source] & ~frozen[into] & (size[into] + area[face] <= largest) & (at_crowded | even_out)
    row = np.flatnonzero(fits)
    gain, ok = _gains(me, state, interior, face[row], into[row])
    row, gain = row[ok], gain[ok]
    keep = (gain > 0) | ((gain == 0) & even_out[row])
    row = row[keep]
    moves = []
    for g, edge, f, src, dst in zip(*(a.tolist() for a in (gain[keep], e[row], face[row], source[row], into[row]))):
        moves.append(_Move(g, float(size[dst] + area[f]), edge, f, src, dst))
    return moves


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


def _feasible(x: np.ndarray, me: MeshEdges, removed: np.ndarray, state: _State, moves: list,
              max_angle: float) -> list:
    """Per move, whether both its voussoirs stay disks in one piece without a corner above
    ``max_angle``."""
    ok, loops = [], []
    for m in moves:
        rest = [f for f in state.members(m.source) if f != m.face]
        grown = _outline(me, state.members(m.target) + [m.face])
        shrunk = _outline(me, rest) if rest else grown
        ok.append(not (grown is None or shrunk is None or (rest and not _connected(me, rest, removed))))
        if ok[-1]:
            loops += [grown, shrunk]
    angle = max_corner_angles(x, loops)[0].reshape(-1, 2) if loops else np.zeros((0, 2))
    good = iter((angle <= max_angle).all(axis=1).tolist())
    return [bool(o and next(good)) for o in ok]


def _outline(me: MeshEdges, faces: list) -> np.ndarray | None:
    """The counter-clockwise boundary loop of a set of faces, or None if it is not one loop."""
    inside = set(faces)
    twin = me.corner_twin
    step = {}
    for f in faces:
        for c in range(int(me.face_start[f]), int(me.face_start[f + 1])):
            if twin[c] < 0 or int(me.corner_face[twin[c]]) not in inside:
                step[int(me.corner_vertex[c])] = step.get(int(me.corner_vertex[c]), []) + [int(me.corner_next[c])]
    if any(len(s) > 1 for s in step.values()):
        return None  # the outline touches itself at a vertex
    start = min(step)
    loop, v = [start], step[start][0]
    while v != start and len(loop) <= len(step):
        loop.append(v)
        v = step[v][0]
    return np.array(loop, dtype=np.int64) if len(loop) == len(step) else None


def _connected(me: MeshEdges, faces: list, removed: np.ndarray) -> bool:
    """Whether ``faces`` are joined into one piece by the removed edges among them."""
    inside, seen, todo = set(faces), {faces[0]}, [faces[0]]
    while todo:
        f = todo.pop()
        for e in me.face_edges(f).tolist():
            g = int(me.other_face(e, f))
            if removed[e] and g in inside and g not in seen:
                seen.add(g)
                todo.append(g)
    return len(seen) == len(inside)


def _apply(x: np.ndarray, me: MeshEdges, removed: np.ndarray, state: _State, moves: list, max_angle: float) -> int:
    """Make the best feasible moves that share no voussoir and no vertex; returns how many. Moves
    are checked in batches: the best ones free of each other, then those they had kept waiting."""
    order = sorted(moves, key=lambda m: (-m.gain, m.area, m.joint, m.face))
    corners = [set(me.corner_vertex[me.face_start[m.face]:me.face_start[m.face + 1]].tolist()) for m in order]
    used_groups: set = set()
    used_vertices: set = set()
    made = 0
    while order:
        batch, later, groups, vertices = [], [], set(used_groups), set(used_vertices)
        for m, c in zip(order, corners):
            if {m.source, m.target} & used_groups or c & used_vertices:
                continue  # beside a move made: never
            (later if {m.source, m.target} & groups or c & vertices else batch).append((m, c))
            groups |= {m.source, m.target}
            vertices |= c
        for (m, c), good in zip(batch, _feasible(x, me, removed, state, [m for m, _ in batch], max_angle)):
            if good:
                used_groups |= {m.source, m.target}
                used_vertices |= c
                _move(me, removed, state.group, m)
                made += 1
        order, corners = [m for m, _ in later], [c for _, c in later]
    return made


def _move(me: MeshEdges, removed: np.ndarray, group: np.ndarray, m: _Move) -> None:
    """Make move ``m``: the face's joints with the target voussoir are removed, the removed edges
    tying it to its own voussoir put back. (No move made in the round touches its sides.)"""
    sides = me.face_edges(m.face)
    across = me.other_face(sides, m.face)
    joins = sides[~removed[sides] & (across >= 0) & (group[np.maximum(across, 0)] == m.target)]
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
    e = np.flatnonzero(~removed & (me.faces_of >= 0).all(axis=1))
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
    kept, loops = [], []
    for a, b in pairs:
        loop = _outline(me, state.members(a) + state.members(b))
        if loop is not None:
            kept.append((a, b))
            loops.append(loop)
    if not kept:
        return []
    angle, _ = max_corner_angles(x, loops)
    return [p for p, good in zip(kept, (angle <= max_angle).tolist()) if good]


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
