"""The geometric helper functions the vault pipeline registers for its rules.

The engine knows nothing about geometry; rules in ``rules/`` may call these by name. The point
functions are pure and local (they read only their arguments), so rules using them re-match
incrementally; the curve functions walk the graph along a curve feature and are declared non-local.
"""

from __future__ import annotations

import math

from vaultgram.engine.expressions import Functions


def distance(p, q) -> float:
    return math.dist(p, q)


def midpoint(p, q) -> tuple[float, ...]:
    return tuple((a + b) / 2 for a, b in zip(p, q))


def lerp(p, q, t) -> tuple[float, ...]:
    return tuple(a + (b - a) * t for a, b in zip(p, q))


def interior_angle(before, corner, after) -> float:
    """The angle inside a counter-clockwise polygon at ``corner`` (degrees in [0, 360)): the turn from
    the direction towards the next corner (``after``) to the direction towards the previous one."""
    a = math.atan2(after[1] - corner[1], after[0] - corner[0])
    b = math.atan2(before[1] - corner[1], before[0] - corner[0])
    return math.degrees((b - a) % (2 * math.pi))


def move_end(polyline, old, new) -> tuple:
    """``polyline`` with the end point that lies at ``old`` moved to ``new`` (the nearer end)."""
    points = [tuple(p) for p in polyline]
    if len(points) < 2:
        return tuple(points)
    k = 0 if math.dist(points[0], old) <= math.dist(points[-1], old) else -1
    points[k] = tuple(new)
    return tuple(points)


def angle_between(p, centre, q) -> float:
    """The angle p-centre-q in degrees, in [0, 180]."""
    a = math.atan2(p[1] - centre[1], p[0] - centre[0])
    b = math.atan2(q[1] - centre[1], q[0] - centre[0])
    d = abs(a - b) % (2 * math.pi)
    return math.degrees(min(d, 2 * math.pi - d))


PLAN_EDGES = ("Branch", "Rebranch", "Boundary", "Curve", "Diagonal")


def curve_side(graph, p: int) -> int:
    """Which side of its curve the plan edges at curve point ``p`` arrive from (§4.2 T-junctions).

    +1: all from the left of the curve's direction (from its first point to its last), -1: all from
    the right, 0: from both sides, from neither, or ``p`` is not an inner point of a curve.
    """
    rotation = [e for e in graph.rotation(p) if graph.edge_type(e) in PLAN_EDGES]
    curve = [e for e in rotation if graph.edge_type(e) == "Curve"]
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


def curve_neighbours(graph, p: int, q: int) -> bool:
    """Whether ``q`` is reached from ``p`` along the curve through points where nothing else arrives."""
    for first in [e for e in graph.incident(p, ["Curve"])]:
        prev, node = p, graph.other(first, p)
        while node != q and graph.degree(node, PLAN_EDGES) == 2 and not graph.get(node, "corner"):
            nxt = [e for e in graph.incident(node, ["Curve"]) if graph.other(e, node) != prev]
            if not nxt:
                break
            prev, node = node, graph.other(nxt[0], node)
        if node == q:
            return True
    return False


def patch_corner(graph, patch: int, index: int) -> int:
    """The corner of a Patch node with the given index (its PatchCorner edge's ``index``)."""
    for e in graph.incident(patch, ["PatchCorner"]):
        if graph.get_edge(e, "index") == index:
            return graph.ends(e)[1]
    raise ValueError(f"patch {patch} has no corner {index}")


def vault_functions() -> Functions:
    """A registry with the engine's builtins plus the vault pipeline's geometry."""
    f = Functions()
    f.register("distance", distance, ("vec", "vec"), "float")
    f.register("midpoint", midpoint, ("vec2", "vec2"), "vec2")
    f.register("lerp", lerp, ("vec2", "vec2", "number"), "vec2")
    f.register("angle_between", angle_between, ("vec2", "vec2", "vec2"), "float")
    f.register("move_end", move_end, ("list", "vec2", "vec2"), "list")
    f.register("interior_angle", interior_angle, ("vec2", "vec2", "vec2"), "float")
    f.register("curve_side", curve_side, ("node",), "int", uses_graph=True, local=False)
    f.register("curve_neighbours", curve_neighbours, ("node", "node"), "bool", uses_graph=True, local=False)
    f.register("patch_corner", patch_corner, ("node", "int"), "node", uses_graph=True, local=False)
    return f
