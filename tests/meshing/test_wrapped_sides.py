"""Boundary sides sampled by their offset length where a quad patch wraps a turning boundary (paper
§3.2's Coons grids; issue 12 What 4, issue 18): hiroshi_senju_museum's patch 38 wraps a hole's lobe
(turning 73.8 degrees in 4.39 m, a 199 degree vertex at (12.36, 5.88)); by arc length that vertex met
the skeleton side's point straight below it, the grid's columns ran along the hole and the Coons grid
was inverted at 16,000 faces. meshing.weld._wrap_turning_sides resamples such sides uniformly in the
length of the side offset half-way into the patch, where the arc-length grid has a face under
WRAP_FLOOR, the new grid is better and the new samples stay within the chord tolerance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vaultgram.domain import load_domain
from vaultgram.geometry.polylines import arc_lengths, resample_polyline
from vaultgram.meshing import weld as weld_module
from vaultgram.meshing.densities import group_counts
from vaultgram.meshing.layout import edge_groups
from vaultgram.meshing.quality import face_scaled_jacobians, mesh_stats
from vaultgram.meshpipeline import decompose, domain_frame, mesh_domain

from paths import ARCHITECTURE

HIROSHI = ARCHITECTURE / "hiroshi_senju_museum.json"
CORNER = np.array([12.36, 5.88])  # the hole's 199 degree vertex in patch 38


def _hiroshi():
    if not HIROSHI.is_file():
        pytest.skip("shared architecture data not found")
    return load_domain(HIROSHI)


def _corner_patch_worst(domain, faces: int) -> float:
    """The worst face of the raw (unsmoothed) Coons grid of the patch at the hole's 199 degree vertex."""
    with domain_frame(domain):
        layout = edge_groups(decompose(domain))
        mesh = weld_module.weld(layout, group_counts(layout, None, math.sqrt(domain.area / faces)))
    x = np.asarray(mesh.vertices)
    corner = int(np.argmin(np.hypot(*(x - CORNER).T)))
    assert np.hypot(*(x[corner] - CORNER)) < 0.01
    patches = {int(mesh.face_patch[k]) for k, f in enumerate(mesh.faces) if corner in f}
    assert len(patches) == 1  # a boundary vertex inside one patch's side
    sj = face_scaled_jacobians(x, mesh.faces)
    return float(sj[mesh.face_patch == patches.pop()].min())


def test_offset_length_gives_a_reflex_vertex_more_samples():
    """A side of 3 m and 1 m turning 90 degrees right (a patch on its left wraps round the vertex):
    offset 1 m into the patch each segment gains pi / 4 m, so the short segment after the turn gets a
    larger share of the samples (the opposite side, 1 m further out, is longer there). Turning into
    the patch takes length away (at least MIN_WRAP of it stays); a straight side keeps arc length."""
    bent = np.array([[0.0, 0.0], [3.0, 0.0], [3.0, -1.0]])  # right turn at (3, 0), patch on the left
    lengths = weld_module._wrapped_lengths(bent, 2.0, False)  # WRAP_SHARE 0.5 of a 2 m wide patch
    assert np.allclose(lengths, [3.0 + math.pi / 4, 1.0 + math.pi / 4])
    plain, _ = resample_polyline(bent, 8)
    wrapped, _ = resample_polyline(bent, 8, lengths=lengths)
    # by arc length samples 1-6 of 8 lie on the 3 m segment, by offset length 5.43 of 8: 1-5
    assert int((plain[1:-1, 1] == 0).sum()) == 6 and int((wrapped[1:-1, 1] == 0).sum()) == 5
    assert np.allclose(wrapped[[0, -1]], bent[[0, -1]])
    # turning into the patch (reversed: the patch is on the right) takes length away, at least MIN_WRAP
    inward = weld_module._wrapped_lengths(bent, 20.0, True)
    assert np.allclose(inward, weld_module.MIN_WRAP * np.array([3.0, 1.0]))
    straight = np.array([[0.0, 0.0], [1.0, 0.0], [4.0, 0.0]])
    assert np.allclose(weld_module._wrapped_lengths(straight, 2.0, False), np.diff(arc_lengths(straight)))


def test_resampling_in_a_measure_hits_the_anchors():
    poly = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [4.0, 0.0]])
    pts, hit = resample_polyline(poly, 4, anchors=[2], lengths=np.array([1.0, 3.0, 1.0]))
    assert hit == [3]  # the anchor's piece measures 4 of 5: 3 of the 4 subdivisions
    # measure 4/3 and 8/3 fall in the 1 m segment measured 3: x = 1 + 1/9 and 1 + 5/9
    assert np.allclose(pts[:, 0], [0.0, 10.0 / 9.0, 14.0 / 9.0, 2.0, 4.0])


def test_hiroshi_patch_wrapping_the_lobe_is_not_inverted_at_sixteen_thousand_faces():
    """The raw Coons grid of the patch at the 199 degree vertex: -0.041 by arc length (main b86dd39),
    0.663 with the side sampled by its offset length."""
    assert _corner_patch_worst(_hiroshi(), 16000) > 0.5


@pytest.mark.parametrize("faces, floor", [(8000, 0.45), (16000, 0.45), (82000, 0.45)])
def test_hiroshi_at_finer_sizes(faces, floor):
    """Min scaled Jacobian 0.154 / 0.114 at 8,000 / 16,000 faces asked and MeshFoldError at 82,000
    (untangled to 0.0065) on main b86dd39; 0.502 / 0.498 / 0.500 with the wrapped side. No boundary
    singularity, no inverted face."""
    domain = _hiroshi()
    mesh = mesh_domain(domain, target_length=math.sqrt(domain.area / faces))
    stats = mesh_stats(mesh, domain)
    assert stats["inverted_faces"] == 0 and stats["boundary_singular"] == 0
    assert stats["min_scaled_jacobian"] >= floor


def test_hiroshi_default_size_keeps_its_arc_length_samples(monkeypatch):
    """At the default length the wrapped hole side would stray 0.11% of the diagonal from the plan
    (over the 0.1% chord tolerance its count was made for), so it keeps its arc-length samples: the
    mesh is the one without the wrapping."""
    domain = _hiroshi()
    mesh = mesh_domain(domain)
    monkeypatch.setattr(weld_module, "WRAP_FLOOR", -1.0)  # no grid is under it: nothing wrapped
    plain = mesh_domain(domain)
    assert np.array_equal(np.asarray(mesh.vertices), np.asarray(plain.vertices))
