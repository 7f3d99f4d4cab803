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

:func:`vertical` reads as its phases: check the force densities, factorise the height system, gather
the loads, iterate heights (and scale) with the loads, then measure the equilibrium (residuals and
reactions).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import scipy.sparse as sp

from vaultgram.errors import FormFindingError, VerticalEquilibriumError
from vaultgram.formfinding.cholesky import Cholesky, ForceDensityMatrix
from vaultgram.formfinding.formdiagram import FormDiagram
from vaultgram.formfinding.loads import HeightAreas, TributaryAreas

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

    Example
    -------
    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> form = form_diagram(*grid_mesh(2))                     # the corners 0, 2, 6, 8 are dropped
    >>> point_load_vector(form, {4: 2.5}).tolist()
    [0.0, 0.0, 2.5, 0.0, 0.0]
    """
    p = np.zeros(form.n_vertices)
    if point_loads is None:
        return p
    if not isinstance(point_loads, dict):
        arr = np.asarray(point_loads, dtype=float).ravel()
        if arr.shape != (form.n_vertices,):
            raise FormFindingError(f"point_loads has {arr.size} entries; give one per form vertex "
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
        Force densities of the form edges, usually ``|force edge| / |form edge|`` from horizontal
        equilibrium (:func:`~vaultgram.formfinding.horizontal.horizontal`); > 0 on edges with a free end.
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
        Cap on load/scale iterations (at least 1).
    tol : float
        Stop when the largest height change is below ``tol * max(1, max |z|)`` and the relative scale
        change below ``tol``.

    Raises
    ------
    FormFindingError
        non-positive force densities, unreachable ``zmax``, singular system, arrays of the wrong size.
    ConvergenceError
        loads/scale not converged within ``kmax`` iterations (``.result`` holds the last state).

    Example
    -------
    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> form = form_diagram(*grid_mesh(4))
    >>> v = vertical(form, np.ones(form.n_edges), zmax=1.0)
    >>> round(float(v.z.max()), 12), bool(abs(v.reactions[:, 2].sum() - v.total_load) < 1e-9)
    (1.0, True)
    """
    q0 = _checked_densities(form, q, scale, kmax)
    system = _HeightSystem.factorised(form, q0, z_fixed)
    loads = _Loads.of(form, point_loads, thickness, density, selfweight)
    xyz, t, history, converged = _iterate_heights(form, system, loads, 1.0 / scale, zmax, kmax, tol)
    res = _equilibrium(form, q0, xyz, t, loads(xyz), history)
    if not converged:
        err = VerticalEquilibriumError(
            f"vertical equilibrium: loads{' and scale' if zmax is not None else ''} did not converge in "
            f"{kmax} iterations (last height change {history[-1]:.3g}, residual {res.residual:.3g}); "
            f"set the height of the vault (--zmax) or lower the loads (--thickness, --density)")
        err.result = res
        raise err
    return res


def _checked_densities(form: FormDiagram, q, scale: float, kmax: int) -> np.ndarray:
    """The force densities as an (m,) array, positive on every edge with a free end (compression)."""
    q0 = np.asarray(q, dtype=float).ravel()
    if q0.shape != (form.n_edges,):
        raise FormFindingError(f"q has {q0.size} entries, the form diagram has {form.n_edges} edges")
    bad = np.flatnonzero(form.active & ~(q0 > 0))
    if len(bad):
        names = ", ".join(f"{form.edge_name(e)}: q = {q0[e]:.3g}" for e in bad[:5])
        raise FormFindingError(
            f"{len(bad)} edges have non-positive force density (tension or slack), e.g. {names}; "
            f"a compression-only network needs q > 0")
    if not np.isfinite(scale) or scale <= 0:
        raise FormFindingError(f"the thrust scale must be positive, got {scale}")
    if kmax < 1:
        raise FormFindingError(f"vertical equilibrium needs at least one iteration, got kmax = {kmax}")
    return q0


class _HeightSystem(NamedTuple):
    """``Ci^T Q0 Ci`` factorised once (sparse Cholesky, :mod:`vaultgram.formfinding.cholesky`) for the
    input force densities ``Q0``: with a thrust scale ``s`` the free heights are ``a t + b`` with
    ``a = lu.solve(p_i)``, ``t = 1 / s`` and ``b`` the part due to the support heights ``z_f``."""

    lu: Cholesky
    z_fixed: np.ndarray
    b: np.ndarray

    @classmethod
    def factorised(cls, form: FormDiagram, q0: np.ndarray, z_fixed) -> "_HeightSystem":
        lu = ForceDensityMatrix(form.C, form.free).factorised(q0, "vertical equilibrium system",
                                                              "; is every part supported?")
        zf = np.zeros(len(form.fixed)) if z_fixed is None else np.asarray(z_fixed, dtype=float).ravel()
        if zf.shape != (len(form.fixed),):
            raise FormFindingError(f"z_fixed needs {len(form.fixed)} entries (one per anchor)")
        if not zf.any():
            return cls(lu, zf, np.zeros(len(form.free)))
        Ci, Cf = form.C[:, form.free].tocsc(), form.C[:, form.fixed].tocsc()
        return cls(lu, zf, -lu.solve(Ci.T @ (q0 * (Cf @ zf))))


