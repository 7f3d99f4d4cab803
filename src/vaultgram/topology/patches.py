"""Patches (paper §3.1, Figure 2f): the faces of the planar map of branches, rebranches and boundary.

Each bounded face of the rewritten decomposition graph that is not the inside of a hole is a patch.
Its *corners* are the face's nodes where a side ends: skeleton vertices (singularities, loop cuts),
boundary points where a rebranch or a branch arrives, and polygon corners. Between consecutive
corners runs a *side*, a polyline made of the edges' own polylines. Every patch must have 3 or 4
sides; any other face is an error naming where it is.
"""

from __future__ import annotations

import functools
import itertools
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np
import shapely

from vaultgram.engine.embedding import face_index, faces
from vaultgram.engine.graph import HostGraph
from vaultgram.errors import DomainError, RewriteError
from vaultgram.geometry.frames import NO_ORIGIN, to_plan
from vaultgram.geometry.polygons import interior_angle, signed_area
from vaultgram.geometry.polylines import turning_angles
from vaultgram.geometry.text import fmt_point
from vaultgram.topology.discretise import Discretisation
from vaultgram.topology.statecache import by_content
from vaultgram.topology.types import BOUNDARY, BOUNDARY_VERTEX, CURVE_EXTREMITY, FEATURE_POINT, SKELETON_VERTEX


@dataclass(frozen=True, eq=False)
class Patch:
    """A 3- or 4-sided patch, counter-clockwise.

    Attributes
    ----------
    id : int
    corners : tuple of int
        Node ids of the decomposition graph, counter-clockwise.
    sides : tuple of ndarray (k, 2)
        ``sides[i]`` runs from ``corners[i]`` to ``corners[i + 1]`` (cyclically).
    side_edges : tuple of tuple of (edge id, start node)
        The graph's half-edges along each side, in order.
    """

    id: int
    corners: tuple
    sides: tuple
    side_edges: tuple

    @property
    def n_sides(self) -> int:
        return len(self.corners)

    def corner_angles(self) -> np.ndarray:
        """The interior angle (degrees) at each corner, between the ends of the sides meeting there: a
        quad mesh of the patch can turn by no more than 180 degrees at a corner (over 180 it folds
        there at any density)."""
        return np.array([interior_angle(self.sides[k - 1][-2], self.sides[k][0], self.sides[k][1])
                         for k in range(self.n_sides)])

    def side_turnings(self) -> np.ndarray:
        """The net turning (degrees, positive to the left, i.e. bulging out of the patch) of each side
        between its corners, from its first segment to its last: a quad patch's Coons map skews its
        quads where a side bends far from straight (issue 12, :func:`vaultgram.meshpipeline._bent`).

        >>> bent = np.array([[2.0, 0.0], [3.0, 1.0], [3.0, 2.0], [2.0, 3.0]])  # two bends of 45 degrees
        >>> sides = (np.array([[0.0, 0.0], [2.0, 0.0]]), bent, np.array([[2.0, 3.0], [0.0, 0.0]]))
        >>> Patch(0, (0, 1, 2), sides, ()).side_turnings().round(6).tolist()
        [0.0, 90.0, 0.0]
        """
        return np.array([turning_angles(side, closed=False).sum() for side in self.sides])

    def polygon(self) -> np.ndarray:
        """The patch outline: the concatenated sides without repeated points."""
        return np.vstack([s[:-1] for s in self.sides])

    def area(self) -> float:
        """Signed area of the outline (positive: counter-clockwise)."""
        return float(signed_area(self.polygon()))

    def to_json(self, origin=NO_ORIGIN) -> dict:
        """Corners, side count and side polylines (in the plan's frame: ``origin`` added, see
        :mod:`vaultgram.geometry.frames`), for ``patches.json``."""
        return {
            "id": self.id,
            "corners": list(self.corners),
            "n_sides": self.n_sides,
            "sides": [to_plan(s, origin).tolist() for s in self.sides],
        }


def half_edge_polyline(graph: HostGraph, edge: int, start: int) -> np.ndarray:
    """The points of an edge from ``start`` to its other end (its polyline, or the straight segment)."""
    return key_polyline(half_edge_key(graph, edge, start))


