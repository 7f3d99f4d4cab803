"""The geometric helper functions the vault pipeline registers for its rules (§3.1, §4).

The engine knows nothing about vaults or geometry; rules in ``rules/`` may call these by name
(``docs/rulebook.md`` lists them). The point functions are pure and local (they read only their
arguments), so rules using them re-match incrementally; the curve and patch functions read the
graph beyond their arguments' incident edges (along a curve feature, around a patch) and are
registered non-local. None of them changes the graph.
"""

from __future__ import annotations

import math
import weakref
from collections import OrderedDict

import numpy as np
import shapely

from vaultgram.engine.expressions import Functions
from vaultgram.errors import RuleError
from vaultgram.geometry.polygons import interior_angle, regular_valence, signed_area
from vaultgram.geometry.polylines import arc_lengths, point_at_length, turning_angles
from vaultgram.topology import corners, fans, reflex
from vaultgram.topology.corner_merges import register_corner_merge_helpers
from vaultgram.topology.hole_fans import register_hole_fan_helpers
from vaultgram.topology.hole_hub import register_hole_hub_helpers
from vaultgram.topology.hole_rebranch import register_hole_rebranch_helpers
from vaultgram.topology.hole_sides import register_hole_side_helpers
from vaultgram.topology.hole_triangles import register_hole_triangle_helpers
from vaultgram.topology.lone_branch import register_lone_branch_helpers
from vaultgram.topology.lone_corners import register_lone_corner_helpers
from vaultgram.topology.ogrid import register_o_grid_helpers
from vaultgram.topology.patches import (
    enclosed_holes,
    face_from,
    face_outline,
    half_edge_key,
    half_edge_polyline,
    hole_rings,
    kept_at_node,
    key_polyline,
    plan_faces,
)
from vaultgram.topology.statecache import by_content, per_state
from vaultgram.topology.strips import register_strip_helpers
from vaultgram.topology.types import BOUNDARY_VERTEX, CURVE, CURVE_POINT, DUAL, PATCH_CORNER, PLAN_EDGES

__all__ = ["vault_functions", "distance", "midpoint", "lerp", "move_end", "move_branch_end", "angle_between",
           "curve_side", "curve_turn",
           "curve_neighbours", "patch_corner", "patch_in_plan", "patch_chains", "patch_side_starts", "patch_angle",
           "patch_angle_split", "diagonal_side_angle", "fan_clear",
           "diagonal_path", "bend_first",
           "path_clear", "plan_area", "domain_area", "plan_euler", "hole_count", "holes_enclosed",
           "curve_crossings", "plan_crossings"]


def distance(p, q) -> float:
    """The distance between two points.

    >>> distance((0, 0), (3, 4))
    5.0
    """
    return math.dist(p, q)


def midpoint(p, q) -> tuple[float, ...]:
    """The point halfway between two points.

    >>> midpoint((0, 0), (3, 4))
    (1.5, 2.0)
    """
    return tuple((a + b) / 2 for a, b in zip(p, q))


def lerp(p, q, t) -> tuple[float, ...]:
    """The point ``p + t (q - p)``: ``p`` at 0, ``q`` at 1.

    >>> lerp((0, 0), (4, 2), 0.25)
    (1.0, 0.5)
    """
    return tuple(a + (b - a) * t for a, b in zip(p, q))


def move_end(polyline, old, new) -> tuple:
    """``polyline`` with the end point that lies at ``old`` moved to ``new`` (the nearer end).

    >>> move_end([(0, 0), (1, 0), (2, 0)], (2, 0), (2, 1))
    ((0, 0), (1, 0), (2, 1))
    """
    points = [tuple(p) for p in polyline]
    if len(points) < 2:
        return tuple(points)
    k = 0 if math.dist(points[0], old) <= math.dist(points[-1], old) else -1
    points[k] = tuple(new)
    return tuple(points)


