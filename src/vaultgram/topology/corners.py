"""Reflex corners of rectilinear plans: the chords that give each one a branch of its own.

The medial axis sends no branch to a reflex corner (§3.1): the corner ends up the side of one patch,
and two quads share its 270 degrees (a boundary singularity), with a singularity of valence 5 beside
it. The paper's conclusion names these distortions as the method's limitation, after Rigby [11] and
Fogg et al. [10]. On a rectilinear plan (every corner a right angle, convex or reflex) there is a
block decomposition without any singular vertex: the side extensions of every reflex corner, drawn
through the domain to the boundary, cut it into rectangles. The reflex corner is then the corner of
three patches (valence 4, regular at 270 degrees), a chord's foot the corner of two (regular on a
straight side), and two chords cross at a regular interior vertex of valence 4.

The rules of ``rules/corners.vgr`` draw these chords; this module gives them their geometry:
:func:`rectilinear_rings` decides whether a plan is rectilinear, :func:`chord_feet` says where the
chords end (the discretisation samples the boundary there, so that every chord ends at a boundary
point), and the rule helpers read the same from the rule graph.
"""

from __future__ import annotations

import math
import weakref

import numpy as np

from vaultgram.geometry.polygons import cross_z, interior_angle, regular_valence, signed_angles
from vaultgram.topology.statecache import per_state
from vaultgram.topology.types import BOUNDARY_VERTEX, CURVE_POINT, FEATURE_POINT

__all__ = ["rectilinear_rings", "chord_feet", "ray_hit", "graph_rings", "boundary_angle", "ring_place",
           "rectilinear_plan", "chord_end", "segments_cross", "segment_crossing", "neck_corner",
           "RIGHT_ANGLE_TOLERANCE"]

#: Degrees by which a corner of a rectilinear plan may differ from 90, 180 or 270.
RIGHT_ANGLE_TOLERANCE = 1.0


def _ring_angles(ring: np.ndarray) -> np.ndarray:
    """Interior angle (degrees, in [0, 360)) at every vertex of a ring that keeps the domain on its left."""
    to_prev = np.roll(ring, 1, axis=0) - ring
    to_next = np.roll(ring, -1, axis=0) - ring
    a = signed_angles(to_next, to_prev)
    return np.degrees(a) % 360.0


def rectilinear_rings(rings) -> bool:
    """Whether every vertex of every ring (domain on the left) is a right angle, convex or reflex, or
    straight (within :data:`RIGHT_ANGLE_TOLERANCE`), and at least four are right angles (a regular
    polygon of many sides, all of whose vertices are nearly straight, is not rectilinear).

    >>> rectilinear_rings([np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2.0]])])
    True
    >>> rectilinear_rings([np.array([[0, 0], [2, 0], [0, 2.0]])])
    False
    >>> t = 2 * np.pi * np.arange(1000) / 1000
    >>> rectilinear_rings([np.column_stack([np.cos(t), np.sin(t)])])
    False
    """
    for ring in rings:
        angles = _ring_angles(np.asarray(ring, dtype=float))
        off = np.abs((angles + 45.0) % 90.0 - 45.0)
        turns = np.abs(angles - 180.0) > RIGHT_ANGLE_TOLERANCE  # a finely sampled circle has none
        if turns.sum() < 4 or off.max() > RIGHT_ANGLE_TOLERANCE:
            return False
    return True


