"""Orthogonalising: raise the mean scaled Jacobian of a smoothed mesh (issue 12, What 4: mean at least 0.9).

Uniform Laplacian smoothing (§3.2) evens the spacing but not the angles: inside a long curved patch
the Coons map (Figure 2g) leaves rows of sheared quads that follow the waves of the patch's sides
(multiple_lobes: two patches of 189 quads at a mean of 0.73), and next to the boundary and the
singularities of a plan of many small patches the quads keep the skew of the layout (mexico_airport:
the quads on the boundary and round the singular vertices carry 95% of the shortfall from 1). The
max-min optimisation (:mod:`vaultgram.meshing.optimise`) lifts only the worst corners.

:func:`orthogonalise` descends the sum over the quads' corners of ``1 - sj`` (``sj`` the corner's
scaled Jacobian, the sine of its angle: the mean the issue measures, corner by corner), all movable
vertices at once, by gradient steps scaled by each vertex's shortest edge squared (the sum is
scale-free, so its gradient at a vertex is about its reciprocal) with an adaptive rate: a step is
taken where the sum falls, halved otherwise. The sum also weighs each quad's area against its own
before the pass (:data:`AREA_WEIGHT`): the voussoirs' areas follow the quads', and the angles alone
spread them. No face may end below the smaller of its scaled Jacobian and a floor
(:data:`MEAN_FLOOR`, or the mesh's worst face where that is better): the vertices of a face a step
takes below it go back, until none does, so the worst face and the orientation of every face are
kept. Triangles (the fans round poles, evened by
:mod:`vaultgram.meshing.fans`) and the rings of the point features (whose faces carry the point
loads' force flow into the tessellation) stay as they are; a boundary or curve vertex slides only
where its polyline runs straight between its neighbours
(:func:`vaultgram.geometry.polylines.straight_spans`), along that line, so the mesh boundary stays
as near to the plan as it was (What 5). Meshes that meet the issue's mean already
(:data:`MEAN_TARGET`), and fine meshes (:data:`MEAN_MAX_FACES`), are left as they are. Not in the
paper, whose meshes are coarser.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vaultgram.geometry.meshes import corner_arrays
from vaultgram.geometry.polylines import straight_spans
from vaultgram.meshing.fidelity import stretch_chain
from vaultgram.meshing.quality import face_scaled_jacobians

__all__ = ["orthogonalise", "MEAN_FLOOR", "MEAN_STEPS"]

#: A face better than this may lose quality down to it (or down to the mesh's worst face, where that
#: is better) when the sum gains: the worst face is kept, the good ones trade a little for the mean.
MEAN_FLOOR = 0.5
#: A mesh whose mean scaled Jacobian is at least this (issue 12's floor) is left alone: the pass trades
#: the evenness of the quads' sizes (the voussoirs' areas) for their angles, and such a mesh has
#: nothing to gain that the issue asks for.
MEAN_TARGET = 0.9
#: A mesh of more faces than this is left alone too: the descent's steps shrink with the edges, so
#: on a fine mesh it gains little for its time (multiple_lobes at 8,159 faces: 0.832 -> 0.837 in
#: 0.5 s, a third of the meshing; at 16,298: 0.822 -> 0.825 in 1.2 s), and what it moves differs
#: between resolutions (the heights of the lobes' vaults at the two then differ by 3.05% of zmax
#: next to the notches, 2.59% without). The default density gives the shared plans 500 to 1,500.
MEAN_MAX_FACES = 5000
#: The weight of the quads' areas' relative change, squared, in the descended sum: without it the
#: voussoir areas of square_point_loads spread (coefficient of variation 0.351 -> 0.429) and two of
#: its voussoirs came out concave; at 4, 0.401; at 16, 0.360 (its mean 0.892 -> 0.926, 0.908, 0.900).
AREA_WEIGHT = 16.0
#: At most this many steps; the descent stops sooner once a step gains less than :data:`MEAN_STALL`
#: of the sum.
MEAN_STEPS = 100
MEAN_STALL = 1e-4
#: No vertex moves by more than this fraction of its shortest edge in one step.
_STEP_CAP = 0.25
#: A step whose faces still go below their floors after this many rounds of reverting is not taken.
_REVERTS = 12
#: The factor that gives an equilateral triangle's corners a scaled Jacobian of 1.
_TRI = 2.0 / np.sqrt(3.0)


class _Region(NamedTuple):
    """The faces round the movable vertices: their corners (face ``face`` numbered within the region,
    vertex ``u``, next ``v``, previous ``p``; ``quad``: in a quad; ``factor``: 2 / sqrt(3) in a triangle, as in
    :func:`~vaultgram.meshing.quality.face_scaled_jacobians`),
    where each face's corners start (``starts``), the faces' floors, the ``free`` vertices, each
    vertex's number of corners in the region (at least 1), the sliding vertices and the unit ``line``
    (n, 2) each moves along (zero for the others)."""

    face: np.ndarray
    u: np.ndarray
    v: np.ndarray
    p: np.ndarray
    quad: np.ndarray
    factor: np.ndarray
    starts: np.ndarray
    floor: np.ndarray
    area: np.ndarray
    free: np.ndarray
    corners: np.ndarray
    sliding: np.ndarray
    line: np.ndarray


class _State(NamedTuple):
    """The region's sum of ``1 - sj`` over its quads' corners, its gradient (n, 2), each face's
    worst corner and each vertex's shortest edge in the region."""

    total: float
    grad: np.ndarray
    face_sj: np.ndarray
    shortest: np.ndarray


