"""Local optimisation of the worst elements: max-min smoothing of the scaled Jacobian.

Laplacian smoothing (:mod:`vaultgram.meshing.smoothing`, §3.2) and the gradient passes of
:mod:`vaultgram.meshing.untangle` leave a few narrow corners where their objectives are flat or
conflict: quads next to fixed boundary corners and singular vertices, and the fans of triangles around
poles, whose corners the Laplacian makes unequal. :func:`maximise_min_quality` moves one vertex at a
time to where the smallest scaled Jacobian of the corners it touches is largest (a pattern search over
a few trial positions, Freitag and Plassmann's "optimisation-based smoothing"), so the worst corner
never gets worse and no valid face is ever inverted; a corner whose side shrinks under a share of the
opposite side counts as worse (:func:`corner_quality`), so no move collapses a quad into a triangle. Not in
the paper: its meshes are coarser.

Vectorised: each sweep works on an independent set of vertices (no two in one face), all of whose
trial positions are evaluated at once; no Python loop runs over vertices or faces.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from vaultgram.geometry.arrays import distinct, pieces, plan_rows
from vaultgram.geometry.meshes import corner_arrays
from vaultgram.geometry.polylines import project_to_polyline
from vaultgram.meshing.fans import FAN_FLOOR, fan_bounds

__all__ = ["maximise_min_quality", "OPTIMISE_TARGET", "OPTIMISE_SWEEPS", "CornerTable", "corner_table",
           "corner_quality", "face_neighbours"]

#: Vertices whose worst corner has a scaled Jacobian below this are optimised (above it they are
#: left alone, and a trial that only raises the mean is taken only where the minimum stays there).
OPTIMISE_TARGET = 0.5
#: At most this many sweeps (each moves an independent set of vertices).
OPTIMISE_SWEEPS = 60
#: A vertex moved after the optimisation restarts it this many rings of faces round it.
MOVED_RINGS = 4
#: Sliding (boundary and curve) vertices are optimised only below this.
SLIDE_TARGET = 0.3
#: A vertex next to a pole aims at this share of the pole's fan bound, and is left alone where that
#: is below FAN_FLOOR (the issue's floor).
FAN_MARGIN = 0.97
#: A corner's quality is its scaled Jacobian times ``min(1, side / (SIDE_SHARE x opposite side))`` for
#: each of its two sides, the opposite side (a triangle's: the mean of its other two) measured before the
#: optimisation (:func:`corner_quality`). 0.1 let shared plans' sides shrink under half of what smoothing left
#: (features_combined 0.012 -> 0.005 of the median edge, multiple_lobes 0.006 -> 0.002); 0.3 cost
#: mexico_airport's worst face 0.659 -> 0.429 and square_point_loads' mean 0.902 -> 0.896.
SIDE_SHARE = 0.2
#: A trial must raise the worst corner (or, that equal, the mean) by more than this to be taken.
_GAIN = 1e-3
#: Rounds of the independent-set selection per sweep.
_ROUNDS = 4
#: Trial moves: eight directions at these fractions of the vertex's shortest edge.
_SCALES = (0.3, 0.1, 0.03, 0.01)
_DIRS = np.array([[math.cos(a), math.sin(a)] for a in np.arange(8) * math.pi / 4])
_MOVES = np.vstack([np.zeros((1, 2))] + [s * _DIRS for s in _SCALES])  # (1 + 8 k, 2), the first stays put
_TRI = 2.0 / math.sqrt(3.0)


class _Groups(NamedTuple):
    """Values grouped by an integer key, for fast per-key minima (``np.minimum.reduceat`` on the values
    sorted by key, much faster than ``np.minimum.at``)."""

    order: np.ndarray
    starts: np.ndarray
    keys: np.ndarray

    @staticmethod
    def of(key: np.ndarray) -> _Groups:
        order = np.argsort(key, kind="stable")
        k = key[order]
        starts = np.flatnonzero(np.r_[True, k[1:] != k[:-1]]) if len(k) else np.zeros(0, dtype=np.int64)
        return _Groups(order, starts, k[starts])

    def minimum(self, values: np.ndarray, n: int, fill) -> np.ndarray:
        """Per key ``0 .. n - 1``, the smallest of its ``values`` (``fill`` where it has none)."""
        out = np.full(n, fill, dtype=values.dtype)
        out[self.keys] = np.minimum.reduceat(values[self.order], self.starts)
        return out


class CornerTable(NamedTuple):
    """The corners of the faces: face, vertex ``u``, next ``v``, previous ``p``, the factor that
    scales a triangle's corner so that an equilateral triangle has 1 (as
    :func:`vaultgram.meshing.quality.face_scaled_jacobians`), the next and previous corner of the
    same face (``after``, ``before``: the corners whose ``u`` are ``v`` and ``p``), the corners
    grouped by vertex ``u`` and by face, and per corner the length ``ref`` under which its side ``u-v``
    lowers the quality of the two corners at its ends (:func:`corner_quality`; 0: never)."""

    face: np.ndarray
    u: np.ndarray
    v: np.ndarray
    p: np.ndarray
    factor: np.ndarray
    after: np.ndarray
    before: np.ndarray
    at: _Groups
    of_face: _Groups
    ref: np.ndarray


def corner_table(faces, x: np.ndarray | None = None) -> CornerTable:
    """The :class:`CornerTable` of ``faces``; ``ref`` :data:`SIDE_SHARE` of the side opposite each corner's
    side ``u-v`` at ``x`` (in a triangle, of the mean of its other two sides; 0 without ``x``)."""
    face, u, v, p = corner_arrays(faces)
    lens = np.bincount(face, minlength=len(faces))
    size, first = lens[face], (np.cumsum(lens) - lens)[face]
    k = np.arange(len(face))
    after = np.where(k + 1 == first + size, first, k + 1)
    before = np.where(k == first, first + size - 1, k - 1)
    ref = np.zeros(len(face))
    if x is not None:
        side = np.hypot(*(plan_rows(x, v) - plan_rows(x, u)).T)
        ref = SIDE_SHARE * np.where(size == 3, 0.5 * (side[after] + side[before]), side[after[after]])
    return CornerTable(face, u, v, p, _factors(face, len(faces)), after, before, _Groups.of(u), _Groups.of(face), ref)


def _factors(face: np.ndarray, n_faces: int) -> np.ndarray:
    """Per corner (of face ``face``), the factor of :class:`CornerTable`: :data:`_TRI` in a triangle, else 1."""
    return np.where(np.bincount(face, minlength=n_faces)[face] == 3, _TRI, 1.0)


def _touching(values: np.ndarray, t: CornerTable, n: int, fill) -> np.ndarray:
    """Per vertex ``0 .. n - 1``, the smallest of the ``values`` of the corners that touch it (as their
    vertex, next or previous vertex; ``fill`` where none does): a vertex ``w`` is the next vertex of
    the corner before each corner at ``w`` and the previous vertex of the one after it, so one grouping
    by vertex does, not a sort of the three roles' 3 10^6 corners at 10^6 faces."""
    return t.at.minimum(np.minimum(np.minimum(values, values[t.before]), values[t.after]), n, fill)


