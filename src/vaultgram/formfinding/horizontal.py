"""Horizontal equilibrium of a thrust network (TNA step 1; Block & Ochsendorf 2007, §5 of the paper).

The form and force diagrams are reciprocal: they are in horizontal equilibrium when corresponding
edges are parallel (our force diagram is stored turned by -90 degrees, see
:mod:`vaultgram.formfinding.forcediagram`). Following compas_tna / RhinoVAULT (Rippmann et al. 2012), both
diagrams are iteratively made parallel to target directions, the normalised blend

    t_e = alpha * form_e / |form_e| + (1 - alpha) * force_e / |force_e|,    alpha in [0, 1]

(``alpha = 100`` percent keeps the form diagram and only moves the force diagram). Each diagram is
updated by a least-squares fit of its edge vectors to the targets ``|current edge| * t_e``, anchors
(form) and one vertex per component (force) held fixed. This is still the parallelisation iteration
(its fixed points are exactly the parallel diagrams), with two changes that make it fast on meshes
with openings; neither replaces it by a direct construction:

* **weighted fit.** compas_tna fits with equal weights (``length_weight = 1``). That is an alternating
  projection between "closed force polygons" and "edges parallel to t", which converges slowly for
  the smooth, nearly-parallel modes of a fine mesh: on the quad-with-hole mesh 19 iterations at 10^3
  faces, 347 at 10^4, thousands at 10^5. We weight a deviation across ``t_e`` ``1 / mu`` times more
  than a change of length (``W_e = n n^T + mu t t^T`` in the frame of the initial target directions,
  ``mu = length_weight = 0.01``); modes are then damped by ``mu / (lambda + mu)`` instead of
  ``1 / (1 + lambda)`` per iteration, and the same meshes need 1, 4 and about 20 iterations. The
  frame is fixed, so each diagram's matrix is factorised once (x and y are coupled; see
  :class:`vaultgram.formfinding.forcediagram.WeightedFit`) and every iteration is one sparse triangular solve
  per moving diagram -- no Python loop over vertices or edges.
* **safeguarded Anderson acceleration** (window ``anderson = 5``) of the fixed-point map: an
  extrapolated iterate is taken only when its max angle is not worse than the plain update's.

A form diagram meshed with a fixed pattern generally has *no* exactly parallel compression-only
reciprocal (the exact LP check finds none for the relaxed quad-with-hole meshes); the iteration then
approaches a floor of small angles (about 0.01 to 0.03 degrees there), and the tolerance is what is
guaranteed, as in compas_tna and RhinoVAULT.

Unlike compas_tna, which runs a fixed number of iterations, the loop stops on a real test: the largest
angle between corresponding edges below ``tol_deg``. It stops early when the angle no longer decreases
and then says why: edges whose force collapsed to zero length or flipped (about 180 degrees, i.e.
tension -- no compression-only solution for this form diagram), or plain non-convergence.

:func:`horizontal` reads as these phases: build the fixed-point map (:class:`_Parallelisation`), iterate
it with acceleration (:func:`_parallelise`), check the form edges, settle (collapse test, LP rescue),
and read the force densities off the diagrams -- or explain the failure (:func:`_failure`).

:func:`vaultgram.formfinding.relaxation.relax_openings` prepares form diagrams with openings: a
straight unsupported edge cannot carry the thrust of the edges meeting it in compression, so open
edges are first bent by the force density method into arches with a prescribed sag (as RhinoVAULT's
"relax"). It is importable from here too (its former home).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import NamedTuple

import numpy as np
import scipy.sparse as sp

from vaultgram import progress
from vaultgram.errors import ConvergenceError, FormFindingError, HorizontalEquilibriumError
from vaultgram.formfinding.forcediagram import ForceDiagram, PinnedLaplacian, WeightedFit, force_diagram
from vaultgram.formfinding.formdiagram import FormDiagram
from vaultgram.formfinding.relaxation import opening_edges, relax_openings  # their former home: still importable
from vaultgram.geometry.arrays import steady

__all__ = ["HorizontalResult", "horizontal", "angle_deviations", "compression_lp",
           "relax_openings", "opening_edges"]


@dataclass(frozen=True, eq=False)
class HorizontalResult:
    """Outcome of :func:`horizontal`.

    Attributes
    ----------
    form, force : the diagrams after parallelisation
    q : ndarray (m,)
        Force densities ``|force edge| / |form edge|`` per form edge (0 on edges between two anchors,
        which have no force edge); negative where an edge is flipped.
    angles : ndarray (k,)
        Angle deviation in degrees per force edge (``force.form_edge`` gives the form edge).
    max_angle : float
        Largest angle deviation (degrees).
    iterations : int
        Parallelisation iterations performed (0 when the initial diagrams were already parallel).
    history : tuple of float
        Max angle deviation before each iteration and after the last one.
    converged : bool
    method : str
        ``"parallelisation"`` or ``"lp"`` (the iteration stalled and :func:`compression_lp` found the
        compression-only reciprocal of the current form diagram).
    """

    form: FormDiagram
    force: ForceDiagram
    q: np.ndarray
    angles: np.ndarray
    max_angle: float
    iterations: int
    history: tuple = field(repr=False)
    converged: bool = True
    method: str = "parallelisation"


def angle_deviations(u: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Angles in degrees, in [0, 180], between row vectors ``u`` and ``d`` (180 for flipped edges).

    >>> angle_deviations(np.array([[1.0, 0.0], [1.0, 0.0]]), np.array([[2.0, 2.0], [-1.0, 0.0]])).tolist()
    [45.0, 180.0]
    """
    cross = u[:, 0] * d[:, 1] - u[:, 1] * d[:, 0]
    dot = np.einsum("ij,ij->i", u, d)
    return np.degrees(np.abs(np.arctan2(cross, dot)))


