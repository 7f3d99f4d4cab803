"""From a domain to a smooth quad mesh (paper §3): the pipeline, its quality metrics and its files.

:func:`mesh_domain` runs the stages in order::

    Domain -> decompose (§3.1) -> edge_groups + group_counts (§3.2) -> weld (discrete Coons patches,
    §3.2) -> laplacian_smooth (§3.2) -> untangle -> check_not_folded -> QuadMesh

A mesh that still has inverted faces after smoothing and untangling is a :class:`MeshFoldError`
saying where (``allow_folds`` returns it anyway).

:func:`mesh_stats` measures what the paper asks of the result: quads only (triangles only at poles),
no boundary singularity, interior singularities where the decomposition has them, no inverted face,
and a boundary that follows the domain's. :func:`write_mesh` writes ``mesh.json`` and ``mesh.obj``
atomically; :func:`read_mesh` reads ``mesh.json`` back.
"""

from __future__ import annotations

import dataclasses
import math
import time
from pathlib import Path

import numpy as np

from vaultgram.topology.decomposition import Decomposition, decompose
from vaultgram.topology.functions import interior_angle
from vaultgram.domain.model import Domain
from vaultgram.meshing.edge_groups import DensitySpec, edge_groups, group_counts
from vaultgram.errors import MeshFoldError, VaultgramError
from vaultgram.io.files import read_json, write_json
from vaultgram.geometry.meshes import boundary_loops, corner_arrays, write_obj
from vaultgram.meshing.smoothing import DEFAULT_ITERATIONS, laplacian_smooth, untangle
from vaultgram.meshing.weld import QuadMesh, weld

__all__ = [
    "mesh_domain",
    "check_feature_spacing",
    "polyline_hausdorff",
    "mesh_stats",
    "regular_boundary_faces",
    "write_mesh",
    "read_mesh",
    "mesh_to_json",
    "mesh_from_json",
    "format_stats",
]

#: Tolerance band (degrees) around 135 and 225 degrees inside which a boundary corner is regular
#: with either neighbouring number of quads (a 135 degree corner takes 1 quad or 2 equally well).
CORNER_TIE_BAND = 10.0

#: Turning angle (degrees) beyond which a ring vertex is a corner (as in :func:`vaultgram.topology.discretise.discretise`).
CORNER_ANGLE = 30.0


def mesh_domain(
    domain: Domain,
    spacing: float = 0.02,
    target_length: float | None = None,
    smooth: int = DEFAULT_ITERATIONS,
    densities: DensitySpec | None = None,
    rules_dir=None,
    allow_folds: bool = False,
) -> QuadMesh:
    """Topology and geometry of §3: a smooth quad mesh of ``domain``.

    Parameters
    ----------
    domain : Domain
    spacing : float
        Relative discretisation spacing of the decomposition (§3.1).
    target_length : float, optional
        Global target edge length in the domain's units; default a fraction
        (:data:`vaultgram.meshing.edge_groups.TARGET_FRACTION`) of the bounding-box diagonal. Overrides the
        density file's.
    smooth : int
        Laplacian smoothing iterations.
    densities : DensitySpec, optional
        Local density control (:func:`vaultgram.meshing.edge_groups.load_densities`).
    allow_folds : bool
        Return a mesh that still has inverted faces after smoothing instead of raising.

    Returns
    -------
    QuadMesh
        ``info`` holds the time per stage (seconds), the number of patches, triangles and edge groups.

    Raises
    ------
    VaultgramError
        From any stage (invalid domain, a patch that is not 3- or 4-sided, bad densities);
        :class:`MeshFoldError` when the smoothed mesh has inverted faces (unless ``allow_folds``).
    """
    check_feature_spacing(domain, spacing)
    t = time.perf_counter()
    dec = decompose(domain, spacing, rules_dir)
    return mesh_decomposition(dec, target_length, smooth, densities, {"decompose": time.perf_counter() - t},
                              allow_folds)


