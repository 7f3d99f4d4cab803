"""The patch layout: atomic sides, patch patterns and edge groups (paper §3.2, second paragraph).

"Based on the set of patches and their respective patterns, the edges sharing the same number of
subdivisions are grouped. The number of edge groups represents the exact number of degrees of
freedom available on the mesh density [...]." (§3.2)

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
  opposite the third side, which stays free). The classes are the :class:`EdgeGroup` s; their
  counts are set in :mod:`vaultgram.meshing.densities`.
* Some points of a side must become mesh vertices (:func:`side_anchors`): the domain's corners and
  sharp input vertices on the boundary (:func:`kept_points`), every input vertex of a curve feature.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from vaultgram.errors import DomainError
from vaultgram.geometry.polylines import halfway_point, polyline_length
from vaultgram.geometry.text import fmt_point
from vaultgram.topology.decomposition import Decomposition

__all__ = [
    "Side",
    "PatchPattern",
    "EdgeGroup",
    "Layout",
    "edge_groups",
    "choose_pole",
    "is_feature_node",
    "is_boundary_node",
    "kept_points",
    "side_anchors",
    "KEEP_ANGLE",
]

#: Input vertices of the domain's rings turning by at least this many degrees are kept as fixed mesh
#: vertices (their group's count is raised to allow it, :func:`vaultgram.meshing.densities.anchor_min_counts`),
#: even below the discretisation's corner angle: sliding boundary vertices would otherwise cut them
#: off (issue 12: a vertex whose angle differs from 180 degrees by more than 15 is a mesh vertex).
KEEP_ANGLE = 12.0


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


# --------------------------------------------------------------------------------------------
# Sides, poles and groups
# --------------------------------------------------------------------------------------------


def is_boundary_node(graph, n: int) -> bool:
    """Whether node ``n`` of the decomposition's graph is a boundary vertex (of any subtype)."""
    return graph.schema.is_subtype(graph.node_type(n), "BoundaryVertex")


def is_feature_node(decomposition: Decomposition, n: int) -> bool:
    """A node labelled 'feature point' (§4.1) or 'curve feature extremity' (§4.2)."""
    graph, disc = decomposition.graph, decomposition.disc
    t = graph.node_type(n)
    if t in ("FeaturePoint", "CurveExtremity"):
        return True
    return 0 <= n < disc.n_points and bool(np.isin(n, disc.feature_points))


def _outside_angle(poly_in: np.ndarray, poly_out: np.ndarray) -> float:
    """The angle (degrees, in (0, 360]) turning counter-clockwise from the direction back along the
    arriving side to the direction along the leaving side: at a corner of a counter-clockwise patch,
    360 minus its interior angle (:func:`vaultgram.geometry.polygons.interior_angle`), the angle
    outside the patch."""
    a = poly_in[-2] - poly_in[-1]
    b = poly_out[1] - poly_out[0]
    ang = math.degrees(math.atan2(a[0] * b[1] - a[1] * b[0], a @ b))
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
    inner = [k for k, c in enumerate(corners) if not is_boundary_node(graph, c) and not on_cut[k]]
    if len(inner) == 1:
        return inner[0]
    # NB: _outside_angle is 360 degrees minus the interior angle, so this takes the corner with the
    # *widest* interior angle, not the smallest as said above; kept so, meshes depend on it
    angles = [_outside_angle(patch.sides[k - 1], patch.sides[k]) for k in range(3)]
    candidates = inner or [0, 1, 2]
    return min(candidates, key=lambda k: angles[k])


def _curve_of_segment(disc) -> dict:
    """``{frozenset((a, b)): c}`` for every segment ``a-b`` of curve feature ``c`` (point indices)."""
    return {frozenset((int(a), int(b))): c for c, pts in enumerate(disc.curves) for a, b in zip(pts[:-1], pts[1:])}


