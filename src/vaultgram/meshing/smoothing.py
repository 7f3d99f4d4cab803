"""Constrained uniform Laplacian smoothing (paper §3.2, Figure 2h; Botsch et al. [12]).

"A uniform Laplacian smoothing can be applied, which iteratively moves each vertex towards the
barycentre of its neighbouring vertices. Constraints are added to respect the boundaries: vertices at
the boundary corners remain fixed and other vertices lying on the boundaries are projected back on it
after each iteration, to allow them to slide along it. Usually, a small number of iterations is
sufficient to obtain a globally smooth mesh." (§3.2) During smoothing, feature points stay fixed and
curve-feature vertices are projected onto their curve (§4.1, §4.2).

One iteration is one sparse product ``x <- D^-1 A x`` (``A`` the vertex adjacency of the mesh edges,
``D`` the degrees; :class:`vaultgram.geometry.meshes.MeanOperator`), fixed vertices reset, then each
:class:`SlideConstraint`'s vertices projected onto its polyline: the nearest point over all
segments, computed for all vertices of the constraint at once
(:func:`vaultgram.geometry.polylines.project_to_polyline`). No Python loop runs over vertices. Faces
that smoothing leaves folded are repaired by :mod:`vaultgram.meshing.untangle`.

Near the boundary's reflex kinks of two faces the barycentres pull every row onto the kink (issues
12 and 18); there each vertex keeps a share of its welded Coons layout's offset from its neighbours'
barycentre (:func:`kink_offsets`, a reference-shape smoothing that fades to the uniform one).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from vaultgram import progress
from vaultgram.geometry.arrays import PIECE, distinct, pieces
from vaultgram.geometry.meshes import (
    Adjacency,
    MeanOperator,
    MeshError,
    adjacency,
    barycentre_operator,
    boundary_adjacency,
    corner_angles,
    corner_arrays,
    corner_vectors,
)
from vaultgram.geometry.polygons import cross_z
from vaultgram.meshing.quadmesh import slide

__all__ = ["laplacian_smooth", "kink_offsets", "reflex_kinks", "DEFAULT_ITERATIONS", "KINK_REACH"]

#: Default number of iterations: smooths the seams between patches visibly without drifting far from
#: the Coons layout (the global shape of the layout comes from the patches, not from smoothing).
DEFAULT_ITERATIONS = 20

_MAX_REVERTS = 8

#: A boundary vertex of two faces whose corners add up to more than 180 plus this many degrees is a
#: reflex kink (:func:`reflex_kinks`): multiple_lobes' notches are 212-237 degrees; a sliding bend
#: vertex of 202.5 (its vertex 7 at the default length) is not, so the rows round it follow it. 25
#: instead of 30 took in the notches' milder 205-210 degree kinks too: the heights at 8,159 and
#: 16,298 faces then differed by 3.28% of zmax within 0.3 m of the top notch (main 2.76%, 30: 2.69%).
KINK_TURN = 30.0
#: The reach of a kink's offsets (:func:`kink_offsets`), in default target lengths
#: (:data:`~vaultgram.meshing.densities.TARGET_FRACTION` of the plan's diagonal): a length of the plan,
#: not a number of rings, since the rows pinch in a region of the plan's size at every resolution
#: (4 rings were too few at 16,298 faces of multiple_lobes, 8 too many for jagged_1 at the default).
KINK_REACH = 4.0
#: A kink's reach is at most this share of its distance to the nearest fixed vertex or pole that is
#: not itself a reflex vertex of two faces (:func:`kink_offsets`): 0.5 left draw 666 at 0.279 (main
#: 0.294), 0.3 multiple_lobes' nearest row at 0.10 target lengths at the default length; 0.4 neither.
KINK_SHARE = 0.4


def laplacian_smooth(
    vertices: np.ndarray,
    faces,
    iterations: int = DEFAULT_ITERATIONS,
    fixed: np.ndarray | None = None,
    constraints=(),
    tangential: bool = True,
    safe: bool = True,
    offsets: np.ndarray | None = None,
) -> np.ndarray:
    """Constrained uniform Laplacian smoothing.

    Parameters
    ----------
    vertices : ndarray (n, 2) or (n, 3)
    faces : list of index sequences
    iterations : int
        At least 0 (a negative number raises :class:`~vaultgram.geometry.meshes.MeshError`).
    fixed : ndarray (n,) bool, optional
        Vertices that never move (domain corners, feature points).
    constraints : sequence of SlideConstraint
        ``(vertices, polyline, closed)``: after each iteration these vertices are projected back
        onto the polyline (boundary stretches, curve features).
    tangential : bool
        If True (default), a vertex of the mesh boundary moves to the midpoint of its two boundary
        neighbours (then is projected), instead of the barycentre of all its neighbours: the full
        barycentre drags boundary vertices next to acute corners onto the corner.
    safe : bool
        If True (default), a step that would invert a face valid before it is undone for that
        face's vertices: near reflex corners the barycentre can lie outside the domain.
    offsets : ndarray like ``vertices``, optional
        Added to every barycentre at every iteration (:func:`kink_offsets`): a vertex with an offset
        moves towards the place that keeps that offset from its neighbours' barycentre.

    Returns
    -------
    ndarray
        New vertex positions (the input is not modified).

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> v, f = grid_mesh(2)
    >>> v[4, :2] += 0.3
    >>> boundary = np.ones(9, bool); boundary[4] = False
    >>> laplacian_smooth(v, f, 1, fixed=boundary)[4, :2].tolist()
    [1.0, 1.0]
    """
    x = np.array(vertices, dtype=float)
    if iterations < 0:
        raise MeshError(f"iterations must be >= 0, got {iterations}")
    if iterations == 0 or len(faces) == 0:
        return x
    w, deg = _barycentre_operator(len(x), faces, tangential)
    keep = (np.zeros(len(x), dtype=bool) if fixed is None else np.asarray(fixed, dtype=bool)) | (deg == 0)
    anchor = x[keep]
    corners = _FaceCorners(*corner_arrays(faces), len(faces))
    valid = _valid_faces(x, corners)
    tick = progress.ticker("smooth", iterations)
    for _ in range(iterations):
        tick()
        old, x = x, _laplacian_step(x, w, keep, anchor, constraints, offsets)
        if safe:
            valid = _undo_inversions(x, old, valid, corners)
    return x


def _laplacian_step(x: np.ndarray, w: MeanOperator, keep: np.ndarray, anchor: np.ndarray, constraints,
                    offsets: np.ndarray | None = None) -> np.ndarray:
    """One iteration (§3.2): every vertex to the barycentre of its neighbours (plus its offset), the
    ``keep`` vertices back at ``anchor``, the sliding ones projected back onto their polylines."""
    y = w @ x
    if offsets is not None:
        y += offsets
    y[keep] = anchor
    return slide(y, constraints)


def _barycentre_operator(n: int, faces, tangential: bool) -> tuple[MeanOperator, np.ndarray]:
    """The operator ``D^-1 A`` that moves every vertex to the barycentre of its neighbours, and
    the degrees ``D``. With ``tangential``, a vertex on the mesh boundary averages its two boundary
    neighbours only: it moves along the boundary, so it cannot be dragged onto a corner or across a
    narrow part."""
    a = adjacency(n, faces)
    if tangential:
        b = boundary_adjacency(n, faces)
        a = a.rows_of(b, b.degrees() > 0)
    return barycentre_operator(a)


class _FaceCorners(NamedTuple):
    """The corner arrays of the faces (:func:`vaultgram.geometry.meshes.corner_arrays`) and their number."""

    face_of: np.ndarray
    u: np.ndarray
    v: np.ndarray
    p: np.ndarray
    n_faces: int


def _undo_inversions(x: np.ndarray, old: np.ndarray, valid: np.ndarray, corners: _FaceCorners) -> np.ndarray:
    """Give the vertices of every face valid before the step and inverted after it their ``old``
    positions, in place (repeated, since reverting may invert a neighbour); the faces now valid."""
    now = _valid_faces(x, corners)
    for _ in range(_MAX_REVERTS):
        broken = valid & ~now
        if not broken.any():
            break
        back = distinct(corners.u[broken[corners.face_of]])
        x[back] = old[back]
        now = _valid_faces(x, corners)
    return now


def _valid_faces(x: np.ndarray, corners: _FaceCorners) -> np.ndarray:
    """Faces whose every corner turns counter-clockwise (positive cross product, above a relative
    1e-9 of the squared edge lengths). The corners are tested a cache-sized piece at a time
    (:func:`~vaultgram.geometry.arrays.pieces`): this test of every face at every iteration was
    most of the smoothing's time at 10^6 faces."""
    xy = np.ascontiguousarray(x[:, :2])
    bad = np.zeros(corners.n_faces, dtype=bool)
    for part in pieces(len(corners.u)):
        e1, e2 = corner_vectors(xy, corners.u[part], corners.v[part], corners.p[part])
        scale = e1[:, 0] * e1[:, 0] + e1[:, 1] * e1[:, 1] + (e2[:, 0] * e2[:, 0] + e2[:, 1] * e2[:, 1])
        bad[corners.face_of[part][cross_z(e1, e2) <= 1e-9 * scale]] = True
    return ~bad


