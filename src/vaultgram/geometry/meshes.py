"""Polygonal meshes as plain data: per-corner arrays, adjacency, boundary loops, regular grids.

A mesh here is ``vertices``, an ``(n, 2)`` or ``(n, 3)`` float array, and ``faces``, a list of
vertex-index sequences, counter-clockwise seen from +z. Every stage that walks a mesh (smoothing,
quality, form finding, tessellation) uses these vectorised helpers instead of loops over faces; they
know nothing about vaults or statics.
"""

from __future__ import annotations

import functools
import itertools
from typing import Iterable, NamedTuple, Sequence

import numpy as np

from vaultgram.errors import MeshError, NonManifoldVertexError
from vaultgram.geometry.arrays import distinct, lookup, pieces, plan_rows, run_starts
from vaultgram.geometry.polygons import signed_angles

__all__ = [
    "MeshError",
    "NonManifoldVertexError",
    "grid_mesh",
    "grid_index",
    "remove_faces",
    "boundary_loops",
    "loops_of",
    "corner_arrays",
    "corners_of_flat",
    "Faces",
    "corner_vectors",
    "corner_angles",
    "with_midpoints",
    "has_side_in",
    "Adjacency",
    "MeanOperator",
    "barycentre_operator",
    "has_twin",
    "twinned_sides",
    "adjacency",
    "boundary_adjacency",
    "face_areas",
    "shoelace_areas",
    "boundary_halfedges",
]


def grid_index(i: int, j: int, nx: int) -> int:
    """Index of grid vertex ``(i, j)`` (at ``x = i * spacing, y = j * spacing``) in :func:`grid_mesh`.

    >>> grid_index(1, 2, nx=2), grid_mesh(2)[1][3]
    (7, (4, 5, 8, 7))
    """
    return j * (nx + 1) + i


def grid_mesh(nx: int, ny: int | None = None, spacing: float = 1.0,
              origin: tuple[float, float] = (0.0, 0.0)) -> tuple[np.ndarray, list[tuple[int, int, int, int]]]:
    """A regular ``nx`` x ``ny`` quad grid, faces counter-clockwise.

    Vertex ``(i, j)`` lies at ``origin + spacing * (i, j)`` and has index ``j * (nx + 1) + i``
    (see :func:`grid_index`).

    Returns
    -------
    vertices : ndarray (n, 3), z = 0
    faces : list of 4-tuples

    Raises
    ------
    MeshError
        if ``nx`` or ``ny`` is less than 1.

    Example
    -------
    >>> v, f = grid_mesh(2)
    >>> v.shape, len(f), f[0]
    ((9, 3), 4, (0, 1, 4, 3))
    """
    ny = nx if ny is None else ny
    if nx < 1 or ny < 1:
        raise MeshError(f"grid needs at least one face in each direction, got {nx} x {ny}")
    i, j = np.meshgrid(np.arange(nx + 1), np.arange(ny + 1))
    vertices = np.zeros(((nx + 1) * (ny + 1), 3))
    vertices[:, 0] = origin[0] + spacing * i.ravel()
    vertices[:, 1] = origin[1] + spacing * j.ravel()
    fi, fj = np.meshgrid(np.arange(nx), np.arange(ny))
    a = (fj * (nx + 1) + fi).ravel()
    quads = np.stack([a, a + 1, a + nx + 2, a + nx + 1], axis=1)
    return vertices, [tuple(int(k) for k in q) for q in quads]


def remove_faces(vertices: np.ndarray, faces: Sequence[Sequence[int]], drop: Iterable[int]
                 ) -> tuple[np.ndarray, list[tuple[int, ...]], np.ndarray]:
    """Remove the faces listed in ``drop`` and the vertices no face uses any more.

    Returns the new vertices, the re-indexed faces, and for each new vertex its old index.
    Used to punch holes (openings) into grids for tests and examples.

    >>> v, f, old = remove_faces(*grid_mesh(2), drop=[0])  # vertex 0 goes with face 0
    >>> len(v), f[0], old.tolist()
    (8, (0, 1, 4, 3), [1, 2, 3, 4, 5, 6, 7, 8])
    """
    drop = set(int(f) for f in drop)
    kept = [tuple(int(v) for v in f) for k, f in enumerate(faces) if k not in drop]
    used = np.zeros(len(vertices), dtype=bool)
    for f in kept:
        used[list(f)] = True
    old = np.flatnonzero(used)
    new_of_old = np.full(len(vertices), -1)
    new_of_old[old] = np.arange(len(old))
    return (np.asarray(vertices)[old].copy(),
            [tuple(int(new_of_old[v]) for v in f) for f in kept], old)