def move_branch_end(graph, polyline, old, new, s: int, t: int) -> tuple:
    """:func:`move_end` for a branch of skeleton vertices ``s`` and ``t`` being merged at ``new``, its
    points next to the moved end dropped where they hook round a radius of the merged circle (from
    ``new`` to a point either circle touches: what the rebranching rule draws, Figure 2e) -- the
    junction the merge collapses -- down to the straight segment to the branch's other end; with no
    hook, exactly ``move_end``."""
    moved = move_end(polyline, old, new)
    ends = [graph.get(graph.ends(e)[1], "pos") for n in (s, t) for e in graph.incident(n, [DUAL])]
    if len(moved) < 3 or not ends:
        return moved
    start = np.repeat(np.asarray([new], dtype=float), len(ends), axis=0)
    end = np.asarray(ends, dtype=float)
    points = np.asarray(moved, dtype=float)
    at_start = math.dist(points[0], new) <= math.dist(points[-1], new)
    points = points if at_start else points[::-1]
    if _clear(points, start, end):
        return moved
    for k in range(2, len(points)):
        candidate = np.vstack([points[:1], points[k:]])
        if _clear(candidate, start, end):
            return _points(candidate if at_start else candidate[::-1])
    return moved


def angle_between(p, centre, q) -> float:
    """The angle p-centre-q in degrees, in [0, 180].

    >>> angle_between((1, 0), (0, 0), (0, -1))
    90.0
    """
    a = math.atan2(p[1] - centre[1], p[0] - centre[0])
    b = math.atan2(q[1] - centre[1], q[0] - centre[0])
    d = abs(a - b) % (2 * math.pi)
    return math.degrees(min(d, 2 * math.pi - d))


def curve_side(graph, p: int) -> int:
    """Which side of its curve the plan edges at curve point ``p`` arrive from (§4.2 T-junctions).

    +1: all from the left of the curve's direction (from its first point to its last), -1: all from
    the right, 0: from both sides, from neither, or ``p`` is not an inner point of a curve.
    """
    rotation = [e for e in graph.rotation(p) if graph.edge_type(e) in PLAN_EDGES]
    curve = [e for e in rotation if graph.edge_type(e) == CURVE]
    if len(curve) != 2 or len(rotation) == 2:
        return 0
    # curve edges are created along the curve, from its first point towards its last
    ahead = next((e for e in curve if graph.ends(e)[0] == p), None)
    if ahead is None:
        return 0
    k = rotation.index(ahead)
    turn = rotation[k:] + rotation[:k]  # counter-clockwise from the direction of travel
    back = turn.index(next(e for e in curve if e != ahead))
    left, right = back - 1, len(turn) - back - 1
    return 1 if right == 0 else -1 if left == 0 else 0


#: Degrees: a turn this small is straight on (the discretisation's rounding along a straight piece).
_STRAIGHT_TURN = math.degrees(1e-9)


def curve_turn(graph, x: int) -> int:
    """Which way its curve turns at the inner curve point ``x`` (§4.2), travelling from the curve's
    first point towards its last: +1 left (counter-clockwise), -1 right, 0 straight on (to rounding)
    or ``x`` not an inner point of a curve. A bend's reflex side is the one it does not turn
    towards: a T-junction arriving from side ``s`` (:func:`curve_side`) sees the bend ``x`` as
    reflex when ``curve_turn(x) == -s``.
    """
    curve = list(graph.incident(x, [CURVE]))
    ahead = [e for e in curve if graph.ends(e)[0] == x]
    behind = [e for e in curve if graph.ends(e)[1] == x]
    if len(curve) != 2 or len(ahead) != 1 or len(behind) != 1:
        return 0
    pts = np.array([graph.get(n, "pos") for n in (graph.ends(behind[0])[0], x, graph.ends(ahead[0])[1])], dtype=float)
    turn = float(turning_angles(pts, closed=False)[1])
    return 0 if abs(turn) <= _STRAIGHT_TURN else 1 if turn > 0 else -1



def curve_neighbours(graph, p: int, q: int) -> bool:
    """Whether ``q`` is reached from ``p`` along the curve through points where nothing else arrives."""
    for first in [e for e in graph.incident(p, [CURVE])]:
        prev, node = p, graph.other(first, p)
        while node != q and graph.degree(node, PLAN_EDGES) == 2 and not graph.get(node, "corner"):
            nxt = [e for e in graph.incident(node, [CURVE]) if graph.other(e, node) != prev]
            if not nxt:
                break
            prev, node = node, graph.other(nxt[0], node)
        if node == q:
            return True
    return False