def mesh_decomposition(
    dec: Decomposition,
    target_length: float | None = None,
    smooth: int = DEFAULT_ITERATIONS,
    densities: DensitySpec | None = None,
    seconds: dict | None = None,
    allow_folds: bool = False,
) -> QuadMesh:
    """Geometry of §3.2 for a decomposition: edge groups, Coons patches, welding, smoothing.

    ``seconds`` (time already spent per stage) is extended with this function's stages in ``info``.
    A smoothed mesh with inverted faces raises :class:`MeshFoldError` unless ``allow_folds``; the raw
    Coons patches (``smooth=0``) are returned as they are.
    """
    if smooth < 0:
        raise VaultgramError(f"smoothing iterations must be >= 0, got {smooth}")
    seconds = dict(seconds or {})
    domain = dec.disc.domain
    t = time.perf_counter()
    layout = edge_groups(dec)
    counts = group_counts(layout, densities, target_length)
    seconds["groups"] = time.perf_counter() - t
    t = time.perf_counter()
    mesh = weld(layout, counts)
    seconds["coons_weld"] = time.perf_counter() - t
    seconds.update({f"weld.{k}": v for k, v in mesh.info.get("seconds", {}).items()})
    t = time.perf_counter()
    x = laplacian_smooth(mesh.vertices, mesh.faces, smooth, mesh.fixed, mesh.constraints)
    seconds["smooth"] = time.perf_counter() - t
    t = time.perf_counter()
    if smooth > 0:
        x = untangle(x, mesh.faces, mesh.fixed, mesh.constraints)
    seconds["untangle"] = time.perf_counter() - t
    info = {
        "domain": domain.name,
        "spacing": dec.disc.spacing,
        "diagonal": domain.diagonal,
        "patches": len(layout.patterns),
        "triangle_patches": sum(p.pole is not None for p in layout.patterns),
        "edge_groups": layout.n_groups,
        "smooth": smooth,
        "seconds": seconds,
    }
    mesh = dataclasses.replace(mesh, vertices=x, info=info)
    if smooth > 0 and not allow_folds:
        check_not_folded(mesh, dec)
    return mesh


# --------------------------------------------------------------------------------------------
# Features against the spacing
# --------------------------------------------------------------------------------------------

#: Features (§4) must be at least this many discretisation spacings ``h = spacing * diagonal`` from
#: the boundary and from each other: closer, the Delaunay triangulation has no room for the skeleton
#: between them and the patches in the gap degenerate.
FEATURE_CLEARANCE = 1.0


def check_feature_spacing(domain: Domain, spacing: float, clearance: float = FEATURE_CLEARANCE) -> None:
    """Raise a :class:`DomainError` if a feature is too close to the boundary or to another feature
    for the discretisation spacing (§3.1, §4).

    Inner point features and curve features must be at least ``clearance * h`` (``h = spacing *
    diagonal``) from the domain's boundary and from each other. What touches on purpose is not
    measured: boundary point features; a curve's end on the boundary (the curve is measured outside a
    disc of radius ``2 h`` around it, so that a curve leaving the boundary at 30 degrees or more
    passes); a point feature on a curve; curves sharing an end point (likewise, outside ``2 h``).

    Raises
    ------
    DomainError
        Naming the features, where they are closest, the distance and the spacing.
    """
    import shapely

    from vaultgram.errors import DomainError

    diag = domain.diagonal
    h = spacing * diag
    tol = 1e-9 * diag
    need = clearance * h
    boundary = domain.polygon().boundary
    items = []  # (name, geometry measured against others)
    for i, p in enumerate(np.asarray(domain.points, dtype=float).reshape(-1, 2)):
        if shapely.distance(shapely.Point(p), boundary) > tol:
            items.append((f"point feature {i} at {_pt(p)}", shapely.Point(p), ()))
    for c, curve in enumerate(domain.curves):
        curve = np.asarray(curve, dtype=float)
        ends = [e for e in (curve[0], curve[-1]) if shapely.distance(shapely.Point(e), boundary) <= tol]
        items.append((f"curve feature {c}", shapely.LineString(curve), [shapely.Point(e) for e in ends]))
    ends_all = [e for _, _, es in items for e in es]

    def trimmed(geom, around):
        if not around:
            return geom
        return shapely.difference(geom, shapely.union_all([e.buffer(2 * h) for e in around]))

    def check(name, geom, other_name, other):
        if geom.is_empty or other.is_empty:
            return
        d = shapely.distance(geom, other)
        if d < need:
            a, b = shapely.get_coordinates(shapely.shortest_line(geom, other))
            raise DomainError(
                f"{name} is {d:.4g} from {other_name} (closest at {_pt(a)} and {_pt(b)}), less than the "
                f"spacing {need:.4g} (spacing {spacing:g} of the diagonal {diag:.4g}): move it, or mesh with "
                f"a spacing below {d / (clearance * diag):.3g}"
            )

    for name, geom, ends in items:
        check(name, trimmed(geom, ends), "the boundary", boundary)
    for k, (name, geom, ends) in enumerate(items):
        for name2, geom2, ends2 in items[k + 1:]:
            if isinstance(geom, shapely.Point) and isinstance(geom2, shapely.LineString) \
                    and shapely.distance(geom, geom2) <= tol:
                continue  # a point feature on a curve is a point of the curve
            if isinstance(geom2, shapely.Point) and isinstance(geom, shapely.LineString) \
                    and shapely.distance(geom2, geom) <= tol:
                continue
            shared = [e for e in ends_all if shapely.distance(e, geom) <= tol and shapely.distance(e, geom2) <= tol]
            if isinstance(geom, shapely.LineString) and isinstance(geom2, shapely.LineString):
                shared += [shapely.Point(q) for q in shapely.get_coordinates(shapely.intersection(geom, geom2))]
            check(name2, trimmed(geom2, shared), name, trimmed(geom, shared))


