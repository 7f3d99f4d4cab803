"""Reflex chords checked as the rules ask for them (issue 18: the chord a corner keeps while the patches it
read are untouched, :func:`vaultgram.topology.reflex._kept_chord`, must be the one worked out afresh).

Used by ``tests/topology/test_chord_cache.py`` and ``benchmarks/decompose_time.py --check-chords``.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable

from vaultgram.topology import reflex


def chord_checks(counts: Counter) -> tuple[Callable, Callable]:
    """Stand-ins for :func:`~vaultgram.topology.reflex.choose_chord` and ``reflex._kept_chord`` that count,
    in ``counts``, the chords worked out (``worked out``) and asked for (``asked``, once per corner and
    state), and compare every chord asked for with a fresh one (``differ``: those that are not the same).
    Put them in place of the two (by monkeypatching, or assignment in a script) before the rules run.
    """
    fresh, kept = reflex.choose_chord, reflex._kept_chord

    def worked_out(graph, r):
        counts["worked out"] += 1
        return fresh(graph, r)

    def asked(graph, r):
        got = kept(graph, r)
        counts["asked"] += 1
        counts["differ"] += got != fresh(graph, r)
        return got

    return worked_out, asked
