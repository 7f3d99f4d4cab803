"""Relaxing the openings of a form diagram before horizontal equilibrium (§5; RhinoVAULT's "relax").

A straight unsupported edge cannot carry the thrust of the edges meeting it in compression: the force
polygons of its vertices would need the edge in tension. As RhinoVAULT does (Rippmann, Lachauer &
Block 2012), the open edges are first bent into compression arches by the force density method
(Schek 1974), in plan: each opening gets one force density ``q_b`` on its edges, every other edge
``q_interior``, and the moving vertices are placed in equilibrium. ``q_b`` is found per opening by
Newton steps (the adjoint gives their Jacobian) so that the opening's vertices move by the prescribed
sag.

:func:`relax_openings` reads as its phases: the opening edges, the moving vertices, each opening's
arch (span and outward normals), the force-density system, the search for the sags, and the check
that no edge collapsed.
"""

from __future__ import annotations

import copy
from typing import NamedTuple

import numpy as np

from vaultgram.errors import FormFindingError
from vaultgram.formfinding.cholesky import Cholesky, ForceDensityMatrix
from vaultgram.formfinding.formdiagram import FormDiagram
from vaultgram.geometry.meshes import corner_arrays, face_areas, shoelace_areas
from vaultgram.geometry.polygons import signed_area
from vaultgram.geometry.polylines import polyline_length
from vaultgram.geometry.spatial import nearest_within, pairs_within

__all__ = ["relax_openings", "relax", "Relaxed", "opening_edges", "folded_faces", "reflex_anchors",
           "isotropic_densities", "notch_densities", "graded_plan"]

RELAX_MODES = ("boundary", "all")
#: At most this many Newton steps of the sag search (:func:`_sag_search`), each one factorisation.
_NEWTON_STEPS = 60


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
                   q_interior: float = 1.0, iterations: int = _NEWTON_STEPS) -> FormDiagram:
    """Bend the open (unsupported) boundary edges into compression arches (force density method).

    Each opening gets one force density ``q_b`` on its edges (all other edges ``q_interior``) and the
    moving vertices are placed in equilibrium (Schek's force density method, in plan). ``q_b`` is
    found per opening (:func:`_sag_search`) so that its vertices move by at most ``sag * span`` away from the
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
        At most this many Newton steps on ``q_b``, each one sparse factorisation; it stops once every
        sag is within a millionth of its target (4-6 steps on the examples).

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
          iterations: int = _NEWTON_STEPS) -> Relaxed:
    """:func:`relax_openings`, with the force densities of the relaxed diagram.

    Each sag is first measured from the meshed positions; where that collapses edges (a closed hole
    that drifts with the pattern, drawn in to a point: :func:`_sag_peaks`), the closed holes' sags
    are measured from their drift instead (issue 12: mexico_airport, rolex_learning_centre).

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
    out = _relaxed(form, moving, eo, fo, q_interior, sag, mode, iterations, drifting=False)
    if _collapsed(form, out.form).any():  # a closed hole drawn in to a point: its sag from its drift
        if any(_arch(form, k, moving, drifting=True).closed for k in np.flatnonzero(~form.loaded)):
            out = _relaxed(form, moving, eo, fo, q_interior, sag, mode, iterations, drifting=True)
    _check_not_collapsed(form, out.form)
    _check_not_folded(out.form)
    return out


def _relaxed(form: FormDiagram, moving: np.ndarray, eo: np.ndarray, fo: np.ndarray, q_interior: float, sag: float,
             mode: str, iterations: int, drifting: bool) -> Relaxed:
    """:func:`relax`'s diagram and densities before its checks: the sag search, and in mode ``"all"``
    the unfolding; ``drifting``: the closed holes' sags measured from their drift (:func:`_arch`)."""
    arches = [_arch(form, k, moving, drifting) for k in np.flatnonzero(~form.loaded)]
    system = _ForceDensities(form, moving, eo, fo, q_interior)
    logq, xy = _sag_search(system, arches, sag, iterations)
    if mode == "all":
        logq, xy = _unfolded(system, form, arches, sag, logq, xy)
    return Relaxed(form.with_xy(xy), system.densities(logq))


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
    loaded side: the opening face lies on the left of its traversal); ``closed``: a hole without
    supports, whose sag is measured from its vertices' mean displacement (:func:`_sag_peaks`)."""

    span: float
    vertices: np.ndarray
    normals: np.ndarray
    closed: bool = False