def patch_corner(graph, patch: int, index: int) -> int:
    """The corner of a Patch node with the given index (its PatchCorner edge's ``index``).

    Raises
    ------
    RuleError
        If the patch has no corner with that index: the rule asked for it.
    """
    for e in graph.incident(patch, [PATCH_CORNER]):
        if graph.get_edge(e, "index") == index:
            return graph.ends(e)[1]
    raise RuleError(f"patch {patch} has no corner {index}")


def _patch_outline(graph, patch: int, x: int) -> tuple[list, np.ndarray, tuple] | None:
    """The face of the plan around a Patch node, walked from its corner ``x``: its half-edges, its
    closed outline (first point = last point = ``x``, read-only) and where each half-edge starts
    along it (:attr:`~.patches.FaceOutline.starts`); None if no face at ``x`` has all the
    patch's corners (a Patch node out of step with the plan, which decompose reports at the end). Only
    the faces at ``x`` are walked, once per state of the graph (the rules ask for the same outlines
    in every match they try)."""
    outlines = per_state(_OUTLINES, graph, lambda g: {})
    if (patch, x) not in outlines:
        outlines[(patch, x)] = _walk_patch_outline(graph, patch, x)
    return outlines[(patch, x)]


def _walk_patch_outline(graph, patch: int, x: int) -> tuple[list, np.ndarray, tuple] | None:
    """:func:`_patch_outline`, kept across the states with the same faces at ``x``
    (:func:`~vaultgram.topology.patches.kept_at_node`)."""
    corners = frozenset(graph.ends(e)[1] for e in graph.incident(patch, [PATCH_CORNER]))
    return kept_at_node(graph, PLAN_EDGES, x, ("outline", corners),
                        lambda look: _find_outline(graph, corners, x, look))


def _find_outline(graph, corners: frozenset, x: int, look) -> tuple[list, np.ndarray, tuple] | None:
    for first in graph.rotation(x):
        if graph.edge_type(first) not in PLAN_EDGES:
            continue
        look((first, x))
        face = face_from(graph, PLAN_EDGES, (first, x))
        if not corners <= {u for _, u in face}:
            continue
        found = face_outline(graph, PLAN_EDGES, face)  # kept with the face, and by content (issue 13)
        if found.closed_area > 0:
            return face, found.closed, found.starts
    return None


def patch_in_plan(graph, patch: int) -> bool:
    """Whether a Patch node is a face of the plan: some face at its first corner has all its corners
    (a rule that splits or merges patches must keep the Patch nodes in step with the faces)."""
    corners = [graph.ends(e)[1] for e in sorted(graph.incident(patch, [PATCH_CORNER]))]
    return bool(corners) and _patch_outline(graph, patch, corners[0]) is not None


def patch_chains(graph, patch: int, x: int, o: int) -> tuple[np.ndarray, np.ndarray] | None:
    """The outline of a Patch node split at its corners ``x`` and ``o``: the chain from ``x`` to ``o``
    counter-clockwise (through the corners after ``x``) and the one clockwise (through those before);
    None if the patch is not a face of the plan."""
    found = _patch_outline(graph, patch, x)
    if found is None:
        return None
    outline, at = found[1], _point_of(found, o)
    return outline[: at + 1], outline[at:][::-1]


def _point_of(found: tuple, o: int) -> int:
    """The index in a face's outline (:func:`_patch_outline`'s) of its node ``o``'s point."""
    face, _, starts = found
    return starts[[u for _, u in face].index(o)]


def patch_side_starts(graph, patch: int, x: int, y: int) -> bool:
    """Whether the outline of a Patch node, walked counter-clockwise from its corner ``x``, goes to
    ``y`` first (``y`` a neighbour of ``x``, e.g. the next point of a boundary side)."""
    found = _patch_outline(graph, patch, x)
    return found is not None and graph.other(found[0][0][0], x) == y


