"""Strips of quads (rules/strips.vgr, vaultgram.topology.strips): every strip option is a valid
decomposition that meshes without folds, a strip splits exactly the patches it crosses, each strip
is offered once, and the default decomposition has none."""

from __future__ import annotations

import json
from collections import Counter
from functools import lru_cache

import numpy as np
import pytest
from click.testing import CliRunner

from vaultgram.cli import main
from vaultgram.domain import load_domain
from vaultgram.exploration.evaluate import mesh_metrics
from vaultgram.exploration.program import Scripted, Stepper
from vaultgram.geometry.polygons import signed_area
from vaultgram.geometry.polylines import arc_lengths, point_at_length
from vaultgram.pipeline import decompose, mesh_decomposition
from vaultgram.topology import strips
from vaultgram.topology.decomposition import block_decomposition, decomposition_graph
from vaultgram.topology.patches import half_edge_polyline
from vaultgram.topology.rulebook import load_vault_rulebook

from paths import EXAMPLES

SPACING = 0.05
STARTS = ("start_strip", "split_quad_at_curve_end_to_side")  # the rules that start a strip


@lru_cache(maxsize=None)
def _domain(name):
    return load_domain(EXAMPLES / f"{name}.json")


class _Recording:
    """The default chooser, recording the rules of the options at every choice point."""

    def __init__(self):
        self.rules = []

    def __call__(self, options):
        self.rules.append([o.rule for o in options])
        return 0


@lru_cache(maxsize=None)
def _strip_options(name) -> tuple:
    """(answers, rule) for every option of the strip choice points on the default path."""
    rec = _Recording()
    decompose(_domain(name), SPACING, chooser=rec)
    return tuple(((0,) * i + (k,), rule) for i, rules in enumerate(rec.rules)
                 for k, rule in enumerate(rules) if rule in STARTS)


def _area(domain):
    return abs(signed_area(domain.outer)) - sum(abs(signed_area(h)) for h in domain.holes)


@lru_cache(maxsize=None)
def _skeleton(name):
    return decompose(_domain(name), SPACING).skeleton


def _variant(name, answers, check_invariants=False):
    return block_decomposition(_skeleton(name), load_vault_rulebook(), check_invariants, chooser=Scripted(answers))


@pytest.mark.parametrize("name", ["fig7_curves", "quad_with_hole"])
def test_every_strip_option_tiles_the_domain_with_three_and_four_sided_patches_and_meshes_without_folds(name):
    domain = _domain(name)
    options = _strip_options(name)
    assert {rule for _, rule in options} == ({"start_strip", "split_quad_at_curve_end_to_side"} if name == "fig7_curves"
                                            else {"start_strip"})
    smoothed = set()
    for answers, rule in options:
        dec = _variant(name, answers, check_invariants=True)  # the rulebook's invariants: planar, tiling, Euler
        assert {p.n_sides for p in dec.patches} <= {3, 4}
        assert sum(p.area() for p in dec.patches) == pytest.approx(_area(domain), rel=1e-6)
        g = dec.graph
        assert not any(g.get_edge(e, "strip") for e in g.of_types(["PatchCorner"]))  # every strip crossed
        around = Counter(c for p in dec.patches for c in p.corners)
        assert all(around[n] == 4 for n in g.nodes() if g.node_type(n) == "StripPoint")  # regular, inside
        smooth = 3 if rule not in smoothed else 0  # the raw Coons patches of every option, smoothed once a rule
        smoothed.add(rule)
        stats = mesh_metrics(mesh_decomposition(dec, None, smooth, allow_folds=True), domain)
        assert stats["faces"] > 0 and stats["inverted_faces"] == 0, answers


def _at_start_strip(name):
    """A stepper stopped at the start_strip choice point of the default path."""
    book = load_vault_rulebook()
    sk = _skeleton(name)
    stepper = Stepper(book, decomposition_graph(sk, book), sk.triangulation.disc)
    options = stepper.advance()
    while options and options[1].rule != "start_strip":
        options = stepper.take(0)
    return stepper, options


def _corners_around(graph) -> Counter:
    return Counter(graph.ends(e)[1] for e in graph.of_types(["PatchCorner"]))


@pytest.mark.parametrize("name", ["quad_with_hole", "fig6_inner_points"])
def test_a_strip_splits_each_patch_it_crosses_in_two_and_changes_valences_only_at_its_ends(name):
    stepper, options = _at_start_strip(name)
    g, pc, answers, mark = stepper.graph, stepper.pc, list(stepper.answers), stepper.graph.mark()
    walks = []
    for k in range(1, len(options)):
        g.rollback(mark)  # back at the choice point (the undo journal, as the search does)
        stepper.pc, stepper.answers = pc, list(answers)
        b = options[k].match.binding
        one, two = strips.strip_through(g, b["p"], b["u"], b["e"])
        walks.append(set(one.edges) | set(two.edges))
        crossed = set(one.patches) | set(two.patches)
        sides = Counter(g.get(p, "sides") for p in g.nodes() if g.node_type(p) == "Patch")
        before = _corners_around(g)
        split = Counter(g.get(p, "sides") for p in crossed)
        ends = Counter(w.end for w in {one, two} if w.end is not None)
        stepper.take(k)
        patches = stepper.complete()
        assert Counter(p.n_sides for p in patches) == sides + split  # each crossed patch: two of its sides
        after = Counter(c for p in patches for c in p.corners)
        new = {n for n in after if n not in before}
        assert all(after[n] == before[n] + ends[n] for n in before), k  # old points: +1 at a triangle's end
        assert all(g.node_type(n) == "StripPoint" and after[n] == 4 or after[n] == 2 and ends[n] for n in new), k
    assert all(not (a & c) for i, a in enumerate(walks) for c in walks[i + 1:])  # each strip offered once


