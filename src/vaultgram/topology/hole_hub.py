"""Hole corners inside a patch side beside a narrow fan triangle: the helpers of ``rules/corners.vgr``'s
``split_hole_side_at_hub`` (issue 12, item 2; paper §3.2 and §4.1).

A reflex corner ``r`` of a hole (225-315 degrees, three faces) inside a side ``a -> b`` of the ring
patch ``P = (a, b, c, d)`` takes a cut across ``P`` (:func:`~vaultgram.topology.reflex.reflex_cut`)
or, where the cut's strip is the one triangle ``T = (d, c, F)`` of a point feature ``F``'s fan beyond
``P``'s side ``c -> d``, a rebranch to ``F`` (:mod:`vaultgram.topology.hole_sides`) or a cut to the foot
bisecting ``T``. Where ``T`` is narrow at ``F`` (36-54 degrees: a cut leaves two fan triangles of
18-27) and the pentagon ``P + T`` turns past straight at ``c`` or ``d`` (the fan's side from ``F``
runs on through ``d`` to the hole corner ``a``, so the chord ``r -> F`` would leave a quad turning
there), none serves: 12 of the 24 boundary singular vertices of the 700 saved random plans (s25).

The hexagon ``(a, r, b, c, F, d)`` is split into three quads round a new inner point ``X`` instead:
``(r, b, c, X)``, ``(c, F, d, X)`` and ``(d, a, r, X)``; the branch ``c - d`` goes. ``r`` becomes the
corner of two quads (the chords of ``rules/corners.vgr`` give it its third, as at any hole corner of
two patches), ``c``, ``d``, ``a`` and ``b`` keep their number of patches, ``F`` (singular by design,
§4.1) has a quad's corner for the narrow triangle's fan, and ``X`` is an inner vertex of valence 3:
the index ``r`` gives up goes inside the plan, as where the mesher splits a triangle round an inner
point. ``X`` lies on the chord from ``r`` to a foot on ``c - d`` (where a cut's strip would cross it),
:data:`HUB_STEPS` of the way, at the place whose worst quad angle is widest (:func:`_best_hub`).
Only where the three chords run inside ``P``, every angle of the three quads is within
:data:`MIN_HUB_ANGLE` to :data:`MAX_HUB_ANGLE` (at ``r`` at least
:data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE`), and each quad's opposite sides are within
:data:`MAX_HUB_RATIO` of each other in length (one edge group, §3.2).
"""

from __future__ import annotations

import math
import weakref

import numpy as np

from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.topology import hole_sides, reflex
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.statecache import memo_at
from vaultgram.topology.strips import chord_inside, edge_cut, patch_sides

__all__ = ["hub_at", "hub_edge", "hub_index", "hub_patch", "hub_pole", "hub_point", "MIN_HUB_ANGLE",
           "MAX_HUB_ANGLE", "MAX_HUB_RATIO", "register_hole_hub_helpers"]

#: Degrees: no angle of the three new quads narrower (a quad corner of 30 degrees has a scaled
#: Jacobian of 0.5), but at ``F`` (the fan triangle's angle there, kept) and at ``r``.
MIN_HUB_ANGLE = 30.0
#: Degrees: no angle of the three new quads wider (a quad corner of 165 degrees has a scaled Jacobian
#: of 0.26; the pentagon's angle of 191-265 degrees at ``c`` or ``d`` is split by the chord there).
MAX_HUB_ANGLE = 165.0

#: Each new quad's opposite sides (one edge group, §3.2) may differ in length by this factor at most:
#: more than the rebranch's :data:`~vaultgram.topology.hole_sides.MAX_GROUP_RATIO` (4), as the hub only
#: serves corners every other rule leaves singular. On the 700 saved random plans of session 25,
#: plans 461 and 462 take it only above 4 (4.35: the ring patch's long side against the chord from
#: the corner to ``X``), for no loss (min scaled Jacobian 0.402 either way, 835 faces for 851).
MAX_HUB_RATIO = 5.0
#: Where ``X`` may lie along the chord from ``r`` to a foot on ``c - d`` (fractions of its length).
HUB_STEPS = (0.5, 0.4, 0.6, 0.3, 0.7)

_STATE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # graph -> {state: {corner: choice}}