def _unit(v: np.ndarray) -> np.ndarray:
    """Rows of ``v`` scaled to unit length (zero rows stay zero)."""
    n = np.hypot(v[:, 0], v[:, 1])[:, None]
    return np.divide(v, n, out=np.zeros_like(v), where=n > 0)  # no gather of the non-zero rows


def _lengths(v: np.ndarray) -> np.ndarray:
    return np.hypot(v[:, 0], v[:, 1])


def _max_angle(u: np.ndarray, d: np.ndarray) -> float:
    return float(angle_deviations(u, d).max()) if len(u) else 0.0


def _targets(u: np.ndarray, d: np.ndarray, a: float) -> np.ndarray:
    """Unit target directions ``t_e``: the blend ``a form_e / |form_e| + (1 - a) force_e / |force_e|``,
    the form's own direction where the blend vanishes (form and force opposite, ``a = 1/2``)."""
    uh = _unit(u)
    t = a * uh + (1.0 - a) * _unit(d)
    vanishing = np.hypot(t[:, 0], t[:, 1]) < 1e-12
    t[vanishing] = uh[vanishing]
    return _unit(t)


def _signed_densities(angles: np.ndarray, force_lengths: np.ndarray, form_lengths: np.ndarray) -> np.ndarray:
    """``|force edge| / |form edge|``, negative for flipped edges (tension)."""
    return np.where(angles > 90.0, -1.0, 1.0) * force_lengths / form_lengths


def _collapsed(force_lengths: np.ndarray, min_force: float) -> np.ndarray:
    """Force edges shorter than ``min_force`` times the median force length."""
    return np.flatnonzero(force_lengths <= min_force * max(float(np.median(force_lengths)), 1e-300))


def compression_lp(form: FormDiagram, force: ForceDiagram, q_ref: np.ndarray | None = None
                   ) -> tuple[float, np.ndarray, np.ndarray]:
    """Decide whether the (fixed) form diagram admits a compression-only reciprocal, by linear programming.

    Unknowns: force densities ``q`` of the active edges and force-diagram positions ``y``. Constraints:
    ``force_e = q_e * form_e`` for every edge (reciprocity, exact), ``sum q = sum q_ref``. Objective:
    maximise ``s`` subject to ``q_e >= s * q_ref_e``. A compression-only solution exists iff ``s > 0``.
    This is the exact test behind the error "no compression-only solution", and the rescue when the
    parallelisation iteration stalls although a solution exists.

    Returns
    -------
    s : float
        Optimal ``s`` (``<= 0``: no compression-only equilibrium; ``-inf`` if the LP failed).
    q : ndarray (k,)
        Force densities per force edge.
    y : ndarray (F, 2)
        Force-diagram positions.

    Example
    -------
    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> form = form_diagram(*grid_mesh(3))
    >>> s, q, y = compression_lp(form, force_diagram(form))
    >>> bool(s > 0), bool(np.all(q > 0))
    (True, True)
    """
    from scipy.optimize import linprog

    k, F = force.n_edges, force.n_vertices
    q_ref = np.ones(k) if q_ref is None else q_ref
    A_eq, b_eq = _reciprocity_constraints(form, force, q_ref)
    A_ub = sp.hstack([-sp.identity(k), sp.csr_matrix((k, 2 * F)), sp.csr_matrix(q_ref.reshape(-1, 1))]).tocsc()
    c = np.zeros(k + 2 * F + 1)
    c[-1] = -1.0
    bounds = [(0, None)] * k + [(None, None)] * (2 * F) + [(None, 1.0)]
    res = linprog(c, A_ub=A_ub, b_ub=np.zeros(k), A_eq=A_eq, b_eq=b_eq, bounds=bounds, method="highs")
    if res.status != 0:
        return -np.inf, np.zeros(k), np.array(force.xy)
    x = res.x
    return float(x[-1]), x[:k], np.column_stack([x[k:k + F], x[k + F:k + 2 * F]])