def orthogonalise(vertices: np.ndarray, faces, fixed: np.ndarray | None = None, constraints=(), still=None,
                  steps: int = MEAN_STEPS) -> np.ndarray:
    """Raise the mean scaled Jacobian of the quads by moving their vertices (not ``fixed``, not on a
    triangle, not on a face of a vertex in ``still``;
    the sliding vertices of ``constraints`` only where their polylines run straight, along them),
    keeping every face at least as good as the smaller of its scaled Jacobian and its floor
    (:data:`MEAN_FLOOR`, the worst face where better). A mesh with an inverted face (untangling
    comes first), a mean of at least :data:`MEAN_TARGET` or more than :data:`MEAN_MAX_FACES` faces
    is returned as it is.

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.meshing.quality import face_scaled_jacobians
    >>> v, f = grid_mesh(3)
    >>> inner = (v[:, 0] % 3 != 0) & (v[:, 1] % 3 != 0)
    >>> v[inner, 0] += 1.2 * (v[inner, 1] - 1.5)  # the inner vertices of a 3 x 3 grid sheared
    >>> before, after = face_scaled_jacobians(v, f), face_scaled_jacobians(orthogonalise(v, f, ~inner), f)
    >>> round(float(before.mean()), 3), round(float(after.mean()), 3), bool(after.min() >= before.min())
    (0.785, 0.923, True)
    """
    x = np.array(vertices, dtype=float)
    if len(faces) == 0 or len(faces) > MEAN_MAX_FACES:
        return x
    region = _region(x, faces, fixed, constraints, still)
    if region is None:
        return x
    return _descend(x, region, steps)


