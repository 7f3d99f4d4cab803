"""The force diagram of Thrust Network Analysis: the reciprocal (dual) of the form diagram.

Block & Ochsendorf (2007) read horizontal equilibrium of a thrust network from a pair of reciprocal
diagrams: every face of the form diagram (openings included) is a vertex of the force diagram, every
form edge with a free end an edge of it, and the length of a force edge is the horizontal force in the
corresponding thrust edge. Each free vertex is in equilibrium when its force polygon (the face of the
force diagram around the dual of that vertex) closes with edges parallel to the form edges.

Orientation convention (documented, used everywhere in vaultgram). The dual of form edge ``(u, v)``
runs from its right face to its left face. The classical reciprocal is perpendicular to the form; we
store it turned by -90 degrees, so that after horizontal equilibrium corresponding edges are
**parallel**, and for compression point the same way:

    force.xy[left] - force.xy[right] = q_e * (form.xy[v] - form.xy[u]),   q_e > 0.

A flipped edge (angle 180 degrees) is tension. Force polygons close by construction (the edge vectors
around a free vertex telescope), so equilibrium is exactly "every edge parallel".
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components
from scipy.sparse.linalg import splu

from vaultgram.errors import FormFindingError
from vaultgram.formfinding.formdiagram import FormDiagram, connectivity_matrix

__all__ = ["ForceDiagram", "force_diagram", "PinnedLaplacian", "WeightedFit"]


class PinnedLaplacian:
    """Factorised graph Laplacian ``C^T C`` with some vertices held fixed.

    Solves ``min |C x - t|^2`` over the unpinned vertices for many right-hand sides ``t`` with one
    sparse LU factorisation (the pattern and values of ``C^T C`` never change during the
    parallelisation iterations).
    """

    def __init__(self, C: sp.csr_matrix, pinned: np.ndarray):
        n = C.shape[1]
        mask = np.zeros(n, dtype=bool)
        mask[pinned] = True
        self.n = n
        self.pinned = np.flatnonzero(mask)
        self.unpinned = np.flatnonzero(~mask)
        self.Cu = C[:, self.unpinned].tocsc()
        self.Cp = C[:, self.pinned].tocsc()
        self.CuT = self.Cu.T.tocsr()
        A = (self.CuT @ self.Cu).tocsc()
        try:
            self.lu = splu(A, permc_spec="MMD_AT_PLUS_A")
        except RuntimeError as exc:  # pragma: no cover - guarded by connectivity checks
            raise FormFindingError(f"singular least-squares system ({exc}); a part of the diagram is not connected to a fixed vertex") from None

    def solve(self, t: np.ndarray, x: np.ndarray) -> np.ndarray:
        """New positions: pinned rows of ``x`` kept, others solving the least-squares problem."""
        out = np.array(x, dtype=float, copy=True)
        rhs = self.CuT @ (t - self.Cp @ x[self.pinned])
        out[self.unpinned] = self.lu.solve(rhs)
        return out


class WeightedFit:
    """Factorised weighted least-squares fit of a diagram's edge vectors, some vertices held fixed.

    Solves ``min sum_e (C_e x - t_e)^T W_e (C_e x - t_e)`` over the unpinned vertices for many targets
    ``t`` (k, 2), with the per-edge weight ``W_e = n_e n_e^T + mu f_e f_e^T`` in a fixed frame: ``f_e`` a
    unit direction (the edge's target direction), ``n_e`` its normal. A deviation *across* the
    direction costs ``1 / mu`` times more than one *along* it (a change of length); ``mu = 1`` is
    the plain fit of :class:`PinnedLaplacian`. x and y are coupled, so the unknowns are interleaved
    per vertex and ordered by the minimum-degree ordering of the graph Laplacian ``C^T C`` (the
    2 x 2 block pattern keeps that ordering good), then factorised once without pivoting (the
    matrix is symmetric positive definite when every component has a pinned vertex).
    """

    def __init__(self, C: sp.csr_matrix, pinned: np.ndarray, frame: np.ndarray, mu: float):
        n = C.shape[1]
        mask = np.zeros(n, dtype=bool)
        mask[pinned] = True
        self.pinned = np.flatnonzero(mask)
        self.unpinned = np.flatnonzero(~mask)
        Cu = C[:, self.unpinned].tocsc()
        self.Cp = C[:, self.pinned].tocsc()
        fx, fy = frame[:, 0], frame[:, 1]
        # W = n n^T + mu f f^T with n = (-fy, fx)
        self.w = (fy * fy + mu * fx * fx, -fx * fy + mu * fx * fy, fx * fx + mu * fy * fy)
        wxx, wxy, wyy = (sp.diags(w) for w in self.w)
        A = sp.bmat([[Cu.T @ wxx @ Cu, Cu.T @ wxy @ Cu], [Cu.T @ wxy @ Cu, Cu.T @ wyy @ Cu]]).tocsr()
        N = len(self.unpinned)
        try:
            lap = splu((Cu.T @ Cu).tocsc(), permc_spec="MMD_AT_PLUS_A")
        except RuntimeError as exc:  # pragma: no cover - guarded by connectivity checks
            raise FormFindingError(f"singular least-squares system ({exc}); a part of the diagram is not connected to a fixed vertex") from None
        order = np.argsort(lap.perm_c)
        P = np.empty(2 * N, dtype=np.int64)
        P[0::2] = order
        P[1::2] = order + N
        self.P = P
        try:
            self.lu = splu(A[P][:, P].tocsc(), permc_spec="NATURAL", diag_pivot_thresh=0.0,
                           options=dict(SymmetricMode=True))
        except RuntimeError as exc:  # pragma: no cover
            raise FormFindingError(f"singular weighted least-squares system ({exc})") from None
        self.CuT = Cu.T.tocsr()
        self.N = N

    def solve(self, t: np.ndarray, x: np.ndarray) -> np.ndarray:
        """New positions: pinned rows of ``x`` kept, others solving the weighted least-squares fit."""
        out = np.array(x, dtype=float, copy=True)
        r = t - self.Cp @ x[self.pinned]
        wxx, wxy, wyy = self.w
        bx = self.CuT @ (wxx * r[:, 0] + wxy * r[:, 1])
        by = self.CuT @ (wxy * r[:, 0] + wyy * r[:, 1])
        b = np.concatenate([bx, by])[self.P]
        z = np.empty(2 * self.N)
        z[self.P] = self.lu.solve(b)
        out[self.unpinned, 0] = z[:self.N]
        out[self.unpinned, 1] = z[self.N:]
        return out


@dataclass(frozen=True, eq=False)
class ForceDiagram:
    """A force diagram (stored turned by -90 degrees: parallel to the form diagram).

    Attributes
    ----------
    xy : ndarray (F, 2)
        One vertex per form face (``form.faces`` order, openings included).
    edges : ndarray (k, 2) int
        ``(right face, left face)`` of each active form edge.
    form_edge : ndarray (k,) int
        Index of the corresponding form edge (the form's edges with at least one free end, in order).
    C : scipy.sparse.csr_matrix (k, F)
        Connectivity matrix: ``C @ xy`` are the force vectors, parallel to ``form.C @ form.xy``.
    """

    xy: np.ndarray
    edges: np.ndarray
    form_edge: np.ndarray
    C: sp.csr_matrix = field(repr=False)

    @property
    def n_vertices(self) -> int:
        return len(self.xy)

    @property
    def n_edges(self) -> int:
        return len(self.edges)

    def edge_vectors(self) -> np.ndarray:
        return self.C @ self.xy

    def edge_lengths(self) -> np.ndarray:
        return np.hypot(*self.edge_vectors().T)

    @cached_property
    def components(self) -> tuple[int, np.ndarray]:
        """Connected components of the force graph (number, label per vertex)."""
        n = self.n_vertices
        adj = sp.csr_matrix((np.ones(len(self.edges)), (self.edges[:, 0], self.edges[:, 1])), shape=(n, n))
        return connected_components(adj, directed=False)

    @cached_property
    def pins(self) -> np.ndarray:
        """One vertex per connected component, held fixed (the diagram floats otherwise)."""
        ncomp, labels = self.components
        _, first = np.unique(labels, return_index=True)
        return np.sort(first)

    def with_xy(self, xy: np.ndarray) -> "ForceDiagram":
        xy = np.array(xy, dtype=float, copy=True)
        xy.setflags(write=False)
        return replace(self, xy=xy)

    def to_json(self) -> dict:
        """JSON-serialisable description (for ``force.json``)."""
        return {
            "vertices": self.xy.tolist(),
            "edges": self.edges.tolist(),
            "form_edge": self.form_edge.tolist(),
            "orientation": "parallel (turned -90 degrees from the classical perpendicular reciprocal)",
        }


def force_diagram(form: FormDiagram, init: str = "lsq") -> ForceDiagram:
    """The reciprocal force diagram of ``form`` with initial positions.

    Parameters
    ----------
    form : FormDiagram
    init : {"lsq", "centroid"}
        ``"lsq"`` (default): least-squares reciprocal with unit force densities, i.e. positions
        minimising ``sum |force_e - (form_e)|^2`` -- exact when the form is in equilibrium with equal
        force densities (a regular grid). ``"centroid"``: loaded faces at their centroids (turned),
        opening vertices by least squares.

    Returns
    -------
    ForceDiagram
    """
    active = np.flatnonzero(form.active)
    left, right = form.edge_faces[active, 0], form.edge_faces[active, 1]
    edges = np.stack([right, left], axis=1)
    F = form.n_faces
    C = connectivity_matrix(edges, F)
    for a in (edges, active):
        a.setflags(write=False)
    force = ForceDiagram(xy=np.zeros((F, 2)), edges=edges, form_edge=active, C=C)
    target = (form.C @ form.xy)[active]
    if init == "lsq":
        xy = PinnedLaplacian(C, force.pins).solve(target, np.zeros((F, 2)))
    elif init == "centroid":
        xy = np.zeros((F, 2))
        for k, f in enumerate(form.faces):
            if form.loaded[k]:
                c = form.xy[list(f)].mean(axis=0)
                xy[k] = (c[1], -c[0])          # turned by -90 degrees
        loaded = np.flatnonzero(form.loaded)
        pinned = np.union1d(loaded, force.pins) if len(loaded) else force.pins
        xy = PinnedLaplacian(C, pinned).solve(target, xy)
    else:
        raise ValueError(f"unknown init {init!r}; use 'lsq' or 'centroid'")
    return force.with_xy(xy)