def patch_angle(graph, patch: int, x: int) -> float:
    """The interior angle (degrees) of a Patch node at its corner ``x``, between the directions in
    which its two sides leave ``x`` (not the chords to the neighbouring corners: sides may curve);
    NaN (every comparison false) if the patch is not a face of the plan."""
    found = _patch_outline(graph, patch, x)
    if found is None:
        return math.nan
    outline = found[1]
    return interior_angle(outline[-2], outline[0], outline[1])


def patch_angle_split(graph, patch: int, x: int, point) -> float:
    """The narrower of the two parts into which a chord from the corner ``x`` of a Patch node to
    ``point`` (inside it) splits the patch's angle there (degrees; between the directions in which its
    sides leave ``x``, as :func:`patch_angle` measures it; NaN if the patch is not a face of the plan).
    A side may curve away from the chord to its far corner: a triangle at a curve's free end whose
    side runs along the curve to a skeleton vertex beyond its other end is 38 degrees wide there
    between its side and the chord to its opposite side's middle, 65 between the chords (draw 80 of
    the 700 saved random plans, split_triangle_under_curve_tip's wide step, rules/curves.vgr)."""
    found = _patch_outline(graph, patch, x)
    if found is None:
        return math.nan
    outline = found[1]
    return min(interior_angle(point, outline[0], outline[1]), interior_angle(outline[-2], outline[0], point))


def diagonal_side_angle(graph, patch: int, x: int, o: int, y: int) -> float:
    """The corner (degrees) that the diagonal of a Patch node from its corner ``x`` to its corner ``o``
    (:func:`diagonal_path`) would leave at ``o`` on the side of ``o``'s neighbouring corner ``y``:
    between the diagonal's last segment and the first segment of the patch's side from ``o`` towards
    ``y`` (the sides may curve: a skeleton branch bending round a curve's end leaves ``o`` at 17.1
    degrees to the diagonal of fig7_curves' quad at the end (1, 1), 5.6 between the chords; Figure 8,
    §4.2). NaN (every comparison false) where there is no such diagonal or the patch is not a face
    of the plan."""
    path, found = diagonal_path(graph, patch, x, o), _patch_outline(graph, patch, o)
    if len(path) < 2 or found is None:
        return math.nan
    outline = found[1]
    ahead = _point_of(found, y) < _point_of(found, x)  # y comes before x counter-clockwise from o
    return angle_between(outline[1] if ahead else outline[-2], outline[0], path[-2])


def fan_clear(graph, patch: int, x: int, o: int) -> bool:
    """Whether the split of a Patch node by its diagonal from corner ``x`` to corner ``o``
    (:func:`diagonal_path`) leaves two parts that mesh as fans round ``x`` as their pole, neither a
    crescent whose outline turns back about ``x`` by more than half its angle there (Figure 4, §4.1;
    :func:`~vaultgram.topology.fans.fan_parts_seen`); False where there is no such diagonal."""
    found, path = _patch_outline(graph, patch, x), diagonal_path(graph, patch, x, o)
    return bool(path) and fans.fan_parts_seen(found[1], _point_of(found, o), path)


def bend_first(graph, patch: int) -> bool:
    """Whether a Patch node of 5 or more sides turns by more than 180 degrees at a bend of a curve
    (a curve point marked corner, not an extremity: §4.2) from which a diagonal to a corner two or
    more places away runs inside it (:func:`diagonal_path`). ``spread_curve_bend`` splits such a
    patch at the bend before ``spread_t_junction`` spreads any T-junction of it: a diagonal from the
    T-junction may go round the bend, which then stays a reflex corner of a part."""
    corners = sorted((graph.get_edge(e, "index"), graph.ends(e)[1]) for e in graph.incident(patch, [PATCH_CORNER]))
    n = len(corners)
    if n < 5:
        return False
    for i, y in corners:
        if graph.node_type(y) != CURVE_POINT or not graph.get(y, "corner") or not patch_angle(graph, patch, y) > 180:
            continue
        if any(len(diagonal_path(graph, patch, y, o)) >= 2 for j, o in corners if 2 <= (j - i) % n <= n - 2):
            return True
    return False