def _pt(p) -> str:
    return f"({p[0]:.6g}, {p[1]:.6g})"


# --------------------------------------------------------------------------------------------
# Quality
# --------------------------------------------------------------------------------------------


def regular_boundary_faces(
    turning: np.ndarray, band: float = CORNER_TIE_BAND, corner_angle: float = CORNER_ANGLE
) -> tuple[np.ndarray, np.ndarray]:
    """Regular number of faces at boundary vertices, from the domain's turning angle (degrees).

    Two readings of "regular" are accepted, and both are reported as regular:

    * the acceptance's: valence 2 (1 face) at a convex corner, 3 (2 faces) on a smooth stretch,
      4 (3 faces) at a reflex corner, a corner being a ring vertex turning by more than
      ``corner_angle`` (the discretisation's corner threshold, §3.1);
    * the corner angle's: the interior angle ``180 - turning`` divided by 90 and rounded, at least
      1, and within ``band`` degrees of a tie (135, 225, ...) both neighbours. This one is stricter
      on smooth stretches and at sharp corners (a 300 degree corner is regular with 3 faces only)
      and adds flat corners (a 215 degree corner with 2 faces, a 145 degree one with 2).

    Returns
    -------
    low, high : ndarray int
        Lowest and highest regular number of faces.
    """
    turning = np.asarray(turning, dtype=float)
    q = (180.0 - turning) / 90.0
    base = np.maximum(1, np.floor(q + 0.5)).astype(np.int64)
    frac = q - np.floor(q)
    tie = np.abs(frac - 0.5) * 90.0 <= band
    low = np.where(tie, np.maximum(1, np.floor(q)), base).astype(np.int64)
    high = np.where(tie, np.maximum(1, np.floor(q) + 1), base).astype(np.int64)
    kind = np.where(turning > corner_angle, 1, np.where(turning < -corner_angle, 3, 2))
    return np.minimum(low, kind), np.maximum(high, kind)


def _face_array(faces) -> np.ndarray:
    """Faces as an (f, 4) array, triangles padded with -1."""
    out = np.full((len(faces), 4), -1, dtype=np.int64)
    lens = np.fromiter((len(f) for f in faces), dtype=np.int64, count=len(faces))
    if len(faces) and (lens.max() > 4 or lens.min() < 3):
        raise VaultgramError("faces must be triangles or quads")
    q = lens == 4
    if q.any():
        out[q] = np.array([f for f in faces if len(f) == 4], dtype=np.int64)
    if (~q).any():
        out[~q, :3] = np.array([f for f in faces if len(f) == 3], dtype=np.int64)
    return out


def _turning_from_domain(x: np.ndarray, domain: Domain) -> np.ndarray:
    """Domain turning angle at each point lying on a domain ring vertex (0 elsewhere)."""
    from scipy.spatial import cKDTree

    from vaultgram.topology.discretise import turning_angles

    pts = np.vstack(domain.rings)
    ang = np.concatenate([turning_angles(r) for r in domain.rings])
    d, k = cKDTree(pts).query(x)
    return np.where(d <= 1e-7 * domain.diagonal, ang[k], 0.0)


