"""A hole corner inside a side of a triangle whose pole is an end of that side is cut across the
triangle to the pole's other side (``rules/corners.vgr``'s ``cut_triangle_at_hole_corner_to_pole_*``,
:mod:`vaultgram.topology.hole_triangles`; issue 12 acceptance 3). Such a corner had no move: no quad
to cut, and a chord to the triangle's third corner gives it two triangles, two faces where its angle
asks for three. The last of the 7 boundary singular vertices of the 700 random plans saved in session
25 that lies inside a triangle's side (main 171d5a0: plans 688 and 689, one plan)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from layout_probes import assert_regular_hole_corner, faces_at, laid_out, node_at

from vaultgram.geometry.polygons import ccw_degrees, direction
from vaultgram.meshing.quality import mesh_stats
from vaultgram.topology import hole_triangles, reflex
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.strips import patch_sides
from vaultgram.topology.types import DIAGONAL, PATCH_CORNER

#: Saved random plan 688 of the 700 (spacing 0.02; 689 is the same plan): a nonagon with a heptagonal
#: hole and one boundary point feature. On main 171d5a0 the neighbouring hole corners' chords leave the
#: hole corner :data:`CORNER` (231.4 degrees) inside the hole side of the triangle whose corners are
#: the hole corners :data:`POLE` (its marked pole, meshed as three quads) and :data:`AHEAD` and a strip
#: point: two faces, 1 boundary singular vertex, min scaled Jacobian 0.500.
DRAW_688 = {
    "outer": [[6.366513294051941, 1.529066473727368], [3.357932193726691, 4.538833307448916],
              [-0.3804302153203142, 6.210868595470527], [-4.505903139036946, 4.747381278265598],
              [-5.96149182011542, 0.6786864362111167], [-8.33836485592913, -5.520115173563498],
              [-2.571701500034317, -8.684769239379872], [2.86470774545044, -6.586766702375415],
              [5.626718233070554, -2.8047503069877044]],
    "holes": [[[1.2754913575903433, -1e-05], [0.7952558538165302, -0.997229298980018],
               [-0.28382352814421047, -1.2435221262615133], [-1.149178004467491, -0.5534249594434286],
               [-1.1491780044674913, 0.5534049594434285], [-0.2838235281442108, 1.2435021262615131],
               [0.79525585381653, 0.9972092989800182]]],
    "points": [[1.4521814113646052, 5.39120721067798]],
}
SPACING = 0.02
CORNER = (0.7952558538165302, -0.997229298980018)
POLE = (-0.28382352814421047, -1.2435221262615133)
AHEAD = (1.2754913575903433, -1e-05)


def _patches(g, n) -> list:
    return sorted({g.ends(e)[0] for e in g.incident(n, [PATCH_CORNER])})


def _pole_of(g, patch) -> int | None:
    return next((g.ends(e)[1] for e in g.incident(patch, [PATCH_CORNER]) if g.get_edge(e, "pole")), None)


@pytest.fixture(scope="module")
def cut():
    return laid_out(DRAW_688, SPACING)


def test_the_hole_corner_gets_its_third_face(cut):
    """The 231.4 degree hole corner is the corner of three patches and has three faces in the mesh
    (valence 4, regular); no boundary singular vertex is left (main 1), no inverted face, min scaled
    Jacobian at least main's 0.500 less 0.01."""
    assert_regular_hole_corner(cut, CORNER, 231.4, 0.49, tol=0.05)


