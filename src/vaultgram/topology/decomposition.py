"""The block decomposition (paper §3.1, Figure 2d-2f): the skeleton as a typed graph, rewritten by rules.

:func:`decomposition_graph` turns the skeleton into a host graph of the rulebook's schema
(``rules/schema.vgr``):

* every ring point becomes a ``BoundaryVertex`` (a ``Corner`` where a corner face ends the skeleton),
  consecutive ring points are joined by ``Boundary`` edges; feature and curve points become
  ``FeaturePoint`` and ``CurvePoint`` nodes;
* every singularity of the skeleton becomes a ``Singularity``, with a ``Dual`` edge to each vertex of
  its dual (singular) face; skeleton branches become ``Branch`` edges carrying their polylines;
* skeleton cycles that meet no singularity (the loop of an annulus, or a branch that returns to its
  own node) are cut by ``LoopVertex`` nodes, whose duals are the two boundary points their maximal
  circle touches, one on each side; a domain without corners or holes keeps its single centre cell
  as a singularity whose dual is three points of that cell a third of the way around apart.

:func:`block_decomposition` then runs the rulebook's ``topology`` strategy on it (prune corner branches,
rebranch) -- the topology is decided by the rule files, not by this module -- and extracts the
patches (:mod:`vaultgram.topology.patches`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from vaultgram.engine.graph import HostGraph
from vaultgram.engine.rulebook import Rulebook
from vaultgram.engine.strategy import Chooser, Runner, first_option
from vaultgram.errors import DomainError, RewriteError
from vaultgram.geometry.frames import NO_ORIGIN, to_plan
from vaultgram.geometry.polylines import arc_lengths
from vaultgram.geometry.text import fmt_point
from vaultgram.topology.discretise import RING_POINT, Discretisation
from vaultgram.topology.patches import Patch, check_no_enclosed_holes, find_patches, half_edge_polyline
from vaultgram.topology.skeleton import Skeleton
from vaultgram.topology.types import (
    BOUNDARY,
    BOUNDARY_VERTEX,
    BRANCH,
    CORNER,
    CURVE,
    CURVE_EXTREMITY,
    CURVE_POINT,
    DUAL,
    FEATURE_POINT,
    LOOP_VERTEX,
    PATCH,
    PATCH_CORNER,
    PATCH_STRATEGIES,
    PLAN_EDGES,
    SINGULARITY,
    TOPOLOGY_STRATEGY,
)

LOOP_CUTS = 4  # cut points on a skeleton loop without singularity (an annulus becomes 2 x 4 quads)


class RuleStep(NamedTuple):
    """A strategy step the rulebook ran, and how many rule applications it made."""

    step: str
    applications: int


@dataclass(frozen=True, eq=False)
class Decomposition:
    """The result of topology finding: the rewritten typed graph and its 3- and 4-sided patches."""

    disc: Discretisation
    skeleton: Skeleton
    graph: HostGraph
    patches: tuple[Patch, ...]
    reports: tuple[RuleStep, ...]
    trace: list[dict]
    invariant_checks: int = 0  # how many invariant checks the run made (check_invariants)
    start_graph: dict | None = None  # the graph before the rules, as JSON (block_decomposition's trace)

    def marked_pole(self, patch: Patch) -> int | None:
        """The corner a patching rule marked as the pole of this patch (``PatchCorner {pole = true}``)."""
        return self._marked_poles.get(frozenset(patch.corners))

    @functools.cached_property
    def _marked_poles(self) -> dict:
        """The marked pole of each Patch node that has one, keyed by the set of its corners."""
        g = self.graph
        out = {}
        for node in self.patch_nodes():
            edges = list(g.incident(node, [PATCH_CORNER]))
            pole = [g.ends(e)[1] for e in edges if g.get_edge(e, "pole")]
            if pole:
                out[frozenset(g.ends(e)[1] for e in edges)] = pole[0]
        return out

    def patch_nodes(self) -> list[int]:
        """The ``Patch`` nodes of the graph (one per patch after the patching rules)."""
        return [n for n in self.graph.nodes() if self.graph.node_type(n) == PATCH]

    def singularities(self) -> list[int]:
        """The ``Singularity`` nodes of the rewritten graph."""
        return [n for n in self.graph.nodes() if self.graph.node_type(n) == SINGULARITY]

    def valence(self, n: int) -> int:
        """Number of patch-layout edges (branches, rebranches, boundary pieces) at node ``n``."""
        return self.graph.degree(n, PLAN_EDGES)

    @property
    def origin(self) -> tuple:
        """Where the frame of the decomposition's coordinates starts in the plan's (its domain's
        ``origin``, :mod:`vaultgram.geometry.frames`): the JSON adds it back."""
        return self.disc.domain.origin

    def to_json(self) -> dict:
        """The typed graph, in the plan's coordinates: nodes with types and attributes, edges with types
        and polylines."""
        g, origin = self.graph, self.origin
        return {
            "name": self.disc.domain.name,
            "spacing": self.disc.spacing,
            "nodes": [{"id": n, "type": g.node_type(n), **_plain_attrs(g.node_attrs(n), origin)} for n in g.nodes()],
            "edges": [self._edge_json(e) for e in g.edges()],
            "rules": [{"step": r.step, "applications": r.applications} for r in self.reports],
        }

    def _edge_json(self, e: int) -> dict:
        """One edge for :meth:`to_json`: a patch corner's index, or a plan edge's polyline."""
        g = self.graph
        u, v = g.ends(e)
        out = {"id": e, "type": g.edge_type(e), "source": u, "target": v}
        if g.edge_type(e) == PATCH_CORNER:
            return {**out, "index": g.get_edge(e, "index")}
        return {**out, "polyline": to_plan(half_edge_polyline(g, e, u), self.origin).tolist()}

    def patches_json(self) -> dict:
        """The patches: corners and sides (in the plan's coordinates), and how many have 3 and 4 sides."""
        return {
            "name": self.disc.domain.name,
            "patches": [p.to_json(self.origin) for p in self.patches],
            "counts": {str(k): sum(p.n_sides == k for p in self.patches) for k in (3, 4)},
        }


def edge_angle(graph: HostGraph, e: int, n: int) -> float:
    """Direction in which edge ``e`` leaves node ``n`` (along its polyline if it has one).

    Edges to nodes without a position (patch nodes) are not part of the plan: they sort first.
    """
    u, v = graph.ends(e)
    if "pos" not in graph.node_attrs(u) or "pos" not in graph.node_attrs(v):
        return -math.pi
    poly = graph.get_edge(e, "polyline") if "polyline" in graph.edge_attrs(e) else ()
    if len(poly) >= 2:
        a, b = (poly[0], poly[1]) if n == u else (poly[-1], poly[-2])
    else:
        a, b = graph.get(n, "pos"), graph.get(graph.other(e, n), "pos")
    return math.atan2(b[1] - a[1], b[0] - a[0])


def decomposition_graph(sk: Skeleton, rulebook: Rulebook) -> HostGraph:
    """The typed graph of §3.1 before rewriting (see the module docstring): the points of the plan,
    its boundary and curve segments, the skeleton vertices with their duals, the branches, and the
    skeleton loops cut into branches.

    Example
    -------
    >>> from collections import Counter
    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.pipeline import decompose
    >>> from vaultgram.topology.rulebook import load_vault_rulebook
    >>> rewritten = decompose(load_domain("examples/l_shape.json"), 0.05)
    >>> g = decomposition_graph(rewritten.skeleton, load_vault_rulebook())  # the graph before the rules
    >>> sorted(Counter(g.node_type(n) for n in g.nodes()).items())
    [('BoundaryVertex', 59), ('Corner', 5), ('Singularity', 3)]
    """
    disc = sk.triangulation.disc
    g = HostGraph(rulebook.schema, angle=edge_angle)
    _add_plan_points(g, disc, {int(n.point) for n in sk.nodes if n.kind == "corner"})
    _add_plan_segments(g, disc)
    node_of = _add_skeleton_vertices(g, sk)
    for branch in sk.branches:
        _add_branch(g, sk, node_of[branch.start], node_of[branch.end], branch)
    for loop in sk.loops:
        _cut_loop(g, sk, loop)
    g.forget()
    return g


def _add_plan_points(g: HostGraph, disc: Discretisation, corner_points: set) -> None:
    """A node for every sample point, with the point's index as id: ring points (``Corner`` at a
    polygon corner), then point features and curve points (§4); point features are marked
    ``feature``, the corner vertices of corner faces ``corner`` (their branches are to be pruned)."""
    pts = disc.points
    for ring in disc.rings:
        for k, p in enumerate(ring):
            kind = CORNER if disc.corner_kind[p] == 1 else BOUNDARY_VERTEX
            g.add_node(kind, {"pos": tuple(pts[p]), "ring": int(disc.ring[p]), "index": k}, id=int(p))
    curve_ends = {int(c[k]) for c in disc.curves for k in (0, -1)}
    for p in np.flatnonzero(disc.ring < 0):
        kind = FEATURE_POINT if disc.ring[p] == RING_POINT else CURVE_EXTREMITY if p in curve_ends else CURVE_POINT
        g.add_node(kind, {"pos": tuple(pts[p])}, id=int(p))
    for p in disc.feature_points:  # point features, on the boundary or inside (§4.1)
        g.set_node_attr(int(p), "feature", True)
    for p in corner_points:
        g.set_node_attr(p, "corner", True)


def _add_plan_segments(g: HostGraph, disc: Discretisation) -> None:
    """``Boundary`` edges between consecutive ring points, ``Curve`` edges along each curve feature
    from its first point towards its last."""
    for ring in disc.rings:
        for a, b in zip(ring, np.roll(ring, -1)):
            g.add_edge(BOUNDARY, int(a), int(b))
    for curve in disc.curves:
        for a, b in zip(curve[:-1], curve[1:]):
            g.add_edge(CURVE, int(a), int(b))


def _add_skeleton_vertices(g: HostGraph, sk: Skeleton) -> dict[int, int]:
    """A ``Singularity`` for every singularity of the skeleton, and for the centre cell of a domain
    without corners and holes (its dual: three points of the cell, a third of the way around apart),
    with ``Dual`` edges to its dual; corner nodes are their corner points. Returns the graph node of
    each skeleton node."""
    node_of: dict[int, int] = {}
    for node in sk.nodes:
        if node.kind == "corner":
            node_of[node.id] = int(node.point)
            continue
        dual = node.dual
        radius = float(sk.triangulation.cell_radii[node.cell])
        s = g.add_node(SINGULARITY, {"pos": tuple(node.pos), "radius": radius})
        node_of[node.id] = s
        for p in dual:
            g.add_edge(DUAL, s, int(p))
    return node_of


def _add_branch(g: HostGraph, sk: Skeleton, a: int, b: int, branch) -> None:
    """A ``Branch`` edge from node ``a`` to ``b`` along the branch's polyline; a branch returning to
    its own node is cut once in the middle by a ``LoopVertex``."""
    poly = branch.polyline
    if a != b:
        g.add_edge(BRANCH, a, b, {"polyline": _plain(poly)})
        return
    cut = _add_loop_vertex(g, sk, poly, branch.faces, len(poly) // 2)
    g.add_edge(BRANCH, a, cut, {"polyline": _plain(poly[: len(poly) // 2 + 1])})
    g.add_edge(BRANCH, cut, b, {"polyline": _plain(poly[len(poly) // 2 :])})


def _cut_loop(g: HostGraph, sk: Skeleton, loop) -> None:
    """Cut a skeleton loop without singularity at :data:`LOOP_CUTS` points evenly spaced along it,
    joined by ``Branch`` edges (an annulus becomes a ring of quads on each side)."""
    poly = loop.polyline[:-1]
    if len(poly) < 2 * LOOP_CUTS:
        raise DomainError("a skeleton loop is too short to cut into patches; use a smaller spacing")
    length = arc_lengths(loop.polyline)
    at = [int(np.searchsorted(length, length[-1] * k / LOOP_CUTS)) % len(poly) for k in range(LOOP_CUTS)]
    cuts = [_add_loop_vertex(g, sk, loop.polyline, loop.faces, i) for i in at]
    for k in range(LOOP_CUTS):
        i, j = at[k], at[(k + 1) % LOOP_CUTS]
        piece = loop.polyline[i : j + 1] if j > i else np.vstack([loop.polyline[i:-1], loop.polyline[: j + 1]])
        g.add_edge(BRANCH, cuts[k], cuts[(k + 1) % LOOP_CUTS], {"polyline": _plain(piece)})


def _add_loop_vertex(g: HostGraph, sk: Skeleton, poly: np.ndarray, faces, i: int) -> int:
    """A LoopVertex at ``poly[i]`` whose dual is the nearest boundary point of its face on each side."""
    p = poly[i]
    d = poly[min(i + 1, len(poly) - 1)] - poly[max(i - 1, 0)]
    tri = sk.triangulation
    verts = tri.triangles[faces[i]]
    rel = tri.points[verts] - p
    side = np.sign(d[0] * rel[:, 1] - d[1] * rel[:, 0])
    along = np.abs(rel @ d)
    n = g.add_node(LOOP_VERTEX, {"pos": tuple(p), "radius": float(np.linalg.norm(rel, axis=1).max())})
    for s in (1, -1):
        candidates = np.flatnonzero(side == s)
        if len(candidates) == 0:
            raise DomainError(f"cannot cut the skeleton loop at {fmt_point(p)}; use a smaller spacing")
        g.add_edge(DUAL, n, int(verts[candidates[np.argmin(along[candidates])]]))
    return n


def _plain_attrs(attrs, origin=NO_ORIGIN) -> dict:
    """Node attributes for JSON: tuples (positions) as lists, in the frame of the plan (``origin`` added)."""
    moved = origin != NO_ORIGIN
    return {k: (to_plan(v, origin).tolist() if moved else list(v)) if isinstance(v, tuple) else v
            for k, v in attrs.items()}


def _plain(poly: np.ndarray) -> tuple:
    """A polyline as a graph attribute: a tuple of (x, y) float pairs."""
    return tuple((float(x), float(y)) for x, y in poly)


def add_patch_nodes(graph: HostGraph, patches) -> tuple[list[int], list[int]]:
    """Make the patches visible to rules: a ``Patch`` node each, ``PatchCorner`` edges to its corners.
    Returns the ids of the nodes and the edges added (for the trace)."""
    nodes, edges = [], []
    for patch in patches:
        p = graph.add_node(PATCH, {"sides": patch.n_sides})
        nodes.append(p)
        for k, c in enumerate(patch.corners):
            edges.append(graph.add_edge(PATCH_CORNER, p, c, {"index": k}))
    return nodes, edges


def check_patch_nodes(graph: HostGraph, patches) -> None:
    """The patching rules must keep the patch nodes in step with the faces of the plan."""
    nodes = sorted(
        sorted(graph.ends(e)[1] for e in graph.incident(p, [PATCH_CORNER]))
        for p in graph.nodes() if graph.node_type(p) == PATCH
    )
    faces = sorted(sorted(patch.corners) for patch in patches)
    if nodes != faces:  # a fault of the rules, not of the domain
        raise RewriteError(
            f"after the patching rules the graph has {len(nodes)} patch nodes but the plan has {len(faces)} "
            "patches with other corners: a patching rule must replace the Patch nodes it splits"
        )


def patch_strategies_of(rulebook: Rulebook) -> list[str]:
    """The patching strategies the rulebook has (:data:`PATCH_STRATEGIES`, in their order)."""
    return [name for name in PATCH_STRATEGIES if name in rulebook.strategies]


def start_patching(graph: HostGraph, disc: Discretisation, trace, patching: bool) -> None:
    """Between the topology strategy and the patching ones: the faces of the plan become ``Patch``
    nodes (recorded in ``trace`` as a host edit, for replay); nothing when the rulebook has no
    patching strategies (``patching`` false), whose faces are only checked at the end."""
    if not patching:
        return
    added = add_patch_nodes(graph, find_patches(graph, disc, PLAN_EDGES, strict=False))
    part = graph.to_json()
    trace.record_edit(*([x for x in part[kind] if x["id"] in set(ids)] for kind, ids in zip(("nodes", "edges"), added)))


def final_patches(graph: HostGraph, disc: Discretisation, patching: bool) -> list[Patch]:
    """The patches of the rewritten plan, checked: 3 or 4 sides each, in step with the ``Patch``
    nodes (when the rulebook patches), and no hole inside one."""
    patches = find_patches(graph, disc, PLAN_EDGES)
    if patching:
        check_patch_nodes(graph, patches)
    check_no_enclosed_holes(graph, patches)
    return patches


def block_decomposition(sk: Skeleton, rulebook: Rulebook, check_invariants: bool = False,
                        trace: bool = False, chooser: Chooser = first_option) -> Decomposition:
    """The block decomposition of a skeleton by the rulebook (§3.1 pruning and rebranching, §4).

    The rulebook's ``topology`` strategy rewrites the skeleton graph (:func:`decomposition_graph`);
    the faces it leaves become ``Patch`` nodes and the ``curve_patching`` and ``patching`` strategies
    (when the rulebook has them) may split them (curve T-junctions, Figures 4 and 8); the patches are
    then read off the faces again, and must all have 3 or 4 sides and enclose no hole (whatever the
    rules did). ``check_invariants`` checks the rulebook's invariants while its strategies run
    (:mod:`vaultgram.engine.invariants`; ``vaultgram rules test`` does); ``trace`` keeps the graph
    the rules start from (``start_graph``, graph JSON) for ``vaultgram rules replay``.

    Example
    -------
    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.topology.discretise import discretise
    >>> from vaultgram.topology.rulebook import load_vault_rulebook
    >>> from vaultgram.topology.skeleton import skeleton
    >>> from vaultgram.topology.triangulation import triangulate
    >>> sk = skeleton(triangulate(discretise(load_domain("examples/l_shape.json"), 0.05)))  # 3 rectangles (corners.vgr)
    >>> dec = block_decomposition(sk, load_vault_rulebook())
    >>> dec.patches_json()["counts"], [dec.valence(s) for s in dec.singularities()]
    ({'3': 0, '4': 3}, [])
    """
    disc = sk.triangulation.disc
    graph = decomposition_graph(sk, rulebook)
    start = graph.to_json() if trace else None
    runner = Runner(rulebook, graph, chooser, check_invariants=check_invariants)
    runner.run(TOPOLOGY_STRATEGY)
    patch_strategies = patch_strategies_of(rulebook)
    start_patching(graph, disc, runner.trace, bool(patch_strategies))
    for name in patch_strategies:
        runner.run(name)
    patches = final_patches(graph, disc, bool(patch_strategies))
    reports = tuple(RuleStep(r.step, r.applications) for r in runner.reports)
    return Decomposition(disc, sk, graph, tuple(patches), reports, runner.trace.to_json(), runner.invariant_checks,
                         start)
