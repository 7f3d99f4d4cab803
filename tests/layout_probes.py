"""Probes the layout and mesh tests share: a plan laid out and meshed, the decomposition's node at a
point, the mesh faces at a polygon corner (a corner's face count is its valence on the boundary less
one, issue 12)."""

from __future__ import annotations

import numpy as np

from vaultgram.domain import domain_from_dict
from vaultgram.geometry.polygons import regular_valence
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.types import PATCH_CORNER


def laid_out(plan: dict, spacing: float) -> tuple:
    """The plan ``plan`` (vaultgram JSON as a dict): its domain, its decomposition at ``spacing`` and
    that decomposition's mesh."""
    domain = domain_from_dict(plan)
    dec = decompose(domain, spacing)
    return domain, dec, mesh_decomposition(dec)


def node_at(graph, at, tol: float = 1e-9) -> int:
    """The one non-patch node of the decomposition ``graph`` within ``tol`` of the point ``at``."""
    (n,) = [n for n in graph.nodes()
            if graph.node_type(n) != "Patch" and np.allclose(graph.get(n, "pos"), at, atol=tol)]
    return n


def patch_with(graph, corners: set):
    """The Patch node of the decomposition ``graph`` whose corners are exactly ``corners``, or None."""
    for e in graph.incident(next(iter(corners)), [PATCH_CORNER]):
        p = graph.ends(e)[0]
        if {graph.ends(f)[1] for f in graph.incident(p, [PATCH_CORNER])} == corners:
            return p
    return None


def faces_at(mesh, at, tol: float = 1e-9) -> int:
    """The number of faces at the mesh vertex nearest ``at``, which lies within ``tol`` of it (a fixed
    polygon corner)."""
    x = np.asarray(mesh.vertices, dtype=float)[:, :2]
    v = int(np.hypot(*(x - np.asarray(at)).T).argmin())
    assert np.hypot(*(x[v] - np.asarray(at))) < tol
    return sum(v in face for face in mesh.faces)


def assert_regular_hole_corner(laid, corner, angle: float, min_sj: float, tol: float = 1e-6) -> None:
    """The hole corner at ``corner`` of the plan ``laid`` (:func:`laid_out`), of interior angle ``angle``
    degrees (within ``tol``), is the corner of three patches with three faces in the mesh (valence 4,
    regular for 225-315 degrees); the mesh has no boundary singular vertex, no inverted face and a min
    scaled Jacobian of at least ``min_sj``."""
    domain, dec, mesh = laid
    r = node_at(dec.graph, corner)
    assert abs(boundary_angle(dec.graph, r) - angle) <= tol
    assert dec.graph.degree(r, [PATCH_CORNER]) == 3
    assert_three_faces_and_regular(domain, mesh, corner, min_sj, tol=1e-9)


def assert_three_faces_and_regular(domain, mesh, corner, min_sj: float, tol: float = 1e-6) -> None:
    """The mesh of ``domain`` has three faces at the polygon corner ``corner`` (a reflex corner's regular
    number), no boundary singular vertex, no inverted face and a min scaled Jacobian of at least ``min_sj``."""
    assert faces_at(mesh, corner, tol) == 3
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= min_sj


def assert_the_one_singular_corner(domain, dec, corner, faces: int, angle: float) -> None:
    """The mesh of ``dec`` (the decomposition of ``domain``) has one boundary singular vertex, the polygon
    corner ``corner`` of ``angle`` degrees (within 0.5), with ``faces`` faces: a control arm's layout, the
    corner as main left it."""
    mesh = mesh_decomposition(dec)
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 1 and abs(stats["boundary_singular_angles"][0] - angle) <= 0.5, stats
    assert faces_at(mesh, corner, 1e-6) == faces


def assert_regular_corner(dec, mesh, at, tol: float = 1e-6) -> None:
    """The boundary point at ``at`` is the corner of as many patches of ``dec`` as its angle's regular
    number of faces (``1 + max(1, round(theta / 90))`` less one, issue 12 What 1), and has that many faces
    in ``mesh``."""
    b = node_at(dec.graph, at, tol)
    regular = int(regular_valence(boundary_angle(dec.graph, b))) - 1
    assert dec.graph.degree(b, [PATCH_CORNER]) == regular
    assert faces_at(mesh, at, tol) == regular