def _arch(form: FormDiagram, k: int, moving: np.ndarray, drifting: bool = False) -> _Arch:
    """The arch along opening face ``k``: a run between two supports spans their chord, a closed hole
    ``4 area / perimeter`` (the side of a square hole); the largest vertex distance if that is zero.
    ``drifting``: a closed hole (every vertex moving) is :attr:`_Arch.closed`, its sag measured from its
    drift; :func:`relax` first measures every sag from the meshed positions, and from the drift only
    where that collapsed edges."""
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
    return _Arch(span, vs[sel], normals[sel], bool(drifting and sel.all()))


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
        self.mv, self.st = np.flatnonzero(moving), np.flatnonzero(~moving)
        self.Cm = form.C[:, self.mv].tocsr()
        self.K = ForceDensityMatrix(form.C, self.mv)
        self.CmT, self.Cs = self.Cm.T.tocsr(), form.C[:, self.st].tocsc()
        self.xy0 = np.asarray(form.xy)
        self.xs = self.xy0[self.st]
        self._factor: Cholesky | None = None

    def at(self, xy: np.ndarray) -> _ForceDensities:
        """The same system with the stationary vertices at ``xy`` (and the sags measured from there);
        the densities are copied, the factorisation's symbolic part is shared."""
        out = copy.copy(self)
        out.base, out.xy0 = self.base.copy(), np.asarray(xy)
        out.xs = out.xy0[self.st]
        return out

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


#: The sag search (:func:`_sag_search`): Newton steps on ``q_b`` until every reachable sag is
#: within ``_SAG_TOL`` of its target, in the bracket ``_LOG_Q`` (``1e-4 <= q_b <= 1e4``); a step may
#: leave an opening's bracket by ``_TRUST`` (:func:`_next_logq`).
_SAG_TOL = 1e-6
_TRUST = 0.5
_LOG_Q = (np.log(1e-4), np.log(1e4))


