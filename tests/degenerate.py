"""The checks shared by the tests of the degenerate-skeleton rules (rules/topology.vgr: the O-grid
and the lone branch cut in three): the layout they draw and the mesh it gives."""

from __future__ import annotations

from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition


def nodes_of(dec, node_type: str) -> list[int]:
    """The decomposition graph's nodes of one type."""
    return [n for n in dec.graph.nodes() if dec.graph.node_type(n) == node_type]


def assert_quads_round(domain, node_type: str, patches: int, spacing: float = 0.03, min_quality: float = 0.3):
    """``patches`` four-sided patches whose only inner corners are nodes of ``node_type``, each of
    valence 3; the mesh has exactly those interior singular vertices (valence 3), none on the
    boundary, no triangle and no inverted face, a disc's Euler characteristic (V - E + F = 1) and no
    quad worse than ``min_quality`` (scaled Jacobian). Returns the decomposition."""
    dec = decompose(domain, spacing)
    assert sorted(p.n_sides for p in dec.patches) == [4] * patches
    corners = nodes_of(dec, node_type)
    assert corners and [dec.valence(n) for n in corners] == [3] * len(corners)
    mesh = mesh_decomposition(dec)
    stats = mesh_stats(mesh, domain)
    assert stats["interior_singular_valences"] == [3] * len(corners)
    assert stats["boundary_singular"] == 0 and stats["triangles"] == 0 and stats["inverted_faces"] == 0
    assert len(mesh.vertices) - mesh_edges(mesh.faces).n_edges + len(mesh.faces) == 1
    assert stats["min_scaled_jacobian"] > min_quality
    return dec