def corner_quality(pu: np.ndarray, pv: np.ndarray, pp: np.ndarray, factor, ref1=0.0, ref2=0.0) -> np.ndarray:
    """Qualities of corners given their three points (..., 2): the scaled Jacobian ``(e1 x e2) / (|e1|
    |e2|)`` times ``factor``, at most 1, -1 for a degenerate corner; where positive, times
    ``min(1, |e1| / ref1, |e2| / ref2)`` (:data:`SIDE_SHARE` of the opposite sides).

    The scaled Jacobian sees directions, not lengths: the search slid a vertex until a side was all but
    gone (saved random plan 48: 0.18 m -> 0.05 mm beside sides of 0.07-0.25 m; 44 of the 700 saved plans
    with a side under 0.001 of the median edge), a quad that is a triangle whose two corners at that
    side measure as any quad's, and a voussoir of no size. With the factor such corners count as poor:
    the search keeps the side and, where a vertex presses on its neighbour, moves the neighbour on to
    make room (the strips under features_combined's curve end (5, 7.5): 0.358 without a collapsed side,
    where a hard floor on the moves stopped at 0.298). Against the opposite side, not the face's mean
    side: a long thin quad (multiple_lobes' rows into a short stretch of outline, 1 m by 0.03 m) is no
    collapse, and measured against its mean side it was moved to 0.293.

    >>> o, a = np.array([0.0, 0.0]), np.array([1.0, 0.0])
    >>> float(corner_quality(o, a, np.array([0.0, 1.0]), 1.0)), round(float(corner_quality(o, a, np.ones(2), 1.0)), 3)
    (1.0, 0.707)
    >>> float(corner_quality(o, a, np.array([0.0, 0.1]), 1.0, ref2=0.2))   # the side under its share of the opposite
    0.5
    """
    e1, e2 = pv - pu, pp - pu
    l1, l2 = np.hypot(e1[..., 0], e1[..., 1]), np.hypot(e2[..., 0], e2[..., 1])
    norm = l1 * l2
    cross = e1[..., 0] * e2[..., 1] - e1[..., 1] * e2[..., 0]
    sj = np.minimum(np.where(norm > 0, cross / np.where(norm > 0, norm, 1.0), -1.0) * factor, 1.0)
    short = np.minimum(l1 / np.maximum(ref1, 1e-300), l2 / np.maximum(ref2, 1e-300))
    return np.where(sj > 0, sj * np.minimum(1.0, short), sj)


