"""A reflex corner's chord kept while the patches it read are untouched (issue 18:
:func:`vaultgram.topology.reflex._kept_chord`, :class:`vaultgram.topology.statecache.Untouched`), and the
fixpoint's lazy match sets (:mod:`vaultgram.engine.incremental`) that ask for it less often.

Each kept chord must be the one :func:`~vaultgram.topology.reflex.choose_chord` works out afresh in that
state of the graph (after every rewrite of a decomposition, after a change of a patch's corner and after
the change is rolled back), and far fewer are worked out than the rules ask for. A hand-made plan: a
strip 40 long and 6 wide whose top side has eight notches (reflex corners of 263-290 degrees, regular
valence 4: each takes a chord and a strip across the strip), so that a chord's strip changes a few
patches and the other corners keep theirs.
"""

from __future__ import annotations

from collections import Counter

import pytest

from vaultgram.domain import domain_from_dict
from vaultgram.engine import strategy
from vaultgram.engine.incremental import MatchSet
from vaultgram.geometry.polygons import regular_valence
from vaultgram.meshpipeline import decompose
from vaultgram.testing.chords import chord_checks
from vaultgram.testing.jagged import jagged_plans
from vaultgram.topology import reflex
from vaultgram.topology.corners import boundary_angle
from vaultgram.topology.strips import patch_sides
from vaultgram.topology.types import PATCH_CORNER

COMB = [(0.0, 0.0), (20.0, -1.0), (40.0, 0.0), (40.0, 6.0), (37.0, 2.5), (35.0, 6.0), (32.5, 3.0), (30.0, 6.0),
        (27.5, 3.6), (25.0, 6.0), (22.5, 3.2), (20.0, 6.5), (17.5, 3.2), (15.0, 6.0), (12.5, 3.8), (10.0, 6.0),
        (7.5, 3.1), (5.0, 6.0), (2.5, 3.5), (0.0, 6.0)]


def _comb():
    return domain_from_dict({"outer": [list(p) for p in COMB]}, "comb")


@pytest.fixture
def checked(monkeypatch) -> Counter:
    """Counts of the chords the rules asked for (``asked``, once per corner and state) and of those
    :func:`~vaultgram.topology.reflex.choose_chord` worked out (``worked out``); every chord asked for is
    compared with a fresh one (``differ`` counts those that are not the same)."""
    counts: Counter = Counter()
    worked_out, asked = chord_checks(counts)
    monkeypatch.setattr(reflex, "choose_chord", worked_out)
    monkeypatch.setattr(reflex, "_kept_chord", asked)
    return counts


def _reflex_corners(g) -> list[int]:
    """The boundary vertices of ``g`` whose angle asks for four faces or more."""
    return [n for n in g.nodes() if g.schema.is_subtype(g.node_type(n), "BoundaryVertex")
            and regular_valence(boundary_angle(g, n)) >= 4]


@pytest.mark.parametrize("name", ["comb", "jagged_1"])
def test_kept_chords_are_the_fresh_ones(checked, name):
    """After every rewrite of the decomposition, each corner's kept chord is the fresh one, and some are
    kept (comb: 12 worked out for 22 asked; jagged_1 138 for 353). Every notch of the comb becomes the
    corner of three patches (its chord taken)."""
    domain = _comb() if name == "comb" else domain_from_dict(jagged_plans()[name], name)
    g = decompose(domain).graph
    assert checked["asked"] > 0 and checked["differ"] == 0, checked
    assert checked["worked out"] < 0.75 * checked["asked"], checked
    if name == "comb":
        corners = _reflex_corners(g)
        assert len(corners) == 8 and all(g.degree(r, [PATCH_CORNER]) == 3 for r in corners)


def test_fewer_chords_are_worked_out(checked, monkeypatch):
    """The comb's decomposition works out 12 chords (``choose_chord`` calls); kept per state of the graph
    only, as on main, 22 (every one asked for); with the eager match sets of main, which re-match the chord
    rules after every step of a strip, 153."""
    decompose(_comb())
    assert checked["differ"] == 0 and checked["worked out"] <= 14 and checked["asked"] >= 20, checked
    lazy = checked["worked out"]
    monkeypatch.setattr(reflex, "_kept_chord", lambda graph, r: reflex.choose_chord(graph, r))
    checked.clear()
    decompose(_comb())
    per_state = checked["worked out"]
    monkeypatch.setattr(strategy, "MatchSet", lambda matcher, lazy=False: MatchSet(matcher))
    checked.clear()
    decompose(_comb())
    assert per_state >= lazy + 8 and checked["worked out"] >= 10 * lazy, (lazy, per_state, checked)


def test_a_moved_corner_drops_the_chords_that_read_it(monkeypatch):
    """On the comb's decomposed graph: moving the far corner of one notch's patch drops the kept chords
    whose patches have it (worked out again: the fresh ones there), keeps the others (not worked out
    again), and after the move is rolled back every chord is the first one again."""
    g = decompose(_comb()).graph
    corners = _reflex_corners(g)
    first = {r: reflex._once(g, reflex.choose_chord, r) for r in corners}
    r0 = corners[0]
    patch = min(g.ends(e)[0] for e in g.incident(r0, [PATCH_CORNER]))
    found = patch_sides(g, patch)
    far = found.corners[(found.corners.index(r0) + 2) % len(found.corners)]
    reading = {r for r in corners if any(far in patch_sides(g, g.ends(e)[0]).corners
                                         for e in g.incident(r, [PATCH_CORNER]))}
    worked = Counter()
    fresh = reflex.choose_chord
    monkeypatch.setattr(reflex, "choose_chord", lambda graph, r: worked.update([r]) or fresh(graph, r))
    mark = g.mark()
    x, y = g.get(far, "pos")
    g.set_node_attr(far, "pos", (x + 0.4, y - 0.3))
    moved = {r: reflex._once(g, reflex.choose_chord, r) for r in corners}
    assert moved == {r: fresh(g, r) for r in corners}
    assert r0 in worked and reading <= set(worked) and len(worked) < len(corners), (worked, reading)
    g.rollback(mark)
    worked.clear()
    assert {r: reflex._once(g, reflex.choose_chord, r) for r in corners} == first
    assert reading <= set(worked) and len(worked) < len(corners), worked
