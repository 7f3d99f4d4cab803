"""Faces of a planar host graph, walked with its rotation system.

With the edges around every node in counter-clockwise order (the host graph's rotation system, set
by an angle function), the face to the left of a half-edge u -> v continues with the edge that comes
just *before* (v, u) in the counter-clockwise order around v. Walking every half-edge once gives
every face exactly once: bounded faces counter-clockwise, the unbounded face clockwise.

Only edges of the given types take part (the others are skipped in the rotations), so a host graph
can carry auxiliary edges (e.g. dual links) that are not part of the planar map.
"""

from __future__ import annotations

from typing import Iterable

from .graph import HostGraph

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
    for e in sorted(e for e in graph.edges() if graph.edge_type(e) in types):
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