def test_every_strip_the_plan_allows_is_offered():
    stepper, options = _at_start_strip("quad_with_hole")
    g = stepper.graph
    offered = set().union(*(_edges(g, o.match.binding) for o in options[1:]))
    possible = set()
    for p in (n for n in g.nodes() if g.node_type(n) == "Patch"):
        for c in strips.patch_sides(g, p).corners:
            e = strips.side_edge(g, p, c)
            walks = strips.strip_through(g, p, c, e) if e >= 0 else None
            if walks and any(g.get(q, "sides") == 4 for w in walks for q in w.patches):
                possible.add(e)
    assert possible and offered == possible


def _edges(g, b):
    one, two = strips.strip_through(g, b["p"], b["u"], b["e"])
    return set(one.edges) | set(two.edges)


def test_a_cut_edge_is_split_halfway_into_two_pieces_that_make_it_up():
    stepper, _ = _at_start_strip("fig7_curves")
    g = stepper.graph
    edges = [e for e in g.of_types(list(strips.SPLITTABLE))]
    assert edges
    for e in edges:
        u, v = g.ends(e)
        poly = half_edge_polyline(g, e, u)
        first, second = np.array(strips.strip_piece(g, e, u)), np.array(strips.strip_piece(g, e, v))
        mid = np.array(strips.strip_point(g, e))
        assert np.allclose(first[-1], mid) and np.allclose(second[-1], mid)
        assert np.allclose(first[0], poly[0]) and np.allclose(second[0], poly[-1])
        length = arc_lengths(poly)[-1]
        fraction = strips.strip_fraction(g, e)  # the middle but at a feature's fan triangle (reflex.fan_foot)
        assert arc_lengths(first)[-1] == pytest.approx(length * fraction)
        assert arc_lengths(second)[-1] == pytest.approx(length * (1.0 - fraction))


def test_a_strip_cuts_an_edge_at_its_stored_foot_and_both_pieces_meet_there():
    """Where a strip cuts an edge is the edge's ``foot`` (rules/schema.vgr's Splittable; place_fan_foot
    stores one off the middle at a point feature's fan triangle): the start rule's new corner and both
    pieces lie at that fraction of the edge, though the rule makes the second piece in another state of
    the graph than the first (worked out from the patches round the edge at each call instead, the two
    pieces of one cut ended at different points: fig7_curves' tiling broke, session 27)."""
    stepper, options = _at_start_strip("fig7_curves")
    g, pc, answers, mark = stepper.graph, stepper.pc, list(stepper.answers), stepper.graph.mark()
    for k in range(1, 4):
        g.rollback(mark)
        stepper.pc, stepper.answers = pc, list(answers)
        e = options[k].match.binding["e"]
        u, v = g.ends(e)
        poly = half_edge_polyline(g, e, u)
        g.set_edge_attr(e, "foot", 0.45)
        assert strips.strip_fraction(g, e) == 0.45
        foot = point_at_length(poly, 0.45 * arc_lengths(poly)[-1])
        stepper.take(k)
        patches = stepper.complete()
        assert sum(p.area() for p in patches) == pytest.approx(_area(_domain("fig7_curves")), rel=1e-6)
        (m,) = [n for n in g.nodes() if g.node_type(n) == "StripPoint" and np.allclose(g.get(n, "pos"), foot)]
        pieces = [g.get_edge(d, "polyline") for d in g.incident(m, ["Diagonal"]) if g.other(d, m) in (u, v)]
        assert len(pieces) == 2 and all(np.allclose(piece[-1], foot) or np.allclose(piece[0], foot)
                                        for piece in pieces)
        lengths = sorted(arc_lengths(np.asarray(piece, dtype=float))[-1] for piece in pieces)
        assert lengths == pytest.approx(sorted([0.45 * arc_lengths(poly)[-1], 0.55 * arc_lengths(poly)[-1]]))


