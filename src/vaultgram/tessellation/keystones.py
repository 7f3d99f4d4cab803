"""Keystones (paper §5, Figure 11b), decided by the rulebook on the thrust network's graph.

"Having many voussoirs coming to the same point makes the assembly task more difficult [...].
Therefore [...] singularities with a valency of five or more are transformed into their dual face"
(§5). Which vertices become keystones, and how, is the rule ``keystone`` of
``rules/tessellation.vgr``; this module only lays the network out as a host graph for it (a
``Vertex`` per vertex, a ``Joint`` per edge, edges around each vertex counter-clockwise in plan),
runs the strategy ``tessellation`` and reads the faces back: the faces no rule touched as they were,
the others walked again with the graph's rotation system.
"""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from vaultgram.engine.embedding import face_walk
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.rulebook import Rulebook, load_rulebook
from vaultgram.engine.strategy import Runner
from vaultgram.errors import RuleError
from vaultgram.geometry.arrays import plan_rows
from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.geometry.meshes import Faces, corner_arrays
from vaultgram.tessellation.functions import tessellation_functions
from vaultgram.topology.rulebook import default_rules_dir

__all__ = ["CutMesh", "cut_keystones", "pinwheel", "load_tessellation_rulebook", "STRATEGY", "RULE_FILE"]

STRATEGY = "tessellation"
RULE_FILE = "tessellation.vgr"
NODE, CORNER, EDGE = "Vertex", "KeystoneCorner", "Joint"


@dataclass(frozen=True, eq=False)
class CutMesh:
    """The thrust network after the keystone rules: a polygon mesh on the thrust surface.

    Attributes
    ----------
    vertices : ndarray (n, 3)
        The network's vertices that remain, then the keystone corners.
    faces : tuple of tuple
        Counter-clockwise in plan.
    keystones : ndarray (k,)
        The faces that are keystones.
    source : ndarray (n,)
        For each vertex its index in the thrust network, -1 for a keystone corner.
    steps : tuple of (str, int)
        The strategy's steps and how many rule applications each made.
    """

    vertices: np.ndarray
    faces: tuple
    keystones: np.ndarray
    source: np.ndarray
    steps: tuple


def load_tessellation_rulebook(rules_dir: str | Path | None = None) -> Rulebook:
    """``tessellation.vgr`` from ``rules_dir`` if it has one, else the rulebook shipped with vaultgram."""
    directory = Path(rules_dir) if rules_dir is not None else default_rules_dir()
    path = directory / RULE_FILE if (directory / RULE_FILE).is_file() else default_rules_dir() / RULE_FILE
    stamp = tuple(sorted((f.name, f.stat().st_mtime_ns) for f in path.parent.glob("*.vgr")))
    return _load_checked(path.resolve(), stamp)


@functools.lru_cache(maxsize=8)
def _load_checked(path: Path, stamp: tuple) -> Rulebook:
    book = load_rulebook([path], tessellation_functions())
    missing = [t for t in (NODE, CORNER) if t not in book.schema.node_types]
    missing += [t for t in (EDGE,) if t not in book.schema.edge_types]
    if missing:
        raise RuleError(f"{path}: the rulebook's schema lacks the type(s) {', '.join(missing)} that the "
                        "tessellation builds its graph with (see rules/tessellation.vgr)")
    if STRATEGY not in book.strategies:
        raise RuleError(f"{path}: the rulebook has no strategy '{STRATEGY}'")
    return book


def _plan_angle(graph: HostGraph, e: int, n: int) -> float:
    """Direction in plan in which edge ``e`` leaves node ``n`` (the rotation system's order)."""
    p, q = graph.get(n, "pos"), graph.get(graph.other(e, n), "pos")
    return math.atan2(q[1] - p[1], q[0] - p[0])


def network_graph(x: np.ndarray, me: MeshEdges, rulebook: Rulebook) -> HostGraph:
    """The host graph of a mesh: node ``i`` is vertex ``i``, edge ``e`` is mesh edge ``e``."""
    graph = HostGraph(rulebook.schema, angle=_plan_angle)
    on_boundary = np.zeros(len(x), dtype=bool)
    on_boundary[me.edges[me.boundary].ravel()] = True
    graph.add_nodes(NODE, range(len(x)), {"pos": x, "index": np.arange(len(x)), "boundary": on_boundary})
    a, b = plan_rows(x, me.edges[:, 0]), plan_rows(x, me.edges[:, 1])
    angles = np.column_stack([np.arctan2(b[:, 1] - a[:, 1], b[:, 0] - a[:, 0]),
                              np.arctan2(a[:, 1] - b[:, 1], a[:, 0] - b[:, 0])])  # as _plan_angle gives them
    graph.add_edges(EDGE, me.edges, angles=angles)
    return graph


