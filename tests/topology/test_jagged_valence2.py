"""Jagged outlines' corners with too many patches, round 2 (issue 12, acceptance 3): a thin triangle ``(b, x, y)``
beside a quad ``(b, u, v, x)`` at a corner of 225 degrees or more that is the corner of one patch too many; their
shared rebranch ``x-b`` flips to the chord ``v-y`` between skeleton vertices (``flip_over_served_corner``,
:func:`~vaultgram.topology.corner_merges.flip_rebranch`).

On main 28c810b jagged_2's 228 degree corner at (-16.178, -17.462) (a 9.5 degree triangle beside a 12.6 degree
quad) and its 291 degree corner at (4.523, -13.403) (17.4 beside 19.8) were the corners of four patches, and the
small star below had its 243 degree corner the corner of four (a 22.1 degree triangle beside a 34.5 degree quad),
one boundary singular vertex each.
"""

from __future__ import annotations

import functools

from layout_probes import assert_regular_corner, faces_at, node_at, patch_with

from vaultgram.domain import domain_from_dict
from vaultgram.geometry.polygons import regular_valence
from vaultgram.meshing.quality import mesh_stats
from vaultgram.meshpipeline import decompose, mesh_decomposition
from vaultgram.testing.jagged import jagged_plans
from vaultgram.topology import corner_merges
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.functions import patch_angle
from vaultgram.topology.types import PATCH_CORNER

# A jagged star of 23 points (drawn like jagged_plans at radius 10): its 243 degree corner FLIP was the corner
# of four patches on main (bs 1, min SJ 0.5003).
FLIP_PLAN = {"outer": [[8.61, 0.96], [8.74, 2.0], [8.9, 6.62], [7.45, 12.09], [-2.9, 8.08], [-3.17, 6.67],
                       [-4.57, 6.13], [-4.23, 5.6], [-4.32, 5.48], [-5.9, 5.75], [-6.41, 5.34], [-10.25, 2.49],
                       [-8.01, -5.48], [-5.45, -6.75], [-3.35, -7.48], [-1.36, -10.49], [-0.05, -11.5], [-0.01, -10.83],
                       [0.18, -10.58], [2.17, -10.98], [8.25, -7.52], [7.5, -2.75], [6.76, -0.24]]}
FLIP = (-4.32, 5.48)
# s29-jmany's star whose 274 degree corner's spread is refused by the edge-group limit (test_jagged_valence.py):
# a 9.4 degree triangle beside a 69.9 degree quad, flipped (main: bs 1, min SJ 0.5028).
UNEVEN_PLAN = {"outer": [[9.9, 4.16], [5.38, 6.26], [3.78, 5.28], [2.34, 8.04], [2.32, 8.89], [-6.79, 6.66],
                         [-9.19, 5.99], [-8.42, 5.31], [-7.96, 4.39], [-7.87, 4.34], [-6.68, 1.47], [-6.49, 0.66],
                         [-8.08, -0.19], [-8.99, -1.11], [-9.27, -2.48], [-7.95, -4.45], [-7.91, -6.15],
                         [-6.67, -10.58], [-6.61, -10.85], [-6.5, -11.03], [0.42, -9.98], [2.12, -8.54], [2.36, -8.6],
                         [3.39, -6.32], [7.02, -6.04], [12.15, -5.21]]}
UNEVEN = (3.78, 5.28)
JAGGED_2 = [(-16.178, -17.462), (4.523, -13.403)]  # jagged_2's 228 and 291 degree corners


@functools.lru_cache(maxsize=None)
def _laid_out(name: str) -> tuple:
    """The plan ``name`` (``flip`` or a jagged plan): domain, decomposition, mesh."""
    domain = domain_from_dict(FLIP_PLAN if name == "flip" else jagged_plans()[name])
    dec = decompose(domain, 0.02)
    return domain, dec, mesh_decomposition(dec)


def _flips(dec) -> list:
    return [step for step in dec.trace if step["rule"] in ("flip_over_served_corner", "flip_over_served_corner_back")]


def _assert_regular(name: str, at) -> None:
    """:func:`layout_probes.assert_regular_corner` at ``at`` in the layout and mesh of ``name``."""
    _, dec, mesh = _laid_out(name)
    assert_regular_corner(dec, mesh, at)