def _sag_search(system: _ForceDensities, arches: list[_Arch], sag: float, iterations: int = _NEWTON_STEPS,
                start: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """``log q_b`` per opening such that its largest outward displacement is ``sag * span``, and the plan
    positions for them: safeguarded Newton steps on ``g = sag / target - 1``, all openings together
    (in mode ``"all"`` each opening's sag depends on the others' densities), the Jacobian by the
    adjoint (:func:`_sag_jacobian`: one solve per opening, no factorisation), from ``start`` (default
    ``q_b = 1``). A step that leaves an opening's bracket (:func:`_narrowed`) bisects it instead
    (:func:`_next_logq`). An opening whose target is out of reach (too much sag even at ``q_b = 1e4``,
    too little at ``1e-4``) keeps the end of :data:`_LOG_Q`. Each step is one factorisation: 5 on the
    quad with a hole at 10^6 faces, where bisection to a bracket of 0.1 and quasi-Newton steps took 13.
    Returns the iterate with the smallest ``max |g|`` if ``iterations`` do not suffice."""
    if not arches:
        return np.zeros(0), system.solve(np.zeros(0))
    target = sag * np.array([a.span for a in arches])
    x = np.where([len(a.vertices) > 0 for a in arches], 0.0, _LOG_Q[0]) if start is None else np.array(start, float)
    lo, hi = (np.full(len(arches), end) for end in _LOG_Q)
    best = (np.inf, x, None)
    for _ in range(iterations):
        xy = system.solve(x)
        s, peak = _sag_peaks(xy, system.xy0, arches)
        g = s / target - 1.0
        lo, hi = _narrowed(x, g, lo, hi)
        done = (np.abs(g) <= _SAG_TOL) | ((x >= _LOG_Q[1]) & (g > 0)) | ((x <= _LOG_Q[0]) & (g < 0))
        if np.max(np.abs(g), initial=0.0, where=~done) < best[0] or done.all():
            best = (np.max(np.abs(g), initial=0.0, where=~done), x, xy)
        if done.all():
            break
        x = _next_logq(x, g, _sag_jacobian(system, arches, xy, x, peak) / target[:, None], lo, hi, done)
    return best[1], best[2]


def _narrowed(x: np.ndarray, g: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each opening's bracket on ``log q_b`` narrowed by the sag at ``x``: too much sag (``g > 0``)
    raises its lower end, too little lowers its upper end (the sag falls as ``q_b`` grows). Where
    openings interact a bracket can go stale as the others' densities move (the Armadillo plan's feet);
    one that closed without a root is opened again to the whole of :data:`_LOG_Q`."""
    lo, hi = np.where(g > 0, np.maximum(lo, x), lo), np.where(g > 0, hi, np.minimum(hi, x))
    stale = hi - lo < 1e-12
    return np.where(stale, _LOG_Q[0], lo), np.where(stale, _LOG_Q[1], hi)


def _next_logq(x: np.ndarray, g: np.ndarray, jacobian: np.ndarray, lo: np.ndarray, hi: np.ndarray,
               done: np.ndarray) -> np.ndarray:
    """The Newton step on ``g`` of the openings not ``done``, in ``q_b`` (``jacobian``: ``d g_i / d log
    q_j``): the sags are nearly linear in ``q_b`` and flat in ``log q_b`` below the root (the quad with
    a hole at 10^5 faces: from ``q_b = 1`` the step in ``q_b`` lands at 22.6 for a root at 27.4, the
    step in ``log q_b`` at 3e9). Where it leaves an opening's bracket ``(lo, hi)`` by more than
    :data:`_TRUST` in ``log q_b``, the bracket's middle, or its end if that is an end of
    :data:`_LOG_Q` (so that an unreachable target is found at the end, not approached). Short steps out
    of a bracket are taken: where openings interact, one's density may have to fall while its sag is
    too large, the others' rising ones pulling it in (the brackets hold for one opening alone)."""
    out = x.copy()
    k = np.flatnonzero(~done)
    q = np.exp(x[k])
    q_new = q + np.linalg.lstsq(jacobian[np.ix_(k, k)] / q[None, :], -g[k], rcond=None)[0]
    new = np.log(np.maximum(q_new, 1e-300))
    inside = ((new > lo[k]) & (new < hi[k])) | (np.abs(new - x[k]) <= _TRUST)
    at_end = np.where(new <= lo[k], lo[k] == _LOG_Q[0], hi[k] == _LOG_Q[1])
    edge = np.where(new <= lo[k], lo[k], hi[k])
    out[k] = np.where(inside, new, np.where(at_end, edge, 0.5 * (lo[k] + hi[k])))
    return out


def _sag_jacobian(system: _ForceDensities, arches: list[_Arch], xy: np.ndarray, x: np.ndarray,
                  peak: np.ndarray) -> np.ndarray:
    """``d s_i / d log q_j``: the sag ``s_i`` of opening ``i`` is the displacement of its vertex
    ``peak[i]`` along that vertex's normal (less the mean displacement on a closed hole), whose density
    gradient the adjoint gives (:meth:`_ForceDensities.density_gradient`); ``q_b = exp(log q_j)`` on
    the edges of opening ``j`` that take its density (an edge on two openings takes the larger)."""
    q = system.densities(x)
    own = np.exp(x[system.slot_of_edge]) >= q[system.eo]
    out = np.zeros((len(arches), len(arches)))
    for i, (a, k) in enumerate(zip(arches, peak)):
        if not len(a.vertices):
            continue
        g = np.zeros_like(xy)
        if a.closed:  # the sag is measured from the mean displacement
            g[a.vertices] = -a.normals[k] / len(a.vertices)
        g[a.vertices[k]] += a.normals[k]
        dq = system.density_gradient(xy, g)[system.eo] * q[system.eo]
        out[i] = np.bincount(system.slot_of_edge[own], dq[own], minlength=len(arches))
    return out


def _displacements(xy: np.ndarray, xy0: np.ndarray, arch: _Arch) -> np.ndarray:
    """The arch's vertices' displacements from ``xy0``, less their mean on a closed hole."""
    d = xy[arch.vertices] - xy0[arch.vertices]
    return d - d.mean(axis=0) if arch.closed and len(d) else d


def _sags(xy: np.ndarray, xy0: np.ndarray, arches: list[_Arch]) -> np.ndarray:
    """Largest displacement of each arch's vertices along their outward normals."""
    return _sag_peaks(xy, xy0, arches)[0]


def _sag_peaks(xy: np.ndarray, xy0: np.ndarray, arches: list[_Arch]) -> tuple[np.ndarray, np.ndarray]:
    """Each arch's sag (:func:`_sags`) and the index (among its vertices) of the vertex that has it.

    A closed hole's displacements (:attr:`_Arch.closed`) are taken relative to their mean: nothing
    holds such a hole in place, and in mode ``"all"`` it drifts with the pattern relaxing round it
    (hiroshi_senju_museum's two small holes by 0.42 and 0.75 m, two and five times their sags).
    Measured from where it was meshed, the drift's side of the hole counts as sag that no ``q_b`` can
    take back, and the search draws the hole in towards a point until its sag is met (on
    hiroshi_senju_museum its edges at 1.2% of their length) or, one subdivision finer, ``q_b = 1e4``
    collapses it (issue 12)."""
    moves = [np.einsum("ij,ij->i", _displacements(xy, xy0, a), a.normals) for a in arches]
    peak = np.array([int(np.argmax(m)) if len(m) else 0 for m in moves], dtype=np.int64)
    return np.array([m[k] if len(m) else 0.0 for m, k in zip(moves, peak)]), peak


#: Unfolding (:func:`_unfold`): the penalty acts on faces thinner than ``_THIN`` of their meshed area,
#: on quads whose second thinnest corner triangle is thinner than ``_CORNER`` of its meshed area (about
#: to cross themselves: on the multiple-lobes plan, unfolding the faces alone crossed 30 quads at
#: 10^5 faces and 93 at 10^6, and a second round had to unfold those, in more steps than the first)
#: and on edges shorter than ``_SHORT`` of their meshed length, and the descent stops once every face,
#: quad corner and edge has half that; at most ``_UNFOLD_STEPS`` steps (on the multiple-lobes plan at 6,400 faces
#: 15), each changing a density by at most a factor ``e``, and ``_UNFOLD_ROUNDS`` rounds of unfolding
#: and re-met sags. The edges' term: the large densities the descent gives the edges at a notch's
#: corner shrink them, the more the finer the mesh (the shortest keeps 1.4% of its length at 6,400
#: faces of the multiple-lobes plan, 0.6% at 65,000, 0.04% at 810,000, under :func:`_check_not_collapsed`'s
#: 0.1%); below ``_SHORT`` they weigh as a face at the same share of ``_THIN``.
_THIN = 0.1
_CORNER = 0.05
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
    face_of, u, v, p = corner_arrays(faces)
    turned = _corner_areas(xy, u, v, p) <= 0
    return (face_areas(xy, faces) <= 0) | (np.bincount(face_of, weights=turned, minlength=len(faces)) >= 2)


class _Folds:
    """The loaded faces' signed areas relative to their meshed ones, ``r_f = a_f / a0_f`` (positive: the
    form diagram checks that its faces are counter-clockwise); per quad, the second thinnest of its
    corner triangles (a corner with its two neighbours along the face) relative to its meshed area,
    ``t_f`` (a quad crossing itself keeps a positive area, but two of its corners turn over; one
    reflex corner is no fold); the edges' lengths relative to their meshed ones, ``s_e = l_e / l0_e``;
    and the penalty ``P = sum_f max(0, _THIN - r_f)^2 + sum_f max(0, _CORNER - t_f)^2
    + sum_e (_THIN max(0, 1 - s_e / _SHORT))^2`` on the thin and folded faces, the quads about to
    cross and the short edges."""

    def __init__(self, form: FormDiagram):
        loaded = form.loaded_faces
        self.face, self.u, self.v, p = corner_arrays(loaded)
        self.n_faces = len(loaded)
        self.a0 = self.areas(form.xy)
        quad = np.bincount(self.face, minlength=self.n_faces)[self.face] == 4   # a quad's corners are in a row
        self.corners = (self.u[quad], self.v[quad], p[quad])                     # 4 per quad, in its order
        self.c0 = np.maximum(np.abs(_corner_areas(form.xy, *self.corners)), 1e-3 * self.a0[self.face[quad]])
        self.edges, self.l0 = form.edges, form.edge_lengths()
        self.n = form.n_vertices

    def areas(self, xy: np.ndarray) -> np.ndarray:
        return shoelace_areas(xy, self.face, self.u, self.v, self.n_faces)

    def ratios(self, xy: np.ndarray) -> np.ndarray:
        return self.areas(xy) / self.a0

    def second_corners(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Per quad, which of its corners (0-3) has the second thinnest corner triangle, and ``t_f``."""
        t = (_corner_areas(xy, *self.corners) / self.c0).reshape(-1, 4)
        k = np.argpartition(t, 1, axis=1)[:, 1]
        return k, t[np.arange(len(t)), k]

    def edge_vectors(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Each edge's vector ``x_v - x_u`` and its length."""
        d = xy[self.edges[:, 1]] - xy[self.edges[:, 0]]
        return d, np.hypot(d[:, 0], d[:, 1])

    def settled(self, xy: np.ndarray) -> bool:
        """Every face keeps half of ``_THIN`` of its area, every quad's second corner half of ``_CORNER``
        and every edge half of ``_SHORT`` of its length (:meth:`penalty`'s ``settled``)."""
        return self.penalty(xy).settled

    def penalty(self, xy: np.ndarray) -> _Penalty:
        """``P``, its gradient in the plan positions, ``(n, 2)``, and whether the positions are
        :meth:`settled`: a face's area (the shoelace) has ``dA/dx_u = y_v / 2`` and
        ``dA/dy_u = -x_v / 2`` over its halfedges ``u -> v``, the opposite at ``v`` (a corner
        triangle's too, :func:`_corner_area_gradient`); an edge's length ``l = |x_v - x_u|`` has
        ``dl/dx_v = (x_v - x_u) / l = -dl/dx_u``. Only the thin faces and corners and the short edges
        have a gradient."""
        r = self.ratios(xy)
        k, t = self.second_corners(xy)
        d, length = self.edge_vectors(xy)
        settled = bool(r.min() >= 0.5 * _THIN and t.min(initial=1.0) >= 0.5 * _CORNER
                       and (length / self.l0).min() >= 0.5 * _SHORT)
        h = np.maximum(0.0, _THIN - r)
        mine = np.flatnonzero(h[self.face] > 0)            # the thin faces' corners
        w = (-h / self.a0)[self.face[mine]]                # half of dP/dA per corner
        u, v, n = self.u[mine], self.v[mine], self.n
        g = np.zeros((n, 2))
        g[:, 0] += np.bincount(u, w * xy[v, 1], n) - np.bincount(v, w * xy[u, 1], n)
        g[:, 1] += np.bincount(v, w * xy[u, 0], n) - np.bincount(u, w * xy[v, 0], n)
        thin = np.flatnonzero(t < _CORNER)
        c = _CORNER - t[thin]
        at = 4 * thin + k[thin]                           # the thin corners, in the quads' corner arrays
        g += _corner_area_gradient(xy, *(a[at] for a in self.corners), -2.0 * c / self.c0[at], n)
        short = np.flatnonzero(length < _SHORT * self.l0)
        e = _THIN * (1.0 - length[short] / (_SHORT * self.l0[short]))
        per = np.divide(e, self.l0[short] * length[short], out=np.zeros_like(e), where=length[short] > 0)
        dv = (-2.0 * _THIN / _SHORT) * per[:, None] * d[short]   # dP/dx_v (none along an edge of no length)
        a, b = self.edges[short, 0], self.edges[short, 1]
        for j in range(2):
            g[:, j] += np.bincount(b, dv[:, j], n) - np.bincount(a, dv[:, j], n)
        return _Penalty(float(h @ h + c @ c + e @ e), g, settled)


class _Penalty(NamedTuple):
    """:meth:`_Folds.penalty`: its value, its gradient in the plan positions and whether they settled."""

    value: float
    gradient: np.ndarray
    settled: bool


def _corner_areas(xy: np.ndarray, u: np.ndarray, v: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Signed areas of the corner triangles of vertices ``u`` with next ``v`` and previous ``p``:
    ``(x_v - x_u) x (x_p - x_u) / 2``, positive where the corner turns counter-clockwise."""
    x, y = np.ascontiguousarray(xy[:, 0]), np.ascontiguousarray(xy[:, 1])   # one gather per coordinate
    xu, yu = x[u], y[u]
    return 0.5 * ((x[v] - xu) * (y[p] - yu) - (y[v] - yu) * (x[p] - xu))


def _corner_area_gradient(xy: np.ndarray, u: np.ndarray, v: np.ndarray, p: np.ndarray, weight: np.ndarray,
                          n: int) -> np.ndarray:
    """``sum_k weight_k d a_k / d x`` over the corner triangles of :func:`_corner_areas`, ``(n, 2)``:
    ``da/dx_v = (e2_y, -e2_x) / 2``, ``da/dx_p = (-e1_y, e1_x) / 2``, ``da/dx_u`` minus their sum."""
    e1, e2 = xy[v] - xy[u], xy[p] - xy[u]
    dv = 0.5 * weight[:, None] * np.column_stack([e2[:, 1], -e2[:, 0]])
    dp = 0.5 * weight[:, None] * np.column_stack([-e1[:, 1], e1[:, 0]])
    return np.column_stack([np.bincount(v, dv[:, j], n) + np.bincount(p, dp[:, j], n)
                            - np.bincount(u, dv[:, j] + dp[:, j], n) for j in range(2)])


def _unfolded(system: _ForceDensities, form: FormDiagram, arches: list[_Arch], sag: float, logq: np.ndarray,
              xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The relaxation of mode ``"all"`` without folded faces. Equal force densities place every free
    vertex at a convex combination of its neighbours, which folds the diagram where the supported
    boundary has reflex corners (Tutte's embedding needs a convex one): the edge lines along the
    boundary pull straight across a notch and drag the first rows of faces over its corner. There the
    interior densities become those of the plan graded towards its reflex corners (:func:`graded_plan`,
    :func:`notch_densities`), whose equilibrium is near that graded plan, so that the result is a
    discretisation of one problem at every resolution, its rows graded to the corners' singularity, and
    are then made unequal where faces still fold (:func:`_unfolding_rounds`); should that leave a fold
    (a notch spanned by a cell or two, whose isotropic densities are no discretisation of anything), the
    rounds start again from equal densities and the plan as meshed. Unchanged if nothing is folded.
    Returns ``log q_b`` and the positions (the anchors near a reflex corner moved along the outline)."""
    if not folded_faces(xy, form.loaded_faces).any():
        return logq, xy
    equal, graded = system.base.copy(), graded_plan(form)
    factors = notch_densities(graded)
    if np.any(factors != 1.0):
        notch = system.at(graded.xy)
        notch.base = equal * factors
        drifting = any(a.closed for a in arches)
        bent = [_arch(graded, k, ~form.anchors, drifting) for k in np.flatnonzero(~form.loaded)]
        start, near = notch.solve(logq), logq
        if bent:
            near, start = _sag_search(notch, bent, sag, start=logq)
        out = _unfolding_rounds(notch, _Folds(graded), graded, bent, sag, near, start)
        if not folded_faces(out[1], form.loaded_faces).any():
            system.base = notch.base
            return out
    return _unfolding_rounds(system, _Folds(form), form, arches, sag, logq, xy)


def _unfolding_rounds(system: _ForceDensities, folds: _Folds, form: FormDiagram, arches: list[_Arch], sag: float,
                      logq: np.ndarray, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """At most :data:`_UNFOLD_ROUNDS` rounds of the descent (:func:`_unfold`) and the openings' sags met
    again, from the densities in ``system.base`` and the positions ``xy``, until nothing is folded."""
    for _ in range(_UNFOLD_ROUNDS):
        if not folded_faces(xy, form.loaded_faces).any():
            break
        xy = _unfold(system, folds, system.solve(logq), logq)
        if arches:
            logq, xy = _sag_search(system, arches, sag, start=logq)
    return logq, xy


#: :func:`notch_densities`: the plan's own densities within half of ``_NOTCH_REACH`` times the plan's
#: diagonal of a reflex corner of the supported boundary, blending into equal ones at ``_NOTCH_REACH``
#: (2.1 m on the multiple-lobes plan); a reflex corner: an anchor whose loaded faces' corner angles sum
#: to more than ``_REFLEX`` degrees and less than 355 (an isolated point support has 360).
_NOTCH_REACH = 1.0 / 20.0
_REFLEX = 200.0


def reflex_anchors(form: FormDiagram) -> np.ndarray:
    """Indices of the anchors at reflex corners of the supported boundary: the corner angles of the
    loaded faces round each sum to more than :data:`_REFLEX` degrees (the notches between lobes;
    a straight boundary gives 180, an interior point support 360, which is not one).

    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh, remove_faces
    >>> v, f, _ = remove_faces(*grid_mesh(4), drop=[10, 11, 14, 15])   # an L, its outline supported
    >>> form = form_diagram(v, f)
    >>> form.xy[reflex_anchors(form)].tolist()                          # the L's inner corner
    [[2.0, 2.0]]
    """
    total = _loaded_angles(form)
    return np.flatnonzero(form.anchors & (total > _REFLEX) & (total < 355.0))


def _loaded_angles(form: FormDiagram) -> np.ndarray:
    """Per vertex, the sum of the corner angles of the loaded faces round it, in degrees (360 inside
    the loaded region, 180 on a straight stretch of its boundary)."""
    face, u, v, p = corner_arrays(form.loaded_faces)
    xy = np.asarray(form.xy)
    a, b = xy[v] - xy[u], xy[p] - xy[u]
    angle = np.mod(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b)), 2 * np.pi)
    return np.degrees(np.bincount(u, angle, form.n_vertices))


def isotropic_densities(form: FormDiagram) -> np.ndarray:
    """Per edge, the length of its dual (from the centroid of each loaded face beside it to the edge's
    midpoint, summed) over its own length, relative to the median: the force densities of a membrane
    stressed alike in every direction, discretised on the plan as meshed. Equal densities place each
    free vertex at the mean of its neighbours, the Laplacian of index space, whose harmonic map onto a
    plan with notches folds over them; these discretise the plan's own Laplacian, for which the meshed
    plan itself is (in the limit) the equilibrium: nothing moves, nothing folds.

    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> v = np.array([[0, 0], [2, 0], [4, 0], [0, 1], [2, 1], [4, 1]], dtype=float)  # two 2 x 1 faces
    >>> form = form_diagram(v, [(0, 1, 4, 3), (1, 2, 5, 4)], supports=[0, 2, 3, 5])
    >>> form.edges.tolist(), isotropic_densities(form).tolist()  # the middle edge: dual 2 m, 1 m long
    ([[0, 1], [1, 2], [1, 4], [3, 4], [4, 5]], [1.0, 1.0, 8.0, 1.0, 1.0])
    """
    xy = np.asarray(form.xy)
    face, u, _, _ = corner_arrays(form.loaded_faces)
    n_loaded = len(form.loaded_faces)
    centroid = np.column_stack([np.bincount(face, xy[u, j], n_loaded) for j in range(2)])
    centroid /= np.bincount(face, minlength=n_loaded)[:, None]
    mid = 0.5 * (xy[form.edges[:, 0]] + xy[form.edges[:, 1]])
    dual = np.zeros(form.n_edges)
    for side in form.edge_faces.T:
        has = (side >= 0) & (side < n_loaded)
        dual[has] += np.hypot(*(centroid[side[has]] - mid[has]).T)
    q = dual / form.edge_lengths()
    return q / np.median(q)


def notch_densities(form: FormDiagram) -> np.ndarray:
    """Factors on the interior densities that make the relaxation of mode ``"all"`` a discretisation of
    a fixed problem near the reflex corners of the supported boundary: within ``R / 2`` of one
    (``R``: :data:`_NOTCH_REACH` of the plan's diagonal) the :func:`isotropic_densities`, blended into
    equal ones by ``q ** w``, ``w`` falling from 1 to 0 between ``R / 2`` and ``R``; 1 farther away and
    everywhere on a plan without reflex corners. The unfolding's descent alone changes the densities
    face by face until the first moment nothing is folded, so which rows next to a notch are pinched,
    and how the steep heights there sit, depends on the mesh (issue 18: multiple_lobes' heights
    differed by 7.06% of zmax between 8,159 and 82,399 faces, 12.59% between 16,298 and 82,399);
    started from these, 3.49% and 3.36%; from these of the :func:`graded_plan` (as :func:`_unfolded`
    does since session 22), 2.37% and 2.52%.

    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh, remove_faces
    >>> v, f, _ = remove_faces(*grid_mesh(4), drop=[10, 11, 14, 15])   # an L of unit squares
    >>> bool(np.all(notch_densities(form_diagram(v, f)) == 1.0))  # squares: the plan's densities are equal
    True
    """
    corners = reflex_anchors(form)
    if not len(corners):
        return np.ones(form.n_edges)
    xy = np.asarray(form.xy)
    reach = _NOTCH_REACH * float(np.hypot(*(xy.max(axis=0) - xy.min(axis=0))))
    _, distance = nearest_within(xy[corners], 0.5 * (xy[form.edges[:, 0]] + xy[form.edges[:, 1]]), reach)
    w = np.clip(2.0 * (reach - distance) / reach, 0.0, 1.0)  # 0 beyond the reach (infinite distance)
    return isotropic_densities(form) ** w


def graded_plan(form: FormDiagram) -> FormDiagram:
    """The plan graded towards its reflex corners of the supported boundary (§5; issue 18): within a
    reach ``rho`` of each such corner ``c`` of angle ``alpha``, every free vertex moves towards ``c`` along
    its ray, ``r -> rho (r / rho) ** k`` with ``k = alpha / pi``, and every anchor on the two stretches of
    outline from ``c`` along the outline, its arc length from ``c`` mapped alike (it stays on the outline
    as meshed); the rest stays. A membrane's heights at a re-entrant corner grow like
    ``r ** (pi / alpha)`` (unbounded slope), on rows of even spacing with an error that shrinks like
    ``h ** (pi / alpha)``; on these rows they grow linearly with the row's index, as a smooth surface
    does. ``rho``: half of :data:`_NOTCH_REACH` of the plan's diagonal (where :func:`notch_densities` are
    the plan's own), at most half the way along the outline to a kink (a turn of more than
    :data:`_KINK` degrees) or to a free vertex, and half the distance to any other anchor, so that no
    kink moves and the reaches do not overlap. The plan as given where it has no such corner, or where
    the graded one would fold a face.

    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh, remove_faces
    >>> v, f, _ = remove_faces(*grid_mesh(40), drop=[k for k in range(1600) if k % 40 >= 20 and k >= 800])
    >>> form = form_diagram(v / 4.0, f)             # an L of 10 m in cells of 0.25 m, its inner corner at (5, 5)
    >>> rho = 0.5 * 0.05 * np.hypot(10.0, 10.0)     # 0.354 m: the first row moves, k = 270 / 180
    >>> graded = graded_plan(form).xy
    >>> at = [int(np.flatnonzero((form.xy == p).all(axis=1))[0]) for p in ([4.75, 5.0], [5.25, 5.0])]
    >>> form.anchors[at].tolist()                   # a free vertex and an anchor on the outline
    [False, True]
    >>> graded[at].round(4).tolist(), round(float(rho * (0.25 / rho) ** 1.5), 4)
    ([[4.7898, 5.0], [5.2102, 5.0]], 0.2102)
    """
    corners = reflex_anchors(form)
    if not len(corners):
        return form
    xy, angles = np.asarray(form.xy), _loaded_angles(form)
    k = angles[corners] / 180.0
    reach = _NOTCH_REACH * float(np.hypot(*np.ptp(xy, axis=0)))
    chains = [_outline_chain(form, corners, step, np.abs(angles - 180.0), reach) for step in _outline_neighbours(form)]
    rho = _grading_reach(form, corners, chains, 0.5 * reach)
    graded = xy.copy()
    index, r = nearest_within(xy[corners], xy, float(rho.max()))
    inside = np.flatnonzero((index >= 0) & (r < rho[np.maximum(index, 0)]) & (r > 0) & ~form.anchors)
    i = index[inside]
    graded[inside] = xy[corners[i]] + (xy[inside] - xy[corners[i]]) * ((r[inside] / rho[i]) ** (k[i] - 1))[:, None]
    for chain, arc in chains:
        for j, c in enumerate(corners):
            on = np.flatnonzero(arc[j] < rho[j])
            s = rho[j] * (arc[j, on] / rho[j]) ** k[j]
            path = xy[np.r_[c, chain[j]]]
            length = np.r_[0.0, arc[j]]
            graded[chain[j, on]] = np.column_stack([np.interp(s, length, path[:, d]) for d in range(2)])
    return form if folded_faces(graded, form.loaded_faces).any() else form.with_xy(graded)


#: :func:`graded_plan`: a turn of the outline by more than this many degrees is a kink, which stays.
_KINK = 20.0


def _outline_chain(form: FormDiagram, corners: np.ndarray, step: np.ndarray, turn: np.ndarray,
                   reach: float) -> tuple[np.ndarray, np.ndarray]:
    """From each corner, the vertices met going along the outline by ``step`` (next or previous,
    :func:`_outline_neighbours`) up to the first that is no straight anchor (a free vertex, or a kink:
    ``turn``, the vertex's loaded angles' difference to 180 degrees, over :data:`_KINK`; it is the
    chain's last), at most ``reach`` along it; per corner, their indices and arc lengths from it,
    ``(corners, m)``, the arc infinite past the end."""
    xy = np.asarray(form.xy)
    at, arc = corners.copy(), np.zeros(len(corners))
    open_ = np.ones(len(corners), dtype=bool)
    vertices, lengths = [], []
    while open_.any():
        nxt = np.where(open_, step[at], at)
        open_ &= nxt >= 0
        nxt = np.where(open_, nxt, at)
        arc = np.where(open_, arc + np.hypot(*(xy[nxt] - xy[at]).T), np.inf)
        vertices.append(nxt)
        lengths.append(arc.copy())
        at = nxt
        open_ &= form.anchors[at] & (turn[at] <= _KINK) & (arc < reach) & ~np.isin(at, corners)
    return np.column_stack(vertices), np.column_stack(lengths)


def _grading_reach(form: FormDiagram, corners: np.ndarray, chains: list, reach: float) -> np.ndarray:
    """Per reflex anchor in ``corners``, the reach of :func:`graded_plan`: ``reach``, at most half the arc
    length along either of its outline ``chains`` to the chain's last vertex (a kink, a free vertex, or
    as far as the chain looked), and half the distance to the nearest anchor on neither chain."""
    xy = np.asarray(form.xy)
    rho = np.full(len(corners), float(reach))
    on_chain = np.zeros((len(corners), form.n_vertices), dtype=bool)
    for chain, arc in chains:
        finite = np.isfinite(arc)
        last = np.where(finite, arc, -np.inf).max(axis=1)
        rho = np.minimum(rho, 0.5 * last)
        rows = np.repeat(np.arange(len(corners)), finite.sum(axis=1))
        on_chain[rows, chain[finite]] = True
    on_chain[np.arange(len(corners)), corners] = True
    anchors = np.flatnonzero(form.anchors)
    at, j = pairs_within(xy[anchors], xy[corners], reach)
    off = ~on_chain[at, anchors[j]]
    np.minimum.at(rho, at[off], 0.5 * np.hypot(*(xy[anchors[j[off]]] - xy[corners[at[off]]]).T))
    return rho


def _outline_neighbours(form: FormDiagram) -> tuple[np.ndarray, np.ndarray]:
    """Per vertex, its next and previous vertex along the outline of the loaded faces (-1 inside): the
    halfedges of loaded faces without a twin among them, the faces on their left."""
    _, u, v, _ = corner_arrays(form.loaded_faces)
    n = form.n_vertices
    keys = np.sort(u * n + v)
    twin = v * n + u
    at = np.minimum(np.searchsorted(keys, twin), len(keys) - 1)
    lone = keys[at] != twin
    nxt, prv = np.full(n, -1), np.full(n, -1)
    nxt[u[lone]], prv[v[lone]] = v[lone], u[lone]
    return nxt, prv


def _unfold(system: _ForceDensities, folds: _Folds, xy: np.ndarray, logq: np.ndarray) -> np.ndarray:
    """Descent on the log densities of the interior edges (so every ``q`` stays positive, and the
    positions stay in exact equilibrium with them) against :class:`_Folds`' penalty, gradient by the
    adjoint (:meth:`_ForceDensities.density_gradient`), steps of at most ``eta`` in any log density,
    halved until the penalty drops; it stops when :meth:`_Folds.settled`.
    On the multiple-lobes plan the densities grow on the edges holding the first rows to the notches'
    corners and drop on those along the boundary. ``xy``: the positions of the last solve; returns the
    final ones (``system.base`` holds the densities)."""
    inner = system.interior
    penalty, g, settled = folds.penalty(xy)
    eta = 0.5
    for _ in range(_UNFOLD_STEPS):
        if settled:
            break
        grad = (system.base * system.density_gradient(xy, g))[inner]
        if not np.any(grad):
            break
        s = np.log(system.base[inner])
        while eta > 1e-6:
            system.base[inner] = np.exp(s - eta * grad / np.abs(grad).max())
            trial = system.solve(logq)
            p_trial, g_trial, settled_trial = folds.penalty(trial)
            if p_trial < penalty:
                xy, penalty, g, settled, eta = trial, p_trial, g_trial, settled_trial, min(1.5 * eta, 1.0)
                break
            eta *= 0.5
        else:
            system.base[inner] = np.exp(s)
            return system.solve(logq)
    return xy


def _collapsed(form: FormDiagram, out: FormDiagram) -> np.ndarray:
    """Per edge, whether it shrank below a thousandth of its length."""
    return ~(out.edge_lengths() > 1e-3 * form.edge_lengths())


def _check_not_collapsed(form: FormDiagram, out: FormDiagram) -> None:
    """No edge shrank below a thousandth of its length: the supports held the open edges apart."""
    l0, l1 = form.edge_lengths(), out.edge_lengths()
    short = np.flatnonzero(_collapsed(form, out))
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
