"""Three-sided patches meshed as three quads where Figure 3's fan would be too thin (issue 12).

Figure 3 meshes a three-sided patch as a quad with one side collapsed to the pole: ``n`` triangles
fan round the pole, ``n`` the count of the side opposite it. Their corners at the pole share the
patch's angle there, so with ``n`` large for that angle no smoothing can give them a scaled Jacobian
above the floor (:func:`vaultgram.meshing.fans.fan_bounds`; 12 triangles in a 90 degree corner reach
0.15 at best, issue 12 asks for 0.3).

Where a fan's triangles would be thinner than :data:`FAN_FLOOR` the patch is meshed instead as three
quads meeting at an inner point ``O`` (the midpoint subdivision of a triangle). With the pole ``A``,
its sides ``AB`` and ``AC`` of count ``m`` (one edge group, §3.2) and the opposite side ``BC`` of
count ``n``, the spokes from ``O`` to the three sides have counts ``n/2`` (to ``AB`` and ``AC``) and
``m - n/2`` (to ``BC``): the quad at ``A`` is ``n/2 x n/2``, those at ``B`` and ``C`` are
``n/2 x (m - n/2)``. So the split needs ``n`` even and ``n < 2m``; :func:`split_counts` raises the
counts (length-given groups only, never a designer's) until every thin fan can split. The pole keeps
one quad of this patch instead of ``n`` triangles, and ``O`` is one interior vertex of valence 3.

A finer target length gives every fan more triangles (issue 18's 10^4 to 10^6 faces): the fans that
stay, at an inner point feature (kept for their radial load paths, §4) and at a feature whose splits
would leave it regular (§4.1: point features are poles), thin without bound (armadillo_vault_plan's
worst face 0.544 at the default, 0.090 at 8,000 faces, 0.060 at 16,000). Finer than the default, an
inner point feature's fan splits too once it has more triangles than at the default length, and a
feature the splits would leave regular keeps two quads of one patch cut in two (:func:`divided_patterns`)
instead of a thin fan: the faces at the pole then no longer grow with the resolution.

A split at a pole wider than :data:`PART_ANGLE` is first cut into parts by straight spokes from the pole
(:func:`divided_patterns`, :func:`division`), each part split into three quads: the quad at the pole of
one three-quad split keeps the pole's whole angle, and past about 140 degrees its inner point ``O``
(the mean of the split points) comes to lie near the opposite side, so the quads at ``B`` and ``C``
fold (square_point_loads at half the default target length: the 155.8 degree triangles round its
point loads, 10 inverted faces, and the mesh fell back to fans of 0.045). Parts of at most
:data:`PART_ANGLE` degrees each keep their quads convex, and poles up to :data:`MAX_DIVIDED_ANGLE`
(fig6_inner_points' 166 and 194 degree fans) split too.
"""

from __future__ import annotations

import math
import weakref

import numpy as np

from vaultgram.geometry.polygons import regular_valence
from vaultgram.meshing.fans import FAN_FLOOR
from vaultgram.meshing.layout import (
    Layout,
    PatchPattern,
    _outside_angle,
    is_boundary_node,
    is_feature_node,
)

__all__ = ["boundary_pole_splits", "fan_estimate", "inner_point_feature", "pole_angle", "divided_patterns", "division",
           "split_patterns", "split_counts", "split_points", "remember_default_counts", "thinnest_fan"]

