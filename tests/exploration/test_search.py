"""The bounded search: distinct, valid, meshed variants on the acceptance plans; bounds; the journal."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from exploration.conftest import SPACING, domain_of

from vaultgram.errors import VaultgramError
from vaultgram.exploration.layout import isomorphic, layout_of
from vaultgram.exploration.search import layout_cost, search
from vaultgram.geometry.polygons import signed_area
from vaultgram.pipeline import decompose
from vaultgram.topology.decomposition import decomposition_graph
from vaultgram.topology.rulebook import load_vault_rulebook

ACCEPTANCE = ["two_holes_five_points", "armadillo_vault_plan", "fig5_boundary_points", "fig6_inner_points",
              "fig7_curves", "features_combined"]  # the shared plans and every example with features


@pytest.mark.parametrize("name", ACCEPTANCE)
def test_at_least_five_variants_no_two_isomorphic(explorations, name):
    exp = explorations(name)
    layouts = []
    for v in exp.result.variants:
        dec = decompose(exp.domain, SPACING, chooser=_scripted(exp, v))
        layouts.append(layout_of(dec.graph, list(dec.patches)))
    assert len(layouts) >= 5
    assert not any(isomorphic(a, b) for a, b in itertools.combinations(layouts, 2))  # networkx's exact VF2


def _scripted(exp, variant):
    from vaultgram.exploration.program import Scripted

    return Scripted(exp.result.states[variant.states[0]].answers)


@pytest.mark.parametrize("name", ACCEPTANCE)
def test_every_variant_tiles_the_domain_with_three_and_four_sided_patches_and_meshes(explorations, name):
    exp = explorations(name)
    domain_area = abs(signed_area(exp.domain.outer)) - sum(abs(signed_area(h)) for h in exp.domain.holes)
    for v, ev in zip(exp.result.variants, exp.evaluations):
        dec = decompose(exp.domain, SPACING, chooser=_scripted(exp, v))
        assert {p.n_sides for p in dec.patches} <= {3, 4}
        assert sum(p.area() for p in dec.patches) == pytest.approx(domain_area, rel=1e-6)
        assert "error" not in ev.metrics and ev.metrics["faces"] > 0 and ev.metrics["inverted_faces"] == 0
        assert ev.metrics["patches_by_sides"] == {"3": sum(p.n_sides == 3 for p in dec.patches),
                                                  "4": sum(p.n_sides == 4 for p in dec.patches)}


def test_every_path_to_a_variant_is_kept_and_first_options_inherit(explorations):
    result = explorations("two_holes_five_points").result
    reached = sorted(s for v in result.variants for s in v.states)
    assert reached == [s.id for s in result.states if s.variant is not None]
    for state in result.states[1:]:
        parent = result.states[state.parent]
        assert state.depth == parent.depth + 1 and state.answers[:len(parent.answers)] == parent.answers
        if state.option["choice"] == 0:
            assert state.variant == parent.variant


def _start(name):
    domain = domain_of(name)
    book = load_vault_rulebook()
    sk = decompose(domain, SPACING).skeleton
    return book, decomposition_graph(sk, book), sk.triangulation.disc


def test_the_search_leaves_the_graph_as_it_found_it_and_keeps_its_bounds():
    book, graph, disc = _start("fig5_boundary_points")
    before = graph.snapshot()
    result = search(book, graph, disc, limit=7, depth=8)
    assert graph.snapshot() == before
    assert len(result.states) == 7 and max(s.depth for s in result.states) <= 8
    shallow = search(book, graph, disc, limit=50, depth=1)
    assert max(s.depth for s in shallow.states) == 1 and len(shallow.states) == 1 + len(shallow.states[0].options)
    assert len(search(book, graph, disc, limit=50, depth=0).states) == 1


def test_a_seed_visits_other_options_first_reproducibly():
    book, graph, disc = _start("fig5_boundary_points")
    runs = [[s.answers for s in search(book, graph, disc, limit=5, depth=8, seed=seed).states] for seed in (3, 3, None)]
    assert runs[0] == runs[1]
    assert sorted(runs[0]) != runs[0] or runs[0] != runs[2]
    assert np.all([len(a) >= 0 for a in runs[0]])


def test_best_first_expands_the_least_costly_state_of_its_frontier():
    book, graph, disc = _start("fig7_curves")
    result = search(book, graph, disc, limit=20, order="best")
    cost = {s.id: layout_cost(result.variants[s.variant].layout) if s.variant is not None else float("inf")
            for s in result.states}
    done: set[int] = set()
    for state_id, made in result.expanded:
        waiting = [s for s in result.states[:made] if s.id not in done and s.id != state_id and s.options != []]
        assert all((cost[s.id], s.id) > (cost[state_id], state_id) for s in waiting)
        done.add(state_id)
    assert len(result.states) == 20 and len(result.expanded) >= 2


def test_best_first_and_breadth_first_cover_the_same_whole_space():
    book, graph, disc = _start("fig6_inner_points")
    found = {}
    for order in ("breadth", "best"):
        result = search(book, graph, disc, limit=1000, order=order)
        found[order] = sorted(v.hash for v in result.variants)
    assert found["breadth"] == found["best"] and len(found["best"]) >= 5


def test_an_unknown_order_is_refused():
    book, graph, disc = _start("fig5_boundary_points")
    with pytest.raises(VaultgramError, match="--order"):
        search(book, graph, disc, order="depth")
