"""Mesh densities (paper §3.2): counts from a target length, designer counts, regions, minimum counts,
the chord constraint, density files and their errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

from vaultgram.errors import VaultgramError
from vaultgram.meshing.densities import DensitySpec, densities_from_dict, group_counts, load_densities


def test_counts_follow_target_length(qwh_layout):
    diag = qwh_layout.decomposition.disc.domain.diagonal
    c1 = group_counts(qwh_layout, target_length=0.05 * diag)
    c2 = group_counts(qwh_layout, target_length=0.025 * diag)
    assert (c1 >= 1).all()
    assert np.allclose(c2 / c1, 2, atol=0.5)
    for g, c in zip(qwh_layout.groups, c2):
        assert c == max(1, round(g.mean_length / (0.025 * diag)))
    cmax = group_counts(qwh_layout, DensitySpec(length_mode="max"), target_length=0.025 * diag)
    assert (cmax >= c2).all()


def test_designer_counts_regions_and_minimum(qwh_layout):
    spec = DensitySpec(target_length=100.0, min_count=3, groups={"0": 7, 1: {"length": 0.5}})
    c = group_counts(qwh_layout, spec)
    assert c[0] == 7
    assert c[1] == max(3, round(qwh_layout.groups[1].mean_length / 0.5))
    rest = np.delete(c, [0, 1])  # huge target length: the minimum, or more where a side is curved
    assert rest.min() == 3 and (rest >= 3).all()


def test_curved_boundary_sides_get_enough_subdivisions(qwh_layout):
    """The chord constraint (CHORD_TOLERANCE): a curved boundary side resampled at its group's count
    stays within the tolerance of the domain's ring, even for a huge target length."""
    from vaultgram.geometry.polylines import chord_deviation, resample_polyline
    from vaultgram.meshing.densities import CHORD_TOLERANCE
    from vaultgram.meshing.layout import kept_points, side_anchors

    c = group_counts(qwh_layout, target_length=100.0)
    disc = qwh_layout.decomposition.disc
    keep = kept_points(disc)
    curved = 0
    for side in qwh_layout.sides:
        if side.boundary and len(side.polyline) > 2:
            n = int(c[qwh_layout.group_of[side.id]])
            pts, _ = resample_polyline(side.polyline, n, side_anchors(side, keep))
            assert chord_deviation(side.polyline, pts) <= CHORD_TOLERANCE * disc.domain.diagonal
            curved += chord_deviation(side.polyline, side.polyline[[0, -1]]) > 0
    assert curved > 0  # the hole's sides are curved
    # a region covering the whole domain sets every group
    region = DensitySpec(regions=((np.array([[-1, -1], [11, -1], [11, 11], [-1, 11.0]]), {"count": 5}),))
    assert (group_counts(qwh_layout, region) == 5).all()
    # a region covering nothing changes nothing
    away = DensitySpec(regions=((np.array([[50, 50], [51, 50], [51, 51.0]]), {"count": 5}),))
    assert (group_counts(qwh_layout, away) == group_counts(qwh_layout)).all()


def test_density_file(tmp_path, qwh_layout):
    path = tmp_path / "d.json"
    path.write_text(json.dumps({"target_length": 1.0, "groups": {"2": 9},
                                "regions": [{"polygon": [[0, 0], [1, 0], [0, 1]], "length": 0.1}]}))
    spec = load_densities(path)
    assert spec.target_length == 1.0 and spec.groups == {"2": 9} and len(spec.regions) == 1
    assert group_counts(qwh_layout, spec)[2] == 9


@pytest.mark.parametrize(
    "data, message",
    [
        ({"groups": {"x": 3}}, "integer"),
        ({"groups": {"99": 3}}, "groups 0 to"),
        ({"groups": {"0": 0}}, "positive integer"),
        ({"groups": {"0": {"count": 2, "length": 1}}}, "count or a length"),
        ({"regions": [{"polygon": [[0, 0], [1, 1]], "count": 2}]}, "at least 3"),
        ({"target_length": -1}, "positive"),
        ({"colour": "red"}, "unknown key"),
    ],
)
def test_bad_densities_raise_clear_errors(qwh_layout, data, message):
    with pytest.raises(VaultgramError, match=message):
        group_counts(qwh_layout, densities_from_dict(data))


def test_bad_target_length(qwh_layout):
    with pytest.raises(VaultgramError, match="target length"):
        group_counts(qwh_layout, target_length=0.0)
