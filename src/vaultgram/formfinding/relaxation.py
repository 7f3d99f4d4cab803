"""Relaxing the openings of a form diagram before horizontal equilibrium (§5; RhinoVAULT's "relax").

A straight unsupported edge cannot carry the thrust of the edges meeting it in compression: the force
polygons of its vertices would need the edge in tension. As RhinoVAULT does (Rippmann, Lachauer &
Block 2012), the open edges are first bent into compression arches by the force density method
(Schek 1974), in plan: each opening gets one force density ``q_b`` on its edges, every other edge
``q_interior``, and the moving vertices are placed in equilibrium. ``q_b`` is found per opening by
bisection so that the opening's vertices move by the prescribed sag.

:func:`relax_openings` reads as its phases: the opening edges, the moving vertices, each opening's
arch (span and outward normals), the force-density system, the bisection on the sag, and the check
that no edge collapsed.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vaultgram.errors import FormFindingError
from vaultgram.formfinding.cholesky import Cholesky, ForceDensityMatrix
from vaultgram.formfinding.formdiagram import FormDiagram
from vaultgram.geometry.meshes import corner_arrays, corner_triangles, face_areas
from vaultgram.geometry.polygons import signed_area
from vaultgram.geometry.polylines import polyline_length

__all__ = ["relax_openings", "relax", "Relaxed", "opening_edges", "folded_faces"]

RELAX_MODES = ("boundary", "all")


def opening_edges(form: FormDiagram) -> tuple[np.ndarray, np.ndarray]:
    """Form edges along openings and, for each, the opening face index (position in ``form.faces``).

    Example
    -------
    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh, remove_faces
    >>> v, f, _ = remove_faces(*grid_mesh(3), drop=[4])            # a square hole in the middle
    >>> edges, faces = opening_edges(form_diagram(v, f))
    >>> len(edges), faces.tolist() == [8] * 4
    (4, True)
    """
    eidx, fidx = [], []
    for k in np.flatnonzero(~form.loaded):
        sel = np.flatnonzero((form.edge_faces[:, 0] == k) | (form.edge_faces[:, 1] == k))
        eidx.append(sel)
        fidx.append(np.full(len(sel), k))
    if not eidx:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(eidx), np.concatenate(fidx)


class Relaxed(NamedTuple):
    """A relaxed form diagram and the force densities (per form edge) it is in equilibrium with: in
    mode ``"all"`` exactly, so the force diagram fitted to them is reciprocal from the start."""

    form: FormDiagram
    q: np.ndarray


def relax_openings(form: FormDiagram, sag: float = 0.1, *, mode: str = "boundary",
                   q_interior: float = 1.0, iterations: int = 60) -> FormDiagram:
    """Bend the open (unsupported) boundary edges into compression arches (force density method).

    Each opening gets one force density ``q_b`` on its edges (all other edges ``q_interior``) and the
    moving vertices are placed in equilibrium (Schek's force density method, in plan). ``q_b`` is
    found per opening by bisection so that its vertices move by at most ``sag * span`` away from the
    opening, towards the loaded side (``span``: the chord between the two supports of a boundary run;
    ``4 area / perimeter`` for a closed hole, i.e. the side of a square hole). The opening grows: a
    compression arch along an opening curves around it. Larger sag, lower thrust along the opening.
    A sag beyond what the adjacent edges allow (about one edge length in mode ``"boundary"``) is
    clamped by the bracket ``1e-4 <= q_b <= 1e4``.

    Parameters
    ----------
    form : FormDiagram
    sag : float
        Sag-to-span ratio of the open edges (0.1 default, as the usual RhinoVAULT setting).
    mode : {"boundary", "all"}
        ``"boundary"`` moves only the free vertices on openings (the rest of the pattern is kept);
        ``"all"`` moves every free vertex (a full force-density relaxation, which also smooths the
        pattern and yields a form diagram in exact equilibrium with positive force densities).
    q_interior : float
        Force density of non-opening edges.
    iterations : int
        At most this many bisection steps on ``log q_b``; it stops once every bracket is narrower than
        ``1e-6`` (q_b known to a millionth: 25 steps, each one sparse factorisation).

    Returns
    -------
    FormDiagram
        The diagram with new plan positions (unchanged when there is no opening).

    Raises
    ------
    FormFindingError
        a sag that is not positive, an unknown mode, or supports that cannot hold the open edges
        apart (edges collapse).

    Example
    -------
    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh, remove_faces
    >>> v, f, _ = remove_faces(*grid_mesh(6), drop=[14, 15, 20, 21])  # a 2 x 2 hole in a 6 x 6 grid
    >>> form = form_diagram(v, f)
    >>> moved = np.linalg.norm(relax_openings(form, 0.1).xy - form.xy, axis=1)
    >>> round(float(moved.max()), 6)                                # sag x span (the side of the hole)
    0.2
    """
    return relax(form, sag, mode=mode, q_interior=q_interior, iterations=iterations).form


def relax(form: FormDiagram, sag: float = 0.1, *, mode: str = "boundary", q_interior: float = 1.0,
          iterations: int = 60) -> Relaxed:
    """:func:`relax_openings`, with the force densities of the relaxed diagram.

    In mode ``"all"`` a diagram without openings is relaxed too (every edge ``q_interior``: each free
    vertex at the mean of its neighbours), and the result is in exact equilibrium with ``q > 0``. Where
    equal densities fold the diagram (near reflex corners of the supported boundary, which a convex
    combination does not respect), the interior densities are made unequal until it unfolds
    (:func:`_unfolded`): still every ``q > 0``, still in exact equilibrium.

    Example
    -------
    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> r = relax(form_diagram(*grid_mesh(4)), mode="all")
    >>> bool(np.allclose(r.form.xy, form_diagram(*grid_mesh(4)).xy)), r.q.tolist() == [1.0] * 24
    (True, True)
    """
    _check_options(sag, mode)
    eo, fo = opening_edges(form)
    if len(eo) == 0 and mode != "all":
        return Relaxed(form, np.full(form.n_edges, float(q_interior)))
    moving = _moving_vertices(form, eo, mode)
    arches = [_arch(form, k, moving) for k in np.flatnonzero(~form.loaded)]
    system = _ForceDensities(form, moving, eo, fo, q_interior)
    logq, xy = _sag_search(system, arches, sag, iterations)
    if mode == "all":
        logq, xy = _unfolded(system, form, arches, sag, logq, xy)
    out = form.with_xy(xy)
    _check_not_collapsed(form, out)
    _check_not_folded(out)
    return Relaxed(out, system.densities(logq))


def _check_options(sag: float, mode: str) -> None:
    if sag <= 0:
        raise FormFindingError(f"sag must be positive, got {sag}")
    if mode not in RELAX_MODES:
        raise FormFindingError(f"unknown mode {mode!r}; use 'boundary' or 'all'")


def _moving_vertices(form: FormDiagram, eo: np.ndarray, mode: str) -> np.ndarray:
    """Boolean mask of the vertices that move: the free ones on openings, or every free one."""
    if mode == "all":
        return ~form.anchors
    moving = np.zeros(form.n_vertices, dtype=bool)
    moving[form.edges[eo].ravel()] = True
    return moving & ~form.anchors


class _Arch(NamedTuple):
    """An opening to be bent: its span, and its moving vertices with their outward normals (towards the
    loaded side: the opening face lies on the left of its traversal)."""

    span: float
    vertices: np.ndarray
    normals: np.ndarray


def _arch(form: FormDiagram, k: int, moving: np.ndarray) -> _Arch:
    """The arch along opening face ``k``: a run between two supports spans their chord, a closed hole
    ``4 area / perimeter`` (the side of a square hole); the largest vertex distance if that is zero."""
    vs = np.array(form.faces[k])
    pts = np.asarray(form.xy)[vs]
    prv, nxt = np.roll(pts, 1, axis=0), np.roll(pts, -1, axis=0)
    if _is_run(vs, form.anchors):
        span = np.linalg.norm(pts[-1] - pts[0])
    else:
        span = 4.0 * abs(signed_area(pts)) / polyline_length(np.vstack([pts, pts[:1]]))
    if span <= 0:
        span = np.sqrt(((pts[:, None, :] - pts[None, :, :]) ** 2).sum(-1)).max()
    t = nxt - prv
    normals = np.column_stack([t[:, 1], -t[:, 0]])
    normals /= np.maximum(np.linalg.norm(normals, axis=1), 1e-300)[:, None]
    sel = moving[vs]
    return _Arch(span, vs[sel], normals[sel])


def _is_run(vs: np.ndarray, anchors: np.ndarray) -> bool:
    """An open opening face: from one support to another through free vertices only."""
    return bool(anchors[vs[0]] and anchors[vs[-1]] and len(vs) >= 3 and np.all(~anchors[vs[1:-1]]))


class _ForceDensities:
    """The plan force-density system ``Cm^T Q Cm x_m = -Cm^T Q Cs x_s`` for the moving vertices, with
    ``q_b = exp(logq[j])`` on the edges of opening ``j`` (an edge on two openings takes the larger) and
    ``base`` on the others (``q_interior`` unless :func:`_unfold` changed them).
    Every solve has the same pattern: its Cholesky factorisation's symbolic part is made once, on the
    first solve, and each further solve only refactorises the values."""

    def __init__(self, form: FormDiagram, moving: np.ndarray, eo: np.ndarray, fo: np.ndarray, q_interior: float):
        openings = np.flatnonzero(~form.loaded)
        slot = np.full(form.n_faces, -1)
        slot[openings] = np.arange(len(openings))
        self.eo, self.slot_of_edge = eo, slot[fo]
        self.base = np.full(form.n_edges, float(q_interior))
        self.interior = np.ones(form.n_edges, dtype=bool)
        self.interior[eo] = False
        self.mv, st = np.flatnonzero(moving), np.flatnonzero(~moving)
        self.Cm = form.C[:, self.mv].tocsr()
        self.K = ForceDensityMatrix(form.C, self.mv)
        self.CmT, self.Cs = self.Cm.T.tocsr(), form.C[:, st].tocsc()
        self.xy0 = np.asarray(form.xy)
        self.xs = self.xy0[st]
        self._factor: Cholesky | None = None

    def densities(self, logq: np.ndarray) -> np.ndarray:
        """Force density per form edge for the opening force densities ``exp(logq)``."""
        q = self.base.copy()
        np.maximum.at(q, self.eo, np.exp(logq[self.slot_of_edge]))
        return q

    def solve(self, logq: np.ndarray) -> np.ndarray:
        """Plan positions in equilibrium for the opening force densities ``exp(logq)``."""
        q = self.densities(logq)
        if self._factor is None:
            self._factor = self.K.factorised(q, "force-density system of the relaxation")
        else:
            self._factor.refactor(self.K.values(q))
        xy = self.xy0.copy()
        xy[self.mv] = self._factor.solve(-(self.CmT @ (q[:, None] * (self.Cs @ self.xs))))
        return xy

    def density_gradient(self, xy: np.ndarray, g: np.ndarray) -> np.ndarray:
        """``dF/dq_e`` of a function ``F`` of the plan positions with gradient ``g`` (per vertex), at the
        positions ``xy`` of the last :meth:`solve`, by the adjoint: differentiating
        ``Cm^T Q (C x) = 0`` gives ``dx_m/dq_e = -K^{-1} Cm_e^T u_e`` (``u_e``: edge ``e``'s vector),
        so ``dF/dq_e = -(Cm lam)_e . u_e`` with ``K lam = g_m``: one more solve for every edge."""
        lam = self._factor.solve(g[self.mv])
        return -np.einsum("ij,ij->i", self.Cm @ lam, self.Cm @ xy[self.mv] + self.Cs @ self.xs)


#: Width of the bisection bracket on ``log q_b`` at which :func:`_bisect_sag` hands over to
#: :func:`_coupled_sag`; the sags it leaves are then met to :data:`_SAG_TOL` of their targets (on the
#: Armadillo plan 19 solves, 26 with a bracket of 1e-3); ``_DIFF``: the finite-difference step.
_BRACKET = 0.1
_DIFF = 1e-3
_SAG_TOL = 1e-6
_LOG_Q = (np.log(1e-4), np.log(1e4))


def _sag_search(system: _ForceDensities, arches: list[_Arch], sag: float, iterations: int
                ) -> tuple[np.ndarray, np.ndarray]:
    """``log q_b`` per opening such that its largest outward displacement is ``sag * span``, and the plan
    positions for them: bisection to a bracket of 0.1, then the openings' coupled sags met together."""
    if not arches:
        return np.zeros(0), system.solve(np.zeros(0))
    target = sag * np.array([a.span for a in arches])
    return _coupled_sag(system, arches, target, _bisect_sag(system, arches, target, iterations))


def _bisect_sag(system: _ForceDensities, arches: list[_Arch], target: np.ndarray, iterations: int) -> np.ndarray:
    """``log q_b`` per opening, bisected in ``[log 1e-4, log 1e4]`` towards a largest outward
    displacement of ``target`` (too much sag: raise ``q_b``). Each opening's bracket is narrowed with
    the others' current values, which still move: where openings interact (the relaxation moves every
    vertex in mode ``"all"``), a bracket can go stale and miss the root by far (on the Armadillo plan a
    sag 27% too large), so the result is only the start of :func:`_coupled_sag`."""
    lo, hi = (np.full(len(arches), end) for end in _LOG_Q)
    for _ in range(iterations):
        if np.all(hi - lo < _BRACKET):
            break
        mid = 0.5 * (lo + hi)
        too_much = _sags(system.solve(mid), system.xy0, arches) > target
        lo = np.where(too_much, mid, lo)
        hi = np.where(too_much, hi, mid)
    return 0.5 * (lo + hi)


def _coupled_sag(system: _ForceDensities, arches: list[_Arch], target: np.ndarray, x: np.ndarray,
                 steps: int = 12) -> tuple[np.ndarray, np.ndarray]:
    """Every opening's sag met together: quasi-Newton (Broyden) steps on ``g = sag / target - 1`` from
    the bisection's ``x``, the Jacobian started by finite differences, over the openings strictly
    inside the bracket (the others' targets are out of reach: they take its end). Returns ``log q_b``
    and the plan positions; the iterate with the smallest ``max |g|`` if ``steps`` do not suffice."""
    def g(logq: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        xy = system.solve(logq)
        return _sags(xy, system.xy0, arches) / target - 1.0, xy

    x = np.where(x < _LOG_Q[0] + _BRACKET, _LOG_Q[0], np.where(x > _LOG_Q[1] - _BRACKET, _LOG_Q[1], x))
    inner = np.flatnonzero((x > _LOG_Q[0]) & (x < _LOG_Q[1]))
    gx, xy = g(x)
    if len(inner) == 0 or np.max(np.abs(gx[inner])) <= _SAG_TOL:
        return x, xy
    J = np.column_stack([(g(x + _DIFF * (np.arange(len(x)) == j))[0][inner] - gx[inner]) / _DIFF
                         for j in inner])
    best = (np.max(np.abs(gx[inner])), x, xy)
    for _ in range(steps):
        step = np.zeros_like(x)
        step[inner] = np.linalg.lstsq(J, -gx[inner], rcond=None)[0]
        x_new = np.clip(x + step, *_LOG_Q)
        g_new, xy = g(x_new)
        s, dg = (x_new - x)[inner], (g_new - gx)[inner]
        if s @ s > 0:
            J += np.outer(dg - J @ s, s) / (s @ s)
        x, gx = x_new, g_new
        if np.max(np.abs(gx[inner])) < best[0]:
            best = (np.max(np.abs(gx[inner])), x, xy)
        if best[0] <= _SAG_TOL:
            break
    return best[1], best[2]


def _sags(xy: np.ndarray, xy0: np.ndarray, arches: list[_Arch]) -> np.ndarray:
    """Largest displacement of each arch's vertices along their outward normals."""
    return np.array([np.max(np.einsum("ij,ij->i", xy[a.vertices] - xy0[a.vertices], a.normals))
                     if len(a.vertices) else 0.0 for a in arches])


#: Unfolding (:func:`_unfold`): the penalty acts on faces thinner than ``_THIN`` of their meshed area
#: and on edges shorter than ``_SHORT`` of their meshed length, and the descent stops once every face
#: and edge has half that; at most ``_UNFOLD_STEPS`` steps (on the multiple-lobes plan at 6,400 faces
#: 15), each changing a density by at most a factor ``e``, and ``_UNFOLD_ROUNDS`` rounds of unfolding
#: and re-met sags. The edges' term: the large densities the descent gives the edges at a notch's
#: corner shrink them, the more the finer the mesh (the shortest keeps 1.4% of its length at 6,400
#: faces of the multiple-lobes plan, 0.6% at 65,000, 0.04% at 810,000, under :func:`_check_not_collapsed`'s
#: 0.1%); below ``_SHORT`` they weigh as a face at the same share of ``_THIN``.
_THIN = 0.1
_SHORT = 0.005
_UNFOLD_STEPS = 100
_UNFOLD_ROUNDS = 3


def folded_faces(xy: np.ndarray, faces) -> np.ndarray:
    """Per face, whether it is folded: clockwise (a signed area of 0 or less), or a quad crossing
    itself, whose area stays positive but two of whose corners turn the wrong way (a quad with one
    reflex corner is not folded).

    >>> folded_faces(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]), [(0, 1, 3, 2), (0, 1, 2, 3)]).tolist()
    [False, True]
    """
    face_of = corner_arrays(faces)[0]
    wrong = np.bincount(face_of, weights=face_areas(xy, corner_triangles(faces)) <= 0, minlength=len(faces))
    return (face_areas(xy, faces) <= 0) | (wrong >= 2)


class _Folds:
    """The loaded faces' signed areas relative to their meshed ones, ``r_f = a_f / a0_f`` (positive: the
    form diagram checks that its faces are counter-clockwise), with the corner triangles (each corner
    with its two neighbours along the face) of the quads given as ``crossed`` among the faces (a quad
    crossing itself keeps a positive area, but two of its corners turn over), the edges' lengths
    relative to their meshed ones, ``s_e = l_e / l0_e``, and the penalty
    ``P = sum_f max(0, _THIN - r_f)^2 + sum_e (_THIN max(0, 1 - s_e / _SHORT))^2`` on the thin and folded
    faces and corners and the short edges."""

    def __init__(self, form: FormDiagram, crossed=()):
        self.loaded = form.loaded_faces
        corners = corner_triangles([self.loaded[int(k)] for k in crossed]) if len(crossed) else ()
        self.faces = [*self.loaded, *map(tuple, corners)] if len(corners) else self.loaded
        self.face, self.u, self.v, _ = corner_arrays(self.faces)
        self.a0 = face_areas(form.xy, self.faces)
        self.edges, self.l0 = form.edges, form.edge_lengths()
        self.n = form.n_vertices

    def ratios(self, xy: np.ndarray) -> np.ndarray:
        return face_areas(xy, self.faces) / self.a0

    def edge_vectors(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Each edge's vector ``x_v - x_u`` and its length."""
        d = xy[self.edges[:, 1]] - xy[self.edges[:, 0]]
        return d, np.hypot(d[:, 0], d[:, 1])

    def settled(self, xy: np.ndarray) -> bool:
        """Every face keeps half of ``_THIN`` of its area and every edge half of ``_SHORT`` of its length."""
        return bool(self.ratios(xy).min() >= 0.5 * _THIN and (self.edge_vectors(xy)[1] / self.l0).min() >= 0.5 * _SHORT)

    def penalty(self, xy: np.ndarray) -> tuple[float, np.ndarray]:
        """``P`` and its gradient in the plan positions, ``(n, 2)``: a face's area (the shoelace) has
        ``dA/dx_u = y_v / 2`` and ``dA/dy_u = -x_v / 2`` over its halfedges ``u -> v``, the opposite at
        ``v``; an edge's length ``l = |x_v - x_u|`` has ``dl/dx_v = (x_v - x_u) / l = -dl/dx_u``."""
        h = np.maximum(0.0, _THIN - self.ratios(xy))
        w = (-h / self.a0)[self.face]                     # half of dP/dA per corner
        u, v, n = self.u, self.v, self.n
        gx = np.bincount(u, w * xy[v, 1], n) - np.bincount(v, w * xy[u, 1], n)
        gy = np.bincount(v, w * xy[u, 0], n) - np.bincount(u, w * xy[v, 0], n)
        g = np.column_stack([gx, gy])
        d, length = self.edge_vectors(xy)
        short = np.flatnonzero(length < _SHORT * self.l0)
        if len(short) == 0:
            return float(h @ h), g
        k = _THIN * (1.0 - length[short] / (_SHORT * self.l0[short]))
        per = np.divide(k, self.l0[short] * length[short], out=np.zeros_like(k), where=length[short] > 0)
        dv = (-2.0 * _THIN / _SHORT) * per[:, None] * d[short]   # dP/dx_v (none along an edge of no length)
        a, b = self.edges[short, 0], self.edges[short, 1]
        for c in range(2):
            g[:, c] += np.bincount(b, dv[:, c], n) - np.bincount(a, dv[:, c], n)
        return float(h @ h + k @ k), g


def _unfolded(system: _ForceDensities, form: FormDiagram, arches: list[_Arch], sag: float, logq: np.ndarray,
              xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The relaxation of mode ``"all"`` without folded faces. Equal force densities place every free
    vertex at a convex combination of its neighbours, which folds the diagram where the supported
    boundary has reflex corners (Tutte's embedding needs a convex one): the edge lines along the
    boundary pull straight across a notch and drag the first rows of faces over its corner. There the
    interior densities are made unequal (:func:`_unfold`) and the openings' sags met again, for at most
    :data:`_UNFOLD_ROUNDS` rounds; unchanged if nothing is folded. Returns ``log q_b`` and the positions."""
    target = sag * np.array([a.span for a in arches])
    for _ in range(_UNFOLD_ROUNDS):
        folded = folded_faces(xy, form.loaded_faces)
        if not folded.any():
            break
        folds = _Folds(form, np.flatnonzero(folded & (face_areas(xy, form.loaded_faces) > 0)))
        xy = _unfold(system, folds, system.solve(logq), logq)
        if arches:
            logq, xy = _coupled_sag(system, arches, target, logq)
    return logq, xy


def _unfold(system: _ForceDensities, folds: _Folds, xy: np.ndarray, logq: np.ndarray) -> np.ndarray:
    """Descent on the log densities of the interior edges (so every ``q`` stays positive, and the
    positions stay in exact equilibrium with them) against :class:`_Folds`' penalty, gradient by the
    adjoint (:meth:`_ForceDensities.density_gradient`), steps of at most ``eta`` in any log density,
    halved until the penalty drops; it stops when every face keeps half of :data:`_THIN` of its area.
    On the multiple-lobes plan the densities grow on the edges holding the first rows to the notches'
    corners and drop on those along the boundary. ``xy``: the positions of the last solve; returns the
    final ones (``system.base`` holds the densities)."""
    inner = system.interior
    penalty, g = folds.penalty(xy)
    eta = 0.5
    for _ in range(_UNFOLD_STEPS):
        if folds.settled(xy):
            break
        grad = (system.base * system.density_gradient(xy, g))[inner]
        if not np.any(grad):
            break
        s = np.log(system.base[inner])
        while eta > 1e-6:
            system.base[inner] = np.exp(s - eta * grad / np.abs(grad).max())
            trial = system.solve(logq)
            p_trial, g_trial = folds.penalty(trial)
            if p_trial < penalty:
                xy, penalty, g, eta = trial, p_trial, g_trial, min(1.5 * eta, 1.0)
                break
            eta *= 0.5
        else:
            system.base[inner] = np.exp(s)
            return system.solve(logq)
    return xy


def _check_not_collapsed(form: FormDiagram, out: FormDiagram) -> None:
    """No edge shrank below a thousandth of its length: the supports held the open edges apart."""
    l0, l1 = form.edge_lengths(), out.edge_lengths()
    short = np.flatnonzero(~(l1 > 1e-3 * l0))
    if len(short):
        raise FormFindingError(
            f"relaxing the openings collapsed {len(short)} edges, e.g. {form.edge_name(int(short[0]))} "
            f"(length {l0[short[0]]:.3g} -> {l1[short[0]]:.3g}): the supports cannot hold the open edges "
            f"apart; add supports or relax with a larger sag", places=form.xy[form.edges[short]])


def _check_not_folded(out: FormDiagram) -> None:
    """No loaded face is :func:`folded <folded_faces>`: the relaxation did not fold the form diagram,
    nor cross a quad over itself (the error's ``places``: the folded faces' sides, in plan)."""
    loaded = out.loaded_faces
    folded = np.flatnonzero(folded_faces(out.xy, loaded))
    if len(folded):
        face = [int(out.vertex_ids[v]) for v in loaded[int(folded[0])]]
        of, u, v, _ = corner_arrays(loaded)
        bad = np.zeros(len(loaded), dtype=bool)
        bad[folded] = True
        sides = bad[of]
        raise FormFindingError(
            f"relaxing the openings folded {len(folded)} face(s) of the form diagram, e.g. the face of mesh "
            f"vertices {face}: the supports cannot hold the open edges apart there; add supports (--supports) "
            f"or relax less (a smaller --sag)", places=np.stack([out.xy[u[sides]], out.xy[v[sides]]], axis=1))