class _UnionFind:
    """Disjoint sets of ``0 .. n - 1`` (path halving; a union keeps the smaller root)."""

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

    Each patch side is stored once as an atomic :class:`Side`; each patch gets its pattern
    (:class:`PatchPattern`, with :func:`choose_pole` for a triangle); sides that must have equal
    counts (opposite sides of a quad, the two sides at a triangle's pole) form one :class:`EdgeGroup`.

    Returns
    -------
    Layout

    Raises
    ------
    DomainError
        If two patches traverse a side in the same direction (they overlap).

    Example
    -------
    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.pipeline import decompose
    >>> layout = edge_groups(decompose(load_domain("examples/quad_with_hole.json")))
    >>> len(layout.patterns), all(p.pole is None for p in layout.patterns)
    (12, True)
    """
    sides = _AtomicSides(decomposition)
    patterns = tuple(_pattern(decomposition, patch, sides) for patch in decomposition.patches)
    group_of, n_groups = _group_of_sides(len(sides.sides), patterns)
    groups = tuple(_edge_group(g, sides.sides, group_of) for g in range(n_groups))
    return Layout(decomposition, tuple(sides.sides), patterns, groups, group_of)


class _AtomicSides:
    """The atomic sides met so far, each stored once, in the direction of its first traversal: a side
    is identified by the set of its edge ids."""

    def __init__(self, decomposition: Decomposition):
        self.graph = decomposition.graph
        self.curve_of = _curve_of_segment(decomposition.disc)
        self.sides: list[Side] = []
        self.index: dict[frozenset, int] = {}

    def ref(self, patch, i: int) -> tuple[int, bool]:
        """``(side id, reversed)`` of side ``i`` of ``patch``, storing the side if it is new."""
        key = frozenset(e for e, _ in patch.side_edges[i])
        start, end = patch.corners[i], patch.corners[(i + 1) % patch.n_sides]
        if key not in self.index:
            self.index[key] = len(self.sides)
            self.sides.append(self._side(len(self.sides), patch, i, start, end))
            return self.index[key], False
        s = self.sides[self.index[key]]
        if s.start == start and s.end == end and s.start != s.end:
            raise DomainError(
                f"side from {fmt_point(self.graph.get(start, 'pos'))} to {fmt_point(self.graph.get(end, 'pos'))} is "
                "traversed twice in the same direction: the patches overlap"
            )
        return self.index[key], True

    def _side(self, sid: int, patch, i: int, start: int, end: int) -> Side:
        """Side ``i`` of ``patch`` as a :class:`Side`: on a ring if made of ``Boundary`` edges, on a
        curve feature if made of ``Curve`` edges."""
        half_edges = patch.side_edges[i]
        types = {self.graph.edge_type(e) for e, _ in half_edges}
        nodes = tuple(u for _, u in half_edges) + (end,)
        boundary = types == {"Boundary"}
        ring = int(self.graph.get(start, "ring")) if boundary else -1
        poly = np.asarray(patch.sides[i], dtype=float)
        curve = self.curve_of.get(frozenset(nodes[:2]), -1) if types == {"Curve"} else -1
        return Side(sid, start, end, poly, nodes, boundary, ring, polyline_length(poly), curve)


def _pattern(decomposition: Decomposition, patch, sides: _AtomicSides) -> PatchPattern:
    """The pattern of a patch (Figure 3): its sides as atomic sides, and the pole of a triangle."""
    refs = tuple(sides.ref(patch, i) for i in range(patch.n_sides))
    pole = choose_pole(decomposition, patch) if patch.n_sides == 3 else None
    return PatchPattern(patch.id, tuple(patch.corners), refs, pole)


def _group_of_sides(n_sides: int, patterns) -> tuple[np.ndarray, int]:
    """The edge group of each side, numbered by the smallest side id in it, and the number of groups:
    opposite sides of a quad share a count, and so do the two sides adjacent to a triangle's pole (the
    pole is a collapsed fourth side opposite the third, which stays free)."""
    uf = _UnionFind(n_sides)
    for pat in patterns:
        ids = [s for s, _ in pat.sides]
        if pat.pole is None:
            uf.union(ids[0], ids[2])
            uf.union(ids[1], ids[3])
        else:
            uf.union(ids[pat.pole - 1], ids[pat.pole])
    roots = sorted({uf.find(s) for s in range(n_sides)})
    gid = {r: g for g, r in enumerate(roots)}
    return np.array([gid[uf.find(s)] for s in range(n_sides)], dtype=np.int64), len(roots)


def _edge_group(g: int, sides: list[Side], group_of: np.ndarray) -> EdgeGroup:
    """Edge group ``g`` with the mean and maximum length and the midpoints of its sides."""
    members = tuple(int(s) for s in np.flatnonzero(group_of == g))
    lengths = np.array([sides[s].length for s in members])
    mids = np.array([halfway_point(sides[s].polyline) for s in members])
    return EdgeGroup(g, members, float(lengths.mean()), float(lengths.max()), mids)


# --------------------------------------------------------------------------------------------
# Points of a side that must be mesh vertices
# --------------------------------------------------------------------------------------------


def kept_points(disc) -> np.ndarray:
    """Domain points the mesh must keep (fixed vertices): corners, point features, and input vertices
    of the rings turning by :data:`KEEP_ANGLE` or more.

    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.topology.discretise import discretise
    >>> np.flatnonzero(kept_points(discretise(load_domain("examples/quad_with_hole.json")))).tolist()
    [0, 36, 72, 108]
    """
    keep = disc.is_corner | (disc.is_input_vertex & (np.abs(disc.turning) >= KEEP_ANGLE))
    keep[np.asarray(disc.feature_points, dtype=np.int64)] = True  # boundary point features (§4.1)
    return keep


def side_anchors(side, keep_point, disc=None) -> list[int]:
    """Indices of a side's polyline points that should be mesh vertices.

    On a boundary side the points of :func:`kept_points`; on a curve side (``side.curve >= 0``,
    given ``disc``) every vertex of the input curve feature, so that the chain of mesh edges along the
    curve passes through all its bends (§4.2: the curve is captured exactly, not by chords).
    """
    if side.boundary:
        return [k for k, v in enumerate(side.nodes[1:-1], 1) if keep_point[v]]
    if disc is not None and getattr(side, "curve", -1) >= 0 and len(side.nodes) == len(side.polyline):
        return [k for k, v in enumerate(side.nodes[1:-1], 1)
                if 0 <= v < disc.n_points and disc.is_input_vertex[v]]
    return []
