"""Sparse Cholesky factorisations for form finding: CHOLMOD's supernodal ``L L^T`` through cvxopt.

Every linear system of form finding is symmetric positive definite: the force-density stiffness
``C^T Q C`` of the free vertices (vertical equilibrium, the relaxation of openings; positive force
densities, every part supported) and the least-squares fits of the diagrams (every component pinned).
A general sparse LU (SuperLU) factorises them at about twice the cost of a Cholesky factorisation
and stores both triangles; CHOLMOD (Chen, Davis, Hager & Rajamanickam 2008) keeps its AMD
fill-reducing ordering and supernodal structure in a *symbolic* factorisation that new values on the
same pattern reuse (:meth:`Cholesky.refactor`): the search for the openings' sags factorises the same
pattern several times.

:class:`ForceDensityMatrix` assembles ``Cm^T diag(q) Cm`` for many ``q`` on one fixed pattern by a
precomputed sparse map from edge densities to the matrix entries (one sparse product per ``q``,
no sparse matrix-matrix product), so the symbolic factorisation stays valid.

Determinism: cvxopt reads CHOLMOD's settings from one module-level dict (``cvxopt.cholmod.options``)
that any code in the process may change (``supernodal = 0`` makes it an ``L D L^T`` factorisation,
with other rounding). Each call here runs under :data:`SETTINGS`, whatever that dict holds, and
leaves it as it found it: form finding gives the same bits whatever ran before it in the process.
"""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np
import scipy.sparse as sp
from cvxopt import cholmod, matrix, spmatrix

from vaultgram.errors import FormFindingError

__all__ = ["Cholesky", "ForceDensityMatrix", "SETTINGS"]

#: The CHOLMOD settings of every factorisation and solve: supernodal ``L L^T``, postordered, the
#: orderings CHOLMOD picks from by default (AMD here).
SETTINGS = {"supernodal": 2, "postorder": True, "nmethods": 0}


@contextmanager
def _settings():
    """Run with :data:`SETTINGS` as cvxopt's CHOLMOD options, then put back what was there."""
    saved = dict(cholmod.options)
    cholmod.options.clear()
    cholmod.options.update(SETTINGS)
    try:
        yield
    finally:
        cholmod.options.clear()
        cholmod.options.update(saved)


class Cholesky:
    """``P A P^T = L L^T`` of a sparse symmetric positive definite ``n`` x ``n`` matrix given by its
    lower-triangle entries (``rows >= cols``, no duplicates), ``what`` naming the system in the error
    when it is not positive definite (singular). :meth:`of` takes a scipy matrix.

    Example
    -------
    >>> A = sp.csc_matrix(np.array([[4.0, -1.0, 0.0], [-1.0, 4.0, -1.0], [0.0, -1.0, 4.0]]))
    >>> np.round(Cholesky.of(A, "a path").solve(np.array([3.0, 2.0, 3.0])), 12).tolist()
    [1.0, 1.0, 1.0]
    >>> Cholesky.of(-A, "negative matrix")
    Traceback (most recent call last):
    vaultgram.errors.FormFindingError: singular negative matrix (not positive definite)
    """

    def __init__(self, rows: np.ndarray, cols: np.ndarray, values: np.ndarray, n: int, what: str, hint: str = ""):
        self.n, self.what, self.hint = n, what, hint
        self._rows, self._cols = np.asarray(rows, dtype=np.int64), np.asarray(cols, dtype=np.int64)
        M = self._matrix(values)
        with _settings():
            self._factor = cholmod.symbolic(M)
        self._numeric(M)

    @classmethod
    def of(cls, A: sp.spmatrix, what: str, hint: str = "") -> "Cholesky":
        """The factorisation of the lower triangle of a scipy sparse matrix."""
        lower = sp.tril(A, format="coo")
        lower.sum_duplicates()
        return cls(lower.row, lower.col, lower.data, A.shape[0], what, hint)

    def _matrix(self, values: np.ndarray) -> spmatrix:
        return spmatrix(np.ascontiguousarray(values, dtype=float), self._rows, self._cols, (self.n, self.n))

    def _numeric(self, M: spmatrix) -> None:
        try:
            with _settings():
                cholmod.numeric(M, self._factor)
        except ArithmeticError:
            raise FormFindingError(f"singular {self.what} (not positive definite){self.hint}") from None

    def refactor(self, values: np.ndarray) -> "Cholesky":
        """Factorise new values of the same entries, reusing the symbolic factorisation (ordering,
        elimination tree, supernodes)."""
        self._numeric(self._matrix(values))
        return self

    def solve(self, b: np.ndarray) -> np.ndarray:
        """``A^{-1} b`` for a vector or for the columns of an (n, k) array."""
        b = np.asarray(b, dtype=float)
        B = matrix(np.asfortranarray(b.reshape(self.n, -1)))
        with _settings():
            cholmod.solve(self._factor, B)
        return np.array(B).reshape(b.shape)


class ForceDensityMatrix:
    """The lower triangle of ``Cm^T diag(q) Cm``, ``Cm`` the columns ``cols`` of a branch-node matrix
    ``C`` (each row: -1 and +1 at an edge's ends), for any edge densities ``q`` on one fixed pattern:
    :meth:`values` are its entries at ``rows, cols``, by a sparse map from edges to entries built once.

    Example
    -------
    >>> from vaultgram.formfinding.diagrams import connectivity_matrix
    >>> C = connectivity_matrix(np.array([[0, 1], [1, 2]]), 3)          # a path 0 - 1 - 2
    >>> K = ForceDensityMatrix(C, np.array([1, 2]))                    # vertex 0 held
    >>> K.rows.tolist(), K.cols.tolist(), K.values(np.array([2.0, 3.0])).tolist()
    ([0, 1, 1], [0, 1, 0], [5.0, 3.0, -3.0])
    """

    def __init__(self, C: sp.spmatrix, cols: np.ndarray):
        Cm = sp.csr_matrix(C)[:, cols]
        Cm.sort_indices()
        m, self.n = Cm.shape
        count, col = np.diff(Cm.indptr), Cm.indices.astype(np.int64)
        both = np.flatnonzero(count == 2)                  # edges with two moving ends
        first = Cm.indptr[both]
        # the entries: the diagonal (every moving vertex: its edges, the columns of Cm), then one below
        # it per edge with two moving ends (edges are distinct, so no entry twice); the map's rows in
        # CSR order as they come (Cm's columns by a CSC conversion), no sort of the entries
        by_vertex = Cm.tocsc()
        by_vertex.sort_indices()
        indptr = np.concatenate([by_vertex.indptr, by_vertex.indptr[-1] + 1 + np.arange(len(both))])
        signs = np.concatenate([by_vertex.data * by_vertex.data, Cm.data[first] * Cm.data[first + 1]])
        self.rows = np.concatenate([np.arange(self.n), col[first + 1]])
        self.cols = np.concatenate([np.arange(self.n), col[first]])
        self._map = sp.csr_matrix((signs, np.concatenate([by_vertex.indices, both]), indptr),
                                  shape=(self.n + len(both), m))

    def values(self, q: np.ndarray) -> np.ndarray:
        """The entries of ``Cm^T diag(q) Cm`` at ``rows, cols``."""
        return self._map @ np.asarray(q, dtype=float)

    def factorised(self, q: np.ndarray, what: str, hint: str = "") -> Cholesky:
        """The Cholesky factorisation for the densities ``q`` (refactor it for others)."""
        return Cholesky(self.rows, self.cols, self.values(q), self.n, what, hint)
