"""Which mesh vertices bear thrust (paper §5: "edges with both end points bearing thrust").

A support specification comes from the domain file's ``supports`` key (documented in
``domain.schema.json``), from a ``--supports`` file, or from a mesh file's own ``supports`` list:

* none: the whole outer boundary is supported and holes are open (the usual vault on a perimeter
  wall);
* ``{"rings": ["outer", 0, 2]}``: every vertex on those rings ("outer" or hole indices);
* ``{"polylines": [[[x, y], ...], ...]}``: every boundary vertex lying on one of these polylines;
* ``{"vertices": [i, j, ...]}``: mesh vertex indices.

:func:`support_vertices` resolves any of them to sorted vertex indices of the mesh.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
import shapely

from vaultgram.errors import FormFindingError, VaultgramError
from vaultgram.geometry.frames import NO_ORIGIN, to_local
from vaultgram.geometry.meshes import boundary_halfedges, loops_of
from vaultgram.geometry.polygons import bbox_diagonal, signed_area
from vaultgram.io import strict


def outer_loop(vertices: np.ndarray, faces: Sequence[Sequence[int]]) -> list[int]:
    """The boundary loop enclosing the largest area (the outer boundary of a mesh with holes).

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh, remove_faces
    >>> v, f, _ = remove_faces(*grid_mesh(3), drop=[4])          # a 3 x 3 grid without its centre
    >>> len(outer_loop(v, f))
    12
    """
    return largest_loop(vertices, _boundary_loops(faces))


def largest_loop(vertices: np.ndarray, loops: list[list[int]]) -> list[int]:
    """Of a mesh's boundary ``loops``, the one enclosing the largest area: :func:`outer_loop` for a
    caller that has the loops already (the form diagram walks them from its own sorted sides)."""
    if not loops:
        raise FormFindingError("the mesh has no boundary, so nothing can be supported by default")
    xy = np.asarray(vertices, dtype=float)[:, :2]
    return max(loops, key=lambda loop: abs(signed_area(xy[loop])) if len(loop) >= 3 else 0.0)


def support_vertices(vertices, faces, spec=None, domain=None, origin=NO_ORIGIN) -> np.ndarray:
    """Sorted indices of the supported vertices for a support specification (see the module docstring).

    ``domain`` is needed to resolve ``rings`` (which mesh boundary loop is which ring). Boundary
    vertices count as lying on a ring or polyline when within 1e-3 of the mesh's bounding-box diagonal.
    The polylines are in the plan's coordinates, the vertices (and the domain's rings) in the frame
    starting at ``origin`` (:mod:`vaultgram.geometry.frames`).

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> v, f = grid_mesh(2)
    >>> support_vertices(v, f).tolist(), support_vertices(v, f, {"polylines": [[[0, 0], [2, 0]]]}).tolist()
    ([0, 1, 2, 3, 5, 6, 7, 8], [0, 1, 2])
    """
    xy = np.asarray(vertices, dtype=float)[:, :2]
    if spec is None:
        return np.array(sorted(outer_loop(xy, faces)), dtype=np.int64)
    if not isinstance(spec, dict) or len(set(spec) - {"comment"}) != 1:
        raise FormFindingError('supports: expected one of {"rings": ...}, {"polylines": ...} or {"vertices": ...}')
    try:
        chosen = _chosen(xy, faces, spec, domain, origin)
    except FormFindingError:
        raise
    except VaultgramError as exc:  # a type or range error of the specification
        raise FormFindingError(str(exc)) from None
    if len(chosen) == 0:
        raise FormFindingError(f"supports {spec}: no mesh vertex lies on them, so nothing bears thrust")
    return chosen


def _chosen(xy: np.ndarray, faces, spec: dict, domain, origin) -> np.ndarray:
    """The vertices a specification of one key names (none found is not an error here)."""
    if "vertices" in spec:
        chosen = _listed_vertices(spec["vertices"], len(xy))
    elif "polylines" in spec:
        chosen = _boundary_on_lines(xy, faces, [to_local(p, origin) for p in _polylines(spec["polylines"])])
    elif "rings" in spec:
        chosen = _boundary_on_lines(xy, faces, _ring_lines(strict.json_list(spec["rings"], "supports.rings"), domain))
    else:
        raise FormFindingError(f"supports: unknown key {sorted(spec)[0]!r}")
    return chosen


def _listed_vertices(vertices, n: int) -> np.ndarray:
    """``supports.vertices``: distinct, existing mesh vertex indices (integers, strictly)."""
    return np.unique(strict.indices(vertices, n, "supports.vertices"))


def _polylines(value) -> list[np.ndarray]:
    """``supports.polylines``: a list of polylines of at least two [x, y] (or [x, y, z]) points."""
    lines = []
    for k, p in enumerate(strict.json_list(value, "supports.polylines")):
        line = strict.points(p, f"supports.polylines[{k}]")
        if len(line) < 2:
            raise FormFindingError(f"supports.polylines[{k}]: expected at least 2 points, got {len(line)}")
        lines.append(line[:, :2])
    return lines


def _ring_lines(names, domain) -> list[np.ndarray]:
    """``supports.rings``: the domain's rings ("outer" or hole indices) as closed polylines."""
    if domain is None:
        raise FormFindingError("supports.rings needs the domain (rings are named by the domain file)")
    rings = {"outer": domain.outer, **{k: h for k, h in enumerate(domain.holes)}}
    missing = [r for r in names if r not in rings]
    if missing:
        raise FormFindingError(f"supports.rings: no ring {missing[0]!r} (the domain has {len(domain.holes)} holes)")
    return [np.vstack([rings[r], rings[r][:1]]) for r in names]


def _boundary_on_lines(xy: np.ndarray, faces, lines: list[np.ndarray]) -> np.ndarray:
    """The boundary vertices within 1e-3 of the bounding-box diagonal of one of the polylines."""
    tol = 1e-3 * bbox_diagonal(xy)
    boundary = np.array(sorted({v for loop in _boundary_loops(faces) for v in loop}), dtype=np.int64)
    near = shapely.distance(shapely.points(xy[boundary]), shapely.MultiLineString(lines)) <= tol
    return boundary[near]


def _boundary_loops(faces) -> list[list[int]]:
    """The mesh's boundary loops; a pinched boundary vertex is a :class:`FormFindingError`."""
    return manifold_loops(*boundary_halfedges(faces))


def manifold_loops(starts: np.ndarray, ends: np.ndarray) -> list[list[int]]:
    """The boundary loops walked along the boundary halfedges ``starts -> ends``
    (:func:`~vaultgram.geometry.meshes.loops_of`); a pinched boundary vertex is a :class:`FormFindingError`."""
    try:
        return loops_of(starts, ends)
    except ValueError as exc:
        raise FormFindingError(f"the mesh boundary is not manifold: {exc}; split the vertex or support it") from None
