"""Constrained uniform Laplacian smoothing (paper §3.2, Figure 2h; Botsch et al. [12]).

"A uniform Laplacian smoothing can be applied, which iteratively moves each vertex towards the
barycentre of its neighbouring vertices. Constraints are added to respect the boundaries: vertices at
the boundary corners remain fixed and other vertices lying on the boundaries are projected back on it
after each iteration, to allow them to slide along it. Usually, a small number of iterations is
sufficient to obtain a globally smooth mesh." (§3.2) During smoothing, feature points stay fixed and
curve-feature vertices are projected onto their curve (§4.1, §4.2).

One iteration is one sparse matrix product ``x <- D^-1 A x`` (``A`` the vertex adjacency of the mesh
edges, ``D`` the degrees), fixed vertices reset, then each :class:`SlideConstraint`'s vertices
projected onto its polyline: the nearest point over all segments, computed for all vertices of the
constraint at once (:func:`project_to_polyline`). No Python loop runs over vertices.

Uniform Laplacian smoothing can leave faces folded next to concave boundaries (its fixed point lies
outside the valid region there); :func:`untangle` then works on those faces only, by gradient steps
on their corners' scaled Jacobians (not in the paper: the paper's meshes are coarser).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from vaultgram.geometry.meshes import corner_arrays

__all__ = ["adjacency", "laplacian_smooth", "untangle", "project_to_polyline", "DEFAULT_ITERATIONS"]

#: Default number of iterations: smooths the seams between patches visibly without drifting far from
#: the Coons layout (the global shape of the layout comes from the patches, not from smoothing).
DEFAULT_ITERATIONS = 20

_CHUNK = 2_000_000  # points x segments per block in the projection
_MAX_REVERTS = 8

#: Untangling aims at this scaled Jacobian (sine of the corner angle) at every corner it works on.
UNTANGLE_TARGET = 0.1
#: Untangling steps, and the largest move per step as a fraction of the shortest incident edge.
UNTANGLE_STEPS = 300
UNTANGLE_STEP = 0.1


def adjacency(n: int, faces) -> sp.csr_matrix:
    """Symmetric 0/1 vertex adjacency (``n x n``) of the edges of ``faces``."""
    _, u, v, _ = corner_arrays(faces)
    a = sp.coo_matrix((np.ones(len(u)), (u, v)), shape=(n, n)).tocsr()
    a = a + a.T
    a.data[:] = 1.0
    return a


def boundary_adjacency(n: int, faces) -> sp.csr_matrix:
    """Symmetric 0/1 adjacency of the boundary edges (half-edges without twin) of ``faces``."""
    _, u, v, _ = corner_arrays(faces)
    code = u * n + v
    free = ~np.isin(v * n + u, code)
    a = sp.coo_matrix((np.ones(int(free.sum())), (u[free], v[free])), shape=(n, n)).tocsr()
    a = a + a.T
    a.data[:] = 1.0
    return a


def project_to_polyline(points: np.ndarray, poly: np.ndarray, closed: bool = False) -> np.ndarray:
    """The nearest point of a polyline to each of ``points`` (vectorised over points and segments)."""
    points = np.asarray(points, dtype=float)
    a = np.asarray(poly, dtype=float)
    b = np.roll(a, -1, axis=0) if closed else a[1:]
    a = a if closed else a[:-1]
    if len(a) == 0:
        return np.repeat(poly[:1], len(points), axis=0)
    ab = b - a
    ab2 = np.maximum((ab * ab).sum(1), 1e-300)
    out = np.empty_like(points)
    step = max(1, _CHUNK // len(a))
    for k in range(0, len(points), step):
        p = points[k:k + step, None, :]
        t = np.clip(((p - a) * ab).sum(-1) / ab2, 0.0, 1.0)
        q = a + t[..., None] * ab
        d = ((q - p) ** 2).sum(-1)
        best = np.argmin(d, axis=1)
        out[k:k + step] = q[np.arange(len(best)), best]
    return out


def laplacian_smooth(
    vertices: np.ndarray,
    faces,
    iterations: int = DEFAULT_ITERATIONS,
    fixed: np.ndarray | None = None,
    constraints=(),
    tangential: bool = True,
    safe: bool = True,
) -> np.ndarray:
    """Constrained uniform Laplacian smoothing.

    Parameters
    ----------
    vertices : ndarray (n, 2) or (n, 3)
    faces : list of index sequences
    iterations : int
    fixed : ndarray (n,) bool, optional
        Vertices that never move (domain corners, feature points).
    constraints : sequence of SlideConstraint
        ``(vertices, polyline, closed)``: after each iteration these vertices are projected back
        onto the polyline (boundary stretches, curve features).
    tangential : bool
        If True (default), a vertex of the mesh boundary moves to the midpoint of its two boundary
        neighbours (then is projected), instead of the barycentre of all its neighbours: the full
        barycentre drags boundary vertices next to acute corners onto the corner.
    safe : bool
        If True (default), a step that would invert a face valid before it is undone for that
        face's vertices: near reflex corners the barycentre can lie outside the domain.

    Returns
    -------
    ndarray
        New vertex positions (the input is not modified).

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> v, f = grid_mesh(2)
    >>> v[4, :2] += 0.3
    >>> boundary = np.ones(9, bool); boundary[4] = False
    >>> laplacian_smooth(v, f, 1, fixed=boundary)[4, :2].tolist()
    [1.0, 1.0]
    """
    x = np.array(vertices, dtype=float)
    if iterations < 0:
        raise ValueError(f"iterations must be >= 0, got {iterations}")
    if iterations == 0 or len(faces) == 0:
        return x
    n = len(x)
    a = adjacency(n, faces)
    if tangential:
        # a vertex on the mesh boundary averages its two boundary neighbours only: it moves along
        # the boundary, so it cannot be dragged onto a corner or across a narrow part
        b = boundary_adjacency(n, faces)
        on_b = np.asarray(b.sum(axis=1)).ravel() > 0
        a = sp.diags((~on_b).astype(float)) @ a + sp.diags(on_b.astype(float)) @ b
    deg = np.asarray(a.sum(axis=1)).ravel()
    w = sp.diags(1.0 / np.maximum(deg, 1)) @ a
    keep = np.asarray(fixed, dtype=bool) if fixed is not None else np.zeros(n, dtype=bool)
    keep = keep | (deg == 0)
    anchor = x[keep]
    face_of, u, v, p = corner_arrays(faces)
    valid = _valid_faces(x, face_of, u, v, p, len(faces))
    for _ in range(iterations):
        old = x
        x = w @ old
        x[keep] = anchor
        for c in constraints:
            x[c.vertices, :2] = project_to_polyline(x[c.vertices, :2], c.polyline, c.closed)
        if safe:
            # a face valid before the step and inverted after it: its vertices keep their old
            # positions (repeated, since reverting may invert a neighbour)
            for _ in range(_MAX_REVERTS):
                now = _valid_faces(x, face_of, u, v, p, len(faces))
                broken = valid & ~now
                if not broken.any():
                    break
                back = np.unique(u[broken[face_of]])
                x[back] = old[back]
            valid = _valid_faces(x, face_of, u, v, p, len(faces))
    return x


def _valid_faces(x, face_of, u, v, p, n_faces) -> np.ndarray:
    """Faces whose every corner turns counter-clockwise (positive cross product)."""
    e1, e2 = x[v, :2] - x[u, :2], x[p, :2] - x[u, :2]
    cross = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    scale = (e1 * e1).sum(1) + (e2 * e2).sum(1)
    bad = np.zeros(n_faces, dtype=bool)
    bad[face_of[cross <= 1e-9 * scale]] = True
    return ~bad


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
        for c in constraints:
            y[c.vertices, :2] = project_to_polyline(y[c.vertices, :2], c.polyline, c.closed)
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
