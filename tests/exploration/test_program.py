"""The decomposition program: choice steps, the scripted chooser, stopping and resuming at choice points."""

from __future__ import annotations

import pytest

from vaultgram.domain import load_domain
from vaultgram.engine.rulebook import describe_step
from vaultgram.exploration.program import Scripted, Stepper, choice_steps, decomposition_program, noop_by_default
from vaultgram.pipeline import decompose
from vaultgram.topology.decomposition import decomposition_graph
from vaultgram.topology.rulebook import load_vault_rulebook

from paths import EXAMPLES


def test_the_bundled_rulebook_has_choice_points():
    steps = choice_steps(load_vault_rulebook())
    assert any("keep_quad_at_feature" in s for s in steps) and any("keep_close_singularities" in s for s in steps)
    assert all(s.startswith("choose ") for s in steps)


def test_the_program_runs_topology_then_the_patch_step_then_patching():
    program = decomposition_program(load_vault_rulebook())
    strategies = [i.strategy for i in program]
    first_patch = strategies.index("patch nodes")
    assert set(strategies[:first_patch]) == {"topology", "curve_topology", "reflex_corners"}
    # strip: run by both; reflex_corner_patches: run by patching (rules/corners.vgr)
    assert set(strategies[first_patch + 1:]) == {"curve_patching", "patching", "strip", "reflex_corner_patches"}


def test_no_answers_is_the_default_decomposition():
    domain = load_domain(EXAMPLES / "fig5_boundary_points.json")
    assert decompose(domain, 0.05, chooser=Scripted([])).to_json() == decompose(domain, 0.05).to_json()


def test_an_answer_out_of_range_is_refused():
    with pytest.raises(IndexError, match="choice 3 at choice point 0, which has 2 options"):
        Scripted([3])(["a", "b"])


def test_the_stepper_stops_at_choice_points_and_its_answers_replay():
    domain = load_domain(EXAMPLES / "fig5_boundary_points.json")
    book = load_vault_rulebook()
    dec = decompose(domain, 0.05)
    stepper = Stepper(book, decomposition_graph(dec.skeleton, book), dec.disc)
    options = stepper.advance()
    assert len(options) >= 2 and stepper.program[stepper.pc].step.choose
    options = stepper.take(1)  # the second option at the first choice point, then on to the next
    patches = stepper.complete()
    replayed = decompose(domain, 0.05, chooser=Scripted(stepper.answers))
    corners = sorted(map(sorted, (p.corners for p in patches)))
    assert corners == sorted(map(sorted, (p.corners for p in replayed.patches)))
    assert len(patches) != len(dec.patches)  # a quad kept instead of split


def test_only_the_steps_whose_first_option_is_leave_are_skipped_by_complete():
    book = load_vault_rulebook()
    program = decomposition_program(book)
    skipped = [describe_step(i.step) for i in program if i.noop_by_default]
    assert skipped and all(s.startswith("choose { leave, ") and s.endswith(" once") for s in skipped)
    assert not any(noop_by_default(book, i.step) for i in program if i.step is not None and not i.step.choose)


@pytest.mark.parametrize("name", ["fig6_inner_points", "fig7_curves"])
def test_complete_skipping_the_no_op_steps_makes_the_default_decomposition(name):
    domain = load_domain(EXAMPLES / f"{name}.json")
    book = load_vault_rulebook()
    dec = decompose(domain, 0.05)
    stepper = Stepper(book, decomposition_graph(dec.skeleton, book), dec.disc)
    patches = stepper.complete()
    assert sorted(p.corners for p in patches) == sorted(p.corners for p in dec.patches)
    assert stepper.graph.snapshot() == dec.graph.snapshot()


def test_a_stepper_that_defers_options_stops_at_the_same_choice_points():
    domain = load_domain(EXAMPLES / "fig5_boundary_points.json")
    book = load_vault_rulebook()
    dec = decompose(domain, 0.05)
    full = Stepper(book, decomposition_graph(dec.skeleton, book), dec.disc)
    lazy = Stepper(book, decomposition_graph(dec.skeleton, book), dec.disc, defer_options=True)
    options, deferred = full.advance(), lazy.advance()
    assert deferred is None  # the first choice point is at the start of its step: not searched
    for _ in range(3):  # a later one may come inside a fixpoint step, with its options found
        assert (lazy.pc, lazy.answers) == (full.pc, full.answers)
        found = lazy.options() if deferred is None else deferred  # nothing applied: still stopped
        assert found == options and lazy.pc == full.pc and lazy.graph.snapshot() == full.graph.snapshot()
        options, deferred = full.take(1), lazy.take(1)
        assert lazy.records() == full.records()