def test_the_triangle_is_cut_to_its_poles_other_side(cut):
    """The cut runs from the corner to a strip point on the triangle's side from its pole to its third
    corner (collinear with the two, between them), leaving the triangle (corner, pole, strip point) with
    its pole kept at the hole corner :data:`POLE`, whose two sides there are within 3.5 of each other in
    length (one edge group); the corner's angle is split by its two chords into three parts of at least
    40 degrees, each patch at the corner convex there; every patch at the corner is a quad or that
    triangle."""
    _, dec, _ = cut
    g = dec.graph
    r, pole = node_at(g, CORNER), node_at(g, POLE)
    (tri,) = [p for p in _patches(g, r) if _pole_of(g, p) == pole]
    assert len(patch_sides(g, tri).corners) == 3
    (m,) = [c for c in patch_sides(g, tri).corners if c not in (r, pole)]
    assert g.node_type(m) == "StripPoint" and any(g.other(e, r) == m for e in g.incident(r, [DIAGONAL]))
    pm, at = np.asarray(g.get(pole, "pos")), np.asarray(g.get(m, "pos"))
    ends = [np.asarray(g.get(g.other(e, m), "pos")) for e in g.incident(m, [DIAGONAL])]
    cross = [float((at - pm)[0] * (x - pm)[1] - (at - pm)[1] * (x - pm)[0]) for x in ends]
    assert any(abs(c) < 1e-9 * float(np.dot(x - pm, x - pm))
               and 0.0 < float(np.dot(at - pm, x - pm)) < float(np.dot(x - pm, x - pm)) for c, x in zip(cross, ends))
    sides = sorted((math.dist(g.get(pole, "pos"), g.get(r, "pos")), math.dist(g.get(pole, "pos"), g.get(m, "pos"))))
    assert sides[1] <= hole_triangles.MAX_RATIO * sides[0]
    angles = [reflex.patch_corner(g, patch_sides(g, p), patch_sides(g, p).corners.index(r))[2] for p in _patches(g, r)]
    assert sum(angles) == pytest.approx(boundary_angle(g, r), abs=1e-6)
    assert min(angles) >= reflex.MIN_CUT_ANGLE and max(angles) < 180.0
    kinds = sorted((len(patch_sides(g, p).corners), _pole_of(g, p) == r) for p in _patches(g, r) if p != tri)
    assert kinds == [(3, True), (4, False)]  # the chord's triangle (its pole r: three quads) and a quad


def test_the_cut_leaves_the_boundary_at_40_degrees_or_more(cut):
    """The cut's chord leaves the hole corner at least 40 degrees from either boundary side (a quad cut's
    limit, :data:`vaultgram.topology.reflex.MIN_CUT_ANGLE`)."""
    _, dec, _ = cut
    g = dec.graph
    r, pole = node_at(g, CORNER), node_at(g, POLE)
    (tri,) = [p for p in _patches(g, r) if _pole_of(g, p) == pole]
    (m,) = [c for c in patch_sides(g, tri).corners if c not in (r, pole)]
    first = ccw_degrees(reflex.boundary_ahead(g, r), direction(g.get(r, "pos"), g.get(m, "pos")))
    assert reflex.MIN_CUT_ANGLE <= first <= boundary_angle(g, r) - reflex.MIN_CUT_ANGLE


def test_without_the_cut_the_corner_keeps_two_faces(monkeypatch):
    """With the cut off the hole corner is the corner of no patch, inside the side of the triangle whose
    pole is :data:`POLE` and whose other corner on that side is :data:`AHEAD`, and has two faces: the
    one boundary singular vertex of main 171d5a0."""
    monkeypatch.setattr(hole_triangles, "_triangle_cut", lambda graph, r: None)
    domain, dec, mesh = laid_out(DRAW_688, SPACING)
    g = dec.graph
    r = node_at(g, CORNER)
    assert g.degree(r, [PATCH_CORNER]) == 0
    tri, i = reflex.on_side(g, r)
    corners = patch_sides(g, tri).corners
    assert len(corners) == 3 and (corners[i], corners[(i + 1) % 3]) == (node_at(g, AHEAD), node_at(g, POLE))
    assert _pole_of(g, tri) == node_at(g, POLE)
    assert faces_at(mesh, CORNER) == 2
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 1 and stats["boundary_singular_angles"][0] == pytest.approx(231.4, abs=0.05)
