"""Faces of a planar host graph, walked with its rotation system.

With the edges around every node in counter-clockwise order (the host graph's rotation system, set
by an angle function), the face to the left of a half-edge u -> v continues with the edge that comes
just *before* (v, u) in the counter-clockwise order around v. Walking every half-edge once gives
every face exactly once: bounded faces counter-clockwise, the unbounded face clockwise.

Only edges of the given types take part (the others are skipped in the rotations), so a host graph
can carry auxiliary edges (e.g. dual links) that are not part of the planar map.

A :class:`FaceIndex` keeps the faces walked, and what a caller works out from each, for as long as
nothing on the face changes, across rewrites and rollbacks (:func:`face_index`).
"""

from __future__ import annotations

import weakref
from typing import Iterable

from .graph import HostGraph, face_changes

HalfEdge = tuple[int, int]  # (edge id, node it leaves from)


def faces(graph: HostGraph, edge_types: Iterable[str], walk=None) -> list[list[HalfEdge]]:
    """All faces of the planar map formed by edges of ``edge_types``, as cycles of half-edges.

    Faces are listed in a deterministic order: by their smallest (edge id, start node) half-edge.
    ``walk(graph, types, start)``: what :func:`face_walk` gives (the default), for a caller that
    keeps the faces it walked.
    """
    types = set(edge_types)
    walk = walk or face_walk
    seen: set[HalfEdge] = set()
    out: list[list[HalfEdge]] = []
    for e in sorted(graph.of_types(t for t in types if t in graph.schema.edge_types)):
        for start in graph.ends(e):
            if (e, start) not in seen:
                face = walk(graph, types, (e, start))
                seen.update(face)
                out.append(face)
    return out


def face_walk(graph: HostGraph, edge_types: Iterable[str], start: HalfEdge) -> list[HalfEdge]:
    """The face to the left of the half-edge ``start`` = (edge, node it leaves from), as the cycle of
    half-edges around it; only edges of ``edge_types`` take part. Costs the length of that face."""
    types = edge_types if isinstance(edge_types, (set, frozenset)) else set(edge_types)
    face = [start]
    edge, u = start
    while True:
        v = graph.other(edge, u)
        edge, u = graph.before_around(v, edge, types), v
        if (edge, u) == start:
            return face
        face.append((edge, u))


class _Face:
    """A face the index walked: its half-edges from the first one walked, its nodes and the
    caller's data about it (:meth:`FaceIndex.data`)."""

    __slots__ = ("half_edges", "nodes", "data")

    def __init__(self, half_edges: tuple):
        self.half_edges = half_edges
        self.nodes = frozenset(u for _, u in half_edges)
        self.data: dict = {}


