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
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import breadth_first_order

from vaultgram.geometry.arrays import run_starts
from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.geometry.meshes import Faces, corner_arrays, has_side_in, with_midpoints
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
    k, best = np.array(_halving_edges(me, removed, group, area, size, size > UPPER * target), dtype=np.int64
                       ).reshape(-1, 2).T
    ends = me.edges[best]
    # an edge whose ends no other edge here has sees the counts as they were, whatever comes first
    alone = (np.bincount(ends.ravel(), minlength=n_vertices)[ends] == 1).all(axis=1)
    back = alone & ~((inner[ends] & (count[ends] >= 3)).any(axis=1) & (size[k] <= OVERSIZED * target))
    removed[best[back]] = False
    count[ends[back]] += 1
    restored = int(back.sum())
    for i in np.flatnonzero(~alone).tolist():  # the others in order, each seeing the counts the ones before left
        if (inner[ends[i]] & (count[ends[i]] >= 3)).any() and size[k[i]] <= OVERSIZED * target:
            continue
        removed[best[i]] = False
        count[ends[i]] += 1
        restored += 1
    return removed, restored


def _halving_edges(me: MeshEdges, removed: np.ndarray, group: np.ndarray, area: np.ndarray, size: np.ndarray,
                   large: np.ndarray) -> list[tuple[int, int]]:
    """``(voussoir, edge)`` for every ``large`` voussoir of several faces: the removed edge inside it
    that splits it most evenly (the smallest edge among equals). The faces and removed edges of a
    voussoir mostly form a tree: one side of an edge is then the subtree below it, summed for all
    edges at once; a voussoir whose removed edges close a cycle is walked edge by edge."""
    inside = removed & ~me.boundary
    links = np.flatnonzero(inside & large[group[np.maximum(me.faces_of[:, 0], 0)]])
    a, b = me.faces_of[links].T
    g = group[a]
    faces = np.flatnonzero(large[group])
    n_links = np.bincount(g, minlength=len(size))
    tree = n_links == np.bincount(group[faces], minlength=len(size)) - 1
    below, parent = _subtree_areas(a, b, group, area, faces)
    gap = np.abs(size[g] - 2 * below[np.where(parent[a] == b, a, b)])  # below the end further from the root
    order = np.lexsort((links, gap, g))
    order = order[tree[g[order]]]
    first = order[run_starts(g[order])]
    found = dict(zip(g[first].tolist(), links[first].tolist()))
    for k in np.flatnonzero(large & ~tree & (n_links > 0)).tolist():
        mine = links[g == k]
        found[k] = min(mine.tolist(), key=lambda e: (abs(size[k] - 2 * _side_area(me, mine, area, e)), e))
    return sorted(found.items())


def _subtree_areas(a: np.ndarray, b: np.ndarray, group: np.ndarray, area: np.ndarray, faces: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The trees of ``faces`` joined by the pairs ``a[i]``-``b[i]``, each voussoir's rooted at its
    first face: per face, the area of its subtree (0 outside the trees) and its parent (-1 at a root
    and outside)."""
    n = len(area)
    by_group = faces[np.argsort(group[faces], kind="stable")]
    roots = by_group[run_starts(group[by_group])]
    top = n  # one node above every root, so that one search roots them all
    pairs = (np.concatenate([a, np.full(len(roots), top)]), np.concatenate([b, roots]))
    graph = coo_matrix((np.ones(len(pairs[0])), pairs), shape=(n + 1, n + 1))
    _, parent = breadth_first_order(graph, top, directed=False, return_predecessors=True)
    parent = parent[:n]
    parent[(parent < 0) | (parent == top)] = -1
    depth = np.zeros(n, dtype=np.int64)
    up = parent.copy()
    while (up >= 0).any():
        depth += up >= 0
        up = np.where(up >= 0, parent[np.maximum(up, 0)], -1)
    below = np.zeros(n)
    below[faces] = area[faces]
    for level in range(int(depth.max()) if n else 0, 0, -1):  # leaves first
        at = np.flatnonzero(depth == level)
        np.add.at(below, parent[at], below[at])
    return below, parent


def _side_area(me: MeshEdges, inside: np.ndarray, area: np.ndarray, e: int) -> float:
    """Area of the faces on one side of the removed edge ``e`` of a voussoir whose removed edges are
    ``inside`` (the faces reached from one of its faces without crossing ``e``)."""
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
    sides = np.bincount(corner_arrays(faces)[0], minlength=len(faces))
    cut = np.flatnonzero(alone & (sides == 4) & (size[group] > UPPER * target)).tolist()
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
    out, origin = list(faces), list(range(len(faces)))
    for f in cut:
        out[f], half = _halves(list(faces[f]), _split_sides(x, faces[f]), midpoint)
        out.append(half)
        origin.append(f)
    touched = has_side_in(faces, midpoint, len(x))[origin].tolist()  # a cut quad's halves: always
    out = [with_midpoints(f, midpoint) if t else tuple(f) for f, t in zip(out, touched)]
    group = np.concatenate([group, int(group.max()) + 1 + np.arange(len(cut))])  # a new voussoir per second half
    halved = np.array(sorted(midpoint, key=midpoint.get), dtype=np.int64).reshape(-1, 2)
    return np.vstack([x, new_points]), Faces(out), group.astype(np.int64), halved, len(cut)


def _halves(q: list, sides: tuple[int, int], midpoint: dict) -> tuple[list, list]:
    """The two quads of quad ``q`` cut between the midpoints of its sides ``sides``."""
    s, t = sides
    m = midpoint[(min(q[s], q[s + 1]), max(q[s], q[s + 1]))]
    n = midpoint[(min(q[t], q[(t + 1) % 4]), max(q[t], q[(t + 1) % 4]))]
    rot = q[s + 1:] + q[:s + 1]  # starts after side s: rot[0] = q[s + 1], ..., rot[3] = q[s]
    return [m, rot[0], rot[1], n], [n, rot[2], rot[3], m]