def test_a_thin_triangle_beside_a_quad_flips_its_rebranch():
    """The star's 243 degree corner: the 22 degree triangle and the 34 degree quad beside it become a quad of
    their summed angle there (56.6 degrees) and a triangle whose corners are all skeleton vertices, none under
    FLIP_MIN_ANGLE; the corner has three patches and three faces, the mesh no boundary singular vertex (main:
    one) and a worst face no lower than main's."""
    domain, dec, mesh = _laid_out("flip")
    (step,) = _flips(dec)
    g = dec.graph
    b, u, v, x, y = (step["binding"][k] for k in "buvxy")
    assert node_at(g, FLIP, 1e-6) == b and 225.0 < boundary_angle(g, b) < 315.0
    _assert_regular("flip", FLIP)
    quad, tri = patch_with(g, {b, u, v, y}), patch_with(g, {v, x, y})
    assert quad is not None and tri is not None
    assert all(g.schema.is_subtype(g.node_type(n), "SkeletonVertex") for n in (v, x, y))
    assert abs(patch_angle(g, quad, b) - 56.63) < 0.05  # 34.49 + 22.14 on main
    assert min(patch_angle(g, tri, n) for n in (v, x, y)) >= corner_merges.FLIP_MIN_ANGLE
    assert max(patch_angle(g, quad, n) for n in (b, u, v, y)) <= corner_merges.FLIP_MAX_ANGLE
    assert min(patch_angle(g, graph_patch, b) for graph_patch in
               (g.ends(e)[0] for e in g.incident(b, [PATCH_CORNER]))) > 55.0  # main's thinnest: 22.1
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 0 and stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.5003  # main 0.5003


def test_the_corner_whose_spread_is_refused_flips_instead():
    """The 274 degree corner that the spread leaves the corner of four patches (its quad would join 0.47 to
    1.21 in one edge group) flips its 9.4 degree triangle's rebranch: three patches, three faces, the mesh no
    boundary singular vertex (main: one); its worst face, now beside the new triangle, 0.5007 (main 0.5028)."""
    domain = domain_from_dict(UNEVEN_PLAN)
    dec = decompose(domain, 0.02)
    assert len(_flips(dec)) == 1
    g = dec.graph
    b = node_at(g, UNEVEN, 1e-6)
    assert g.degree(b, [PATCH_CORNER]) == int(regular_valence(boundary_angle(g, b))) - 1 == 3
    mesh = mesh_decomposition(dec)
    assert faces_at(mesh, UNEVEN, 1e-6) == 3
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 0 and stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.5


def test_without_the_flip_the_corner_keeps_four_patches(monkeypatch):
    """With the flip's angle floor above its triangle's corners the rule does not fire: the corner keeps four
    patches and the mesh its boundary singular vertex, as on main."""
    monkeypatch.setattr(corner_merges, "FLIP_MIN_ANGLE", 90.0)
    domain = domain_from_dict(FLIP_PLAN)
    dec = decompose(domain, 0.02)
    assert not _flips(dec)
    assert dec.graph.degree(node_at(dec.graph, FLIP, 1e-6), [PATCH_CORNER]) == 4
    assert mesh_stats(mesh_decomposition(dec), domain)["boundary_singular"] == 1


def test_a_triangle_wider_than_flip_thin_is_not_flipped(monkeypatch):
    """The star's triangle is 22.1 degrees wide at the corner: with FLIP_THIN under that it is a face of its own,
    left alone (jagged_3's 78.7 degree triangle at its 304 degree corner is, at 45)."""
    monkeypatch.setattr(corner_merges, "FLIP_THIN", 20.0)
    dec = decompose(domain_from_dict(FLIP_PLAN), 0.02)
    assert not _flips(dec)
    assert dec.graph.degree(node_at(dec.graph, FLIP, 1e-6), [PATCH_CORNER]) == 4


def test_jagged_2s_over_served_corners_are_regular():
    """jagged_2's 228 and 291 degree corners (main: four patches each) are the corners of three patches with three
    faces; the plan has 6 boundary singular vertices (main 8), its worst face no lower than main's 0.271."""
    domain, dec, mesh = _laid_out("jagged_2")
    assert len(_flips(dec)) == 2
    for at in JAGGED_2:
        _assert_regular("jagged_2", at)
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] <= 6 and stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.27
