"""Smooth plans as O-grids: four quads round a quad at the centre (issue 12).

A plan whose outline has no corner sharper than 135 degrees (a disc, an oval, a stadium, a regular
polygon of 8 sides or more) has a degenerate skeleton: every branch ends at a corner face and is
pruned (Figure 2d), leaving one singularity with no branch at all. Its dual face is then any three
boundary points (on a disc the Delaunay triangulation (§3.1) may take two close together), and
rebranching (Figure 2e) cuts the plan into three-sided patches whose common pole at the centre is a
fan of as many triangles as the boundary has edges: rv_pillow_pattern got rebranches 19, 161 and
180 degrees apart and a pole of 89 triangles of 4 degrees (scaled Jacobian 0.07); ovals of every
aspect 90-108 triangles. Two of the pillow's patches were too wide at the pole for the three-quad
split of :mod:`vaultgram.meshing.splits`, and spreading the rebranches evenly does not help: a 120
degree sector's arc is longer than twice its radius, so its split puts the inner point one edge
from the boundary. A regular octagon to 12-gon got one patch per corner round a pole of valence n,
each corner (135-150 degrees, regular with two faces) with one face: n boundary singularities.

The structured mesh of such a plan is the O-grid: a quad at the centre and four quads between it and
the boundary. Its corners lie on four rays from the outline's centroid, a quarter turn apart and at
45 degrees to the outline's principal axes (so that on an oval the central quad is a rectangle along
them), three fifths of the way to the boundary points the rays meet (at 0.5 the quads at the centre
are half as wide as those at the boundary on a disc; at 0.6 the pillow plan's worst scaled Jacobian
is 0.81, 0.80 at 0.5). Every patch is four-sided, the central quad's four corners are the only
singular vertices (valence 3) and none is on the boundary: the plan's corners lie on the patches'
sides (rule ``soften_o_grid_corner``), with two faces each. ``rules/topology.vgr`` draws it (rule
``o_grid``) with :func:`o_grid_plan`, which recognises such a plan, :func:`o_grid_centre`,
:func:`o_grid_foot`, which picks the four boundary points, and :func:`o_grid_clear`. A plan with one
corner sharper than 135 degrees (a teardrop's tip) gets a sixth patch with the tip as its corner
(rule ``o_grid_round_tip``, :func:`o_grid_tip_foot`).
"""

from __future__ import annotations

import math
import weakref

import numpy as np
import shapely

from vaultgram.geometry.polygons import elongation, regular_valence
from vaultgram.topology.corners import boundary_angle, graph_rings, ray_hit
from vaultgram.topology.statecache import per_state
from vaultgram.topology.types import BRANCH, CORNER, CURVE_POINT, FEATURE_POINT, SKELETON_VERTEX

__all__ = ["featureless_plan", "lone_skeleton", "o_grid_plan", "o_grid_centre", "o_grid_foot", "o_grid_corner",
           "o_grid_clear", "has_sharp_corner", "o_grid_tip_foot", "principal_axes", "register_o_grid_helpers", "ROUND"]

#: Outlines less elongated than this (:func:`~vaultgram.geometry.polygons.elongation`) are round:
#: the O-grid's corners radial (:func:`o_grid_corner`). rv_pillow_pattern (1.001) has its feet 43
#: rather than 45 degrees off its axes (its 24 points): the 45 degree links made its central quad
#: 6.5 x 5.8 and its worst face 0.818 -> 0.807. The cut disc (1.05) gains 0.791 -> 0.812.
ROUND = 1.02

#: The rule helpers' answers, per state of the rule graph (the rule asks for the same feet at
#: every boundary point it tries).
_ANSWERS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def principal_axes(ring: np.ndarray) -> np.ndarray:
    """The principal axes of a ring's points, scaled by their spread: rows ``sigma_1 e_1`` and
    ``sigma_2 e_2`` (``sigma`` the root mean square distance from the centroid along each axis), the
    larger first. A ring without a preferred direction (the two second moments within 1e-9: a disc, a
    regular polygon) takes the x and y axes.

    >>> t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    >>> (np.round(principal_axes(np.column_stack([2 * np.cos(t), np.sin(t)])), 6) + 0.0).tolist()
    [[1.414214, 0.0], [0.0, 0.707107]]
    >>> axes = principal_axes(np.column_stack([np.cos(t) - np.sin(t), np.cos(t) + 2 * np.sin(t)]))
    >>> round(math.degrees(math.atan2(axes[0, 1], axes[0, 0])) % 180, 1)
    106.8
    """
    d = ring - ring.mean(axis=0)
    sxx, syy, sxy = (float(a @ b) / len(d) for a, b in ((d[:, 0], d[:, 0]), (d[:, 1], d[:, 1]), (d[:, 0], d[:, 1])))
    gap = math.hypot(sxx - syy, 2 * sxy)
    angle = 0.0 if gap <= 1e-9 * (sxx + syy) else 0.5 * math.atan2(2 * sxy, sxx - syy)
    c, s = math.cos(angle), math.sin(angle)
    major, minor = (sxx + syy + gap) / 2, max((sxx + syy - gap) / 2, 0.0)
    return np.array([[c, s], [-s, c]]) * np.sqrt([[major], [minor]])


