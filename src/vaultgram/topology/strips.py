"""Strips of quads across the patch layout: the helpers of ``rules/strips.vgr``.

A *strip insertion* (the chord that inserts a row of quads, and the paper's Figure 8 split of a
quad at a curve extremity to the midpoint of the opposite side, §4.2) puts a new corner in the
middle of a side. Where that side is shared with a neighbouring patch, the new corner is a
T-junction there: the neighbour must be split too, from the new corner to the middle of its
opposite side, and so on across quads until the strip reaches the boundary, ends in a triangle
(split to its opposite corner) or closes on itself. The rules do the rewriting one patch at a time;
the functions here let them start a strip only where it certainly completes as a valid layout
(:func:`strip_start`, :func:`strip_from_curve_end`): they walk it first across the patches it
would cross, and refuse it where it would meet a patch that is no quad or triangle, a side it
cannot split (a curve, a boundary stretch of several edges without a free point, a side of several edges), the
same patch twice, or a chord that would leave its patch. The engine knows nothing of this; the
vault pipeline registers the functions (:mod:`vaultgram.topology.functions`).
"""

from __future__ import annotations

import weakref
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np
import shapely

from vaultgram.geometry.polygons import interior_angle
from vaultgram.geometry.polylines import arc_lengths, point_at_length
from vaultgram.topology.patches import (
    FaceOutline,
    face_from,
    face_outline,
    half_edge_key,
    half_edge_polyline,
    kept_at_node,
    key_polyline,
)
from vaultgram.topology.statecache import by_content, per_state
from vaultgram.topology.types import (
    BOUNDARY,
    BOUNDARY_VERTEX,
    BRANCH,
    CORNER,
    DIAGONAL,
    PATCH_CORNER,
    PLAN_EDGES,
    REBRANCH,
)

__all__ = ["SPLITTABLE", "PatchSides", "patch_sides", "side_edge", "corner_chord_angle", "strip_point",
           "strip_piece", "strip_piece_to", "side_through", "strip_boundary_end", "strip_boundary_split", "Walk",
           "strip_walk", "strip_through", "strip_start", "strip_from_curve_end", "register_strip_helpers",
           "edge_halves", "strip_fraction", "cut_along", "chord_inside", "patch_across"]

#: The plan edges a strip may cut in two (not a curve feature: the layout must not cross it, §4.2;
#: not the boundary, which a strip ends at, at one of its points): the types of ``rules/schema.vgr``'s
#: ``Splittable``, whose ``foot`` holds where a strip cuts them (:func:`strip_fraction`).
SPLITTABLE = (BRANCH, REBRANCH, DIAGONAL)


@dataclass(frozen=True)
class PatchSides:
    """A Patch node's corners by index and its sides: side ``k`` is the list of half-edges
    ``(edge, start node)`` from corner ``k`` to corner ``k + 1``, counter-clockwise; ``face`` the
    outline of the face (:func:`~vaultgram.topology.patches.face_outline`, shared by every state
    with that face, with its prepared polygon for the chords' containment tests)."""

    corners: tuple
    sides: tuple
    face: FaceOutline

    @property
    def polygon(self) -> shapely.Polygon:
        """The face's outline as a prepared shapely polygon (made once for all states with it)."""
        return self.face.polygon


_STATE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: {key: value}}


def _memo(graph) -> dict:
    """What the helpers worked out in this state of the graph (:mod:`vaultgram.topology.statecache`):
    the rules ask for the same sides and strips in every match they try."""
    return per_state(_STATE, graph, lambda g: {})


#: The lists to which :func:`patch_sides` adds each patch it is asked for and its sides, while a result
#: kept by its footprint is worked out (:func:`vaultgram.topology.reflex.choose_chord`'s, kept while those
#: patches are untouched: :class:`~vaultgram.topology.statecache.Untouched`).
READS: list = []


def patch_sides(graph, patch: int) -> PatchSides | None:
    """The sides of a Patch node (once per state of the graph); None if no face of the plan at its
    first corner has all its corners (a Patch node out of step with the plan)."""
    memo = _memo(graph)
    key = ("sides", patch)
    if key not in memo:
        memo[key] = _walk_sides(graph, patch)
    for read in READS:
        read.append((patch, memo[key]))
    return memo[key]


