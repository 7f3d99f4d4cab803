"""Orthogonalising: raise the mean scaled Jacobian of a smoothed mesh (issue 12, What 4: mean at least 0.9).

Uniform Laplacian smoothing (§3.2) evens the spacing but not the angles: inside a long curved patch
the Coons map (Figure 2g) leaves rows of sheared quads that follow the waves of the patch's sides
(multiple_lobes: two patches of 189 quads at a mean of 0.73), and next to the boundary and the
singularities of a plan of many small patches the quads keep the skew of the layout (mexico_airport:
the quads on the boundary and round the singular vertices carry 95% of the shortfall from 1). The
max-min optimisation (:mod:`vaultgram.meshing.optimise`) lifts only the worst corners.

:func:`orthogonalise` descends the sum over the quads of ``1 - sj`` at a soft minimum of their
corners (``sj`` the corner's scaled Jacobian, the sine of its angle; the issue's mean counts each
face's worst corner, :data:`SOFT_WORST`), all movable vertices at once, by conjugate-gradient steps
(:func:`_direction`) on the gradient scaled by each vertex's shortest edge squared (the sum is
scale-free, so its gradient at a vertex is about its reciprocal) with an adaptive rate: a step is
taken where the sum falls, halved otherwise. Down the scaled gradient alone a bend of the rows
crosses a long patch one quad per step (multiple_lobes' two curved patches of 189 quads: 0.872 at
120 steps, 0.907 at 1,000); the conjugate directions carry it across in far fewer. The sum
also holds the quads' sizes relative to their neighbours' (:data:`GRADE_WEIGHT`): the jump in log
area across each side shared by two quads may shrink but not grow past what it was before the pass.
The voussoirs' areas follow the quads', and the angles alone spread them; a term on each quad's own
area (session 18) held them too, but also the grading the angles need (the four plans below the
issue's mean gained 0.008-0.015 under it, 0.010-0.041 under this one). No face may end below the
smaller of its scaled Jacobian and a floor
(:data:`MEAN_FLOOR`, or the mesh's worst face where that is better): the vertices of a face a step
takes below it go back, until none does, so the worst face and the orientation of every face are
kept. Triangles (the fans round poles, evened by
:mod:`vaultgram.meshing.fans`) and the rings of the point features (whose faces carry the point
loads' force flow into the tessellation) stay as they are; a boundary or curve vertex slides only
where its polyline runs straight between its neighbours
(:func:`vaultgram.geometry.polylines.straight_spans`), along that line, so the mesh boundary stays
as near to the plan as it was (What 5). Meshes that meet the issue's mean already
(:data:`MEAN_TARGET`), and fine meshes (:data:`MEAN_MAX_FACES`), are left as they are, and the
descent stops once the mesh's mean reaches :data:`MEAN_AIM`. Not in the paper, whose meshes are
coarser.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vaultgram.geometry.arrays import lookup
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
#: The descent stops once the mesh's mean scaled Jacobian reaches this (a little above
#: :data:`MEAN_TARGET`, so that what later stages do to the vertices' last digits cannot take it back
#: under), for the reason above: beyond the issue's mean the angles gain only what the voussoirs'
#: evenness pays for (the conjugate descent run to its end takes square_point_loads to 0.938, its
#: voussoir area CV at rhythm 2 to 0.422 against its bound 0.382, and four voussoirs concave).
MEAN_AIM = 0.902
#: A mesh of more faces than this is left alone too: the descent's steps shrink with the edges, so
#: on a fine mesh it gains little for its time (multiple_lobes at 8,159 faces: 0.832 -> 0.837 in
#: 0.5 s, a third of the meshing; at 16,298: 0.822 -> 0.825 in 1.2 s), and what it moves differs
#: between resolutions (the heights of the lobes' vaults at the two then differ by 3.05% of zmax
#: next to the notches, 2.59% without). The default density gives the shared plans 500 to 1,500.
MEAN_MAX_FACES = 5000
#: The weight of the size term: per pair of quads that share a side, the growth of the jump of their
#: sizes (``|log A - log A'|`` above its value before the pass), squared. The angles alone spread the
#: quads' sizes and the voussoirs' with them (square_point_loads: voussoir area CV 0.360 -> 0.419 and
#: concave voussoirs); the term lets the sizes grade, and even out, but not jump where they did not.
#: square_point_loads' voussoirs are the touchstone (their area CV at rhythm 4, bound 0.328: 0.330 at
#: 4.5, 0.324 at 5, 0.298 at 5.5); heavier weights hold the angles back (fig7_curves 0.902 at 4.5,
#: 0.899 at 6, at 100 steps).
GRADE_WEIGHT = 5.5
#: The sharpness of the soft minimum of a quad's corners (:func:`_soft_worst`): the issue's mean is
#: over the faces' worst corners, so the descent weighs each corner by how near it is to its face's
#: worst (at 0.5, nearly even weights: mexico_airport 0.880, fig7_curves 0.891; at 10, 0.890, 0.901).
SOFT_WORST = 10.0
#: At most this many steps; the descent stops sooner once a step gains less than :data:`MEAN_STALL`
#: of the sum, or at :data:`MEAN_AIM`. multiple_lobes needs about 350 steps to reach the aim (0.893 at
#: 200; 1e-5 and 1e-6 stop it at 0.894: a conjugate step after a restart may gain little).
#: square_point_loads, whose point loads' fans are evened at the floor
#: (:func:`vaultgram.meshing.densities.point_load_caps`), starts at 0.865 and climbs slowly past its
#: rings, which stay: 0.898 at 400 steps, 0.8997 at 600, 0.9009 at 800, 0.9016 at 1,000 (1.9 s of
#: CPU for its mesh against 1.15 s at 400). Meshes that reach the aim sooner stop there as before.
MEAN_STEPS = 1000
MEAN_STALL = 1e-7
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
    (n, 2) each moves along (zero for the others), the ``pairs`` of quads that share a side and their
    ``jump`` in log area before the pass, and the ``goal``: the sum of the region's faces' scaled
    Jacobians at which the mesh's mean reaches :data:`MEAN_AIM`."""

    face: np.ndarray
    u: np.ndarray
    v: np.ndarray
    p: np.ndarray
    quad: np.ndarray
    factor: np.ndarray
    starts: np.ndarray
    floor: np.ndarray
    free: np.ndarray
    corners: np.ndarray
    sliding: np.ndarray
    line: np.ndarray
    pairs: np.ndarray
    jump: np.ndarray
    goal: float


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
    is returned as it is; the others are worked on until their mean reaches :data:`MEAN_AIM` (or the
    descent stops). A sheared 3 x 3 grid, squared to a mean of 1.0 when the descent ran on, stops
    past the aim:

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.meshing.quality import face_scaled_jacobians
    >>> v, f = grid_mesh(3)
    >>> inner = (v[:, 0] % 3 != 0) & (v[:, 1] % 3 != 0)
    >>> v[inner, 0] += 1.2 * (v[inner, 1] - 1.5)  # the inner vertices of a 3 x 3 grid sheared
    >>> before, after = face_scaled_jacobians(v, f), face_scaled_jacobians(orthogonalise(v, f, ~inner), f)
    >>> round(float(before.mean()), 3), round(float(after.mean()), 3), bool(after.min() >= before.min())
    (0.785, 0.911, True)
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
                     np.flatnonzero(np.r_[True, f[1:] != f[:-1]]), None, free,
                     np.maximum(np.bincount(u[keep], minlength=n), 1), sliding & free, line,
                     _side_pairs(u[keep], v[keep], f, quad[keep], n), None, None)
    at = _geometry(x, region)
    return region._replace(floor=np.minimum(at.face_sj, max(MEAN_FLOOR, float(sj.min()))),
                           jump=np.abs(_jumps(at.area, region.pairs)),
                           goal=MEAN_AIM * n_faces - float(sj[~work].sum()))


