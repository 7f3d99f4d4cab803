"""Keystones (Figure 11b): the rule in rules/tessellation.vgr turns a singularity of valency five or
more into its dual face, and the rule really drives the result."""

import math

import numpy as np
import pytest

from vaultgram.errors import RuleError
from vaultgram.pipeline import form_find, tessellate
from vaultgram.tessellation.keystones import RULE_FILE, cut_keystones, load_tessellation_rulebook
from vaultgram.tessellation.metrics import inner_vertices
from vaultgram.tessellation.surface import surface_from_network
from vaultgram.tessellation.voussoirs import voussoirs_at_vertices
from vaultgram.topology.rulebook import default_rules_dir

SCHEMA = """schema tessellation {
  node Vertex { pos: vec3, index: int = -1, boundary: bool = false }
  node KeystoneCorner : Vertex { keystone: int = -1 }
  edge Joint (Vertex -- Vertex)
}
"""


def star(n: int):
    """A fan of ``n`` quads around a centre of valency ``n`` (corners ``a_i`` at radius 1, ``b_i`` at
    radius 1.4 between them), and a ring of ``2 n`` quads around the fan."""
    t = 2 * math.pi * np.arange(n) / n
    half = t + math.pi / n
    circle = lambda r, angle: np.column_stack([r * np.cos(angle), r * np.sin(angle)])  # noqa: E731
    pts = np.vstack([[0.0, 0.0], circle(1.0, t), circle(1.4, half), circle(2.0, t), circle(2.8, half)])
    a, b, a2, b2 = (lambda i: 1 + i % n), (lambda i: 1 + n + i % n), (lambda i: 1 + 2 * n + i % n), \
        (lambda i: 1 + 3 * n + i % n)
    faces = [(0, a(i), b(i), a(i + 1)) for i in range(n)]
    faces += [(a(i), a2(i), b2(i), b(i)) for i in range(n)] + [(b(i), b2(i), a2(i + 1), a(i + 1)) for i in range(n)]
    return pts, faces


@pytest.fixture(scope="module")
def star_surface():
    v, f = star(6)
    return surface_from_network(form_find(v, f, zmax=1.0))


def test_star_mesh_has_one_inner_vertex_of_valency_six():
    v, f = star(6)
    valence = np.bincount(np.array([p for face in f for p in face]))
    assert valence[0] == 6


def test_the_singularity_becomes_a_keystone_whose_corners_join_three_voussoirs(star_surface):
    rulebook = load_tessellation_rulebook()
    cut = cut_keystones(star_surface.vertices, star_surface.faces, star_surface.edges, rulebook)
    assert len(cut.keystones) == 1
    keystone = cut.faces[cut.keystones[0]]
    assert len(keystone) == 6
    centre = star_surface.vertices[0]
    corners = cut.vertices[list(keystone)]
    # each corner halfway along one of the singularity's edges (cut = 0.5 in the rule)
    spoke_ends = star_surface.vertices[[v for v in range(1, 7)]]
    halfway = 0.5 * (centre + spoke_ends)
    assert np.allclose(np.sort(corners, axis=0), np.sort(halfway, axis=0))
    t = tessellate(star_surface, thickness=0.1)
    count = voussoirs_at_vertices(t.layout.edges, t.layout.group, len(t.vertices))
    ring = t.layout.loops[t.layout.keystones[0]]
    assert (count[ring] == 3).all()
    assert count[inner_vertices(t.layout, len(t.vertices))].max() <= 4


def test_without_the_keystone_rule_six_voussoirs_meet(star_surface, tmp_path):
    (tmp_path / "tessellation.vgr").write_text(SCHEMA + "strategy tessellation { }\n")
    t = tessellate(star_surface, thickness=0.1, rules_dir=tmp_path)
    assert t.summary["keystones"] == 0
    assert t.summary["meeting_points"].get("6", 0) == 1


def test_the_valency_threshold_is_a_rule_parameter(star_surface, tmp_path):
    shipped = (default_rules_dir() / RULE_FILE).read_text()
    (tmp_path / RULE_FILE).write_text(shipped.replace("keystone(min_valence = 5)", "keystone(min_valence = 7)"))
    t = tessellate(star_surface, thickness=0.1, rules_dir=tmp_path)
    assert t.summary["keystones"] == 0


def test_a_rulebook_without_the_tessellation_types_is_a_rule_error(tmp_path):
    (tmp_path / "tessellation.vgr").write_text("schema s { node Point { pos: vec2 } }\nstrategy tessellation { }\n")
    with pytest.raises(RuleError, match="lacks the type"):
        load_tessellation_rulebook(tmp_path)