def find_patches(graph: HostGraph, disc: Discretisation, edge_types, strict: bool = True) -> list[Patch]:
    """The patches of a rewritten decomposition graph (see the module docstring).

    With ``strict`` every patch must have 3 or 4 sides; without, faces with more sides are returned
    too (for the patching rules to split).

    Example
    -------
    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.pipeline import decompose
    >>> from vaultgram.topology.types import PLAN_EDGES
    >>> dec = decompose(load_domain("examples/quad_with_hole.json"), 0.05)
    >>> patches = find_patches(dec.graph, dec.disc, PLAN_EDGES)
    >>> len(patches), {p.n_sides for p in patches}
    (12, {4})
    """
    types = set(edge_types)
    patches, corner = [], {}
    for face, polys, outline in plan_faces(graph, types):
        corners, sides, side_edges = _sides(graph, face, polys, outline, types, corner)
        if len(corners) < 3 or (strict and len(corners) > 4):
            raise DomainError(
                f"patch around {_where(outline)} has {len(corners)} sides (corners at "
                f"{', '.join(fmt_point(graph.get(c, 'pos')) for c in corners)}); only 3- and 4-sided patches "
                "can be meshed: try another spacing or check the rules", places=[outline]
            )
        patches.append(Patch(len(patches), corners, sides, side_edges))
    return patches


def plan_faces(graph: HostGraph, edge_types) -> list[tuple[list, list, np.ndarray]]:
    """The bounded faces of the plan that are not the inside of a hole, each as its half-edges, their
    polylines and its outline (counter-clockwise, not closed)."""
    out, index = [], face_index(graph, edge_types)
    for face in faces(graph, edge_types, walk=face_from):
        found = face_outline(graph, edge_types, face)
        data = index.data(face[0])
        if "patch" not in data:  # not the unbounded face, nor a hole (kept with the face)
            data["patch"] = found.area > 0 and not _is_hole(graph, face)
        if data["patch"]:
            out.append((face, list(found.polylines), found.outline))
    return out


def face_from(graph: HostGraph, edge_types, half_edge: tuple) -> list:
    """The face to the left of ``half_edge`` from it on, as :func:`~vaultgram.engine.embedding.face_walk`
    walks it (a new list), from the graph's face index (:func:`~vaultgram.engine.embedding.face_index`):
    each face is walked once and kept until a change touches it. The rules' helpers look for the
    face of each Patch node from its first corner, trying the faces there one after another, in
    every state the search makes, and a state differs from the one before in a few faces (issue 13)."""
    return face_index(graph, edge_types).face(half_edge)


def kept_at_node(graph: HostGraph, edge_types, x: int, key, find):
    """``find(look)``: a search among the faces of the map of ``edge_types`` at node ``x`` (in the
    rotation there) that reads each face it looks at through ``look(half_edge)``, which gives the
    face's data dictionary (:meth:`~vaultgram.engine.embedding.FaceIndex.data`). The result is
    kept in the node data of ``x`` under ``key`` (what else it depends on: the Patch node's
    corners) with the dictionaries it read, and found again while the map's edges at ``x`` are
    unchanged and each face it read is the same, unchanged (its dictionary is the same one): the
    rule helpers look for the face of each Patch node in every state of the search (issue 13)."""
    index = face_index(graph, edge_types)
    kept = index.node_data(x).get(key)
    if kept is not None and all(index.data(h) is data for h, data in kept[0]):
        return kept[1]
    read = []

    def look(half_edge):
        read.append((half_edge, index.data(half_edge)))
        return read[-1][1]

    result = find(look)
    index.node_data(x)[key] = (tuple(read), result)
    return result


@dataclass(frozen=True)
class FaceOutline:
    """A face's half-edge polylines, its outline (not closed), the outline closed (its first point
    repeated at the end) and their signed areas (the rule helpers test the closed one). The arrays
    are read-only: they are shared by every state of the graph with that face."""

    polylines: tuple
    outline: np.ndarray
    closed: np.ndarray
    area: float
    closed_area: float

    @functools.cached_property
    def starts(self) -> tuple:
        """Where each half-edge's polyline starts along the outline (the index of its first point)."""
        return tuple(itertools.accumulate((len(p) - 1 for p in self.polylines[:-1]), initial=0))

    @functools.cached_property
    def polygon(self) -> shapely.Polygon:
        """The outline as a prepared shapely polygon (the strip helpers' containment tests), made
        once for every state of the graph with this face."""
        polygon = shapely.Polygon(self.outline)
        shapely.prepare(polygon)
        return polygon


#: The face outlines kept (the most recently asked) by :func:`face_outline`.
OUTLINES = 4096
_OUTLINES: OrderedDict = OrderedDict()


def face_outline(graph: HostGraph, edge_types, face) -> FaceOutline:
    """The outline of a face of the map of ``edge_types`` (its half-edges, from :func:`face_from` or
    :func:`~vaultgram.engine.embedding.faces`), kept with the face in the graph's face index while
    the face is unchanged, and by what it is made of: each half-edge's polyline attribute and
    direction, or its ends' positions (:func:`half_edge_key`). Exploration (issue 13) asks for the
    same faces in state after state, each rewrite changing only a few; a key by content is right in
    every state (ids are reused across the branches of a search, the geometry they carry is not), so
    a face walked again finds its outline (the same object) there."""
    data = face_index(graph, edge_types).data(face[0])
    found = data.get(("outline", face[0]))
    if found is None:
        key = tuple(half_edge_key(graph, e, u) for e, u in face)
        found = data[("outline", face[0])] = by_content(_OUTLINES, key, lambda: _outline_of(key), OUTLINES)
    return found