def o_grid_plan(graph) -> bool:
    """Whether the rule graph's plan is one ring with no point or curve feature inside and no corner
    sharper than 135 degrees (at most one where the skeleton has no branch), its centroid inside it:
    the plans whose skeleton can shrink to one singularity without a branch or to one branch. Their
    corners of 135 degrees or more are regular as the side points of an O-grid's patches (valence 3
    from 135 to 225 degrees, :func:`~vaultgram.geometry.polygons.regular_valence`: a regular
    octagon's); a sharp one (the tip of a teardrop, :func:`sharp_corner`) is the corner of a sixth patch
    (:func:`o_grid_tip_foot`). A
    branch with a sharp corner at an end is cut in three instead (``cut_lone_branch``)."""
    memo = per_state(_ANSWERS, graph, lambda g: {})
    if "plan" not in memo:
        corners = list(graph.of_types(graph.schema.subtypes(CORNER)))
        sharp = regular_valence(np.array([boundary_angle(graph, c) for c in corners], dtype=float)) != 3
        memo["sharp"] = [c for c, s in zip(corners, sharp) if s]
        sharp_allowed = 1 if next(iter(graph.of_types([BRANCH])), None) is None else 0  # else cut in three
        memo["plan"] = (featureless_plan(graph) and len(memo["sharp"]) <= sharp_allowed
                        and shapely.Polygon(graph_rings(graph)[0][0]).contains(shapely.Point(o_grid_centre(graph))))
    return memo["plan"]


def sharp_corner(graph) -> int | None:
    """The one corner of an O-grid plan (:func:`o_grid_plan`) sharper than 135 degrees, or None."""
    o_grid_plan(graph)
    sharp = per_state(_ANSWERS, graph, lambda g: {})["sharp"]
    return sharp[0] if sharp else None


def featureless_plan(graph) -> bool:
    """Whether the rule graph's plan is one ring (no hole) of three points or more with no point or
    curve feature inside: its skeleton is one connected piece drawn by the outline alone."""
    memo = per_state(_ANSWERS, graph, lambda g: {})
    if "featureless" not in memo:
        rings = graph_rings(graph)[0]
        inside = frozenset().union(*(graph.schema.subtypes(t) for t in (FEATURE_POINT, CURVE_POINT)))
        memo["featureless"] = (len(rings) == 1 and len(rings[0]) >= 3
                               and next(iter(graph.of_types(inside)), None) is None)
    return memo["featureless"]


def lone_skeleton(graph) -> bool:
    """Whether the rule graph's skeleton is one singularity without a branch, or one branch and no
    singularity (between two corners: a lens, a disc cut by a wall)."""
    memo = per_state(_ANSWERS, graph, lambda g: {})
    if "lone" not in memo:
        skeleton = sum(1 for _ in graph.of_types(graph.schema.subtypes(SKELETON_VERTEX)))
        memo["lone"] = (skeleton, sum(1 for _ in graph.of_types([BRANCH]))) in ((1, 0), (0, 1))
    return memo["lone"]


def o_grid_centre(graph) -> tuple[float, float]:
    """The centre of the O-grid: the centroid of the area inside the (outer) ring. Not the
    singularity: on a stadium every point of the segment between its two half circles' centres has a
    maximal circle of the same radius, and the discrete skeleton's one singularity may lie anywhere
    on it."""
    memo = per_state(_ANSWERS, graph, lambda g: {})
    if "centre" not in memo:
        c = shapely.Polygon(graph_rings(graph)[0][0]).centroid
        memo["centre"] = (float(c.x), float(c.y))
    return memo["centre"]