def diagonal_path(graph, patch: int, x: int, o: int) -> tuple:
    """A diagonal of a patch from corner ``x`` to corner ``o`` that stays inside it, or ``()``.

    The straight segment when it runs inside the patch (it leaves ``x`` and reaches ``o`` within the
    patch's corner angles there, and crosses no plan edge); otherwise two straight pieces through the
    nearest point (shortest detour) of the patch's mid-line that does, the mid-line being the
    average of the two outline chains from ``x`` to ``o`` resampled at the same fractions of their
    length. Where a side is curved or the patch wraps round a reflex corner (a curve extremity) the
    diagonal thus bends inside the patch instead of cutting across a side or running through the
    neighbouring patch. ``()`` when no such path exists: a rule should then leave the patch whole.

    Kept by what it is made of (issue 13: the rules ask for the same diagonals in state after
    state): the patch's closed outline (one of :func:`~.patches.face_outline`'s, shared by every
    state with that face), where ``o`` is along it, the two corners' positions and the plan's
    segments (shared by every state with that plan geometry, :func:`_all_plan_segments`). The
    entry keeps the outline and the segments alive, so that their ``id`` names them.
    """
    found = _patch_outline(graph, patch, x)
    if found is None:
        return ()
    outline, at, segments = found[1], _point_of(found, o), _plan_segments(graph)
    p, q = graph.get(x, "pos"), graph.get(o, "pos")
    return by_content(_DIAGONALS, (id(outline), at, p, q, id(segments)),
                      lambda: (outline, segments, _diagonal(outline, at, p, q, segments)), DIAGONALS)[2]


#: The diagonals kept (the most recently asked) by :func:`diagonal_path`; as many as the plans'
#: segments kept, since each entry keeps its plan's segments alive.
DIAGONALS = 256
_DIAGONALS: OrderedDict = OrderedDict()


def _diagonal(outline: np.ndarray, at: int, x_pos, o_pos, segments) -> tuple:
    """:func:`diagonal_path` in the patch of closed ``outline`` (from corner x) whose corner o is
    its point ``at``, with the plan's ``segments``."""
    p, q = np.asarray(x_pos, dtype=float), np.asarray(o_pos, dtype=float)
    a, b = outline[: at + 1], outline[at:][::-1]

    def inside(path):
        return (_within(path[1] - p, a[1] - p, b[1] - p) and _within(path[-2] - q, b[-2] - q, a[-2] - q)
                and _clear(path, *segments))

    if inside(np.array([p, q])):
        return _points([p, q])
    t = np.linspace(0.0, 1.0, max(len(a), len(b), 8) + 1)
    mid = (_resample(a, t) + _resample(b, t)) / 2
    detour = np.hypot(*(mid - p).T) + np.hypot(*(mid - q).T)
    for k in np.argsort(detour[1:-1], kind="stable") + 1:
        path = np.array([p, mid[k], q])
        if inside(path):
            return _points(path)
    return ()


def _within(d, first, last) -> bool:
    """Whether direction ``d`` lies strictly inside the counter-clockwise turn from ``first`` to ``last``."""
    def angle(v):
        return math.atan2(v[1], v[0])
    return 0 < (angle(d) - angle(first)) % (2 * math.pi) < (angle(last) - angle(first)) % (2 * math.pi)


def path_clear(graph, path) -> bool:
    """Whether a polyline crosses no plan edge (touching at its two ends does not count): a diagonal
    drawn by a rule must keep the plan planar."""
    return _clear(np.asarray(path, dtype=float), *_plan_segments(graph))


def path_crosses_only(graph, path, edge: int) -> bool:
    """Whether a polyline crosses the plan once, and there the plan edge ``edge`` (a branch that the
    rule drawing the path deletes): the path then stays in the two patches on either side of it."""
    path = np.asarray(path, dtype=float)
    pts = half_edge_polyline(graph, edge, graph.ends(edge)[0])
    return _crossings(path, pts[:-1], pts[1:]) == 1 == _crossings(path, *_plan_segments(graph))


