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

__all__ = ["Strip", "quad_strips"]


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


def _walk(me: MeshEdges, link: np.ndarray, start: int, entry: int, seen: np.ndarray) -> Strip:
    """Follow a strip from node ``start``, entered through its side ``entry`` (0 or 1)."""
    quads, rungs = [], []
    node, j = start, entry
    while True:
        q, d = divmod(node, 2)
        seen[node] = True
        sides = me.face_edges(q)
        quads.append(q)
        rungs.append(int(sides[d + 2 * j]))
        nxt = int(link[node, 1 - j])
        if nxt < 0 or nxt == start:
            rungs.append(int(sides[d + 2 * (1 - j)]))
            return Strip(np.array(quads, dtype=np.int64), np.array(rungs, dtype=np.int64), nxt == start)
        j = int(np.flatnonzero(link[nxt] == node)[0]) if link[nxt, 0] != link[nxt, 1] else \
            _entry_side(me, nxt, int(sides[d + 2 * (1 - j)]))
        node = nxt


def _entry_side(me: MeshEdges, node: int, edge: int) -> int:
    """Which side (0 or 1) of strip node ``node`` is ``edge`` (when both sides lead to one neighbour)."""
    q, d = divmod(node, 2)
    return 0 if int(me.face_edges(q)[d]) == edge else 1


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
    is_quad = np.array([len(f) == 4 for f in faces], dtype=bool)
    link = _strip_links(me, is_quad)
    seen = ~np.repeat(is_quad, 2)
    strips = []
    for node in np.flatnonzero(~seen & (link < 0).any(axis=1)).tolist():  # open strips, from an end
        if not seen[node]:
            strips.append(_walk(me, link, node, int(np.flatnonzero(link[node] < 0)[0]), seen))
    for node in np.flatnonzero(~seen).tolist():  # what is left closes on itself
        if not seen[node]:
            strips.append(_walk(me, link, node, 0, seen))
    return strips
