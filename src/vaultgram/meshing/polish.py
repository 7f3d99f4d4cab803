"""The worst corners raised together: gradient ascent of a soft minimum of the corner qualities.

:func:`vaultgram.meshing.optimise.maximise_min_quality` moves one vertex at a time, so it stops where
the worst corner can only be widened by moving two or more vertices at once: a row of slivers squeezed
through a narrow passage (jagged_1's spike neck, 0.6 m wide for four strips of 1.3 m quads), where
each vertex's move narrows the corner across the row as much as it widens its own. :func:`polish_worst`
moves every free vertex round the poor corners at once, up a soft minimum of their qualities (the
worst corners weigh most; limited-memory BFGS), and keeps the positions with the best worst corner it
met, never worse than it started: a valid mesh stays valid. Not in the paper (§3.2 stops at Laplacian
smoothing): its meshes are coarser than issue 12's jagged outlines.

Vectorised over the corners of the region; no Python loop runs over vertices or faces.
"""

from __future__ import annotations

import dataclasses
from typing import NamedTuple

import numpy as np

from vaultgram.geometry.arrays import distinct, plan_rows
from vaultgram.meshing.optimise import corner_quality, corner_table, face_neighbours
from vaultgram.meshing.quadmesh import slide

__all__ = ["polish_worst", "POLISH_TARGET"]

#: Corners whose quality is under this are polished (with the faces :data:`POLISH_RINGS` rings round
#: them): issue 12 What 4's floor.
POLISH_TARGET = 0.3
#: The region: the faces of the poor corners and this many rings of faces round them.
POLISH_RINGS = 3
#: Sharpness of the soft minimum ``-log(sum(exp(-BETA q))) / BETA``: a corner 0.025 above the worst
#: weighs ``1/e`` of it.
BETA = 40.0
#: Where the soft minimum stops rising, its sharpness doubles, up to this.
BETA_MAX = 640.0
#: A side shorter than this share of its length on entry lowers its corners' quality too (besides the
#: optimiser's SIDE_SHARE of the opposite side).
KEEP_SIDE = 0.5
#: The polished positions are kept only where they raise the worst corner by this much: a mesh at its
#: bound (a pole's fan, a sharp corner of the plan) is left as it was, not drifted for nothing (saved
#: random plans 140, 230, 471: shortest edge 0.050 -> 0.033, 0.088 -> 0.040, 0.078 -> 0.032 of the median
#: edge for a gain under 0.001).
MIN_GAIN = 0.005
#: Ascent steps at most, and the largest move of a vertex in a step as a share of its mean side.
POLISH_STEPS = 400
POLISH_STEP = 0.2
#: Pairs of steps and gradient changes the ascent remembers (limited-memory BFGS), and halvings of a
#: step before the memory is dropped.
MEMORY = 8
_HALVINGS = 20
#: The ascent stops after this many steps in a row that raised the best worst corner by less than
#: _STALL_GAIN.
_STALL = 100
_STALL_GAIN = 1e-3
#: A sliding stretch with this many (free vertex, segment) pairs or more is projected on its own.
_PAIRS = 20000


class _Region(NamedTuple):
    """The corners polished (vertex ``u``, next ``v``, previous ``p``, triangle ``factor``, the side
    lengths ``ref1``, ``ref2`` under which a side lowers the quality,
    :func:`~vaultgram.meshing.optimise.corner_quality`), the vertices that move (``free``, n bool) and the
    smallest scaled Jacobian of the corners no move changes (``rest``; inf where none)."""

    u: np.ndarray
    v: np.ndarray
    p: np.ndarray
    factor: np.ndarray
    ref1: np.ndarray
    ref2: np.ndarray
    free: np.ndarray
    rest: float


