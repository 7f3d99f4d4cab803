"""Jagged outlines' corners with too many patches (issue 12, acceptance 3): the skeleton rebranches three
or four of its vertices to one reflex corner, so the corner is the corner of one patch more than its
regular faces; ``rules/corner_merges.vgr`` takes one rebranch away (:mod:`vaultgram.topology.corner_merges`).

On main ff28880 jagged_0's spikes at (21.057, 5.133) and (-14.577, -4.973), jagged_1's at (5.191, 13.316) and
jagged_3's at (9.094, 15.388) were the corners of five patches (boundary singular, five faces); the four plans had
11 / 9 / 9 / 9 boundary singular vertices. The 225-315 degree corners of four patches there (jagged_1's 281
degree corner at (10.649, -9.675), jagged_2's 228 at (-16.178, -17.462), jagged_3's 304 at (-12.471, 6.561)) stay
so: the spread to the neighbour would join a boundary piece to a branch 3-16 times its length in one edge group
(:func:`~vaultgram.topology.corner_merges.spread_rebranch`; without that limit jagged_1's mesh got an edge of
0.0025 of its median).
"""

from __future__ import annotations

import functools
import math

import pytest
from layout_probes import assert_regular_corner, node_at

from vaultgram.domain import domain_from_dict
from vaultgram.meshing.quality import mesh_stats
from vaultgram.meshpipeline import decompose, mesh_decomposition
from vaultgram.testing.jagged import jagged_plans
from vaultgram.topology import corner_merges
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.types import PATCH_CORNER

PLANS = jagged_plans()

# Small plans (a jagged star of 25 and 26 points, drawn like jagged_plans at radius 10) that show each
# rule alone: main ff28880 leaves the marked corner one patch too many and the mesh one boundary
# singular vertex there.
SPIKE_PLAN = {"outer": [[7.4, 1.83], [6.63, 2.13], [6.61, 4.29], [5.58, 10.18], [2.78, 10.83], [2.42, 11.4],
                        [-1.95, 10.65], [-3.46, 9.02], [-4.35, 8.93], [-4.96, 6.74], [-6.3, 4.51], [-7.59, 4.4],
                        [-7.34, 2.91], [-10.59, -2.84], [-8.06, -7.0], [-5.15, -6.75], [-3.45, -7.5], [-2.0, -7.46],
                        [-1.61, -6.5], [-1.18, -7.92], [8.49, -9.27], [10.18, -3.51], [11.33, -2.78], [10.68, -1.75],
                        [8.22, -0.43]]}
SPIKE = (-1.61, -6.5)  # 321 degrees: main five patches
SPREAD_PLAN = {"outer": [[11.47, 1.33], [9.76, 2.09], [5.41, 3.91], [5.88, 6.48], [4.42, 6.86], [3.5, 9.03],
                         [-0.47, 13.29], [-5.39, 12.54], [-5.18, 9.14], [-5.14, 8.56], [-7.02, 8.01], [-6.98, 7.37],
                         [-6.68, 4.77], [-7.1, 4.81], [-10.61, -1.15], [-10.61, -1.61], [-10.65, -3.57],
                         [-11.56, -7.57], [-11.41, -7.99], [-7.85, -10.35], [-6.41, -8.48], [1.89, -7.45],
                         [3.83, -7.68], [4.88, -8.37], [7.0, -7.58], [8.13, -7.64], [12.74, -3.73], [10.02, -0.2]]}
SPREAD = (-6.68, 4.77)  # 282 degrees: main four patches
BEFORE = (-6.98, 7.37)  # the plan's corner before it: the moved rebranch ends at a boundary point between
UNEVEN_PLAN = {"outer": [[9.9, 4.16], [5.38, 6.26], [3.78, 5.28], [2.34, 8.04], [2.32, 8.89], [-6.79, 6.66],
                         [-9.19, 5.99], [-8.42, 5.31], [-7.96, 4.39], [-7.87, 4.34], [-6.68, 1.47], [-6.49, 0.66],
                         [-8.08, -0.19], [-8.99, -1.11], [-9.27, -2.48], [-7.95, -4.45], [-7.91, -6.15],
                         [-6.67, -10.58], [-6.61, -10.85], [-6.5, -11.03], [0.42, -9.98], [2.12, -8.54], [2.36, -8.6],
                         [3.39, -6.32], [7.02, -6.04], [12.15, -5.21]]}
UNEVEN = (3.78, 5.28)  # 274 degrees, four patches: the spread's quad would be 0.47 against 1.21

FIXED = [("jagged_0", (21.057, 5.133)), ("jagged_0", (-14.577, -4.973)), ("jagged_1", (5.191, 13.316)),
         ("jagged_3", (9.094, 15.388))]  # the spikes of five patches on main


@functools.lru_cache(maxsize=None)
def _laid_out(name: str) -> tuple:
    """The plan ``name`` (a jagged plan, ``spike`` or ``spread``): domain, decomposition, mesh."""
    domain = domain_from_dict({"spike": SPIKE_PLAN, "spread": SPREAD_PLAN}.get(name) or PLANS[name])
    dec = decompose(domain, 0.02)
    return domain, dec, mesh_decomposition(dec)


def _applied(dec, rule: str) -> int:
    return sum(1 for step in dec.trace if step["rule"] == rule)


def _moved_to(dec) -> int:
    """The boundary point where spread_over_served_corner_back moved the rebranch (its one application)."""
    (step,) = [step for step in dec.trace if step["rule"] == "spread_over_served_corner_back"]
    return step["binding"]["a"]


