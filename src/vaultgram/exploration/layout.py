"""Typed patch layouts: when two decompositions are the same variant, by hash and by exact check.

A :class:`PatchLayout` is the combinatorial part of a decomposition: its corner points, each with a
label (node type, and ``*`` for a point feature), its patches (``3`` or ``4`` sides) and, for each
patch, its corners counter-clockwise as *darts* (a patch's corner ``i``; a dart is labelled
``pole`` at the triangle's marked pole). Two decompositions are the same variant when a bijection of
points, patches and darts keeps every label, every dart's point and patch, and every dart's
successor round its patch: an isomorphism of oriented maps. The cyclic order round a patch fixes the
cyclic order of the patches round each point, so the rotation system is compared too.

**Mirror images** are distinguished on purpose: a reflection reverses every patch's cycle, and on a
given plan a layout and its mirror image are two patterns a designer may want to compare (a
symmetric plan shows both). Relabelling the nodes, renumbering the patches or starting a patch's
cycle at another corner changes nothing.

:func:`layout_hash` is a colour refinement (Weisfeiler-Leman) over darts, points and patches, with
numpy arrays and a fixed 64-bit mixing function, so it is the same in every process; refinement is
invariant under isomorphism, so isomorphic layouts hash alike. Different layouts may collide:
:func:`same_layout` decides exactly: when refinement gave every dart its own colour the bijection
is forced, and :attr:`PatchLayout.certificate` writes the layout in that canonical order, so the
check is a comparison of bytes; else networkx's VF2 on :func:`layout_graph` with the colours as
labels decides.
"""

from __future__ import annotations

import functools
import hashlib
from dataclasses import dataclass
from functools import cached_property

import networkx as nx
import numpy as np

from vaultgram.engine.graph import HostGraph
from vaultgram.topology.patches import Patch
from vaultgram.topology.types import PATCH_CORNER

MAX_ROUNDS = 64  # refinement stops earlier, when a round separates no more darts (or all of them)
_M1, _SHIFT = np.uint64(0xBF58476D1CE4E5B9), np.uint64(29)
_ROLE = [np.uint64(c) for c in (0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9, 0x27D4EB2F165667C5,
                                0x85EBCA77C2B2AE63, 0xFF51AFD7ED558CCD)]


def _mix(x: np.ndarray) -> np.ndarray:
    """A multiply-xorshift mix, elementwise on uint64 (wrapping arithmetic): a fixed bijection that
    spreads the high bits of the product back into the low ones (a cheap one, since refinement mixes
    every dart every round; the exact check, not the mix, decides isomorphism)."""
    x = x * _M1
    return x ^ (x >> _SHIFT)


def _distinct(x: np.ndarray) -> int:
    """The number of distinct values (a sort: numpy's hashed unique is slower at these sizes)."""
    s = np.sort(x)
    return int(1 + np.count_nonzero(s[1:] != s[:-1])) if len(s) else 0


def _code(labels) -> np.ndarray:
    """64-bit codes of label strings (the same in every process: not Python's salted ``hash``)."""
    return np.array([_label_code(s) for s in labels], dtype=np.uint64)


@functools.lru_cache(maxsize=None)
def _label_code(label: str) -> int:
    return int.from_bytes(hashlib.blake2b(label.encode(), digest_size=8).digest(), "little")


