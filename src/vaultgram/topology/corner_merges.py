"""Boundary corners with too many patches: the helper of ``rules/corner_merges.vgr`` (issue 12,
acceptance 3; paper §3.1, Figure 2e).

The rebranching rule links each skeleton vertex to every boundary point its maximal circle touches
(§3.1). A reflex corner of the plan lies on the circles of every skeleton vertex along the medial
axis' arc round it, so on a jagged outline (short edges, :func:`vaultgram.testing.jagged.jagged_plans`)
three or four skeleton vertices rebranch to one reflex corner: it becomes the corner of four or five
patches, two of them thin triangles (``(b, x, y)``: both skeleton vertices rebranched to ``b``, a few
degrees wide there). A corner of angle ``theta`` is regular with ``regular_valence(theta) - 1`` faces
(one a patch), so one patch too many is a boundary singularity however the patches are meshed.

The rules take one rebranch away from such a corner: two triangles sharing one become a quad
(``merge_triangles_at_over_served_spike``, at spikes of 315 degrees or more, as
``merge_triangles_at_reflex_corner`` does below 315), or the rebranch
from a triangle's skeleton vertex moves to the neighbouring boundary point (``spread_over_served_corner``,
the move of ``spread_boundary_pole`` for corners of 225 degrees or more): the triangle becomes the quad
``(b, c, x, y)``, ``b`` keeps one patch less, and the neighbour ``c``, a smooth boundary point (135-225
degrees, regular with two faces), becomes the corner of two. :func:`spread_rebranch` checks the move's
geometry.

A thin triangle ``(b, x, y)`` beside a quad ``(b, u, v, x)`` at such a corner (the rebranch ``x-b``
their shared side; jagged_2's 228 and 291 degree corners, where the spread is refused by the
edge-group limit or has no free neighbour) is a pentagon ``(b, u, v, x, y)`` cut by the rebranch; the rebranch
is flipped to the pentagon's other diagonal from ``x``'s neighbours, ``v-y``
(``flip_over_served_corner``): the quad ``(b, u, v, y)`` and the triangle ``(v, x, y)``, whose pole is
off the boundary. ``b`` keeps one patch less; :func:`flip_rebranch` checks the flip's geometry.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
import shapely.ops

from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.topology.reflex import MAX_RATIO, MIN_ANGLE
from vaultgram.topology.strips import chord_inside, patch_sides
from vaultgram.topology.types import BOUNDARY

__all__ = ["flip_rebranch", "flip_angles", "spread_rebranch", "register_corner_merge_helpers"]

#: The least angle the flipped chord ``v-y`` leaves either side at ``v`` and ``y``, and the least
#: corner of its triangle (degrees). All three are skeleton vertices, which smoothing moves: jagged_2's
#: 291 degree corner's flip leaves 11.3 degrees at ``y`` and its mesh's worst face stays 0.271 (at 20
#: that flip was refused). jagged_1's 281 degree corner's would leave 5.5 (and a quad of 172.6).
FLIP_MIN_ANGLE = 10.0

#: The widest corner of the flip's new quad (degrees): a quad corner near straight gives a mesh
#: corner near straight too (scaled Jacobian sin(170) = 0.17 at the corner itself).
FLIP_MAX_ANGLE = 165.0

#: The widest the triangle may be at ``b`` (degrees): the flip is for the thin triangle between two
#: rebranches from the skeleton's arc round ``b`` (jagged_2's 228 degree corner: 9.5 degrees). A wider
#: one is a face of its own there (jagged_3's 304 degree corner: 78.7 degrees, beside a thin quad);
#: flipped, it gave bs -1 but moved the plan's counts so that its worst face, 25 away, fell 0.369 -> 0.321.
FLIP_THIN = 45.0


def spread_rebranch(graph, patch: int, b: int, c: int, s: int, t: int) -> bool:
    """Whether the rebranch from the skeleton vertex ``s`` to the boundary corner ``b`` may move to
    ``b``'s ring neighbour ``c``: ``patch`` is the patch beyond the rebranch (it keeps ``c`` as its corner
    instead of ``b``), ``t`` the triangle's other skeleton vertex, whose rebranch to ``b`` stays.
    The moved rebranch must run straight inside ``patch``, split ``c``'s angle into two of at least
    :data:`~vaultgram.topology.reflex.MIN_ANGLE` degrees (the limit of a reflex corner's chord: a sliver
    beside ``c`` would cost more than the singularity it removes), and the new quad ``(b, c, s, t)``
    must turn by less than 180 degrees at ``b`` (a quad past straight folds its mesh). The quad's side
    along the boundary from ``b`` to ``c`` and its opposite side from ``s`` to ``t`` share a count (one edge
    group): their lengths must be within :data:`~vaultgram.topology.reflex.MAX_RATIO` of each other, as
    for a chord's edge group (jagged_1's 281 degree corner: 0.43 against 1.53 gave the mesh an edge of
    0.005 of its median beside the corner)."""
    found = patch_sides(graph, patch)
    if found is None or b not in found.corners:
        return False
    k = found.corners.index(b)
    leaving, arriving = found.sides[k], found.sides[k - 1]
    forward = graph.other(*leaving[0]) == c  # c comes after b along the ring and the patch's side
    side = leaving[:2] if forward else arriving[::-1][:2]
    ends = [graph.other(*h) for h in side] if forward else [u for _, u in side]
    if len(side) < 2 or any(graph.edge_type(e) != BOUNDARY for e, _ in side) or ends[0] != c:
        return False
    pc, ps, pb, pt, other = (graph.get(n, "pos") for n in (c, s, b, t, ends[1]))
    to_s = direction(pc, ps)
    if forward:
        parts = ccw_degrees(direction(pc, other), to_s), ccw_degrees(to_s, direction(pc, pb))
        at_b = ccw_degrees(direction(pb, pc), direction(pb, pt))
    else:
        parts = ccw_degrees(direction(pc, pb), to_s), ccw_degrees(to_s, direction(pc, other))
        at_b = ccw_degrees(direction(pb, pt), direction(pb, pc))
    sides = math.dist(pb, pc), math.dist(ps, pt)  # opposite in the new quad: one edge group
    return (min(parts) >= MIN_ANGLE and at_b < 180.0 and max(sides) <= MAX_RATIO * min(sides)
            and chord_inside(found, pc, ps))


def _ring_angle(ring: np.ndarray, point) -> float:
    """The interior angle (degrees) of a counter-clockwise ring ``ring`` (closed, first point
    repeated) at its vertex nearest ``point``."""
    pts = ring[:-1]
    i = int(np.argmin(np.hypot(*(pts - np.asarray(point, dtype=float)).T)))
    here, before, after = pts[i], pts[i - 1], pts[(i + 1) % len(pts)]
    return ccw_degrees(direction(here, after), direction(here, before))


def _ccw_ring(polygon) -> np.ndarray:
    """A polygon's outline, counter-clockwise, as a closed array of points."""
    return np.asarray(shapely.ops.orient(polygon).exterior.coords)