def test_the_halves_of_an_edge_are_kept_by_its_geometry():
    # issue 13: the same edge in another state of the graph finds its halves again (read-only);
    # moved, it is cut anew, at its new middle; rolled back, the old halves again
    stepper, _ = _at_start_strip("fig7_curves")
    g = stepper.graph
    e = next(e for e in g.of_types(list(strips.SPLITTABLE)) if not g.edge_attrs(e).get("polyline"))
    u, v = g.ends(e)
    halves = strips.edge_halves(g, e)
    assert all(not a.flags.writeable for a in halves)
    mark = g.mark()
    g.set_node_attr(g.add_node("StripPoint", {"pos": (0.0, 0.0)}), "pos", (1.0, 1.0))  # a change elsewhere
    assert strips.edge_halves(g, e) is halves
    (x, y) = g.get(v, "pos")
    g.set_node_attr(v, "pos", (x + 2.0, y))
    moved = strips.strip_point(g, e)
    assert moved != tuple(halves[1]) and np.allclose(moved, (np.add(g.get(u, "pos"), (x + 2.0, y))) / 2)
    g.rollback(mark)
    assert strips.edge_halves(g, e) is halves


def test_patch_sides_share_the_prepared_polygon_of_their_face():
    stepper, _ = _at_start_strip("fig7_curves")
    g = stepper.graph
    sides = [strips.patch_sides(g, p) for p in g.of_types(["Patch"])]
    assert sides and all(s is not None for s in sides)
    for s in sides:
        assert s.polygon is s.face.polygon and s.polygon.area == pytest.approx(signed_area(s.face.outline))
        assert s.polygon.contains(s.polygon.representative_point())


def test_figure_8_to_the_side_makes_the_curve_end_a_triangle_pole_and_carries_the_strip_on():
    for answers, rule in _strip_options("fig7_curves"):
        if rule != "split_quad_at_curve_end_to_side":
            continue
        dec = _variant("fig7_curves", answers)
        g = dec.graph
        ends = [n for n in g.nodes() if g.node_type(n) == "CurveExtremity"]
        poles = {g.ends(e)[1] for e in g.of_types(["PatchCorner"]) if g.get_edge(e, "pole")}
        cut = [n for n in g.nodes() if g.node_type(n) == "StripPoint"]
        assert cut and any(x in poles for x in ends)
        assert any(g.other(e, x) in cut for x in ends for e in g.incident(x, ["Diagonal"]))


def test_the_default_decomposition_has_strips_only_from_curve_ends():
    """No choice point starts a strip by default; the only strips are those started at a curve's free
    end (rules/curves.vgr): each strip point is joined by a diagonal to the end it starts from. fig7's
    curve x = 5 from y = 7.5 to 9 has one straight beyond each end (the patches wrapped under it,
    split_triangle_under_curve_tip); since session 27 its end (1, 1) starts one on each side of the
    curve y = x, mirror images, across the branch bending round it to the wall (the sliver step,
    split_quad_at_curve_end_to_side(sliver = 30)). quad_with_hole has none."""
    for name in ("fig7_curves", "quad_with_hole"):
        dec = decompose(_domain(name), SPACING)
        g = dec.graph
        cut = [n for n in g.nodes() if g.node_type(n) == "StripPoint"]
        assert all(r.applications == 0 for r in dec.reports if r.step.startswith("{ absorb_strip_point"))
        ends = set(g.of_types(["CurveExtremity"]))
        starts = [{g.other(e, n) for e in g.incident(n, ["Diagonal"])} & ends for n in cut]
        assert all(len(s) == 1 for s in starts)
        at = {tuple(np.round(g.get(x, "pos"), 6)) for s in starts for x in s}
        assert at == ({(5.0, 7.5), (5.0, 9.0), (1.0, 1.0)} if name == "fig7_curves" else set())
        origin = [np.asarray(g.get(next(iter(s)), "pos")) for s in starts]
        beyond = [np.asarray(g.get(n, "pos")) for n, o in zip(cut, origin) if o[0] == pytest.approx(5.0)]
        side = [np.asarray(g.get(n, "pos")) for n, o in zip(cut, origin) if np.allclose(o, 1.0)]
        assert len(beyond) == len(side) == (2 if name == "fig7_curves" else 0)
        assert all(p[0] == pytest.approx(5.0) for p in beyond)
        assert not side or np.allclose(side[0], side[1][::-1], atol=1e-6)


def test_explore_offers_the_strips_of_a_plan_without_other_choices_and_replays_them(tmp_path):
    domain = str(EXAMPLES / "l_shape.json")
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["explore", domain, "--out", str(out), "--spacing", str(SPACING), "--limit", "8",
                                       "--smooth", "3"])
    assert result.exit_code == 0, result.output
    variants = json.loads((out / "variants.json").read_text())["variants"]
    assert len(variants) == 3  # the rectangles, and a strip across each of the two chords
    assert sorted(v["metrics"]["patches"] for v in variants) == [3, 5, 5]
    assert all(v["metrics"]["inverted_faces"] == 0 and v["metrics"]["patches_by_sides"]["3"] == 0 for v in variants)
    space = json.loads((out / "state_space.json").read_text())
    strip = next(v for v in space["variants"] if v["metrics"]["patches"] == 5)
    result = CliRunner().invoke(main, ["replay", domain, str(out / "state_space.json"), "--variant", str(strip["id"]),
                                       "--out", str(tmp_path / "replayed")])
    assert result.exit_code == 0, result.output
    for name in ("decomposition.json", "patches.json", "mesh.json"):
        assert (tmp_path / "replayed" / name).read_bytes() == (out / strip["folder"] / name).read_bytes()
