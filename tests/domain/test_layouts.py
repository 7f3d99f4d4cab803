"""Feature layouts: those the rules decompose (bends, curve ends on the outline or a hole, points at
curve ends) mesh; those they cannot yet (features meeting inside the plan) are refused naming them."""

from __future__ import annotations

import pytest

from vaultgram.domain import domain_from_dict
from vaultgram.errors import DomainError
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import mesh_domain

SQUARE = [[0, 0], [30, 0], [30, 30], [0, 30]]


@pytest.mark.parametrize("extra", [
    {"curves": [[[8, 8], [20, 8], [20, 20]]]},  # an L: a bend of 90 degrees
    {"curves": [[[8, 8], [20, 8], [9.6, 14]]]},  # a bend of about 150 degrees
    {"holes": [[[18, 12], [24, 12], [24, 18], [18, 18]]], "curves": [[[6, 15], [18, 15]]]},  # ends on a hole
    {"curves": [[[8, 15], [22, 15]]], "points": [[22, 15]]},  # a point at a curve's end
    {"curves": [[[0, 15], [12, 10]], [[0, 15], [12, 20]]]},  # curves sharing an end on the boundary
], ids=["L", "sharp-bend", "end-on-hole", "point-at-end", "shared-boundary-end"])
def test_layouts_the_rules_decompose_give_a_valid_mesh(extra):
    mesh = mesh_domain(domain_from_dict({"outer": SQUARE, **extra}), 0.02)
    stats = mesh_stats(mesh)
    assert stats["inverted_faces"] == 0 and stats["triangles"] + stats["quads"] == len(mesh.faces)


@pytest.mark.parametrize("extra, words", [
    ({"curves": [[[8, 15], [15, 15]], [[15, 15], [22, 22]]]}, "curve features 0 and 1 share an end at (15, 15)"),
    ({"curves": [[[8, 15], [22, 15]], [[15, 15], [15, 24]]]}, "curve feature 1 ends on curve feature 0 at (15, 15)"),
    ({"curves": [[[8, 15], [22, 15]]], "points": [[15, 15]]}, "point feature 0 at (15, 15) lies on curve feature 0"),
], ids=["shared-end", "T", "point-on-curve"])
def test_layouts_the_rules_cannot_decompose_are_named(extra, words):
    with pytest.raises(DomainError, match="the rules cannot decompose") as info:
        mesh_domain(domain_from_dict({"outer": SQUARE, **extra}), 0.02)
    assert words in str(info.value)