def maximise_min_quality(vertices: np.ndarray, faces, fixed: np.ndarray | None = None, constraints=(),
                         target: float = OPTIMISE_TARGET, sweeps: int = OPTIMISE_SWEEPS,
                         still=None, moved=None) -> np.ndarray:
    """Raise the smallest scaled Jacobian around every vertex whose worst corner is below its goal.

    A corner's quality is its scaled Jacobian, lowered where one of its sides is under
    :data:`SIDE_SHARE` of the opposite side as it was on entry (:func:`corner_quality`). A vertex's goal is
    ``target``, less for a sliding vertex or next to a pole's fan, none next to a pole whose fan cannot
    reach the floor (:func:`_goals`). Each sweep takes the vertices below their
    goals that are not fixed and not known to be stuck, keeps those whose worst corner is the lowest
    among the vertices sharing a face with them (an independent set: their moves do not interact), and
    tries for each the positions :data:`_MOVES` times its shortest edge away (projected onto its
    polyline for a sliding vertex of ``constraints``). It takes the trial with the largest worst corner
    (counted up to the goal; ties by the largest mean) when that beats the current one by :data:`_GAIN`,
    else marks the vertex stuck until a neighbour moves. So the worst corner of a vertex's faces only
    grows: a valid mesh stays valid, and an inverted face is untangled where one vertex's move can do
    it. The vertices sharing a face with one of ``still`` are not moved unless the mesh has an inverted
    face (a fold is worse): the pipeline passes the point features, whose rings carry the point loads'
    force flow into the tessellation (moving them changed its joint angles and voussoir sizes there).
    Given ``moved`` (vertices just moved in an optimised mesh), the sweeps start from the vertices
    within :data:`MOVED_RINGS` rings of faces of them, the others counted stuck until a neighbour moves.

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.meshing.quality import face_scaled_jacobians
    >>> v, f = grid_mesh(2)
    >>> v[4, :2] = [1.8, 1.7]  # the centre of a 2 x 2 grid dragged near the corner (2, 2): folded
    >>> fixed = np.ones(9, bool); fixed[4] = False
    >>> x = maximise_min_quality(v, f, fixed)
    >>> bool(face_scaled_jacobians(v, f).min() < 0 < OPTIMISE_TARGET <= face_scaled_jacobians(x, f).min())
    True
    """
    x = np.array(vertices, dtype=float)
    if len(faces) == 0:
        return x
    table = corner_table(faces, x)
    sj = _corner_jacobians(x, table)
    if not (sj < target).any():  # no vertex below its goal, at most the target: a fine mesh, smoothed
        return x
    keep = np.zeros(len(x), dtype=bool) if fixed is None else np.asarray(fixed, dtype=bool).copy()
    worst = _touching(sj, table, len(x), np.inf)
    if still is not None and np.any(still) and worst.min() > 0:  # unfolding comes first
        keep[face_neighbours(table, np.flatnonzero(still), len(x))] = True
    slide_of = _slide_index(len(x), constraints)
    goal = _goals(x, faces, table, target, slide_of >= 0)
    stuck = keep.copy()
    if moved is not None:
        near = np.asarray(moved, dtype=np.int64)
        for _ in range(MOVED_RINGS):
            near = face_neighbours(table, near, len(x))
        stuck[np.setdiff1d(np.arange(len(x)), near)] = True
    for sweep in range(sweeps):
        if sweep:
            worst = _vertex_minima(x, table)
        chosen = _independent(worst, table, ~stuck & (worst < goal))
        if not len(chosen):
            break
        moved = _try_moves(x, table, chosen, goal[chosen], slide_of, constraints)
        stuck[chosen[~moved]] = True
        stuck[face_neighbours(table, chosen[moved], len(x))] = False
        stuck |= keep
    return x