def _hub(graph, r: int):
    """The hub split for the hole corner ``r`` (see the module docstring): ``(patch, side index, edge
    c - d, fan triangle, pole F, position of X)``, or None. A fallback after the cut, the rebranch and
    the bisecting cut."""
    if not hole_sides.inside_corner(graph, r) or hole_sides.fan_rebranch_at(graph, r):
        return None
    if reflex.reflex_bisecting_cut_at(graph, r):
        return None
    cand = hole_sides.rebranch_candidate(graph, r)  # None where the cut qualifies
    if cand is None:
        return None
    patch, i, edge, tri, pole, fan = cand
    found, sides = patch_sides(graph, patch), patch_sides(graph, tri)
    c, d = found.corners[(i + 2) % 4], found.corners[(i + 3) % 4]
    t = sides.corners.index(pole) if pole in sides.corners else -1
    if t < 0 or (sides.corners[(t + 1) % 3], sides.corners[t - 1]) != (d, c):
        return None
    x = _best_hub(graph, r, found, i, sides, t, edge)
    return None if x is None else (patch, i, edge, tri, pole, (float(x[0]), float(x[1])))


def _best_hub(graph, r: int, found, i: int, sides, t: int, edge: int):
    """Where ``X`` goes: of the points :data:`HUB_STEPS` of the way from ``r`` to a foot of
    :data:`~vaultgram.topology.reflex.FEET` along ``c - d``, the one whose worst quad angle is widest
    (the least sine), where the angles fit (:func:`_angles_fit`) and the sides are even (:func:`_even`);
    None where none does."""
    pos, best = np.asarray(graph.get(r, "pos"), dtype=float), None
    for f in reflex.FEET:
        foot = np.asarray(edge_cut(graph, edge, f)[1], dtype=float)
        for step in HUB_STEPS:
            x = pos + step * (foot - pos)
            angles = _hub_angles(graph, r, found, i, sides, t, x)
            if angles is None or not _angles_fit(angles) or not _even(graph, found, i, r, sides, t, x):
                continue
            score = min(math.sin(math.radians(a)) for a in angles)
            if best is None or score > best[0] + 1e-12:
                best = (score, x)
    return None if best is None else best[1]


def _angles_fit(angles: list) -> bool:
    """Whether the three quads' angles (:func:`_hub_angles`) are all within :data:`MIN_HUB_ANGLE` to
    :data:`MAX_HUB_ANGLE`, those at ``r`` from :data:`~vaultgram.topology.reflex.MIN_CUT_ANGLE`."""
    return (min(angles[:2]) >= reflex.MIN_CUT_ANGLE
            and all(MIN_HUB_ANGLE <= a <= MAX_HUB_ANGLE for a in angles))


def _hub_angles(graph, r: int, found, i: int, sides, t: int, x) -> list | None:
    """The angles (degrees) of the three quads round ``x``: at ``r`` (two), at ``c`` and ``d`` (two
    each: the pentagon's angle there split by the chord to ``x``) and at ``x`` (three), each between
    the first steps of its sides as :func:`~vaultgram.topology.reflex.patch_corner` measures a patch's;
    None where a chord leaves ``P`` (``found``; ``x`` must lie inside it) or the angles at ``x`` do
    not close (``x`` outside the triangle ``r, c, d``'s order)."""
    c, d = found.corners[(i + 2) % 4], found.corners[(i + 3) % 4]
    pos = {n: graph.get(n, "pos") for n in (r, c, d)}
    if not all(chord_inside(found, pos[n], x) for n in (r, c, d)):
        return None
    to_x = {n: direction(pos[n], x) for n in (r, c, d)}
    from_x = {n: direction(x, pos[n]) for n in (r, c, d)}
    p_c = reflex.patch_corner(graph, found, (i + 2) % 4)[2]
    _, p_out_d, p_d = reflex.patch_corner(graph, found, (i + 3) % 4)
    _, t_out_c, t_c = reflex.patch_corner(graph, sides, (t - 1) % 3)  # T at c: leaving towards F
    t_d = reflex.patch_corner(graph, sides, (t + 1) % 3)[2]
    first = ccw_degrees(reflex.boundary_ahead(graph, r), to_x[r])
    at_c = ccw_degrees(t_out_c, to_x[c])  # quad (c, F, d, X) at c; (r, b, c, X) has the rest
    at_d = ccw_degrees(p_out_d, to_x[d])  # quad (d, a, r, X) at d; (c, F, d, X) has the rest
    around = [ccw_degrees(from_x[r], from_x[c]), ccw_degrees(from_x[c], from_x[d]), ccw_degrees(from_x[d], from_x[r])]
    if abs(sum(around) - 360.0) > 1e-6:
        return None
    return [first, boundary_angle(graph, r) - first, at_c, p_c + t_c - at_c, at_d, p_d + t_d - at_d, *around]


