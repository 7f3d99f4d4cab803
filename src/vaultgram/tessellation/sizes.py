"""Even voussoir sizes: breaking up the voussoirs the bond left too large (paper §5).

"Regarding fabrication, shape and size uniformity between the voussoirs is preferred. However, high
differences can occur in areas with important slope." (§5) The bond aims at a target area
(:mod:`vaultgram.tessellation.stagger`), but a voussoir cannot be smaller than its largest face, and
runs of large faces may overshoot. A voussoir more than :data:`UPPER` times the target is therefore
broken up, in this order:

* a voussoir of several faces gets back the removed edge that splits it most evenly, unless that
  would make a point of four voussoirs at either end of the edge and the voussoir is less than
  :data:`OVERSIZED` times the target (such points are mended afterwards,
  :mod:`vaultgram.tessellation.mending`);
* a voussoir of one quad is cut in two by the segment between the midpoints of its two longer
  opposite sides. The midpoints become vertices of the faces beside those sides too, so each is a
  point of exactly three voussoirs (the two halves and the neighbour) and no joint crosses another.
"""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.geometry.meshes import Faces, with_midpoints
from vaultgram.geometry.surfaces import surface_areas
from vaultgram.tessellation.voussoirs import face_groups, voussoirs_at_vertices

__all__ = ["unmerge_large", "split_large_quads", "UPPER"]

#: A voussoir more than this many times the target area is broken up.
UPPER = 1.5
#: A voussoir more than this many times the target gets its edge back even where that makes a point
#: of four voussoirs (:mod:`vaultgram.tessellation.mending` mends most of them afterwards).
OVERSIZED = 2.5


def unmerge_large(me: MeshEdges, removed: np.ndarray, inner: np.ndarray, area: np.ndarray, target: float,
                  n_vertices: int) -> tuple[np.ndarray, int]:
    """Give the voussoirs larger than ``UPPER * target`` (faces of ``area``) back the removed edge
    that halves them best, where no point of four voussoirs results; returns the removed edges and how
    many came back."""
    removed = removed.copy()
    group = face_groups(me, removed)
    size = np.bincount(group, weights=area)
    if not (size > UPPER * target).any():
        return removed, 0
    count = voussoirs_at_vertices(me, group, n_vertices)
    links = np.flatnonzero(removed)
    owner = group[me.faces_of[links, 0]]
    order = np.argsort(owner, kind="stable")
    links, owner = links[order], owner[order]
    start = np.searchsorted(owner, np.arange(len(size) + 1))
    restored = 0
    for k in np.flatnonzero(size > UPPER * target).tolist():
        inside = links[start[k]:start[k + 1]]
        best = min(inside.tolist(), key=lambda e: (abs(size[k] - 2 * _side_area(me, inside, area, e)), e),
                   default=None)
        if best is None:
            continue
        ends = me.edges[best]
        if (inner[ends] & (count[ends] >= 3)).any() and size[k] <= OVERSIZED * target:
            continue
        removed[best] = False
        count[ends] += 1
        restored += 1
    return removed, restored


def _side_area(me: MeshEdges, inside: np.ndarray, area: np.ndarray, e: int) -> float:
    """Area of the faces on one side of the removed edge ``e`` of a voussoir whose removed edges are
    ``inside`` (the faces and removed edges of a voussoir form a tree)."""
    links = [tuple(p) for p in me.faces_of[inside[inside != e]].tolist()]
    seen, stack = {int(me.faces_of[e, 0])}, [int(me.faces_of[e, 0])]
    while stack:
        f = stack.pop()
        for a, b in links:
            for u, v in ((a, b), (b, a)):
                if u == f and v not in seen:
                    seen.add(v)
                    stack.append(v)
    return float(area[list(seen)].sum())


def _split_sides(x: np.ndarray, face) -> tuple[int, int]:
    """Side indices (0 and 2, or 1 and 3) of the quad's two longer opposite sides."""
    p = x[list(face)]
    length = np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)
    return (0, 2) if length[0] + length[2] >= length[1] + length[3] else (1, 3)


def split_large_quads(x: np.ndarray, faces, group: np.ndarray, target: float
                      ) -> tuple[np.ndarray, tuple, np.ndarray, np.ndarray, int]:
    """Cut every single-quad voussoir larger than ``UPPER * target`` in two (see the module docstring).

    Returns the vertices (midpoints appended), the faces (each cut quad's first half in its place,
    the second halves appended; neighbours with a midpoint inserted), each face's voussoir (a second
    half is a new voussoir), for each new vertex the edge it halves, and the number of cuts.
    """
    area = surface_areas(x, faces)
    size = np.bincount(group, weights=area)
    alone = np.bincount(group)[group] == 1
    cut = [f for f in range(len(faces)) if alone[f] and len(faces[f]) == 4 and size[group[f]] > UPPER * target]
    if not cut:
        return x, Faces(faces), group, np.zeros((0, 2), dtype=np.int64), 0
    midpoint: dict[tuple[int, int], int] = {}
    new_points = []
    for f in cut:
        q = faces[f]
        for s in _split_sides(x, q):
            a, b = q[s], q[(s + 1) % 4]
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                midpoint[key] = len(x) + len(new_points)
                new_points.append(0.5 * (x[a] + x[b]))
    faces = [list(f) for f in faces]
    group = list(group.tolist())
    for f in cut:
        faces[f], half = _halves(faces[f], _split_sides(x, faces[f]), midpoint)
        faces.append(half)
        group.append(max(group) + 1)
    faces = [with_midpoints(f, midpoint) for f in faces]
    halved = np.array(sorted(midpoint, key=midpoint.get), dtype=np.int64).reshape(-1, 2)
    return (np.vstack([x, new_points]), Faces(tuple(f) for f in faces), np.array(group, dtype=np.int64), halved,
            len(cut))


def _halves(q: list, sides: tuple[int, int], midpoint: dict) -> tuple[list, list]:
    """The two quads of quad ``q`` cut between the midpoints of its sides ``sides``."""
    s, t = sides
    m = midpoint[(min(q[s], q[s + 1]), max(q[s], q[s + 1]))]
    n = midpoint[(min(q[t], q[(t + 1) % 4]), max(q[t], q[(t + 1) % 4]))]
    rot = q[s + 1:] + q[:s + 1]  # starts after side s: rot[0] = q[s + 1], ..., rot[3] = q[s]
    return [m, rot[0], rot[1], n], [n, rot[2], rot[3], m]