#: No split where the pole's angle is wider: the quad there would keep a flat or reflex corner
#: (a fan spans any angle).
MAX_SPLIT_ANGLE = 160.0
#: A split pole wider than this many degrees is cut into ``ceil(angle / PART_ANGLE)`` parts, each split
#: into three quads (:func:`divided_patterns`): the quad at the pole of a part keeps the part's angle,
#: and a three-quad split of a wider pole folds or stays thin (its inner point near the opposite side:
#: square_point_loads' 155.8 degree splits fold at half the default target length, fig7_curves' 147
#: and 158 degree ones leave 0.046 there), while splits of 121 to 136 degrees mesh well
#: (rv_lips_pattern and armadillo_vault_plan at a quarter of the default target length: 0.54, 0.51).
PART_ANGLE = 140.0
#: No split where the pole's angle is wider (degrees), in parts or not: three parts of 100 degrees.
MAX_DIVIDED_ANGLE = 300.0
#: Per layout, its counts at the default target length (:func:`_default_counts`), and the layouts
#: whose default counts are being made.
_DEFAULT_COUNTS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_PENDING: weakref.WeakSet = weakref.WeakSet()
_NO_REFERENCE = np.zeros(0, dtype=np.int64)
#: Rounds of :func:`split_counts` (each only raises counts; two or three settle every plan).
MAX_ROUNDS = 32


def fan_estimate(angle: float, n: int) -> float:
    """The scaled Jacobian of ``n`` equal triangles sharing ``angle`` degrees at a pole (each corner's
    sine, scaled so that an equilateral triangle has 1).

    >>> round(fan_estimate(90.0, 6), 4)  # 15 degree corners
    0.2989
    """
    return 2.0 / math.sqrt(3.0) * math.sin(math.radians(min(angle / max(n, 1), 90.0)))


def pole_angle(layout: Layout, pat: PatchPattern) -> float:
    """The patch's interior angle (degrees) at its pole."""
    patch = layout.decomposition.patches[pat.patch]
    k = pat.pole
    return 360.0 - _outside_angle(patch.sides[k - 1], patch.sides[k])


def _thin(layout: Layout, pat: PatchPattern, side_count: np.ndarray) -> bool:
    """A triangle whose fan is below :data:`FAN_FLOOR` and whose split can do better: the quad corner
    at the pole keeps about the patch's angle there, so its sine must reach the floor (a sliver's
    pole stays a fan: a quad of a 5 degree corner folds in smoothing) and the angle be at most
    :data:`MAX_DIVIDED_ANGLE` (past :data:`PART_ANGLE` the split is cut into parts, the sine is the
    part's; past :data:`MAX_SPLIT_ANGLE` only in parts). An inner point feature keeps its fan
    (:func:`inner_point_feature`) but where a target length finer than the default one thins it
    (:func:`_finer_than_default`)."""
    if pat.pole is None:
        return False
    angle = pole_angle(layout, pat)
    part = angle / _parts_at(angle, _corner_pole(layout, pat))
    if angle > MAX_DIVIDED_ANGLE or math.sin(math.radians(part)) < FAN_FLOOR:
        return False
    if inner_point_feature(layout, pat.corners[pat.pole]):
        return _finer_than_default(layout, pat, side_count)
    n = int(side_count[pat.sides[(pat.pole + 1) % 3][0]])
    return fan_estimate(angle, n) < FAN_FLOOR or _boundary_pole(layout, pat)


def _finer_than_default(layout: Layout, pat: PatchPattern, side_count: np.ndarray) -> bool:
    """A fan at a point feature that a target length finer than the default one makes thinner than
    :data:`FAN_FLOOR`: more triangles than it has at the default counts (:func:`_default_counts`;
    issues 12 and 18), by two at least (:func:`split_counts` may make a count even, at the default
    length too: saved random plan 243's boundary feature would be halved there). Its triangles
    would share the pole's angle ever more thinly as the mesh is refined (armadillo_vault_plan's inner
    points: 3 or 4 triangles per patch at the default, 15 to 22 at 8,000 faces, scaled Jacobian 0.09),
    so it is split instead; at the default length and coarser it stays the paper's fan (§4.1)."""
    if layout in _PENDING or layout not in _DEFAULT_COUNTS:  # Figure 3's fans at the default counts
        return False
    default = _default_counts(layout)[layout.group_of][pat.sides[(pat.pole + 1) % 3][0]]
    return _fan_of(layout, pat, side_count) < FAN_FLOOR and _pole_counts(pat, side_count)[1] > default + 1


