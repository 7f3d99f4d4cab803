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

from vaultgram.geometry.arrays import lookup, sorted_keys
from vaultgram.geometry.halfedges import MeshEdges, mesh_edges
from vaultgram.geometry.meshes import Faces, corner_arrays, has_side_in
from vaultgram.geometry.surfaces import surface_areas
from vaultgram.tessellation.strips import Strip, node_strips, quad_strips, strip_directions

__all__ = ["refine_large_faces", "LARGE", "PASSES"]

#: Quads more than this many times the median quad's area get their strip refined.
LARGE = 2.0
#: At most this many refinement passes.
PASSES = 3


def _strips_to_refine(x: np.ndarray, me: MeshEdges, strips: list[Strip], big: np.ndarray) -> set[int]:
    """The strips through the longer sides of every quad in ``big`` (the quads too large)."""
    corners = me.face_start[big][:, None] + np.arange(4)
    length = np.linalg.norm(x[me.corner_next[corners]] - x[me.corner_vertex[corners]], axis=2)
    d = np.where(length[:, 0] + length[:, 2] >= length[:, 1] + length[:, 3], 0, 1)
    strip = node_strips(me, strips)[2 * big + d]
    return set(strip[strip >= 0].tolist())


def _cut_directions(faces, me: MeshEdges, strips: list[Strip], chosen: set[int]) -> dict[int, set[int]]:
    """Per quad, the directions (0: sides 0 and 2 halved, 1: sides 1 and 3) in which it is cut."""
    cuts: dict[int, set[int]] = {}
    for k in sorted(chosen):
        s = strips[k]
        for q, d in zip(s.quads.tolist(), strip_directions(me, s).tolist()):
            cuts.setdefault(q, set()).add(d)
    return cuts


def _cut_quad(q: list, directions: set[int], mid, centre: int) -> list[list[int]]:
    """The quads of quad ``q`` cut in ``directions`` (midpoint ids from ``mid(a, b)``)."""
    a, b, c, d = q
    sides = {0, 2} if directions == {0} else {1, 3} if directions == {1} else {0, 1, 2, 3}
    m = {k: mid(q[k], q[(k + 1) % 4]) for k in sorted(sides)}
    if directions == {0}:
        return [[a, m[0], m[2], d], [m[0], b, c, m[2]]]
    if directions == {1}:
        return [[a, b, m[1], m[3]], [m[3], m[1], c, d]]
    return [[a, m[0], centre, m[3]], [m[0], b, m[1], centre], [centre, m[1], c, m[2]], [m[3], centre, m[2], d]]


def _refined(x: np.ndarray, faces, cuts: dict[int, set[int]]) -> tuple[np.ndarray, list, list, np.ndarray,
                                                                     np.ndarray]:
    """The mesh with the quads cut: vertices, faces, for each new vertex the vertices it is the mean
    of, for each face the face it was cut from, and which faces are new or changed (cut, or given a
    midpoint: the others are their origin's face as it was). Only the cut quads are visited one by
    one; the other faces are copied in runs, and a face gets the midpoints of its sides inserted only
    if one of its sides was cut (:func:`~vaultgram.geometry.meshes.has_side_in`)."""
    points, parents, index = [], [], {}

    def mid(a: int, b: int) -> int:
        key = (min(a, b), max(a, b))
        if key not in index:
            index[key] = len(x) + len(points)
            points.append(0.5 * (x[a] + x[b]))
            parents.append(key)
        return index[key]

    out, counts, done = [], np.ones(len(faces), dtype=np.int64), 0
    for f in sorted(cuts):
        out.extend(faces[done:f])
        face, directions = list(faces[f]), cuts[f]
        centre = -1
        if len(directions) == 2:
            centre = len(x) + len(points)
            points.append(x[face].mean(axis=0))
            parents.append(tuple(face))
        pieces = _cut_quad(face, directions, mid, centre)
        out.extend(pieces)
        counts[f], done = len(pieces), f + 1
    out.extend(faces[done:])
    origin = np.repeat(np.arange(len(faces)), counts)
    touched = has_side_in(faces, index, len(x))[origin]
    out = [tuple(f) for f in out]
    redo = np.flatnonzero(touched).tolist()
    for k, face in zip(redo, _midpoints_inserted([out[k] for k in redo], index, len(x) + len(points))):
        out[k] = face
    return np.vstack([x, *points]) if points else x, out, parents, origin, touched | (counts > 1)[origin]


