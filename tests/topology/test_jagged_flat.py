"""Jagged outlines' over-served corners beside a quad that is flat at a skeleton vertex (issue 12, acceptance 3):
the pentagon ``(b, u, v, x, y)`` of a thin triangle ``(b, x, y)`` and a quad ``(b, u, v, x)`` flat at ``v`` (170
degrees or more) is cut from ``v`` to the strip point of its side ``y-b`` (``strip_over_served_corner``,
:func:`~vaultgram.topology.corner_merges.flat_corner_strip`), the strip carried on to the boundary.

On main 8763e05 jagged_1's 281 degree corner at (10.649, -9.675) (a 7.5 degree triangle beside a quad of 178.2
degrees at ``v``) and jagged_2's 307 degree corner at (-0.619, -17.265) (6.0 beside 172.0) were the corners of four
patches, one boundary singular vertex each; every diagonal of their pentagons left a sliver (s30-jmany3).
"""

from __future__ import annotations

import functools

from layout_probes import assert_regular_corner, node_at, patch_with

from vaultgram.domain import domain_from_dict
from vaultgram.meshing.quality import mesh_stats
from vaultgram.meshpipeline import decompose, mesh_decomposition
from vaultgram.testing.jagged import jagged_plans
from vaultgram.topology import corner_merges
from vaultgram.topology.functions import patch_angle
from vaultgram.topology.types import PATCH_CORNER

JAGGED_1 = (10.649, -9.675)  # jagged_1's 281 degree corner
JAGGED_2 = (-0.619, -17.265)  # jagged_2's 307 degree corner
STRIPS = ("strip_over_served_corner", "strip_over_served_corner_back")


@functools.lru_cache(maxsize=None)
def _laid_out(name: str) -> tuple:
    """The jagged plan ``name``: domain, decomposition, mesh."""
    domain = domain_from_dict(jagged_plans()[name])
    dec = decompose(domain, 0.02)
    return domain, dec, mesh_decomposition(dec)


def _strips(dec) -> list:
    return [step for step in dec.trace if step.get("rule") in STRIPS]


def _cut(name: str, at) -> tuple:
    """The one cut of the plan ``name``: its binding's corner ``b`` (at ``at``), ``u``, ``v``, ``x``, ``y``."""
    _, dec, _ = _laid_out(name)
    (step,) = _strips(dec)
    b, u, v, x, y = (step["binding"][k] for k in "buvxy")
    assert node_at(dec.graph, at, 1e-6) == b
    return b, u, v, x, y


def _quads(graph, b, u, v, x, y) -> tuple:
    """The strip point ``m`` of the cut (the strip point joined to ``v`` whose quad ``(b, u, v, m)`` is a patch)
    and the two quads ``(b, u, v, m)``, ``(m, v, x, y)``."""
    (m,) = [n for n in (graph.other(e, v) for e in graph.incident(v, ["Diagonal"]))
            if graph.node_type(n) == "StripPoint" and patch_with(graph, {b, u, v, n}) is not None]
    return m, patch_with(graph, {b, u, v, m}), patch_with(graph, {m, v, x, y})


def test_jagged_1s_corner_is_cut_from_the_flat_corner():
    """jagged_1's 281 degree corner: the pentagon is cut from ``v`` into two quads, the corner keeps the
    triangle's and the quad's summed angle (51.8 degrees) in one quad and is the corner of three patches with
    three faces; the chord leaves MIN_ANGLE or more either side at ``v`` and at the strip point; no quad corner
    past straight. The plan has 4 boundary singular vertices (main 5) and its worst face rises (main 0.302)."""
    domain, dec, mesh = _laid_out("jagged_1")
    g = dec.graph
    b, u, v, x, y = _cut("jagged_1", JAGGED_1)
    m, near, far = _quads(g, b, u, v, x, y)
    assert far is not None
    assert abs(patch_angle(g, near, b) - 51.8) < 0.1  # 44.3 + 7.5 on main
    assert_regular_corner(dec, mesh, JAGGED_1)
    chord = [patch_angle(g, near, v), patch_angle(g, near, m), patch_angle(g, far, v), patch_angle(g, far, m)]
    assert min(chord) >= corner_merges.MIN_ANGLE
    assert max(patch_angle(g, p, n) for p, ns in ((near, (b, u, v, m)), (far, (m, v, x, y))) for n in ns) < 180.0
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] <= 4 and stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.32  # main 0.302 (0.329 here)


def test_jagged_2s_corner_is_cut_and_its_flat_vertex_is_regular():
    """jagged_2's 307 degree corner: cut from ``v`` (172.0 degrees in the quad), the corner of three patches
    with three faces (reflex corners' strips cross the two quads later); ``v``, an inner point, is the corner
    of four patches (its regular valence); 5 boundary singular vertices (main 6), worst face no lower than
    main's 0.271."""
    domain, dec, mesh = _laid_out("jagged_2")
    g = dec.graph
    b, u, v, x, y = _cut("jagged_2", JAGGED_2)
    assert_regular_corner(dec, mesh, JAGGED_2)
    assert g.degree(v, [PATCH_CORNER]) == 4
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] <= 5 and stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.271


def test_below_the_flat_bound_the_corner_keeps_four_patches(monkeypatch):
    """With FLAT_CORNER above the quad's 178.2 degrees at ``v`` the cut is refused: jagged_1's corner keeps
    four patches (main's layout there)."""
    monkeypatch.setattr(corner_merges, "FLAT_CORNER", 179.0)
    dec = decompose(domain_from_dict(jagged_plans()["jagged_1"]), 0.02)
    assert not _strips(dec)
    assert dec.graph.degree(node_at(dec.graph, JAGGED_1, 1e-6), [PATCH_CORNER]) == 4
