"""Array helpers the stages share.

The meshes' bookkeeping reduces to sets of integer keys (an edge ``lo * n + hi``, a voussoir at a
vertex ``group * n + vertex``). ``np.unique`` without ``return_*`` uses a hash table in numpy 2.3 and
later, some 30 times slower than sorting on 10^5-10^6 such keys, and imports ``numpy.ma`` the first
time (10 ms of a command's start, to ask whether its input is masked); :func:`distinct` sorts.

The choices the stages make between computed values (the largest score, the nearest edge) meet ties
wherever a plan is symmetric: mirror edges have equal scores in exact arithmetic, and which of them
wins then follows the last bits of the arithmetic, which differ between machines (the BLAS kernels
of the form finding's solvers). :func:`steady` and :func:`nearest` take values within :data:`TIE`
of each other as equal and give a tie to the lowest index, so the same plan gives the same pattern
everywhere.
"""

from __future__ import annotations

import numpy as np

__all__ = ["TIE", "TIED", "PIECE", "cross_rows", "distinct", "json_array", "link_components", "lookup", "nearest",
           "pieces", "plan_rows", "ranges", "row_dot", "run_starts", "sorted_keys", "steady", "unit_rows"]

#: Relative difference under which two computed values are a tie (round-off differs between
#: machines by some 1e-15 relative; the stages' real differences are far above 1e-9).
TIE = 1e-9
#: How many points as near as the nearest :func:`nearest` looks through (a vertex of a regular grid
#: has four neighbours at one distance, a point of a regular triangulation six).
TIED = 8
#: Rows per piece of :func:`pieces`: the temporaries of a dozen arithmetic steps on this many rows of
#: two floats fit in a core's 1 MB level-2 cache.
PIECE = 1 << 14


def distinct(values) -> np.ndarray:
    """The sorted distinct values of a 1-d array (``np.unique`` by sorting).

    >>> distinct(np.array([7, 3, 7, 1, 3])).tolist()
    [1, 3, 7]
    """
    s = sorted_keys(np.asarray(values).ravel())
    return s[run_starts(s)]


def link_components(n: int, a, b) -> np.ndarray:
    """The smallest element of the component of each of ``n`` elements linked in pairs ``(a[k], b[k])``.

    Each round hooks every link's larger root under the smaller one and flattens the trees by pointer
    jumping, all vectorised; it ends when every link's two ends have one root. The components are
    scipy's ``connected_components``'s, without importing ``scipy.sparse.csgraph``, which imports
    ``scipy.sparse.linalg``: 10 ms of every ``vaultgram mesh`` (issue 18).

    >>> link_components(6, [4, 1, 5], [1, 3, 0]).tolist()
    [0, 1, 2, 1, 1, 0]
    """
    root = np.arange(n)
    a, b = np.asarray(a, dtype=np.int64), np.asarray(b, dtype=np.int64)
    while True:
        ra, rb = root[a], root[b]
        if np.array_equal(ra, rb):
            return root
        low = np.minimum(ra, rb)
        np.minimum.at(root, ra, low)
        np.minimum.at(root, rb, low)
        while not np.array_equal(up := root[root], root):
            root = up


def json_array(values, arrays: bool = False):
    """``values`` for a JSON file: a list, or with ``arrays`` the C-contiguous array itself, which
    :func:`vaultgram.io.files.write_json` (orjson) writes as the same bytes as the list, 4-5 times
    faster and without making 10^6 Python numbers first (the ``to_json`` of the stage values).

    >>> json_array(np.array([[1.5, 2.0]])), json_array(np.array([[1.5, 2.0]]).T, arrays=True).flags.c_contiguous
    ([[1.5, 2.0]], True)
    """
    return np.ascontiguousarray(values) if arrays else np.asarray(values).tolist()


