"""Edge groups and mesh densities (paper §3.2, second paragraph).

"Based on the set of patches and their respective patterns, the edges sharing the same number of
subdivisions are grouped. The number of edge groups represents the exact number of degrees of
freedom available on the mesh density [...]. The number of subdivisions of each group can be chosen
by the designer or set based on a target length and the average or maximum length of the edges in
the group [...]. An additional constraint on the minimum number of subdivisions can also be taken
into account." (§3.2)

Method
------
* Every patch side of the decomposition is an *atomic side*: the chain of graph edges between two
  patch corners. Adjacent patches traverse the same chain in opposite directions, so a side is
  identified by the set of its edge ids and stored once, in the direction of its first traversal
  (:class:`Side`).
* Each patch gets its pattern (Figure 3): a four-sided patch is a quad without pole; a three-sided
  patch is a triangle whose *pole* is the corner labelled as a feature point (§4.1, §4.2) if there
  is exactly one, else the unique naked corner (on the boundary), else the unique non-naked corner
  (:func:`choose_pole`).
* Sides that must share a number of subdivisions are united with a union-find: opposite sides of a
  quad, and the two sides adjacent to the pole of a triangle (the pole is a collapsed fourth side,
  opposite the third side, which stays free). The classes are the :class:`EdgeGroup` s.
* :func:`group_counts` gives each group its number of subdivisions: a designer's count, or the
  group's average (or maximum) side length divided by a target length, rounded, and at least a
  minimum. Local control maps group ids, or regions given as polygons, to counts or lengths
  (:class:`DensitySpec`, read from a JSON density file by :func:`load_densities`).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from vaultgram.topology.decomposition import Decomposition
from vaultgram.errors import DomainError, VaultgramError

__all__ = [
    "Side",
    "PatchPattern",
    "EdgeGroup",
    "Layout",
    "DensitySpec",
    "edge_groups",
    "choose_pole",
    "group_counts",
    "load_densities",
    "densities_from_dict",
    "polyline_length",
    "curve_min_counts",
]

#: Default global target edge length, as a fraction of the bounding-box diagonal of the domain.
TARGET_FRACTION = 0.025

#: A boundary side is subdivided at least finely enough that its resampled polyline stays within this
#: fraction of the bounding-box diagonal of the domain's ring (a curved side with too few
#: subdivisions cuts across the domain and folds the faces next to it).
CHORD_TOLERANCE = 0.002

#: The geometric minimum count of a side is searched up to this multiple of its length count.
CHORD_MAX_FACTOR = 6


@dataclass(frozen=True, eq=False)
class Side:
    """An atomic patch side: the chain of decomposition edges between two patch corners.

    Attributes
    ----------
    id : int
    start, end : int
        Corner node ids (decomposition graph) at the ends, in the stored direction.
    polyline : ndarray (k, 2)
        The side from ``start`` to ``end``.
    nodes : tuple of int
        Graph nodes along the side, ``start`` first and ``end`` last.
    boundary : bool
        True when the side is made of ``Boundary`` edges (it lies on a ring of the domain).
    ring : int
        The ring of a boundary side (0 outer, ``1 + k`` hole ``k``), else -1.
    length : float
        Arc length of the polyline.
    curve : int
        The curve feature a side made of ``Curve`` edges lies on (index into
        ``Discretisation.curves``, §4.2), else -1.
    """

    id: int
    start: int
    end: int
    polyline: np.ndarray
    nodes: tuple
    boundary: bool
    ring: int
    length: float
    curve: int = -1


@dataclass(frozen=True, eq=False)
class PatchPattern:
    """A patch with its pattern: a quad without pole, or a triangle with a pole (Figure 3).

    Attributes
    ----------
    patch : int
        Id of the :class:`vaultgram.topology.patches.Patch`.
    corners : tuple of int
        Corner node ids, counter-clockwise.
    sides : tuple of (int, bool)
        ``(side id, reversed)`` per patch side; side ``i`` runs from ``corners[i]`` to
        ``corners[i + 1]``, which is the stored direction of the side unless ``reversed``.
    pole : int or None
        Index into ``corners`` of the pole of a triangle, None for a quad.
    """

    patch: int
    corners: tuple
    sides: tuple
    pole: int | None


@dataclass(frozen=True, eq=False)
class EdgeGroup:
    """Sides that share one number of subdivisions.

    Attributes
    ----------
    id : int
    sides : tuple of int
        Atomic side ids.
    mean_length, max_length : float
        Average and maximum length of the sides.
    midpoints : ndarray (k, 2)
        The point halfway along each side (used to select groups by region).
    """

    id: int
    sides: tuple
    mean_length: float
    max_length: float
    midpoints: np.ndarray

    def length(self, mode: str = "average") -> float:
        return self.max_length if mode == "max" else self.mean_length


@dataclass(frozen=True, eq=False)
class Layout:
    """The patches of a decomposition with their patterns, atomic sides and edge groups.

    ``len(groups)`` is the number of degrees of freedom of the mesh density (§3.2).
    """

    decomposition: Decomposition
    sides: tuple
    patterns: tuple
    groups: tuple
    group_of: np.ndarray  # side id -> group id

    @property
    def n_groups(self) -> int:
        return len(self.groups)


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


# --------------------------------------------------------------------------------------------
# Sides, poles and groups
# --------------------------------------------------------------------------------------------


def polyline_length(poly: np.ndarray) -> float:
    return float(np.hypot(*np.diff(poly, axis=0).T).sum()) if len(poly) > 1 else 0.0


def _midpoint(poly: np.ndarray) -> np.ndarray:
    seg = np.hypot(*np.diff(poly, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    half = s[-1] / 2
    return np.array([np.interp(half, s, poly[:, 0]), np.interp(half, s, poly[:, 1])])


def _is_boundary_node(graph, n: int) -> bool:
    return graph.schema.is_subtype(graph.node_type(n), "BoundaryVertex")


def is_feature_node(decomposition: Decomposition, n: int) -> bool:
    """A node labelled 'feature point' (§4.1) or 'curve feature extremity' (§4.2)."""
    graph, disc = decomposition.graph, decomposition.disc
    t = graph.node_type(n)
    if t in ("FeaturePoint", "CurveExtremity"):
        return True
    return 0 <= n < disc.n_points and bool(np.isin(n, disc.feature_points))


def _corner_angle(poly_in: np.ndarray, poly_out: np.ndarray) -> float:
    """Interior angle (degrees, in (0, 360)) at the corner between an arriving and a leaving side."""
    a = poly_in[-2] - poly_in[-1]
    b = poly_out[1] - poly_out[0]
    ang = math.degrees(math.atan2(a[0] * b[1] - a[1] * b[0], a @ b))  # from b to a, ccw
    return ang % 360.0 if ang % 360.0 > 0 else 360.0


def choose_pole(decomposition: Decomposition, patch) -> int:
    """Index of the pole among a three-sided patch's corners (§3.2, §4.1, §4.2).

    The corner a patching rule marked as the pole, if any (the rule knows why it made the triangle).
    Else the corner labelled as a feature point if there is exactly one (§4.1, §4.2). Otherwise the paper
    takes "the unique naked vertex (on the boundaries) or the unique non-naked vertex (on the
    skeleton branches)"; we take a non-naked corner whenever there is one, because a pole on the
    boundary is always a boundary singularity: a naked corner that is the pole of ``n`` triangles
    takes ``n`` faces from this patch instead of 1, which at a reflex corner (corner of two more
    patches, regular with 3 faces) or a smooth stretch (regular with 2) makes it irregular for any
    ``n >= 2``. The interior pole is a singular node of the decomposition, where the acceptance
    allows singularities. Points inside a curve feature count as naked (the curve is a cut, and no
    singular vertex may lie on it). Among two non-naked (or three naked) corners the one with the smallest
    angle: the pole's fan of triangles splits it least badly.
    """
    graph = decomposition.graph
    corners = patch.corners
    marked = decomposition.marked_pole(patch)
    if marked is not None:
        return corners.index(marked)
    feature = [k for k, c in enumerate(corners) if is_feature_node(decomposition, c)]
    if len(feature) == 1:
        return feature[0]
    # a point inside a curve feature is naked too: the curve cuts the domain (§4.2), and a pole there
    # would be a singular vertex on the curve
    on_cut = [graph.node_type(c) == "CurvePoint" for c in corners]
    inner = [k for k, c in enumerate(corners) if not _is_boundary_node(graph, c) and not on_cut[k]]
    if len(inner) == 1:
        return inner[0]
    angles = [_corner_angle(patch.sides[k - 1], patch.sides[k]) for k in range(3)]
    candidates = inner or [0, 1, 2]
    return min(candidates, key=lambda k: angles[k])


def _curve_of_segment(disc) -> dict:
    """``{frozenset((a, b)): c}`` for every segment ``a-b`` of curve feature ``c`` (point indices)."""
    return {frozenset((int(a), int(b))): c for c, pts in enumerate(disc.curves) for a, b in zip(pts[:-1], pts[1:])}


class _UnionFind:
    def __init__(self, n: int):
        self.parent = list(range(n))

    def find(self, a: int) -> int:
        while self.parent[a] != a:
            self.parent[a] = self.parent[self.parent[a]]
            a = self.parent[a]
        return a

    def union(self, a: int, b: int) -> None:
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.parent[max(ra, rb)] = min(ra, rb)


def edge_groups(decomposition: Decomposition) -> Layout:
    """Atomic sides, patch patterns and edge groups of a decomposition (§3.2).

    Returns
    -------
    Layout

    Example
    -------
    >>> from vaultgram.domain.model import load_domain
    >>> from vaultgram.topology.decomposition import decompose
    >>> layout = edge_groups(decompose(load_domain("examples/quad_with_hole.json")))
    >>> len(layout.patterns), layout.n_groups  # doctest: +SKIP
    (12, 6)
    """
    graph = decomposition.graph
    curve_of = _curve_of_segment(decomposition.disc)
    side_of_key: dict[frozenset, int] = {}
    sides: list[Side] = []
    patterns: list[PatchPattern] = []
    for patch in decomposition.patches:
        refs = []
        k = patch.n_sides
        for i in range(k):
            half_edges = patch.side_edges[i]
            key = frozenset(e for e, _ in half_edges)
            start, end = patch.corners[i], patch.corners[(i + 1) % k]
            if key not in side_of_key:
                types = {graph.edge_type(e) for e, _ in half_edges}
                nodes = tuple(u for _, u in half_edges) + (end,)
                boundary = types == {"Boundary"}
                ring = int(graph.get(start, "ring")) if boundary else -1
                poly = np.asarray(patch.sides[i], dtype=float)
                curve = curve_of.get(frozenset(nodes[:2]), -1) if types == {"Curve"} else -1
                side_of_key[key] = len(sides)
                sides.append(Side(len(sides), start, end, poly, nodes, boundary, ring, polyline_length(poly), curve))
                refs.append((side_of_key[key], False))
            else:
                s = sides[side_of_key[key]]
                if s.start == start and s.end == end and s.start != s.end:
                    raise DomainError(
                        f"side from {_fmt(graph.get(start, 'pos'))} to {_fmt(graph.get(end, 'pos'))} is "
                        "traversed twice in the same direction: the patches overlap"
                    )
                refs.append((side_of_key[key], True))
        pole = choose_pole(decomposition, patch) if k == 3 else None
        patterns.append(PatchPattern(patch.id, tuple(patch.corners), tuple(refs), pole))

    uf = _UnionFind(len(sides))
    for pat in patterns:
        ids = [s for s, _ in pat.sides]
        if pat.pole is None:
            uf.union(ids[0], ids[2])
            uf.union(ids[1], ids[3])
        else:  # the two sides adjacent to the pole
            uf.union(ids[pat.pole - 1], ids[pat.pole])
    roots = sorted({uf.find(s) for s in range(len(sides))})
    gid = {r: g for g, r in enumerate(roots)}
    group_of = np.array([gid[uf.find(s)] for s in range(len(sides))], dtype=np.int64)
    groups = []
    for g in range(len(roots)):
        members = tuple(int(s) for s in np.flatnonzero(group_of == g))
        lengths = np.array([sides[s].length for s in members])
        mids = np.array([_midpoint(sides[s].polyline) for s in members])
        groups.append(EdgeGroup(g, members, float(lengths.mean()), float(lengths.max()), mids))
    return Layout(decomposition, tuple(sides), tuple(patterns), tuple(groups), group_of)


# --------------------------------------------------------------------------------------------
# Densities
# --------------------------------------------------------------------------------------------


def group_counts(layout: Layout, spec: DensitySpec | None = None, target_length: float | None = None) -> np.ndarray:
    """Number of subdivisions of each edge group (§3.2).

    Parameters
    ----------
    layout : Layout
    spec : DensitySpec, optional
        Local control and defaults; ``target_length`` overrides ``spec.target_length``.
    target_length : float, optional
        Global target edge length; default ``TARGET_FRACTION`` of the domain's diagonal.

    Returns
    -------
    ndarray (n_groups,) int
        ``max(min_count, round(L / target))`` for a group of length ``L`` (average or maximum of its
        sides), unless a region or the designer gives a count or a local target length.

    Raises
    ------
    VaultgramError
        For a bad target length, count, length mode or group id.
    """
    spec = spec or DensitySpec()
    diag = layout.decomposition.disc.domain.diagonal
    target = target_length if target_length is not None else spec.target_length
    if target is None:
        target = TARGET_FRACTION * diag
    if not (target > 0 and math.isfinite(target)):
        raise VaultgramError(f"target length must be a positive number, got {target!r}")
    if spec.length_mode not in ("average", "max"):
        raise VaultgramError(f"length mode must be 'average' or 'max', got {spec.length_mode!r}")
    if int(spec.min_count) < 1:
        raise VaultgramError(f"minimum count must be at least 1, got {spec.min_count!r}")
    n = layout.n_groups
    local = [None] * n  # ("count", n) or ("length", L)
    if spec.regions:
        import shapely

        for poly, value in spec.regions:
            region = shapely.Polygon(np.asarray(poly, dtype=float))
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
    counts = np.empty(n, dtype=np.int64)
    for g in layout.groups:
        kind, v = local[g.id] or ("length", target)
        if kind == "count":
            counts[g.id] = v
        else:
            counts[g.id] = max(int(spec.min_count), int(round(g.length(spec.length_mode) / v)))
            counts[g.id] = max(counts[g.id], _chord_count(layout, g, counts[g.id], CHORD_TOLERANCE * diag))
    return np.maximum(counts, curve_min_counts(layout))


def curve_min_counts(layout: Layout) -> np.ndarray:
    """Least number of subdivisions of each group that keeps every vertex of the input curve features
    (§4.2) as a mesh vertex: one more than the number of input vertices inside each curve side of the
    group (:func:`vaultgram.meshing.weld.side_anchors`), 1 for groups without curve sides. Applied to every
    count, a designer's too: with fewer, the mesh edges would cut the curve's bends."""
    from vaultgram.meshing.weld import kept_points, side_anchors

    disc = layout.decomposition.disc
    keep = kept_points(disc)
    need = np.ones(layout.n_groups, dtype=np.int64)
    for side in layout.sides:
        if side.curve >= 0:
            g = layout.group_of[side.id]
            need[g] = max(need[g], len(side_anchors(side, keep, disc)) + 1)
    return need


def _chord_count(layout: Layout, group: EdgeGroup, count: int, tol: float) -> int:
    """The least count (from ``count`` up) at which every boundary side of the group, resampled as the
    welding does it, stays within ``tol`` of its curve: the "additional constraint on the minimum
    number of subdivisions" of §3.2, from the geometry. Capped at ``CHORD_MAX_FACTOR * count``."""
    from vaultgram.meshing.weld import chord_deviation, kept_points, resample_polyline, side_anchors

    keep = kept_points(layout.decomposition.disc)
    best = count
    for s in group.sides:
        side = layout.sides[s]
        if not side.boundary or len(side.polyline) <= 2:
            continue
        anchors = side_anchors(side, keep, layout.decomposition.disc)
        n = best
        while n < CHORD_MAX_FACTOR * max(count, 1):
            pts, _ = resample_polyline(side.polyline, n, anchors)
            if chord_deviation(side.polyline, pts) <= tol:
                break
            n += max(1, n // 8)
        best = max(best, n)
    return best


def _value(value, where: str):
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        value = {"count": int(value)}
    if not isinstance(value, dict) or len(set(value) & {"count", "length"}) != 1:
        raise VaultgramError(f"density for {where}: give a count or a length, e.g. {{\"count\": 4}}")
    if "count" in value:
        c = value["count"]
        if not isinstance(c, (int, np.integer)) or isinstance(c, bool) or c < 1:
            raise VaultgramError(f"density for {where}: count must be a positive integer, got {c!r}")
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
    """
    if not isinstance(data, dict):
        raise VaultgramError(f"{where}: a density file is a JSON object")
    unknown = set(data) - {"target_length", "length_mode", "min_count", "groups", "regions"}
    if unknown:
        raise VaultgramError(f"{where}: unknown key(s) {', '.join(sorted(unknown))}")
    regions = []
    for k, r in enumerate(data.get("regions", [])):
        if not isinstance(r, dict) or "polygon" not in r:
            raise VaultgramError(f"{where}: region {k} needs a 'polygon' [[x, y], ...]")
        poly = np.asarray(r["polygon"], dtype=float)
        if poly.ndim != 2 or poly.shape[1] != 2 or len(poly) < 3:
            raise VaultgramError(f"{where}: region {k}: polygon must have at least 3 [x, y] points")
        value = {key: r[key] for key in ("count", "length") if key in r}
        _value(value, f"region {k}")
        regions.append((poly, value))
    groups = data.get("groups", {})
    if not isinstance(groups, dict):
        raise VaultgramError(f"{where}: 'groups' maps group ids to counts or lengths")
    target = data.get("target_length")
    if target is not None and not (isinstance(target, (int, float)) and target > 0):
        raise VaultgramError(f"{where}: target_length must be a positive number, got {target!r}")
    min_count = data.get("min_count", 1)
    if not isinstance(min_count, int) or min_count < 1:
        raise VaultgramError(f"{where}: min_count must be a positive integer, got {min_count!r}")
    for key, value in groups.items():
        _value(value, f"group {key}")
    return DensitySpec(target, data.get("length_mode", "average"), min_count, dict(groups), tuple(regions))


def load_densities(path: str | Path) -> DensitySpec:
    """Read a density file (see :func:`densities_from_dict`)."""
    try:
        data = json.loads(Path(path).read_text())
    except OSError as exc:
        raise VaultgramError(f"{path}: cannot read: {exc.strerror}") from None
    except json.JSONDecodeError as exc:
        raise VaultgramError(f"{path}:{exc.lineno}:{exc.colno}: invalid JSON: {exc.msg}") from None
    return densities_from_dict(data, str(path))


def _fmt(p) -> str:
    return f"({p[0]:.6g}, {p[1]:.6g})"