def _midpoints_inserted(faces: list, midpoint: dict, n: int) -> Faces:
    """:func:`~vaultgram.geometry.meshes.with_midpoints` of every face at once (vertex ids below
    ``n``): each corner's vertex, then the midpoint of the side it starts if that side was cut and
    the midpoint is not in the face already. One sorted search over the corners instead of a walk
    per face in Python (0.8 s for the 177,000 faces beside the cuts at 10^6 faces)."""
    face, u, v, _ = corner_arrays(faces)
    sides = np.array(list(midpoint), dtype=np.int64).reshape(-1, 2)
    keys = sides[:, 0] * n + sides[:, 1]
    order = np.argsort(keys)
    keys, mids = keys[order], np.fromiter(midpoint.values(), dtype=np.int64, count=len(midpoint))[order]
    at, cut = lookup(keys, np.minimum(u, v) * n + np.maximum(u, v))
    m = mids[at] if len(mids) else at
    cut &= ~lookup(sorted_keys(face * n + u), face * n + m)[1]  # the midpoint is a corner already
    size = 1 + cut
    start = np.cumsum(size) - size
    flat = np.empty(int(size.sum()), dtype=np.int64)
    flat[start] = u
    flat[start[cut] + 1] = m[cut]
    return Faces.from_flat(flat, np.bincount(face, weights=size, minlength=len(faces)).astype(np.int64))


def refine_large_faces(x: np.ndarray, faces, large: float = LARGE, passes: int = PASSES
                       ) -> tuple[np.ndarray, tuple, list, np.ndarray, int]:
    """Refine the strips of the quads larger than ``large`` times the median quad (module docstring).

    Returns the vertices, the faces, for every added vertex the vertices it is the mean of, for every
    face the input face it comes from, and the number of strips refined.
    """
    faces = faces if isinstance(faces, Faces) else Faces(tuple(f) for f in faces)
    area, quads = surface_areas(x, faces), _quads(faces)
    limit = large * float(np.median(area[quads])) if quads.any() else np.inf
    parents: list = []
    refined = 0
    origin = np.arange(len(faces))
    for _ in range(passes):
        big = np.flatnonzero((area > limit) & quads)
        if not len(big):
            break  # (the strips are walked only when there is something to refine)
        me = mesh_edges(faces, len(x))
        strips = quad_strips(me, faces)
        chosen = _strips_to_refine(x, me, strips, big)
        x, new_faces, new_parents, new_origin, changed = _refined(x, faces, _cut_directions(faces, me, strips, chosen))
        faces = Faces(new_faces)
        parents += new_parents
        origin = origin[new_origin]
        refined += len(chosen)
        area, quads = _areas_after(x, faces, area[new_origin], changed), _quads(faces)
    return x, faces, parents, origin, refined


def _quads(faces: Faces) -> np.ndarray:
    """Which faces are quads."""
    return np.bincount(corner_arrays(faces)[0], minlength=len(faces)) == 4


def _areas_after(x: np.ndarray, faces: Faces, before: np.ndarray, changed: np.ndarray) -> np.ndarray:
    """The area of every face of a refined mesh, given the area ``before`` of each face's origin: a
    face that did not change keeps it (an area is its own corners' sum, the same bits in any mesh),
    the ``changed`` ones are measured (measuring every face again took up to a second per pass at
    10^6 faces, where a pass changes a fifth of them)."""
    area = before.copy()
    redo = np.flatnonzero(changed)
    area[redo] = surface_areas(x, [faces[f] for f in redo.tolist()])
    return area
