"""Strips of quads: the rows along which voussoirs are laid (paper §5, Figure 11a).

A *strip* is a chain of quads, each joined to the next across opposite sides; those sides are the
strip's *rungs*. Every quad lies on two strips, one per pair of opposite sides (its *directions* 0
and 1: sides 0 and 2, sides 1 and 3), and every edge between two quads is a rung of exactly one
strip. Strips end at the boundary and at faces that are not quads (triangles at poles, the pentagons
around keystones); a strip that closes on itself (a ring around an opening) is *cyclic*. The
staggered bond removes rungs of some strips (:mod:`vaultgram.tessellation.stagger`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vaultgram.geometry.halfedges import MeshEdges

__all__ = ["Strip", "quad_strips", "strip_directions", "node_strips"]


@dataclass(frozen=True, eq=False)
class Strip:
    """A chain of quads and its rungs.

    Attributes
    ----------
    quads : ndarray (k,)
        Face indices in order along the strip.
    rungs : ndarray (k + 1,)
        ``rungs[i]`` is the edge through which ``quads[i]`` is entered and ``rungs[i + 1]`` the edge
        through which it is left, so ``rungs[1:k]`` join consecutive quads; for a cyclic strip
        ``rungs[k] == rungs[0]`` joins the last quad to the first.
    cyclic : bool
    """

    quads: np.ndarray
    rungs: np.ndarray
    cyclic: bool

    def __len__(self) -> int:
        return len(self.quads)


def _strip_links(me: MeshEdges, is_quad: np.ndarray) -> np.ndarray:
    """``link[2 * quad + direction, j]``: the strip node across the quad's side ``direction + 2 j``
    (-1 where that side is on the boundary or borders a face that is not a quad)."""
    in_quad = is_quad[me.corner_face]
    node = 2 * me.corner_face + me.corner_side % 2
    twin = me.corner_twin
    across = np.where((twin >= 0) & in_quad & in_quad[np.maximum(twin, 0)], node[np.maximum(twin, 0)], -1)
    link = np.full((2 * len(is_quad), 2), -1, dtype=np.int64)
    c = np.flatnonzero(in_quad)
    link[node[c], me.corner_side[c] // 2] = across[c]
    return link


def _walk(link: list, rungs: list, start: int, entry: int, seen: list) -> Strip:
    """Follow a strip from node ``start``, entered through its side ``entry`` (0 or 1); ``link[2 n + j]``
    and ``rungs[2 n + j]`` are the node and the edge across side ``j`` of node ``n`` (flat plain
    lists: the walk is scalar)."""
    quads, path = [], []
    node, j = start, entry
    while True:
        seen[node] = True
        quads.append(node >> 1)
        path.append(rungs[2 * node + j])
        nxt, exit_edge = link[2 * node + 1 - j], rungs[2 * node + 1 - j]
        if nxt < 0 or nxt == start:
            path.append(exit_edge)
            return Strip(np.array(quads, dtype=np.int64), np.array(path, dtype=np.int64), nxt == start)
        j = 0 if rungs[2 * nxt] == exit_edge else 1  # the side of the next quad we enter through
        node = nxt


def quad_strips(me: MeshEdges, faces) -> list[Strip]:
    """Every strip of the quads of a polygon mesh, each walked from one end (a cyclic one from its
    smallest node), in a deterministic order.

    >>> from vaultgram.geometry.halfedges import mesh_edges
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> _, f = grid_mesh(3, 2)
    >>> strips = quad_strips(mesh_edges(f), f)
    >>> sorted(len(s) for s in strips), sum(len(s.rungs) - 1 for s in strips) == 2 * len(f)
    ([2, 2, 2, 3, 3], True)
    """
    is_quad = np.diff(me.face_start) == 4
    link = _strip_links(me, is_quad)
    rungs = _strip_rungs(me, is_quad)
    seen = (~np.repeat(is_quad, 2)).tolist()
    ends = np.flatnonzero(np.repeat(is_quad, 2) & (link < 0).any(axis=1)).tolist()
    link_list, rung_list = link.ravel().tolist(), rungs.ravel().tolist()
    strips = []
    for node in ends:  # open strips, from an end
        if not seen[node]:
            strips.append(_walk(link_list, rung_list, node, 0 if link_list[2 * node] < 0 else 1, seen))
    for node in range(len(seen)):  # what is left closes on itself
        if not seen[node]:
            strips.append(_walk(link_list, rung_list, node, 0, seen))
    return strips


def _strip_rungs(me: MeshEdges, is_quad: np.ndarray) -> np.ndarray:
    """``rungs[2 * quad + direction, j]``: the edge of the quad's side ``direction + 2 j``."""
    out = np.full((2 * len(is_quad), 2), -1, dtype=np.int64)
    c = np.flatnonzero(is_quad[me.corner_face])
    side = me.corner_side[c]
    out[2 * me.corner_face[c] + side % 2, side // 2] = me.corner_edge[c]
    return out


def strip_directions(me: MeshEdges, s: Strip) -> np.ndarray:
    """For each quad of a strip, its direction there (0: sides 0 and 2 are the rungs, 1: sides 1, 3)."""
    start = me.face_start[s.quads]
    even = (me.corner_edge[start] == s.rungs[:-1]) | (me.corner_edge[start + 2] == s.rungs[:-1])
    return np.where(even, 0, 1)


def node_strips(me: MeshEdges, strips: list[Strip]) -> np.ndarray:
    """Per strip node ``2 * quad + direction``, the strip through it (-1 for faces that are not quads)."""
    out = np.full(2 * (len(me.face_start) - 1), -1, dtype=np.int64)
    for k, s in enumerate(strips):
        out[2 * s.quads + strip_directions(me, s)] = k
    return out