def sorted_keys(values: np.ndarray) -> np.ndarray:
    """``values`` sorted; integers by the stable sort (timsort), which runs 10-25 times faster than the
    default on keys made in mesh order (an edge ``lo * n + hi`` per face corner, a voussoir at each
    vertex: long sorted runs) and about 15% slower on random ones. The sorted integers are the same
    whichever sort; floats keep the default sort, where the order of -0.0 and 0.0 would change.

    >>> sorted_keys(np.array([3, 1, 2])).tolist(), sorted_keys(np.array([0.5, -1.0])).tolist()
    ([1, 2, 3], [-1.0, 0.5])
    """
    return np.sort(values, kind="stable" if values.dtype.kind in "iub" else None)


def lookup(keys: np.ndarray, wanted) -> tuple[np.ndarray, np.ndarray]:
    """Where each of ``wanted`` is in the sorted 1-d ``keys``, and whether it is there at all (the
    position is then meaningless): a sorted search, where ``np.isin`` is some 50 times slower on
    10^6 keys (numpy 2.4).

    >>> pos, found = lookup(np.array([2, 5, 9]), np.array([9, 4, 2, 12]))
    >>> pos[found].tolist(), found.tolist()
    ([2, 0], [True, False, True, False])
    """
    wanted = np.asarray(wanted)
    if len(keys) == 0:
        return np.zeros(wanted.shape, dtype=np.int64), np.zeros(wanted.shape, dtype=bool)
    pos = np.minimum(np.searchsorted(keys, wanted), len(keys) - 1)
    return pos, keys[pos] == wanted


def run_starts(keys: np.ndarray) -> np.ndarray:
    """Where each run of equal values of the sorted 1-d ``keys`` starts.

    >>> run_starts(np.array([1, 1, 3, 7, 7])).tolist()
    [True, False, True, True, False]
    """
    return np.concatenate([[True], keys[1:] != keys[:-1]]) if len(keys) else np.zeros(0, dtype=bool)


def ranges(start, length) -> tuple[np.ndarray, np.ndarray]:
    """The ranges ``start[i] .. start[i] + length[i] - 1`` one after another: for every index, its
    range ``i``, and the index (the faces of a set of voussoirs, the corners of a set of faces).

    >>> [a.tolist() for a in ranges(np.array([5, 0]), np.array([2, 3]))]
    [[0, 0, 1, 1, 1], [5, 6, 0, 1, 2]]
    """
    length = np.asarray(length)
    row = np.repeat(np.arange(len(length)), length)
    return row, np.repeat(np.asarray(start) - np.cumsum(length) + length, length) + np.arange(int(length.sum()))


def pieces(n: int, size: int = PIECE) -> list[slice]:
    """The slices ``0:size, size:2 size, ...`` that cover ``range(n)``: elementwise arithmetic on the
    4 10^6 corners of a 10^6-face mesh done a piece at a time, whose temporaries stay in the
    processor's cache instead of going to memory and back at every step (the smoothing's test of
    every face, :func:`vaultgram.meshing.smoothing.laplacian_smooth`, ran three times as fast).

    >>> pieces(5, 2)
    [slice(0, 2, None), slice(2, 4, None), slice(4, 6, None)]
    """
    return [slice(s, s + size) for s in range(0, n, size)]


def plan_rows(x: np.ndarray, index) -> np.ndarray:
    """The plan coordinates (first two columns) of rows ``index`` of ``x``: ``x[index, :2]``, gathered
    with ``take`` (the mixed fancy-and-slice index copies element by element: about three times
    slower on the 10^5-10^6 rows of a mesh's corners or edges).

    >>> plan_rows(np.array([[0.0, 1, 9], [2, 3, 9], [4, 5, 9]]), np.array([2, 0])).tolist()
    [[4.0, 5.0], [0.0, 1.0]]
    """
    return x[:, :2].take(index, axis=0)