def _walk_sides(graph, patch: int) -> PatchSides | None:
    """:func:`patch_sides`, kept across the states with the same faces at the first corner
    (:func:`~vaultgram.topology.patches.kept_at_node`)."""
    by_index = sorted((graph.get_edge(e, "index"), graph.ends(e)[1]) for e in graph.incident(patch, [PATCH_CORNER]))
    corners = tuple(c for _, c in by_index)
    if not corners:
        return None
    return kept_at_node(graph, PLAN_EDGES, corners[0], ("sides", corners),
                        lambda look: _find_sides(graph, corners, look))


def _find_sides(graph, corners: tuple, look) -> PatchSides | None:
    for first in graph.rotation(corners[0]):
        if graph.edge_type(first) not in PLAN_EDGES:
            continue
        look((first, corners[0]))
        face = face_from(graph, PLAN_EDGES, (first, corners[0]))
        nodes = [u for _, u in face]
        if not set(corners) <= set(nodes):
            continue
        found = face_outline(graph, PLAN_EDGES, face)
        if found.closed_area <= 0:
            continue
        starts = [nodes.index(c) for c in corners] + [len(face)]
        if starts != sorted(starts):
            return None
        return PatchSides(corners, tuple(tuple(face[a:b]) for a, b in zip(starts, starts[1:])), found)
    return None


def side_edge(graph, patch: int, corner: int) -> int:
    """The plan edge that is the whole side of a Patch node from its corner ``corner``, when a strip
    may cut it (one edge of :data:`SPLITTABLE`); -1 otherwise."""
    found = patch_sides(graph, patch)
    if found is None or corner not in found.corners:
        return -1
    side = found.sides[found.corners.index(corner)]
    return side[0][0] if len(side) == 1 and graph.edge_type(side[0][0]) in SPLITTABLE else -1


def corner_chord_angle(graph, patch: int, x: int) -> float:
    """The interior angle (degrees) of a Patch node at its corner ``x`` between the chords to its two
    neighbouring corners (as split_quad_at_curve_end measures it); NaN if ``x`` is not a corner."""
    found = patch_sides(graph, patch)
    if found is None or x not in found.corners:
        return float("nan")
    k, n = found.corners.index(x), len(found.corners)
    before, after = found.corners[(k - 1) % n], found.corners[(k + 1) % n]
    return interior_angle(graph.get(before, "pos"), graph.get(x, "pos"), graph.get(after, "pos"))


#: The edges cut kept (the most recently asked) by :func:`edge_cut`.
CUTS = 1024
_CUTS: OrderedDict = OrderedDict()


