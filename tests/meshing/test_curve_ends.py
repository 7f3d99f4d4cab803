"""Curve free ends whose two triangles share their 360 degrees (§4.2, issue 12 What 4): the wide step
of ``split_triangle_under_curve_tip`` (rules/curves.vgr) halves a triangle of 165 to 195 degrees at the
end, so that the mesher meshes each half as three quads (vaultgram.meshing.splits) instead of a fan of
thin triangles."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vaultgram.domain import domain_from_dict
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_domain
from vaultgram.topology.functions import patch_angle, patch_angle_split
from vaultgram.topology.types import PATCH, PATCH_CORNER

#: Saved random plan 278 of the 700 (benchmarks/reliability.py, seed 17): an octagon with a boundary point and a short
#: curve inside a lens of the skeleton. On main 16e0c9d the curve's end (2.442, -1.418) was the pole of
#: two triangles of 134 and 195 degrees, 24 and 16 triangles: 42 faces, min scaled Jacobian 0.098.
PLAN_278 = {
    "outer": [[8.79469818809903, 1.350376176415134], [5.032503849038097, 6.858264017604828],
              [-0.9067076701216029, 5.90518437960247], [-4.031153005175167, 2.958007006223486],
              [-5.930498926629401, -0.910594575674334], [-5.324732953336218, -7.256511969523986],
              [1.271076297100863, -8.27823579998645], [4.031153005175167, -2.9580070062234864]],
    "points": [[6.987383552479692, 3.996301774510803]],
    "curves": [[[2.4420538894201655, -1.417652450586072], [3.4875767834919227, 0.27204537074778457]]],
}
END = (2.4421, -1.4177)
WIDE_STEP = "wide = true"


def _faces_at(mesh, point) -> int:
    """The number of mesh faces at the vertex at ``point``."""
    v = int(np.argmin(np.hypot(*(mesh.vertices[:, :2] - np.asarray(point)).T)))
    return sum(v in f for f in mesh.faces)


def test_a_curve_end_between_two_wide_triangles_keeps_few_faces():
    """The triangle of 195 degrees at plan 278's curve end is split from the end to its opposite side's
    middle (the wide step, once, at the end); its halves and the 134 degree triangle are meshed as
    three quads each: 5 faces at the end (42 on main), min scaled Jacobian at least 0.3 (0.098),
    no boundary singular vertex."""
    domain = domain_from_dict(PLAN_278)
    dec = decompose(domain, 0.02)
    wide = [r for r in dec.reports if WIDE_STEP in str(r.step)]
    assert len(wide) == 1 and wide[0].applications >= 1
    g = dec.graph
    tips = [step["binding"]["x"] for step in dec.trace if step.get("rule") == "split_triangle_under_curve_tip"]
    assert tips and all(np.allclose(g.get(x, "pos"), END, atol=1e-3) for x in tips)
    mesh = mesh_domain(domain, 0.02)
    stats = mesh_stats(mesh, domain)
    assert _faces_at(mesh, END) <= 6
    assert stats["boundary_singular"] == 0
    assert stats["min_scaled_jacobian"] >= 0.3


def test_patch_angle_split_parts_add_up_to_the_patch_angle():
    """patch_angle_split on every corner of every patch of a plan with a curve: the chord along the
    bisector of a corner (between the directions the sides leave it) splits it into two equal
    halves, and a chord along one of the sides leaves a part of about 0 degrees."""
    dec = decompose(domain_from_dict(PLAN_278), 0.02)
    g = dec.graph
    checked = 0
    for patch in (n for n in g.nodes() if g.node_type(n) == PATCH):
        for e in g.incident(patch, [PATCH_CORNER]):
            x = g.ends(e)[1]
            whole = patch_angle(g, patch, x)
            if not 1.0 < whole < 359.0:
                continue
            pos = np.asarray(g.get(x, "pos"), dtype=float)
            outline = _outline_ends(g, patch, x)
            after = math.atan2(*(outline[1] - pos)[::-1])
            bisector = after + math.radians(whole / 2)
            at = pos + 1e-3 * np.array([math.cos(bisector), math.sin(bisector)])
            assert patch_angle_split(g, patch, x, at) == pytest.approx(whole / 2, abs=1e-6)
            assert patch_angle_split(g, patch, x, outline[1]) == pytest.approx(0.0, abs=1e-6)
            checked += 1
    assert checked >= 30


def _outline_ends(g, patch, x) -> np.ndarray:
    """The patch's outline from its corner ``x`` (the point after ``x`` second)."""
    from vaultgram.topology.functions import _patch_outline

    return np.asarray(_patch_outline(g, patch, x)[1], dtype=float)