def polish_worst(vertices: np.ndarray, faces, fixed: np.ndarray | None = None, constraints=(), still=None,
                 target: float = POLISH_TARGET, steps: int = POLISH_STEPS) -> np.ndarray:
    """Raise the corners under ``target`` of a valid mesh together (module docstring).

    A corner's quality is the max-min optimiser's (the scaled Jacobian, lowered where a side is under
    :data:`~vaultgram.meshing.optimise.SIDE_SHARE` of the opposite side as on entry, so no side
    collapses), lowered too where a side is under :data:`KEEP_SIDE` of its own length on entry. The
    vertices within :data:`POLISH_RINGS` rings of the corners whose scaled Jacobian is under ``target``
    move, unless ``fixed`` or sharing a face with one of ``still`` (point features' rings carry the
    point loads' force flow, as in the optimiser), sliding ones kept on their polylines; the corners of
    every face they touch are measured (:func:`_ascend`). A mesh with an inverted face, or none under
    ``target``, is returned as it is; so is one the ascent cannot raise by :data:`MIN_GAIN`.

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.meshing.quality import face_scaled_jacobians
    >>> v, f = grid_mesh(3)
    >>> v[[5, 6, 9, 10], :2] = [[1.9, 1.0], [2.2, 1.2], [1.9, 2.0], [2.2, 1.8]]  # the inner four squeezed right
    >>> fixed = np.ones(16, bool); fixed[[5, 6, 9, 10]] = False
    >>> before, after = face_scaled_jacobians(v, f).min(), face_scaled_jacobians(polish_worst(v, f, fixed), f).min()
    >>> round(float(before), 3), round(float(after), 3)
    (0.247, 1.0)
    """
    x = np.array(vertices, dtype=float)
    if len(faces) == 0:
        return x
    region = _region(x, faces, fixed, still, target)
    if region is None:
        return x
    return _ascend(x, region, constraints, steps)


def _region(x: np.ndarray, faces, fixed, still, target: float) -> _Region | None:
    """The :class:`_Region` of ``x``: the corners of the faces with a free vertex, the free vertices
    those within :data:`POLISH_RINGS` rings of a corner whose scaled Jacobian is under ``target``, not
    ``fixed`` and sharing no face with one of ``still``; None when no corner is under ``target`` (or
    one is inverted, or no vertex may move, or the worst corner is in no face a free vertex is in)."""
    t = corner_table(faces, x)
    sj = corner_quality(plan_rows(x, t.u), plan_rows(x, t.v), plan_rows(x, t.p), t.factor)
    if sj.min() <= 0 or sj.min() >= target:
        return None
    low = sj < target
    near = distinct(np.concatenate([t.u[low], t.v[low], t.p[low]]))
    for _ in range(POLISH_RINGS):
        near = face_neighbours(t, near, len(x))
    free = np.zeros(len(x), dtype=bool)
    free[near] = True
    if fixed is not None:
        free &= ~np.asarray(fixed, dtype=bool)
    if still is not None and np.any(still):
        free[face_neighbours(t, np.flatnonzero(still), len(x))] = False
    if not free.any():
        return None
    in_face = np.zeros(len(faces), dtype=bool)
    in_face[t.face[free[t.u]]] = True  # every face a move changes
    k = in_face[t.face]
    rest = float(sj[~k].min()) if (~k).any() else np.inf
    if rest <= sj[k].min():  # the worst corner is one no vertex here may widen: nothing to gain
        return None
    own1 = np.hypot(*(plan_rows(x, t.v[k]) - plan_rows(x, t.u[k])).T)
    own2 = np.hypot(*(plan_rows(x, t.p[k]) - plan_rows(x, t.u[k])).T)
    return _Region(t.u[k], t.v[k], t.p[k], t.factor[k], np.maximum(t.ref[k], KEEP_SIDE * own1),
                   np.maximum(t.ref[t.before][k], KEEP_SIDE * own2), free, rest)


