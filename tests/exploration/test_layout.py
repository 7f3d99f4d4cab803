"""Layout hashes and the exact check: relabelled copies alike, mirror images and other layouts apart."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from vaultgram.domain import load_domain
from vaultgram.exploration.layout import PatchLayout, isomorphic, layout_of, same_layout
from vaultgram.pipeline import decompose

from paths import ARCHITECTURE, EXAMPLES


@pytest.fixture(scope="module")
def layout() -> PatchLayout:
    dec = decompose(load_domain(EXAMPLES / "fig5_boundary_points.json"), 0.05)
    return layout_of(dec.graph, list(dec.patches))


def relabelled(layout: PatchLayout, seed: int) -> PatchLayout:
    """The same layout with its points and patches renumbered, its darts listed in another order and
    each patch's cycle started at another corner (dart order is what the arrays index)."""
    rng = np.random.default_rng(seed)
    n_points, n_patches, n_darts = layout.size(), len(layout.patch_sides), len(layout.dart_point)
    points, patches, darts = rng.permutation(n_points), rng.permutation(n_patches), rng.permutation(n_darts)
    new_of_dart = np.empty(n_darts, dtype=np.int64)
    new_of_dart[darts] = np.arange(n_darts)  # old dart darts[i] becomes dart i
    labels = [None] * n_points
    for old, new in enumerate(points):
        labels[new] = layout.point_labels[old]
    sides = [None] * n_patches
    for old, new in enumerate(patches):
        sides[new] = layout.patch_sides[old]
    return PatchLayout(tuple(labels), tuple(sides), points[layout.dart_point[darts]], patches[layout.dart_patch[darts]],
                       new_of_dart[layout.dart_next[darts]], layout.dart_pole[darts])


def mirrored(layout: PatchLayout) -> PatchLayout:
    """Every patch's cycle reversed: the mirror image."""
    prev = np.empty_like(layout.dart_next)
    prev[layout.dart_next] = np.arange(len(prev))
    return dataclasses.replace(layout, dart_next=prev)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_relabelled_and_reordered_copies_hash_alike(layout, seed):
    copy = relabelled(layout, seed)
    assert copy.hash == layout.hash
    assert same_layout(layout, copy) and isomorphic(layout, copy)


def test_a_patch_cycle_started_elsewhere_changes_nothing(layout):
    starts = np.flatnonzero(layout.dart_patch == 0)  # shift which dart of patch 0 comes first in the arrays
    order = np.arange(len(layout.dart_point))
    order[starts] = np.roll(starts, 1)
    inverse = np.argsort(order)
    copy = PatchLayout(layout.point_labels, layout.patch_sides, layout.dart_point[order], layout.dart_patch[order],
                       inverse[layout.dart_next[order]], layout.dart_pole[order])
    assert copy.hash == layout.hash and same_layout(layout, copy)


def test_mirror_images_are_distinct_variants():
    path = ARCHITECTURE / "two_holes_five_points.json"
    if not path.is_file():
        pytest.skip("shared architecture data not found")
    dec = decompose(load_domain(path), 0.05)
    layout = layout_of(dec.graph, list(dec.patches))
    mirror = mirrored(layout)
    assert not isomorphic(layout, mirror)  # the free plan has no symmetry
    assert mirror.hash != layout.hash and not same_layout(layout, mirror)


def test_a_symmetric_plan_merges_its_mirror_image(layout):
    """fig5 is symmetric: its layout and the layout's mirror image are one variant."""
    assert isomorphic(layout, mirrored(layout)) and same_layout(layout, mirrored(layout))


def test_another_label_is_another_layout(layout):
    labels = list(layout.point_labels)
    labels[0] = labels[0] + "*"
    other = dataclasses.replace(layout, point_labels=tuple(labels))
    assert other.hash != layout.hash and not same_layout(layout, other)


def _grid(labels=("Singularity",) * 9) -> PatchLayout:
    """A 2 x 2 grid of quads (points 0..8 row by row): symmetric, so refinement leaves shared colours."""
    quads = [(0, 1, 4, 3), (1, 2, 5, 4), (3, 4, 7, 6), (4, 5, 8, 7)]
    point = [c for q in quads for c in q]
    nxt = [4 * k + (i + 1) % 4 for k in range(4) for i in range(4)]
    return PatchLayout(tuple(labels), (4, 4, 4, 4), np.array(point), np.repeat(np.arange(4), 4), np.array(nxt),
                       np.zeros(16, dtype=bool))


def test_symmetric_layouts_are_decided_by_vf2():
    grid = _grid()
    assert len(np.unique(grid.colours[0])) < 16  # not every dart coloured apart: the VF2 path
    assert same_layout(grid, relabelled(grid, 3))
    corner_moved = _grid(("Corner",) + ("Singularity",) * 8)
    assert not same_layout(grid, corner_moved)


def test_equal_hashes_of_different_layouts_are_told_apart(monkeypatch, layout):
    """A forced collision (every hash equal) is refuted by the exact check."""
    labels = list(layout.point_labels)
    labels[0] = labels[0] + "*"
    other = dataclasses.replace(layout, point_labels=tuple(labels))
    monkeypatch.setattr(PatchLayout, "hash", property(lambda self: "0" * 16))
    assert layout.hash == other.hash
    assert not same_layout(layout, other)
    assert same_layout(layout, relabelled(layout, 5))