@dataclass(frozen=True, eq=False)
class PatchLayout:
    """Points, patches and darts of a decomposition (see the module docstring), as index arrays."""

    point_labels: tuple[str, ...]
    patch_sides: tuple[int, ...]
    dart_point: np.ndarray  # the point of each dart
    dart_patch: np.ndarray  # the patch of each dart
    dart_next: np.ndarray  # the next dart counter-clockwise round the same patch
    dart_pole: np.ndarray  # bool: the dart is its triangle's marked pole

    @cached_property
    def colours(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Refined colours of darts, points and patches (rounds until stable, :func:`_refine`)."""
        return _refine(self)

    @cached_property
    def hash(self) -> str:
        """The layout hash: 16 hex digits over the multisets of refined colours."""
        digest = hashlib.blake2b(digest_size=8)
        for colours in self.colours:
            digest.update(np.sort(colours).tobytes())
        return digest.hexdigest()

    @cached_property
    def certificate(self) -> bytes | None:
        """A canonical form, when refinement coloured every dart apart (else None): the darts in the
        order of their colours, each with its colour, its successor's and its point's and patch's
        first dart in that order, and its pole flag, then the point labels and patch sides in the
        order of their first darts. Any isomorphism keeps colours, so with every colour distinct the
        colour order is the only candidate bijection, and two layouts are isomorphic exactly when
        their certificates are equal (the exact check, a comparison of bytes)."""
        dart = self.colours[0]
        order = np.argsort(dart, kind="stable")
        ranked = dart[order]
        if np.any(ranked[1:] == ranked[:-1]):
            return None
        rank = np.empty_like(order)
        rank[order] = np.arange(len(order))
        point_first, patch_first = _first_darts(self.dart_point[order]), _first_darts(self.dart_patch[order])
        labels = [self.point_labels[i] for i in np.argsort(point_first, kind="stable")]
        sides = np.asarray(self.patch_sides, dtype=np.int64)[np.argsort(patch_first, kind="stable")]
        parts = (ranked, rank[self.dart_next[order]], point_first[self.dart_point[order]],
                 patch_first[self.dart_patch[order]], self.dart_pole[order], sides)
        return b"".join(np.ascontiguousarray(x).tobytes() for x in parts) + "\0".join(labels).encode()

    def size(self) -> int:
        """Number of points (the layout's nodes)."""
        return len(self.point_labels)


def point_label(graph: HostGraph, n: int) -> str:
    """A point's label: its node type, with ``*`` for a point feature."""
    return graph.node_type(n) + ("*" if graph.node_attrs(n).get("feature") else "")


def layout_of(graph: HostGraph, patches: list[Patch]) -> PatchLayout:
    """The layout of a decomposition's patches (corners counter-clockwise) in its graph (index
    arrays made with numpy: this runs once per state of a search)."""
    sizes = np.fromiter((len(p.corners) for p in patches), dtype=np.int64, count=len(patches))
    flat = np.fromiter((c for p in patches for c in p.corners), dtype=np.int64, count=int(sizes.sum()))
    corners, point = np.unique(flat, return_inverse=True)
    patch = np.repeat(np.arange(len(patches)), sizes)
    base = np.repeat(np.cumsum(sizes) - sizes, sizes)
    nxt = base + (np.arange(len(flat)) - base + 1) % np.repeat(sizes, sizes)
    poles = _marked_poles(graph)
    pole_of = np.array([poles.get(frozenset(p.corners), -1) for p in patches], dtype=np.int64)
    return PatchLayout(tuple(point_label(graph, int(c)) for c in corners), tuple(sizes.tolist()),
                       point.astype(np.int64), patch, nxt, flat == pole_of[patch])


def _marked_poles(graph: HostGraph) -> dict:
    """The marked pole of each Patch node that has one, keyed by the set of its corners."""
    edges = list(graph.of_types([PATCH_CORNER]))
    out = {}
    for e, pole in zip(edges, graph.values("edge", edges, "pole")):
        if pole:
            node, c = graph.ends(e)
            out[frozenset(graph.ends(f)[1] for f in graph.incident(node, [PATCH_CORNER]))] = c
    return out


def _refine(layout: PatchLayout) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Colour refinement, until a round separates no more darts (a criterion that isomorphic
    layouts meet at the same round, so the colours stay invariant). A dart starts from its label,
    its point's label and number of darts, and its patch's sides; each round its colour is mixed
    from its own, its point's and its successor's and predecessor's round its patch (each role
    weighed by its own odd constant), and a point's from its own and the sum (a multiset) of its
    darts'. A patch's colour is the sum of its darts' at the end (the successor and predecessor
    carry a patch's cycle into its darts already, so it needs no round of its own)."""
    nxt = layout.dart_next
    prev = np.empty_like(nxt)
    prev[nxt] = np.arange(len(prev))
    by_point = _groups(layout.dart_point)
    degree = np.bincount(layout.dart_point, minlength=layout.size()).astype(np.uint64)
    point = _mix(_code(layout.point_labels) + degree * _ROLE[2])[layout.dart_point]
    sides = np.asarray(layout.patch_sides, dtype=np.uint64)[layout.dart_patch]
    dart = _mix(np.where(layout.dart_pole, _ROLE[0], _ROLE[1]) + sides * _ROLE[3])
    distinct = 0
    for _ in range(MAX_ROUNDS):
        dart = _mix(dart * _ROLE[0] + point * _ROLE[1] + dart[nxt] * _ROLE[3] + dart[prev] * _ROLE[4])
        point = _mix(point * _ROLE[5] + _sums(dart, by_point)[layout.dart_point])
        now = _distinct(dart)
        if now == distinct or now == len(dart):
            break
        distinct = now
    order, starts = by_point
    patch_order = _groups(layout.dart_patch)
    return dart, point[order[starts]], _mix(_sums(dart ^ _ROLE[1], patch_order))


def _groups(owner: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The darts sorted by their owner (point or patch), and where each owner's run starts (every
    owner has a dart: points and patches are made from them)."""
    order = np.argsort(owner, kind="stable")
    return order, np.flatnonzero(np.r_[True, np.diff(owner[order]) != 0])


def _sums(values: np.ndarray, groups: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Wrapping uint64 sums of ``values`` by owner (a multiset's code, independent of order)."""
    order, starts = groups
    return np.add.reduceat(values[order], starts)


def same_layout(a: PatchLayout, b: PatchLayout) -> bool:
    """Whether two layouts are isomorphic (exact; see the module docstring)."""
    if (a.size(), len(a.patch_sides), len(a.dart_point)) != (b.size(), len(b.patch_sides), len(b.dart_point)):
        return False
    if a.hash != b.hash:
        return False
    if a.certificate is not None and b.certificate is not None:
        return a.certificate == b.certificate
    return _vf2(a, b)


def _first_darts(owner_in_order: np.ndarray) -> np.ndarray:
    """For each owner (point or patch) id, the position of its first dart in the given order."""
    _, first = np.unique(owner_in_order, return_index=True)
    return first


def layout_graph(layout: PatchLayout) -> nx.DiGraph:
    """The layout as a labelled digraph (points ``("v", i)``, patches ``("f", k)``, darts ``("d", j)``
    with edges dart -> its point, dart -> its patch, dart -> next dart): isomorphic exactly when
    the layouts are (networkx's VF2 with ``label`` and ``kind`` matching)."""
    g = nx.DiGraph()
    g.add_nodes_from((("v", i), {"label": s}) for i, s in enumerate(layout.point_labels))
    g.add_nodes_from((("f", k), {"label": f"patch{s}"}) for k, s in enumerate(layout.patch_sides))
    for j in range(len(layout.dart_point)):
        g.add_node(("d", j), label="pole" if layout.dart_pole[j] else "corner")
        g.add_edge(("d", j), ("v", int(layout.dart_point[j])), kind="at")
        g.add_edge(("d", j), ("f", int(layout.dart_patch[j])), kind="of")
        g.add_edge(("d", j), ("d", int(layout.dart_next[j])), kind="next")
    return g


def isomorphic(a: PatchLayout, b: PatchLayout) -> bool:
    """networkx's exact check (VF2) on :func:`layout_graph`, with plain labels."""
    return nx.is_isomorphic(layout_graph(a), layout_graph(b), node_match=_same("label"), edge_match=_same("kind"))


def _same(key: str):
    return lambda x, y: x[key] == y[key]


def _vf2(a: PatchLayout, b: PatchLayout) -> bool:
    """VF2 with the refined colours as labels (a sound pruning: isomorphisms keep colours)."""
    ga, gb = layout_graph(a), layout_graph(b)
    for g, layout in ((ga, a), (gb, b)):
        darts, points, patches = layout.colours
        for kind, colours in (("d", darts), ("v", points), ("f", patches)):
            for i, c in enumerate(colours):
                g.nodes[(kind, i)]["colour"] = int(c)
    return nx.is_isomorphic(ga, gb, node_match=_same("colour"), edge_match=_same("kind"))