def _side_pairs(u: np.ndarray, v: np.ndarray, face: np.ndarray, quad: np.ndarray, n: int) -> np.ndarray:
    """The pairs (m, 2) of quads (``face``'s numbers) that share a side, found as a halfedge ``u -> v``
    with ``u < v`` and its twin ``v -> u`` (sorted keys, :func:`~vaultgram.geometry.arrays.lookup`):
    the neighbours whose sizes :func:`_size_term` compares.

    >>> from vaultgram.geometry.meshes import corner_arrays, grid_mesh
    >>> face, u, v, _ = corner_arrays(grid_mesh(2)[1])  # faces 0 1 / 2 3
    >>> sorted(map(sorted, _side_pairs(u, v, face, np.ones(len(u), dtype=bool), 9).tolist()))
    [[0, 1], [0, 2], [1, 3], [2, 3]]
    """
    up, down = quad & (u < v), quad & (u > v)
    key_up, key_down = u[up] * n + v[up], v[down] * n + u[down]
    order = np.argsort(key_down, kind="stable")
    pos, found = lookup(key_down[order], key_up)
    return np.column_stack([face[up][found], face[down][order][pos[found]]])


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
    """The :class:`_State` of the region given its corners' :class:`_Geometry`: the angle term
    (:func:`_soft_worst`) through ``d sj / d e1 = J e2 / (|e1| |e2|) - sj e1 / |e1|^2`` and
    ``d sj / d e2 = -J e1 / (|e1| |e2|) - sj e2 / |e2|^2`` (``J`` the quarter turn clockwise), and the
    size term (:func:`_size_term`) through the shoelace formula, ``d A / d u = J (v - p) / 2``."""
    angle, by_sj = _soft_worst(r, g)
    w = np.where(r.quad, by_sj, 0.0) / g.norm  # d angle / d sj, over |e1| |e2|
    a1, a2 = w * g.sj * g.norm / g.l1, w * g.sj * g.norm / g.l2
    g1x, g1y = w * g.e2[:, 1] - a1 * g.e1[:, 0], -w * g.e2[:, 0] - a1 * g.e1[:, 1]
    g2x, g2y = -w * g.e1[:, 1] - a2 * g.e2[:, 0], w * g.e1[:, 0] - a2 * g.e2[:, 1]
    size, by_area = _size_term(r, g.area)
    da = 0.5 * by_area[r.face]
    ax, ay = da * (g.e1[:, 1] - g.e2[:, 1]), da * (g.e2[:, 0] - g.e1[:, 0])
    grad = np.column_stack([np.bincount(r.v, g1x, n) + np.bincount(r.p, g2x, n) - np.bincount(r.u, g1x + g2x - ax, n),
                            np.bincount(r.v, g1y, n) + np.bincount(r.p, g2y, n) - np.bincount(r.u, g1y + g2y - ay, n)])
    shortest = np.full(n, np.inf)
    np.minimum.at(shortest, r.u, np.minimum(g.l1, g.l2))
    return _State(angle + size, grad, g.face_sj, np.sqrt(shortest))