class FaceIndex:
    """The faces of the planar map of ``edge_types`` in a graph, each walked once and kept while it
    is the face a walk would give. The graph's journal says what changed
    (:func:`~.graph.face_changes`): the records since the index last looked (on the next question)
    and those a rollback undoes (:meth:`HostGraph.watch`). A face with an edge added or removed is
    dropped; a face through a node where the rotation changed is checked there (the edge it leaves
    by must still come just before the one it arrives by), since an edge added at a node splits
    only the face it is drawn in, not the others round that node. So a face that a rewrite or a
    rollback left alone is not walked again.

    :meth:`data` keeps what a caller works out from a face and the attributes and types of its nodes
    and edges (an outline, say): a new, empty one replaces it when one of those attributes or types
    changes, and it is dropped with the face (so the same dictionary means the same face,
    unchanged). :meth:`node_data` keeps what a caller works out from a node and the map's edges at
    it (whether it is a corner, say), until one of those changes.

    A walk per face and per change instead of per state of the graph: exploration (issue 13) steps
    back and forth between states that differ in a few faces.
    """

    def __init__(self, graph: HostGraph, edge_types: Iterable[str]):
        self.types = frozenset(edge_types)
        self._graph = weakref.ref(graph)
        self._at: dict[HalfEdge, tuple[_Face, int]] = {}  # half-edge -> (its face, its place there)
        self._through: dict[int, set[_Face]] = {}  # node -> the faces kept through it
        self._synced = graph.mark()  # the journal records before this one are accounted for
        self._check: set[int] = set()  # nodes whose faces are to be checked (rotations changed)
        self._nodes: dict[int, dict] = {}  # node -> the caller's data about it (node_data)
        self.walks = 0  # faces walked (for tests and benchmarks)
        graph.watch(self)

    def face(self, half_edge: HalfEdge) -> list[HalfEdge]:
        """The face to the left of ``half_edge``, from it on (:func:`face_walk`, a new list)."""
        face, i = self._entry(half_edge)
        return list(face.half_edges[i:] + face.half_edges[:i])

    def data(self, half_edge: HalfEdge) -> dict:
        """The caller's dictionary kept with the face of ``half_edge`` (see the class docstring)."""
        return self._entry(half_edge)[0].data

    def node_data(self, n: int) -> dict:
        """The caller's dictionary kept for node ``n`` while it, its attributes and type and the
        map's edges at it are unchanged (see the class docstring)."""
        self._sync(self._graph())
        found = self._nodes.get(n)
        if found is None:
            found = self._nodes[n] = {}
        return found

    def undoing(self, graph: HostGraph, record) -> None:
        """Account for a record about to be undone (:meth:`HostGraph.watch`)."""
        self._account(graph, record)
        self._synced = min(self._synced, graph.mark())

    def forgetting(self, graph: HostGraph) -> None:
        """Account for the whole journal before the graph drops it."""
        self._sync(graph)
        self._synced = 0

    def _entry(self, half_edge: HalfEdge) -> tuple[_Face, int]:
        graph = self._graph()
        self._sync(graph)
        found = self._at.get(half_edge)
        if found is None:
            face = _Face(tuple(face_walk(graph, self.types, half_edge)))
            self.walks += 1
            self._at.update({h: (face, i) for i, h in enumerate(face.half_edges)})
            for u in face.nodes:
                self._through.setdefault(u, set()).add(face)
            found = self._at[half_edge]
        return found

    def _sync(self, graph: HostGraph) -> None:
        """Account for the records journaled since the last look, then check the faces through the
        nodes where a rotation changed."""
        mark = graph.mark()
        if mark != self._synced:
            for record in graph.journal_since(self._synced):
                self._account(graph, record)
            self._synced = mark
        if self._check:
            for n in self._check:
                for face in [f for f in self._through.get(n, ()) if not self._holds_at(graph, f, n)]:
                    self._drop(face)
            self._check.clear()

    def _account(self, graph: HostGraph, record) -> None:
        half_edges, rotated, attributed = face_changes(graph, record, self.types)
        for h in half_edges:
            found = self._at.get(h)
            if found is not None:
                self._drop(found[0])
        self._check |= rotated
        for n in attributed:
            for face in self._through.get(n, ()):
                face.data = {}  # a new one: a caller that kept the old one knows it is out of date
        for n in attributed | rotated:
            self._nodes.pop(n, None)

    def _holds_at(self, graph: HostGraph, face: _Face, n: int) -> bool:
        """Whether the walk of ``face`` still turns at ``n`` as it did: wherever it arrives at ``n``
        by an edge, it leaves by the edge just before that one round ``n``."""
        half_edges = face.half_edges
        for i, (out, u) in enumerate(half_edges):
            if u != n:
                continue
            into, start = half_edges[i - 1]
            if not (graph.has_edge(into) and graph.has_edge(out) and n in graph.ends(into)
                    and graph.other(into, start) == n and graph.edge_type(into) in self.types
                    and graph.before_around(n, into, self.types) == out):
                return False
        return True

    def _drop(self, face: _Face) -> None:
        for h in face.half_edges:
            if self._at.get(h, (None,))[0] is face:
                del self._at[h]
        for u in face.nodes:
            self._through[u].discard(face)


_INDEXES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {edge types: FaceIndex}


def face_index(graph: HostGraph, edge_types: Iterable[str]) -> FaceIndex:
    """The graph's :class:`FaceIndex` of the map of ``edge_types`` (made on first use, one per graph
    and set of types)."""
    types = frozenset(edge_types)
    indexes = _INDEXES.get(graph)
    if indexes is None:
        indexes = _INDEXES[graph] = {}
    index = indexes.get(types)
    if index is None:
        index = indexes[types] = FaceIndex(graph, types)
    return index
