"""Random valid plans (the ``vault_domains`` strategy: non-convex outlines, 0-3 holes, points and
boundary points, 0-2 curves) mesh without a fold, or are refused with a message naming the place. A
few examples here; the rate over a fixed list of 200 is benchmarks/reliability.py ``plans``."""

from __future__ import annotations

import re

from hypothesis import HealthCheck, given, settings

from vaultgram.domain import domain_from_dict
from vaultgram.errors import VaultgramError
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import mesh_domain
from vaultgram.testing.domains import vault_domains

PLACE = re.compile(r"\(-?[\d.e+-]+, -?[\d.e+-]+\)")


@settings(max_examples=6, deadline=None, suppress_health_check=list(HealthCheck))
@given(vault_domains())
def test_a_random_plan_meshes_or_the_refusal_names_the_place(plan):
    data, spacing = plan
    try:
        mesh = mesh_domain(domain_from_dict(data), spacing)
    except VaultgramError as exc:
        assert PLACE.search(str(exc)), str(exc)
        return
    assert mesh_stats(mesh)["inverted_faces"] == 0