def _goals(x: np.ndarray, faces, t: CornerTable, target: float, sliding: np.ndarray) -> np.ndarray:
    """Per vertex, the worst corner to aim at: ``target`` (:data:`SLIDE_TARGET` for a sliding
    vertex: moved along the boundary it cuts off the domain's bends, so only where a face is poor),
    at most :data:`FAN_MARGIN` of the fan bound of a corner it touches
    (:func:`vaultgram.meshing.fans.fan_bounds`: no sweep is spent on what cannot be reached); and 0
    (left alone) where that is below :data:`FAN_FLOOR`: the ring round such a pole gains little
    (square_point_loads 0.093 -> 0.106) and moving it shifts the force flow round point loads (the
    tessellation's joint angles there: 8.3 -> 11.0 degrees)."""
    reach = _touching(fan_bounds(x, faces)[t.u], t, len(x), np.inf)
    goal = np.minimum(np.where(sliding, min(target, SLIDE_TARGET), target), FAN_MARGIN * reach)
    return np.where(FAN_MARGIN * reach < FAN_FLOOR, 0.0, goal)


def _vertex_minima(x: np.ndarray, t: CornerTable) -> np.ndarray:
    """Per vertex, the smallest quality (:func:`corner_quality`) of the corners it touches (as vertex, next or
    previous)."""
    return _touching(_corner_jacobians(x, t), t, len(x), np.inf)


def _corner_jacobians(x: np.ndarray, t: CornerTable) -> np.ndarray:
    """:func:`corner_quality` of every corner of ``t``, computed a cache-sized piece at a time
    (:func:`~vaultgram.geometry.arrays.pieces`)."""
    xy = np.ascontiguousarray(x[:, :2])
    sj = np.empty(len(t.u))
    for part in pieces(len(t.u)):
        sj[part] = corner_quality(plan_rows(xy, t.u[part]), plan_rows(xy, t.v[part]), plan_rows(xy, t.p[part]),
                           t.factor[part], t.ref[part], t.ref[t.before[part]])
    return sj


def _independent(worst: np.ndarray, t: CornerTable, candidate: np.ndarray) -> np.ndarray:
    """An independent set of candidates (no two share a face), the worst first: :func:`_lowest`, then
    again among the candidates sharing no face with those, for :data:`_ROUNDS` rounds (Luby's)."""
    left = candidate.copy()
    picked = []
    for _ in range(_ROUNDS):
        if not left.any():
            break
        got = _lowest(worst, t, left)
        picked.append(got)
        left[face_neighbours(t, got, len(worst))] = False
    return np.sort(np.concatenate(picked)) if picked else np.zeros(0, dtype=np.int64)


def _lowest(worst: np.ndarray, t: CornerTable, candidate: np.ndarray) -> np.ndarray:
    """The candidates whose ``worst`` (ties by index) is the lowest of every face they are in: no two
    of them share a face."""
    rank = np.full(len(worst), np.iinfo(np.int64).max)
    idx = np.flatnonzero(candidate)
    rank[idx[np.lexsort((idx, worst[idx]))]] = np.arange(len(idx))
    top = np.iinfo(np.int64).max
    face_min = t.of_face.minimum(rank[t.u], int(t.face.max()) + 1, top)
    lowest = t.at.minimum(face_min[t.face], len(worst), top)
    return idx[lowest[idx] == rank[idx]]