def _region(x: np.ndarray, faces, fixed, constraints, still) -> _Region | None:
    """The :class:`_Region` of :func:`orthogonalise`, or None where nothing is to move (a mean of at
    least :data:`MEAN_TARGET`, or an inverted face). The floors and areas are taken from
    :func:`_geometry`, the numbers the descent compares them with."""
    face, u, v, p = corner_arrays(faces)
    n, n_faces = len(x), len(faces)
    quad = (np.bincount(face, minlength=n_faces) == 4)[face]
    sj = face_scaled_jacobians(x, faces)
    if sj.min() <= 0 or sj.mean() >= MEAN_TARGET:
        return None
    free = np.zeros(n, dtype=bool)
    free[u[quad]] = True
    held = np.zeros(n, dtype=bool) if fixed is None else np.asarray(fixed, dtype=bool).copy()
    held[u[~quad]] = True
    if still is not None and np.any(still):
        near = np.zeros(n_faces, dtype=bool)
        near[face[np.asarray(still, dtype=bool)[u]]] = True
        held[u[near[face]]] = True
    sliding, line = _straight_slides(x, constraints, n)
    for c in constraints:
        held[np.asarray(c.vertices, dtype=np.int64)] = True
    free &= ~held | sliding
    if not free.any():
        return None
    work = np.zeros(n_faces, dtype=bool)
    work[face[free[u]]] = True
    keep = work[face]
    renumber = np.cumsum(work) - 1
    f = renumber[face[keep]]
    region = _Region(f, u[keep], v[keep], p[keep], quad[keep], np.where(quad[keep], 1.0, _TRI),
                     np.flatnonzero(np.r_[True, f[1:] != f[:-1]]), None, None, free,
                     np.maximum(np.bincount(u[keep], minlength=n), 1), sliding & free, line)
    at = _geometry(x, region._replace(area=np.ones(int(work.sum()))))
    return region._replace(floor=np.minimum(at.face_sj, max(MEAN_FLOOR, float(sj.min()))), area=at.area)