def _default_counts(layout: Layout) -> np.ndarray:
    """The layout's counts at the default target length, as :func:`remember_default_counts` made them;
    where they were never made (counts not from ``group_counts``), whatever counts are given are taken
    as the default (Figure 3's fans at point features, as at the default length)."""
    return _DEFAULT_COUNTS.get(layout, _NO_REFERENCE)


def remember_default_counts(layout: Layout, make) -> None:
    """Make the layout's counts at the default target length once (``make()``: ``group_counts`` at
    the default, with :func:`_finer_than_default` off while they are made), for
    :func:`_finer_than_default`. ``group_counts`` calls it (it cannot be imported here: it imports this
    module)."""
    if layout in _DEFAULT_COUNTS or layout in _PENDING:
        return
    _PENDING.add(layout)
    try:
        _DEFAULT_COUNTS[layout] = np.asarray(make(), dtype=np.int64)
    finally:
        _PENDING.discard(layout)


def _boundary_pole(layout: Layout, pat: PatchPattern) -> bool:
    """A triangle whose pole a rule marked on the boundary, not at a point feature: a reflex corner
    given a patch of its own (``split_quad_at_reflex_corner_to_side``, rules/corners.vgr). A fan of
    ``n >= 2`` triangles there would be a boundary singularity whatever its shape (the corner is
    regular with one face in this patch), so the patch is split into three quads like a thin fan."""
    dec = layout.decomposition
    node = pat.corners[pat.pole]
    patch = dec.patches[pat.patch]
    return (dec.marked_pole(patch) == node and is_boundary_node(dec.graph, node)
            and not is_feature_node(dec, node))


def inner_point_feature(layout: Layout, node: int) -> bool:
    """A point feature inside the domain: a point load or a column, whose high-valency pole gives "a
    large number of load paths" (§4) -- the voussoirs follow its radial force flow: split, the
    joints of square_point_loads turned 11.4 degrees from the force flow (median; 8.3 with the fans,
    the tessellation's floor is 10). Boundary features and curve extremities split. At a target
    length finer than the default it splits too (:func:`_finer_than_default`): its fan's count grows
    with the resolution, its quality would fall without bound."""
    dec = layout.decomposition
    graph = dec.graph
    return (is_feature_node(dec, node) and graph.node_type(node) != "CurveExtremity"
            and not graph.schema.is_subtype(graph.node_type(node), "BoundaryVertex"))


def _pole_counts(pat: PatchPattern, side_count: np.ndarray) -> tuple[int, int]:
    """``(m, n)``: the count of the sides at the pole and of the side opposite it."""
    return int(side_count[pat.sides[pat.pole][0]]), int(side_count[pat.sides[(pat.pole + 1) % 3][0]])


def split_patterns(layout: Layout, counts) -> frozenset:
    """Indices (into ``layout.patterns``) of the three-sided patches meshed as three quads: thin fans
    (see the module docstring) whose counts allow the split (``n`` even, ``n < 2m``); the ones cut into
    parts (:func:`divided_patterns`) among them.

    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.meshing.densities import group_counts
    >>> from vaultgram.meshing.layout import edge_groups
    >>> from vaultgram.pipeline import decompose
    >>> layout = edge_groups(decompose(load_domain("examples/fig5_boundary_points.json")))
    >>> len(split_patterns(layout, group_counts(layout)))  # 6 triangles in each 45 degrees
    8
    """
    return _splits(layout, counts)[0]


def boundary_pole_splits(layout: Layout, counts) -> frozenset:
    """The split patterns (:func:`split_patterns`) whose pole a rule marked on the boundary, not at a
    point feature (:func:`_boundary_pole`): the ones the mesh keeps where the splits fold and it falls
    back to Figure 3's fans (:func:`vaultgram.meshpipeline.mesh_decomposition`). As a fan, such a
    pole has as many faces in its triangle as the side opposite it has edges, a boundary singularity
    whatever the fan's shape; the rule that marked it made it the corner of one more patch only, for
    one face there (``move_rebranch_to_lone_corner``, ``split_quad_at_reflex_corner_to_side``). Saved
    random plan 511 of the 700: the split of a boundary point feature's thin triangle (6 by 1 quads)
    folds, and with every split dropped the 136 degree corner that ``move_rebranch_to_lone_corner``
    gave two faces got nine."""
    split = split_patterns(layout, counts)
    return frozenset(k for k in split if _boundary_pole(layout, layout.patterns[k]))