def _boundary_distance(x: np.ndarray, loops, domain: Domain) -> float:
    """Symmetric distance between the mesh boundary loops and the domain's rings."""
    import shapely

    rings = shapely.MultiLineString([np.vstack([r, r[:1]]) for r in domain.rings])
    mesh_lines = shapely.MultiLineString([np.vstack([x[lp], x[lp[:1]]]) for lp in loops]) if loops else None
    mids = np.vstack([0.5 * (x[lp] + x[np.roll(lp, -1)]) for lp in loops]) if loops else np.zeros((0, 2))
    probe = np.vstack([x[np.concatenate(loops)], mids]) if loops else np.zeros((0, 2))
    d1 = shapely.distance(shapely.points(probe), rings).max() if len(probe) else 0.0
    dom_pts = np.vstack([*domain.rings, *[0.5 * (r + np.roll(r, -1, axis=0)) for r in domain.rings]])
    d2 = shapely.distance(shapely.points(dom_pts), mesh_lines).max() if mesh_lines is not None else math.inf
    return float(max(d1, d2))


def face_scaled_jacobians(x: np.ndarray, faces) -> np.ndarray:
    """Per face, the smallest scaled Jacobian of its corners (the sine of the corner angle for a
    quad, scaled so that an equilateral triangle has 1); <= 0 for an inverted or degenerate face."""
    fa = _face_array(faces)
    face_of, u, v, w = corner_arrays(faces)
    x = np.asarray(x, dtype=float)[:, :2]
    e1, e2 = x[v] - x[u], x[w] - x[u]
    cross = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    norm = np.hypot(*e1.T) * np.hypot(*e2.T)
    sj = np.where(norm > 0, cross / np.where(norm > 0, norm, 1.0), -1.0)
    sj = np.where(fa[face_of, 3] < 0, np.minimum(sj * 2.0 / math.sqrt(3.0), 1.0), sj)
    face_sj = np.full(len(faces), np.inf)
    np.minimum.at(face_sj, face_of, sj)
    return face_sj


def check_not_folded(mesh: QuadMesh, decomposition: Decomposition) -> None:
    """Raise :class:`MeshFoldError` naming where the mesh folds, if any face is inverted."""
    face_sj = face_scaled_jacobians(mesh.vertices, mesh.faces)
    bad = np.flatnonzero(face_sj <= 0)
    if not len(bad):
        return
    first = int(bad[np.argmin(face_sj[bad])])
    where = mesh.vertices[list(mesh.faces[first]), :2].mean(axis=0)
    patch = decomposition.patches[int(mesh.face_patch[first])]
    corners = ", ".join(_pt(decomposition.graph.get(c, "pos")) for c in patch.corners)
    angles = [interior_angle(patch.sides[k - 1][-2], patch.sides[k][0], patch.sides[k][1])
              for k in range(patch.n_sides)]
    k = int(np.argmax(angles))
    if angles[k] > 180:
        why = (f"the patch turns by {angles[k]:.0f} degrees at its corner {_pt(patch.sides[k][0])}, which no "
               "quad mesh of it can do at any density: move the feature or curve there")
    else:
        why = "features, curves or boundaries this close together need a smaller --target-length or more room"
    raise MeshFoldError(
        f"the mesh folds: {len(bad)} inverted face(s), the worst near {_pt(where)} in the patch with corners "
        f"{corners}; {why} (vaultgram mesh --allow-folds writes the mesh anyway)"
    )