def _straight_slides(x: np.ndarray, constraints, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Per vertex, whether it slides on a straight run of its constraint's polyline
    (:func:`~vaultgram.geometry.polylines.straight_spans` of the stretch's chain), and the unit
    direction of that run (zero elsewhere)."""
    sliding, line = np.zeros(n, dtype=bool), np.zeros((n, 2))
    for c in constraints:
        chain, ids = stretch_chain(x, c)
        ok = straight_spans(chain, np.asarray(c.polyline, dtype=float), c.closed) & (ids >= 0)
        if not ok.any():
            continue
        d = np.roll(chain, -1, axis=0) - np.roll(chain, 1, axis=0)
        sliding[ids[ok]] = True
        line[ids[ok]] = d[ok] / np.hypot(*d[ok].T)[:, None]
    return sliding, line


class _Geometry(NamedTuple):
    """The region's corners at one position: sides ``e1 = v - u`` and ``e2 = p - u``, their squared
    lengths, ``|e1| |e2|``, scaled Jacobians and each face's worst (times its factor, at most 1)."""

    e1: np.ndarray
    e2: np.ndarray
    l1: np.ndarray
    l2: np.ndarray
    norm: np.ndarray
    sj: np.ndarray
    face_sj: np.ndarray
    area: np.ndarray


def _geometry(x: np.ndarray, r: _Region) -> _Geometry:
    """The :class:`_Geometry` of the region's corners at positions ``x`` (-1 at a corner with a side
    of no length)."""
    at = x[r.u, :2]
    e1, e2 = x[r.v, :2] - at, x[r.p, :2] - at
    l1, l2 = (e1 * e1).sum(axis=1), (e2 * e2).sum(axis=1)
    norm = np.sqrt(l1 * l2)
    good = norm > 0
    sj = np.where(good, (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]) / np.where(good, norm, 1.0), -1.0)
    area = 0.5 * np.add.reduceat(at[:, 0] * e1[:, 1] - at[:, 1] * e1[:, 0], r.starts)  # the shoelace formula
    return _Geometry(e1, e2, l1, l2, norm, sj, np.minimum.reduceat(np.minimum(sj * r.factor, 1.0), r.starts), area)


def _state(n: int, r: _Region, g: _Geometry) -> _State:
    """The :class:`_State` of the region given its corners' :class:`_Geometry`: ``d sj / d e1 =
    J e2 / (|e1| |e2|) - sj e1 / |e1|^2`` and ``d sj / d e2 = -J e1 / (|e1| |e2|) - sj e2 / |e2|^2``
    (``J`` the quarter turn clockwise), summed with the sign of ``-sj`` over the quads' corners."""
    w = np.where(r.quad, -1.0, 0.0) / g.norm  # d (1 - sj) / d sj, over |e1| |e2|
    a1, a2 = w * g.sj * g.norm / g.l1, w * g.sj * g.norm / g.l2
    g1x, g1y = w * g.e2[:, 1] - a1 * g.e1[:, 0], -w * g.e2[:, 0] - a1 * g.e1[:, 1]
    g2x, g2y = -w * g.e1[:, 1] - a2 * g.e2[:, 0], w * g.e1[:, 0] - a2 * g.e2[:, 1]
    ratio = np.where(r.quad[r.starts], g.area / r.area - 1.0, 0.0)
    da = (AREA_WEIGHT * ratio / r.area)[r.face]  # d/dA of the weighted (A / A0 - 1)^2, over 2
    ax, ay = da * (g.e1[:, 1] - g.e2[:, 1]), da * (g.e2[:, 0] - g.e1[:, 0])
    grad = np.column_stack([np.bincount(r.v, g1x, n) + np.bincount(r.p, g2x, n) - np.bincount(r.u, g1x + g2x - ax, n),
                            np.bincount(r.v, g1y, n) + np.bincount(r.p, g2y, n) - np.bincount(r.u, g1y + g2y - ay, n)])
    shortest = np.full(n, np.inf)
    np.minimum.at(shortest, r.u, np.minimum(g.l1, g.l2))
    total = float(np.where(r.quad, 1.0 - g.sj, 0.0).sum()) + AREA_WEIGHT * float((ratio * ratio).sum())
    return _State(total, grad, g.face_sj, np.sqrt(shortest))


def _descend(x: np.ndarray, r: _Region, steps: int) -> np.ndarray:
    """Gradient steps on the sum (:func:`orthogonalise`) with an adaptive rate: a guarded step
    (:func:`_guarded`) that lowers the sum is taken and the next tried longer, any other halved; it
    stops after ``steps``, when the rate has shrunk to nothing or a step gains less than
    :data:`MEAN_STALL` of the sum."""
    now, rate = _state(len(x), r, _geometry(x, r)), 1.0
    for _ in range(steps):
        trial = _guarded(x, _step(now, r, rate), r)
        after = _state(len(x), r, trial[1]) if trial is not None else None
        if after is not None and after.total < now.total:
            stalled = now.total - after.total < MEAN_STALL * now.total
            x, now, rate = trial[0], after, min(1.5 * rate, 1.0)
            if stalled:
                break
        else:
            rate *= 0.5
            if rate < 1e-3:
                break
    return x


def _step(now: _State, r: _Region, rate: float) -> np.ndarray:
    """The move (n, 2) of each free vertex down the gradient, ``rate`` times its shortest edge squared
    (over the number of corners the gradient sums), at most :data:`_STEP_CAP` of that edge; a sliding
    vertex's along its line."""
    h = np.where(np.isfinite(now.shortest), now.shortest, 0.0)
    step = -now.grad * (rate * h * h / r.corners)[:, None]
    along = (step * r.line).sum(axis=1)
    step = np.where(r.sliding[:, None], along[:, None] * r.line, step)
    length = np.hypot(*step.T)
    cap = _STEP_CAP * h
    step *= np.where(length > cap, cap / np.maximum(length, 1e-300), 1.0)[:, None]
    step[~r.free] = 0.0
    return step


def _guarded(x: np.ndarray, step: np.ndarray, r: _Region) -> tuple[np.ndarray, _Geometry] | None:
    """``x`` moved by ``step`` with the vertices of every face that falls below its floor put back,
    round after round (putting back may take a neighbour below), and its :class:`_Geometry`; None
    where faces still fall after :data:`_REVERTS` rounds."""
    y = x.copy()
    y[:, :2] += step
    for _ in range(_REVERTS):
        g = _geometry(y, r)
        below = g.face_sj < r.floor
        if not below.any():
            return y, g
        back = r.u[below[r.face]]
        y[back] = x[back]
    return None