def _reciprocity_constraints(form: FormDiagram, force: ForceDiagram, q_ref: np.ndarray
                             ) -> tuple[sp.csc_matrix, np.ndarray]:
    """``force_e - q_e form_e = 0`` (x and y) for every force edge, and ``sum q = sum q_ref``, over the
    unknowns ``(q, y_x, y_y, s)`` of :func:`compression_lp`."""
    U = form.C[force.form_edge] @ form.xy
    k, F = force.n_edges, force.n_vertices
    D = force.C.tocsr()
    Z = sp.csr_matrix((k, F))
    zcol = sp.csr_matrix((k, 1))
    A_eq = sp.vstack([
        sp.hstack([-sp.diags(U[:, 0]), D, Z, zcol]),
        sp.hstack([-sp.diags(U[:, 1]), Z, D, zcol]),
        sp.hstack([sp.csr_matrix(np.ones((1, k))), sp.csr_matrix((1, 2 * F + 1))]),
    ]).tocsc()
    return A_eq, np.concatenate([np.zeros(2 * k), [q_ref.sum()]])


def horizontal(form: FormDiagram, force: ForceDiagram | None = None, *, alpha: float = 100.0,
               kmax: int = 1000, tol_deg: float = 0.5, min_force: float = 1e-6,
               stall_window: int = 50, rescue: bool = True, raise_on_failure: bool = True,
               length_weight: float = 0.01, anderson: int = 5, lp_max_edges: int = 5000) -> HorizontalResult:
    """Parallelise form and force diagrams until the max angle deviation is below ``tol_deg`` (TNA step 1).

    Parameters
    ----------
    form : FormDiagram
    force : ForceDiagram, optional
        Initial force diagram (default: :func:`vaultgram.formfinding.forcediagram.force_diagram`).
    alpha : float
        Percentage weight of the form diagram in the target directions (100: form fixed, force moves;
        0: force fixed, form moves), as compas_tna ``horizontal_nodal``.
    kmax, tol_deg : int, float
        Iteration cap; stopping tolerance on the largest angle between corresponding edges (degrees).
    min_force : float
        A force edge shorter than ``min_force * median force length`` counts as collapsed.
    stall_window : int
        Stop early when the max angle has not dropped by 1% over this many iterations.
    rescue : bool
        When the iteration stalls or hits ``kmax``, decide exactly by linear programming
        (:func:`compression_lp`, up to ``lp_max_edges`` force edges: HiGHS takes about 1 s at 2,000,
        minutes at 20,000) whether the current form diagram has a compression-only reciprocal; if so,
        use it (``method == "lp"``), otherwise raise :class:`HorizontalEquilibriumError`.
    raise_on_failure : bool
        Raise (default) or return a result with ``converged=False``.
    length_weight : float in (0, 1]
        ``mu`` of the weighted fit (module docstring): a change of length costs ``mu`` times a deviation
        across the target direction. 1 is compas_tna's plain fit (hundreds to thousands of iterations
        on meshes with openings); the default 0.01 needs a few.
    anderson : int
        Window of the safeguarded Anderson acceleration (0: off); stopping test and failure detection
        stay those of the plain iteration.

    Raises
    ------
    HorizontalEquilibriumError
        edges flipped (tension) or collapsed: no compression-only solution; names edges and angles.
    ConvergenceError
        the angle did not drop below ``tol_deg`` within ``kmax`` iterations (``.result`` attached).

    Example
    -------
    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> h = horizontal(form_diagram(*grid_mesh(4)))
    >>> h.converged, h.iterations, h.max_angle < 1e-9
    (True, 0, True)
    """
    force = force_diagram(form) if force is None else force
    fpm = _Parallelisation(form, force, _form_weight(alpha, length_weight), length_weight)
    lp_ok = rescue and len(force.form_edge) <= lp_max_edges
    flip_window = None if lp_ok else min(stall_window, _FLIP_WINDOW)
    it, k, history, converged = _parallelise(fpm, tol_deg, kmax, stall_window, anderson, flip_window)
    new_form = _moved_form(form, fpm, it)
    end = _settled(new_form, fpm, it, converged, min_force, lp_ok, tol_deg, tuple(history))
    res = HorizontalResult(form=new_form, force=force.with_xy(end.y), q=_force_densities(form, force, end),
                           angles=end.angles, max_angle=end.max_angle, iterations=k, history=end.history,
                           converged=end.converged, method=end.method)
    if res.converged or not raise_on_failure:
        return res
    raise _failure(res, force.form_edge, end, min_force, rescue, lp_max_edges, tol_deg)