def _soft_worst(r: _Region, g: _Geometry) -> tuple[float, np.ndarray]:
    """The angle term, four times the sum over the quads of ``1 - m``, ``m`` the soft minimum
    ``-log(sum exp(-k sj)) / k`` of the quad's corners (``k`` :data:`SOFT_WORST`; a little below the
    worst corner, the number the issue's mean counts), and its derivative by each corner's ``sj``
    (minus four times the corner's share of ``exp(-k sj)`` in its face: the worst corner weighs most).

    >>> from vaultgram.geometry.meshes import corner_arrays
    >>> x = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.5, 1.0]])  # corners' sj 0.894, 1, 1, 0.894
    >>> face, u, v, p = corner_arrays([(0, 1, 2, 3)])
    >>> r = _Region(face, u, v, p, np.ones(4, dtype=bool), np.ones(4), np.array([0]), *[None] * 8)
    >>> angle, by_sj = _soft_worst(r, _geometry(x, r))
    >>> round(angle, 3), np.round(by_sj, 2).tolist()
    (0.819, [-1.48, -0.52, -0.52, -1.48])
    """
    low = np.minimum.reduceat(g.sj, r.starts)
    e = np.exp(-SOFT_WORST * (g.sj - low[r.face]))
    total = np.add.reduceat(e, r.starts)
    soft = low - np.log(total) / SOFT_WORST
    return float(4.0 * np.where(r.quad[r.starts], 1.0 - soft, 0.0).sum()), -4.0 * e / total[r.face]