def o_grid_foot(graph, k: int) -> int:
    """The ring point nearest to where the ray from :func:`o_grid_centre` meets the ring, the ray
    along ``sigma_1 cos(t) e_1 + sigma_2 sin(t) e_2`` with ``t`` = 45 + 90 ``k`` degrees and the
    outline's principal axes (:func:`principal_axes`): on an ellipse, the points of parameter 45, 135,
    225 and 315 degrees, so that the central quad is a rectangle of the ellipse's proportions. With a
    sharp corner (:func:`sharp_corner`) the rays turn so that the first goes through it: the central
    quad's corner 0 lies on the way to the tip, and links to :func:`o_grid_tip_foot` on either side of
    it rather than to the tip."""
    memo = per_state(_ANSWERS, graph, lambda g: {})
    if ("foot", k) not in memo:
        rings, nodes = graph_rings(graph)
        axes, centre, tip = principal_axes(rings[0]), np.asarray(o_grid_centre(graph)), sharp_corner(graph)
        if tip is None:
            turn = math.pi / 4 + k * math.pi / 2
        else:  # the first ray through the sharp corner, in the same scaled frame
            u = np.linalg.solve(axes.T, np.asarray(graph.get(tip, "pos"), dtype=float) - centre)
            turn = math.atan2(u[1], u[0]) + k * math.pi / 2
        direction = np.array([math.cos(turn), math.sin(turn)]) @ axes
        hit = ray_hit(rings[:1], centre, direction)  # inside: it meets the ring
        memo[("foot", k)] = nodes[0][int(np.argmin(np.hypot(*(rings[0] - hit).T)))]
    return memo[("foot", k)]


def o_grid_corner(graph, k: int, inner: float) -> tuple[float, float]:
    """Corner ``k`` of the O-grid's central quad, between :func:`o_grid_centre` and foot ``k``
    (:func:`o_grid_foot`), so that the ring of four patches round the quad is as thick at the ends of
    an elongated plan as at its sides. With the foot's offset ``(a, b)`` from the centre along the
    outline's principal axes (major, minor), the corner is ``(a - (1 - inner) |b| sign(a), inner b)``:
    the fraction ``inner`` of the way across the minor axis, as before, and as far in from the foot
    along the major axis, so that the link to the foot is at 45 degrees to the axes. Radial (the
    fraction ``inner`` of the way to the foot) where that is farther in (``|a| <= |b|``: a disc, a
    regular polygon, whose feet have ``a = b``, keep their corners), on a round plan (:data:`ROUND`) and on
    a plan with a sharp corner (:func:`sharp_corner`: the teardrop's first ray goes through its tip,
    ``b = 0``, where the corner would fall on the tip).

    On the stadium (20 x 4 between half circles) the radial corners left the central quad 12 x 2.4,
    the end patches 8.3 round the half circle and 2.4 wide inside, the side patches 20 long at the
    boundary and 12 inside (scaled Jacobian 0.36, mean 0.78)."""
    memo = per_state(_ANSWERS, graph, lambda g: {})
    if ("corner", k, inner) not in memo:
        rings, nodes = graph_rings(graph)
        centre = np.asarray(o_grid_centre(graph))
        d = np.asarray(graph.get(o_grid_foot(graph, k), "pos"), dtype=float)[:2] - centre
        axes = principal_axes(rings[0])
        unit = axes / np.maximum(np.hypot(*axes.T), 1e-300)[:, None]
        a, b = unit @ d
        along = abs(a) - (1 - inner) * abs(b)
        if (sharp_corner(graph) is not None or elongation(rings[0]) < ROUND
                or along <= inner * abs(a) + 1e-9 * math.hypot(a, b)):
            corner = centre + inner * d
        else:
            corner = centre + np.array([math.copysign(along, a), inner * b]) @ unit
        memo[("corner", k, inner)] = (float(corner[0]), float(corner[1]))
    return memo[("corner", k, inner)]


def has_sharp_corner(graph) -> bool:
    """Whether the O-grid plan has a corner sharper than 135 degrees (:func:`sharp_corner`)."""
    return sharp_corner(graph) is not None


