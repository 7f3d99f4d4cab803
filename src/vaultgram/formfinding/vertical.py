"""Vertical equilibrium of a thrust network (TNA step 2; Block & Ochsendorf 2007, §5 of the paper).

Given the form diagram (plan) and force densities ``q`` from horizontal equilibrium, the heights of the
free vertices solve the linear force-density system (Schek 1974)

    Ci^T Q Ci z_i = p_i - Ci^T Q Cf z_f

with ``C`` the branch-node matrix, ``Q = diag(scale * q)``, ``z_f`` the (fixed) support heights and
``p`` the vertical loads. Sign convention (that of the reference figures): ``q > 0`` is compression and
positive loads give positive z, i.e. the vault stands above its supports and loads act downwards.

Self-weight depends on the 3D tributary areas (:mod:`vaultgram.formfinding.loads`), so loads and heights are
iterated to a fixed point. With ``zmax`` the thrust scale is solved for as well, so that the highest
free vertex is exactly ``zmax``; scale and loads are iterated together. The matrix pattern and
values are fixed (a common scale only divides the solution), so the system is factorised once.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from vaultgram.errors import ConvergenceError, FormFindingError
from vaultgram.formfinding.formdiagram import FormDiagram
from vaultgram.formfinding.loads import TributaryAreas

__all__ = ["VerticalResult", "vertical", "point_load_vector"]


@dataclass(frozen=True, eq=False)
class VerticalResult:
    """Heights, loads and reactions of a thrust network in vertical equilibrium.

    Attributes
    ----------
    xyz : ndarray (n, 3)
        Vertex positions (plan of the form diagram, solved heights).
    q : ndarray (m,)
        Force densities actually used: ``scale * q_input``.
    scale : float
        Horizontal thrust scale (multiplier of the input force densities).
    loads : ndarray (n,)
        Vertical loads at the final geometry (self-weight + point loads), positive downwards.
    reactions : ndarray (n_anchors, 3)
        Support reactions ``(Rx, Ry, Rz)`` in the order of ``form.fixed``; ``Rz`` is positive upwards and
        ``sum(Rz) == total_load``. (The reference files list ``-Rz`` as ``_rz``.)
    total_load : float
        Sum of the loads on all vertices (supported ones included).
    residual : float
        ``max |Ci^T Q C z - p_i|`` over the free vertices (vertical equilibrium).
    residual_xy : float
        ``max |Ci^T Q C xy|`` over free vertices (horizontal equilibrium of the plan with these q).
    iterations : int
        Load (and scale) updates performed.
    history : tuple of float
        Largest height change at each iteration.
    """

    xyz: np.ndarray
    q: np.ndarray
    scale: float
    loads: np.ndarray
    reactions: np.ndarray
    total_load: float
    residual: float
    residual_xy: float
    iterations: int
    history: tuple = field(repr=False)

    @property
    def z(self) -> np.ndarray:
        return self.xyz[:, 2]


def point_load_vector(form: FormDiagram, point_loads) -> np.ndarray:
    """Point loads as an (n,) vector over form vertices.

    ``point_loads`` is None, an array with one entry per *form* vertex, or a dict
    ``{input mesh vertex index: load}`` (the form diagram may have dropped or renumbered vertices).
    A non-zero load on a mesh vertex that is not in the form diagram is an error.
    """
    p = np.zeros(form.n_vertices)
    if point_loads is None:
        return p
    if not isinstance(point_loads, dict):
        arr = np.asarray(point_loads, dtype=float).ravel()
        if arr.shape != (form.n_vertices,):
            raise ValueError(f"point_loads has {arr.size} entries; give one per form vertex "
                             f"({form.n_vertices}) or a dict {{mesh vertex: load}}")
        return arr.copy()
    pos = {int(v): k for k, v in enumerate(form.vertex_ids)}
    for v, load in point_loads.items():
        v = int(v)
        if load == 0:
            continue
        if v not in pos:
            raise FormFindingError(
                f"point load {load} on mesh vertex {v}, which is not in the form diagram (a supported "
                f"vertex left without edges, or not a mesh vertex)")
        p[pos[v]] += float(load)
    return p


def _solve_t(a: np.ndarray, b: np.ndarray, zmax: float) -> float:
    """Smallest-residual ``t > 0`` with ``max(a t + b) == zmax`` (Newton on a convex piecewise-linear map)."""
    i = int(np.argmax(a))
    if a[i] <= 0:
        raise FormFindingError("zmax cannot be reached: the loads do not lift any free vertex")
    t = max((zmax - b[i]) / a[i], 0.0)
    for _ in range(100):
        i = int(np.argmax(a * t + b))
        if a[i] <= 0:
            raise FormFindingError(f"zmax = {zmax} cannot be reached: the supports are higher than the vault")
        t_new = (zmax - b[i]) / a[i]
        if t_new == t:
            break
        t = t_new
    if t <= 0:
        raise FormFindingError(f"zmax = {zmax} is below the supports")
    return t


def vertical(form: FormDiagram, q, *, scale: float = 1.0, zmax: float | None = None,
             thickness=1.0, density: float = 1.0, selfweight: bool = True, point_loads=None,
             z_fixed=None, kmax: int = 500, tol: float = 1e-12) -> VerticalResult:
    """Heights of the thrust network for given force densities and loads (TNA vertical equilibrium).

    Parameters
    ----------
    form : FormDiagram
    q : array (m,)
        Force densities of the form edges, usually ``|force edge| / |form edge|`` from
        :func:`vaultgram.formfinding.horizontal.horizontal`; positive (compression) on every edge with a free end.
    scale : float
        Horizontal thrust scale: the force densities used are ``scale * q`` (ignored with ``zmax``).
    zmax : float, optional
        Target height of the highest free vertex; the scale is solved for.
    thickness : float or array (n,)
        Thickness per vertex (self-weight = tributary area x thickness x density).
    density : float
        Weight per unit volume.
    selfweight : bool
        Include self-weight (False: point loads only, a single linear solve).
    point_loads : dict, array (n,) or None
        Extra vertical loads, see :func:`point_load_vector`; positive downwards.
    z_fixed : array (n_anchors,), optional
        Heights of the anchors (default 0).
    kmax : int
        Cap on load/scale iterations.
    tol : float
        Stop when the largest height change is below ``tol * max(1, max |z|)`` and the relative scale
        change below ``tol``.

    Returns
    -------
    VerticalResult

    Raises
    ------
    FormFindingError
        non-positive force densities, unreachable ``zmax``, singular system.
    ConvergenceError
        loads/scale not converged within ``kmax`` iterations (``.result`` holds the last state).
    """
    q0 = np.asarray(q, dtype=float).ravel()
    if q0.shape != (form.n_edges,):
        raise ValueError(f"q has {q0.size} entries, the form diagram has {form.n_edges} edges")
    bad = np.flatnonzero(form.active & ~(q0 > 0))
    if len(bad):
        names = ", ".join(f"{form.edge_name(e)}: q = {q0[e]:.3g}" for e in bad[:5])
        raise FormFindingError(
            f"{len(bad)} edges have non-positive force density (tension or slack), e.g. {names}; "
            f"a compression-only network needs q > 0")
    if not np.isfinite(scale) or scale <= 0:
        raise FormFindingError(f"the thrust scale must be positive, got {scale}")
    free, fixed = form.free, form.fixed
    C = form.C
    Ci = C[:, free].tocsc()
    Cf = C[:, fixed].tocsc()
    Q0 = sp.diags(q0)
    A0 = (Ci.T @ Q0 @ Ci).tocsc()
    try:
        lu = splu(A0, permc_spec="MMD_AT_PLUS_A")
    except RuntimeError as exc:
        raise FormFindingError(f"vertical equilibrium system is singular ({exc}); is every part supported?") from None
    zf = np.zeros(len(fixed)) if z_fixed is None else np.asarray(z_fixed, dtype=float).ravel()
    if zf.shape != (len(fixed),):
        raise ValueError(f"z_fixed needs {len(fixed)} entries (one per anchor)")
    b = -lu.solve(Ci.T @ (Q0 @ (Cf @ zf))) if zf.any() else np.zeros(len(free))

    p0 = point_load_vector(form, point_loads)
    thick = np.broadcast_to(np.asarray(thickness, dtype=float), (form.n_vertices,))
    trib = TributaryAreas.from_faces(form.loaded_faces, form.n_vertices)
    use_sw = selfweight and density != 0 and np.any(thick != 0)

    xyz = np.zeros((form.n_vertices, 3))
    xyz[:, :2] = form.xy
    xyz[fixed, 2] = zf

    def loads(x):
        return p0 + trib(x) * thick * density if use_sw else p0

    t = 1.0 / scale
    history = []
    converged = False
    k = 0
    for k in range(1, kmax + 1):
        p = loads(xyz)
        a = lu.solve(p[free])
        t_new = _solve_t(a, b, zmax) if zmax is not None else t
        z_new = a * t_new + b
        dz = float(np.max(np.abs(z_new - xyz[free, 2]))) if len(free) else 0.0
        ds = abs(t_new - t) / t_new
        xyz[free, 2] = z_new
        t = t_new
        history.append(dz)
        if not use_sw and (zmax is None or k > 1):
            converged = True
            break
        if dz <= tol * max(1.0, float(np.max(np.abs(z_new)))) and ds <= tol and k > 1:
            converged = True
            break
    s = 1.0 / t
    qs = s * q0
    p = loads(xyz)
    CtQC = C.T @ sp.diags(qs) @ C
    r = CtQC @ xyz[:, 2] - p
    rxy = CtQC @ form.xy
    reactions = np.column_stack([-rxy[fixed], -r[fixed]])
    res = VerticalResult(
        xyz=xyz, q=qs, scale=s, loads=p, reactions=reactions, total_load=float(p.sum()),
        residual=float(np.max(np.abs(r[free]))) if len(free) else 0.0,
        residual_xy=float(np.max(np.abs(rxy[free]))) if len(free) else 0.0,
        iterations=k, history=tuple(history))
    if not converged:
        err = ConvergenceError(
            f"vertical equilibrium: loads{' and scale' if zmax is not None else ''} did not converge in "
            f"{kmax} iterations (last height change {history[-1]:.3g}, residual {res.residual:.3g}); "
            f"raise kmax or lower the thrust (larger zmax or scale)")
        err.result = res
        raise err
    return res