def _reflex_rays(ring: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The reflex corners of a ring (interior angle with regular valence 4) and, for each, the two
    directions into the domain along its sides' extensions: the incoming side continued (side 0),
    the outgoing side continued backwards (side 1). Returns ``(indices, directions (k, 2, 2))``."""
    at = np.flatnonzero(regular_valence(_ring_angles(ring)) == 4)
    d_in = ring[at] - ring[at - 1]
    d_out = ring[(at + 1) % len(ring)] - ring[at]
    dirs = np.stack([d_in / np.hypot(*d_in.T)[:, None], -d_out / np.hypot(*d_out.T)[:, None]], axis=1)
    return at, dirs


def ray_hit(rings, origin, direction) -> np.ndarray | None:
    """The first point where the ray from ``origin`` along ``direction`` meets a ring segment (not at
    the origin itself), or None.

    >>> ray_hit([np.array([[0, 0], [4, 0], [4, 4], [0, 4.0]])], np.array([1.0, 1.0]), np.array([1.0, 0.0])).tolist()
    [4.0, 1.0]
    """
    a = np.vstack([np.asarray(r, dtype=float) for r in rings])
    b = np.vstack([np.roll(np.asarray(r, dtype=float), -1, axis=0) for r in rings])
    o, d = np.asarray(origin, dtype=float), np.asarray(direction, dtype=float)
    e = b - a
    denom = cross_z(np.broadcast_to(d, e.shape), e)
    rel = a - o
    with np.errstate(divide="ignore", invalid="ignore"):
        t = cross_z(rel, e) / denom  # along the ray
        s = cross_z(rel, np.broadcast_to(d, e.shape)) / denom  # along the segment
    scale = max(float(np.ptp(a, axis=0).max()), 1.0)
    ok = (np.abs(denom) > 1e-12) & (t > 1e-9 * scale) & (s >= -1e-12) & (s <= 1 + 1e-12)
    if not ok.any():
        return None
    return o + d * t[ok].min()


def chord_feet(rings) -> list[np.ndarray]:
    """Where the side extensions of the reflex corners of a rectilinear plan meet the boundary (none
    for another plan): the discretisation samples the rings there (§3.1), so that each chord of
    ``rules/corners.vgr`` ends at a boundary point."""
    rings = [np.asarray(r, dtype=float) for r in rings]
    if not rectilinear_rings(rings):
        return []
    feet = []
    for ring in rings:
        at, dirs = _reflex_rays(ring)
        for k, i in enumerate(at):
            for side in (0, 1):
                hit = ray_hit(rings, ring[i], dirs[k, side])
                if hit is not None and not any(np.allclose(hit, f, rtol=0, atol=1e-9) for f in feet):
                    feet.append(hit)
    return feet


# --------------------------------------------------------------------------------------------
# The rule helpers (registered by vaultgram.topology.functions.vault_functions)
# --------------------------------------------------------------------------------------------

_RINGS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: (rings, nodes, memo)}


def graph_rings(graph) -> tuple[list, list]:
    """The rings of the rule graph's boundary vertices, in ring order (by ``index``; equal indices by
    node id: a boundary edge a strip splits, :func:`~vaultgram.topology.strips.strip_boundary_split`,
    gives its new point its first point's index): their positions and node ids (computed once per
    state of the graph)."""
    rings, nodes, _ = per_state(_RINGS, graph, _rings_now)
    return rings, nodes


def _rings_now(graph) -> tuple[list, list, dict]:
    """The rings of :func:`graph_rings` worked out, with each vertex's place and angle."""
    by_ring: dict[int, list] = {}
    for n in graph.of_types(graph.schema.subtypes(BOUNDARY_VERTEX)):
        by_ring.setdefault(graph.get(n, "ring"), []).append((graph.get(n, "index"), n))
    nodes = [[n for _, n in sorted(v)] for _, v in sorted(by_ring.items())]
    rings = [np.array([graph.get(n, "pos") for n in ids], dtype=float) for ids in nodes]
    where = {n: (r, k) for r, ids in enumerate(nodes) for k, n in enumerate(ids)}
    angles = {n: float(a) for ids, ring in zip(nodes, rings) for n, a in zip(ids, _ring_angles(ring))}
    return rings, nodes, {"where": where, "angle": angles}


def _cache(graph) -> dict:
    """A per-state memo of the rule helpers (the chord ends a rule asks for at every candidate)."""
    return per_state(_RINGS, graph, _rings_now)[2]


def ring_place(graph, v: int) -> tuple[int, int]:
    """The ring of boundary vertex ``v`` and its place along it (:func:`graph_rings`)."""
    return _cache(graph)["where"][v]


def boundary_angle(graph, v: int) -> float:
    """The domain's interior angle (degrees) at boundary vertex ``v``, between its ring neighbours."""
    return _cache(graph)["angle"][v]