def divided_patterns(layout: Layout, counts) -> dict:
    """The split patches (:func:`split_patterns`) cut into parts by spokes from the pole, each part
    split into three quads, with their number of parts (2 or more; :func:`division` says where the
    spokes meet the opposite side): ``ceil(angle / PART_ANGLE)`` at a pole wider than
    :data:`PART_ANGLE` (fewer where the counts do not allow as many), and one part more at a point
    feature the splits would leave regular (:func:`_keep_feature_poles`).

    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.meshing.densities import group_counts
    >>> from vaultgram.meshing.layout import edge_groups
    >>> from vaultgram.pipeline import decompose
    >>> layout = edge_groups(decompose(load_domain("examples/square_point_loads.json")))
    >>> divided_patterns(layout, group_counts(layout, target_length=0.177))  # 155.8 degree poles
    {8: 2, 9: 2, 12: 2, 13: 2}
    """
    return _splits(layout, counts)[1]


def _splits(layout: Layout, counts) -> tuple[frozenset, dict]:
    """The split patterns and the divided ones among them with their numbers of parts."""
    side_count = np.asarray(counts)[layout.group_of]
    parts = {}
    for k, pat in enumerate(layout.patterns):
        if _thin(layout, pat, side_count):
            count = _parts(pole_angle(layout, pat), *_pole_counts(pat, side_count), _corner_pole(layout, pat))
            if count:
                parts[k] = count
    split = _whole_poles(layout, side_count, set(parts))
    split, parts = _keep_feature_poles(layout, side_count, split, parts)
    return frozenset(split), {k: parts[k] for k in sorted(split) if parts[k] > 1}


def _parts_at(angle: float, corner: bool = False) -> int:
    """Parts of a split at a pole of ``angle`` degrees: each at most :data:`PART_ANGLE` wide; one at a
    ``corner`` (:func:`_corner_pole`)."""
    return 1 if corner else max(1, math.ceil(angle / PART_ANGLE - 1e-9))


def _corner_pole(layout: Layout, pat: PatchPattern) -> bool:
    """A triangle whose pole is a boundary vertex but not a point feature: a plan corner, whose faces
    the patches round it count (issue 12: regular by its angle), so its split keeps one part (saved
    random plan 642's 300 degree hole tip, the corner of three patches of 86, 57 and 157 degrees: the
    157 degree one halved gave it four faces, a boundary singularity)."""
    node = pat.corners[pat.pole]
    return is_boundary_node(layout.decomposition.graph, node) and not is_feature_node(layout.decomposition, node)


def _parts(angle: float, m: int, n: int, corner: bool = False) -> int:
    """The number of parts of a split at a pole of ``angle`` degrees whose counts allow it
    (:func:`division`): :func:`_parts_at`, or fewer where the counts do not allow as many (one part,
    the plain three-quad split, only up to :data:`MAX_SPLIT_ANGLE`); 0 where none does."""
    for count in range(_parts_at(angle, corner), 0, -1):
        if division(m, n, count) is not None and (count > 1 or angle <= MAX_SPLIT_ANGLE):
            return count
    return 0


