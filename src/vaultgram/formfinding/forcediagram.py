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

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import breadth_first_order

from vaultgram.formfinding.cholesky import Cholesky, ForceDensityMatrix
from vaultgram.formfinding.diagrams import Diagram, connectivity_matrix
from vaultgram.formfinding.formdiagram import FormDiagram
from vaultgram.geometry.arrays import json_array

__all__ = ["ForceDiagram", "force_diagram", "PinnedLaplacian", "WeightedFit"]

_DISCONNECTED = "; a part of the diagram is not connected to a fixed vertex"


def _split_columns(C: sp.csr_matrix, pinned: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Sorted pinned and unpinned column indices of ``C`` (the vertices held fixed and the moving ones)."""
    mask = np.zeros(C.shape[1], dtype=bool)
    mask[pinned] = True
    return np.flatnonzero(mask), np.flatnonzero(~mask)


class PinnedLaplacian:
    """Factorised graph Laplacian ``C^T C`` with some vertices held fixed.

    Solves ``min |C x - t|^2`` over the unpinned vertices for many right-hand sides ``t`` with one
    sparse Cholesky factorisation (the pattern and values of ``C^T C`` never change during the
    parallelisation iterations).

    Example
    -------
    >>> C = connectivity_matrix(np.array([[0, 1], [1, 2]]), 3)           # a path 0 - 1 - 2, 0 fixed
    >>> x = PinnedLaplacian(C, np.array([0])).solve(np.array([[1.0, 0.0], [0.0, 2.0]]), np.zeros((3, 2)))
    >>> np.round(x, 12).tolist()
    [[0.0, 0.0], [1.0, 0.0], [1.0, 2.0]]
    """

    def __init__(self, C: sp.csr_matrix, pinned: np.ndarray):
        self.n = C.shape[1]
        self.pinned, self.unpinned = _split_columns(C, pinned)
        self.Cu = C[:, self.unpinned].tocsc()
        self.Cp = C[:, self.pinned].tocsc()
        self.CuT = self.Cu.T.tocsr()
        self.lu = ForceDensityMatrix(C, self.unpinned).factorised(np.ones(C.shape[0]), "least-squares system",
                                                                  _DISCONNECTED)

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
    the plain fit of :class:`PinnedLaplacian`. x and y are coupled, so all ``2 N`` unknowns are
    factorised together, once, by a sparse Cholesky factorisation with its own fill-reducing ordering
    (the matrix is symmetric positive definite when every component has a pinned vertex).
    """

    def __init__(self, C: sp.csr_matrix, pinned: np.ndarray, frame: np.ndarray, mu: float):
        self.pinned, self.unpinned = _split_columns(C, pinned)
        Cu = C[:, self.unpinned].tocsc()
        self.Cp = C[:, self.pinned].tocsc()
        fx, fy = frame[:, 0], frame[:, 1]
        # W = n n^T + mu f f^T with n = (-fy, fx)
        self.w = (fy * fy + mu * fx * fx, -fx * fy + mu * fx * fy, fx * fx + mu * fy * fy)
        wxx, wxy, wyy = (sp.diags(w) for w in self.w)
        A = sp.bmat([[Cu.T @ wxx @ Cu, None], [Cu.T @ wxy @ Cu, Cu.T @ wyy @ Cu]])
        self.N = len(self.unpinned)
        self.lu = Cholesky.of(A, "weighted least-squares system", _DISCONNECTED)
        self.CuT = Cu.T.tocsr()

    def solve(self, t: np.ndarray, x: np.ndarray) -> np.ndarray:
        """New positions: pinned rows of ``x`` kept, others solving the weighted least-squares fit."""
        out = np.array(x, dtype=float, copy=True)
        r = t - self.Cp @ x[self.pinned]
        wxx, wxy, wyy = self.w
        bx = self.CuT @ (wxx * r[:, 0] + wxy * r[:, 1])
        by = self.CuT @ (wxy * r[:, 0] + wyy * r[:, 1])
        z = self.lu.solve(np.concatenate([bx, by]))
        out[self.unpinned, 0] = z[:self.N]
        out[self.unpinned, 1] = z[self.N:]
        return out


@dataclass(frozen=True, eq=False)
class ForceDiagram(Diagram):
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

    Sizes, edge vectors and lengths, :attr:`components` and :meth:`with_xy` come from
    :class:`vaultgram.formfinding.diagrams.Diagram`.
    """

    xy: np.ndarray
    edges: np.ndarray
    form_edge: np.ndarray
    C: sp.csr_matrix = field(repr=False)

    @cached_property
    def pins(self) -> np.ndarray:
        """One vertex per connected component, held fixed (the diagram floats otherwise)."""
        ncomp, labels = self.components
        first = np.full(ncomp, len(labels), dtype=np.int64)
        np.minimum.at(first, labels, np.arange(len(labels)))  # each component's first vertex, no sort
        return np.sort(first)

    def to_json(self, arrays: bool = False) -> dict:
        """JSON-serialisable description (for ``force.json``); ``arrays``: numpy arrays kept as they are,
        for :func:`vaultgram.io.files.write_json` (:func:`~vaultgram.geometry.arrays.json_array`)."""
        return {
            "vertices": json_array(self.xy, arrays),
            "edges": json_array(self.edges, arrays),
            "form_edge": json_array(self.form_edge, arrays),
            "orientation": "parallel (turned -90 degrees from the classical perpendicular reciprocal)",
        }


def force_diagram(form: FormDiagram, q: np.ndarray | None = None) -> ForceDiagram:
    """The reciprocal force diagram of ``form`` (Block & Ochsendorf 2007), positioned by least squares.

    Every face of the form (openings included) becomes a vertex, every form edge with a free end an
    edge from its right face to its left face. The positions minimise ``sum |force_e - q_e form_e|^2``
    (unit force densities ``q`` unless given, one per form edge), one vertex per component held at the
    origin: exact when the form is in equilibrium with these force densities (equal ones on a regular
    grid, those of a relaxation; the reciprocal is then walked out along a tree, :func:`_walked`, not
    fitted), otherwise the start of :func:`vaultgram.formfinding.horizontal.horizontal`.

    Example
    -------
    >>> from vaultgram.formfinding.formdiagram import form_diagram
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> form = form_diagram(*grid_mesh(4))
    >>> force = force_diagram(form)
    >>> force.n_vertices, force.n_edges, bool(np.allclose(force.edge_vectors(), form.edge_vectors()))
    (16, 24, True)
    """
    active = np.flatnonzero(form.active)
    edges = np.stack([form.edge_faces[active, 1], form.edge_faces[active, 0]], axis=1)
    C = connectivity_matrix(edges, form.n_faces)
    for a in (edges, active):
        a.setflags(write=False)
    force = ForceDiagram(xy=np.zeros((form.n_faces, 2)), edges=edges, form_edge=active, C=C)
    target = (form.C @ form.xy)[active]
    if q is not None:
        target = np.asarray(q, dtype=float)[active, None] * target
    xy = _walked(force, target)
    if xy is None:
        xy = PinnedLaplacian(C, force.pins).solve(target, np.zeros((form.n_faces, 2)))
    return force.with_xy(xy)


#: Largest closure error, relative to the largest target, of targets taken as exactly reciprocal.
_CLOSED = 1e-12


def _walked(force: ForceDiagram, target: np.ndarray) -> np.ndarray | None:
    """The positions whose edge vectors are the targets, walked out from the pins along a
    breadth-first spanning tree, or None when the targets do not close around some form vertex
    (within :data:`_CLOSED`) and only a least-squares fit exists.

    When the form is in equilibrium with the force densities (a regular grid with equal ones, a
    relaxed pattern with its own), a reciprocal diagram exists (Block & Ochsendorf 2007): it is the
    least-squares fit (residual zero, unique with one pin per component), and walking it costs a
    breadth-first search and log2(depth) gathers instead of a sparse Cholesky factorisation.
    A root vertex joined to every pin makes one tree of all components.
    """
    n, m, root = force.n_vertices, force.n_edges, force.n_vertices
    pins = force.pins
    rows = np.concatenate([force.edges[:, 0], force.edges[:, 1], np.full(len(pins), root), pins])
    cols = np.concatenate([force.edges[:, 1], force.edges[:, 0], pins, np.full(len(pins), root)])
    code = np.concatenate([np.arange(1, m + 1), -np.arange(1, m + 1), np.full(2 * len(pins), m + 1)])
    adj = sp.csr_matrix((code.astype(float), (rows, cols)), shape=(n + 1, n + 1))
    if m == 0 or adj.nnz != len(rows):       # two edges between one pair of faces: not a tree walk
        return None
    pred = breadth_first_order(adj, root, directed=True, return_predecessors=True)[1].astype(np.int64)
    if (pred[:n] < 0).any():
        return None
    step = _tree_steps(force.edges, pred)
    walk = np.vstack([target[np.abs(step) - 1] * np.sign(step)[:, None], np.zeros((1, 2))])
    up = np.append(pred[:n], root)
    while (up != root).any():                        # pointer jumping: sums along the paths to the root
        walk += walk.take(up, axis=0)                # (take: a third of the time of walk[up] on 10^6 rows)
        up = up.take(up)
    xy = walk[:n]
    closure = np.abs(force.C @ xy - target).max()
    return xy if closure <= _CLOSED * max(float(np.abs(target).max()), 1e-300) else None


def _tree_steps(edges: np.ndarray, pred: np.ndarray) -> np.ndarray:
    """Per vertex ``v`` of a spanning tree given by its predecessors ``pred``, the edge joining it to
    ``pred[v]``, signed: ``e + 1`` for the edge ``e = (pred[v], v)``, ``-(e + 1)`` for ``(v, pred[v])``,
    0 at a pin (its predecessor the root, beyond the vertices). One edge joins a vertex and its
    predecessor (:func:`_walked` turns down diagrams with two between the same faces).

    >>> _tree_steps(np.array([[0, 1], [2, 1]]), np.array([3, 0, 1, -9999])).tolist()
    [0, 1, -2]
    """
    a, b = edges[:, 0], edges[:, 1]
    code = np.arange(1, len(edges) + 1)
    step = np.zeros(len(pred) - 1, dtype=np.int64)
    down, up = pred[b] == a, pred[a] == b
    step[b[down]] = code[down]
    step[a[up]] = -code[up]
    return step
