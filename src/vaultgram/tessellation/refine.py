"""Refining the strips of large faces before the bond (paper §5: "shape and size uniformity").

The bond can join small faces into longer voussoirs, but not make a voussoir smaller than a face.
Where faces are much larger than the typical one (in the corners of large patches, where the vault is
steep), their strips are refined first: every quad of such a strip is cut in two between the
midpoints of its rungs, so the strip becomes two. The mesh stays a conforming quad mesh (the
midpoints of a strip's end rungs are added to the boundary or to the face beyond); a quad on two
refined strips is cut in four. The strip chosen through a large quad is the one whose rungs are the
quad's longer sides, so the halves are squarer than the quad. Passes repeat until no quad is more
than :data:`LARGE` times the median quad of the unrefined mesh, or for :data:`PASSES` passes.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.arrays import lookup, ranges, sorted_keys
from vaultgram.geometry.halfedges import MeshEdges, corner_edges
from vaultgram.geometry.meshes import Faces, corner_arrays, corners_of_flat
from vaultgram.geometry.surfaces import surface_areas
from vaultgram.tessellation.strips import strip_labels

__all__ = ["refine_large_faces", "LARGE", "PASSES"]

#: Quads more than this many times the median quad's area get their strip refined.
LARGE = 2.0
#: At most this many refinement passes.
PASSES = 3

#: Per kind of cut (1: direction 0, sides 0 and 2 halved; 2: direction 1, sides 1 and 3; 3: both), the
#: quads a cut quad becomes, as columns of its row ``a, b, c, d, m0, m1, m2, m3, centre`` (``mk`` the
#: midpoint of side ``k``); rows past its pieces are -1.
PIECES = np.array([[[-1] * 4] * 4,
                   [[0, 4, 6, 3], [4, 1, 2, 6], [-1] * 4, [-1] * 4],
                   [[0, 1, 5, 7], [7, 5, 2, 3], [-1] * 4, [-1] * 4],
                   [[0, 4, 8, 7], [4, 1, 5, 8], [8, 5, 2, 6], [7, 8, 6, 3]]])
#: Per kind of cut, the sides it halves.
HALVED = np.array([[0, 0, 0, 0], [1, 0, 1, 0], [0, 1, 0, 1], [1, 1, 1, 1]], dtype=bool)


def _nodes_to_refine(x: np.ndarray, me: MeshEdges, big: np.ndarray) -> tuple[np.ndarray, int]:
    """The strip nodes ``2 * quad + direction`` of the strips through the longer sides of every quad in
    ``big`` (the quads too large), and how many strips those are."""
    corners = me.face_start[big][:, None] + np.arange(4)
    length = np.linalg.norm(x[me.corner_next[corners]] - x[me.corner_vertex[corners]], axis=2)
    d = np.where(length[:, 0] + length[:, 2] >= length[:, 1] + length[:, 3], 0, 1)
    label = strip_labels(me)
    chosen = np.zeros(int(label.max()) + 1, dtype=bool)
    chosen[label[2 * big + d]] = True
    return np.flatnonzero(chosen[label] & (label >= 0)), int(np.count_nonzero(chosen))


def _new_vertices(x: np.ndarray, quad: np.ndarray, kind: np.ndarray) -> tuple[np.ndarray, np.ndarray, list]:
    """The vertices that cutting the quads ``quad`` (rows ``a, b, c, d``) by ``kind`` adds, numbered
    from ``len(x)`` in the order the quads make them: quad by quad, its centre if it is cut both ways,
    then the midpoints of its halved sides in side order, a side's midpoint made once, by the first
    quad that halves it. Returns their points, each quad's row ``a, b, c, d, m0, m1, m2, m3, centre``
    (-1 where it has none) and, per new vertex, the vertices it is the mean of."""
    n, m = len(x), len(quad)
    nxt = np.roll(quad, -1, axis=1)
    lo, hi = np.minimum(quad, nxt), np.maximum(quad, nxt)
    want = np.column_stack([kind == 3, HALVED[kind]])  # per quad: its centre, then its sides' midpoints
    key = np.column_stack([-1 - np.arange(m), lo * n + hi])  # a centre is its quad's alone
    q, slot = np.nonzero(want)  # row by row: the order the vertices are asked for
    _, first, which = np.unique(key[q, slot], return_index=True, return_inverse=True)
    made = np.zeros(len(q), dtype=bool)
    made[first] = True
    ids = np.full((m, 5), -1, dtype=np.int64)
    ids[q, slot] = (n + np.cumsum(made) - 1)[first[which.ravel()]]
    q, side = q[made], slot[made] - 1
    centre = side < 0
    points = np.empty((len(q), x.shape[1]))
    points[centre] = x[quad[q[centre]]].mean(axis=1)
    points[~centre] = 0.5 * (x[quad[q, side][~centre]] + x[nxt[q, side][~centre]])
    ends = np.where(centre[:, None], quad[q], np.column_stack([lo[q, side], hi[q, side]] * 2))
    parents = [p if c else p[:2] for p, c in zip(map(tuple, ends.tolist()), centre.tolist())]
    return points, np.column_stack([quad, ids[:, 1:], ids[:, 0]]), parents


def _refined(x: np.ndarray, me: MeshEdges, cut: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray, list, np.ndarray, np.ndarray]:
    """The mesh of ``me`` with the quads cut (``cut[f, d]``: quad ``f`` is cut in direction ``d``):
    vertices, faces (their corners end to end and their sizes), for each new vertex the vertices it is
    the mean of, for each face the face it was cut from, and which faces are new or changed (cut, or
    given a midpoint: the others are their origin's face as it was). All at once on the corner arrays:
    each cut quad's pieces take its place, and each other face across a halved side (a strip's end)
    gets the midpoint inserted."""
    quads = np.flatnonzero(cut.any(axis=1))
    kind = cut[quads, 0] + 2 * cut[quads, 1]
    corners = me.face_start[quads][:, None] + np.arange(4)
    points, row, parents = _new_vertices(x, me.corner_vertex[corners], kind)
    halved = row[:, 4:8] >= 0
    across = me.corner_twin[corners[halved]]
    touched = np.zeros(len(cut), dtype=bool)
    touched[me.corner_face[across[across >= 0]]] = True
    beside = np.flatnonzero(touched & ~cut.any(axis=1))
    touched[quads] = True
    sides = np.column_stack([row[:, :4][halved], np.roll(row[:, :4], -1, axis=1)[halved]])
    member, corner = ranges(me.face_start[beside], np.diff(me.face_start)[beside])
    inserted = _midpoints_inserted(member, me.corner_vertex[corner], me.corner_next[corner], np.sort(sides, axis=1),
                                   row[:, 4:8][halved], len(x) + len(points))
    template = PIECES[kind]
    pieces = row[np.arange(len(quads))[:, None, None], template][template[:, :, 0] >= 0]
    counts = np.ones(len(cut), dtype=np.int64)
    counts[quads] = 2 + 2 * (kind == 3)
    origin = np.repeat(np.arange(len(cut)), counts)
    flat, sizes = _assembled(me, beside, inserted, quads, pieces, counts)
    return np.vstack([x, points]), flat, sizes, parents, origin, touched[origin]


def _assembled(me: MeshEdges, beside: np.ndarray, inserted: tuple[np.ndarray, np.ndarray], quads: np.ndarray,
               pieces: np.ndarray, counts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The refined faces in order, their corners end to end and their sizes: each face of ``me`` as it
    was, or with midpoints inserted (the faces ``beside``: ``inserted`` their corners end to end and
    sizes), or the ``counts`` quads ``pieces`` it is cut into (the ``quads``); the corners gathered
    from the three by runs, not face by face."""
    flat, sizes = inserted
    size = np.diff(me.face_start)
    at = me.face_start[:-1].copy()  # where each face's corners start, in the three end to end
    at[beside] = len(me.corner_vertex) + np.cumsum(sizes) - sizes
    size[beside] = sizes
    at[quads] = len(me.corner_vertex) + len(flat) + 4 * (np.cumsum(counts[quads]) - counts[quads])
    size[quads] = 4 * counts[quads]
    corners = np.concatenate([me.corner_vertex, flat, pieces.ravel()])[ranges(at, size)[1]]
    size[quads] = 4
    return corners, np.repeat(size, counts)


