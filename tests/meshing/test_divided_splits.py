"""Splits at wide poles cut into parts (vaultgram.meshing.splits.divided_patterns, issue 12 What 4): a
three-quad split keeps the pole's whole angle in its quad there, and past PART_ANGLE its inner point
lies so near the opposite side that the quads beside it fold; cut by spokes from the pole into parts
of at most PART_ANGLE degrees, each split into three quads, the meshes finer than the default length
stay valid and above 0.3 round the point loads."""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest

from vaultgram.domain import load_domain
from vaultgram.meshing.densities import TARGET_FRACTION, group_counts
from vaultgram.meshing.guards import estimate_mesh
from vaultgram.meshing.layout import edge_groups
from vaultgram.meshing.quality import face_scaled_jacobians, mesh_stats
from vaultgram.meshing.splits import PART_ANGLE, divided_patterns, division, pole_angle, split_patterns
from vaultgram.meshing.weld import weld
from vaultgram.meshpipeline import _welded_and_smoothed, decompose, mesh_domain

from paths import EXAMPLES


def _layout(name):
    domain = load_domain(EXAMPLES / f"{name}.json")
    return domain, edge_groups(decompose(domain))


def _half_target(domain) -> float:
    """Half the default target length: about four times the default's faces."""
    return TARGET_FRACTION * domain.diagonal / 2


def _faces_at(mesh, xy) -> list:
    pole = int(np.argmin(np.linalg.norm(np.asarray(mesh.vertices)[:, :2] - xy, axis=1)))
    assert np.linalg.norm(np.asarray(mesh.vertices)[pole, :2] - xy) < 1e-9
    return [k for k, f in enumerate(mesh.faces) if pole in f]


def _half_length_mesh(domain):
    """The mesh at half the default target length, checked valid and at least 0.3 everywhere."""
    mesh = mesh_domain(domain, target_length=_half_target(domain))
    stats = mesh_stats(mesh, domain)
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= 0.3
    return mesh


def _five_quads_at(mesh, xy) -> list:
    """The faces at the point feature ``xy``, checked to be five quads (a pole, §4.1)."""
    at = _faces_at(mesh, np.asarray(xy, dtype=float))
    assert len(at) == 5 and all(len(mesh.faces[k]) == 4 for k in at)
    return at


def test_division_spreads_even_parts_under_twice_the_pole_count():
    """Every part even, at least 2 and under 2 m, the cuts as even as that allows; None where no
    cut does, and the plain split (no cut) for one part."""
    for m in range(1, 12):
        for n in range(1, 30):
            for parts in (1, 2, 3):
                cuts = division(m, n, parts)
                sizes = np.diff((0, *cuts, n)) if cuts is not None else None
                ok = n % 2 == 0 and n >= 2 * parts and all(
                    2 * ((i + 1) * n // (2 * parts)) - 2 * (i * n // (2 * parts)) < 2 * m for i in range(parts))
                assert (cuts is not None) == ok, (m, n, parts)
                if cuts is not None:
                    assert len(cuts) == parts - 1 and sizes.min() >= 2 and sizes.max() < 2 * m
                    assert not (sizes % 2).any() and sizes.max() - sizes.min() <= 2


def test_square_point_loads_obtuse_splits_are_halved_at_half_the_default_length():
    """The point loads' 155.8 degree triangles, split into three quads, folded at half the default
    target length (10 inverted faces beside the inner points, and the mesh fell back to fans of
    0.045). Halved, each point load keeps five quads (two per wide patch, one in its 48 degree
    patch), each with at most PART_ANGLE degrees there, and the mesh has no face under 0.3."""
    domain, layout = _layout("square_point_loads")
    counts = group_counts(layout, target_length=_half_target(domain))
    divided = divided_patterns(layout, counts)
    wide = {k for k, p in enumerate(layout.patterns) if p.pole is not None and pole_angle(layout, p) > PART_ANGLE}
    assert len(wide) == 4 and divided == {k: 2 for k in wide}
    mesh, x = _welded_and_smoothed(layout, counts, 20, None)  # the split mesh itself, before any fallback
    assert face_scaled_jacobians(x, mesh.faces).min() > 0.25
    assert len(weld(layout, counts).faces) == estimate_mesh(layout, counts).faces
    mesh = _half_length_mesh(domain)
    for xy in domain.points:
        at = _five_quads_at(mesh, xy)
        assert sorted(Counter(int(mesh.face_patch[k]) for k in at).values()) == [1, 2, 2]


def test_fig6_inner_points_wide_fans_split_in_parts_and_stay_poles():
    """fig6_inner_points' inner points are the poles of two triangles of 166.2 and 193.8 degrees,
    too wide for a three-quad split: their fans thinned with the resolution (0.099 at half the default
    target length). Now each is cut into two parts, and since four quads would leave the point
    regular (§4.1: point features are poles) the wider gets a third part: five quads meet there, and
    the mesh has no face under 0.3. At the default length the fans stay (the paper's, §4.1)."""
    domain, layout = _layout("fig6_inner_points")
    assert not divided_patterns(layout, group_counts(layout))
    assert not split_patterns(layout, group_counts(layout))
    counts = group_counts(layout, target_length=_half_target(domain))
    divided = divided_patterns(layout, counts)
    angles = {k: round(pole_angle(layout, layout.patterns[k]), 1) for k in divided}
    assert sorted(angles.values()) == [166.2, 166.2, 193.8, 193.8]
    assert all(divided[k] == (3 if angles[k] > 180 else 2) for k in divided)
    assert len(weld(layout, counts).faces) == estimate_mesh(layout, counts).faces
    mesh = _half_length_mesh(domain)
    for xy in domain.points:
        at = _five_quads_at(mesh, xy)
        x = np.asarray(mesh.vertices)[:, :2]
        for k in at:  # every quad's corner at the point is convex and at most PART_ANGLE wide
            f = list(mesh.faces[k])
            i = f.index(int(np.argmin(np.linalg.norm(x - xy, axis=1))))
            a, b = x[f[(i + 1) % 4]] - x[f[i]], x[f[i - 1]] - x[f[i]]
            assert 0 < math.degrees(math.atan2(a[0] * b[1] - a[1] * b[0], a @ b)) <= PART_ANGLE


@pytest.mark.parametrize("name", ["features_combined", "fig7_curves"])
def test_wide_splits_mesh_above_the_floor_at_half_the_default_length(name):
    """features_combined (two 166-194 degree fans at an inner point) and fig7_curves (147 and 158
    degree splits at curve ends, which folded and fell back to fans): 0.099 and 0.046 at half the
    default target length on main 7aa879d."""
    domain = load_domain(EXAMPLES / f"{name}.json")
    stats = mesh_stats(mesh_domain(domain, target_length=_half_target(domain)), domain)
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= 0.3
