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

:func:`relax_openings` prepares form diagrams with openings: a straight unsupported edge cannot carry
the thrust of the edges meeting it in compression, so open edges are first bent by the force density
method into arches with a prescribed sag (as RhinoVAULT's "relax").
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from vaultgram.errors import ConvergenceError, FormFindingError, HorizontalEquilibriumError
from vaultgram.formfinding.forcediagram import ForceDiagram, PinnedLaplacian, WeightedFit, force_diagram
from vaultgram.formfinding.formdiagram import FormDiagram

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
    """Angles in degrees, in [0, 180], between row vectors ``u`` and ``d`` (180 for flipped edges)."""
    cross = u[:, 0] * d[:, 1] - u[:, 1] * d[:, 0]
    dot = np.einsum("ij,ij->i", u, d)
    return np.degrees(np.abs(np.arctan2(cross, dot)))


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.hypot(v[:, 0], v[:, 1])
    out = np.zeros_like(v)
    ok = n > 0
    out[ok] = v[ok] / n[ok, None]
    return out


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
    """
    from scipy.optimize import linprog

    act = force.form_edge
    U = (form.C[act] @ form.xy)
    k, F = force.n_edges, force.n_vertices
    if q_ref is None:
        q_ref = np.ones(k)
    D = force.C.tocsr()
    Z = sp.csr_matrix((k, F))
    zcol = sp.csr_matrix((k, 1))
    A_eq = sp.vstack([
        sp.hstack([-sp.diags(U[:, 0]), D, Z, zcol]),
        sp.hstack([-sp.diags(U[:, 1]), Z, D, zcol]),
        sp.hstack([sp.csr_matrix(np.ones((1, k))), sp.csr_matrix((1, 2 * F + 1))]),
    ]).tocsc()
    b_eq = np.concatenate([np.zeros(2 * k), [q_ref.sum()]])
    A_ub = sp.hstack([-sp.identity(k), sp.csr_matrix((k, 2 * F)), sp.csr_matrix(q_ref.reshape(-1, 1))]).tocsc()
    b_ub = np.zeros(k)
    c = np.zeros(k + 2 * F + 1)
    c[-1] = -1.0
    bounds = [(0, None)] * k + [(None, None)] * (2 * F) + [(None, 1.0)]
    res = linprog(c, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=b_eq, bounds=bounds, method="highs")
    if res.status != 0:
        return -np.inf, np.zeros(k), np.array(force.xy)
    x = res.x
    y = np.column_stack([x[k:k + F], x[k + F:k + 2 * F]])
    return float(x[-1]), x[:k], y


def horizontal(form: FormDiagram, force: ForceDiagram | None = None, *, alpha: float = 100.0,
               kmax: int = 1000, tol_deg: float = 0.5, min_force: float = 1e-6,
               stall_window: int = 50, rescue: bool = True, raise_on_failure: bool = True,
               length_weight: float = 0.01, anderson: int = 5, lp_max_edges: int = 5000) -> HorizontalResult:
    """Parallelise form and force diagrams until the max angle deviation is below ``tol_deg``.

    Parameters
    ----------
    form : FormDiagram
    force : ForceDiagram, optional
        Initial force diagram (default: :func:`vaultgram.formfinding.forcediagram.force_diagram` least squares).
    alpha : float
        Percentage weight of the form diagram in the target directions (100: form fixed, force moves;
        0: force fixed, form moves), as compas_tna ``horizontal_nodal``.
    kmax : int
        Iteration cap.
    tol_deg : float
        Stopping tolerance on the largest angle between corresponding edges (degrees).
    min_force : float
        A force edge shorter than ``min_force * median force length`` counts as collapsed.
    stall_window : int
        Stop early when the max angle has not dropped by 1% over this many iterations.
    rescue : bool
        When the iteration stalls or hits ``kmax`` (and there are at most ``lp_max_edges`` force
        edges), decide exactly by linear programming
        (:func:`compression_lp`) whether the current form diagram has a compression-only reciprocal;
        if so, use it (``method == "lp"`` in the result), otherwise raise
        :class:`HorizontalEquilibriumError`.
    raise_on_failure : bool
        Raise (default) or return a result with ``converged=False``.
    length_weight : float in (0, 1]
        ``mu`` of the weighted fit (see the module docstring): a change of an edge's length costs
        ``mu`` times a deviation across its target direction. 1 is the plain fit of compas_tna
        (hundreds to thousands of iterations on meshes with openings); the default 0.01 needs a few.
    anderson : int
        Window of the Anderson acceleration of the iteration (0: off). An extrapolated iterate is
        accepted only if its max angle is not worse than the plain update's; otherwise the plain
        update is taken and the window restarts, so the stopping test and failure detection are
        those of the plain iteration.
    lp_max_edges : int
        The exact linear-programming check (``rescue``) is run only up to this many force edges
        (HiGHS takes about 1 s at 2,000 edges, minutes at 20,000); above it failures are reported
        as not checked exactly.

    Returns
    -------
    HorizontalResult

    Raises
    ------
    HorizontalEquilibriumError
        edges flipped (tension) or collapsed: no compression-only solution; names edges and angles.
    ConvergenceError
        the angle did not drop below ``tol_deg`` within ``kmax`` iterations (``.result`` attached).
    """
    if force is None:
        force = force_diagram(form)
    a = min(max(float(alpha) / 100.0, 0.0), 1.0)
    if not 0.0 < length_weight <= 1.0:
        raise ValueError(f"length_weight must be in (0, 1], got {length_weight}")
    act = force.form_edge
    Cu = form.C[act].tocsr()
    Cd = force.C
    xy = np.array(form.xy, dtype=float)
    y = np.array(force.xy, dtype=float)
    u = Cu @ xy
    d = Cd @ y
    # the frame of the weighted fit: the initial target directions (fixed, so one factorisation)
    uh = _unit(u)
    frame = a * uh + (1.0 - a) * _unit(d)
    frame[np.hypot(frame[:, 0], frame[:, 1]) < 1e-12] = uh[np.hypot(frame[:, 0], frame[:, 1]) < 1e-12]
    frame = _unit(frame)
    solvers: list = []   # factorised on the first iteration (none when the start is already parallel)

    def step(xy_, y_, u_, d_):
        """One parallelisation update of both diagrams (the fixed-point map)."""
        if not solvers:
            if length_weight == 1.0:
                solvers.append(PinnedLaplacian(Cu, form.fixed) if a < 1.0 else None)
                solvers.append(PinnedLaplacian(Cd, force.pins) if a > 0.0 else None)
            else:
                solvers.append(WeightedFit(Cu, form.fixed, frame, length_weight) if a < 1.0 else None)
                solvers.append(WeightedFit(Cd, force.pins, frame, length_weight) if a > 0.0 else None)
        form_solver, force_solver = solvers
        lu_ = np.hypot(u_[:, 0], u_[:, 1])
        ld = np.hypot(d_[:, 0], d_[:, 1])
        uh_ = _unit(u_)
        t = a * uh_ + (1.0 - a) * _unit(d_)
        bad = np.hypot(t[:, 0], t[:, 1]) < 1e-12
        t[bad] = uh_[bad]
        t = _unit(t)
        if form_solver is not None:
            xy_ = form_solver.solve(lu_[:, None] * t, xy_)
        if force_solver is not None:
            y_ = force_solver.solve(ld[:, None] * t, y_)
        return xy_, y_

    def max_angle(u_, d_) -> float:
        return float(angle_deviations(u_, d_).max()) if len(u_) else 0.0

    history: list[float] = []
    converged = False
    k = 0
    X: list[np.ndarray] = []       # Anderson history: iterates and their residuals g(x) - x
    G: list[np.ndarray] = []
    angles = angle_deviations(u, d)
    amax = float(angles.max()) if len(angles) else 0.0
    while True:
        history.append(amax)
        if amax < tol_deg:
            converged = True
            break
        if k >= kmax:
            break
        if k >= stall_window and history[-1 - stall_window] - amax < 0.01 * history[-1 - stall_window]:
            break
        xy_g, y_g = step(xy, y, u, d)
        k += 1
        x_now = np.concatenate([xy.ravel(), y.ravel()])
        x_g = np.concatenate([xy_g.ravel(), y_g.ravel()])
        u_g, d_g = Cu @ xy_g, Cd @ y_g
        a_g = max_angle(u_g, d_g)
        accepted = False
        if anderson > 0:
            X.append(x_now)
            G.append(x_g - x_now)
            if len(X) > anderson + 1:
                X.pop(0)
                G.pop(0)
            if len(X) > 1:
                dX = np.diff(np.array(X), axis=0).T
                dG = np.diff(np.array(G), axis=0).T
                gam = np.linalg.lstsq(dG, G[-1], rcond=None)[0]
                x_aa = x_g - (dX + dG) @ gam
                xy_aa = x_aa[:xy.size].reshape(xy.shape)
                y_aa = x_aa[xy.size:].reshape(y.shape)
                u_aa, d_aa = Cu @ xy_aa, Cd @ y_aa
                a_aa = max_angle(u_aa, d_aa)
                # safeguard: take the extrapolation only if it beats the plain update
                if a_aa <= a_g and np.all(np.isfinite(x_aa)):
                    xy, y, u, d, amax = xy_aa, y_aa, u_aa, d_aa, a_aa
                    accepted = True
                else:
                    X, G = [], []
        if not accepted:
            xy, y, u, d, amax = xy_g, y_g, u_g, d_g, a_g
        angles = angle_deviations(u, d)

    u = Cu @ xy
    d = Cd @ y
    lu_ = np.hypot(u[:, 0], u[:, 1])
    ld = np.hypot(d[:, 0], d[:, 1])
    if not np.all(lu_ > 0):
        e = int(np.flatnonzero(~(lu_ > 0))[0])
        raise FormFindingError(f"form {form.edge_name(int(act[e]))} has collapsed to zero length during "
                               f"horizontal equilibrium; use a larger alpha")
    new_form = form.with_xy(xy) if a < 1.0 else form
    method = "parallelisation"
    lp_s = None
    if converged:
        collapsed = np.flatnonzero(ld <= min_force * max(float(np.median(ld)), 1e-300))
        converged = len(collapsed) == 0
    lp_ok = rescue and len(act) <= lp_max_edges
    if not converged and lp_ok:
        signed = np.where(angles > 90.0, -1.0, 1.0) * ld / lu_
        pos = signed[signed > 0]
        floor = 0.1 * float(np.median(pos)) if len(pos) else 1.0
        lp_s, q_lp, y_lp = compression_lp(new_form, force, np.maximum(signed, floor))
        if lp_s > 1e-9:
            y = y_lp
            d = Cd @ y
            ld = np.hypot(d[:, 0], d[:, 1])
            angles = angle_deviations(u, d)
            amax = float(angles.max()) if len(angles) else 0.0
            history.append(amax)
            converged = amax < tol_deg
            method = "lp"
    q = np.zeros(form.n_edges)
    q[act] = np.where(angles > 90.0, -1.0, 1.0) * ld / lu_
    res = HorizontalResult(form=new_form, force=force.with_xy(y), q=q, angles=angles, max_angle=amax,
                           iterations=k, history=tuple(history), converged=converged, method=method)
    if converged or not raise_on_failure:
        return res
    flipped = np.flatnonzero(angles > 90.0)
    collapsed = np.flatnonzero(ld <= min_force * max(float(np.median(ld)), 1e-300))
    if lp_s is not None and lp_s <= 1e-9 or (lp_s is None and (len(flipped) or len(collapsed))):
        bad = np.union1d(flipped, collapsed)
        if len(bad) == 0:
            bad = np.argsort(-angles)[:8]
        worst = bad[np.argsort(-angles[bad])][:8]
        desc = "; ".join(f"{form.edge_name(act[i])}: {angles[i]:.1f} deg, force length {ld[i]:.2g}"
                         for i in worst)
        proof = (" (checked exactly by linear programming)" if lp_s is not None else
                 " (not checked exactly: rescue=False)" if not rescue else
                 f" (not checked exactly: {len(act)} force edges > lp_max_edges = {lp_max_edges})")
        if len(flipped) == 0 and len(collapsed) == 0:
            raise HorizontalEquilibriumError(
                f"horizontal equilibrium stalled at a max angle deviation of {amax:.3g} deg > {tol_deg} deg after "
                f"{k} iterations, with every force edge in compression; this form diagram has no exactly "
                f"parallel compression-only reciprocal{proof}, so the tolerance is below what it allows "
                f"(worst: {desc}); raise tol_deg or relax the form diagram (relax_mode='all')",
                edges=act[bad].tolist(), angles=angles[bad].tolist(), result=res)
        raise HorizontalEquilibriumError(
            f"no compression-only horizontal equilibrium for this form diagram{proof}: after {k} iterations "
            f"{len(flipped)} force edges flipped (tension) and {len(collapsed)} collapsed to zero length, "
            f"e.g. {desc}. Straight unsupported edges cannot be in compression: relax the openings "
            f"(relax_openings), move the pattern or add supports",
            edges=act[bad].tolist(), angles=angles[bad].tolist(), result=res)
    worst = np.argsort(-angles)[:5]
    desc = "; ".join(f"{form.edge_name(act[i])}: {angles[i]:.2f} deg" for i in worst)
    err = ConvergenceError(
        f"horizontal equilibrium did not converge: max angle deviation {amax:.3g} deg > {tol_deg} deg after "
        f"{k} iterations (worst: {desc}); raise kmax, change alpha or relax the form diagram")
    err.result = res
    raise err


# ---------------------------------------------------------------------------------------------------
# Relaxing open edges
# ---------------------------------------------------------------------------------------------------


def opening_edges(form: FormDiagram) -> tuple[np.ndarray, np.ndarray]:
    """Form edges along openings and, for each, the opening face index (position in ``form.faces``)."""
    eidx, fidx = [], []
    for k in np.flatnonzero(~form.loaded):
        left = form.edge_faces[:, 0] == k
        right = form.edge_faces[:, 1] == k
        sel = np.flatnonzero(left | right)
        eidx.append(sel)
        fidx.append(np.full(len(sel), k))
    if not eidx:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    return np.concatenate(eidx), np.concatenate(fidx)


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

    Returns
    -------
    FormDiagram
        The diagram with new plan positions (unchanged when there is no opening).
    """
    if sag <= 0:
        raise ValueError(f"sag must be positive, got {sag}")
    eo, fo = opening_edges(form)
    if len(eo) == 0:
        return form
    openings = np.flatnonzero(~form.loaded)
    slot = np.full(form.n_faces, -1)
    slot[openings] = np.arange(len(openings))
    if mode == "boundary":
        moving = np.zeros(form.n_vertices, dtype=bool)
        moving[form.edges[eo].ravel()] = True
        moving &= ~form.anchors
    elif mode == "all":
        moving = ~form.anchors
    else:
        raise ValueError(f"unknown mode {mode!r}; use 'boundary' or 'all'")
    mv = np.flatnonzero(moving)
    st = np.flatnonzero(~moving)
    C = form.C
    Cm, Cs = C[:, mv].tocsc(), C[:, st].tocsc()
    xy0 = np.asarray(form.xy)
    # the moving vertices of each opening, their outward normals (towards the loaded side: the opening
    # face lies on the left of its traversal) and the opening's span
    span = np.zeros(len(openings))
    vert_of, normal_of = [], []
    for j, k in enumerate(openings):
        vs = np.array(form.faces[k])
        pts = xy0[vs]
        if form.anchors[vs[0]] and form.anchors[vs[-1]] and len(vs) >= 3 and np.all(~form.anchors[vs[1:-1]]):
            # a run between two supports: span = chord between them
            span[j] = np.linalg.norm(pts[-1] - pts[0])
            prv, nxt = np.roll(pts, 1, axis=0), np.roll(pts, -1, axis=0)
        else:
            # a closed opening (hole): span = 4 area / perimeter (the side of a square hole)
            nxt, prv = np.roll(pts, -1, axis=0), np.roll(pts, 1, axis=0)
            area = 0.5 * abs(np.sum(pts[:, 0] * nxt[:, 1] - nxt[:, 0] * pts[:, 1]))
            perim = np.linalg.norm(nxt - pts, axis=1).sum()
            span[j] = 4.0 * area / perim
        if span[j] <= 0:
            span[j] = np.sqrt(((pts[:, None, :] - pts[None, :, :]) ** 2).sum(-1)).max()
        t = nxt - prv
        nrm = np.column_stack([t[:, 1], -t[:, 0]])
        nrm /= np.maximum(np.linalg.norm(nrm, axis=1), 1e-300)[:, None]
        sel = moving[vs]
        vert_of.append(vs[sel])
        normal_of.append(nrm[sel])
    # an edge can border two openings (rare); it then takes the larger q_b
    lo = np.full(len(openings), np.log(1e-4))
    hi = np.full(len(openings), np.log(1e4))

    def solve(logq: np.ndarray) -> np.ndarray:
        q = np.full(form.n_edges, float(q_interior))
        np.maximum.at(q, eo, np.exp(logq[slot[fo]]))
        Q = sp.diags(q)
        A = (Cm.T @ Q @ Cm).tocsc()
        b = -(Cm.T @ (Q @ (Cs @ xy0[st])))
        xy = xy0.copy()
        xy[mv] = splu(A, permc_spec="MMD_AT_PLUS_A").solve(b)
        return xy

    target = sag * span
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        xy = solve(mid)
        got = np.array([np.max(np.einsum("ij,ij->i", xy[vs] - xy0[vs], nr)) if len(vs) else 0.0
                        for vs, nr in zip(vert_of, normal_of)])
        too_much = got > target          # too much sag: raise q_b
        lo = np.where(too_much, mid, lo)
        hi = np.where(too_much, hi, mid)
    out = form.with_xy(solve(0.5 * (lo + hi)))
    l0, l1 = form.edge_lengths(), out.edge_lengths()
    short = np.flatnonzero(~(l1 > 1e-3 * l0))
    if len(short):
        raise FormFindingError(
            f"relaxing the openings collapsed {len(short)} edges, e.g. {form.edge_name(int(short[0]))} "
            f"(length {l0[short[0]]:.3g} -> {l1[short[0]]:.3g}): the supports cannot hold the open edges "
            f"apart; add supports or relax with a larger sag")
    return out
