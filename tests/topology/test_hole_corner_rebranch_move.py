"""A hole corner left inside a ring patch's side beside a rebranch's end: the rebranch moves one boundary
edge along, to the corner (issue 12, item 2; hole_rebranch). Where the corner's cut ends in a narrow fan
triangle and neither a foot, the rebranch to the fan's pole nor the hub serves it, the corner kept two
faces: plan 317 of the 700 random plans saved in session 25 (main 171d5a0: 7 boundary singular
vertices left, all hole corners)."""

from __future__ import annotations

import numpy as np
import pytest
from layout_probes import node_at

from vaultgram.domain import domain_from_dict
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology import hole_fans, hole_rebranch
from vaultgram.topology.types import BOUNDARY, PATCH_CORNER, REBRANCH

#: Saved random plan 317 (spacing 0.03): a hexagon with a triangular and a pentagonal hole and three
#: point features. On main 171d5a0 the pentagon's 252 degree corner (5.308, 2.753) lies inside the side
#: of the ring patch (171, 120, 111, 92); its cut's strip would be the 39.6 degree triangle of the fan
#: round (8.237, 2.165), which no foot halves into two of 36, and the hub leaves 20 degrees at the
#: skeleton vertex (3.908, 5.030). That vertex's rebranch ends at (4.783, 2.582), the corner's neighbour
#: along the hole's side: 1 boundary singular vertex, min scaled Jacobian 0.349.
DRAW_317 = {
    "outer": [[9.316221613247592, 0.0], [5.000000000000001, 8.660254037844386],
              [-2.499999999999999, 4.330127018922194], [-6.0, 7.347880794884119e-16],
              [-4.117406676484139, -7.131557559093832], [4.882191778399439, -8.456204212482897]],
    "holes": [[[4.241817058508406, -4.344448303911648], [1.4771842890775828, -5.940609777552995],
               [1.4771842890775817, -2.7482868302703016]],
              [[6.931286477514053, 0.5183888186053744], [5.307884202399713, -1.7160327225137744],
               [2.6811641438508023, -0.8625596390011805], [2.6811641438508014, 1.899337276211929],
               [5.307884202399713, 2.7528103597245233]]],
    "points": [[8.237166209935694, 2.1650635094610964], [7.651495122431529, -3.1748246377671823],
               [1.6044110129030607, -7.973749207037435]],
}
SPACING = 0.03
CORNER = (5.307884202399713, 2.7528103597245233)
SKELETON_VERTEX = (3.908, 5.030)
OLD_END = (4.783, 2.582)


def _plan_edges(g, n: int, kind: str) -> list:
    return [g.other(e, n) for e in g.incident(n) if g.edge_type(e) == kind]


def test_the_rebranch_moves_from_the_corners_neighbour_to_the_corner():
    """The skeleton vertex's rebranch ends at the hole corner, which is the corner of three patches whose
    angles there sum to its 252 degrees, each 30 to under 180 (none turns there); the old end is the
    corner of no patch (inside a side, two faces at its straight angle: regular) and keeps its two boundary
    edges only. In the mesh: no boundary singularity (main 1), three faces at the corner, no inverted face,
    min scaled Jacobian at least main's 0.349 less 0.005."""
    domain = domain_from_dict(DRAW_317)
    dec = decompose(domain, SPACING)
    g = dec.graph
    r, x, w = node_at(g, CORNER), node_at(g, SKELETON_VERTEX, 1e-3), node_at(g, OLD_END, 1e-3)
    assert _plan_edges(g, r, REBRANCH) == [x] and not _plan_edges(g, w, REBRANCH)
    assert g.degree(r, [PATCH_CORNER]) == 3 and g.degree(w, [PATCH_CORNER]) == 0
    assert len(_plan_edges(g, w, BOUNDARY)) == 2
    angles = [p.corner_angles()[list(p.corners).index(r)] for p in dec.patches if r in p.corners]
    assert sum(angles) == pytest.approx(252.0, abs=0.5) and all(30.0 <= a < 180.0 for a in angles), angles
    mesh = mesh_decomposition(dec)
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    at = int(np.hypot(*(np.asarray(mesh.vertices)[:, :2] - CORNER).T).argmin())
    assert sum(at in f for f in mesh.faces) == 3
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= 0.344


def test_without_the_move_the_corner_keeps_two_faces(monkeypatch):
    """With the move refused (main's layout) the rebranch ends at the neighbour, the hole corner is the
    corner of no patch and the one boundary singular vertex, as on main 171d5a0. The merge of two fan
    triangles, the fallback after the move (session 31, hole_fans), is off too: it would take the corner
    in the move's place."""
    monkeypatch.setattr(hole_rebranch, "_fits", lambda *args: False)
    monkeypatch.setattr(hole_fans, "_pair", lambda *args: None)
    domain = domain_from_dict(DRAW_317)
    dec = decompose(domain, SPACING)
    g = dec.graph
    r, w = node_at(g, CORNER), node_at(g, OLD_END, 1e-3)
    assert g.degree(r, [PATCH_CORNER]) == 0 and not _plan_edges(g, r, REBRANCH)
    assert len(_plan_edges(g, w, REBRANCH)) == 1 and g.degree(w, [PATCH_CORNER]) == 2
    mesh = mesh_decomposition(dec)
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 1
    assert np.allclose(np.asarray(mesh.vertices[stats["boundary_singular_vertices"][0]])[:2], CORNER, atol=1e-6)