def _outline_of(key: tuple) -> FaceOutline:
    polys = tuple(key_polyline(k) for k in key)
    outline = np.vstack([p[:-1] for p in polys])
    closed = np.vstack([outline, outline[:1]])
    for array in (*polys, outline, closed):
        array.flags.writeable = False
    return FaceOutline(polys, outline, closed, float(signed_area(outline)), float(signed_area(closed)))


def half_edge_key(graph: HostGraph, edge: int, start: int) -> tuple:
    """What :func:`half_edge_polyline` makes the half-edge's points from: the edge's polyline and
    whether it runs from ``start``, or the positions of ``start`` and the other end."""
    poly = graph.edge_attrs(edge).get("polyline") or ()
    if len(poly) < 2:
        return (graph.get(start, "pos"), graph.get(graph.other(edge, start), "pos"))
    return (poly, graph.ends(edge)[0] == start)


def key_polyline(key: tuple) -> np.ndarray:
    """The points of a half-edge from its :func:`half_edge_key` (as :func:`half_edge_polyline`)."""
    points, forward = key
    if isinstance(forward, bool):
        pts = np.asarray(points, dtype=float)
        return pts if forward else pts[::-1]
    return np.asarray(key, dtype=float)


def hole_rings(graph: HostGraph) -> list[np.ndarray]:
    """The hole rings of the plan (ring 1, 2, ...) as point arrays in ring order, from the graph's
    ``BoundaryVertex`` nodes (their ``ring`` and ``index``, equal indices by node id as in
    :func:`~vaultgram.topology.corners.graph_rings`)."""
    rings: dict[int, list] = {}
    for n in graph.of_types(graph.schema.subtypes(BOUNDARY_VERTEX)):
        ring = graph.get(n, "ring")
        if ring > 0:
            rings.setdefault(ring, []).append((graph.get(n, "index"), n, graph.get(n, "pos")))
    return [np.array([p for _, _, p in sorted(rings[r])], dtype=float) for r in sorted(rings)]


def enclosed_holes(outlines, holes) -> list[tuple[int, int]]:
    """The pairs (outline k, hole h) where outline ``k`` has hole ``h`` inside it: a face of the plan
    that encloses a hole is no disk, whatever its number of sides (§3.1: every patch is a disk). A
    hole is inside when a point inside the hole is (each hole is tested at one such point; all the
    outlines at once, as one array of polygons)."""
    if not holes:
        return []
    return _holes_inside(outlines, np.array([_point_inside(ring) for ring in holes]))


def _holes_inside(outlines, inside: np.ndarray) -> list[tuple[int, int]]:
    """:func:`enclosed_holes` with each hole's point inside it given (``inside``, (h, 2))."""
    if not len(outlines):
        return []
    sizes = [len(outline) for outline in outlines]
    rings = shapely.linearrings(np.vstack(outlines), indices=np.repeat(np.arange(len(sizes)), sizes))
    within = shapely.contains_xy(shapely.polygons(rings)[:, None], inside[None, :, 0], inside[None, :, 1])
    return [(int(k), int(h)) for k, h in np.argwhere(within)]


def check_no_enclosed_holes(graph: HostGraph, patches) -> None:
    """The stage check of the topology: no patch may enclose a hole (a wrong rulebook can leave a hole's
    ring unconnected to the layout, and the ring of patches around it comes out as one patch).

    Each patch's answer is kept by its sides (shared by every state of the graph with that face,
    :func:`_sides`; kept alive with the entry, so that their ``id`` names them) and the holes'
    inner points: exploration (issue 13) checks the same patches in state after state.

    Raises
    ------
    RewriteError
        Naming the patch and the hole: a fault of the rules, whatever they did.
    """
    holes = hole_rings(graph)
    if not holes:
        return
    inside = np.array([by_content(_INSIDE, ring.tobytes(), lambda: _point_inside(ring), INSIDE) for ring in holes])
    key = inside.tobytes()
    found = [(k, h) for k, p in enumerate(patches) for h in
             by_content(_ENCLOSED, (id(p.sides), key), lambda: (p.sides, _enclosed_by(p, inside)), ENCLOSED)[1]]
    if found:
        k, h = found[0]
        where = _where(patches[k].polygon())
        raise RewriteError(
            f"patch {patches[k].id} around {where} ({patches[k].n_sides} sides) encloses hole {h + 1}: it is no "
            "disk; no rule connected the hole's ring to the patch layout: check the rules (rebranching)"
        )