def thinnest_fan(layout: Layout, counts) -> float:
    """The smallest :func:`fan_estimate` of the layout's fans of two or more triangles that stay fans
    (not in :func:`split_patterns`) at ``counts``; 1.0 where there is none.

    A cheap forecast of the mesh's worst face, from the layout alone: a fan's triangles share the
    patch's angle at the pole, and a fan below the floor is neither split nor evened, so the mesh
    keeps it (draw 33 of 700 random plans: a fan of 19 triangles in 46 degrees at a boundary point
    feature, estimate 0.049, meshed 0.034). A lone triangle is left out: at a skeleton vertex,
    which smoothing moves, its corner in the layout says little (draw 278: 5.6 degrees, meshed 0.24).

    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.meshing.densities import group_counts
    >>> from vaultgram.meshing.layout import edge_groups
    >>> from vaultgram.pipeline import decompose
    >>> layout = edge_groups(decompose(load_domain("examples/quad_with_hole.json")))
    >>> thinnest_fan(layout, group_counts(layout))  # quads only
    1.0
    """
    side_count = np.asarray(counts)[layout.group_of]
    split = split_patterns(layout, counts)
    fans = [_fan_of(layout, pat, side_count) for k, pat in enumerate(layout.patterns)
            if pat.pole is not None and k not in split and _pole_counts(pat, side_count)[1] >= 2]
    return min(fans, default=1.0)


def _whole_poles(layout: Layout, side_count: np.ndarray, split: set) -> set:
    """``split`` without the splits at a pole that keeps another fan below the floor (too wide, too
    sharp or with counts that do not allow it): that fan bounds the pole's corners anyway, so the
    quads would gain nothing there (an oval's centre before it became an O-grid, rules/topology.vgr: a 19 degree
    triangle beside a fan of 44 in 180)."""
    def pole(k):
        return layout.patterns[k].corners[layout.patterns[k].pole]

    stuck = {pole(k) for k, p in enumerate(layout.patterns)
             if p.pole is not None and k not in split and _fan_of(layout, p, side_count) < FAN_FLOOR}
    return {k for k in split if pole(k) not in stuck}


def _keep_feature_poles(layout: Layout, side_count: np.ndarray, split: set, parts: dict) -> tuple[set, dict]:
    """``split`` without the splits that would leave a point feature regular (§4.1: point features
    are poles), and ``parts`` (the numbers of parts of the splits, :func:`divided_patterns`) with one
    more at such a feature: one split patch gets one part more (its pole keeps one quad more of it:
    :func:`division`) where the fan it would get back is thinner than :data:`FAN_FLOOR` (a finer mesh
    gives a fan more triangles: 18 in 112 degrees at two_holes_five_points' inner point at 8,000
    faces, 0.125); otherwise its split patches are meshed as fans again, the least thin first, until
    its number of faces is irregular."""
    dec = layout.decomposition
    parts = dict(parts)
    for node in sorted({layout.patterns[k].corners[layout.patterns[k].pole] for k in split}):
        if not is_feature_node(dec, node):
            continue
        mine = sorted((k for k in split if layout.patterns[k].corners[layout.patterns[k].pole] == node),
                      key=lambda k: (-_fan_of(layout, layout.patterns[k], side_count), k))
        if not mine or _faces_at(layout, node, side_count, split, parts) != _regular_faces(dec, node):
            continue
        more = _to_divide(layout, side_count, mine, parts)
        fewer = _to_undivide(layout, mine, parts)
        if more is not None and _finer_than_default(layout, layout.patterns[mine[0]], side_count):
            parts[more] += 1
        elif fewer is not None:  # the parts left it regular: one part fewer keeps the splits
            parts[fewer] -= 1
        while mine and _faces_at(layout, node, side_count, split, parts) == _regular_faces(dec, node):
            split.discard(mine.pop(0))
    return split, parts


def _to_divide(layout: Layout, side_count: np.ndarray, mine: list, parts: dict):
    """Of the split patterns ``mine`` at one pole, the one to cut into one part more: the widest at the
    pole (per part) whose counts allow it (:func:`division`); None where none does."""
    ok = [k for k in mine if division(*_pole_counts(layout.patterns[k], side_count), parts[k] + 1) is not None]
    return max(ok, key=lambda k: (pole_angle(layout, layout.patterns[k]) / parts[k], -k), default=None)


