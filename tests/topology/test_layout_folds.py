"""The two layout folds among the 700 saved random plans (issue 12, What 4: "smoothing and
untangling ... rather than failing with a fold"; the clear error only where no valid mesh exists).

Saved random plan 642 (a square turned 45 degrees with an equilateral triangular hole of side 2.07
and a curve): the hole's right tip is a 300 degree corner of the domain. Its quad (214 degrees
there) was split by split_quad_at_reflex_corner with the diagonal to the singularity opposite, which
lies almost on the line of the hole's upper side: 18 and 196 degrees, and the mesh folded in the
196 degree triangle at any density. The split is made only where it leaves no part over 180
degrees; the corner then takes a chord to a side (rules/corners.vgr) like any reflex corner."""

from __future__ import annotations

import pytest

from vaultgram.domain import domain_from_dict
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_decomposition

#: Saved random plan 642 of /work/plans700.json (session 23), meshed at spacing 0.02.
TRIANGLE_HOLE = {
    "name": "random",
    "outer": [[9.47084251771326, 9.470842517713261e-09], [-9.470842721412436e-09, 9.47084251771326],
              [-9.78412900810179, -9.784128619434026e-09], [9.470841561568737e-09, -9.47084251771326]],
    "holes": [[[2.697527427539362, 3.2844947809168623], [0.9012362862303192, 2.247405606939146],
               [0.9012362862303184, 4.321583954894578]]],
    "curves": [[[-5.746083091077161, 0.16638200309940565], [-2.753095985915797, -0.03862577318675223]]]}


@pytest.fixture(scope="module")
def triangle_hole():
    domain = domain_from_dict(TRIANGLE_HOLE)
    dec = decompose(domain, spacing=0.02)
    return domain, dec


def test_no_patch_turns_past_straight_at_the_hole_tip(triangle_hole):
    """A quad mesh gives a patch's corner one face: no patch may turn by 180 degrees or more there.
    On main the hole's right tip (2.69753, 3.28449) was the corner of patches of 86, 18 and 196."""
    _, dec = triangle_hole
    pos = dec.graph.get
    angles = [float(a) for p in dec.patches for c, a in zip(p.corners, p.corner_angles())
              if max(abs(u - v) for u, v in zip(pos(c, "pos"), (2.697527427539362, 3.2844947809168623))) < 1e-6]
    assert len(angles) == 3 and max(angles) < 180, angles
    assert sum(angles) == pytest.approx(300, abs=1e-6)


def test_the_triangular_hole_plan_meshes_without_a_fold(triangle_hole):
    domain, dec = triangle_hole
    stats = mesh_stats(mesh_decomposition(dec), domain)
    assert stats["inverted_faces"] == 0
    assert stats["boundary_singular"] == 0, stats["boundary_singular_angles"]
    assert stats["min_scaled_jacobian"] >= 0.2
