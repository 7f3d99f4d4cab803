"""What the two diagrams of Thrust Network Analysis share: a planar graph and its branch-node matrix.

Form and force diagram (Block & Ochsendorf 2007; §5 of the paper) are both plain arrays of plan
positions ``xy`` and edges ``(u, v)``; their edge vectors are ``C @ xy`` with the branch-node
connectivity matrix ``C`` of :func:`connectivity_matrix`. :class:`Diagram` gives both the same sizes,
edge vectors, connected components and "same topology, new positions".
"""

from __future__ import annotations

from dataclasses import replace
from functools import cached_property

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from vaultgram.errors import FormFindingError

__all__ = ["Diagram", "connectivity_matrix", "edge_components"]


def connectivity_matrix(edges: np.ndarray, n: int) -> sp.csr_matrix:
    """Branch-node matrix ``C`` (m x n): row ``e = (u, v)`` has -1 at ``u`` and +1 at ``v``.

    ``C @ x`` gives the edge vectors ``x[v] - x[u]``; ``C.T @ diag(q) @ C`` is the force-density
    stiffness of Schek's force density method used for vertical equilibrium.

    Example
    -------
    >>> connectivity_matrix(np.array([[0, 1], [1, 2]]), 3).toarray().tolist()
    [[-1.0, 1.0, 0.0], [0.0, -1.0, 1.0]]
    """
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    m = len(edges)
    # two entries per row, made in CSR order (columns ascending) without a sort of 2m coordinates
    u, v = edges[:, 0], edges[:, 1]
    cols = np.column_stack([np.minimum(u, v), np.maximum(u, v)])
    data = np.empty((m, 2))
    data[:, 0] = np.where(u < v, -1.0, 1.0)
    np.negative(data[:, 0], out=data[:, 1])
    return sp.csr_matrix((data.ravel(), cols.ravel(), np.arange(0, 2 * m + 1, 2)), shape=(m, n))


def edge_components(edges: np.ndarray, n: int) -> tuple[int, np.ndarray]:
    """Connected components of the graph of ``n`` vertices and ``edges``: (number, label per vertex).

    Example
    -------
    >>> count, labels = edge_components(np.array([[0, 1], [2, 3]]), 5)
    >>> count, labels.tolist()
    (3, [0, 0, 1, 1, 2])
    """
    adj = sp.csr_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
    return connected_components(adj, directed=False)


class Diagram:
    """Mixin of the frozen diagram dataclasses, which define ``xy`` (n, 2), ``edges`` (m, 2) and ``C``."""

    xy: np.ndarray
    edges: np.ndarray
    C: sp.csr_matrix

    @property
    def n_vertices(self) -> int:
        return len(self.xy)

    @property
    def n_edges(self) -> int:
        return len(self.edges)

    def edge_vectors(self) -> np.ndarray:
        """``xy[v] - xy[u]`` per edge, shape (m, 2)."""
        return self.C @ self.xy

    def edge_lengths(self) -> np.ndarray:
        return np.hypot(*self.edge_vectors().T)

    @cached_property
    def components(self) -> tuple[int, np.ndarray]:
        """Connected components of the diagram's graph (number, label per vertex)."""
        return edge_components(self.edges, self.n_vertices)

    def with_xy(self, xy: np.ndarray):
        """The same diagram with new plan positions (topology unchanged)."""
        xy = np.array(xy, dtype=float, copy=True)
        if xy.shape != self.xy.shape:
            raise FormFindingError(f"xy has shape {xy.shape}, expected {self.xy.shape}")
        xy.setflags(write=False)
        return replace(self, xy=xy)
