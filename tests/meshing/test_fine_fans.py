"""Fans at point features on meshes finer than the default (issues 12 and 18): a finer target length
gives a fan more triangles, which share the pole's angle ever more thinly; beyond its count at the
default length the fan is split into quads (vaultgram.meshing.splits), and a point feature that the
splits would leave regular keeps two quads of one patch (a halved split) instead of a thin fan."""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest

from vaultgram.domain import load_domain
from vaultgram.meshing.densities import group_counts
from vaultgram.meshing.guards import estimate_mesh
from vaultgram.meshing.layout import edge_groups
from vaultgram.meshing.quality import mesh_stats
from vaultgram.meshing.splits import divided_patterns, split_patterns
from vaultgram.meshing.weld import weld
from vaultgram.meshpipeline import decompose, mesh_domain

from paths import ARCHITECTURE


def _plan(name):
    path = ARCHITECTURE / f"{name}.json"
    if not path.is_file():
        pytest.skip("shared architecture data not found")
    return load_domain(path)


def _target(domain, faces: int) -> float:
    """The target length of about ``faces`` faces (issue 18's sizes)."""
    return math.sqrt(domain.area / faces)


def _inner_point_fans(layout):
    """The three-sided patterns whose pole is an inner point feature."""
    graph = layout.decomposition.graph
    return [k for k, p in enumerate(layout.patterns)
            if p.pole is not None and graph.node_type(p.corners[p.pole]) == "FeaturePoint"]


@pytest.mark.parametrize("name", ["rv_lips_pattern", "armadillo_vault_plan", "two_holes_five_points"])
def test_point_feature_fans_do_not_thin_at_eight_thousand_faces(name):
    """At 8,000 faces asked, no fold and a worst face of at least 0.3 (main b7eedca: 0.043, 0.090 and
    0.051, fans of 40 to 121 triangles round the inner point features)."""
    domain = _plan(name)
    mesh = mesh_domain(domain, target_length=_target(domain, 8000))  # raises on a fold
    stats = mesh_stats(mesh, domain)
    assert stats["inverted_faces"] == 0
    assert stats["min_scaled_jacobian"] >= 0.3


def test_point_feature_fans_stay_fans_at_the_default_length():
    """At the default target length the inner point's fans are the paper's (§4.1: many load paths),
    thin as they are (rv_lips_pattern: 9 triangles in each of three 120 degree patches); at 8,000
    faces every one is split and the pole keeps one quad of each (three: still a pole)."""
    layout = edge_groups(decompose(_plan("rv_lips_pattern")))
    fans = _inner_point_fans(layout)
    assert len(fans) == 3
    assert not set(fans) & split_patterns(layout, group_counts(layout))
    fine = group_counts(layout, target_length=_target(layout.decomposition.disc.domain, 8000))
    assert set(fans) <= split_patterns(layout, fine)
    mesh = weld(layout, fine)
    pole = mesh.vertices.tolist().index(list(layout.decomposition.graph.get(
        layout.patterns[fans[0]].corners[layout.patterns[fans[0]].pole], "pos")))
    assert sum(pole in f for f in mesh.faces) == 3
    assert all(len(f) == 4 for f in mesh.faces if pole in f)


def test_a_point_feature_the_splits_would_leave_regular_keeps_two_quads_of_a_halved_patch():
    """two_holes_five_points' inner point (7.09, 5.56) is the pole of four triangles: split, it would
    be regular (four quads), against §4.1. At 8,000 faces its widest patch is halved instead of one
    fan kept (that fan: 18 triangles in 112 degrees, 0.125): five quads meet there, two of them in the
    halved patch, each with about half its angle; the mesh's face count is the guard's estimate."""
    domain = _plan("two_holes_five_points")
    layout = edge_groups(decompose(domain))
    counts = group_counts(layout, target_length=_target(domain, 8000))
    fans = _inner_point_fans(layout)
    halved = set(divided_patterns(layout, counts)) & set(fans)
    assert len(fans) == 4 and len(halved) == 1 and set(fans) <= split_patterns(layout, counts)
    mesh = weld(layout, counts)
    assert len(mesh.faces) == estimate_mesh(layout, counts).faces
    pat = layout.patterns[next(iter(halved))]
    xy = np.asarray(layout.decomposition.graph.get(pat.corners[pat.pole], "pos"), dtype=float)
    pole = int(np.argmin(np.linalg.norm(mesh.vertices - xy, axis=1)))
    at_pole = [k for k, f in enumerate(mesh.faces) if pole in f]
    assert len(at_pole) == 5 and all(len(mesh.faces[k]) == 4 for k in at_pole)
    assert Counter(int(mesh.face_patch[k]) for k in at_pole)[pat.patch] == 2
    # inside the halved patch, two vertices of three faces (its halves' inner points), the rest four
    faces_at = Counter(v for f in mesh.faces for v in f)
    own = Counter(v for k, f in enumerate(mesh.faces) if mesh.face_patch[k] == pat.patch for v in f)
    inside = [v for v in own if own[v] == faces_at[v] and not mesh.boundary[v] and v != pole]
    assert sorted(Counter(own[v] for v in inside).items())[:1] == [(3, 2)]


def test_halving_leaves_the_default_meshes_alone():
    """At the default length no patch of the plans is halved (a fan kept at a point feature is no
    thinner there than the default makes it). Splits at poles wider than PART_ANGLE are cut into parts
    at any length (fig7_curves' 147 degree curve end: tests/meshing/test_divided_splits.py); these
    plans have none at the default."""
    for name in ("two_holes_five_points", "armadillo_vault_plan", "rv_lips_pattern"):
        layout = edge_groups(decompose(_plan(name)))
        assert not divided_patterns(layout, group_counts(layout))