def _form_weight(alpha: float, length_weight: float) -> float:
    """``alpha`` as a fraction in [0, 1]; ``length_weight`` checked."""
    if not 0.0 < length_weight <= 1.0:
        raise FormFindingError(f"length_weight must be in (0, 1], got {length_weight}")
    return min(max(float(alpha) / 100.0, 0.0), 1.0)


# ---- the iteration ---------------------------------------------------------------------------------


class _Iterate(NamedTuple):
    """Both diagrams at one iterate: positions, edge vectors of the active edges, the max angle."""

    xy: np.ndarray
    y: np.ndarray
    u: np.ndarray
    d: np.ndarray
    amax: float


class _Parallelisation:
    """The fixed-point map of the parallelisation: each diagram fitted to its targets ``|edge| t_e``.

    The fit's frame is the initial target directions, fixed, so each moving diagram's matrix is
    factorised once, on the first step (never when the start is already parallel).
    """

    def __init__(self, form: FormDiagram, force: ForceDiagram, a: float, length_weight: float):
        self.form, self.force, self.a, self.mu = form, force, a, length_weight
        self.Cu = form.C[force.form_edge].tocsr()
        self.Cd = force.C
        self.start = self.iterate(np.array(form.xy, dtype=float), np.array(force.xy, dtype=float))

    @cached_property
    def frame(self) -> np.ndarray:
        """The initial target directions (made on the first step: never when the start is parallel)."""
        return _targets(self.start.u, self.start.d, self.a)

    def iterate(self, xy: np.ndarray, y: np.ndarray) -> _Iterate:
        u, d = self.Cu @ xy, self.Cd @ y
        return _Iterate(xy, y, u, d, _max_angle(u, d))

    @cached_property
    def solvers(self) -> tuple:
        """Form and force fits (None for a diagram that does not move: ``alpha`` 100 or 0)."""
        return (self._fit(self.Cu, self.form.fixed) if self.a < 1.0 else None,
                self._fit(self.Cd, self.force.pins) if self.a > 0.0 else None)

    def _fit(self, C: sp.csr_matrix, pinned: np.ndarray):
        """The plain fit of compas_tna (``mu = 1``) or the weighted one in the fixed frame."""
        return PinnedLaplacian(C, pinned) if self.mu == 1.0 else WeightedFit(C, pinned, self.frame, self.mu)

    def step(self, it: _Iterate) -> _Iterate:
        """One parallelisation update of both diagrams (the fixed-point map)."""
        form_fit, force_fit = self.solvers
        t = _targets(it.u, it.d, self.a)
        xy = form_fit.solve(_lengths(it.u)[:, None] * t, it.xy) if form_fit is not None else it.xy
        y = force_fit.solve(_lengths(it.d)[:, None] * t, it.y) if force_fit is not None else it.y
        return self.iterate(xy, y)


class _Anderson:
    """Safeguarded Anderson acceleration of a fixed-point map over the last ``window`` iterates: an
    extrapolation is taken only when its max angle is not worse than the plain update's (otherwise
    the window restarts)."""

    def __init__(self, window: int):
        self.window = window
        self.X: list[np.ndarray] = []       # iterates and their residuals g(x) - x
        self.G: list[np.ndarray] = []

    def next(self, fpm: _Parallelisation, it: _Iterate, plain: _Iterate) -> _Iterate:
        if self.window <= 0:
            return plain
        x_now = np.concatenate([it.xy.ravel(), it.y.ravel()])
        x_g = np.concatenate([plain.xy.ravel(), plain.y.ravel()])
        self.X.append(x_now)
        self.G.append(x_g - x_now)
        if len(self.X) > self.window + 1:
            self.X.pop(0)
            self.G.pop(0)
        if len(self.X) == 1:
            return plain
        dX = np.diff(np.array(self.X), axis=0).T
        dG = np.diff(np.array(self.G), axis=0).T
        x_aa = x_g - (dX + dG) @ np.linalg.lstsq(dG, self.G[-1], rcond=None)[0]
        n = it.xy.size
        extrapolated = fpm.iterate(x_aa[:n].reshape(it.xy.shape), x_aa[n:].reshape(it.y.shape))
        if extrapolated.amax <= plain.amax and np.all(np.isfinite(x_aa)):
            return extrapolated
        self.X, self.G = [], []
        return plain


