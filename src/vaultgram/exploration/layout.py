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
:func:`same_layout` decides exactly, in linear time when refinement gave every element its own
colour (the bijection is then forced), else with networkx's VF2 on :func:`layout_graph` with the
colours as labels.
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
from vaultgram.topology.types import PATCH, PATCH_CORNER

MAX_ROUNDS = 64  # refinement stops earlier, when a round separates no more darts (or all of them)
_M1, _M2 = np.uint64(0xBF58476D1CE4E5B9), np.uint64(0x94D049BB133111EB)
_ROLE = [np.uint64(c) for c in (0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9, 0x27D4EB2F165667C5,
                                0x85EBCA77C2B2AE63, 0xFF51AFD7ED558CCD)]


def _mix(x: np.ndarray) -> np.ndarray:
    """The splitmix64 finaliser, elementwise on uint64 (wrapping arithmetic): a fixed bijection."""
    x = x ^ (x >> np.uint64(30))
    x = x * _M1
    x = x ^ (x >> np.uint64(27))
    x = x * _M2
    return x ^ (x >> np.uint64(31))


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

    def size(self) -> int:
        """Number of points (the layout's nodes)."""
        return len(self.point_labels)


def point_label(graph: HostGraph, n: int) -> str:
    """A point's label: its node type, with ``*`` for a point feature."""
    return graph.node_type(n) + ("*" if graph.node_attrs(n).get("feature") else "")


def layout_of(graph: HostGraph, patches: list[Patch]) -> PatchLayout:
    """The layout of a decomposition's patches (corners counter-clockwise) in its graph."""
    corners = sorted({c for p in patches for c in p.corners})
    index = {c: i for i, c in enumerate(corners)}
    poles = _marked_poles(graph)
    point, patch, nxt, pole = [], [], [], []
    for k, p in enumerate(patches):
        base = len(point)
        m = len(p.corners)
        for i, c in enumerate(p.corners):
            point.append(index[c])
            patch.append(k)
            nxt.append(base + (i + 1) % m)
            pole.append(poles.get(frozenset(p.corners)) == c)
    return PatchLayout(tuple(point_label(graph, c) for c in corners), tuple(len(p.corners) for p in patches),
                       np.array(point, dtype=np.int64), np.array(patch, dtype=np.int64),
                       np.array(nxt, dtype=np.int64), np.array(pole, dtype=bool))


def _marked_poles(graph: HostGraph) -> dict:
    """The marked pole of each Patch node that has one, keyed by the set of its corners."""
    out = {}
    for node in graph.of_types([PATCH]):
        ends = [(graph.ends(e)[1], graph.get_edge(e, "pole")) for e in graph.incident(node, [PATCH_CORNER])]
        for c, pole in ends:
            if pole:
                out[frozenset(c for c, _ in ends)] = c
    return out


def _refine(layout: PatchLayout) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Colour refinement, until a round separates no more darts (a criterion that isomorphic
    layouts meet at the same round, so the colours stay invariant): a dart's colour from its own,
    its point's, its patch's and its successor's and predecessor's (each role weighed by its own
    odd constant, then mixed); a point's and a patch's from theirs and the sum (a multiset) of
    their darts'."""
    prev = np.empty_like(layout.dart_next)
    prev[layout.dart_next] = np.arange(len(prev))
    by_point, by_patch = _groups(layout.dart_point), _groups(layout.dart_patch)
    dart = _code(["pole" if p else "corner" for p in layout.dart_pole])
    point = _code(layout.point_labels)
    patch = _code([f"patch{s}" for s in layout.patch_sides])
    distinct = 0
    for _ in range(MAX_ROUNDS):
        dart = _mix(dart * _ROLE[0] + point[layout.dart_point] * _ROLE[1] + patch[layout.dart_patch] * _ROLE[2]
                    + dart[layout.dart_next] * _ROLE[3] + dart[prev] * _ROLE[4])
        point = _mix(point * _ROLE[5] + _sums(dart, by_point))
        patch = _mix(patch * _ROLE[5] + _sums(dart ^ _ROLE[1], by_patch))
        now = len(np.unique(dart))
        if now == distinct or now == len(dart):
            break
        distinct = now
    return dart, point, patch


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
    forced = _forced_map(a, b)
    if forced is not None:
        return forced
    return _vf2(a, b)


def _forced_map(a: PatchLayout, b: PatchLayout) -> bool | None:
    """With every dart coloured apart in both, the only candidate bijection maps equal colours:
    whether it is an isomorphism; None when some colour is shared (then VF2 decides)."""
    da, db = a.colours[0], b.colours[0]
    if len(np.unique(da)) < len(da) or len(np.unique(db)) < len(db):
        return None
    order_a, order_b = np.argsort(da), np.argsort(db)
    if not np.array_equal(da[order_a], db[order_b]):
        return False
    to_b = np.empty(len(da), dtype=np.int64)
    to_b[order_a] = order_b  # dart i of a -> dart to_b[i] of b
    if not np.array_equal(to_b[a.dart_next], b.dart_next[to_b]) or not np.array_equal(a.dart_pole, b.dart_pole[to_b]):
        return False
    return _consistent(a.dart_point, b.dart_point[to_b], a.point_labels, b.point_labels) and _consistent(
        a.dart_patch, b.dart_patch[to_b], a.patch_sides, b.patch_sides)


def _consistent(src: np.ndarray, dst: np.ndarray, labels_a, labels_b) -> bool:
    """Whether dart images induce a label-keeping bijection of the elements the darts point to."""
    image = np.full(len(labels_a), -1, dtype=np.int64)
    image[src] = dst
    if np.any(image[src] != dst) or len(np.unique(image)) != len(image) or np.any(image < 0):
        return False
    return all(labels_a[i] == labels_b[j] for i, j in enumerate(image))


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