class Faces(tuple):
    """Faces (vertex-index sequences) that keep their corner arrays (:func:`corner_arrays`): a mesh
    that several steps flatten in turn (the tessellation's areas, normals, edges and outlines) is
    flattened once. The arrays are read-only, as the faces are. They keep which sides have a twin
    too (:func:`twinned_sides`): the smoothing, the supports (twice) and the mesh statistics each
    asked for a 10^6-face mesh's boundary.

    >>> f = Faces([(0, 1, 2), (2, 1, 3)])
    >>> corner_arrays(f)[1] is corner_arrays(f)[1], len(f), f[1]
    (True, 2, (2, 1, 3))
    """

    @functools.cached_property
    def corners(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        return _read_only(_flattened(self))

    @functools.cached_property
    def twinned(self) -> np.ndarray:
        _, u, v, _ = self.corners
        return _read_only((has_twin(u, v),))[0]

    def __reduce__(self):
        """Pickled as its corners end to end and the face sizes (two arrays, copied whole), not as 10^5
        tuples or small arrays one by one: the figure process gets each stage's value through a
        pipe (:mod:`vaultgram.io.figures.worker`), where a 10^5-face tessellation's voussoir loops
        took 0.4 s to pickle.

        >>> import pickle
        >>> f = Faces([(0, 1, 2), (2, 1, 3, 4)])
        >>> g = pickle.loads(pickle.dumps(f))
        >>> g == f, type(g).__name__, corner_arrays(g)[2].tolist() == corner_arrays(f)[2].tolist()
        (True, 'Faces', True)
        >>> [a.tolist() for a in pickle.loads(pickle.dumps(Faces([np.array([5, 6, 7]), np.array([8, 9])])))]
        [[5, 6, 7], [8, 9]]
        """
        face, vert, _, _ = self.corners
        lens = np.bincount(face, minlength=len(self))
        return _unpickled, (vert, lens, len(self) > 0 and isinstance(self[0], np.ndarray))

    @classmethod
    def from_flat(cls, vert: np.ndarray, lens: np.ndarray, faces: Sequence[tuple[int, ...]] | None = None) -> "Faces":
        """Faces from their vertices end to end and their sizes, the corner arrays made from these
        arrays (not from the tuples): how a vectorised step hands on faces of 10^6-face meshes.
        ``faces``: the same faces (tuples, or vertex arrays) when the caller has them (not made again).

        >>> f = Faces.from_flat(np.array([0, 1, 2, 2, 1, 3]), np.array([3, 3]))
        >>> f, corner_arrays(f)[2].tolist() == corner_arrays([(0, 1, 2), (2, 1, 3)])[2].tolist()
        (((0, 1, 2), (2, 1, 3)), True)
        """
        vert, lens = np.array(vert, dtype=np.int64), np.array(lens, dtype=np.int64)  # copies: made read-only
        out = cls(_tuples(vert, lens) if faces is None else faces)
        out.__dict__["corners"] = _read_only(corners_of_flat(vert, lens))  # the cached_property's slot
        return out


def _unpickled(vert: np.ndarray, lens: np.ndarray, arrays: bool) -> Faces:
    """:class:`Faces` from their pickled corners and sizes: tuples, or vertex arrays if they were."""
    loops = np.split(vert.copy(), np.cumsum(lens)[:-1]) if arrays else None  # apart from the corners
    return Faces.from_flat(vert, lens, loops)


def _tuples(vert: np.ndarray, lens: np.ndarray) -> list[tuple[int, ...]]:
    """Faces as tuples of Python ints from their vertices end to end and their sizes: each run of
    faces of one size is cut by ``zip`` over one iterator (a third faster than slicing face by face
    on 10^6 quads).

    >>> _tuples(np.array([0, 1, 2, 3, 4, 5, 6, 7, 8, 9]), np.array([3, 3, 4]))
    [(0, 1, 2), (3, 4, 5), (6, 7, 8, 9)]
    """
    corners, out = iter(vert.tolist()), []
    if len(lens) == 0:
        return out
    runs = np.flatnonzero(np.diff(lens)) + 1
    starts, ends = np.concatenate([[0], runs]).tolist(), np.concatenate([runs, [len(lens)]]).tolist()
    for a, b, size in zip(starts, ends, lens[starts].tolist()):
        run = itertools.islice(corners, (b - a) * size)  # this run's corners, taken from the one iterator
        out.extend(zip(*[run] * size) if size else [()] * (b - a))
    return out


def _read_only(arrays: tuple) -> tuple:
    for a in arrays:
        a.flags.writeable = False
    return arrays


def corner_arrays(faces: Sequence[Sequence[int]]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Flatten faces into per-corner arrays ``(face, vertex, next vertex, previous vertex)``.

    Corner ``k`` of face ``f`` has vertex ``faces[f][k]``; the halfedge ``vertex -> next`` belongs to
    ``f`` (``f`` lies on its left for counter-clockwise faces). Vectorised stages use these instead
    of loops over faces.

    >>> [a.tolist() for a in corner_arrays([(0, 1, 2), (2, 1, 3)])]
    [[0, 0, 0, 1, 1, 1], [0, 1, 2, 2, 1, 3], [1, 2, 0, 1, 3, 2], [2, 0, 1, 3, 2, 1]]
    >>> [a.tolist() for a in corner_arrays([(4, 5), (), (6,)])]  # short and empty faces too
    [[0, 0, 2], [4, 5, 6], [5, 4, 6], [5, 4, 6]]
    """
    return faces.corners if isinstance(faces, Faces) else _flattened(faces)


def _flattened(faces: Sequence[Sequence[int]]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    if len(faces) == 0:
        e = np.zeros(0, dtype=np.int64)
        return e, e, e, e
    lens = np.fromiter(map(len, faces), dtype=np.int64, count=len(faces))
    if isinstance(faces[0], np.ndarray):  # loops of vertex arrays: joined whole, not element by element
        vert = np.concatenate(faces).astype(np.int64, copy=False)
    else:
        vert = np.fromiter(itertools.chain.from_iterable(faces), dtype=np.int64, count=int(lens.sum()))
    return corners_of_flat(vert, lens)


def corners_of_flat(vert: np.ndarray, lens: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The corner arrays (:func:`corner_arrays`) of faces given end to end (``vert``) with their sizes
    (``lens``), for a step that holds faces as arrays and not as tuples.

    >>> [a.tolist() for a in corners_of_flat(np.array([0, 1, 2, 2, 1, 3]), np.array([3, 3]))]
    [[0, 0, 0, 1, 1, 1], [0, 1, 2, 2, 1, 3], [1, 2, 0, 1, 3, 2], [2, 0, 1, 3, 2, 1]]
    """
    if len(lens) == 0:
        return vert, vert, vert, vert
    face = np.repeat(np.arange(len(lens)), lens)
    end = np.cumsum(lens)[lens > 0]  # an empty face (bad input, reported by the caller) has no corner
    start = end - lens[lens > 0]
    nxt, prv = np.roll(vert, -1), np.roll(vert, 1)  # the next and previous corner in the whole array,
    nxt[end - 1] = vert[start]  # but a face's last corner is followed by its first
    prv[start] = vert[end - 1]
    return face, vert, nxt, prv


def corner_vectors(x: np.ndarray, u: np.ndarray, v: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The edge vectors (in the plan) from each corner's vertex ``u`` to the next vertex ``v`` and to
    the previous vertex ``p`` (the arrays of :func:`corner_arrays`): the two sides of the corner,
    whose cross product is positive at a counter-clockwise corner.

    >>> x = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    >>> [e.tolist() for e in corner_vectors(x, np.array([0]), np.array([1]), np.array([2]))]
    [[[1.0, 0.0]], [[0.0, 1.0]]]
    """
    at = plan_rows(x, u)
    return plan_rows(x, v) - at, plan_rows(x, p) - at


def corner_angles(x: np.ndarray, u: np.ndarray, v: np.ndarray, p: np.ndarray) -> np.ndarray:
    """The signed angle (radians, in [-pi, pi]) of each corner, from its side to the next vertex ``v``
    to its side to the previous vertex ``p`` (positive at a counter-clockwise corner): the
    :func:`~vaultgram.geometry.polygons.signed_angles` of :func:`corner_vectors`, the same numbers,
    computed a cache-sized piece at a time (:func:`~vaultgram.geometry.arrays.pieces`; half the
    time on the 4 10^6 corners of a 10^6-face mesh).

    >>> x = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    >>> corner_angles(x, np.array([0, 1]), np.array([1, 2]), np.array([2, 0])).round(4).tolist()
    [1.5708, 0.7854]
    """
    xy = np.ascontiguousarray(x[:, :2])
    out = np.empty(len(u))
    for part in pieces(len(u)):
        out[part] = signed_angles(*corner_vectors(xy, u[part], v[part], p[part]))
    return out


def has_twin(u: np.ndarray, v: np.ndarray, n: int | None = None) -> np.ndarray:
    """For each halfedge ``u[k] -> v[k]``, whether the mesh also has ``v[k] -> u[k]``: False on the
    boundary. ``n`` is any number above the largest vertex index (default: that index plus one).

    The halfedges are sorted by their undirected edge ``min * n + max``, once (a stable sort: fast on
    a mesh's keys, :func:`~vaultgram.geometry.arrays.sorted_keys`), so that an edge's halfedges lie
    together: one has a twin when its run holds one running the other way (a loop ``u -> u`` is its
    own twin). A search for every reversed halfedge in the sorted halfedges took twice as long.

    >>> has_twin(np.array([0, 1, 1]), np.array([1, 0, 2])).tolist()
    [True, True, False]
    """
    if len(u) == 0:
        return np.zeros(0, dtype=bool)
    if n is None:
        n = int(max(u.max(), v.max())) + 1
    edge = np.minimum(u, v) * n + np.maximum(u, v)
    order = np.argsort(edge, kind="stable")
    run = np.cumsum(run_starts(edge[order])) - 1
    up = (u > v)[order]
    has_up, has_down = np.zeros(run[-1] + 1, dtype=bool), np.zeros(run[-1] + 1, dtype=bool)
    has_up[run[up]] = True
    has_down[run[~up]] = True
    out = np.empty(len(u), dtype=bool)
    out[order] = np.where(up, has_down[run], has_up[run])
    return out | (u == v)


def twinned_sides(faces: Sequence[Sequence[int]]) -> np.ndarray:
    """Per corner of ``faces`` (:func:`corner_arrays`), whether the mesh also has its side the other way
    (:func:`has_twin`; False on the boundary), kept by :class:`Faces`.

    >>> twinned_sides([(0, 1, 2), (2, 1, 3)]).tolist()
    [False, True, False, True, False, False]
    """
    if isinstance(faces, Faces):
        return faces.twinned
    _, u, v, _ = corner_arrays(faces)
    return has_twin(u, v)


def boundary_loops(faces: Sequence[Sequence[int]]) -> list[list[int]]:
    """The boundary loops of a manifold, consistently oriented mesh.

    Each loop is the list of vertices met along the face halfedges that have no twin, so the outer
    boundary of a counter-clockwise mesh is counter-clockwise and holes are clockwise.

    Raises
    ------
    NonManifoldVertexError
        if a vertex starts two boundary halfedges (a non-manifold "pinched" vertex).

    Example
    -------
    >>> boundary_loops(grid_mesh(1)[1])
    [[0, 1, 3, 2]]
    """
    return loops_of(*boundary_halfedges(faces))


def loops_of(starts: np.ndarray, ends: np.ndarray) -> list[list[int]]:
    """The boundary loops walked along the boundary halfedges ``starts[k] -> ends[k]`` (those of
    :func:`boundary_halfedges`, when a caller has them already), each from its first halfedge.

    >>> loops_of(np.array([0, 1, 2, 5, 6]), np.array([1, 2, 0, 6, 5]))
    [[0, 1, 2], [5, 6]]
    """
    return _walk_loops(_next_boundary_vertex(starts.tolist(), ends.tolist()))


def _next_boundary_vertex(starts: list[int], ends: list[int]) -> dict[int, int]:
    """``{a: b}`` for every boundary halfedge ``a -> b``, in the order given."""
    nxt: dict[int, int] = {}
    for a, b in zip(starts, ends):
        if a in nxt:
            raise NonManifoldVertexError(
                f"vertex {a} starts two boundary halfedges (non-manifold boundary vertex)", vertex=a)
        nxt[a] = b
    return nxt


def _walk_loops(nxt: dict[int, int]) -> list[list[int]]:
    """The cycles of the successor map ``nxt``, each from its first vertex in ``nxt``'s order."""
    loops: list[list[int]] = []
    seen: set[int] = set()
    for a in nxt:
        if a in seen:
            continue
        loop = [a]
        seen.add(a)
        b = nxt[a]
        while b != a:
            loop.append(b)
            seen.add(b)
            b = nxt[b]
        loops.append(loop)
    return loops


def has_side_in(faces, sides, n: int) -> np.ndarray:
    """Per face, whether one of its sides is among ``sides`` (pairs ``(lo, hi)`` of vertex ids below
    ``n``): the faces that :func:`with_midpoints` changes, found without visiting every face in Python.

    >>> has_side_in([(0, 1, 2, 3), (1, 4, 5, 2), (4, 6, 7, 5)], {(1, 2): 9}, 10).tolist()
    [True, True, False]
    """
    fid, u, v, _ = corner_arrays(faces)
    keys = np.sort(np.array([a * n + b for a, b in sides], dtype=np.int64))
    hit = lookup(keys, np.minimum(u, v) * n + np.maximum(u, v))[1]
    return np.bincount(fid[hit], minlength=len(faces)) > 0


def with_midpoints(face, midpoint: dict) -> tuple:
    """A face with the midpoints of its cut sides inserted after their first vertex: ``midpoint``
    maps a side ``(min, max)`` to its new vertex (a face beside one that was cut keeps the mesh
    conforming).

    >>> with_midpoints((0, 1, 2, 3), {(1, 2): 9})
    (0, 1, 9, 2, 3)
    """
    face = list(face)
    out = []
    for a, b in zip(face, face[1:] + face[:1]):
        out.append(a)
        m = midpoint.get((min(a, b), max(a, b)))
        if m is not None and m not in face:
            out.append(m)
    return tuple(out)


class Adjacency(NamedTuple):
    """A symmetric 0/1 vertex adjacency of ``n`` vertices as its pairs ``(rows[k], cols[k])``, sorted by
    row, then column (the non-zeros of a sparse matrix in row order): numpy arrays instead of a scipy
    matrix, so that meshing does not import scipy (issue 18)."""

    n: int
    rows: np.ndarray
    cols: np.ndarray

    @property
    def nnz(self) -> int:
        """The number of pairs."""
        return len(self.rows)

    def degrees(self) -> np.ndarray:
        """The number of neighbours of each vertex, as floats."""
        return np.bincount(self.rows, minlength=self.n).astype(float)

    def rows_of(self, other: Adjacency, mask: np.ndarray) -> Adjacency:
        """This adjacency with the rows of the vertices of ``mask`` taken from ``other`` (no longer
        symmetric)."""
        take, take_other = ~np.asarray(mask, dtype=bool)[self.rows], np.asarray(mask, dtype=bool)[other.rows]
        rows = np.concatenate([self.rows[take], other.rows[take_other]])
        cols = np.concatenate([self.cols[take], other.cols[take_other]])
        order = np.argsort(rows, kind="stable")  # a row comes from one of the two, its columns stay sorted
        return Adjacency(self.n, rows[order], cols[order])


#: From this many vertices on, :class:`MeanOperator` multiplies by a scipy CSR matrix: 4-5 times
#: faster per product than numpy's ``bincount`` (at 1.2 10^6 vertices, 20 smoothing iterations took
#: 3.6 s instead of 2.5 s), and its import (0.2 s) no longer counts. Below, numpy: ``vaultgram mesh``
#: of a small plan imports no scipy (issue 18).
SCIPY_FROM = 1 << 18


class MeanOperator(NamedTuple):
    """``D^-1 A`` of an :class:`Adjacency` ``A`` with degrees ``D``: ``w @ x`` moves every row of ``x``
    to the mean of its neighbours' rows (a vertex without any to the origin)."""

    adjacency: Adjacency
    inverse_degrees: np.ndarray  # 1 / max(degree, 1) per vertex
    matrix: object = None  # the scipy CSR matrix, from SCIPY_FROM vertices

    def __matmul__(self, x) -> np.ndarray:
        """The means: per column, the neighbours' values summed (``np.bincount``), times the inverse
        degree; or the CSR product (the same means to the last bits: its sums run in its order)."""
        x = np.asarray(x, dtype=float)
        if self.matrix is not None:
            return self.matrix @ x
        a = self.adjacency
        flat = x.reshape(a.n, -1)
        out = [np.bincount(a.rows, weights=np.take(flat[:, k], a.cols), minlength=a.n) * self.inverse_degrees
               for k in range(flat.shape[1])]
        return np.stack(out, axis=1).reshape(x.shape) if out else np.zeros_like(x)


def barycentre_operator(a: Adjacency) -> tuple[MeanOperator, np.ndarray]:
    """``D^-1 A`` of a vertex adjacency ``A`` (each vertex to the mean of its neighbours; a vertex
    without any goes to the origin) and the degrees ``D``.

    >>> w, deg = barycentre_operator(adjacency(3, [(0, 1, 2)]))
    >>> (w @ np.array([[0.0], [3.0], [6.0]])).ravel().tolist(), deg.tolist()
    ([4.5, 3.0, 1.5], [2.0, 2.0, 2.0])
    """
    deg = a.degrees()
    inverse = 1.0 / np.maximum(deg, 1)
    if a.n < SCIPY_FROM:
        return MeanOperator(a, inverse), deg
    import scipy.sparse as sp  # a large mesh: its import no longer counts

    matrix = sp.csr_matrix((inverse[a.rows], a.cols, np.searchsorted(a.rows, np.arange(a.n + 1))), shape=(a.n, a.n))
    return MeanOperator(a, inverse, matrix), deg


def adjacency(n: int, faces) -> Adjacency:
    """Symmetric 0/1 vertex adjacency of ``n`` vertices by the edges of ``faces``.

    >>> a = adjacency(4, [(0, 1, 2, 3)])
    >>> a.rows.tolist(), a.cols.tolist()
    ([0, 0, 1, 1, 2, 2, 3, 3], [1, 3, 0, 2, 1, 3, 0, 2])
    """
    _, u, v, _ = corner_arrays(faces)
    return _symmetric_adjacency(n, u, v)


def boundary_adjacency(n: int, faces) -> Adjacency:
    """Symmetric 0/1 adjacency of the boundary edges (half-edges without twin) of ``faces``.

    >>> b = boundary_adjacency(4, [(0, 1, 2), (2, 1, 3)])  # two triangles sharing the edge 1-2
    >>> b.nnz, list(zip(b.rows.tolist(), b.cols.tolist()))[:3]
    (8, [(0, 1), (0, 2), (1, 0)])
    """
    _, u, v, _ = corner_arrays(faces)
    free = ~twinned_sides(faces)
    return _symmetric_adjacency(n, u[free], v[free])


def _symmetric_adjacency(n: int, u: np.ndarray, v: np.ndarray) -> Adjacency:
    """The pairs ``(u, v)`` and ``(v, u)``, each once, sorted."""
    keys = distinct(np.concatenate([np.asarray(u, dtype=np.int64) * n + v, np.asarray(v, dtype=np.int64) * n + u]))
    return Adjacency(n, keys // max(n, 1), keys % max(n, 1))


def face_areas(xy: np.ndarray, faces: Sequence[Sequence[int]]) -> np.ndarray:
    """Signed area of every face (shoelace over its corners): positive for counter-clockwise faces.

    Vectorised over all corners at once (no loop over faces); ``xy`` may be ``(n, 2)`` or ``(n, 3)``
    (z is ignored).

    Example
    -------
    >>> v, f = grid_mesh(2, spacing=2.0)
    >>> face_areas(v, [f[0], f[1][::-1]]).tolist()
    [4.0, -4.0]
    """
    face, u, v, _ = corner_arrays(faces)
    return shoelace_areas(xy, face, u, v, len(faces))


def shoelace_areas(xy: np.ndarray, face: np.ndarray, u: np.ndarray, v: np.ndarray, n_faces: int) -> np.ndarray:
    """:func:`face_areas` of faces given by corner arrays (corner ``k``: side ``u[k] -> v[k]`` of face
    ``face[k]``), for a step that holds a mesh's corners and not its faces as tuples.

    >>> shoelace_areas(np.array([[0.0, 0], [2, 0], [0, 1]]), np.zeros(3, int), np.arange(3), np.array([1, 2, 0]), 1)
    array([1.])
    """
    xy = np.asarray(xy)
    x, y = np.ascontiguousarray(xy[:, 0]), np.ascontiguousarray(xy[:, 1])   # one gather per coordinate
    cross = x[u] * y[v]
    cross -= x[v] * y[u]
    return 0.5 * np.bincount(face, weights=cross, minlength=n_faces)


def boundary_halfedges(faces: Sequence[Sequence[int]]) -> tuple[np.ndarray, np.ndarray]:
    """The halfedges ``u -> v`` of ``faces`` that have no twin ``v -> u``, in corner order.

    For counter-clockwise faces the mesh lies to their left: the outer boundary runs
    counter-clockwise, holes clockwise (as in :func:`boundary_loops`).

    Example
    -------
    >>> u, v = boundary_halfedges([(0, 1, 2), (0, 2, 3)])
    >>> list(zip(u.tolist(), v.tolist()))
    [(0, 1), (1, 2), (2, 3), (3, 0)]
    """
    _, u, v, _ = corner_arrays(faces)
    free = ~twinned_sides(faces)
    return u[free], v[free]