def _walked_faces(graph: HostGraph, touched: list[int], outside: set) -> list[list[int]]:
    """The faces around the nodes the rules touched, each once, as node loops; the outer face and
    the openings (walks along an ``outside`` half-edge) are not faces."""
    seen: set[tuple[int, int]] = set()
    out = []
    for n in touched:
        for e in graph.rotation(n):
            if (e, n) in seen:
                continue
            walk = face_walk(graph, (EDGE,), (e, n))
            seen.update(walk)
            loop = [u for _, u in walk]
            if not any((p, q) in outside for p, q in zip(loop, loop[1:] + loop[:1])):
                out.append(loop)
    return out


def _renumbered(faces, kept: np.ndarray, walked: list, ids: np.ndarray) -> Faces:
    """The faces ``kept`` (indices into ``faces``), then the ``walked`` node loops, with node ids
    replaced by their positions in the sorted ``ids``: made from the flat array at once
    (:meth:`~vaultgram.geometry.meshes.Faces.from_flat`, which also keeps its corner arrays)."""
    position = np.full(int(ids.max()) + 1 if len(ids) else 0, -1, dtype=np.int64)
    position[ids] = np.arange(len(ids))
    face, vertex, _, _ = corner_arrays(faces)
    old = np.zeros(len(faces), dtype=bool)
    old[kept] = True
    lens = np.concatenate([np.bincount(face, minlength=len(faces))[kept],
                           np.fromiter(map(len, walked), dtype=np.int64, count=len(walked))])
    new = np.fromiter(itertools.chain.from_iterable(walked), dtype=np.int64, count=int(lens[len(kept):].sum()))
    return Faces.from_flat(position[np.concatenate([vertex[old[face]], new])], lens)


def _outside_half_edges(faces, me: MeshEdges) -> set:
    """The half-edges with no face on their left: the reverse of every boundary side."""
    c = me.corners_of[me.boundary]
    c = c[c >= 0]
    return {(int(b), int(a)) for a, b in zip(me.corner_vertex[c].tolist(), me.corner_next[c].tolist())}


def cut_keystones(x: np.ndarray, faces, me: MeshEdges, rulebook: Rulebook) -> CutMesh:
    """Run the rulebook's ``tessellation`` strategy on the network's graph; the mesh it leaves.

    Faces with no node the rules touched stay as they were; the faces around touched nodes are
    walked again. A face whose nodes all carry one ``keystone`` number is a keystone.
    """
    graph = network_graph(x, me, rulebook)
    graph.forget()
    runner = Runner(rulebook, graph)
    runner.run(STRATEGY)
    n = len(x)
    changed = graph.changes_since(0).nodes
    touched_ids = sorted(v for v in changed if graph.has_node(v))
    old_touched = np.zeros(n, dtype=bool)
    old_touched[[v for v in changed if v < n]] = True
    hit = np.bincount(me.corner_face, weights=old_touched[me.corner_vertex], minlength=len(faces)) > 0
    old = np.flatnonzero(~hit)
    walked = _walked_faces(graph, touched_ids, _outside_half_edges(faces, me))
    ids = np.array(sorted(graph.nodes()), dtype=np.int64)
    out_faces = _renumbered(faces, old, walked, ids)
    keystone = {v: graph.get(v, "keystone") for v in touched_ids}
    keystones = [len(old) + k for k, f in enumerate(walked)
                 if len({keystone.get(v, -1) for v in f}) == 1 and keystone.get(f[0], -1) >= 0]
    vertices = np.vstack([x[ids[ids < n]], np.array([graph.get(int(v), "pos") for v in ids[ids >= n]],
                                                    dtype=float).reshape(-1, 3)])
    source = np.where(ids < n, ids, -1)
    steps = tuple((r.step, r.applications) for r in runner.reports)
    return CutMesh(vertices, out_faces, np.array(keystones, dtype=np.int64), source, steps)


def pinwheel(mesh: CutMesh, me: MeshEdges) -> np.ndarray:
    """Edges to remove so that the keystones' neighbours turn like a pinwheel (Figure 11b).

    Each face beside a keystone is joined to the face across its first side after the keystone's
    spoke (the side leaving the spoke's far end, turning the same way round every keystone). Then
    every point around the ring of neighbours is a point of three voussoirs, as the keystone's own
    corners are, where joining nothing would leave points of four. A face already taken by another
    join, a keystone, or a side on the boundary is skipped.
    """
    removed = np.zeros(me.n_edges, dtype=bool)
    used = np.zeros(len(mesh.faces), dtype=bool)
    used[mesh.keystones] = True
    size = np.diff(me.face_start)
    for key in mesh.keystones.tolist():
        for c in range(me.face_start[key], me.face_start[key + 1]):
            t = int(me.corner_twin[c])  # the neighbour's corner at b, its side running b -> a
            if t < 0 or used[me.corner_face[t]]:
                continue
            neighbour = int(me.corner_face[t])
            start, n = int(me.face_start[neighbour]), int(size[neighbour])
            side = start + (int(me.corner_side[t]) + 2) % n  # after a -> w (the spoke): the side w -> c
            across = int(me.corner_twin[side])
            if across < 0 or used[me.corner_face[across]]:
                continue
            removed[me.corner_edge[side]] = True
            used[[neighbour, me.corner_face[across]]] = True
    return removed
