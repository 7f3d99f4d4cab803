"""Lone corners of 135 to 225 degrees split to the skeleton: the helper of ``rules/corners.vgr``'s
``split_lone_corner_quad`` (issue 12, item 3; paper §3.1-3.2, Figure 3).

A corner ``b`` of 135 to 225 degrees (regular valence 3: two faces) that is the corner of one quad
``(b, c, x, a)`` only has one face, a boundary singularity. On the saved random plans these are the tips
of quads between two rebranches from one skeleton vertex ``x`` (a kite whose sides at ``b`` are short
boundary sides, its sides at ``x`` long rebranches), where moving a rebranch to ``b``
(``move_rebranch_to_lone_corner``) is refused: the triangle it cuts off would have its pole at ``b`` and
all three sides in one edge group, a short boundary side against a long rebranch
(:data:`~vaultgram.topology.reflex.MAX_POLE_RATIO`). The diagonal from ``b`` to ``x`` splits the quad into
two triangles ``(b, c, x)`` and ``(x, a, b)`` whose pole is ``x``, the skeleton vertex (the one corner
inside the plan, :func:`vaultgram.meshing.layout.choose_pole`): each is meshed as a fan round ``x``
(or split in three quads where that fan is too thin, :mod:`vaultgram.meshing.splits`), and ``b``, a
corner of each, gets one face in both: two, regular. A fan triangle's sides at its pole form one edge
group and the side opposite its own (Figure 3), so the long rebranches and the diagonal (about as
long) share a count and the short boundary sides keep theirs: no group joins a short side to a long
one. ``x`` gains a face, and stays an interior singularity.

The two triangles' sides at ``x`` are one edge group, so the diagonal joins the quad's two groups (the
strip of quads through ``c -> x`` and ``a -> b``, and the one through ``x -> a`` and ``b -> c``). Where
one of them runs on to sides much longer than the other's, the join raises the other's count along its
whole strip: multiple_lobes' 136 degree corner, a strip reaching a 23 long lobe side joined to one whose
longest side is 4.7, tripled the mesh (1080 faces to 3024). So the longest side along either strip
(:func:`strip_lengths`) must be within :data:`~vaultgram.topology.reflex.MAX_RATIO` of the other's.
"""

from __future__ import annotations

from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.topology import reflex
from vaultgram.topology.strips import chord_inside, patch_across, patch_sides, side_edge, strip_walk

__all__ = ["lone_diagonal", "register_lone_corner_helpers", "strip_lengths"]


def lone_diagonal(graph, patch: int, b: int, x: int) -> bool:
    """Whether the diagonal from the corner ``b`` of the quad ``patch`` to its opposite corner ``x``
    runs straight inside the quad, splits its angle at ``b`` into two of at least
    :data:`~vaultgram.topology.reflex.MIN_ANGLE` degrees (the limit of a reflex corner's chord:
    a sliver beside ``b`` would cost more than its singularity) and joins two edge groups whose
    longest sides are within :data:`~vaultgram.topology.reflex.MAX_RATIO` of each other (see the
    module docstring)."""
    found = patch_sides(graph, patch)
    if found is None or len(found.corners) != 4 or b not in found.corners:
        return False
    k = found.corners.index(b)
    if found.corners[(k + 2) % 4] != x:
        return False
    pos, d_out, whole = reflex.patch_corner(graph, found, k)
    to = graph.get(x, "pos")
    first = ccw_degrees(d_out, direction(pos, to))
    if not (reflex.MIN_ANGLE <= first <= whole - reflex.MIN_ANGLE and chord_inside(found, pos, to)):
        return False
    longest = [max(strip_lengths(graph, patch, found, (k + j) % 4)) for j in (1, 2)]
    return max(longest) <= reflex.MAX_RATIO * min(longest)


def strip_lengths(graph, patch: int, found, i: int) -> list[float]:
    """The lengths of the sides in one edge group with the side ``i`` of the quad ``patch`` (its sides
    ``found``), as far as the strip of quads through it shows them: that side, the opposite one, and
    the side each quad beyond side ``i`` has opposite the one the strip enters by
    (:func:`~vaultgram.topology.strips.strip_walk`; none where the walk does not complete)."""
    lengths = [reflex.side_length(graph, found.sides[i]), reflex.side_length(graph, found.sides[(i + 2) % 4])]
    edge = side_edge(graph, patch, found.corners[i])
    beyond = patch_across(graph, patch, edge) if edge >= 0 else None
    walk = strip_walk(graph, beyond[0], beyond[1], frozenset([patch])) if beyond is not None else None
    for q, e in zip(walk.patches, walk.edges) if walk is not None else ():
        sides = patch_sides(graph, q)
        entry = [j for j, side in enumerate(sides.sides) if len(side) == 1 and side[0][0] == e]
        if len(sides.corners) == 4 and entry:
            lengths.append(reflex.side_length(graph, sides.sides[(entry[0] + 2) % 4]))
    return lengths


def register_lone_corner_helpers(f) -> None:
    """Register the helper with a function registry (``rules/corners.vgr`` calls it)."""
    f.register("lone_diagonal", lone_diagonal, ("node", "node", "node"), "bool", uses_graph=True, local=False)