def edge_cut(graph, edge: int, fraction: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An edge's polyline (from its source) cut at ``fraction`` of its length (:func:`cut_along`): the
    piece before, the point, the piece after (read-only arrays). Kept by what the edge's points are
    made of (:func:`~vaultgram.topology.patches.half_edge_key`) and the fraction, so every state of
    the search with that edge finds it (issue 13), and the reflex corners' chords, which try the
    same feet of an edge in every state the rules pass through (:mod:`vaultgram.topology.reflex`),
    cut it once."""
    key = (half_edge_key(graph, edge, graph.ends(edge)[0]), fraction)
    return by_content(_CUTS, key, lambda: cut_along(key_polyline(key[0]), fraction), CUTS)


def edge_halves(graph, edge: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An edge's polyline (from its source) cut at half its length (:func:`edge_cut`)."""
    return edge_cut(graph, edge, 0.5)


def cut_along(pts: np.ndarray, fraction: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An open polyline cut at ``fraction`` (0 to 1) of its length: the piece before, the point, the
    piece after (the point is in neither; read-only arrays).

    >>> [a.tolist() for a in cut_along(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]]), 0.25)]
    [[[0.0, 0.0]], [1.0, 0.0], [[2.0, 0.0], [2.0, 2.0]]]
    """
    s = arc_lengths(pts)
    at = s[-1] * fraction
    mid = point_at_length(pts, at)
    j = int(np.searchsorted(s, at, side="left"))
    after = j + int(bool(np.allclose(pts[j], mid)))
    halves = pts[:j], mid, pts[after:]
    for array in halves:
        array.flags.writeable = False  # shared by every state with this edge (see edge_halves)
    return halves


def strip_point(graph, edge: int) -> tuple[float, float]:
    """Where a strip cuts a plan edge: at :func:`strip_fraction` of its length (halfway, but where a
    rule placed the edge's foot elsewhere)."""
    mid = edge_cut(graph, edge, strip_fraction(graph, edge))[1]
    return float(mid[0]), float(mid[1])


def strip_fraction(graph, edge: int) -> float:
    """The fraction of the plan edge ``edge``'s length (from its source) where a strip cuts it: the
    edge's ``foot`` (``rules/schema.vgr``, the type ``Splittable``), the middle unless
    ``rules/strips.vgr``' ``place_fan_foot`` moved it to where the strip's last chord halves a point
    feature's fan triangle (:func:`vaultgram.topology.reflex.fan_foot`, §4.1); the middle of an edge of
    another type (a boundary edge a strip splits, :func:`strip_boundary_split`). Data of the edge, not
    worked out from the layout round it: the walk that checks a strip (:func:`strip_walk`), the rule
    that cuts the edge and both pieces it makes (:func:`strip_piece`, each asked in its own state of
    the graph) read the same fraction, whatever changed round the edge meanwhile."""
    return float(graph.get_edge(edge, "foot")) if graph.edge_type(edge) in SPLITTABLE else 0.5


def strip_piece(graph, edge: int, end: int) -> tuple:
    """The part of a plan edge from its end ``end`` to the strip point (:func:`strip_point`), as a
    polyline."""
    before, mid, after = edge_cut(graph, edge, strip_fraction(graph, edge))
    piece = np.vstack([before, mid[None]]) if graph.ends(edge)[0] == end else np.vstack([after[::-1], mid[None]])
    return tuple((float(x), float(y)) for x, y in piece)


def strip_piece_to(graph, edge: int, point, end: int) -> tuple:
    """The part of a plan edge from its end ``end`` to ``point``, a point on it (a chord's foot that is
    not the middle: :func:`vaultgram.topology.reflex.reflex_point`), as a polyline: the edge's points
    up to the segment ``point`` lies on (the nearest), then ``point``."""
    pts = half_edge_polyline(graph, edge, end)
    q = np.asarray(point, dtype=float)
    a, b = pts[:-1], pts[1:]
    d = b - a
    t = np.clip(((q - a) * d).sum(axis=1) / np.maximum((d * d).sum(axis=1), 1e-300), 0.0, 1.0)
    j = int(np.argmin(np.hypot(*(a + t[:, None] * d - q).T)))
    head = pts[:j + 1] if not np.allclose(pts[j], q) or j == 0 else pts[:j]
    return tuple((float(x), float(y)) for x, y in np.vstack([head, q[None]]))


def side_through(graph, patch: int, corner: int, m: int) -> bool:
    """Whether the side of a Patch node from its corner ``corner`` is two plan edges meeting at
    ``m``: a strip point that the patch does not have as a corner yet."""
    found = patch_sides(graph, patch)
    if found is None or corner not in found.corners:
        return False
    side = found.sides[found.corners.index(corner)]
    return len(side) == 2 and side[1][1] == m


def strip_boundary_end(graph, patch: int, corner: int) -> int:
    """The point where a strip ends on a boundary side of a Patch node (the side from ``corner``, all
    boundary pieces): the free boundary point nearest its middle by arc length (no patch's corner, no
    feature, no polygon corner), or ``corner`` itself where there is none or the side is not on the
    boundary. Once per state of the graph (``end_strip_at_boundary`` asks it for every boundary point
    it tries as the end)."""
    memo = _memo(graph)
    if ("end", patch, corner) not in memo:
        memo[("end", patch, corner)] = _boundary_end(graph, patch, corner)
    return memo[("end", patch, corner)]


def _boundary_end(graph, patch: int, corner: int) -> int:
    """:func:`strip_boundary_end`, worked out."""
    found = patch_sides(graph, patch)
    if found is None or corner not in found.corners:
        return corner
    side = found.sides[found.corners.index(corner)]
    if any(graph.edge_type(e) != BOUNDARY for e, _ in side):
        return corner
    pieces = [half_edge_polyline(graph, e, u) for e, u in side]
    at = np.concatenate([[0.0], np.cumsum([arc_lengths(piece)[-1] for piece in pieces])])
    inner = [(abs(at[k] - at[-1] / 2), u) for k, (_, u) in enumerate(side) if k > 0 and _free_boundary_point(graph, u)]
    return min(inner)[1] if inner else corner


def strip_boundary_split(graph, patch: int, corner: int) -> int:
    """The boundary edge a strip splits at its middle to end there, where the side of the Patch node
    ``patch`` from ``corner`` is that one boundary edge (both its points patch corners already: no free
    point inside the side for :func:`strip_boundary_end`); -1 otherwise. The strip's chord then ends
    at a new boundary point of 180 degrees with two faces, regular (§4.2's strip reaches the boundary
    as anywhere else): saved random plans 456-458 (an octagonal hole's 225 degree corner inside a
    ring patch's side), whose cut's strip crossed one quad to a 0.57 long boundary edge between two
    other strips' ends and was refused, the corner left with two faces. Only the walks of a hole
    corner's cut ask for it (:func:`strip_walk`'s ``split``,
    :func:`vaultgram.topology.reflex.cut_walk`): allowed for every strip walk (the chords of corners of
    two patches, Figure 8's and the lone corners' strips too), it changed jagged_1's layout (three patch
    corners past straight for two, worst scaled Jacobian 0.061 -> 0.043)."""
    found = patch_sides(graph, patch)
    if found is None or corner not in found.corners:
        return -1
    side = found.sides[found.corners.index(corner)]
    return side[0][0] if len(side) == 1 and graph.edge_type(side[0][0]) == BOUNDARY else -1


def _free_boundary_point(graph, n: int) -> bool:
    return (graph.schema.is_subtype(graph.node_type(n), BOUNDARY_VERTEX) and graph.node_type(n) != CORNER
            and not graph.get(n, "feature") and graph.degree(n, [PATCH_CORNER]) == 0
            and graph.degree(n, PLAN_EDGES) == 2)


def chord_inside(found: PatchSides, a, b) -> bool:
    """Whether the straight chord from ``a`` to ``b`` (points of the outline) runs inside the patch,
    touching its outline only at its ends."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    d = (b - a) * 1e-6
    return bool(shapely.contains_properly(found.polygon, shapely.LineString([a + d, b - d])))


def patch_across(graph, patch: int, edge: int) -> tuple[int, int] | None:
    """The Patch node on the other side of a plan edge that is a whole side of ``patch``, and the
    index of that side there; None where there is none (or more than one)."""
    found = [(q, k) for q in _patches_at(graph, graph.ends(edge)[0]) if q != patch
             for sides in (patch_sides(graph, q),) if sides
             for k, side in enumerate(sides.sides) if len(side) == 1 and side[0][0] == edge]
    return found[0] if len(found) == 1 else None


def _patches_at(graph, n: int) -> list:
    return sorted({graph.ends(e)[0] for e in graph.incident(n, [PATCH_CORNER])})


@dataclass(frozen=True)
class Walk:
    """The patches a strip crosses from one side on (in order), the plan edges it cuts on the way
    (the entry edge first), and where it ends: the corner of a triangle opposite the strip, a
    boundary point, or None when it came back to its entry edge (a closed strip). Where it ends on a
    boundary side that is one boundary edge with no free point (:func:`strip_boundary_split`),
    ``split`` is that edge, cut at its middle by a new boundary point, and ``end`` the quad's corner
    where the side starts; -1 otherwise."""

    patches: tuple
    edges: tuple
    end: int | None
    split: int = -1

    def end_point(self, graph) -> tuple:
        """Where the strip ends: the middle of the split boundary edge, else the end's position."""
        return strip_point(graph, self.split) if self.split >= 0 else graph.get(self.end, "pos")

    @property
    def closed(self) -> bool:
        return self.end is None


def strip_walk(graph, patch: int, k: int, seen: frozenset = frozenset(), split: bool = False) -> Walk | None:
    """The strip that enters ``patch`` through the middle of its side ``k`` (a plan edge it may cut),
    walked on: across a quad to the middle of its opposite side, into the patch beyond, until it
    ends on the boundary (at a free point of a boundary side; with ``split``, also at the middle of a
    boundary side that is one boundary edge: :func:`strip_boundary_split`), in a triangle (at its
    corner opposite the entry), or back at its entry edge. None where it cannot: a patch that is no
    quad or triangle, a side it may not cut, a patch twice (or one of ``seen``), a chord that leaves
    its patch.
    """
    entry = side_edge(graph, patch, patch_sides(graph, patch).corners[k]) if patch_sides(graph, patch) else -1
    patches, edges = [], [entry]
    while True:
        found = patch_sides(graph, patch)
        if entry < 0 or found is None or patch in patches or patch in seen or len(found.corners) not in (3, 4):
            return None
        patches.append(patch)
        here = strip_point(graph, entry)
        out = found.corners[(k + 2) % len(found.corners)]
        nxt = side_edge(graph, patch, out) if len(found.corners) == 4 else -1
        if nxt < 0:  # the end: the triangle's corner opposite the strip, or a point of a boundary side
            end = out if len(found.corners) == 3 else strip_boundary_end(graph, patch, out)
            cut = strip_boundary_split(graph, patch, out) if split and end == out and len(found.corners) == 4 else -1
            walk = Walk(tuple(patches), tuple(edges), end, cut)
            ok = end != out or len(found.corners) == 3 or cut >= 0
            return walk if ok and chord_inside(found, here, walk.end_point(graph)) else None
        if not chord_inside(found, here, strip_point(graph, nxt)):
            return None
        if nxt == edges[0]:
            return Walk(tuple(patches), tuple(edges), None)
        edges.append(nxt)
        beyond = patch_across(graph, patch, nxt)
        patch, k, entry = (beyond[0], beyond[1], nxt) if beyond else (patch, k, -1)


def strip_through(graph, patch: int, corner: int, edge: int) -> tuple[Walk, Walk] | None:
    """The strip through the plan edge ``edge``, the side of ``patch`` from its corner ``corner``:
    its walks into ``patch`` and into the patch beyond (the same walk twice for a closed strip), or
    None where one does not complete or the two cross a patch twice."""
    found = patch_sides(graph, patch)
    if side_edge(graph, patch, corner) != edge:
        return None
    beyond = patch_across(graph, patch, edge)
    one = strip_walk(graph, patch, found.corners.index(corner)) if beyond else None
    if one is None:
        return None
    two = one if one.closed else strip_walk(graph, beyond[0], beyond[1], frozenset(one.patches))
    return None if two is None else (one, two)


def strip_start(graph, patch: int, corner: int, edge: int) -> bool:
    """Whether a strip may start at the plan edge ``edge``, the side of ``patch`` from its corner
    ``corner`` (:func:`strip_through`): it completes, crosses at least one quad, and this is the
    strip's one start (its cut edge of the smallest id, from the patch on the left of that edge
    walked from its source), so that each strip is offered once. A strip is walked once per state:
    what it is is kept for every edge it cuts."""
    if graph.ends(edge)[0] != corner or side_edge(graph, patch, corner) != edge:
        return False
    memo = _memo(graph)
    if ("strip", edge) not in memo:
        walks = strip_through(graph, patch, corner, edge)
        memo[("strip", edge)] = None
        if walks is not None:
            edges = set(walks[0].edges) | set(walks[1].edges)
            quads = any(len(patch_sides(graph, p).corners) == 4 for w in walks for p in w.patches)
            memo.update({("strip", e): min(edges) if quads else None for e in edges})
    return memo[("strip", edge)] == edge


def strip_from_curve_end(graph, patch: int, x: int, edge: int) -> bool:
    """Whether the quad ``patch`` may be split from its corner ``x`` (a curve extremity) to the middle
    of its side ``edge`` (Figure 8, §4.2): the chord runs inside the quad, and the strip that the new
    corner starts in the patch beyond completes (:func:`strip_walk`)."""
    found = patch_sides(graph, patch)
    if found is None or edge < 0 or x not in found.corners:
        return False
    beyond = patch_across(graph, patch, edge)
    return (beyond is not None and chord_inside(found, graph.get(x, "pos"), strip_point(graph, edge))
            and strip_walk(graph, beyond[0], beyond[1], frozenset([patch])) is not None)


def register_strip_helpers(f) -> None:
    """Register the strip helpers with a function registry (``rules/strips.vgr`` calls them)."""
    for name, fn, params, returns in (
            ("side_edge", side_edge, ("node", "node"), "edge"),
            ("side_through", side_through, ("node", "node", "node"), "bool"),
            ("corner_chord_angle", corner_chord_angle, ("node", "node"), "float"),
            ("strip_point", strip_point, ("edge",), "vec2"),
            ("strip_piece", strip_piece, ("edge", "node"), "list"),
            ("strip_piece_to", strip_piece_to, ("edge", "vec2", "node"), "list"),
            ("strip_boundary_end", strip_boundary_end, ("node", "node"), "node"),
            ("strip_boundary_split", strip_boundary_split, ("node", "node"), "edge"),
            ("strip_start", strip_start, ("node", "node", "edge"), "bool"),
            ("strip_from_curve_end", strip_from_curve_end, ("node", "node", "edge"), "bool")):
        f.register(name, fn, params, returns, uses_graph=True, local=False)