#: Without the LP rescue (too many edges), the iteration gives up once some edge has stayed flipped
#: (max angle above 90 degrees) for this many iterations: on the fine meshes where that happens it
#: never recovered, and each iteration costs a solve (the pipeline then relaxes the pattern).
_FLIP_WINDOW = 10


def _parallelise(fpm: _Parallelisation, tol_deg: float, kmax: int, stall_window: int, anderson: int,
                 flip_window: int | None = None) -> tuple[_Iterate, int, list[float], bool]:
    """Iterate until the max angle is below ``tol_deg`` (converged), ``kmax`` iterations, a stall, or
    an edge flipped for ``flip_window`` iterations (None: no such test): the last iterate, the number
    of iterations, the max angle before each and after the last, and whether it converged."""
    it, history, acceleration = fpm.start, [], _Anderson(anderson)
    flip_window = kmax + 1 if flip_window is None else flip_window
    tick = progress.ticker("horizontal", kmax)
    while True:
        tick()
        history.append(it.amax)
        if it.amax < tol_deg:
            return it, len(history) - 1, history, True
        if len(history) > kmax or _stalled(history, stall_window) or _flipped(history, flip_window):
            return it, len(history) - 1, history, False
        it = acceleration.next(fpm, it, fpm.step(it))


def _flipped(history: list[float], window: int) -> bool:
    """Some edge has been flipped (max angle above 90 degrees) at each of the last ``window`` iterates
    after the start."""
    return len(history) > window and min(history[-window:]) > 90.0


def _stalled(history: list[float], window: int) -> bool:
    """The max angle has not dropped by 1% over the last ``window`` iterations."""
    return len(history) > window and history[-1 - window] - history[-1] < 0.01 * history[-1 - window]


# ---- after the iteration ----------------------------------------------------------------------------


def _moved_form(form: FormDiagram, fpm: _Parallelisation, it: _Iterate) -> FormDiagram:
    """The form diagram at the last iterate (itself when ``alpha = 100``); no form edge may vanish."""
    short = np.flatnonzero(~(_lengths(it.u) > 0))
    if len(short):
        raise FormFindingError(f"form {form.edge_name(int(fpm.force.form_edge[short[0]]))} has collapsed to zero "
                               f"length during horizontal equilibrium; use a larger alpha")
    return form.with_xy(it.xy) if fpm.a < 1.0 else form


class _Settled(NamedTuple):
    """Where horizontal equilibrium ended, per force edge, after the LP rescue if there was one."""

    y: np.ndarray
    angles: np.ndarray
    form_lengths: np.ndarray
    force_lengths: np.ndarray
    max_angle: float
    converged: bool
    method: str
    lp_s: float | None
    history: tuple


def _settled(form: FormDiagram, fpm: _Parallelisation, it: _Iterate, converged: bool, min_force: float,
             lp_ok: bool, tol_deg: float, history: tuple) -> _Settled:
    """The end state: converged only if no force edge collapsed either; when the iteration failed, the
    compression-only reciprocal of the current form diagram by :func:`compression_lp` if there is one
    (``method == "lp"``)."""
    angles, lu, ld = angle_deviations(it.u, it.d), _lengths(it.u), _lengths(it.d)
    converged = converged and not len(_collapsed(ld, min_force))
    end = _Settled(it.y, angles, lu, ld, it.amax, converged, "parallelisation", None, history)
    if converged or not lp_ok:
        return end
    signed = _signed_densities(angles, ld, lu)
    positive = signed[signed > 0]
    floor = 0.1 * float(np.median(positive)) if len(positive) else 1.0
    lp_s, _, y = compression_lp(form, fpm.force, np.maximum(signed, floor))
    if lp_s <= 1e-9:
        return end._replace(lp_s=lp_s)
    d = fpm.Cd @ y
    angles = angle_deviations(it.u, d)
    amax = float(angles.max()) if len(angles) else 0.0
    return _Settled(y, angles, lu, _lengths(d), amax, amax < tol_deg, "lp", lp_s, (*history, amax))


