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
"""

from __future__ import annotations

import math

from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.topology.reflex import MAX_RATIO, MIN_ANGLE
from vaultgram.topology.strips import chord_inside, patch_sides
from vaultgram.topology.types import BOUNDARY

__all__ = ["spread_rebranch", "register_corner_merge_helpers"]


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


def register_corner_merge_helpers(f) -> None:
    """Register the helper with a function registry (``rules/corner_merges.vgr`` calls it)."""
    f.register("spread_rebranch", spread_rebranch, ("node", "node", "node", "node", "node"), "bool", uses_graph=True,
               local=False)