def _jumps(area: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """Per pair of quads that share a side (:func:`_side_pairs`), the log of the ratio of their areas."""
    log = np.log(np.maximum(area, 1e-300))
    return log[pairs[:, 0]] - log[pairs[:, 1]]


def _size_term(r: _Region, area: np.ndarray) -> tuple[float, np.ndarray]:
    """The size term, :data:`GRADE_WEIGHT` times the sum over the pairs of quads that share a side of
    the growth of their jump (:func:`_jumps`, in absolute value) above its value before the pass
    (zero where it is no larger), squared; and its derivative by each face's area. Graded sizes, and
    sizes the angles even out, cost nothing: only a new step in size between neighbours, which the
    voussoirs built of those quads would show, does."""
    jump = _jumps(area, r.pairs)
    grown = np.sign(jump) * np.maximum(np.abs(jump) - r.jump, 0.0)
    by_log = np.bincount(r.pairs[:, 0], grown, len(area)) - np.bincount(r.pairs[:, 1], grown, len(area))
    return GRADE_WEIGHT * float((grown * grown).sum()), 2.0 * GRADE_WEIGHT * by_log / area


def _descend(x: np.ndarray, r: _Region, steps: int) -> np.ndarray:
    """Conjugate-gradient steps on the sum (:func:`orthogonalise`) with an adaptive rate: a guarded
    step (:func:`_guarded`) along the direction (:func:`_direction`) that lowers the sum is taken and
    the next tried longer, any other halved and the direction started again down the gradient; it
    stops after ``steps``, when the rate has shrunk to nothing, a step gains less than
    :data:`MEAN_STALL` of the sum or the faces' scaled Jacobians add up to the region's goal (the mesh's
    mean at :data:`MEAN_AIM`). Keeping the direction after a refused step (halving the rate only)
    took half the steps on multiple_lobes but longer strides elsewhere: square_point_loads stopped at
    0.905 after four steps with four voussoirs concave."""
    now, rate = _state(len(x), r, _geometry(x, r)), 1.0
    down = _preconditioned(now, r)
    direction = down
    for _ in range(steps):
        trial = _guarded(x, _step(direction, now, r, rate), r)
        after = _state(len(x), r, trial[1]) if trial is not None else None
        if after is not None and after.total < now.total:
            stalled = now.total - after.total < MEAN_STALL * now.total
            x, rate = trial[0], min(1.5 * rate, 1.0)
            old, old_down, now, down = now, down, after, _preconditioned(after, r)
            direction = _direction(now.grad, down, old.grad, old_down, direction)
            if stalled or trial[1].face_sj.sum() >= r.goal:
                break
        else:
            rate, direction = 0.5 * rate, down
            if rate < 1e-3:
                break
    return x


def _preconditioned(now: _State, r: _Region) -> np.ndarray:
    """Minus the gradient scaled by each free vertex's shortest edge squared over its number of
    corners (the sum is scale-free, so its gradient at a vertex is about its reciprocal), along its
    line for a sliding vertex, zero for the others."""
    h = np.where(np.isfinite(now.shortest), now.shortest, 0.0)
    down = -now.grad * (h * h / r.corners)[:, None]
    along = (down * r.line).sum(axis=1)
    down = np.where(r.sliding[:, None], along[:, None] * r.line, down)
    down[~r.free] = 0.0
    return down


def _direction(grad: np.ndarray, down: np.ndarray, old_grad: np.ndarray, old_down: np.ndarray,
               direction: np.ndarray) -> np.ndarray:
    """The next conjugate direction, ``down + beta direction`` (Polak-Ribiere with the preconditioner
    of :func:`_preconditioned`, ``down = -P grad``): ``beta = grad . P (grad - old_grad) / old_grad .
    P old_grad``, at least 0; ``down`` itself (a restart) where that would not go downhill.

    >>> g, old = np.array([[1.0, 0.0]]), np.array([[2.0, 0.0]])  # P = 1: down = -g
    >>> _direction(g, -g, old, -old, np.array([[-2.0, 1.0]])).tolist()  # beta = (1 - 2) / 4: restart
    [[-1.0, 0.0]]
    >>> _direction(g, -g, -old, old, np.array([[-2.0, 1.0]])).tolist()  # beta = 3 / 4
    [[-2.5, 0.75]]
    """
    scale = -float((old_grad * old_down).sum())
    if scale <= 0:
        return down
    beta = max(float((grad * (old_down - down)).sum()) / scale, 0.0)
    conjugate = down + beta * direction
    return conjugate if float((grad * conjugate).sum()) < 0 else down


def _step(direction: np.ndarray, now: _State, r: _Region, rate: float) -> np.ndarray:
    """The move (n, 2) of each free vertex, ``rate`` times ``direction``, at most :data:`_STEP_CAP` of
    its shortest edge."""
    h = np.where(np.isfinite(now.shortest), now.shortest, 0.0)
    step = rate * direction
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