def _ascend(x: np.ndarray, r: _Region, constraints, steps: int) -> np.ndarray:
    """Ascent of the soft minimum of the region's corner qualities (:func:`polish_worst`) by limited-memory
    BFGS (:data:`MEMORY` pairs; the first direction the gradient scaled by each vertex's mean side
    squared, each vertex's move at most :data:`POLISH_STEP` of its mean side): a step is halved until it
    raises the soft minimum and inverts no corner. Returned: the positions met on the way with the best
    smallest scaled Jacobian (the mesh's measure) among those whose smallest quality (with the side
    term) is no worse than on entry; the start where none beats it by :data:`MIN_GAIN`. Plain gradient
    steps, each vertex's
    scaled by its shortest side, reached on jagged_1 in 3,000 steps what this reaches in about 300."""
    moving = _Slides.of(constraints, r.free)
    idx = np.flatnonzero(r.free)
    reach = np.repeat(POLISH_STEP * _mean_side(x, r)[idx], 2)
    beta = BETA
    low, soft, q = _soft(x, r, beta)
    g = _gradient(x, r, q, low, beta)[idx].ravel()
    start, start_sj = x, _worst_jacobian(x, r)
    floor, best, best_sj, pairs, length, since = low, x, start_sj, [], 1.0, 0
    for _ in range(steps):
        d = _direction(g, pairs, reach)
        d = d * np.repeat(np.minimum(1.0, reach[0::2] / np.maximum(np.hypot(d[0::2], d[1::2]), 1e-300)), 2)
        length = min(1.0, 2.0 * length)
        for _ in range(_HALVINGS):
            trial = x.copy()
            trial[idx, :2] += (length * d).reshape(-1, 2)
            t_low, t_soft, t_q = _soft(moving(trial), r, beta)
            if t_low > 0 and t_soft > soft:
                break
            length *= 0.5
        else:
            if not pairs and beta >= BETA_MAX:
                break
            if not pairs:  # the soft minimum at its top: a sharper one, nearer the worst corner
                beta *= 2
                low, soft, q = _soft(x, r, beta)
                g = _gradient(x, r, q, low, beta)[idx].ravel()
            pairs, length = [], 1.0  # a direction that gains nothing: the memory starts afresh
            continue
        t_g = _gradient(trial, r, t_q, t_low, beta)[idx].ravel()
        step, turn = (trial - x)[idx, :2].ravel(), g - t_g
        if step @ turn > 1e-12 * (step @ step):
            pairs = (pairs + [(step, turn)])[-MEMORY:]
        x, low, soft, g = trial, t_low, t_soft, t_g
        now = _worst_jacobian(x, r) if low >= floor else -1.0
        if now > best_sj + 1e-9:
            best, best_sj, since = x, now, (0 if now > best_sj + _STALL_GAIN else since + 1)
        else:
            since += 1
        if since >= _STALL:
            break
    return best if best_sj >= start_sj + MIN_GAIN else start


def _worst_jacobian(x: np.ndarray, r: _Region) -> float:
    """The mesh's smallest corner scaled Jacobian (its measure,
    :func:`~vaultgram.meshing.quality.face_scaled_jacobians`, without the side term): the region's, or
    that of the corners it leaves (``rest``) where smaller."""
    return min(r.rest, float(corner_quality(plan_rows(x, r.u), plan_rows(x, r.v), plan_rows(x, r.p), r.factor).min()))


def _direction(g: np.ndarray, pairs: list, reach: np.ndarray) -> np.ndarray:
    """The L-BFGS ascent direction for the gradient ``g`` (two-loop recursion on the minimised negative
    soft minimum), its initial inverse Hessian ``reach`` squared (a vertex's steps scale with its edges),
    scaled by the latest pair."""
    q = -g
    alphas = []
    for s, y in reversed(pairs):
        a = (s @ q) / (y @ s)
        alphas.append(a)
        q = q - a * y
    h0 = reach * reach
    if pairs:
        s, y = pairs[-1]
        h0 = h0 * (s @ y) / (y @ (h0 * y))
    z = h0 * q
    for (s, y), a in zip(pairs, reversed(alphas)):
        z = z + s * (a - (y @ z) / (y @ s))
    return -z


def _mean_side(x: np.ndarray, r: _Region) -> np.ndarray:
    """Per vertex, the mean length of its sides in the region (0 for a vertex in none): a sliver's
    short side would stall the vertex that must move to widen it."""
    e = np.hypot(*(plan_rows(x, r.v) - plan_rows(x, r.u)).T)
    total = np.bincount(r.u, e, len(x)) + np.bincount(r.v, e, len(x))
    return total / np.maximum(np.bincount(r.u, minlength=len(x)) + np.bincount(r.v, minlength=len(x)), 1)