def _to_undivide(layout: Layout, mine: list, parts: dict):
    """Of the split patterns ``mine`` at one pole, the one to cut into one part fewer where the parts
    leave the pole regular at the default length: the narrowest per part among those that can lose
    one (one part only up to :data:`MAX_SPLIT_ANGLE`); None where none can. (tests/meshing/test_fans.py's
    PLAN_111, a curve end: its 148 degree split halved made it regular, and both its splits went back to fans.)"""
    ok = [k for k in mine
          if parts[k] > 2 or parts[k] == 2 and pole_angle(layout, layout.patterns[k]) <= MAX_SPLIT_ANGLE]
    return min(ok, key=lambda k: (pole_angle(layout, layout.patterns[k]) / parts[k], k), default=None)


def division(m: int, n: int, parts: int = 2) -> tuple | None:
    """Where spokes from the pole cut a split triangle (pole sides of count ``m``, opposite side of
    count ``n``) into ``parts`` parts: the samples of the opposite side, as evenly spread as even counts
    allow, at which every part has an even count of at least 2 and under ``2m`` (each then splits into
    three quads, :func:`split_points`; the spokes get the count ``m``); None where there are none.
    One part: no spoke, the plain split (``n`` even, under ``2m``).

    >>> division(7, 12), division(7, 12, 3), division(7, 10, 3), division(3, 10), division(7, 2), division(7, 6, 1)
    ((6,), (4, 8), (2, 6), None, None, ())
    """
    if n % 2 or parts < 1:
        return None
    cuts = tuple(2 * (i * n // (2 * parts)) for i in range(1, parts))
    sizes = np.diff((0, *cuts, n))
    return cuts if sizes.min() >= 2 and sizes.max() < 2 * m else None


def _fan_of(layout: Layout, pat: PatchPattern, side_count: np.ndarray) -> float:
    return fan_estimate(pole_angle(layout, pat), _pole_counts(pat, side_count)[1])


def _faces_at(layout: Layout, node: int, side_count: np.ndarray, split: set, parts: dict) -> int:
    """Faces at a patch corner: 1 per patch, the opposite side's count at the pole of a fan, the
    number of parts at the pole of a split (:func:`divided_patterns`)."""
    def faces(k, p):
        if p.pole is None or p.corners[p.pole] != node:
            return 1
        return parts.get(k, 1) if k in split else _pole_counts(p, side_count)[1]
    return sum(faces(k, p) for k, p in enumerate(layout.patterns) if node in p.corners)


def _regular_faces(dec, node: int) -> int:
    """The regular number of faces at a node: 4 inside, by the angle's regular valence on a ring."""
    disc = dec.disc
    if 0 <= node < disc.n_points and disc.ring[node] >= 0:
        return int(regular_valence(np.array([180.0 - disc.turning[node]]))[0]) - 1
    return 4


def split_counts(layout: Layout, counts: np.ndarray, free: np.ndarray, capped: np.ndarray | None = None
                 ) -> np.ndarray:
    """``counts`` raised where ``free`` (groups whose count comes from a length) so that the thin fans
    can be split: the opposite side's count even, the pole sides' count above half of it. Raised
    only for the fans that then split (:func:`split_patterns`), so that a fan that stays keeps its
    counts. Only raises, so it settles; a group that is not free is never changed (its fan stays).

    A fan that stays below the floor gets no more triangles, unless its count is also the count of a
    boundary pole's fan that splits (:func:`_boundary_pole`: a lone 135-165 degree corner or a reflex
    corner given a patch of its own; or a boundary point feature's, :func:`_frees_groups`), which would
    otherwise stay a boundary singularity (or the plan's worst fan, at a boundary feature): the kept fan
    then takes one triangle more (session 22, 700 saved plans: boundary singular vertices 96 -> 90,
    one more plan with a face under 0.3). So too a group ``capped`` (counted by length, held at an inner
    point feature's fan cap, :func:`~vaultgram.meshing.densities.point_load_caps`) where a boundary pole's
    split needs it raised (:func:`_boundary_groups`)."""
    free = np.asarray(free, dtype=bool)
    if capped is not None:
        free = free | _boundary_groups(layout, counts, free | capped) & capped
    wanted = split_patterns(layout, _raised(layout, counts, free))
    side_count = np.asarray(counts)[layout.group_of]
    free = np.array(free, dtype=bool)
    needed = {_opposite_group(layout, p) for k, p in enumerate(layout.patterns)
              if k in wanted and _frees_groups(layout, p)}
    for k, pat in enumerate(layout.patterns):
        if (pat.pole is not None and k not in wanted and _fan_of(layout, pat, side_count) < FAN_FLOOR
                and _opposite_group(layout, pat) not in needed):
            free[_opposite_group(layout, pat)] = False
    return _raised(layout, counts, free, wanted)


def _boundary_groups(layout: Layout, counts: np.ndarray, free: np.ndarray) -> np.ndarray:
    """Per group, whether it is a side of a boundary pole's or a boundary point feature's triangle
    (:func:`_frees_groups`) that splits once the ``free`` groups are raised (:func:`_raised`): a fan at a
    boundary pole of two or more triangles is a boundary singularity whatever its shape.
    Session 32's draw, plan 197: a hexagonal hole's 240 degree
    corner given a patch of its own, its triangle's sides at the pole (count 2) in one group with an inner
    point feature's 44 degree fan triangle, capped at 2; the side opposite of count 3 cannot become even
    under 4, so its fan of three made the corner singular (raised, the feature's fan has three triangles,
    evened: min scaled Jacobian 0.321 -> 0.357)."""
    wanted = split_patterns(layout, _raised(layout, counts, free))
    groups = np.zeros(len(free), dtype=bool)
    for k, pat in enumerate(layout.patterns):
        if k in wanted and _frees_groups(layout, pat):
            groups[[int(layout.group_of[pat.sides[(pat.pole + j) % 3][0]]) for j in (0, 1)]] = True
    return groups


def _frees_groups(layout: Layout, pat: PatchPattern) -> bool:
    """Whether a triangle's split may raise a group that a kept fan or an inner point feature's cap
    holds (:func:`split_counts`): at a boundary pole (:func:`_boundary_pole`), and at a point feature on
    the boundary, whose fan of 11-27 triangles in about 180 degrees was the worst face of 72 of the 700
    saved random plans, every one at its fan bound, unsplit because one of its triangles' opposite
    count was odd and held by a fan across the strip (session 33: plan 591 0.134 -> 0.221)."""
    node = pat.corners[pat.pole]
    return _boundary_pole(layout, pat) or (is_boundary_node(layout.decomposition.graph, node)
                                           and is_feature_node(layout.decomposition, node))


def _opposite_group(layout: Layout, pat: PatchPattern) -> int:
    """The edge group of a triangle's side opposite its pole (the count of its fan)."""
    return int(layout.group_of[pat.sides[(pat.pole + 1) % 3][0]])


def _raised(layout: Layout, counts: np.ndarray, free: np.ndarray, only=None) -> np.ndarray:
    """``counts`` raised (where ``free``) until every thin fan (of the patterns ``only``, if given) can
    be split."""
    counts = np.array(counts, dtype=np.int64)
    for _ in range(MAX_ROUNDS):
        before = counts.copy()
        side_count = counts[layout.group_of]
        for k, pat in enumerate(layout.patterns):
            if (only is not None and k not in only) or not _thin(layout, pat, side_count):
                continue
            gm, gn = (int(layout.group_of[pat.sides[(pat.pole + j) % 3][0]]) for j in (0, 1))
            if counts[gn] % 2 and free[gn]:
                counts[gn] += 1
            if counts[gm] <= counts[gn] // 2 and free[gm]:
                counts[gm] = counts[gn] // 2 + 1
            side_count = counts[layout.group_of]
        if np.array_equal(before, counts):
            break
    return counts


def split_points(m: int, n: int) -> tuple[int, int, int]:
    """Sample indices of the split points on the sides ``A->B``, ``B->C`` and ``C->A`` (from each
    side's first corner), and the spoke counts follow: ``n/2`` to ``AB`` and ``CA``, ``m - n/2`` to
    ``BC``.

    >>> split_points(7, 6)
    (3, 3, 4)
    """
    h = n // 2
    return h, h, m - h
