"""Constrained-by-density Delaunay triangulation of the domain (paper §3.1, Figure 2b).

"Based on this set of points, a Delaunay triangulation is generated from which the mesh faces lying
outside the outer boundaries or inside the inner boundaries are removed. In this mesh, we call
regular faces those that have two adjacent faces, singular faces those with three adjacent faces and
corner faces those with only one adjacent face." (§3.1)

Method
------
1. Delaunay triangulation of all sample points (:func:`vaultgram.geometry.spatial.delaunay`, GEOS's),
   inside a far frame, counter-clockwise (:func:`_delaunay`).
2. Faces whose centroid is outside the outer ring or inside a hole are removed
   (``shapely.contains_xy``, vectorised).
3. Every boundary segment must be an edge of a kept triangle, with the triangle on the domain side
   (:func:`_check_boundary_recovered`, :func:`_check_curves_recovered`). The discretisation is
   dense enough for Delaunay to recover the boundary in normal cases; if a segment is missing we
   raise :class:`DomainError` naming the ring and vertex and suggesting a smaller spacing, rather
   than returning a triangulation that does not tile the domain.
4. Adjacency across edges (``neighbours``) from sorted directed-edge keys (:class:`_HalfEdges`).
   Curve-feature segments are *cut* (§4.2: "two adjacent faces ... that have their shared edge
   lying on the curve feature are not considered as adjacent") when ``cut_curves`` is true.
5. ``kind`` is the paper's classification by neighbour count (1 corner, 2 regular, 3 singular; 0
   for an isolated face).
6. The faces must tile the domain: same area, and the Euler characteristic of a disc with its
   holes (:func:`_check_tiling`).

Degenerate cases: skeleton cells
--------------------------------
Evenly sampled straight edges make *cocircular* point sets (e.g. four points on one circle): their
Delaunay triangulation is not unique, the triangulator picks an arbitrary diagonal, and two faces with the
same circumcircle appear. Counted face by face they can yield two singular faces joined by a
zero-length skeleton branch, or a singular face next to a regular one at the same centre. We
therefore group faces into **cells**, the faces of the true Delaunay *subdivision*:

* adjacent faces whose circumcentres coincide within ``cocircular_tol * h`` (``h`` the absolute
  boundary spacing) are merged: together they form one convex polygon inscribed in one circle,
  which is one skeleton vertex whatever the diagonal;
* faces of near-zero area (``area < sliver_tol * h**2``, whose circumcentres are meaningless) are
  merged into the neighbour across their longest edge.

Round-off: a cell's centre is the skeleton's node or branch point there, and the rules compare
positions (a strip point on a symmetric plan's axis, a chord to the nearer of two mirror points), so
their last bits decide between mirror choices; those bits follow the order in which the
triangulator lists a triangle's corners (the circumcentre is computed from the first). The centres
are therefore rounded to a power of two near 1e-12 of the plan's extent (:data:`CENTRE_GRID`,
:func:`vaultgram.geometry.arrays.steady`): mirror points are exact mirrors whichever triangulator,
and the move stays far below the stages' tolerances (1e-9). (Measured with qhull's triangles, their
corners turned at random: fig7_curves and features_combined at spacing 0.05 and three non-default
strip options of quad_with_hole, fig6 and fig7 failed with an 11- or 12-sided patch for some turns,
none once rounded; rounded to 1e-9 instead, the notch plan's reflex corner got a second vertex.)

The skeleton (:mod:`vaultgram.topology.skeleton`) is built on cells, not faces; ``kind`` stays the paper's
per-face classification. Ear faces at points that are not corners by angle are handled there (they
are pruned as spurious branches).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import shapely

from vaultgram.domain.model import ring_name
from vaultgram.errors import DomainError
from vaultgram.geometry.arrays import distinct, link_components, steady
from vaultgram.geometry.polygons import bbox_diagonal, signed_area, triangle_areas
from vaultgram.geometry.spatial import delaunay
from vaultgram.geometry.text import fmt_point
from vaultgram.topology.discretise import Discretisation

__all__ = ["Triangulation", "triangulate", "circumcentres", "KIND_CORNER", "KIND_REGULAR", "KIND_SINGULAR"]

#: :attr:`Triangulation.kind` of the paper's corner, regular and singular faces (0: an isolated face).
KIND_CORNER = 1
KIND_REGULAR = 2
KIND_SINGULAR = 3
#: The cell centres are rounded to a power of two near ``TIE * CENTRE_GRID`` (1e-12) of the plan's
#: extent (see "Round-off" above): far above round-off (1e-16), far below the stages' tolerances (1e-9).
CENTRE_GRID = 1e-3


@dataclass(frozen=True, eq=False)
class Triangulation:
    """The Delaunay mesh of the domain with the paper's face classification (§3.1).

    Attributes
    ----------
    disc : Discretisation
        The sample points it was built from.
    points : ndarray (N, 2)
        Same as ``disc.points``.
    triangles : ndarray (M, 3) int
        Point indices, counter-clockwise.
    neighbours : ndarray (M, 3) int
        ``neighbours[t, k]`` is the face across the edge opposite vertex ``k`` of face ``t``, -1
        across a boundary edge, outside, or across a cut curve-feature edge.
    kind : ndarray (M,) int8
        Number of neighbours: 1 corner face, 2 regular, 3 singular (0 isolated face).
    circumcentres : ndarray (M, 2)
    circumradii : ndarray (M,)
    areas : ndarray (M,)
        Unsigned face areas.
    cell : ndarray (M,) int
        Skeleton cell of each face (see module docstring): faces with coincident circumcircles and
        slivers share a cell. Cells are numbered by their smallest face index.
    cell_centres : ndarray (C, 2)
        Centre of each cell (mean circumcentre of its non-sliver faces).
    cell_radii : ndarray (C,)
    cut_curves : bool
        Whether curve-feature edges were cut (§4.2).
    """

    disc: Discretisation
    points: np.ndarray
    triangles: np.ndarray
    neighbours: np.ndarray
    kind: np.ndarray
    circumcentres: np.ndarray
    circumradii: np.ndarray
    areas: np.ndarray
    cell: np.ndarray
    cell_centres: np.ndarray
    cell_radii: np.ndarray
    cut_curves: bool

    @property
    def n_faces(self) -> int:
        return len(self.triangles)

    @property
    def n_cells(self) -> int:
        return len(self.cell_centres)

    def edges(self) -> np.ndarray:
        """Unique undirected edges (E, 2), each as (min, max) point index."""
        return _undirected_edges(self.triangles)

    def __repr__(self) -> str:
        counts = np.bincount(self.kind, minlength=4)
        return (
            f"Triangulation({len(self.points)} points, {len(self.triangles)} faces: "
            f"{counts[1]} corner, {counts[2]} regular, {counts[3]} singular; {self.n_cells} cells)"
        )


def circumcentres(p: np.ndarray, tri: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Circumcentres and circumradii of triangles ``tri`` over points ``p`` (vectorised).

    Computed relative to the first vertex for accuracy; degenerate faces give inf.

    >>> centre, radius = circumcentres(np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]]), np.array([[0, 1, 2]]))
    >>> centre.tolist(), radius.round(6).tolist()
    ([[1.0, 1.0]], [1.414214])
    """
    a = p[tri[:, 0]]
    b = p[tri[:, 1]] - a
    c = p[tri[:, 2]] - a
    d = 2.0 * (b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0])
    b2 = (b * b).sum(1)
    c2 = (c * c).sum(1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (c[:, 1] * b2 - b[:, 1] * c2) / d
        uy = (b[:, 0] * c2 - c[:, 0] * b2) / d
    centre = a + np.stack([ux, uy], axis=1)
    radius = np.hypot(ux, uy)
    bad = ~np.isfinite(radius)
    centre[bad] = np.inf
    radius[bad] = np.inf
    return centre, radius


def triangulate(
    disc: Discretisation,
    cut_curves: bool = True,
    cocircular_tol: float = 1e-6,
    sliver_tol: float = 1e-6,
) -> Triangulation:
    """Delaunay-triangulate the discretised domain and classify its faces (paper §3.1).

    Parameters
    ----------
    disc : Discretisation
        From :func:`vaultgram.topology.discretise.discretise`.
    cut_curves : bool
        Make curve-feature edges non-adjacent (the §4.2 topological cut).
    cocircular_tol : float
        Adjacent faces whose circumcentres are closer than ``cocircular_tol * disc.h`` form one cell.
    sliver_tol : float
        Faces with area below ``sliver_tol * disc.h**2`` are merged into a neighbour's cell.

    Returns
    -------
    Triangulation

    Raises
    ------
    DomainError
        If a boundary (or curve-feature) segment is not an edge of the triangulation: the sampling
        is too coarse for the geometry there.

    Example
    -------
    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.topology.discretise import discretise
    >>> triangulate(discretise(load_domain("examples/quad_with_hole.json"), 0.05))
    Triangulation(124 points, 124 faces: 4 corner, 116 regular, 4 singular; 116 cells)
    """
    pts = disc.points
    tri, areas = _faces_inside(disc)
    half_edges = _HalfEdges.of(tri, len(pts))
    _check_boundary_recovered(disc, half_edges)
    _check_curves_recovered(disc, half_edges)
    neighbours = _neighbours(half_edges, disc.curve_segments() if cut_curves else None)
    kind = (neighbours >= 0).sum(axis=1).astype(np.int8)
    _check_tiling(disc, tri, areas)
    centres, radii = circumcentres(pts, tri)
    cell, cell_centres, cell_radii = _cells(pts, tri, neighbours, centres, radii, areas,
                                            cocircular_tol * disc.h, sliver_tol * disc.h**2)
    cell_centres = steady(cell_centres, CENTRE_GRID * float(np.abs(pts).max()))  # "Round-off" in the module docstring
    for arr in (tri, neighbours, kind, centres, radii, areas, cell, cell_centres, cell_radii):
        arr.setflags(write=False)
    return Triangulation(disc, pts, tri, neighbours, kind, centres, radii, areas, cell, cell_centres, cell_radii,
                         cut_curves)


def _faces_inside(disc: Discretisation) -> tuple[np.ndarray, np.ndarray]:
    """The counter-clockwise Delaunay triangles whose centroid lies in the domain, and their areas."""
    tri, area, centroid = _delaunay(disc.points)
    poly = disc.domain.polygon()
    shapely.prepare(poly)
    inside = shapely.contains_xy(poly, centroid[:, 0], centroid[:, 1])
    return tri[inside], area[inside]


def _delaunay(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The counter-clockwise Delaunay triangles of ``pts`` (:func:`vaultgram.geometry.spatial.delaunay`),
    their areas and centroids.

    A far frame around the points means no sample lies on the convex hull, so collinear boundary
    samples on it never make flat (zero-area) hull triangles; triangles touching the frame are
    dropped.
    """
    n = len(pts)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    mid, big = 0.5 * (lo + hi), 10.0 * max(bbox_diagonal(pts), 1e-300)
    ang = np.radians([15.0, 105.0, 195.0, 285.0, 60.0])
    frame = mid + big * np.stack([np.cos(ang), np.sin(ang)], axis=1) * np.array([[1.0], [1.1], [1.0], [1.2], [1.3]])
    tri = delaunay(np.concatenate([pts, frame]), bbox_diagonal(pts))  # the plan's size: not the frame's
    tri = tri[(tri < n).all(axis=1)]
    centroid = (pts[tri[:, 0]] + pts[tri[:, 1]] + pts[tri[:, 2]]) / 3.0
    return tri, np.abs(triangle_areas(pts, tri)), centroid


def _edge_keys(tri: np.ndarray, n: int) -> np.ndarray:
    """Directed edge keys (M, 3): key of the edge opposite vertex k, oriented as in the ccw face."""
    a = tri[:, [1, 2, 0]]
    b = tri[:, [2, 0, 1]]
    return a.astype(np.int64) * n + b


def _undirected_edges(tri: np.ndarray) -> np.ndarray:
    """Unique undirected edges (E, 2) of triangles, each as (min, max) point index, sorted (as keys
    ``min * n + max``, :func:`~vaultgram.geometry.arrays.distinct`)."""
    e = np.sort(np.concatenate([tri[:, [1, 2]], tri[:, [2, 0]], tri[:, [0, 1]]]), axis=1).astype(np.int64)
    n = int(e.max()) + 1 if len(e) else 1
    return np.stack(np.divmod(distinct(e[:, 0] * n + e[:, 1]), n), axis=1).astype(tri.dtype, copy=False)


class _HalfEdges(NamedTuple):
    """The directed edges of the faces, keyed ``a * n + b`` for the edge from point ``a`` to ``b``:
    the key of the edge opposite corner ``k`` of face ``t`` is ``keys[3 * t + k]``."""

    keys: np.ndarray
    order: np.ndarray  # argsort of keys
    sorted_keys: np.ndarray
    n: int  # number of points

    @classmethod
    def of(cls, tri: np.ndarray, n: int) -> _HalfEdges:
        """The half-edges of counter-clockwise triangles over ``n`` points."""
        keys = _edge_keys(tri, n).ravel()
        order = np.argsort(keys, kind="stable")
        return cls(keys, order, keys[order], n)

    def find(self, q: np.ndarray) -> np.ndarray:
        """Flat position (face*3 + k) of directed edge keys q, or -1."""
        pos = np.searchsorted(self.sorted_keys, q)
        pos = np.minimum(pos, len(self.sorted_keys) - 1)
        hit = self.sorted_keys[pos] == q if len(self.sorted_keys) else np.zeros(len(q), bool)
        return np.where(hit, self.order[pos], -1)


class BoundaryRecoveryError(DomainError):
    """A boundary or curve segment that is not an edge of the triangulation; ``segments`` (k, 2, 2)
    holds the end points of every such segment (:mod:`vaultgram.topology.recovery` refines there)."""

    def __init__(self, message: str, segments: np.ndarray):
        super().__init__(message, places=segments)
        self.segments = segments


def _check_boundary_recovered(disc: Discretisation, half_edges: _HalfEdges) -> None:
    """Every boundary segment is an edge of a face on the domain side."""
    pts, n = disc.points, half_edges.n
    seg = disc.segments()
    found = half_edges.find(seg[:, 0] * n + seg[:, 1])
    if (found < 0).any():
        s = int(np.flatnonzero(found < 0)[0])
        i, j = seg[s]
        r = int(disc.ring[i])
        raise BoundaryRecoveryError(
            f"{ring_name(r)}, vertex {int(disc.index[i])}: boundary segment from {fmt_point(pts[i], 10)} to "
            f"{fmt_point(pts[j], 10)} is not an edge of the Delaunay triangulation (spacing {disc.spacing:g} is "
            "too coarse for the geometry there); use a smaller spacing or add vertices to the ring",
            pts[seg[found < 0]],
        )


def _check_curves_recovered(disc: Discretisation, half_edges: _HalfEdges) -> None:
    """Every curve-feature segment is an edge of a face (on either side)."""
    pts, n = disc.points, half_edges.n
    cseg = disc.curve_segments()
    if not len(cseg):
        return
    missing = (half_edges.find(cseg[:, 0] * n + cseg[:, 1]) < 0) & (half_edges.find(cseg[:, 1] * n + cseg[:, 0]) < 0)
    if missing.any():
        i, j = cseg[int(np.flatnonzero(missing)[0])]
        c_id = next(k for k, cv in enumerate(disc.curves) if np.any((cv[:-1] == i) & (cv[1:] == j)))
        pos = int(np.flatnonzero(disc.curves[c_id] == i)[0])
        raise BoundaryRecoveryError(
            f"curve feature {c_id}, vertex {pos}: segment from {fmt_point(pts[i], 10)} to {fmt_point(pts[j], 10)} "
            f"is not an edge of the Delaunay triangulation (spacing {disc.spacing:g} is too "
            "coarse there); use a smaller spacing",
            pts[cseg[missing]],
        )


def _neighbours(half_edges: _HalfEdges, cut: np.ndarray | None) -> np.ndarray:
    """``(M, 3)``: the face across the edge opposite each corner, -1 across the boundary and across
    the ``cut`` segments (the §4.2 topological cut along curve features)."""
    flat, n = half_edges.keys, half_edges.n
    pos = half_edges.find((flat % n) * n + flat // n)
    neighbours = np.where(pos >= 0, pos // 3, -1).reshape(-1, 3)
    if cut is not None and len(cut):
        und = np.sort(cut, axis=1)
        ckeys = und[:, 0] * n + und[:, 1]
        ea, eb = flat // n, flat % n
        ekeys = np.minimum(ea, eb) * n + np.maximum(ea, eb)
        neighbours = np.where(np.isin(ekeys, ckeys).reshape(-1, 3), -1, neighbours)
    return neighbours


def _check_tiling(disc: Discretisation, tri: np.ndarray, areas: np.ndarray) -> None:
    """The triangles tile the domain: the same area, and the Euler characteristic of a disc with holes."""
    total, expect = float(areas.sum()), _sampled_area(disc)
    if abs(total - expect) > 1e-9 * abs(expect) + 1e-12:
        raise DomainError(
            f"triangulation covers area {total:.12g} but the domain has area {expect:.12g}; "
            "use a smaller spacing"
        )
    euler = len(distinct(tri)) - len(_undirected_edges(tri)) + len(tri)
    if euler != 1 - len(disc.domain.holes):
        raise DomainError(
            f"triangulation is not a valid tiling of the domain (Euler characteristic {euler}, "
            f"expected {1 - len(disc.domain.holes)}); use a smaller spacing"
        )


def _sampled_area(disc: Discretisation) -> float:
    """The area inside the sampled rings (the domain's, but for the thinning of dense runs of
    vertices, :func:`vaultgram.geometry.polylines.thinned_dense_runs`)."""
    areas = [abs(signed_area(disc.points[r])) for r in disc.rings]
    return float(areas[0] - sum(areas[1:]))


# --------------------------------------------------------------------------------------------
# Skeleton cells (see the module docstring)
# --------------------------------------------------------------------------------------------


def _cells(pts, tri, neighbours, centres, radii, areas, ctol, atol):
    """Group faces into skeleton cells: cocircular neighbours and slivers (see module docstring).

    Returns the cell of each face, and the centre and radius of each cell.
    """
    m = len(tri)
    sliver = areas < atol
    ea, eb = _cell_links(pts, tri, neighbours, centres, sliver, ctol)
    cell = _numbered_by_first_face(link_components(m, ea, eb), m)
    cc, rr = _cell_centres(pts, tri, cell, centres, radii, sliver)
    return cell.astype(np.int64), cc, rr


def _cell_links(pts, tri, neighbours, centres, sliver, ctol) -> tuple[np.ndarray, np.ndarray]:
    """Pairs of faces in one cell: adjacent faces with coincident circumcentres (neither a sliver),
    and each sliver with its neighbour across its longest edge."""
    m = len(tri)
    t = np.repeat(np.arange(m), 3)
    u = neighbours.ravel()
    ok = u > t  # each interior edge once
    t, u = t[ok], u[ok]
    good = ~sliver[t] & ~sliver[u]
    with np.errstate(invalid="ignore"):
        same = good & (np.hypot(*(centres[t] - centres[u]).T) <= ctol)
    ea, eb = [t[same]], [u[same]]
    if sliver.any():
        s = np.flatnonzero(sliver)
        p = pts[tri[s]]
        # edge k is opposite vertex k
        lens = np.stack([np.hypot(*(p[:, (k + 2) % 3] - p[:, (k + 1) % 3]).T) for k in range(3)], axis=1)
        nb = neighbours[s]
        lens = np.where(nb >= 0, lens, -1.0)
        k = np.argmax(lens, axis=1)
        target = nb[np.arange(len(s)), k]
        has = target >= 0
        ea.append(s[has])
        eb.append(target[has])
    return np.concatenate(ea), np.concatenate(eb)


def _numbered_by_first_face(labels: np.ndarray, m: int) -> np.ndarray:
    """Component labels renumbered so that cells are in the order of their smallest face index."""
    first = np.full(labels.max() + 1 if m else 0, m, dtype=np.int64)
    np.minimum.at(first, labels, np.arange(m))
    rank = np.empty_like(first)
    rank[np.argsort(first, kind="stable")] = np.arange(len(first))
    return rank[labels]


def _cell_centres(pts, tri, cell, centres, radii, sliver) -> tuple[np.ndarray, np.ndarray]:
    """Centre and radius of each cell: the mean circumcentre and circumradius of its faces that are not
    slivers; a cell made only of slivers has the centroid of its first face and radius 0."""
    nc = int(cell.max()) + 1 if len(cell) else 0
    w = (~sliver).astype(float)
    wsum = np.bincount(cell, weights=w, minlength=nc)
    cx = np.bincount(cell, weights=np.where(sliver, 0.0, centres[:, 0]), minlength=nc)
    cy = np.bincount(cell, weights=np.where(sliver, 0.0, centres[:, 1]), minlength=nc)
    cr = np.bincount(cell, weights=np.where(sliver, 0.0, radii), minlength=nc)
    with np.errstate(invalid="ignore", divide="ignore"):
        cc = np.stack([cx / wsum, cy / wsum], axis=1)
        rr = cr / wsum
    for ci in np.flatnonzero(wsum == 0):
        f = int(np.flatnonzero(cell == ci)[0])
        cc[ci] = pts[tri[f]].mean(axis=0)
        rr[ci] = 0.0
    return cc, rr