def _plan_segments(graph) -> tuple[np.ndarray, np.ndarray]:
    """Start and end points of every straight piece of every plan edge (once per state: every
    diagonal a rule tries in one state is checked against the same plan)."""
    return per_state(_SEGMENTS, graph, _all_plan_segments)


#: The plan segments kept by :func:`_all_plan_segments` (the most recently asked plans).
SEGMENT_PLANS = 256
_SEGMENT_PLANS: OrderedDict = OrderedDict()


def _all_plan_segments(graph) -> tuple[np.ndarray, np.ndarray]:
    """Kept by what the plan edges are made of (:func:`~.patches.half_edge_key`): a rewrite that
    leaves the plan's geometry as it was (a Patch node split, an edge retyped) finds it again."""
    key = tuple(half_edge_key(graph, e, graph.ends(e)[0]) for e in graph.of_types(PLAN_EDGES))
    return by_content(_SEGMENT_PLANS, key, lambda: _segments_of(key), SEGMENT_PLANS)


def _segments_of(key: tuple) -> tuple[np.ndarray, np.ndarray]:
    pieces = [key_polyline(k) for k in key]
    start, end = np.concatenate([poly[:-1] for poly in pieces]), np.concatenate([poly[1:] for poly in pieces])
    start.flags.writeable = end.flags.writeable = False
    return start, end


def _clear(path: np.ndarray, start: np.ndarray, end: np.ndarray) -> bool:
    """No piece of ``path`` properly crosses a segment ``start[i]``-``end[i]``."""
    return _crossings(path, start, end) == 0


def _crossings(path: np.ndarray, start: np.ndarray, end: np.ndarray) -> int:
    """How many times the pieces of ``path`` properly cross the segments ``start[i]``-``end[i]``
    (vectorised)."""
    p, q = path[:-1, None, :], path[1:, None, :]
    s, e = start[None, :, :], end[None, :, :]
    size = float(np.ptp(path, axis=0).max())
    eps = (1e-9 * size * size) ** 2

    def side(o, d, z):  # cross product (d - o) x (z - o)
        return (d[..., 0] - o[..., 0]) * (z[..., 1] - o[..., 1]) - (d[..., 1] - o[..., 1]) * (z[..., 0] - o[..., 0])

    straddles = side(p, q, s) * side(p, q, e) < -eps
    crosses = side(s, e, p) * side(s, e, q) < -eps
    return int(np.count_nonzero(straddles & crosses))


def _points(path) -> tuple:
    """A path as a rule value: a tuple of (x, y) float pairs."""
    return tuple((float(px), float(py)) for px, py in path)