def mesh_stats(mesh: QuadMesh, domain: Domain | None = None) -> dict:
    """Quality metrics of a quad mesh (the acceptance properties of §3.2).

    Parameters
    ----------
    mesh : QuadMesh
    domain : Domain, optional
        Gives the corner angles of boundary vertices (else the mesh's ``turning`` labels) and the
        distance of the mesh boundary from the domain boundary.

    Returns
    -------
    dict
        ``vertices, faces, quads, triangles``; ``interior_singular`` (interior vertices of valence
        other than 4) and ``boundary_singular`` (boundary vertices whose number of faces is not the
        regular one for their corner angle, see :func:`regular_boundary_faces`; feature points, singular
        by design in §4.1, are counted apart in ``boundary_feature_singular``), with the vertex lists;
        ``min_scaled_jacobian, mean_scaled_jacobian, inverted_faces``; ``min_angle, max_angle``
        (degrees); ``manifold, oriented, boundary_loops``; ``boundary_distance`` and
        ``boundary_distance_relative`` (to the domain's bounding-box diagonal) when ``domain`` is given.
    """
    x = np.asarray(mesh.vertices, dtype=float)[:, :2]
    faces = mesh.faces
    nv = len(x)
    fa = _face_array(faces)
    is_tri = fa[:, 3] < 0
    face_of, u, v, w = corner_arrays(faces)  # corner: vertex u, next v, previous w

    # topology
    key = u * nv + v
    uniq, mult = np.unique(key, return_counts=True)
    oriented = bool((mult == 1).all())
    und = np.minimum(u, v) * nv + np.maximum(u, v)
    _, und_mult = np.unique(und, return_counts=True)
    manifold = bool((und_mult <= 2).all())
    twin = np.isin(v * nv + u, uniq)
    try:
        loops = [np.asarray(lp) for lp in boundary_loops(faces)]
    except ValueError:
        loops, manifold = [], False
    on_boundary = np.zeros(nv, dtype=bool)
    on_boundary[u[~twin]] = True

    # valence: number of distinct edges at a vertex; faces per vertex
    edges = np.unique(und)
    valence = np.bincount(edges // nv, minlength=nv) + np.bincount(edges % nv, minlength=nv)
    nfaces = np.bincount(u, minlength=nv)
    used = nfaces > 0
    interior_sing = np.flatnonzero(used & ~on_boundary & (valence != 4))
    if domain is not None:
        turning = _turning_from_domain(x, domain)
    else:
        turning = np.asarray(mesh.turning, dtype=float)
    low, high = regular_boundary_faces(turning)
    irregular = on_boundary & ((nfaces < low) | (nfaces > high))
    # a boundary feature point is a pole on purpose (§4.1: "high valency vertices"): counted apart
    feature = np.asarray(mesh.feature, dtype=bool) if len(mesh.feature) == nv else np.zeros(nv, dtype=bool)
    boundary_sing = np.flatnonzero(irregular & ~feature)
    feature_sing = np.flatnonzero(irregular & feature)

    # shape
    e1, e2 = x[v] - x[u], x[w] - x[u]
    cross = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    face_sj = face_scaled_jacobians(x, faces)
    angle = np.degrees(np.arctan2(cross, (e1 * e2).sum(1)))
    angle = np.where(angle < 0, 360.0 + angle, angle)

    stats = {
        "vertices": int(used.sum()),
        "faces": len(faces),
        "quads": int((~is_tri).sum()),
        "triangles": int(is_tri.sum()),
        "interior_singular": len(interior_sing),
        "interior_singular_vertices": interior_sing.tolist(),
        "interior_singular_valences": valence[interior_sing].tolist(),
        "boundary_singular": len(boundary_sing),
        "boundary_singular_vertices": boundary_sing.tolist(),
        "boundary_feature_singular": len(feature_sing),
        "min_scaled_jacobian": float(face_sj.min()) if len(faces) else None,
        "mean_scaled_jacobian": float(face_sj.mean()) if len(faces) else None,
        "inverted_faces": int((face_sj <= 0).sum()),
        "min_angle": float(angle.min()) if len(angle) else None,
        "max_angle": float(angle.max()) if len(angle) else None,
        "manifold": manifold,
        "oriented": oriented,
        "boundary_loops": len(loops),
    }
    if domain is not None:
        d = _boundary_distance(x, loops, domain)
        stats["boundary_distance"] = d
        stats["boundary_distance_relative"] = d / domain.diagonal
    stats.update(_feature_stats(mesh, x, valence, nfaces, on_boundary, low, high, und, nv, domain))
    return stats


def _feature_stats(mesh: QuadMesh, x, valence, nfaces, on_boundary, low, high, und, nv, domain) -> dict:
    """The §4 checks: point features and curve extremities are poles (a valence other than 4 inside,
    a number of faces other than the regular one on the boundary); curve features are chains of mesh
    edges (Hausdorff distance to the curve) without singular vertices inside."""
    n = len(x)
    curve, ext = mesh.curve_labels()
    feature = np.asarray(mesh.feature, dtype=bool) if len(mesh.feature) == n else np.zeros(n, dtype=bool)
    irregular = np.where(on_boundary, (nfaces < low) | (nfaces > high), valence != 4)
    fp = np.flatnonzero(feature)
    ex = np.flatnonzero(ext)
    diag = domain.diagonal if domain is not None else _diagonal(x)
    lines = [np.asarray(c, dtype=float) for c in domain.curves] if domain is not None else list(mesh.curve_lines)
    # vertices inside a curve: on a curve, not its extremity, not on the boundary, not at a bend of
    # the curve sharper than the corner angle (the curve cuts the domain: a corner on either side)
    bend = np.zeros(n, dtype=bool)
    if lines:
        from scipy.spatial import cKDTree

        from vaultgram.topology.discretise import turning_angles

        sharp = [ln[1:-1][np.abs(turning_angles(ln, closed=False)[1:-1]) > CORNER_ANGLE] for ln in lines if len(ln) > 2]
        sharp = np.vstack(sharp) if sharp else np.zeros((0, 2))
        if len(sharp):
            d, _ = cKDTree(sharp).query(x)
            bend = (d <= 1e-9 * diag) & (curve >= 0)
    inside = np.flatnonzero((curve >= 0) & ~ext & ~on_boundary & ~bend)
    sing_inside = inside[valence[inside] != 4]
    edges = set(und.tolist())
    hausdorff, continuous = [], True
    for c, chain in enumerate(mesh.curves):
        chain = np.asarray(chain, dtype=np.int64)
        if len(chain) < 2 or c >= len(lines):
            hausdorff.append(math.inf)
            continuous = False
            continue
        a, b = np.minimum(chain[:-1], chain[1:]), np.maximum(chain[:-1], chain[1:])
        continuous &= all(int(k) in edges for k in a * nv + b)
        hausdorff.append(polyline_hausdorff(x[chain], lines[c]))
    return {
        "feature_points": len(fp),
        "feature_points_pole": int(irregular[fp].sum()),
        "feature_point_valences": valence[fp].tolist(),
        "curve_extremities": len(ex),
        "curve_extremities_pole": int(irregular[ex].sum()),
        "curve_interior_singular": len(sing_inside),
        "curve_interior_singular_vertices": sing_inside.tolist(),
        "curve_bends": int(bend.sum()),
        "curve_chains_continuous": bool(continuous),
        "curve_hausdorff": [float(h) for h in hausdorff],
        "curve_hausdorff_relative": float(max(hausdorff) / diag) if hausdorff else 0.0,
    }


def _diagonal(x: np.ndarray) -> float:
    return float(np.hypot(*(x.max(axis=0) - x.min(axis=0)))) if len(x) else 1.0


def polyline_hausdorff(a: np.ndarray, b: np.ndarray, samples: int = 8) -> float:
    """Hausdorff distance between two polylines: the larger of the two directed distances, each the
    largest distance from a point of one (its vertices and ``samples - 1`` points inside each segment)
    to the other polyline."""
    import shapely

    def dense(p):
        p = np.asarray(p, dtype=float)[:, :2]
        t = np.linspace(0.0, 1.0, samples, endpoint=False)[None, :, None]
        return np.vstack([(p[:-1, None, :] * (1 - t) + p[1:, None, :] * t).reshape(-1, 2), p[-1:]])

    la, lb = shapely.LineString(np.asarray(a)[:, :2]), shapely.LineString(np.asarray(b)[:, :2])
    d1 = shapely.distance(shapely.points(dense(a)), lb).max()
    d2 = shapely.distance(shapely.points(dense(b)), la).max()
    return float(max(d1, d2))


def format_stats(stats: dict) -> str:
    """A two-column text table of :func:`mesh_stats` (vertex lists summarised by their length)."""
    rows = []
    for k, val in stats.items():
        if isinstance(val, list):
            continue
        if isinstance(val, float):
            val = f"{val:.6g}"
        rows.append((k, str(val)))
    width = max(len(k) for k, _ in rows)
    return "\n".join(f"{k:<{width}}  {val}" for k, val in rows)


# --------------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------------


def mesh_to_json(mesh: QuadMesh) -> dict:
    """``{"vertices": [[x, y, z], ...], "faces": [...], "labels": {...}, "turning": [[v, deg], ...],
    "face_patch": [...], "edge_groups": [...], "info": {...}}``."""
    x = np.asarray(mesh.vertices, dtype=float)
    if x.shape[1] == 2:
        x = np.column_stack([x, np.zeros(len(x))])
    tv = np.flatnonzero(mesh.turning != 0)
    return {
        "vertices": x.tolist(),
        "faces": [list(f) for f in mesh.faces],
        "labels": mesh.labels_json(),
        "ring": mesh.ring.tolist(),
        "turning": [[int(k), float(mesh.turning[k])] for k in tv],
        "node": mesh.node.tolist(),
        "face_patch": mesh.face_patch.tolist(),
        "curves": [{"vertices": np.asarray(c).tolist(), "polyline": np.asarray(p).tolist()}
                   for c, p in zip(mesh.curves, mesh.curve_lines)],
        "edge_groups": list(mesh.groups),
        "info": {k: v for k, v in mesh.info.items() if k != "seconds"},  # timings vary run to run
    }


def mesh_from_json(data: dict, where: str = "mesh") -> QuadMesh:
    """A :class:`QuadMesh` from :func:`mesh_to_json` output (or any ``{"vertices", "faces"}`` dict)."""
    try:
        x = np.asarray(data["vertices"], dtype=float)
        faces = [tuple(int(i) for i in f) for f in data["faces"]]
    except (KeyError, TypeError, ValueError) as exc:
        raise VaultgramError(f"{where}: not a mesh (needs 'vertices' and 'faces'): {exc}") from None
    if x.ndim != 2 or x.shape[1] not in (2, 3):
        raise VaultgramError(f"{where}: vertices must be [x, y] or [x, y, z] points")
    n = len(x)
    if any(len(f) not in (3, 4) or min(f) < 0 or max(f) >= n for f in faces):
        raise VaultgramError(f"{where}: faces must be triangles or quads of valid vertex indices")
    labels = data.get("labels", {})

    def mask(name):
        m = np.zeros(n, dtype=bool)
        m[np.asarray(labels.get(name, []), dtype=np.int64)] = True
        return m

    corner = np.zeros(n, dtype=np.int8)
    corner[mask("corner")] = 1
    corner[mask("reflex_corner")] = -1
    turning = np.zeros(n)
    for k, a in data.get("turning", []):
        turning[int(k)] = float(a)
    ring = np.asarray(data.get("ring", [-1] * n), dtype=np.int64)
    node = np.asarray(data.get("node", [-1] * n), dtype=np.int64)
    fp = np.asarray(data.get("face_patch", [-1] * len(faces)), dtype=np.int64)
    try:
        chains = tuple(np.asarray(c["vertices"], dtype=np.int64) for c in data.get("curves", []))
        lines = tuple(np.asarray(c["polyline"], dtype=float).reshape(-1, 2) for c in data.get("curves", []))
    except (KeyError, TypeError, ValueError) as exc:
        raise VaultgramError(f"{where}: 'curves' must be a list of {{'vertices', 'polyline'}}: {exc}") from None
    curve = np.full(n, -1, dtype=np.int64)
    for c, chain in enumerate(chains):
        curve[chain] = c
    return QuadMesh(x[:, :2].copy(), faces, fp, mask("boundary"), ring, corner, turning, mask("fixed"),
                    mask("pole"), mask("feature"), node, mask("singular_node"),
                    tuple(data.get("edge_groups", ())), (), dict(data.get("info", {})),
                    curve, mask("curve_extremity"), chains, lines)


def write_mesh(mesh: QuadMesh, out_dir: str | Path) -> tuple[Path, Path]:
    """Write ``out_dir/mesh.json`` and ``out_dir/mesh.obj`` (each to a temporary file, then renamed)."""
    out = Path(out_dir)
    paths = out / "mesh.json", out / "mesh.obj"
    write_json(paths[0], mesh_to_json(mesh))
    write_obj(paths[1], mesh.vertices, mesh.faces)
    return paths


def read_mesh(path: str | Path) -> QuadMesh:
    """Read a ``mesh.json`` (see :func:`mesh_to_json`)."""
    return mesh_from_json(read_json(path), str(path))
