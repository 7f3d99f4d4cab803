"""A quad at a curve's free end whose diagonal would leave a sliver (§4.2 Figure 8, issue 12 What 4):
``split_quad_at_curve_end_to_side(sliver = 30)`` (rules/strips.vgr, a default step of curves.vgr's
``curve_patching``) splits it to the middle of the side beside its opposite corner instead.

fig7_curves' curve (1, 1)-(2.5, 2.5): the skeleton branches from (0.585, 0.585) bend round the end (1, 1)
to the vertices (1.6, 3.824) and (3.824, 1.6); split_quad_at_curve_end's diagonal from (1, 1) to them
left a 17.1 degree corner there, and the mesh's rows sheared along those slivers (min scaled Jacobian
0.299 at a quarter of the default length, 0.247 at 16,000 faces)."""

from __future__ import annotations

import numpy as np
import pytest
from diagonal_at_curve_ends import rules_with_diagonals_at_curve_ends

from vaultgram.domain import load_domain
from vaultgram.geometry.polygons import interior_angle
from vaultgram.meshing.densities import TARGET_FRACTION
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import decompose, mesh_domain
from vaultgram.topology.functions import diagonal_side_angle, patch_angle
from vaultgram.topology.types import PATCH, PATCH_CORNER

from paths import EXAMPLES

FIG7 = EXAMPLES / "fig7_curves.json"
END = (1.0, 1.0)
#: The step's name in the decomposition's reports.
SLIVER_STEP = "split_quad_at_curve_end_to_side(sliver = 30)"

pytestmark = pytest.mark.skipif(not FIG7.exists(), reason="examples not present")


def _skeleton_corners_at(dec, point) -> list[float]:
    """The corner angles (degrees, between the first segments of the patch sides) at skeleton vertices
    of the patches that have the node at ``point`` as a corner."""
    g = dec.graph
    out = []
    for p in dec.patches:
        if not any(np.allclose(g.get(c, "pos"), point) for c in p.corners):
            continue
        n = len(p.corners)
        for i, c in enumerate(p.corners):
            if g.schema.is_subtype(g.node_type(c), "SkeletonVertex"):
                out.append(interior_angle(p.sides[(i - 1) % n][-2], p.sides[i][0], p.sides[i][1]))
    return out


def test_the_curve_end_of_fig7_leaves_no_sliver_at_a_skeleton_vertex(tmp_path):
    """fig7's layout: the patches at (1, 1) have no corner under 25 degrees at a skeleton vertex (17.1
    with the diagonals, drawn with the rules as before); the step splits the two quads there (and
    carries their strips to the boundary), and nothing on features_combined, whose curve ends are not
    flat in a quad along the whole curve."""
    dec = decompose(load_domain(FIG7), 0.02)
    g = dec.graph
    splits = [s for s in dec.trace if s.get("rule") == "split_quad_at_curve_end_to_side" and
              np.allclose(g.get(s["binding"]["x"], "pos"), END)]
    assert len(splits) == 2
    corners = _skeleton_corners_at(dec, END)
    assert len(corners) >= 4 and min(corners) >= 25.0
    (end,) = [n for n in g.nodes() if g.node_type(n) == "CurveExtremity" and np.allclose(g.get(n, "pos"), END)]
    assert all(len(p.corners) in (3, 4) and patch_angle(g, _patch_node(g, p), end) < 150
               for p in dec.patches if end in p.corners)  # no flat corner left at the end
    before = decompose(load_domain(FIG7), 0.02, rules_dir=rules_with_diagonals_at_curve_ends(tmp_path))
    assert min(_skeleton_corners_at(before, END)) < 18.0
    combined = decompose(load_domain(EXAMPLES / "features_combined.json"), 0.02)
    assert [r.applications for r in combined.reports if SLIVER_STEP in str(r.step)] == [0]


def _patch_node(g, patch) -> int:
    """The Patch node of the graph with the corners of ``patch``."""
    corners = set(patch.corners)
    return next(n for n in g.nodes() if g.node_type(n) == PATCH
                and {g.ends(e)[1] for e in g.incident(n, [PATCH_CORNER])} == corners)


def test_diagonal_side_angle_splits_the_opposite_corner_in_two(tmp_path):
    """diagonal_side_angle on fig7's quads at (1, 1), left whole (the rules as before without the
    Figure 8 split either): the diagonal to the opposite corner o leaves 17.1 and 46.2 degrees on
    either side there, which add up to the quad's angle at o; the same sum on every quad of the
    default layout where a diagonal runs."""
    rules = rules_with_diagonals_at_curve_ends(tmp_path)
    text = (rules / "curves.vgr").read_text()
    step = "  choose { split_quad_at_curve_end, keep_quad_at_curve_end } fixpoint\n"
    assert step in text
    (rules / "curves.vgr").write_text(text.replace(step, ""))
    whole = decompose(load_domain(FIG7), 0.02, rules_dir=rules)
    found = [sorted(parts) for parts, _ in _quad_diagonals(whole.graph, at=END)]
    assert len(found) == 2 and np.allclose(found, [[17.06, 46.20]] * 2, atol=0.01)
    checked = 0
    for (near, far), at_o in _quad_diagonals(decompose(load_domain(FIG7), 0.02).graph):
        assert near + far == pytest.approx(at_o, abs=1e-6)
        checked += 1
    assert checked >= 20


def _quad_diagonals(g, at=None):
    """For each quad Patch node (with a corner at ``at``, if given: from that corner) and each corner x
    whose diagonal to the opposite corner o runs inside it, the two parts of the diagonal's corner at
    o and the quad's angle at o."""
    for patch in (n for n in g.nodes() if g.node_type(n) == PATCH):
        edges = sorted(g.incident(patch, [PATCH_CORNER]), key=lambda e: g.get_edge(e, "index"))
        cs = [g.ends(e)[1] for e in edges]
        if len(cs) != 4:
            continue
        for k, x in enumerate(cs):
            if at is not None and not np.allclose(g.get(x, "pos"), at):
                continue
            a, o, b = cs[(k + 1) % 4], cs[(k + 2) % 4], cs[(k + 3) % 4]
            parts = (diagonal_side_angle(g, patch, x, o, a), diagonal_side_angle(g, patch, x, o, b))
            if not np.isnan(parts).any():
                yield parts, patch_angle(g, patch, o)


def test_fig7_at_a_quarter_of_the_default_length_keeps_its_faces_over_the_floor():
    """fig7 meshed at a quarter of the default target length: min scaled Jacobian at least 0.35 (0.299
    with the diagonals, whose slivers' rows sheared; 0.408 split to the side), no inverted face."""
    domain = load_domain(FIG7)
    mesh = mesh_domain(domain, 0.02, target_length=TARGET_FRACTION * domain.diagonal / 4)
    stats = mesh_stats(mesh, domain)
    assert stats["inverted_faces"] == 0 and stats["min_scaled_jacobian"] >= 0.35
