"""The fold fallback keeps the splits at poles a rule marked on the boundary (issue 12, item 3): where
the three-quad splits fold, the mesh falls back to Figure 3's fans, but a triangle whose pole
``move_rebranch_to_lone_corner`` (or a reflex corner's rule) marked on the boundary stays three quads,
so that the pole keeps the one face there its rule gave it (:func:`vaultgram.meshing.splits.boundary_pole_splits`,
``vaultgram.meshpipeline._fans_back``)."""

from __future__ import annotations

import numpy as np
import pytest

import vaultgram.meshpipeline as meshpipeline
from vaultgram.domain import domain_from_dict
from vaultgram.meshing.layout import edge_groups
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_domain

#: Draw 511 of the 700 random plans kept in benchmarks/data/random_plans_700.json.gz (spacing 0.05): a
#: heptagon with four point features, two on the boundary beside its 136.4 degree corner (-5.759, 1.685).
#: ``move_rebranch_to_lone_corner`` makes that corner the marked pole of a triangle (68 degrees, a
#: split of three quads: one face) beside a feature's fan (one face): two faces. But the split of a
#: boundary feature's thin triangle near (1.998, 6.912) (6 by 1 quads) folds, and main 18d7fb4 then
#: dropped every split: the corner's triangle became a fan of 8, nine faces, the plan's one boundary
#: singular vertex (min scaled Jacobian 0.180, at that feature's fan, elsewhere).
DRAW_511 = {"name": "random",
            "outer": [[6.250940888777535, 1.035521324429404], [3.7129645735247236, 6.653020728018394],
                      [-3.14699137314874, 7.6871977455140765], [-5.758591369548599, 1.684822079200171],
                      [-4.089724946551006, -2.876482202545041], [-0.34902397124760765, -5.787660363729878],
                      [3.7144122028863773, -3.347109497319856]],
            "holes": [],
            "points": [[1.15, 5.0551419358752625], [-5.105691370448634, 3.185415995778647],
                       [1.9979755868563578, 6.911564982392314], [-4.924158158049803, -0.595830061672435]],
            "curves": []}
SPACING_511 = 0.05
CORNER_511 = (-5.758591369548599, 1.684822079200171)


def _faces_at(mesh, at) -> int:
    x = np.asarray(mesh.vertices)[:, :2]
    (v,) = np.flatnonzero(np.linalg.norm(x - np.asarray(at), axis=1) < 1e-6)
    return sum(int(v) in face for face in mesh.faces)


def _mesh_and_stats():
    domain = domain_from_dict(DRAW_511)
    mesh = mesh_domain(domain, SPACING_511)
    return mesh, mesh_stats(mesh, domain)


def test_the_rule_marks_the_corner_as_a_pole():
    """The layout gives the corner two faces: the triangle whose pole it is (marked by the rule) and a
    triangle whose pole is the boundary feature beside it."""
    dec = decompose(domain_from_dict(DRAW_511), SPACING_511)
    g = dec.graph
    (b,) = [n for n in g.nodes() if g.node_type(n) == "Corner" and np.allclose(g.get(n, "pos"), CORNER_511)]
    layout = edge_groups(dec)
    at_b = [pat for pat in layout.patterns if b in pat.corners]
    assert len(at_b) == 2 and all(len(pat.corners) == 3 for pat in at_b)
    assert sorted(pat.corners[pat.pole] == b for pat in at_b) == [False, True]
    assert any(dec.marked_pole(dec.patches[pat.patch]) == b for pat in at_b)


def test_the_fallback_keeps_the_split_at_the_corner():
    """The splits fold, the mesh falls back to fans but for the corner's: the corner has two faces
    (regular at 136 degrees), no boundary singular vertex is left, no face is inverted, and the worst
    face is main's (0.180, a boundary feature's fan elsewhere)."""
    mesh, stats = _mesh_and_stats()
    assert _faces_at(mesh, CORNER_511) == 2
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    assert stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] >= 0.17


def test_without_it_every_split_is_dropped(monkeypatch):
    """Main's fallback (no split kept): the corner's triangle is a fan of eight, nine faces at the
    corner, the plan's one boundary singular vertex."""
    monkeypatch.setattr(meshpipeline, "boundary_pole_splits", lambda layout, counts: frozenset())
    mesh, stats = _mesh_and_stats()
    assert _faces_at(mesh, CORNER_511) == 9
    assert stats["boundary_singular"] == 1
    assert stats["boundary_singular_angles"] == pytest.approx([136.39], abs=0.01)
