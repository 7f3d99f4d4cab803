"""Mesh densities: the number of subdivisions of each edge group (paper §3.2, second paragraph).

"The number of subdivisions of each group can be chosen by the designer or set based on a target
length and the average or maximum length of the edges in the group, for instance. An additional
constraint on the minimum number of subdivisions can also be taken into account." (§3.2)

:func:`group_counts` gives each group of the :class:`~vaultgram.meshing.layout.Layout` its number of
subdivisions: a designer's count, or the group's average (or maximum) side length divided by a
target length, rounded, and at least a minimum; boundary sides are subdivided finely enough to follow
their curve (:data:`CHORD_TOLERANCE`), curve sides keep every input vertex of the curve. Local control
maps group ids, or regions given as polygons, to counts or lengths (:class:`DensitySpec`, read from a
JSON density file by :func:`load_densities`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from vaultgram.errors import VaultgramError
from vaultgram.geometry.frames import to_local
from vaultgram.geometry.polylines import chord_deviation, resample_polyline
from vaultgram.io import strict
from vaultgram.io.files import read_json
from vaultgram.limits import MAX_COUNT
from vaultgram.meshing.fans import FAN_FLOOR
from vaultgram.meshing.guards import check_mesh_size
from vaultgram.meshing.layout import EdgeGroup, Layout, kept_points, side_anchors
from vaultgram.meshing.splits import (
    fan_estimate,
    inner_point_feature,
    pole_angle,
    remember_default_counts,
    split_counts,
)

__all__ = ["DensitySpec", "group_counts", "group_length", "unresolved_holes", "curve_min_counts",
           "point_load_caps", "most_triangles", "densities_from_dict", "load_densities",
           "TARGET_FRACTION", "CHORD_TOLERANCE"]

#: Default global target edge length, as a fraction of the bounding-box diagonal of the domain.
TARGET_FRACTION = 0.025
#: A boundary side is subdivided at least finely enough that its resampled polyline stays within this
#: fraction of the bounding-box diagonal of the domain's ring (a curved side with too few
#: subdivisions cuts across the domain and folds the faces next to it; issue 12: the mesh boundary
#: within 0.1% of the diagonal, it was 0.2%).
CHORD_TOLERANCE = 0.001
#: The geometric minimum count of a side is searched up to this multiple of its length count (of at
#: least ``CHORD_SEARCH_FLOOR``: a huge target length gives count 1, and a curved side needs more
#: than 6 chords to stay within the tolerance).
CHORD_MAX_FACTOR = 6
CHORD_SEARCH_FLOOR = 4
#: Above this many subdivisions a side is not searched for its chord count (it follows its curve
#: anyway): the search would resample it millions of times over before the size guard
#: (:mod:`vaultgram.meshing.guards`) refuses the mesh.
CHORD_SEARCH_LIMIT = 100_000
#: Length counts are clamped here (a tiny target length would overflow an integer); the size guard
#: refuses any such mesh.
COUNT_CEILING = 10**12


@dataclass(frozen=True)
class DensitySpec:
    """Local and global density control (§3.2).

    Attributes
    ----------
    target_length : float or None
        Global target edge length (absolute units); None: ``TARGET_FRACTION`` of the diagonal.
    length_mode : str
        ``"average"`` or ``"max"``: which side length of a group is divided by the target length.
    min_count : int
        Minimum number of subdivisions of every group.
    groups : dict
        Group id -> ``{"count": n}`` or ``{"length": L}``. Overrides regions.
    regions : tuple of (ndarray (k, 2), dict)
        Polygons with ``{"count": n}`` or ``{"length": L}``: a group any of whose sides has its
        midpoint inside the polygon takes that value; a later region wins.
    """

    target_length: float | None = None
    length_mode: str = "average"
    min_count: int = 1
    groups: dict = field(default_factory=dict)
    regions: tuple = ()


def group_counts(layout: Layout, spec: DensitySpec | None = None, target_length: float | None = None,
                 max_faces: int | None = None, split: bool = True) -> np.ndarray:
    """Number of subdivisions of each edge group (§3.2).

    Parameters
    ----------
    layout : Layout
    spec : DensitySpec, optional
        Local control and defaults; ``target_length`` overrides ``spec.target_length``.
    target_length : float, optional
        Global target edge length; default ``TARGET_FRACTION`` of the domain's diagonal.
    max_faces : int, optional
        Refuse counts that make a mesh of more faces (:func:`vaultgram.meshing.guards.check_mesh_size`),
        checked before the boundary sides are searched for their chord counts too.
    split : bool
        Raise the counts so that thin fans can be meshed as three quads
        (:func:`vaultgram.meshing.splits.split_counts`); False: Figure 3's fans everywhere.

    Returns
    -------
    ndarray (n_groups,) int
        ``max(min_count, round(L / target))`` for a group of length ``L`` (:func:`group_length`: average
        or maximum of its sides), unless a region or the designer gives a count or a local target length.

    Raises
    ------
    VaultgramError
        For a bad target length, count, length mode or group id, or more than ``max_faces`` faces.

    Example
    -------
    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.meshing.layout import edge_groups
    >>> from vaultgram.pipeline import decompose
    >>> layout = edge_groups(decompose(load_domain("examples/quad_with_hole.json")))
    >>> counts = group_counts(layout, DensitySpec(groups={0: 7}))
    >>> len(counts) == layout.n_groups, int(counts[0])
    (True, 7)
    """
    spec = spec or DensitySpec()
    diag = layout.decomposition.disc.domain.diagonal
    target = _checked_target(spec, target_length, diag)
    local = _local_values(layout, spec)
    counts = np.empty(layout.n_groups, dtype=np.int64)
    small = {}  # per target length, the holes it cannot resolve
    by_length, coarse = [], []  # groups counted by length, and whether at the default length or coarser
    for g in layout.groups:
        kind, v = local[g.id] or ("length", target)
        if kind == "count":
            counts[g.id] = v
        else:
            small.setdefault(v, unresolved_holes(layout.decomposition.disc, v))
            counts[g.id] = max(int(spec.min_count), _length_count(group_length(layout, g, v, spec.length_mode,
                                                                               small[v]), v))
            by_length.append(g)
            coarse.append(v >= TARGET_FRACTION * diag)
    capped = np.zeros(layout.n_groups, dtype=bool)  # issue 12: a point load's fans within the floor,
    capped[[g.id for g, c in zip(by_length, coarse) if c]] = True  # at the default length or coarser
    caps = point_load_caps(layout)
    capped &= counts > caps
    counts[capped] = caps[capped]  # the geometric minima below still hold
    if max_faces is not None:  # before the chord search, which resamples each side at its count
        check_mesh_size(layout, np.maximum(counts, 1), max_faces)
    counts = np.maximum(counts, anchor_min_counts(layout))  # issue 12: sharp vertices are mesh vertices
    for g in by_length:
        if counts[g.id] <= CHORD_SEARCH_LIMIT:
            counts[g.id] = max(counts[g.id], _chord_count(layout, g, counts[g.id], CHORD_TOLERANCE * diag))
    counts = np.maximum(counts, curve_min_counts(layout))
    if split:  # issue 12: thin fans become three quads (issue 18: fans at features finer than the default too)
        remember_default_counts(layout, lambda: group_counts(layout))
        free = np.zeros(layout.n_groups, dtype=bool)
        free[[g.id for g in by_length]] = True
        counts = split_counts(layout, counts, free & ~capped, free & capped)
    if max_faces is not None:
        check_mesh_size(layout, counts, max_faces)
    return counts


def point_load_caps(layout: Layout) -> np.ndarray:
    """Per group, the most subdivisions that keep the fans of the inner point features (§4.1: point
    loads, columns) of which it is the opposite side at the floor :data:`~vaultgram.meshing.fans.FAN_FLOOR`:
    the largest ``n`` whose ``n`` equal triangles in the patch's angle at the pole reach it
    (:func:`~vaultgram.meshing.splits.fan_estimate`; at least 1); :data:`COUNT_CEILING` for other groups.

    Such a pole keeps its fans (they carry its radial force flow, :mod:`vaultgram.meshing.splits`),
    and a fan gets one triangle per subdivision of its opposite side (Figure 3), so at the target
    length its triangles may be too many for the pole's 360 degrees: 39 round each point load of
    ``square_point_loads`` (fan bound 0.185, the mesh's worst face 0.093), 27 round that of
    ``rv_lips_pattern`` (0.266). At most ``angle / asin(FAN_FLOOR sqrt(3) / 2)`` (15.06 degrees) per
    patch, the pole's triangles are at most 23, which its fans' evening
    (:func:`~vaultgram.meshing.fans.even_fans`) spreads at 15.65 degrees each (0.311). The price is
    coarser opposite sides (those groups only; a designer's counts and the geometric minima of
    :func:`group_counts` are kept). :func:`group_counts` caps only groups counted at the default
    target length or a coarser one: finer, the fans split into quads instead
    (:func:`vaultgram.meshing.splits.split_counts`, once they have more triangles than at the default)
    and the groups refine with the target length.

    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.meshing.layout import edge_groups
    >>> from vaultgram.pipeline import decompose
    >>> layout = edge_groups(decompose(load_domain("examples/square_point_loads.json")))
    >>> caps = point_load_caps(layout)
    >>> sorted(int(c) for c in caps[caps < COUNT_CEILING])  # two 48 and four 156 degree corners at the loads
    [3, 10, 10, 10, 10]
    """
    caps = np.full(layout.n_groups, COUNT_CEILING, dtype=np.int64)
    for pat in layout.patterns:
        if pat.pole is not None and inner_point_feature(layout, pat.corners[pat.pole]):
            g = int(layout.group_of[pat.sides[(pat.pole + 1) % 3][0]])
            caps[g] = min(caps[g], most_triangles(pole_angle(layout, pat)))
    return caps


def most_triangles(angle: float) -> int:
    """The most equal triangles sharing ``angle`` degrees at a pole whose scaled Jacobian
    (:func:`~vaultgram.meshing.splits.fan_estimate`) reaches :data:`~vaultgram.meshing.fans.FAN_FLOOR`
    (each corner at least ``asin(FAN_FLOOR sqrt(3) / 2)``, 15.06 degrees); at least 1.

    >>> most_triangles(360.0), most_triangles(90.0), most_triangles(10.0)
    (23, 5, 1)
    """
    n = max(1, int(angle // math.degrees(math.asin(FAN_FLOOR * math.sqrt(3.0) / 2))))
    while n > 1 and fan_estimate(angle, n) < FAN_FLOOR:  # round-off at an exact multiple
        n -= 1
    return n


def group_length(layout: Layout, group: EdgeGroup, target: float, mode: str = "average", small=None) -> float:
    """The length of ``group`` that its count divides by the ``target`` length (§3.2: the average or
    maximum length of its sides, ``mode``); the maximum, whatever the mode, for a group with a side on
    a hole that the target length cannot resolve (``small``: :func:`unresolved_holes` of the layout's
    discretisation at ``target``, found where not given).

    Such a hole (mexico_airport: 21 nine-gons 0.57 target lengths across) has its sides subdivided
    at its corners' spacing (:func:`anchor_min_counts`), and its patches fan out from it: each is a
    wedge whose short side is on the hole, and the group of that side holds the long sides the wedges
    face (the skeleton's branches between the holes, the outer boundary). Their average with the
    hole's short sides leaves the long ones a subdivision short: their quads are up to 1.6 times the
    target length wide, and the wedge's taper goes into their corners at the skeleton's singular
    vertices. By the longest side, the wide ends of the wedges are split (issue 12 What 4:
    mexico_airport's mean scaled Jacobian 0.849 -> 0.877 before the mean pass and 0.892 -> 0.904
    after it, its worst face 0.578 -> 0.624, 580 -> 741 faces); the price is thinner quads at the
    hole, whose sides are split too (the 90th percentile of the faces' longest over shortest side
    5.4 -> 9.3). By the average of the group's sides off the hole instead: the same within 0.002
    (mean 0.902, worst face 0.635, 729 faces). The sides of a hole the target resolves count as any
    other side.

    >>> from vaultgram.domain import domain_from_dict
    >>> from vaultgram.meshing.layout import edge_groups
    >>> from vaultgram.pipeline import decompose
    >>> a = np.arange(9) * 2 * np.pi / 9  # a nine-gon of sides 0.34 in a 10 x 10 square
    >>> hole = np.column_stack([5 + 0.5 * np.cos(a), 5 + 0.5 * np.sin(a)]).tolist()
    >>> layout = edge_groups(decompose(domain_from_dict({"outer": [[0, 0], [10, 0], [10, 10], [0, 10]],
    ...                                                  "holes": [hole]})))
    >>> g = layout.groups[layout.group_of[next(s.id for s in layout.sides if s.ring == 1)]]
    >>> [round(layout.sides[s].length, 2) for s in g.sides]  # the outer boundary, the skeleton, the hole
    [4.44, 4.68, 0.68]
    >>> round(group_length(layout, g, 1.0), 2), round(group_length(layout, g, 0.1), 2)  # the hole unresolved, resolved
    (4.68, 3.27)
    """
    small = unresolved_holes(layout.decomposition.disc, target) if small is None else small
    if any(layout.sides[s].boundary and small[layout.sides[s].ring] for s in group.sides):
        return group.max_length
    return group.length(mode)


def unresolved_holes(disc, target: float) -> np.ndarray:
    """Per ring of ``disc`` (0 the outer ring, ``1 + k`` hole ``k``), whether it is a hole that the
    ``target`` length cannot resolve: one narrower than the target length (its perimeter under pi
    target lengths), which a mesh at the target length would cross in less than one quad. Its
    corners keep its sides subdivided finer than that (:func:`anchor_min_counts`; mexico_airport's
    nine-gons, 0.57 target lengths across, nine sides of 0.2 target lengths).

    Holes a few target lengths across keep the average. Taking instead every hole whose corners are
    less than a target length apart, rolex_learning_centre's 10 such holes (4 to 14 target lengths
    round) gain too (mean 0.907 -> 0.913, worst face 0.449 -> 0.480), but hiroshi_senju_museum's two
    gain 0.002 and its finer openings collapse when form finding relaxes them (``vaultgram design``
    fails).

    >>> from vaultgram.domain import domain_from_dict
    >>> from vaultgram.topology.discretise import discretise
    >>> a = np.arange(9) * 2 * np.pi / 9  # a nine-gon 1.0 across, perimeter 3.08
    >>> hole = np.column_stack([5 + 0.5 * np.cos(a), 5 + 0.5 * np.sin(a)]).tolist()
    >>> disc = discretise(domain_from_dict({"outer": [[0, 0], [10, 0], [10, 10], [0, 10]], "holes": [hole]}))
    >>> unresolved_holes(disc, 1.0).tolist(), unresolved_holes(disc, 0.9).tolist()
    ([False, True], [False, False])
    """
    small = np.zeros(len(disc.rings), dtype=bool)
    for k, ring in enumerate(disc.rings[1:], 1):
        pts = disc.points[ring]
        small[k] = float(np.hypot(*(np.roll(pts, -1, axis=0) - pts).T).sum()) < np.pi * target
    return small


def _length_count(length: float, target: float) -> int:
    """``round(length / target)``, clamped at :data:`COUNT_CEILING`."""
    return int(round(min(length / target, COUNT_CEILING)))


def _checked_target(spec: DensitySpec, target_length: float | None, diag: float) -> float:
    """The global target length (the argument, else the spec's, else :data:`TARGET_FRACTION` of the
    diagonal), after checking it and the spec's length mode and minimum count."""
    target = target_length if target_length is not None else spec.target_length
    if target is None:
        target = TARGET_FRACTION * diag
    if not (target > 0 and math.isfinite(target)):
        raise VaultgramError(f"target length must be a positive number, got {target!r}")
    if spec.length_mode not in ("average", "max"):
        raise VaultgramError(f"length mode must be 'average' or 'max', got {spec.length_mode!r}")
    if int(spec.min_count) < 1:
        raise VaultgramError(f"minimum count must be at least 1, got {spec.min_count!r}")
    return target


def _local_values(layout: Layout, spec: DensitySpec) -> list:
    """Per group, the designer's ``("count", n)`` or ``("length", L)``, or None: from the regions
    containing a midpoint of one of its sides (a later region wins; the regions are in the plan's
    coordinates, the layout in its domain's frame), then from the group ids."""
    n = layout.n_groups
    local = [None] * n
    if spec.regions:
        import shapely

        origin = layout.decomposition.disc.domain.origin
        for poly, value in spec.regions:
            region = shapely.Polygon(to_local(poly, origin))
            for g in layout.groups:
                if shapely.contains_xy(region, g.midpoints[:, 0], g.midpoints[:, 1]).any():
                    local[g.id] = _value(value, f"region {np.asarray(poly).tolist()}")
    for key, value in spec.groups.items():
        try:
            g = int(key)
        except (TypeError, ValueError):
            raise VaultgramError(f"density group id must be an integer, got {key!r}") from None
        if not 0 <= g < n:
            raise VaultgramError(f"density for group {g}: the layout has groups 0 to {n - 1}")
        local[g] = _value(value, f"group {g}")
    return local


def curve_min_counts(layout: Layout) -> np.ndarray:
    """Least number of subdivisions of each group that keeps every vertex of the input curve features
    (§4.2) as a mesh vertex: one more than the number of input vertices inside each curve side of the
    group (:func:`vaultgram.meshing.layout.side_anchors`), 1 for groups without curve sides. Applied to every
    count, a designer's too: with fewer, the mesh edges would cut the curve's bends."""
    disc = layout.decomposition.disc
    keep = kept_points(disc)
    need = np.ones(layout.n_groups, dtype=np.int64)
    for side in layout.sides:
        if side.curve >= 0:
            g = layout.group_of[side.id]
            need[g] = max(need[g], len(side_anchors(side, keep, disc)) + 1)
    return need


def anchor_min_counts(layout: Layout) -> np.ndarray:
    """Least number of subdivisions of each group that keeps every anchor of its sides
    (:func:`vaultgram.meshing.layout.side_anchors`: the corners and the ring vertices turning by
    :data:`~vaultgram.meshing.layout.KEEP_ANGLE` or more on boundary sides, the curve's vertices on
    curve sides) as a mesh vertex: one more than the most anchors inside a side of the group (with
    fewer, :func:`~vaultgram.geometry.polylines.resample_polyline` honours none of them)."""
    disc = layout.decomposition.disc
    keep = kept_points(disc)
    need = np.ones(layout.n_groups, dtype=np.int64)
    for side in layout.sides:
        g = layout.group_of[side.id]
        need[g] = max(need[g], len(side_anchors(side, keep, disc)) + 1)
    return need


def _chord_count(layout: Layout, group: EdgeGroup, count: int, tol: float) -> int:
    """The least count (from ``count`` up) at which every boundary side of the group, resampled as the
    welding does it, stays within ``tol`` of its curve: the "additional constraint on the minimum
    number of subdivisions" of §3.2, from the geometry. Capped at ``CHORD_MAX_FACTOR * count``."""
    keep = kept_points(layout.decomposition.disc)
    best = count
    for s in group.sides:
        side = layout.sides[s]
        if not side.boundary or len(side.polyline) <= 2:
            continue
        anchors = side_anchors(side, keep, layout.decomposition.disc)
        n = best
        while n < CHORD_MAX_FACTOR * max(count, CHORD_SEARCH_FLOOR):
            pts, _ = resample_polyline(side.polyline, n, anchors)
            if chord_deviation(side.polyline, pts) <= tol:
                break
            n += max(1, n // 8)
        best = max(best, n)
    return best


def _value(value, where: str) -> tuple[str, float]:
    """A density value, checked: ``("count", n)`` or ``("length", L)`` (a bare integer is a count)."""
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        value = {"count": int(value)}
    if not isinstance(value, dict) or len(set(value) & {"count", "length"}) != 1:
        raise VaultgramError(f"density for {where}: give a count or a length, e.g. {{\"count\": 4}}")
    if "count" in value:
        c = value["count"]
        if not isinstance(c, (int, np.integer)) or isinstance(c, bool) or c < 1:
            raise VaultgramError(f"density for {where}: count must be a positive integer, got {c!r}")
        if c > MAX_COUNT:
            raise VaultgramError(f"density for {where}: count {c} is more than the limit of {MAX_COUNT}")
        return ("count", int(c))
    length = value["length"]
    if not isinstance(length, (int, float)) or isinstance(length, bool) or not length > 0:
        raise VaultgramError(f"density for {where}: length must be a positive number, got {length!r}")
    return ("length", float(length))


def densities_from_dict(data: dict, where: str = "densities") -> DensitySpec:
    """A :class:`DensitySpec` from the JSON form of a density file.

    ``{"target_length": L, "length_mode": "average" | "max", "min_count": n,
    "groups": {"3": 8, "5": {"length": 0.2}}, "regions": [{"polygon": [[x, y], ...], "count": 4}]}``,
    every key optional.

    >>> densities_from_dict({"min_count": 2, "groups": {"3": 8}})
    DensitySpec(target_length=None, length_mode='average', min_count=2, groups={'3': 8}, regions=())
    """
    if not isinstance(data, dict):
        raise VaultgramError(f"{where}: a density file is a JSON object")
    unknown = set(data) - {"target_length", "length_mode", "min_count", "groups", "regions"}
    if unknown:
        raise VaultgramError(f"{where}: unknown key(s) {', '.join(sorted(unknown))}")
    regions = []
    for k, r in enumerate(strict.json_list(data.get("regions", []), f"{where}: regions")):
        if not isinstance(r, dict) or "polygon" not in r:
            raise VaultgramError(f"{where}: region {k} needs a 'polygon' [[x, y], ...]")
        poly = strict.points(r["polygon"], f"{where}: region {k}: polygon", (2,))
        if len(poly) < 3:
            raise VaultgramError(f"{where}: region {k}: polygon must have at least 3 [x, y] points")
        value = {key: r[key] for key in ("count", "length") if key in r}
        _value(value, f"region {k}")
        regions.append((poly, value))
    groups = data.get("groups", {})
    if not isinstance(groups, dict):
        raise VaultgramError(f"{where}: 'groups' maps group ids to counts or lengths")
    target = data.get("target_length")
    if target is not None and not (strict.is_number(target) and target > 0):
        raise VaultgramError(f"{where}: target_length must be a positive number, got {target!r}")
    min_count = data.get("min_count", 1)
    if not isinstance(min_count, int) or isinstance(min_count, bool) or min_count < 1:
        raise VaultgramError(f"{where}: min_count must be a positive integer, got {min_count!r}")
    if min_count > MAX_COUNT:
        raise VaultgramError(f"{where}: min_count {min_count} is more than the limit of {MAX_COUNT}")
    for key, value in groups.items():
        _value(value, f"group {key}")
    return DensitySpec(target, data.get("length_mode", "average"), min_count, dict(groups), tuple(regions))


def load_densities(path: str | Path) -> DensitySpec:
    """Read a density file (see :func:`densities_from_dict`)."""
    return densities_from_dict(read_json(path), str(path))
