"""Untangling: repair the faces that Laplacian smoothing leaves folded or nearly degenerate.

Uniform Laplacian smoothing (:mod:`vaultgram.meshing.smoothing`, §3.2) can leave faces folded next to
concave boundaries: its fixed point lies outside the valid region there. :func:`untangle` then works
on those faces only, by gradient steps on their corners' scaled Jacobians. Not in the paper: the
paper's meshes are coarser.
"""

from __future__ import annotations

import dataclasses
from typing import NamedTuple

import numpy as np

from vaultgram.geometry.arrays import pieces
from vaultgram.geometry.meshes import corner_angles, corner_arrays, corner_vectors
from vaultgram.geometry.polygons import cross_z
from vaultgram.meshing.quadmesh import slide

__all__ = ["untangle", "improve_shapes", "UNTANGLE_TARGET", "SHAPE_TARGET"]

#: Untangling aims at this scaled Jacobian (sine of the corner angle) at every corner it works on.
UNTANGLE_TARGET = 0.1
#: Untangling steps, and the largest move per step as a fraction of the shortest incident edge.
UNTANGLE_STEPS = 300
UNTANGLE_STEP = 0.1
#: :func:`improve_shapes` aims at this scaled Jacobian, in at most this many steps; it stops after
#: SHAPE_STALL steps in a row that each gained less than 0.1% of its objective.
SHAPE_TARGET = 0.3
SHAPE_STEPS = 60
SHAPE_STALL = 10


def untangle(
    vertices: np.ndarray,
    faces,
    fixed: np.ndarray | None = None,
    constraints=(),
    target: float = UNTANGLE_TARGET,
    steps: int = UNTANGLE_STEPS,
    power: int = 1,
) -> np.ndarray:
    """Push inverted and nearly degenerate faces back to a valid shape, where smoothing cannot.

    Uniform Laplacian smoothing has folded fixed points next to concave boundaries (a thin patch
    wrapping a hole): the barycentre of a vertex's neighbours lies outside its valid region. This
    pass works only on the faces with a corner whose scaled Jacobian ``c / (|e1| |e2|)`` is below
    ``target`` (less at a vertex whose corners cannot all be that wide: :func:`_corner_targets`) and
    on the ring of vertices around them. Each step moves those vertices down the gradient of the
    sum of the corner deficits ``target - c / (|e1| |e2|)`` (the gradient of the cross product
    ``c``, scaled by ``|e1| |e2|``), each by at most :data:`UNTANGLE_STEP` of its shortest edge,
    keeps fixed vertices and projects sliding ones back onto their polylines. A step is taken when it
    leaves fewer inverted corners, or as many and a smaller total deficit; otherwise it is halved.
    It stops when no corner is below its target, the step has shrunk to nothing, or after ``steps``
    steps, and returns the input unchanged when nothing is below target (good meshes are not
    touched). Vectorised over corners. ``power`` 2 descends the sum of squared deficits instead (the
    worst corners weigh most; :func:`improve_shapes`).

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.meshing.quality import face_scaled_jacobians
    >>> v, f = grid_mesh(2)
    >>> v[4, :2] = [1.9, 1.9]  # the centre of a 2 x 2 grid dragged near the corner (2, 2)
    >>> fixed = np.ones(9, bool); fixed[4] = False
    >>> x = untangle(v, f, fixed)
    >>> bool(face_scaled_jacobians(v, f).min() < 0 < face_scaled_jacobians(x, f).min())
    True
    >>> np.array_equal(x[fixed], v[fixed])
    True
    """
    x = np.array(vertices, dtype=float)
    if len(faces) == 0:
        return x
    corners = corner_arrays(faces)
    return _untangled(x, corners, len(faces), _scaled_jacobians(x, *corners[1:]), fixed, constraints, target, steps,
                      power)


def _untangled(x: np.ndarray, corners: tuple, n_faces: int, sj: np.ndarray, fixed, constraints, target: float,
               steps: int, power: int) -> np.ndarray:
    """:func:`untangle` of ``x`` (the caller's copy) given its faces' corner arrays and number and the
    scaled Jacobians ``sj`` of the corners. A corner's goal is at most ``target``: with no corner below
    it (a fine mesh's smoothing leaves none), no angle is needed."""
    face_of, u, v, p = corners
    if not (sj < target).any():
        return x
    goal = _corner_targets(x, u, v, p, len(x), target)
    bad = np.zeros(n_faces, dtype=bool)
    bad[face_of[sj < goal]] = True
    if not bad.any():
        return x
    keep = np.asarray(fixed, dtype=bool).copy() if fixed is not None else np.zeros(len(x), dtype=bool)
    region = _region(face_of, u, v, p, bad, keep, goal)
    if power == 1:
        return _descend(x, region, _Settle(keep, x[keep].copy(), constraints), steps)
    return _descend(x, region, _Settle(keep, x[keep].copy(), _within(constraints, region.free)), steps, power,
                    SHAPE_STALL)