def _resample(chain: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The points of a polyline at the fractions ``t`` of its length."""
    return point_at_length(chain, t * arc_lengths(chain)[-1]).T


# -- measures of the whole plan, for the rulebook's invariants (rules/invariants.vgr) -------------

_FACES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: its faces}
_SEGMENTS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: its segments}
_OUTLINES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: {(patch, x): outline}}


def _faces(graph) -> list:
    """:func:`plan_faces` of the graph as it is now, computed once per state (several invariants ask
    for them in one check)."""
    return per_state(_FACES, graph, lambda g: plan_faces(g, PLAN_EDGES))


def plan_area(graph) -> float:
    """The summed area of the faces of the plan (bounded, not inside a hole): the patches' area."""
    return float(sum(signed_area(outline) for _, _, outline in _faces(graph)))


def domain_area(graph) -> float:
    """The area of the domain: its outer ring's less its holes' (from the boundary vertices)."""
    rings: dict[int, list] = {}
    for n in graph.of_types(graph.schema.subtypes(BOUNDARY_VERTEX)):
        rings.setdefault(graph.get(n, "ring"), []).append((graph.get(n, "index"), n, graph.get(n, "pos")))
    areas = {r: abs(signed_area(np.array([p for _, _, p in sorted(pts)]))) for r, pts in rings.items()}
    return float(areas.get(0, 0.0) - sum(a for r, a in areas.items() if r > 0))


def plan_euler(graph) -> int:
    """V - E + F of the patch layout: its points, its edges and its patches (faces not inside a hole);
    1 - holes for a layout of disks (§3.1)."""
    edges = list(graph.of_types(PLAN_EDGES))
    nodes = {n for e in edges for n in graph.ends(e)}
    return len(nodes) - len(edges) + len(_faces(graph))


def hole_count(graph) -> int:
    """The number of holes of the domain (rings of boundary vertices other than the outer one)."""
    return len(hole_rings(graph))


def holes_enclosed(graph) -> int:
    """How many (face, hole) pairs have the hole inside the face of the plan: 0 for a layout of disks."""
    outlines = [outline for _, _, outline in _faces(graph)]
    return len(enclosed_holes(outlines, hole_rings(graph)))


def plan_crossings(graph) -> int:
    """How many pairs of plan edges properly cross (meeting at a shared end is no crossing): 0 for a
    planar layout, which the faces of the plan need. A straight rebranch can cross a skeleton branch
    that bends across it where the discretisation is too coarse for the domain."""
    lines = [shapely.LineString(half_edge_polyline(graph, e, graph.ends(e)[0])) for e in graph.of_types(PLAN_EDGES)]
    if len(lines) < 2:
        return 0
    pairs = shapely.STRtree(lines).query(lines, predicate="crosses")
    return int(np.count_nonzero(pairs[0] < pairs[1]))


def curve_crossings(graph) -> int:
    """How many pieces of the skeleton, rebranches and diagonals properly cross a curve feature's
    segment (§4.2: the skeleton does not cross a curve; meeting it at a point is no crossing)."""
    curve = [half_edge_polyline(graph, e, graph.ends(e)[0]) for e in graph.of_types([CURVE])]
    others = [e for e in graph.of_types(PLAN_EDGES) if graph.edge_type(e) not in (CURVE, "Boundary")]
    if not curve or not others:
        return 0
    start, end = np.concatenate([c[:-1] for c in curve]), np.concatenate([c[1:] for c in curve])
    return sum(not _clear(half_edge_polyline(graph, e, graph.ends(e)[0]), start, end) for e in others)


def vault_functions() -> Functions:
    """A registry with the engine's builtins plus the vault pipeline's geometry (the signatures
    rules see; ``uses_graph`` functions get the host graph as their first argument)."""
    f = Functions()
    f.register("distance", distance, ("vec", "vec"), "float")
    f.register("midpoint", midpoint, ("vec2", "vec2"), "vec2")
    f.register("lerp", lerp, ("vec2", "vec2", "number"), "vec2")
    f.register("angle_between", angle_between, ("vec2", "vec2", "vec2"), "float")
    f.register("move_end", move_end, ("list", "vec2", "vec2"), "list")
    f.register("move_branch_end", move_branch_end, ("list", "vec2", "vec2", "node", "node"), "list", uses_graph=True,
               local=False)
    f.register("interior_angle", interior_angle, ("vec2", "vec2", "vec2"), "float")
    f.register("curve_side", curve_side, ("node",), "int", uses_graph=True, local=False)
    f.register("curve_turn", curve_turn, ("node",), "int", uses_graph=True, local=False)
    f.register("curve_neighbours", curve_neighbours, ("node", "node"), "bool", uses_graph=True, local=False)
    f.register("diagonal_path", diagonal_path, ("node", "node", "node"), "list", uses_graph=True, local=False)
    f.register("bend_first", bend_first, ("node",), "bool", uses_graph=True, local=False)
    f.register("path_clear", path_clear, ("list",), "bool", uses_graph=True, local=False)
    f.register("path_crosses_only", path_crosses_only, ("list", "edge"), "bool", uses_graph=True, local=False)
    f.register("patch_angle", patch_angle, ("node", "node"), "float", uses_graph=True, local=False)
    f.register("patch_angle_split", patch_angle_split, ("node", "node", "vec2"), "float", uses_graph=True,
               local=False)
    f.register("diagonal_side_angle", diagonal_side_angle, ("node", "node", "node", "node"), "float", uses_graph=True,
               local=False)
    f.register("fan_clear", fan_clear, ("node", "node", "node"), "bool", uses_graph=True, local=False)
    f.register("patch_side_starts", patch_side_starts, ("node", "node", "node"), "bool", uses_graph=True,
               local=False)
    f.register("patch_corner", patch_corner, ("node", "int"), "node", uses_graph=True, local=False)
    f.register("patch_in_plan", patch_in_plan, ("node",), "bool", uses_graph=True, local=False)
    for name, fn, returns in (("plan_area", plan_area, "float"), ("domain_area", domain_area, "float"),
                              ("plan_euler", plan_euler, "int"), ("hole_count", hole_count, "int"),
                              ("holes_enclosed", holes_enclosed, "int"), ("curve_crossings", curve_crossings, "int"),
                              ("plan_crossings", plan_crossings, "int")):
        f.register(name, fn, (), returns, uses_graph=True, local=False)
    _register_corner_helpers(f)
    register_o_grid_helpers(f)
    register_lone_branch_helpers(f)
    register_strip_helpers(f)
    register_hole_side_helpers(f)
    register_hole_hub_helpers(f)
    register_hole_triangle_helpers(f)
    register_hole_rebranch_helpers(f)
    register_hole_fan_helpers(f)
    register_lone_corner_helpers(f)
    register_corner_merge_helpers(f)
    return f


def _register_corner_helpers(f: Functions) -> None:
    """The helpers of ``rules/corners.vgr`` (:mod:`vaultgram.topology.corners`): the regular valence
    of a boundary vertex by its angle, whether the plan is rectilinear, where a reflex corner's chord
    ends, and where two chords cross; and on any plan, the side a reflex corner's chord runs to
    (:mod:`vaultgram.topology.reflex`)."""
    f.register("regular_valence", lambda theta: int(regular_valence(theta)), ("number",), "int")
    f.register("boundary_angle", corners.boundary_angle, ("node",), "float", uses_graph=True, local=False)
    f.register("rectilinear_plan", corners.rectilinear_plan, (), "bool", uses_graph=True, local=False)
    f.register("chord_end", corners.chord_end, ("node", "int"), "node", uses_graph=True, local=False)
    f.register("segments_cross", corners.segments_cross, ("vec2", "vec2", "vec2", "vec2"), "bool")
    f.register("segment_crossing", corners.segment_crossing, ("vec2", "vec2", "vec2", "vec2"), "vec2")
    f.register("neck_corner", corners.neck_corner, ("node", "vec2", "vec2"), "bool", uses_graph=True, local=False)
    f.register("reflex_chord", reflex.reflex_chord, ("node", "node"), "edge", uses_graph=True, local=False)
    f.register("reflex_side", reflex.reflex_side, ("node", "node"), "node", uses_graph=True, local=False)
    f.register("reflex_cut", reflex.reflex_cut, ("node", "node"), "edge", uses_graph=True, local=False)
    f.register("reflex_cut_index", reflex.reflex_cut_index, ("node", "node"), "int", uses_graph=True, local=False)
    f.register("reflex_cut_at", reflex.reflex_cut_at, ("node",), "bool", uses_graph=True, local=False)
    f.register("reflex_bisecting_cut", reflex.reflex_bisecting_cut, ("node", "node"), "edge", uses_graph=True,
               local=False)
    f.register("reflex_bisecting_cut_index", reflex.reflex_bisecting_cut_index, ("node", "node"), "int",
               uses_graph=True, local=False)
    f.register("reflex_bisecting_cut_at", reflex.reflex_bisecting_cut_at, ("node",), "bool", uses_graph=True,
               local=False)
    f.register("reflex_foot", reflex.reflex_foot, ("node", "node"), "node", uses_graph=True, local=False)
    f.register("reflex_point", reflex.reflex_point, ("node", "node"), "vec2", uses_graph=True, local=False)
    f.register("fan_foot", reflex.fan_foot, ("edge",), "float", uses_graph=True, local=False)
    f.register("rebranch_to_corner", reflex.rebranch_to_corner, ("node", "node", "node", "node"), "bool",
               uses_graph=True, local=False)