def o_grid_tip_foot(graph, side: int, inner: float) -> int:
    """With a sharp corner (:func:`sharp_corner`, the tip of a teardrop), the ring point on side
    ``side`` (0 or 1) of the tip that the central quad's corner towards the tip (corner 0,
    :func:`o_grid_corner` with ``inner``) links to instead of the tip itself. The two links split the
    angle round that corner outside the central quad into three equal parts, symmetrically about the
    direction to the tip (45 degrees off it where the quad's angle there is 90): the ring point nearest
    to where the ray meets the ring. The tip is then the corner of one patch, a quad with the tip's
    angle and a third of the rest at the quad's corner, which has four links (regular); as a foot the
    tip was the corner of two patches, each with half its angle (issue 12: one face below 135 degrees).
    """
    memo = per_state(_ANSWERS, graph, lambda g: {})
    if ("tip foot", side, inner) not in memo:
        rings, nodes = graph_rings(graph)
        corner = np.asarray(o_grid_corner(graph, 0, inner))
        to_tip = np.asarray(graph.get(sharp_corner(graph), "pos"), dtype=float)[:2] - corner
        sides = [np.asarray(o_grid_corner(graph, k, inner)) - corner for k in (1, 3)]
        quad = math.acos(np.clip(np.dot(*sides) / (np.hypot(*sides[0]) * np.hypot(*sides[1])), -1.0, 1.0))
        turn = (2 * math.pi - quad) / 6 * (1 if side == 0 else -1)
        c, s = math.cos(turn), math.sin(turn)
        hit = ray_hit(rings[:1], corner, np.array([c * to_tip[0] - s * to_tip[1], s * to_tip[0] + c * to_tip[1]]))
        memo[("tip foot", side, inner)] = nodes[0][int(np.argmin(np.hypot(*(rings[0] - hit).T)))]
    return memo[("tip foot", side, inner)]


def o_grid_clear(graph, inner: float) -> bool:
    """Whether the O-grid's links lie inside the plan: the central quad's four sides and the links
    from its corners (:func:`o_grid_corner`, with the fraction ``inner``) to the feet
    (:func:`o_grid_foot`; with a sharp corner, from corner 0 to :func:`o_grid_tip_foot` on either side
    too). A plan that bends round its centroid (a bean) fails it."""
    memo = per_state(_ANSWERS, graph, lambda g: {})
    if ("clear", inner) not in memo:
        rings, nodes = graph_rings(graph)
        ring = rings[0]
        feet = ring[[nodes[0].index(o_grid_foot(graph, k)) for k in range(4)]]
        quad = np.array([o_grid_corner(graph, k, inner) for k in range(4)])
        links = [[quad[k], quad[(k + 1) % 4]] for k in range(4)] + [[quad[k], feet[k]] for k in range(4)]
        if has_sharp_corner(graph):
            links += [[quad[0], ring[nodes[0].index(o_grid_tip_foot(graph, side, inner))]] for side in (0, 1)]
        plan = shapely.Polygon(ring).buffer(1e-9 * np.ptp(ring, axis=0).max())  # the feet lie on its outline
        memo[("clear", inner)] = bool(plan.contains(shapely.MultiLineString(links)))
    return memo[("clear", inner)]


def register_o_grid_helpers(f) -> None:
    """Register :func:`featureless_plan`, :func:`lone_skeleton`, :func:`o_grid_plan`, :func:`o_grid_centre`,
    :func:`o_grid_foot`, :func:`o_grid_corner` and :func:`o_grid_clear` for the rules (they read the
    whole ring)."""
    f.register("featureless_plan", featureless_plan, (), "bool", uses_graph=True, local=False)
    f.register("lone_skeleton", lone_skeleton, (), "bool", uses_graph=True, local=False)
    f.register("o_grid_plan", o_grid_plan, (), "bool", uses_graph=True, local=False)
    f.register("o_grid_centre", o_grid_centre, (), "vec2", uses_graph=True, local=False)
    f.register("o_grid_foot", o_grid_foot, ("int",), "node", uses_graph=True, local=False)
    f.register("o_grid_corner", o_grid_corner, ("int", "number"), "vec2", uses_graph=True, local=False)
    f.register("o_grid_clear", o_grid_clear, ("number",), "bool", uses_graph=True, local=False)
    f.register("has_sharp_corner", has_sharp_corner, (), "bool", uses_graph=True, local=False)
    f.register("sharp_corner", sharp_corner, (), "node", uses_graph=True, local=False)
    f.register("o_grid_tip_foot", o_grid_tip_foot, ("int", "number"), "node", uses_graph=True, local=False)