def _force_densities(form: FormDiagram, force: ForceDiagram, end: _Settled) -> np.ndarray:
    """``q`` per form edge: ``|force edge| / |form edge|``, negative where flipped, 0 without force edge."""
    q = np.zeros(form.n_edges)
    q[force.form_edge] = _signed_densities(end.angles, end.force_lengths, end.form_lengths)
    return q


def _failure(res: HorizontalResult, act: np.ndarray, end: _Settled, min_force: float, rescue: bool,
             lp_max_edges: int, tol_deg: float) -> FormFindingError | ConvergenceError:
    """The error that explains why ``res`` did not converge: no compression-only equilibrium (the LP
    found none, or without the LP, edges flipped or collapsed), or plain non-convergence."""
    collapsed = _collapsed(end.force_lengths, min_force)
    flipped = np.setdiff1d(np.flatnonzero(res.angles > 90.0), collapsed)  # a zero vector's angle is round-off
    disproved = end.lp_s is not None and end.lp_s <= 1e-9
    if not (disproved or (end.lp_s is None and (len(flipped) or len(collapsed)))):
        return _not_converged(res, act, tol_deg)
    proof = (" (checked exactly by linear programming)" if end.lp_s is not None else
             " (not checked exactly: rescue=False)" if not rescue else
             f" (not checked exactly: {len(act)} force edges > lp_max_edges = {lp_max_edges})")
    return _no_compression(res, act, end.force_lengths, flipped, collapsed, proof, tol_deg)


def _not_converged(res: HorizontalResult, act: np.ndarray, tol_deg: float) -> ConvergenceError:
    """Plain non-convergence within ``kmax``, naming the five worst edges (``.result`` attached)."""
    desc = "; ".join(f"{res.form.edge_name(act[i])}: {res.angles[i]:.2f} deg" for i in np.argsort(-res.angles)[:5])
    err = ConvergenceError(
        f"horizontal equilibrium did not converge: max angle deviation {res.max_angle:.3g} deg > {tol_deg} deg "
        f"after {res.iterations} iterations (worst: {desc}); raise kmax, change alpha or relax the form diagram")
    err.result = res
    return err


def _no_compression(res: HorizontalResult, act: np.ndarray, force_lengths: np.ndarray, flipped: np.ndarray,
                    collapsed: np.ndarray, proof: str, tol_deg: float) -> HorizontalEquilibriumError:
    """No compression-only reciprocal: the flipped (tension) and collapsed edges, or, when every force
    edge is in compression, the angle floor of a form that is only approximately balanceable."""
    angles, k, amax = res.angles, res.iterations, res.max_angle
    bad = np.concatenate([flipped[np.argsort(-steady(angles[flipped], 180.0), kind="stable")], collapsed])
    bad = np.argsort(-steady(angles, 180.0), kind="stable")[:8] if len(bad) == 0 else bad
    gone = set(collapsed.tolist())  # no direction to report
    desc = "; ".join(f"{res.form.edge_name(act[i])}: " + ("collapsed" if i in gone else
                     f"{angles[i]:.1f} deg, force length {force_lengths[i]:.2g}") for i in bad[:8])
    if len(flipped) == 0 and len(collapsed) == 0:
        message = (
            f"horizontal equilibrium stalled at a max angle deviation of {amax:.3g} deg > {tol_deg} deg after "
            f"{k} iterations, with every force edge in compression; this form diagram has no exactly "
            f"parallel compression-only reciprocal{proof}, so the tolerance is below what it allows "
            f"(worst: {desc}); raise the tolerance (--tol-deg) or let every vertex move (--relax-mode all)")
    else:
        message = (
            f"no compression-only horizontal equilibrium for this form diagram{proof}: after {k} iterations "
            f"{len(flipped)} force edges flipped (tension) and {len(collapsed)} collapsed to zero length, "
            f"e.g. {desc}. Straight unsupported edges cannot be in compression: bend the openings more "
            f"(--sag, --relax-mode all), move the pattern or support more of the boundary (--supports)")
    return HorizontalEquilibriumError(message, edges=act[bad].tolist(), angles=angles[bad].tolist(), result=res,
                                      places=res.form.xy[res.form.edges[act[bad]]])