def face_neighbours(t: CornerTable, verts: np.ndarray, n: int) -> np.ndarray:
    """The vertices sharing a face with any of ``verts``."""
    mark = np.zeros(n, dtype=bool)
    mark[verts] = True
    in_face = np.zeros(int(t.face.max()) + 1, dtype=bool)
    in_face[t.face[mark[t.u]]] = True
    return distinct(t.u[in_face[t.face]])


def _slide_index(n: int, constraints) -> np.ndarray:
    """Per vertex, the index of the sliding constraint it belongs to, else -1."""
    out = np.full(n, -1, dtype=np.int64)
    for k, c in enumerate(constraints):
        out[np.asarray(c.vertices, dtype=np.int64)] = k
    return out


def _trials(x: np.ndarray, t: CornerTable, chosen: np.ndarray, slide_of: np.ndarray, constraints) -> np.ndarray:
    """Trial positions (k, m, 2) of the chosen vertices: :data:`_MOVES` times each one's shortest edge
    (at least a quarter of its mean edge), sliding vertices projected onto their polylines."""
    e = np.hypot(*(plan_rows(x, t.v) - plan_rows(x, t.u)).T)
    shortest = np.full(len(x), np.inf)
    np.minimum.at(shortest, t.u, e)
    np.minimum.at(shortest, t.v, e)
    mean = (np.bincount(t.u, e, len(x)) + np.bincount(t.v, e, len(x))) / np.maximum(
        np.bincount(t.u, minlength=len(x)) + np.bincount(t.v, minlength=len(x)), 1)
    scale = np.maximum(shortest, 0.25 * mean)  # an edge collapsed to nothing still gives a step
    trial = x[chosen, None, :2] + scale[chosen, None, None] * _MOVES[None]
    on = slide_of[chosen]
    for k in distinct(on[on >= 0]):
        rows = np.flatnonzero(on == k)
        c = constraints[int(k)]
        pts = project_to_polyline(trial[rows].reshape(-1, 2), np.asarray(c.polyline)[:, :2], c.closed)
        trial[rows] = pts.reshape(len(rows), -1, 2)
    return trial


def _try_moves(x: np.ndarray, t: CornerTable, chosen: np.ndarray, goal: np.ndarray, slide_of: np.ndarray,
               constraints) -> np.ndarray:
    """Move each chosen vertex to its best trial position, in place (:func:`maximise_min_quality`),
    its worst corner counted up to its ``goal``; which of them moved."""
    trial = _trials(x, t, chosen, slide_of, constraints)
    slot = np.full(len(x), -1, dtype=np.int64)
    slot[chosen] = np.arange(len(chosen))
    su, sv, sp = slot[t.u], slot[t.v], slot[t.p]
    hit = np.flatnonzero((su >= 0) | (sv >= 0) | (sp >= 0))
    who = np.maximum(np.maximum(su[hit], sv[hit]), sp[hit])

    def at(ends, s):
        return np.where((s[hit] >= 0)[:, None, None], trial[who], x[ends[hit], None, :2])

    sj = corner_quality(at(t.u, su), at(t.v, sv), at(t.p, sp), t.factor[hit, None], t.ref[hit, None],
                 t.ref[t.before[hit], None])
    order = np.argsort(who, kind="stable")  # every chosen vertex has corners: one group each, in order
    starts = np.flatnonzero(np.r_[True, np.diff(who[order]) != 0])
    low = np.minimum.reduceat(sj[order], starts, axis=0)
    mean = np.add.reduceat(sj[order], starts, axis=0)
    primary = np.minimum(low, goal[:, None])
    tie = np.where(primary >= primary.max(axis=1, keepdims=True) - 1e-12, mean, -np.inf)
    best = np.argmax(tie, axis=1)
    row = np.arange(len(chosen))
    better = (primary[row, best] > primary[:, 0] + _GAIN) | (
        (primary[row, best] >= primary[:, 0] - 1e-12) & (mean[row, best] > mean[:, 0] + _GAIN))
    x[chosen[better], :2] = trial[row[better], best[better]]
    return better