def kink_offsets(x: np.ndarray, faces, boundary: np.ndarray, reach: float, stops: np.ndarray | None = None
                 ) -> np.ndarray | None:
    """The offsets (:func:`laplacian_smooth`'s ``offsets``) that keep the rows at the reflex kinks of
    the boundary from pinching (§3.2, issues 12 and 18): a free vertex at distance ``d`` from a kink
    (:func:`reflex_kinks`; the first its rings meet) keeps ``1 - d / r`` of its offset from its
    neighbours' barycentre in ``x`` (the welded Coons layout), ``r`` the kink's reach: ``reach``, or
    :data:`KINK_SHARE` of the distance to the nearest of ``stops`` (the mesh's fixed vertices and
    poles) if less, so that the offsets stay clear of the fans and corners the plain smoothing evens
    (a hole corner's rows beside a point's fan, draw 666 of the saved plans; a spike's quads, jagged_1).
    None where there is no kink.

    Why: the welded Coons patches copy a kink of the side into every row (chevrons), and the uniform
    barycentres flatten each chevron by moving its apex onto the fixed kink (the discrete corner
    singularity of a harmonic map); along multiple_lobes' notches, strings of 212-237 degree kinks, the
    nearest row came within 0.001 target lengths of a kink. With the offsets, near a kink a vertex
    moves towards the place that reproduces its Coons offsets to its neighbours (reference-shape
    smoothing), so the chevrons stay; the weight fades to plain smoothing at ``reach``. ``reach`` is
    a length, not a number of rings: the region that pinches is set by the plan, not the mesh.

    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> v, f = grid_mesh(4)
    >>> boundary = (v[:, 0] % 4 == 0) | (v[:, 1] % 4 == 0)
    >>> v[2, 1] = 0.5  # a 233 degree kink in the bottom side: vertex 7 above it keeps 0.75 of its offset
    >>> off = kink_offsets(v[:, :2], f, boundary, 2.0)
    >>> off[7].round(3).tolist(), np.flatnonzero(off.any(axis=1)).tolist()
    ([0.0, -0.094], [7])
    """
    n = len(x)
    boundary = np.asarray(boundary, dtype=bool)
    kinks = reflex_kinks(x, faces, boundary)
    if not kinks.any():
        return None
    a = adjacency(n, faces)
    if stops is not None:  # the other reflex vertices of two faces are milder kinks of the same notch
        stops = np.asarray(stops, dtype=bool) & ~reflex_kinks(x, faces, boundary, 0.0)
    reaches = _reaches(x, kinks, stops, reach)
    distance, source = _distance_from(kinks, x, a, ~boundary, reaches)
    beta = np.zeros(n)
    near = source >= 0
    beta[near] = np.clip(1.0 - distance[near] / reaches[source[near]], 0.0, 1.0)
    w, _ = _barycentre_operator(n, faces, True)
    return beta[:, None] * (x - w @ x)