class _Slides(NamedTuple):
    """The free sliding vertices projected back onto their polylines in one go: per (vertex, segment of
    its polyline) pair, sorted by vertex, the vertex and the segment's start and vector; the
    constraints too long for pairs (:data:`_PAIRS` or more) are projected one by one."""

    vertex: np.ndarray
    a: np.ndarray
    ab: np.ndarray
    starts: np.ndarray
    rest: tuple

    @staticmethod
    def of(constraints, free: np.ndarray) -> _Slides:
        pairs, rest = [], []
        for c in constraints:
            verts = c.vertices[free[c.vertices]]
            poly = np.asarray(c.polyline, dtype=float)[:, :2]
            ends = np.vstack([poly, poly[:1]]) if c.closed else poly
            if not len(verts) or len(ends) < 2:
                continue
            if len(verts) * (len(ends) - 1) >= _PAIRS:
                rest.append(dataclasses.replace(c, vertices=verts))
                continue
            seg = np.arange(len(ends) - 1)
            pairs.append((np.repeat(verts, len(seg)), np.tile(ends[:-1], (len(verts), 1)),
                          np.tile(np.diff(ends, axis=0), (len(verts), 1))))
        if not pairs:
            z = np.zeros(0, dtype=np.int64)
            return _Slides(z, np.zeros((0, 2)), np.zeros((0, 2)), z, tuple(rest))
        vertex, a, ab = (np.concatenate(k) for k in zip(*pairs))
        order = np.argsort(vertex, kind="stable")
        vertex, a, ab = vertex[order], a[order], ab[order]
        return _Slides(vertex, a, ab, np.flatnonzero(np.r_[True, vertex[1:] != vertex[:-1]]), tuple(rest))

    def __call__(self, y: np.ndarray) -> np.ndarray:
        """``y`` with the sliding vertices on the nearest point of their polylines, in place."""
        if len(self.vertex):
            p = y[self.vertex, :2]
            t = np.clip(((p - self.a) * self.ab).sum(1) / np.maximum((self.ab * self.ab).sum(1), 1e-300), 0.0, 1.0)
            q = self.a + t[:, None] * self.ab
            d = ((q - p) ** 2).sum(1)
            low = np.minimum.reduceat(d, self.starts)
            hit = d <= np.repeat(low, np.diff(np.r_[self.starts, len(d)]))
            first = np.minimum.reduceat(np.where(hit, np.arange(len(d)), len(d)), self.starts)
            y[self.vertex[self.starts], :2] = q[first]
        slide(y, self.rest)
        return y


def _soft(x: np.ndarray, r: _Region, beta: float = BETA) -> tuple[float, float, np.ndarray]:
    """The region's worst corner quality (:func:`~vaultgram.meshing.optimise.corner_quality`), the soft
    minimum ``low - log(sum(exp(-BETA (q - low)))) / BETA`` of its qualities ``q``, and ``q``."""
    q = corner_quality(plan_rows(x, r.u), plan_rows(x, r.v), plan_rows(x, r.p), r.factor, r.ref1, r.ref2)
    low = float(q.min())
    return low, low - float(np.log(np.exp(-beta * (q - low)).sum())) / beta, q


def _gradient(x: np.ndarray, r: _Region, q: np.ndarray, low: float, beta: float = BETA) -> np.ndarray:
    """The gradient (n, 2) of the soft minimum (:func:`_soft`, qualities ``q``, least ``low``) with
    respect to the vertices: each corner's weight ``exp(-BETA (q - low))`` (normalised) times the
    gradient of its quality, the scaled Jacobian's (zero where capped at 1) times the side term plus,
    where a side is under its reference, the side's."""
    w = np.exp(-beta * (q - low))
    w /= w.sum()
    e1, e2 = plan_rows(x, r.v) - plan_rows(x, r.u), plan_rows(x, r.p) - plan_rows(x, r.u)
    l1, l2 = np.maximum(np.hypot(*e1.T), 1e-300), np.maximum(np.hypot(*e2.T), 1e-300)
    sine = (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]) / (l1 * l2)
    s = np.minimum(sine * r.factor, 1.0)
    t1, t2 = l1 / np.maximum(r.ref1, 1e-300), l2 / np.maximum(r.ref2, 1e-300)
    m = np.minimum(1.0, np.minimum(t1, t2))
    live = w * (sine * r.factor < 1.0) * r.factor * m
    side1 = w * ((t1 < 1) & (t1 <= t2)) * s / (l1 * np.maximum(r.ref1, 1e-300))
    side2 = w * ((t2 < 1) & (t2 < t1)) * s / (l2 * np.maximum(r.ref2, 1e-300))
    turn = (live / (l1 * l2))[:, None]
    g1 = np.column_stack([e2[:, 1], -e2[:, 0]]) * turn + e1 * (side1 - live * sine / l1 ** 2)[:, None]
    g2 = np.column_stack([-e1[:, 1], e1[:, 0]]) * turn + e2 * (side2 - live * sine / l2 ** 2)[:, None]
    n = len(x)
    return np.column_stack([np.bincount(r.v, g1[:, k], n) + np.bincount(r.p, g2[:, k], n)
                            - np.bincount(r.u, g1[:, k] + g2[:, k], n) for k in range(2)])
