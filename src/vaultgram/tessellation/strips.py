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
import scipy.sparse as sp
from scipy.sparse import csgraph

from vaultgram.geometry.arrays import distinct
from vaultgram.geometry.halfedges import MeshEdges

__all__ = ["Strip", "quad_strips", "strip_directions", "strip_labels"]


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


def _successors(link: np.ndarray, rungs: np.ndarray) -> np.ndarray:
    """``succ[2 * node + j]``: leaving ``node`` through its side ``j``, the next node entered and left
    through its other side, as ``2 * next + side`` (-1 where the strip ends). The side entered is the
    one on the same edge."""
    h = np.flatnonzero(link.ravel() >= 0)
    nxt = link.ravel()[h]
    enter = np.where(rungs[nxt, 0] == rungs.ravel()[h], 0, 1)
    succ = np.full(link.size, -1, dtype=np.int64)
    succ[h] = 2 * nxt + 1 - enter
    return succ


def _starts(link: np.ndarray, is_node: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The half-link each strip is walked from (an open strip from its smallest end, left away from
    the end; a cyclic one from its smallest node, entered through side 0), whether it is cyclic (open
    strips first, each group by its start), and the strip through each node."""
    n = len(link)
    nodes = np.flatnonzero(is_node)
    comp = _components(link)
    end = is_node & (link < 0).any(axis=1)
    first, lowest = np.full(n, n, dtype=np.int64), np.full(n, n, dtype=np.int64)
    np.minimum.at(first, comp[nodes], np.where(end[nodes], nodes, n))  # the smallest end
    np.minimum.at(lowest, comp[nodes], nodes)
    used = distinct(comp[nodes])
    cyclic = first[used] == n
    start = np.where(cyclic, lowest[used], first[used])
    entry = np.where(cyclic | (link[start, 0] < 0), 0, 1)
    order = np.lexsort((start, cyclic))
    strip_of_comp = np.full(n, -1, dtype=np.int64)
    strip_of_comp[used[order]] = np.arange(len(order))
    return (2 * start + 1 - entry)[order], cyclic[order], strip_of_comp[comp]


def _components(link: np.ndarray) -> np.ndarray:
    """Per strip node, its connected component of the links: the nodes of one strip share it."""
    n = len(link)
    a, j = np.nonzero(link >= 0)
    graph = sp.coo_matrix((np.ones(len(a)), (a, link[a, j])), shape=(n, n))
    return csgraph.connected_components(graph, directed=False)[1]


def _walked(succ: np.ndarray, start: np.ndarray) -> np.ndarray:
    """The half-links met walking every strip from its start at once: a breadth-first order from a
    root joined to the starts, in which each strip's half-links come in the strip's order (a cyclic
    strip ends where its start would come round again)."""
    h = np.flatnonzero(succ >= 0)
    root = len(succ)
    rows = np.concatenate([h, np.full(len(start), root)])
    graph = sp.csr_matrix((np.ones(len(rows)), (rows, np.concatenate([succ[h], start]))), shape=(root + 1, root + 1))
    return csgraph.breadth_first_order(graph, root, directed=True, return_predecessors=False)[1:]


def quad_strips(me: MeshEdges, faces) -> list[Strip]:
    """Every strip of the quads of a polygon mesh, each walked from one end (a cyclic one from its
    smallest node), in a deterministic order: open strips by their start, then cyclic ones.

    >>> from vaultgram.geometry.halfedges import mesh_edges
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> _, f = grid_mesh(3, 2)
    >>> strips = quad_strips(mesh_edges(f), f)
    >>> sorted(len(s) for s in strips), sum(len(s.rungs) - 1 for s in strips) == 2 * len(f)
    ([2, 2, 2, 3, 3], True)
    """
    is_quad = np.diff(me.face_start) == 4
    if not is_quad.any():
        return []
    link, rungs = _strip_links(me, is_quad), _strip_rungs(me, is_quad)
    start, cyclic, strip_of_node = _starts(link, np.repeat(is_quad, 2))
    h = _walked(_successors(link, rungs), start)
    h = h[np.argsort(strip_of_node[h >> 1], kind="stable")]  # strip by strip, each in its own order
    bounds = np.searchsorted(strip_of_node[h >> 1], np.arange(len(start) + 1)).tolist()
    flat = rungs.ravel()
    entered = flat[h ^ 1]
    return [Strip(h[lo:hi] >> 2, np.append(entered[lo:hi], flat[h[hi - 1]]), c)
            for lo, hi, c in zip(bounds[:-1], bounds[1:], cyclic.tolist())]


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


def strip_labels(me: MeshEdges) -> np.ndarray:
    """Per strip node ``2 * quad + direction``, a label the nodes of its strip share (-1 for faces that
    are not quads): the strips as sets of nodes, for a step that asks only which quads a strip holds,
    without walking every strip in order (:func:`quad_strips`; half the time at 10^6 faces).

    >>> from vaultgram.geometry.halfedges import mesh_edges
    >>> strip_labels(mesh_edges([(0, 1, 4, 3), (1, 2, 5, 4), (2, 6, 5)])).tolist()  # two columns, a row
    [0, 1, 2, 1, -1, -1]
    """
    is_quad = np.diff(me.face_start) == 4
    if not is_quad.any():
        return np.full(2 * len(is_quad), -1, dtype=np.int64)
    return np.where(np.repeat(is_quad, 2), _components(_strip_links(me, is_quad)), -1)