def reflex_kinks(x: np.ndarray, faces, boundary: np.ndarray, turn: float | None = None) -> np.ndarray:
    """The boundary vertices of two faces whose corners there add up to more than ``180 +``
    :data:`KINK_TURN` degrees (a reflex kink of one side of a patch, or a patch corner of two faces
    turning by as much): where the rows pinch under plain smoothing (:func:`kink_offsets`).
    Hole corners and spikes of three faces or more are not kinks: their rows meet them at their
    own angle.

    >>> x = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, -0.7], [2.0, 1.0], [1.0, 1.0], [0.0, 1.0]])  # 215 degrees at 1
    >>> reflex_kinks(x, [(0, 1, 4, 5), (1, 2, 3, 4)], np.ones(6, bool)).tolist()
    [False, True, False, False, False, False]
    """
    _, u, v, p = corner_arrays(faces)
    n = len(x)
    total = np.degrees(np.bincount(u, corner_angles(x, u, v, p), n))
    turn = KINK_TURN if turn is None else turn
    return np.asarray(boundary, dtype=bool) & (np.bincount(u, None, n) == 2) & (total > 180.0 + turn)


def _reaches(x: np.ndarray, kinks: np.ndarray, stops: np.ndarray | None, reach: float) -> np.ndarray:
    """Per vertex, the reach of its offsets if it is a kink: ``reach``, or less, :data:`KINK_SHARE` of
    its distance to the nearest of ``stops`` (fixed vertices and poles; the kinks and milder reflex
    vertices of two faces are not stops). Kinks and stops are points of the plan (their number does
    not grow with the mesh's), compared a block of kinks at a time."""
    out = np.full(len(x), float(reach))
    others = x[np.flatnonzero(stops), :2] if stops is not None else np.zeros((0, 2))
    if len(others) == 0:
        return out
    at = np.flatnonzero(kinks)
    for part in pieces(len(at), max(1, PIECE // len(others))):
        block = at[part]
        gap = np.linalg.norm(x[block, None, :2] - others[None], axis=2).min(axis=1)
        out[block] = np.minimum(reach, KINK_SHARE * gap)
    return out


def _distance_from(sources: np.ndarray, x: np.ndarray, a: Adjacency, inside: np.ndarray, reach: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Each vertex's distance from the source its rings meet first (a breadth-first search from all
    ``sources`` at once over the ``inside`` vertices, ring by ring, each ring only the neighbours of
    the last one); ``inf`` where no source lies within ``reach`` that way. The work is the edges of
    the vertices within reach, not the mesh's."""
    n = len(x)
    starts = np.searchsorted(a.rows, np.arange(n + 1))
    source = np.full(n, -1)
    source[sources] = np.flatnonzero(sources)
    distance = np.full(n, np.inf)
    distance[sources] = 0.0
    front = np.flatnonzero(sources)
    while len(front):
        counts = starts[front + 1] - starts[front]
        first = np.repeat(starts[front] - np.cumsum(counts) + counts, counts)
        near = a.cols[first + np.arange(len(first))]
        came = np.repeat(source[front], counts)
        new = inside[near] & (source[near] < 0)
        near, pick = np.unique(near[new], return_index=True)
        came = came[new][pick]
        d = np.linalg.norm(x[near, :2] - x[came, :2], axis=1)
        within = d < reach[came]
        front = near[within]
        source[front], distance[front] = came[within], d[within]
    source[sources] = -1
    return distance, source