def improve_shapes(vertices: np.ndarray, faces, fixed: np.ndarray | None = None, constraints=(),
                   target: float = SHAPE_TARGET, steps: int = SHAPE_STEPS) -> np.ndarray:
    """Widen the corners of an untangled mesh that are still narrow (a scaled Jacobian below
    ``target``): :func:`untangle` on the sum of squared deficits, so that the worst corners move
    most, taking no step that inverts a corner. A mesh with inverted faces is returned as it is
    (untangling comes first).

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.meshing.quality import face_scaled_jacobians
    >>> v, f = grid_mesh(2)
    >>> v[4, :2] = [1.45, 1.45]  # the centre of a 2 x 2 grid pulled towards the corner (2, 2)
    >>> fixed = np.ones(9, bool); fixed[4] = False
    >>> before, after = face_scaled_jacobians(v, f).min(), face_scaled_jacobians(improve_shapes(v, f, fixed), f).min()
    >>> bool(0 < before < 0.3 <= after)
    True
    """
    x = np.array(vertices, dtype=float)
    if len(faces) == 0:
        return x
    corners = corner_arrays(faces)
    sj = _scaled_jacobians(x, *corners[1:])
    if (sj <= 0).any():
        return x
    return _untangled(x, corners, len(faces), sj, fixed, constraints, target, steps, power=2)


def _within(constraints, free: np.ndarray) -> tuple:
    """The sliding constraints restricted to the vertices that move (the others stay on their
    polylines): each step projects only those."""
    out = (dataclasses.replace(c, vertices=c.vertices[free[c.vertices]]) for c in constraints)
    return tuple(c for c in out if len(c.vertices))


class _Corners(NamedTuple):
    """Per corner (vertex ``u``, next ``v``, previous ``p``): the edge vectors ``e1 = v - u`` and
    ``e2 = p - u``, their lengths and the scaled Jacobian ``(e1 x e2) / (|e1| |e2|)``."""

    e1: np.ndarray
    e2: np.ndarray
    l1: np.ndarray
    l2: np.ndarray
    sj: np.ndarray


def _corners(x, u, v, p) -> _Corners:
    """The corner geometry of :class:`_Corners`."""
    e1, e2 = corner_vectors(x, u, v, p)
    l1, l2 = np.hypot(*e1.T), np.hypot(*e2.T)
    return _Corners(e1, e2, l1, l2, cross_z(e1, e2) / np.maximum(l1 * l2, 1e-300))


def _scaled_jacobians(x, u, v, p) -> np.ndarray:
    """The scaled Jacobians of :class:`_Corners` alone, computed a cache-sized piece at a time
    (:func:`~vaultgram.geometry.arrays.pieces`): what untangling tests every corner of the mesh with."""
    xy = np.ascontiguousarray(x[:, :2])
    sj = np.empty(len(u))
    for part in pieces(len(u)):
        sj[part] = _corners(xy, u[part], v[part], p[part]).sj
    return sj


def _corner_targets(x, u, v, p, n, target: float) -> np.ndarray:
    """Per corner, the scaled Jacobian to aim at: ``target``, or half the sine of the mean corner
    angle at its vertex where that is smaller (the corners of a pole's fan of many triangles, or at
    a sharp domain corner, cannot all be wide)."""
    angle = np.abs(corner_angles(x, u, v, p))
    corners = np.bincount(u, minlength=n)
    mean = np.bincount(u, weights=angle, minlength=n) / np.maximum(corners, 1)
    return np.minimum(target, 0.5 * np.sin(np.minimum(mean, np.pi / 2)))[u]


class _Region(NamedTuple):
    """What untangling works on: the corners ``(u, v, p)`` of the faces around the bad ones with their
    target scaled Jacobians ``goal``, and the ``free`` vertices it may move (n,)."""

    u: np.ndarray
    v: np.ndarray
    p: np.ndarray
    goal: np.ndarray
    free: np.ndarray