@dataclass(frozen=True)
class _Loads:
    """Vertical loads at a geometry: point loads, plus self-weight (3D tributary area x thickness x
    density, :mod:`vaultgram.formfinding.loads`) when there is any. The plan is the form diagram's:
    only the heights of ``xyz`` are read."""

    points: np.ndarray
    areas: HeightAreas
    thickness: np.ndarray
    density: float
    selfweight: bool

    @classmethod
    def of(cls, form: FormDiagram, point_loads, thickness, density: float, selfweight: bool) -> "_Loads":
        thick = np.broadcast_to(np.asarray(thickness, dtype=float), (form.n_vertices,))
        areas = TributaryAreas.from_faces(form.loaded_faces, form.n_vertices).over_plan(form.xy)
        weighs = selfweight and density != 0 and bool(np.any(thick != 0))
        return cls(point_load_vector(form, point_loads), areas, thick, density, weighs)

    def __call__(self, xyz: np.ndarray) -> np.ndarray:
        return self.points + self.areas(xyz[:, 2]) * self.thickness * self.density if self.selfweight else self.points


def _iterate_heights(form: FormDiagram, system: _HeightSystem, loads: _Loads, t: float, zmax: float | None,
                     kmax: int, tol: float) -> tuple[np.ndarray, float, list[float], bool]:
    """Heights and ``t = 1 / scale`` at the fixed point of loads (and scale, with ``zmax``): the last
    geometry, ``t``, the largest height change per iteration, and whether it converged. The heights the
    next loads are taken at are :class:`_Mixing`'s, the ones returned those of the last solve."""
    free = form.free
    xyz = np.zeros((form.n_vertices, 3))
    xyz[:, :2] = form.xy
    xyz[form.fixed, 2] = system.z_fixed
    history: list[float] = []
    mixing, z_in = _Mixing(), xyz[free, 2].copy()
    for k in range(1, kmax + 1):
        xyz[free, 2] = z_in
        a = system.lu.solve(loads(xyz)[free])
        t_new = _solve_t(a, system.b, zmax) if zmax is not None else t
        z_new = a * t_new + system.b
        dz = float(np.max(np.abs(z_new - z_in))) if len(free) else 0.0
        ds = abs(t_new - t) / t_new
        xyz[free, 2] = z_new
        t = t_new
        history.append(dz)
        if not loads.selfweight and (zmax is None or k > 1):
            return xyz, t, history, True
        if dz <= tol * max(1.0, float(np.max(np.abs(z_new)))) and ds <= tol and k > 1:
            return xyz, t, history, True
        z_in = mixing.next(z_in, z_new, history)
    return xyz, t, history, False


class _Mixing:
    """Anderson acceleration (Anderson 1965; type II as in Walker & Ni 2011) of the fixed point of
    loads and heights over the last :data:`WINDOW` steps: the next loads are taken at the combination
    of the last solved heights whose height changes cancel best (least squares), not at the last ones.
    On the grids it saves two of twelve solves (0.08 -> 0.05 per step late on) and ends within 1e-13
    of the plain iteration's heights; a step whose height change grew restarts the window.

    Only the heights are combined (the scale follows from them at each solve); the 2 x 2 normal
    equations cost one pass over the heights per column (a least-squares solve of the n x 2 system
    costs 10 times as much at 10^6 vertices).

    Example
    -------
    >>> m = _Mixing()
    >>> g = lambda z: 0.5 * z + 1.0                     # linear: the fixed point 2 in two steps
    >>> z1 = m.next(np.zeros(1), g(np.zeros(1)), [1.0])
    >>> z2 = m.next(z1, g(z1), [1.0, 0.5])
    >>> z2.tolist()
    [2.0]
    """

    WINDOW = 2

    def __init__(self):
        self.out: list[np.ndarray] = []       # solved heights and their changes from the heights in
        self.change: list[np.ndarray] = []

    def next(self, z_in: np.ndarray, z_out: np.ndarray, history: list[float]) -> np.ndarray:
        """The heights to take the next loads at, after the solve ``z_in -> z_out``."""
        if len(history) > 1 and history[-1] > history[-2]:
            self.out, self.change = [], []
        self.out = (self.out + [z_out])[-self.WINDOW - 1:]
        self.change = (self.change + [z_out - z_in])[-self.WINDOW - 1:]
        if len(self.out) == 1:
            return z_out
        dG = np.column_stack([b - a for a, b in zip(self.out, self.out[1:])])
        dR = np.column_stack([b - a for a, b in zip(self.change, self.change[1:])])
        gamma = np.linalg.lstsq(dR.T @ dR, dR.T @ self.change[-1], rcond=None)[0]
        return z_out - dG @ gamma


def _equilibrium(form: FormDiagram, q0: np.ndarray, xyz: np.ndarray, t: float, p: np.ndarray,
                 history: list[float]) -> VerticalResult:
    """Scaled force densities, residuals and support reactions of the network at ``xyz`` under ``p``."""
    free, fixed = form.free, form.fixed
    s = 1.0 / t
    qs = s * q0
    CtQC = form.C.T @ sp.diags(qs) @ form.C
    r = CtQC @ xyz[:, 2] - p
    rxy = CtQC @ form.xy
    return VerticalResult(
        xyz=xyz, q=qs, scale=s, loads=p, reactions=np.column_stack([-rxy[fixed], -r[fixed]]),
        total_load=float(p.sum()), residual=float(np.max(np.abs(r[free]))) if len(free) else 0.0,
        residual_xy=float(np.max(np.abs(rxy[free]))) if len(free) else 0.0,
        iterations=len(history), history=tuple(history))