def _even(graph, found, i: int, r: int, sides, t: int, x) -> bool:
    """Whether each new quad's opposite sides are within :data:`MAX_HUB_RATIO` of each other in
    length (one edge group each, §3.2: the longer's count would over-refine the shorter)."""
    side = found.sides[i]
    k = next(j for j, (_, u) in enumerate(side) if u == r)
    a_r, r_b = reflex.side_length(graph, side[:k]), reflex.side_length(graph, side[k:])
    b_c, d_a = (reflex.side_length(graph, found.sides[(i + j) % 4]) for j in (1, 3))
    f_d, c_f = reflex.side_length(graph, sides.sides[t]), reflex.side_length(graph, sides.sides[t - 1])
    x_r, x_c, x_d = (math.dist(x, graph.get(n, "pos")) for n in (r, found.corners[(i + 2) % 4],
                                                                  found.corners[(i + 3) % 4]))
    pairs = ((r_b, x_c), (b_c, x_r), (c_f, x_d), (f_d, x_c), (d_a, x_r), (a_r, x_d))
    return all(max(p) <= MAX_HUB_RATIO * min(p) for p in pairs)


def _once(graph, r: int):
    """:func:`_hub`, worked out once per corner and state of the graph."""
    return memo_at(_STATE, graph, r, lambda: _hub(graph, r))


def hub_at(graph, r: int) -> bool:
    """Whether the hole corner ``r`` takes the hub split (see the module docstring)."""
    return _once(graph, r) is not None


def _part(graph, patch: int, r: int, k: int, other):
    """Item ``k`` of ``r``'s hub split (:func:`_hub`) where it lies in ``patch``; ``other`` otherwise."""
    got = _once(graph, r)
    return got[k] if got is not None and got[0] == patch else other


def hub_index(graph, patch: int, r: int) -> int:
    """The index of the side of ``patch`` inside which ``r`` lies, where it takes the hub split; -1
    otherwise."""
    return _part(graph, patch, r, 1, -1)


def hub_edge(graph, patch: int, r: int) -> int:
    """The plan edge (``c - d``, between ``patch`` and the fan triangle) the hub split of ``r`` removes;
    -1 where ``r`` takes none in ``patch``."""
    return _part(graph, patch, r, 2, -1)


def hub_patch(graph, patch: int, r: int) -> int:
    """The fan triangle's Patch node split with ``patch`` by ``r``'s hub; ``patch`` otherwise."""
    return _part(graph, patch, r, 3, patch)


def hub_pole(graph, patch: int, r: int) -> int:
    """The point feature (the fan's pole) of the triangle split with ``patch``; ``r`` otherwise."""
    return _part(graph, patch, r, 4, r)


def hub_point(graph, patch: int, r: int) -> tuple[float, float]:
    """Where the inner point ``X`` of ``r``'s hub split lies (``r``'s position where there is none)."""
    pos = graph.get(r, "pos")
    return _part(graph, patch, r, 5, (float(pos[0]), float(pos[1])))


def register_hole_hub_helpers(f) -> None:
    """Register the helpers with a function registry (``rules/corners.vgr`` calls them)."""
    f.register("hub_at", hub_at, ("node",), "bool", uses_graph=True, local=False)
    for name, fn, returns in (("hub_index", hub_index, "int"), ("hub_edge", hub_edge, "edge"),
                              ("hub_patch", hub_patch, "node"), ("hub_pole", hub_pole, "node"),
                              ("hub_point", hub_point, "vec2")):
        f.register(name, fn, ("node", "node"), returns, uses_graph=True, local=False)
