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

from vaultgram.errors import FormFindingError
from vaultgram.geometry.meshes import boundary_loops


def outer_loop(vertices: np.ndarray, faces: Sequence[Sequence[int]]) -> list[int]:
    """The boundary loop enclosing the largest area (the outer boundary of a mesh with holes)."""
    loops = boundary_loops(faces)
    if not loops:
        raise FormFindingError("the mesh has no boundary, so nothing can be supported by default")
    xy = np.asarray(vertices)[:, :2]
    return max(loops, key=lambda loop: shapely.Polygon(xy[loop]).area if len(loop) >= 3 else 0.0)


def support_vertices(vertices, faces, spec=None, domain=None) -> np.ndarray:
    """Sorted indices of the supported vertices for a support specification (see the module docstring).

    ``domain`` is needed to resolve ``rings`` (which mesh boundary loop is which ring). Boundary
    vertices count as lying on a ring or polyline when within 1e-3 of the mesh's bounding-box diagonal.
    """
    xy = np.asarray(vertices, dtype=float)[:, :2]
    if spec is None:
        return np.array(sorted(outer_loop(xy, faces)), dtype=np.int64)
    if not isinstance(spec, dict) or len(set(spec) - {"comment"}) != 1:
        raise FormFindingError('supports: expected one of {"rings": ...}, {"polylines": ...} or {"vertices": ...}')
    tol = 1e-3 * float(np.hypot(*(xy.max(axis=0) - xy.min(axis=0))))
    boundary = np.array(sorted({v for loop in boundary_loops(faces) for v in loop}), dtype=np.int64)
    if "vertices" in spec:
        idx = np.asarray(spec["vertices"], dtype=np.int64).ravel()
        bad = idx[(idx < 0) | (idx >= len(xy))]
        if len(bad):
            raise FormFindingError(f"supports.vertices: vertex {int(bad[0])} does not exist ({len(xy)} vertices)")
        chosen = np.unique(idx)
    elif "polylines" in spec:
        lines = shapely.MultiLineString([np.asarray(p, dtype=float)[:, :2] for p in spec["polylines"]])
        chosen = boundary[shapely.distance(shapely.points(xy[boundary]), lines) <= tol]
    elif "rings" in spec:
        if domain is None:
            raise FormFindingError("supports.rings needs the domain (rings are named by the domain file)")
        rings = {"outer": domain.outer, **{k: h for k, h in enumerate(domain.holes)}}
        missing = [r for r in spec["rings"] if r not in rings]
        if missing:
            raise FormFindingError(f"supports.rings: no ring {missing[0]!r} (the domain has {len(domain.holes)} holes)")
        lines = shapely.MultiLineString([np.vstack([rings[r], rings[r][:1]]) for r in spec["rings"]])
        chosen = boundary[shapely.distance(shapely.points(xy[boundary]), lines) <= tol]
    else:
        raise FormFindingError(f"supports: unknown key {sorted(spec)[0]!r}")
    if len(chosen) == 0:
        raise FormFindingError(f"supports {spec}: no mesh vertex lies on them, so nothing bears thrust")
    return chosen
