"""A strip that reaches a boundary side with no free point splits that boundary edge at its middle
(``rules/strips.vgr``'s ``split_boundary_for_strip``, :func:`vaultgram.topology.strips.strip_boundary_split`;
issue 12 acceptance 3). Where the side is one boundary edge between two points that are patch corners
already (other strips' ends), the strip walk was refused, and a hole corner whose cut needed that strip
kept two faces where its angle asks for three: 3 of the 10 boundary singular vertices of the 700 random
plans saved in session 25 (main af3c82e: plans 456-458, one plan shrunk)."""

from __future__ import annotations

import numpy as np
import pytest
from layout_probes import assert_regular_hole_corner, faces_at, laid_out, node_at

from vaultgram.meshing.quality import mesh_stats
from vaultgram.topology import strips
from vaultgram.topology.corners import boundary_angle, graph_rings
from vaultgram.topology.patches import hole_rings
from vaultgram.topology.types import BOUNDARY, DIAGONAL, PATCH_CORNER

#: Saved random plan 456 of the 700 (spacing 0.03; 457 and 458 are the same plan): an octagon with an
#: octagonal hole (225 degree corners) and one inner point feature. On main af3c82e the hole corner
#: :data:`CORNER` lies inside the ring patch's side; its cut's strip crosses one quad to the outer
#: boundary edge from (0.571, -6.071) to (1.141, -6.141), 0.57 long, whose two points are both the ends
#: of other strips: no free point to end at. 1 boundary singular vertex, min scaled Jacobian 0.357.
DRAW_456 = {
    "outer": [[7.2098196967653765, 0.0], [4.6889855801001366, 4.688985580100136],
              [4.378693638729824e-16, 7.150949386841073], [-6.34795260405791, 6.347952604057911],
              [-6.0, 7.347880794884119e-16], [-6.887712434855355, -6.887712434855352],
              [-1.102182119232618e-15, -6.0], [6.847603801558683, -6.8476038015586855]],
    "holes": [[[2.298830454544171, -2.693716348960335], [1.9477011439011342, -3.541417492861469],
               [1.1, -3.892546803504506], [0.25229885609886604, -3.541417492861469],
               [-0.0988304545441705, -2.693716348960335], [0.2522988560988657, -1.8460152050592011],
               [1.0999999999999999, -1.4948858944161645], [1.947701143901134, -1.8460152050592007]]],
    "points": [[0.10879644339724415, 6.103515625e-05]],
}
SPACING = 0.03
CORNER = (0.25229885609886604, -3.541417492861469)
#: The two outer boundary points the strip ends between (their middle is the new boundary point).
EDGE_ENDS = ((0.5706336501298902, -6.07063365012989), (1.1412673002597804, -6.141267300259781))


@pytest.fixture(scope="module")
def split():
    return laid_out(DRAW_456, SPACING)


def test_the_hole_corner_gets_its_third_face(split):
    """The 225 degree hole corner is the corner of three patches and has three faces in the mesh
    (valence 4, regular); no boundary singular vertex is left (main 1), no inverted face, min scaled
    Jacobian at least main's 0.357 less 0.01."""
    assert_regular_hole_corner(split, CORNER, 225.0, 0.347)


def test_the_boundary_edge_is_split_at_its_middle_into_a_regular_point(split):
    """One boundary point is added: at the middle of the boundary edge, joined by boundary edges to its
    two ends and by one diagonal (the strip's last chord) to the layout, the corner of two patches, at
    180 degrees with two faces in the mesh (regular; the smoothing slides it along the boundary). In ring
    order it lies between the two ends, and the rings keep the domain's area (the boundary polygon gains
    a point on a straight edge)."""
    domain, dec, mesh = split
    g = dec.graph
    a, b = (node_at(g, p) for p in EDGE_ENDS)
    middle = tuple((np.asarray(EDGE_ENDS[0]) + np.asarray(EDGE_ENDS[1])) / 2)
    w = node_at(g, middle)
    assert {g.other(e, w) for e in g.incident(w, [BOUNDARY])} == {a, b}
    assert g.degree(w, [DIAGONAL]) == 1 and g.degree(w, [PATCH_CORNER]) == 2
    assert not any(g.other(e, a) == b for e in g.incident(a, [BOUNDARY]))  # the edge a-b is gone
    assert boundary_angle(g, w) == pytest.approx(180.0)
    assert faces_at(mesh, middle, 0.1 * np.hypot(*np.subtract(*EDGE_ENDS))) == 2  # smoothing slides it a little
    rings, nodes = graph_rings(g)
    k = nodes[0].index(w)
    assert (nodes[0][k - 1], nodes[0][(k + 1) % len(nodes[0])]) == (a, b)
    assert len(nodes[0]) == len(set(nodes[0]))
    outer = np.asarray(DRAW_456["outer"], dtype=float)
    x, y = rings[0][:, 0], rings[0][:, 1]
    area = 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))
    x, y = outer[:, 0], outer[:, 1]
    assert area == pytest.approx(0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)), rel=1e-9)
    assert len(hole_rings(g)) == 1 and len(hole_rings(g)[0]) == len(rings[1])


def test_without_the_split_the_corner_keeps_two_faces(monkeypatch):
    """With the split refused (main's strip walk: a boundary side without a free point ends no strip)
    the hole corner is the corner of no patch and has two faces: the one boundary singular vertex of
    main af3c82e."""
    monkeypatch.setattr(strips, "strip_boundary_split", lambda graph, patch, corner: -1)
    domain, dec, mesh = laid_out(DRAW_456, SPACING)
    assert dec.graph.degree(node_at(dec.graph, CORNER), [PATCH_CORNER]) == 0
    assert faces_at(mesh, CORNER) == 2
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 1 and stats["boundary_singular_angles"][0] == pytest.approx(225.0)