def _assert_regular(name: str, at) -> None:
    """:func:`layout_probes.assert_regular_corner` at ``at`` in the layout and mesh of ``name``."""
    _, dec, mesh = _laid_out(name)
    assert_regular_corner(dec, mesh, at)


@pytest.mark.parametrize("name, at", FIXED)
def test_the_over_served_spikes_of_the_jagged_plans_are_regular(name, at):
    """Each spike main left the corner of five patches is the corner of four, its regular number, with
    four faces in the mesh."""
    _, dec, _ = _laid_out(name)
    assert boundary_angle(dec.graph, node_at(dec.graph, at, 1e-6)) >= 315.0
    _assert_regular(name, at)


@pytest.mark.parametrize("name, most", [("jagged_0", 9), ("jagged_1", 5), ("jagged_2", 6), ("jagged_3", 7)])
def test_the_jagged_plans_have_fewer_boundary_singular_vertices(name, most):
    """Boundary singular vertices, main 11 / 9 / 9 / 9 (38): 9 / 7 / 9 / 8 (33) with these rules, 9 / 7 / 8 / 7
    (31) with the outer ring's fallback chords (s29-jfew), 9 / 5 / 8 / 7 (29) with its second fallback's
    chords to boundary points (s30-jfew2: jagged_1's 299 degree corner and 334 degree spike), 9 / 5 / 6 / 7 (27)
    with the flips of jagged_2's thin triangles (s30-jmany2, test_jagged_valence2.py), no inverted face."""
    domain, _, mesh = _laid_out(name)
    stats = mesh_stats(mesh, domain)
    assert stats["inverted_faces"] == 0
    assert stats["boundary_singular"] <= most, stats["boundary_singular_angles"]


def test_a_spike_of_five_patches_merges_two_triangles():
    """The small plan's 321 degree spike was the corner of five patches (three triangles between four
    rebranches): two triangles become a quad, the spike is the corner of four patches with four faces
    and the mesh has no boundary singular vertex (main: one, the spike)."""
    domain, dec, mesh = _laid_out("spike")
    assert _applied(dec, "merge_triangles_at_over_served_spike") == 1
    assert boundary_angle(dec.graph, node_at(dec.graph, SPIKE)) > 315.0
    _assert_regular("spike", SPIKE)
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 0 and stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.45


def test_a_reflex_corner_of_four_patches_spreads_a_rebranch_to_its_neighbour():
    """The small plan's 282 degree corner was the corner of four patches: the rebranch of its thin
    triangle moves back to the ring neighbour (a free point on the straight side towards the plan's
    previous corner), so the corner has three patches and three faces, the neighbour two, and the mesh
    no boundary singular vertex (main: one)."""
    domain, dec, mesh = _laid_out("spread")
    assert _applied(dec, "spread_over_served_corner_back") == 1
    g = dec.graph
    assert 225.0 < boundary_angle(g, node_at(g, SPREAD)) < 315.0
    a = _moved_to(dec)
    at = tuple(g.get(a, "pos"))
    assert abs(boundary_angle(g, a) - 180.0) < 1e-6
    assert abs(math.dist(SPREAD, at) + math.dist(at, BEFORE) - math.dist(SPREAD, BEFORE)) < 1e-6
    _assert_regular("spread", SPREAD)
    assert g.degree(a, [PATCH_CORNER]) == 2  # (smoothing slides it along the side: no mesh vertex there)
    stats = mesh_stats(mesh, domain)
    assert stats["boundary_singular"] == 0 and stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] > 0.49  # main 0.452


def test_no_spread_that_joins_a_short_boundary_piece_to_a_long_branch(monkeypatch):
    """The other small plan's 274 degree corner is the corner of four patches too, but the spread's quad
    would put the 0.47 boundary piece to the neighbour and the 1.21 branch opposite it in one edge group
    (beyond :data:`~vaultgram.topology.reflex.MAX_RATIO`): no spread, four patches, one boundary singular
    vertex. With the limit at 3 the rebranch moves and the corner has three. (The flip of the thin
    triangle's rebranch, ``flip_over_served_corner``, turned off here, makes the corner regular otherwise:
    test_jagged_valence2.py.)"""
    monkeypatch.setattr(corner_merges, "FLIP_THIN", 0.0)
    domain = domain_from_dict(UNEVEN_PLAN)
    dec = decompose(domain, 0.02)
    assert _applied(dec, "spread_over_served_corner_back") == 0
    assert dec.graph.degree(node_at(dec.graph, UNEVEN), [PATCH_CORNER]) == 4
    assert mesh_stats(mesh_decomposition(dec), domain)["boundary_singular"] == 1
    monkeypatch.setattr(corner_merges, "MAX_RATIO", 3.0)
    dec = decompose(domain, 0.02)
    assert _applied(dec, "spread_over_served_corner_back") == 1
    assert dec.graph.degree(node_at(dec.graph, UNEVEN), [PATCH_CORNER]) == 3
    assert mesh_stats(mesh_decomposition(dec), domain)["boundary_singular"] == 0


def test_without_the_spread_the_corner_keeps_four_patches(monkeypatch):
    """With the moved rebranch refused (``chord_inside`` false in :func:`spread_rebranch`) the 282 degree
    corner keeps its four patches and the mesh its boundary singular vertex, as on main."""
    monkeypatch.setattr(corner_merges, "chord_inside", lambda found, a, b: False)
    domain = domain_from_dict(SPREAD_PLAN)
    dec = decompose(domain, 0.02)
    assert _applied(dec, "spread_over_served_corner_back") == 0
    assert dec.graph.degree(node_at(dec.graph, SPREAD), [PATCH_CORNER]) == 4
    assert mesh_stats(mesh_decomposition(dec), domain)["boundary_singular"] == 1