def _midpoints_inserted(face: np.ndarray, u: np.ndarray, v: np.ndarray, sides: np.ndarray, mids: np.ndarray,
                        n: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`~vaultgram.geometry.meshes.with_midpoints` of every face at once, the faces given by
    their corner arrays (corner ``k`` is the side ``u[k] -> v[k]`` of face ``face[k]``, the faces
    numbered from 0 in order; vertex ids below ``n``), ``sides`` the cut sides ``(lo, hi)`` and
    ``mids`` their midpoints: the corners end to end and the sizes, each corner's vertex, then the
    midpoint of the side it starts if that side was cut and the midpoint is not in the face already.
    One sorted search over the corners, not a walk per face."""
    keys = sides[:, 0] * n + sides[:, 1]
    order = np.argsort(keys)
    keys, mids = keys[order], mids[order]
    at, cut = lookup(keys, np.minimum(u, v) * n + np.maximum(u, v))
    m = mids[at] if len(mids) else at
    cut &= ~lookup(sorted_keys(face * n + u), face * n + m)[1]  # the midpoint is a corner already
    size = 1 + cut
    start = np.cumsum(size) - size
    flat = np.empty(int(size.sum()), dtype=np.int64)
    flat[start] = u
    flat[start[cut] + 1] = m[cut]
    return flat, np.bincount(face, weights=size, minlength=int(face.max()) + 1 if len(face) else 0).astype(np.int64)


def refine_large_faces(x: np.ndarray, faces, large: float = LARGE, passes: int = PASSES
                       ) -> tuple[np.ndarray, tuple, list, np.ndarray, int]:
    """Refine the strips of the quads larger than ``large`` times the median quad (module docstring).

    Returns the vertices, the faces, for every added vertex the vertices it is the mean of, for every
    face the input face it comes from, and the number of strips refined. Between passes the faces are
    their corners end to end and their sizes; they are made :class:`Faces` after the last
    (:func:`_faces_of`).
    """
    faces = faces if isinstance(faces, Faces) else Faces(tuple(f) for f in faces)
    face, flat, _, _ = corner_arrays(faces)
    sizes = np.bincount(face, minlength=len(faces))
    area, quads = surface_areas(x, faces), sizes == 4
    limit = large * float(np.median(area[quads])) if quads.any() else np.inf
    parents: list = []
    refined = 0
    origin = np.arange(len(faces))
    kept = np.ones(len(faces), dtype=bool)  # the face is its origin as it was
    for _ in range(passes):
        big = np.flatnonzero((area > limit) & quads)
        if not len(big):
            break  # (the strips are found only when there is something to refine)
        me = corner_edges(*corners_of_flat(flat, sizes)[:3], sizes, len(x))
        nodes, strips = _nodes_to_refine(x, me, big)
        cut = np.zeros((len(sizes), 2), dtype=bool)
        cut[nodes >> 1, nodes & 1] = True  # node 2 * quad + direction
        x, flat, sizes, new_parents, new_origin, changed = _refined(x, me, cut)
        parents += new_parents
        origin, kept = origin[new_origin], kept[new_origin] & ~changed
        refined += strips
        area, quads = _areas_after(x, flat, sizes, area[new_origin], changed), sizes == 4
    return x, _faces_of(faces, flat, sizes, origin, kept) if refined else faces, parents, origin, refined


def _faces_of(faces: Faces, flat: np.ndarray, sizes: np.ndarray, origin: np.ndarray, kept: np.ndarray) -> Faces:
    """The refined faces (corners ``flat`` end to end, ``sizes``) as :class:`Faces`: a face ``kept`` as
    its origin in ``faces`` was is that very tuple, the others are made from their corners. The input
    mesh's tuples are shared, not made again (at 10^6 faces 0.2 GB more at the peak, and 0.3 s)."""
    out = list(map(faces.__getitem__, origin.tolist()))
    redo = np.flatnonzero(~kept)
    _, at = ranges((np.cumsum(sizes) - sizes)[redo], sizes[redo])
    for k, face in zip(redo.tolist(), Faces.from_flat(flat[at], sizes[redo])):
        out[k] = face
    return Faces.from_flat(flat, sizes, out)


def _areas_after(x: np.ndarray, flat: np.ndarray, sizes: np.ndarray, before: np.ndarray, changed: np.ndarray
                 ) -> np.ndarray:
    """The area of every face of a refined mesh (corners ``flat`` end to end, ``sizes``), given the area
    ``before`` of each face's origin: a face that did not change keeps it (an area is its own corners'
    sum, the same bits in any mesh), the ``changed`` ones are measured (measuring every face again took
    up to a second per pass at 10^6 faces, where a pass changes a fifth of them)."""
    area = before.copy()
    redo = np.flatnonzero(changed)
    _, at = ranges((np.cumsum(sizes) - sizes)[redo], sizes[redo])
    area[redo] = surface_areas(x, Faces.from_flat(flat[at], sizes[redo]))
    return area