def neck_corner(graph, r: int, before, after) -> bool:
    """Whether the corner at reflex corner ``r`` of a counter-clockwise quad across a passage (``before``
    and ``after`` its neighbouring corners, one along the wall, one at a chord's other end) is a
    quad's corner, 45 to 135 degrees, leaving ``r`` a straight angle outside the quad (regular
    valence 3, 135 to 225 degrees): ``r`` is then regular as the corner of three patches
    (``rules/patching.vgr``, cut_neck)."""
    inside = interior_angle(before, graph.get(r, "pos"), after)
    return 45.0 <= inside < 135.0 and int(regular_valence(boundary_angle(graph, r) - inside)) == 3


def rectilinear_plan(graph) -> bool:
    """Whether the rule graph's plan is rectilinear (:func:`rectilinear_rings`) without point or curve
    features (the chords of ``rules/corners.vgr`` would cross them)."""
    memo = _cache(graph)
    if "rectilinear" not in memo:
        featured = any(True for _ in graph.of_types(graph.schema.subtypes(FEATURE_POINT)))
        featured |= any(True for _ in graph.of_types(graph.schema.subtypes(CURVE_POINT)))
        featured |= any(graph.get(n, "feature") for n in graph.of_types(graph.schema.subtypes(BOUNDARY_VERTEX)))
        memo["rectilinear"] = not featured and rectilinear_rings(graph_rings(graph)[0])
    return memo["rectilinear"]


def chord_end(graph, r: int, side: int) -> int:
    """The boundary vertex where the chord from reflex corner ``r`` along side ``side`` (0: the
    incoming side continued, 1: the outgoing side continued backwards) meets the boundary; ``r``
    itself where no boundary vertex lies there (a plan the discretisation did not sample for it)."""
    memo = _cache(graph)
    key = ("end", r, side)
    if key not in memo:
        memo[key] = _chord_end(graph, r, side)
    return memo[key]


def _chord_end(graph, r: int, side: int) -> int:
    """:func:`chord_end`, computed."""
    rings, nodes = graph_rings(graph)
    ring_of, k = ring_place(graph, r)
    ring = rings[ring_of]
    p = ring[k]
    d = p - ring[k - 1] if side == 0 else p - ring[(k + 1) % len(ring)]
    hit = ray_hit(rings, p, d / np.hypot(*d))
    if hit is None:
        return r
    pts = np.vstack(rings)
    flat = [n for ids_ in nodes for n in ids_]
    j = int(np.argmin(np.hypot(*(pts - hit).T)))
    tol = 1e-7 * max(float(np.ptp(pts, axis=0).max()), 1.0)
    return flat[j] if np.hypot(*(pts[j] - hit)) <= tol else r


def _line_params(a, b, c, d) -> tuple[float, float] | None:
    """Where the lines through ``a-b`` and ``c-d`` meet, as parameters ``(t, s)`` along each (plain
    floats: the crossing rules call this for every pair of chord pieces), or None if parallel."""
    ux, uy, vx, vy = b[0] - a[0], b[1] - a[1], d[0] - c[0], d[1] - c[1]
    den = ux * vy - uy * vx
    if abs(den) <= 1e-12 * math.hypot(ux, uy) * math.hypot(vx, vy):
        return None
    wx, wy = c[0] - a[0], c[1] - a[1]
    return (wx * vy - wy * vx) / den, (wx * uy - wy * ux) / den


def segments_cross(a, b, c, d) -> bool:
    """Whether segments ``a-b`` and ``c-d`` cross at a point inside both (not at an end).

    >>> segments_cross((0, 0), (2, 0), (1, -1), (1, 1)), segments_cross((0, 0), (2, 0), (2, -1), (2, 1))
    (True, False)
    """
    ts = _line_params(a, b, c, d)
    eps = 1e-9
    return ts is not None and eps < ts[0] < 1 - eps and eps < ts[1] < 1 - eps


def segment_crossing(a, b, c, d) -> tuple[float, float]:
    """The point where the lines through ``a-b`` and ``c-d`` meet (the crossing of two chords).

    >>> segment_crossing((0, 0), (2, 0), (1, -1), (1, 1))
    (1.0, 0.0)
    """
    t = _line_params(a, b, c, d)[0]
    return float(a[0] + t * (b[0] - a[0])), float(a[1] + t * (b[1] - a[1]))