def _region(face_of, u, v, p, bad: np.ndarray, keep: np.ndarray, goal: np.ndarray) -> _Region:
    """The bad faces and the faces around them (sharing a vertex); their vertices move unless kept."""
    n = len(keep)
    near = np.zeros(n, dtype=bool)
    near[u[bad[face_of]]] = True
    around = np.zeros(len(bad), dtype=bool)
    around[face_of[near[u]]] = True
    free = np.zeros(n, dtype=bool)
    free[u[around[face_of]]] = True
    free &= ~keep
    work = around[face_of]  # corners of the faces in the region
    return _Region(u[work], v[work], p[work], goal[work], free)


class _Settle(NamedTuple):
    """After each trial step: fixed vertices back to their ``anchor`` positions, sliding ones
    projected onto their polylines."""

    keep: np.ndarray
    anchor: np.ndarray
    constraints: tuple

    def __call__(self, y: np.ndarray) -> np.ndarray:
        slide(y, self.constraints)
        y[self.keep] = self.anchor
        return y


class _Deficits(NamedTuple):
    """The region's corners at one position: their geometry, how far each is below its target
    (``deficit``), ``|e1| |e2|`` (``scale``) and the number of inverted corners."""

    corners: _Corners
    deficit: np.ndarray
    scale: np.ndarray
    inverted: int


def _deficits(y: np.ndarray, region: _Region) -> _Deficits:
    """The :class:`_Deficits` of the region's corners at positions ``y``."""
    c = _corners(y, region.u, region.v, region.p)
    scale = np.maximum(c.l1 * c.l2, 1e-300)
    return _Deficits(c, np.maximum(region.goal - c.sj, 0.0), scale, int((c.sj <= 0).sum()))


def _descend(x: np.ndarray, region: _Region, settle: _Settle, steps: int, power: int = 1,
             stall_limit: int | None = None) -> np.ndarray:
    """Gradient steps with an adaptive rate on the sum of the deficits to the ``power``: a step that
    leaves fewer inverted corners, or as many and a smaller sum (with ``power`` 2: and its worst
    corner no worse), is taken (and the next tried longer); any other is halved. With
    ``stall_limit``, it stops once that many steps in a row gained less than a thousandth of the sum
    each (the targets out of reach)."""
    rate, stall = 1.0, 0
    for _ in range(steps):
        now = _deficits(x, region)
        total = (now.deficit ** power).sum()
        if total == 0 or rate < 1e-3 or stall_limit is not None and stall >= stall_limit:
            break
        trial = x.copy()
        trial[:, :2] += _step(len(x), now, region, rate, power)
        trial = settle(trial)
        after = _deficits(trial, region)
        gained = total - (after.deficit ** power).sum()
        kept = power == 1 or after.corners.sj.min() >= now.corners.sj.min()  # the worst corner no worse
        if after.inverted < now.inverted or after.inverted == now.inverted and gained > 0 and kept:
            x, rate = trial, min(rate * 1.5, 1.0)
            stall = stall + 1 if after.inverted == now.inverted and gained < 1e-3 * total else 0
        else:
            rate *= 0.5
    return x


def _step(n: int, d: _Deficits, region: _Region, rate: float, power: int = 1) -> np.ndarray:
    """The move (n, 2) of each free vertex down the gradient of the total deficit (to the ``power``,
    the weights scaled so that the worst corner's is as with power 1), scaled by ``rate`` times its
    shortest edge squared and capped at :data:`UNTANGLE_STEP` of that edge."""
    c = d.corners
    weight = (d.deficit > 0) if power == 1 else (d.deficit / max(float(d.deficit.max()), 1e-12)) ** (power - 1)
    w = (weight / d.scale)[:, None]
    gv = np.column_stack([c.e2[:, 1], -c.e2[:, 0]]) * w
    gp = np.column_stack([-c.e1[:, 1], c.e1[:, 0]]) * w
    grad = np.zeros((n, 2))
    np.add.at(grad, region.v, gv)
    np.add.at(grad, region.p, gp)
    np.add.at(grad, region.u, -(gv + gp))
    shortest = np.full(n, np.inf)
    np.minimum.at(shortest, region.u, np.minimum(c.l1, c.l2))
    shortest[~np.isfinite(shortest)] = 0.0  # vertices without a corner in the region
    step = grad * (rate * shortest * shortest)[:, None]
    length = np.hypot(*step.T)
    limit = UNTANGLE_STEP * shortest
    step *= np.where(length > limit, limit / np.maximum(length, 1e-300), 1.0)[:, None]
    step[~region.free] = 0.0
    return step
