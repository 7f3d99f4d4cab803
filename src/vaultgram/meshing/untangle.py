"""Untangling: repair the faces that Laplacian smoothing leaves folded or nearly degenerate.

Uniform Laplacian smoothing (:mod:`vaultgram.meshing.smoothing`, §3.2) can leave faces folded next to
concave boundaries: its fixed point lies outside the valid region there. :func:`untangle` then works
on those faces only, by gradient steps on their corners' scaled Jacobians. Not in the paper: the
paper's meshes are coarser.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.meshes import corner_arrays
from vaultgram.meshing.quadmesh import slide

__all__ = ["untangle", "UNTANGLE_TARGET"]

#: Untangling aims at this scaled Jacobian (sine of the corner angle) at every corner it works on.
UNTANGLE_TARGET = 0.1
#: Untangling steps, and the largest move per step as a fraction of the shortest incident edge.
UNTANGLE_STEPS = 300
UNTANGLE_STEP = 0.1


def untangle(
    vertices: np.ndarray,
    faces,
    fixed: np.ndarray | None = None,
    constraints=(),
    target: float = UNTANGLE_TARGET,
    steps: int = UNTANGLE_STEPS,
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
    touched). Vectorised over corners.
    """
    x = np.array(vertices, dtype=float)
    if len(faces) == 0:
        return x
    n = len(x)
    face_of, u, v, p = corner_arrays(faces)
    goal = _corner_targets(x, u, v, p, n, target)
    bad = np.zeros(len(faces), dtype=bool)
    bad[face_of[_corners(x, u, v, p)[-1] < goal]] = True
    if not bad.any():
        return x
    keep = np.asarray(fixed, dtype=bool).copy() if fixed is not None else np.zeros(n, dtype=bool)
    # the region: vertices of the bad faces and of the faces around them
    near = np.zeros(n, dtype=bool)
    near[u[bad[face_of]]] = True
    around = np.zeros(len(faces), dtype=bool)
    around[face_of[near[u]]] = True
    free = np.zeros(n, dtype=bool)
    free[u[around[face_of]]] = True
    free &= ~keep
    work = around[face_of]  # corners of the faces in the region
    fu, fv, fp, goal = u[work], v[work], p[work], goal[work]

    def deficits(y):
        e1, e2, l1, l2, sj = _corners(y, fu, fv, fp)
        scale = np.maximum(l1 * l2, 1e-300)
        return np.maximum(goal - sj, 0.0), e1, e2, l1, l2, scale, int((sj <= 0).sum())

    def settle(y):
        slide(y, constraints)
        y[keep] = vertices[keep]
        return y

    rate = 1.0
    for _ in range(steps):
        deficit, e1, e2, l1, l2, scale, inverted = deficits(x)
        total = deficit.sum()
        if total == 0 or rate < 1e-3:
            break
        w = ((deficit > 0) / scale)[:, None]
        gv = np.column_stack([e2[:, 1], -e2[:, 0]]) * w
        gp = np.column_stack([-e1[:, 1], e1[:, 0]]) * w
        grad = np.zeros((n, 2))
        np.add.at(grad, fv, gv)
        np.add.at(grad, fp, gp)
        np.add.at(grad, fu, -(gv + gp))
        shortest = np.full(n, np.inf)
        np.minimum.at(shortest, fu, np.minimum(l1, l2))
        shortest[~np.isfinite(shortest)] = 0.0  # vertices without a corner in the region
        step = grad * (rate * shortest * shortest)[:, None]
        length = np.hypot(*step.T)
        limit = UNTANGLE_STEP * shortest
        step *= np.where(length > limit, limit / np.maximum(length, 1e-300), 1.0)[:, None]
        step[~free] = 0.0
        trial = x.copy()
        trial[:, :2] += step
        trial = settle(trial)
        after = deficits(trial)
        # accept a step with fewer inverted corners, or as many and less deficit; then try longer
        if after[-1] < inverted or after[-1] == inverted and after[0].sum() < total:
            x, rate = trial, min(rate * 1.5, 1.0)
        else:
            rate *= 0.5
    return x


def _corners(x, u, v, p):
    """Per corner (vertex ``u``, next ``v``, previous ``p``): the two edge vectors, their lengths and
    the scaled Jacobian ``(e1 x e2) / (|e1| |e2|)``."""
    e1, e2 = x[v, :2] - x[u, :2], x[p, :2] - x[u, :2]
    l1, l2 = np.hypot(*e1.T), np.hypot(*e2.T)
    sj = (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]) / np.maximum(l1 * l2, 1e-300)
    return e1, e2, l1, l2, sj


def _corner_targets(x, u, v, p, n, target: float) -> np.ndarray:
    """Per corner, the scaled Jacobian to aim at: ``target``, or half the sine of the mean corner
    angle at its vertex where that is smaller (the corners of a pole's fan of many triangles, or at
    a sharp domain corner, cannot all be wide)."""
    e1, e2 = x[v, :2] - x[u, :2], x[p, :2] - x[u, :2]
    angle = np.abs(np.arctan2(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0], (e1 * e2).sum(1)))
    total = np.bincount(u, weights=angle, minlength=n)
    mean = total[u] / np.bincount(u, minlength=n)[u]
    return np.minimum(target, 0.5 * np.sin(np.minimum(mean, np.pi / 2)))