def flip_angles(graph, tri: int, quad: int, corners: tuple) -> list | None:
    """The corner angles (degrees) of the two patches the flip makes: the union of the triangle ``tri``
    and the quad ``quad`` (the pentagon ``(b, u, v, x, y)``, ``corners`` its corners in that order) cut
    by the straight chord ``v-y``; the new quad's at ``b, u, v, y``, then the new triangle's at ``v, x,
    y``. None where either patch is out of step with the plan or the chord does not run inside the
    pentagon (touching it only at its ends)."""
    found = patch_sides(graph, tri), patch_sides(graph, quad)
    if None in found:
        return None
    pos = {n: np.asarray(graph.get(n, "pos"), dtype=float) for n in corners}
    b, u, v, x, y = corners
    pentagon = shapely.union(found[0].polygon, found[1].polygon)
    d = (pos[y] - pos[v]) * 1e-6
    if pentagon.geom_type != "Polygon" or not shapely.contains_properly(
            pentagon, shapely.LineString([pos[v] + d, pos[y] - d])):
        return None
    parts = shapely.get_parts(shapely.ops.split(pentagon, shapely.LineString([pos[v] - d, pos[y] + d])))
    if len(parts) != 2:
        return None
    near_b = 0 if parts[0].distance(shapely.Point(pos[b])) < parts[1].distance(shapely.Point(pos[b])) else 1
    rings = [_ccw_ring(parts[k]) for k in (near_b, 1 - near_b)]
    return [_ring_angle(rings[0], pos[n]) for n in (b, u, v, y)] + [_ring_angle(rings[1], pos[n]) for n in (v, x, y)]


def flip_rebranch(graph, tri: int, quad: int, b: int, u: int, v: int, x: int, y: int) -> bool:
    """Whether the rebranch ``x-b`` shared by the triangle ``tri = (b, x, y)`` and the quad
    ``quad = (b, u, v, x)`` may flip to the chord ``v-y`` (the pentagon's other diagonal from ``x``'s
    neighbours): the chord runs straight inside the pentagon, leaves :data:`FLIP_MIN_ANGLE` or more
    either side at ``v`` and ``y`` and at each corner of the new triangle ``(v, x, y)``, and the new quad
    ``(b, u, v, y)`` turns by at most :data:`FLIP_MAX_ANGLE` at each corner (a quad past straight folds
    its mesh). Only where the triangle is thinner than :data:`FLIP_THIN` at ``b``. The mirror case (the
    triangle after the quad round ``b``) passes the same roles."""
    found = patch_sides(graph, tri)
    if found is None or not _ring_angle(_ccw_ring(found.polygon), graph.get(b, "pos")) < FLIP_THIN:
        return False
    angles = flip_angles(graph, tri, quad, (b, u, v, x, y))
    return angles is not None and max(angles[:4]) <= FLIP_MAX_ANGLE and min(angles[2:]) >= FLIP_MIN_ANGLE


def register_corner_merge_helpers(f) -> None:
    """Register the helpers with a function registry (``rules/corner_merges.vgr`` calls them)."""
    f.register("spread_rebranch", spread_rebranch, ("node", "node", "node", "node", "node"), "bool", uses_graph=True,
               local=False)
    f.register("flip_rebranch", flip_rebranch, ("node",) * 7, "bool", uses_graph=True, local=False)
