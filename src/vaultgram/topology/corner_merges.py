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

Where the quad is flat at ``v`` (170 degrees or more there: jagged_1's 281 and jagged_2's 307 degree
corners, 178.2 and 172.0), every diagonal of the pentagon leaves a sliver (``v`` is a point on the
side ``u-x``, not a corner); the pentagon is cut instead from ``v`` to the strip point ``m`` of its
side ``y-b`` opposite ``v`` (``strip_over_served_corner``): the quads ``(b, u, v, m)`` and ``(m, v, x, y)``,
the strip carried on through the patch beyond ``y-b`` by the strip rules (``rules/strips.vgr``), as a
reflex corner's chord is. ``b`` keeps one patch less, ``v`` takes one more (regular where the flat
corner's other patches are two; :func:`flat_corner_strip` checks the cut).
"""

from __future__ import annotations

import math

import numpy as np
import shapely
import shapely.ops

from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.topology.reflex import MAX_RATIO, MIN_ANGLE, strip_beyond
from vaultgram.topology.strips import chord_inside, patch_sides, strip_point
from vaultgram.topology.types import BOUNDARY

__all__ = ["flip_rebranch", "flip_angles", "spread_rebranch", "flat_corner_strip", "flat_cut_angles",
           "register_corner_merge_helpers"]

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

#: The least angle (degrees) of the quad ``(b, u, v, x)`` at ``v`` at which ``v`` is a point on the side
#: ``u-x`` rather than a corner (:func:`flat_corner_strip`): jagged_1's 281 degree corner's quad is
#: 178.2 there, jagged_2's 307 degree corner's 172.0 (s30-jmany3: 167-179 beside every over-served
#: corner left).
FLAT_CORNER = 170.0


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
    return _split_angles(pentagon, tuple(pos[n] for n in (b, u, v, y)), tuple(pos[n] for n in (v, x, y)),
                         pos[v], pos[y])


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


def _split_angles(pentagon, near: tuple, far: tuple, a, c) -> list | None:
    """The corner angles (degrees) of the two parts into which the straight chord from ``a`` to ``c``
    cuts ``pentagon`` (a shapely polygon): the part nearer ``near[0]``'s at the points ``near``
    (positions), then the other's at ``far``. None where the chord does not
    run inside the pentagon (touching its outline only at its ends) or cuts it into other than two."""
    a, c = np.asarray(a, dtype=float), np.asarray(c, dtype=float)
    d = (c - a) * 1e-6
    if pentagon.geom_type != "Polygon" or not shapely.contains_properly(pentagon, shapely.LineString([a + d, c - d])):
        return None
    parts = shapely.get_parts(shapely.ops.split(pentagon, shapely.LineString([a - d, c + d])))
    if len(parts) != 2:
        return None
    first = shapely.Point(near[0])
    k = 0 if parts[0].distance(first) < parts[1].distance(first) else 1
    rings = _ccw_ring(parts[k]), _ccw_ring(parts[1 - k])
    return [_ring_angle(rings[0], p) for p in near] + [_ring_angle(rings[1], p) for p in far]


def flat_cut_angles(graph, tri: int, quad: int, corners: tuple, edge: int) -> list | None:
    """The corner angles (degrees) of the two quads into which the straight chord from ``v`` to the
    strip point ``m`` of the plan edge ``edge`` (the side ``y-b`` of the triangle ``tri``) cuts the
    pentagon ``(b, u, v, x, y)`` (``corners``), the union of ``tri = (b, x, y)`` and the quad
    ``quad = (b, u, v, x)``: the quad ``(b, u, v, m)``'s at ``b, u, v, m``, then ``(m, v, x, y)``'s at
    ``m, v, x, y``. None where a patch is out of step with the plan or the chord leaves the pentagon."""
    found = patch_sides(graph, tri), patch_sides(graph, quad)
    if None in found:
        return None
    pos = {n: np.asarray(graph.get(n, "pos"), dtype=float) for n in corners}
    b, u, v, x, y = corners
    m = np.asarray(strip_point(graph, edge), dtype=float)
    pentagon = shapely.union(found[0].polygon, found[1].polygon)
    return _split_angles(pentagon, (pos[b], pos[u], pos[v], m), (m, pos[v], pos[x], pos[y]), pos[v], m)


def flat_corner_strip(graph, tri: int, quad: int, b: int, u: int, v: int, x: int, y: int, edge: int) -> bool:
    """Whether the pentagon ``(b, u, v, x, y)`` of the triangle ``tri = (b, x, y)`` and the quad
    ``quad = (b, u, v, x)`` (the rebranch ``x-b`` between them) may be cut from ``v`` to the strip point
    of ``edge``, the rebranch ``y-b`` (``strip_over_served_corner``): the quad is flat at ``v``
    (:data:`FLAT_CORNER` or more: ``v`` is a point on its side ``u-x``, so every diagonal of the
    pentagon leaves a sliver, s30-jmany3), the strip through ``edge`` completes in the patches beyond
    without ending in a triangle at a point it would change
    (:func:`~vaultgram.topology.reflex.strip_beyond`, as a reflex corner's chord's; not back through
    ``quad``), the chord runs straight inside the pentagon and leaves
    :data:`~vaultgram.topology.reflex.MIN_ANGLE` or more either side at ``v`` and at the strip point
    (a reflex corner's chord's bound), and no corner of the two quads turns past straight (§3.1's
    rebranches, §4.2's strips). The mirror case (the triangle after the quad round ``b``) passes the
    same roles."""
    found = patch_sides(graph, quad)
    if found is None or not _ring_angle(_ccw_ring(found.polygon), graph.get(v, "pos")) >= FLAT_CORNER:
        return False
    walk = strip_beyond(graph, tri, edge)
    if walk is None or quad in walk.patches:
        return False
    angles = flat_cut_angles(graph, tri, quad, (b, u, v, x, y), edge)
    return angles is not None and min(angles[2:6]) >= MIN_ANGLE and max(angles) < 180.0


def register_corner_merge_helpers(f) -> None:
    """Register the helpers with a function registry (``rules/corner_merges.vgr`` calls them)."""
    f.register("spread_rebranch", spread_rebranch, ("node", "node", "node", "node", "node"), "bool", uses_graph=True,
               local=False)
    f.register("flip_rebranch", flip_rebranch, ("node",) * 7, "bool", uses_graph=True, local=False)
    f.register("flat_corner_strip", flat_corner_strip, ("node",) * 7 + ("edge",), "bool", uses_graph=True,
               local=False)