#: The patches' answers (the holes inside them) and the holes' inner points kept (the most recently
#: asked) by :func:`check_no_enclosed_holes`.
ENCLOSED, INSIDE = 4096, 64
_ENCLOSED: OrderedDict = OrderedDict()
_INSIDE: OrderedDict = OrderedDict()


def _enclosed_by(patch: Patch, inside: np.ndarray) -> tuple[int, ...]:
    """The holes (by number, from 0) whose inner point ``inside[h]`` is inside the patch."""
    return tuple(h for _, h in _holes_inside([patch.polygon()], inside))


def _point_inside(ring: np.ndarray) -> np.ndarray:
    """A point strictly inside a simple polygon (shapely's representative point)."""
    point = shapely.Polygon(ring).representative_point()
    return np.array([point.x, point.y])


#: The faces cut at their corners kept (the most recently asked) by :func:`_sides`.
SIDES = 4096
_SIDES: OrderedDict = OrderedDict()


def _sides(graph: HostGraph, face: list, polys: list, outline: np.ndarray, types,
           known: dict) -> tuple[tuple, tuple, tuple]:
    """A face of the plan cut at its corners: the corners, the side polylines between them and the
    half-edges along each side, starting at the first corner of the face's walk. Kept with the face
    in the graph's face index while it is unchanged, and by the face's half-edges, which of their
    nodes are corners and its outline (one of :func:`face_outline`'s, kept
    alive with the entry, so that its ``id`` names it): the same face in another state of the graph
    is cut the same way (issue 13). ``known``: node -> whether it is a corner, filled as the faces
    are cut (a node is on the faces of each of its edges), from the face index's node data (kept
    while the node and the plan edges at it are unchanged)."""
    index = face_index(graph, types)
    for _, u in face:
        if u not in known:
            kept = index.node_data(u)
            if "corner" not in kept:
                kept["corner"] = _is_corner(graph, u, types)
            known[u] = kept["corner"]
    corner = tuple(known[u] for _, u in face)
    data = index.data(face[0])
    found = data.get(("sides", face[0], corner))
    if found is None:
        found = data[("sides", face[0], corner)] = by_content(
            _SIDES, (tuple(face), corner, id(outline)),
            lambda: (outline, _cut_at_corners(face, polys, corner, outline)), SIDES)[1]
    return found


def _cut_at_corners(face: list, polys: list, corner: tuple, outline: np.ndarray) -> tuple[tuple, tuple, tuple]:
    """:func:`_sides` for a face whose nodes ``corner`` says are corners (or not)."""
    start = next((i for i, c in enumerate(corner) if c), None)
    if start is None:
        raise DomainError(f"a region around {_where(outline)} has no corner at all; it cannot be a patch")
    face, polys, corner = face[start:] + face[:start], polys[start:] + polys[:start], corner[start:] + corner[:start]
    corners, sides, side_edges = [], [], []
    for (e, u), poly, is_corner in zip(face, polys, corner):
        if is_corner:
            corners.append(u)
            sides.append([poly])
            side_edges.append([(e, u)])
        else:
            sides[-1].append(poly[1:])
            side_edges[-1].append((e, u))
    polylines = tuple(np.vstack(s) for s in sides)
    for side in polylines:
        side.flags.writeable = False  # shared by every state with this face (see _sides)
    return tuple(corners), polylines, tuple(tuple(s) for s in side_edges)


def _is_corner(graph: HostGraph, n: int, types) -> bool:
    """Where a patch side ends: skeleton vertices, point features (inside or on the boundary, §4.1),
    curve extremities, corner vertices of corner faces, and any point where a third edge of the plan
    arrives. A boundary point feature in the middle of a side is thus a flat corner of its patch,
    which the patching rules split there (``split_at_boundary_feature``)."""
    t = graph.node_type(n)
    if t in (FEATURE_POINT, CURVE_EXTREMITY) or graph.schema.is_subtype(t, SKELETON_VERTEX):
        return True
    return graph.get(n, "corner") or graph.get(n, "feature") or graph.degree(n, types) > 2


def _is_hole(graph: HostGraph, face) -> bool:
    """A face made only of boundary edges of one hole ring, walked around the hole."""
    if any(graph.edge_type(e) != BOUNDARY for e, _ in face):
        return False
    rings = {graph.get(u, "ring") if graph.schema.is_subtype(graph.node_type(u), BOUNDARY_VERTEX) else -1
             for _, u in face}
    return len(rings) == 1 and next(iter(rings)) > 0


def _where(outline: np.ndarray) -> str:
    """Where a face is, for messages: the mean of its outline points."""
    return fmt_point(outline.mean(axis=0))
