"""Small helpers for planar polygonal meshes: regular grids, boundary loops, JSON and OBJ.

A mesh here is plain data: ``vertices`` an ``(n, 2)`` or ``(n, 3)`` float array and ``faces`` a
list of vertex-index sequences, counter-clockwise seen from +z. These helpers feed the form-finding
stage (§5 of the paper: "To convert this mesh into a proper form diagram ...") and its tests and
benchmarks; they know nothing about statics.
"""

from __future__ import annotations

from pathlib import Path
from typing import Iterable, Sequence

import numpy as np

from vaultgram.io.files import write_text

__all__ = [
    "grid_mesh",
    "grid_index",
    "remove_faces",
    "boundary_loops",
    "corner_arrays",
    "write_obj",
]


def grid_index(i: int, j: int, nx: int) -> int:
    """Index of grid vertex ``(i, j)`` (at ``x = i * spacing, y = j * spacing``) in :func:`grid_mesh`."""
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

    Example
    -------
    >>> v, f = grid_mesh(2)
    >>> v.shape, len(f), f[0]
    ((9, 3), 4, (0, 1, 4, 3))
    """
    ny = nx if ny is None else ny
    if nx < 1 or ny < 1:
        raise ValueError(f"grid needs at least one face in each direction, got {nx} x {ny}")
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


def corner_arrays(faces: Sequence[Sequence[int]]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Flatten faces into per-corner arrays ``(face, vertex, next vertex, previous vertex)``.

    Corner ``k`` of face ``f`` has vertex ``faces[f][k]``; the halfedge ``vertex -> next`` belongs to
    ``f`` (``f`` lies on its left for counter-clockwise faces). Vectorised stages use these instead
    of loops over faces.
    """
    if len(faces) == 0:
        e = np.zeros(0, dtype=np.int64)
        return e, e, e, e
    lens = np.fromiter((len(f) for f in faces), dtype=np.int64, count=len(faces))
    vert = np.fromiter((v for f in faces for v in f), dtype=np.int64, count=int(lens.sum()))
    face = np.repeat(np.arange(len(faces)), lens)
    start = np.concatenate([[0], np.cumsum(lens)[:-1]])
    pos = np.arange(len(vert)) - np.repeat(start, lens)
    nxt_pos = np.repeat(start, lens) + (pos + 1) % np.repeat(lens, lens)
    prv_pos = np.repeat(start, lens) + (pos - 1) % np.repeat(lens, lens)
    return face, vert, vert[nxt_pos], vert[prv_pos]


def boundary_loops(faces: Sequence[Sequence[int]]) -> list[list[int]]:
    """The boundary loops of a manifold, consistently oriented mesh.

    Each loop is the list of vertices met along the face halfedges that have no twin, so the outer
    boundary of a counter-clockwise mesh is counter-clockwise and holes are clockwise.

    Raises
    ------
    ValueError
        if a vertex starts two boundary halfedges (a non-manifold "pinched" vertex).
    """
    _, u, v, _ = corner_arrays(faces)
    n = int(max(u.max(), v.max())) + 1 if len(u) else 0
    codes = u * n + v
    twins = np.isin(v * n + u, codes)
    bu, bv = u[~twins], v[~twins]
    nxt: dict[int, int] = {}
    for a, b in zip(bu.tolist(), bv.tolist()):
        if a in nxt:
            raise ValueError(f"vertex {a} starts two boundary halfedges (non-manifold boundary vertex)")
        nxt[a] = b
    loops: list[list[int]] = []
    seen: set[int] = set()
    for a in bu.tolist():
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


def write_obj(path: str | Path, vertices: np.ndarray, faces: Sequence[Sequence[int]],
              edges: Sequence[Sequence[int]] | None = None) -> None:
    """Write a Wavefront OBJ file (1-based indices); ``edges`` become ``l`` lines if given."""
    v = np.asarray(vertices, dtype=float)
    if v.shape[1] == 2:
        v = np.column_stack([v, np.zeros(len(v))])
    lines = ["# vaultgram"]
    lines += [f"v {x:.12g} {y:.12g} {z:.12g}" for x, y, z in v.tolist()]
    lines += ["f " + " ".join(str(int(i) + 1) for i in f) for f in faces]
    if edges is not None:
        lines += [f"l {int(a) + 1} {int(b) + 1}" for a, b in edges]
    write_text(path, "\n".join(lines) + "\n")