def row_dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The dot product of each row of ``a`` with the same row of ``b`` (``einsum``: about a third of
    the time of ``(a * b).sum(axis=1)`` on 10^5 rows of three).

    >>> row_dot(np.array([[1.0, 2, 3], [0, 1, 0]]), np.array([[1.0, 1, 1], [2, 5, 7]])).tolist()
    [6.0, 5.0]
    """
    return np.einsum("ij,ij->i", a, b)


def cross_rows(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The cross product of each row of ``a`` with the same row of ``b`` (rows of three), by columns:
    the same products and differences as ``np.cross`` (the same bits), which converts and copies its
    inputs on the way and takes some three times as long on the 10^6 corners of a mesh.

    >>> cross_rows(np.array([[1.0, 0, 0], [0, 2, 0]]), np.array([[0.0, 1, 0], [0, 0, 3]])).tolist()
    [[0.0, 0.0, 1.0], [6.0, 0.0, 0.0]]
    """
    a0, a1, a2 = a[:, 0], a[:, 1], a[:, 2]
    b0, b1, b2 = b[:, 0], b[:, 1], b[:, 2]
    return np.column_stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def unit_rows(v: np.ndarray) -> np.ndarray:
    """Each row of ``v`` scaled to unit length (a zero row stays zero).

    >>> unit_rows(np.array([[3.0, 4.0], [0.0, 0.0]])).tolist()
    [[0.6, 0.8], [0.0, 0.0]]
    """
    return v / np.maximum(np.sqrt(row_dot(v, v)), 1e-300)[:, None]


def steady(values, scale: float | None = None) -> np.ndarray:
    """``values`` rounded to multiples of a power of two near :data:`TIE` times ``scale`` (by default
    their largest magnitude), so that ``np.argmax`` or a stable sort of them treats round-off as a tie
    and takes the lowest index, the same on every machine. Sums and differences of up to some 10^6
    such values are exact (integers times the step, within 53 bits), so comparisons between them are
    steady too.

    >>> a = np.array([0.3, 0.1 + 0.2])  # equal in exact arithmetic, not in floating point
    >>> int(np.argmax(a)), int(np.argmax(steady(a)))
    (1, 0)
    """
    values = np.asarray(values, dtype=float)
    if scale is None:
        scale = float(np.abs(values).max()) if values.size else 1.0
    step = 2.0 ** np.floor(np.log2(TIE * (scale if scale > 0 else 1.0)))
    return np.round(values / step) * step


def nearest(points: np.ndarray, queries: np.ndarray) -> np.ndarray:
    """Per row of ``queries``, the index of the nearest row of ``points``; of up to :data:`TIED` points
    as near within :data:`TIE` of the extent of both, the lowest index (a KD tree's own answer then
    follows round-off). Two neighbours are asked for each query, more only where the two tie. The
    tree's boxes are not shrunk to its points (``compact_nodes=False``): the same answers, 15% less
    time for the 2.2M edges of a 10^6-face bond and its 2,000 free boundary edges.

    >>> nearest(np.array([[1.0, 0.0], [0.0, 1.0], [3.0, 3.0]]), np.array([[0.0, 0.0], [2.0, 2.5]])).tolist()
    [0, 2]
    """
    points, queries = np.asarray(points, dtype=float), np.asarray(queries, dtype=float)
    from scipy.spatial import cKDTree  # not with the module: the mesh command does without scipy (issue 18)

    both = np.vstack([points, queries])
    tol = TIE * max(float(np.ptp(both, axis=0).max()) if len(both) else 0.0, 1e-300)
    tree = cKDTree(points, compact_nodes=False)
    found = _lowest_of_nearest(tree, queries, min(2, len(points)), tol)
    tied = np.flatnonzero(found[1])
    if len(tied):
        found[0][tied] = _lowest_of_nearest(tree, queries[tied], min(TIED, len(points)), tol)[0]
    return found[0]


def _lowest_of_nearest(tree, queries: np.ndarray, k: int, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """The lowest index among the ``k`` nearest points within ``tol`` of the nearest, and whether all
    ``k`` were that near (more might be)."""
    d, i = tree.query(queries, k=k, workers=-1)
    d, i = d.reshape(len(queries), k), i.reshape(len(queries), k)
    near = d <= d[:, :1] + tol
    return np.where(near, i, tree.n).min(axis=1), near.all(axis=1) & (k > 1)
