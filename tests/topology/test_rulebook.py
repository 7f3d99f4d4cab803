"""The vault rulebook (vaultgram.topology.rulebook): a rulebook the pipeline cannot use is a rule error."""

from __future__ import annotations

import pytest

from vaultgram.domain import load_domain
from vaultgram.errors import RuleError
from vaultgram.pipeline import decompose

from paths import EXAMPLES


def test_rulebook_without_pipeline_types_is_a_clear_error(tmp_path):
    (tmp_path / "topology.vgr").write_text("schema s { node Point { pos: vec2 } }\n")
    with pytest.raises(RuleError, match="lacks the type"):  # a fault of the rulebook, not of the domain
        decompose(load_domain(EXAMPLES / "l_shape.json"), 0.02, rules_dir=tmp_path)


@pytest.mark.parametrize("name", ["quad_with_hole", "fig7_curves", "features_combined"])
def test_the_cached_vault_rulebook_decomposes_as_the_checked_one(tmp_path, monkeypatch, name):
    """The vault rulebook read back from the cache of checked rulebooks (vaultgram.engine.bookcache,
    issue 18) gives the checked one's decomposition, invariants checked on the way, to the byte."""
    from vaultgram.engine import bookcache
    from vaultgram.engine.rulebook import load_rulebook
    from vaultgram.meshpipeline import plan_skeleton
    from vaultgram.topology.decomposition import block_decomposition
    from vaultgram.topology.functions import vault_functions
    from vaultgram.topology.rulebook import default_rules_dir

    monkeypatch.setenv("VAULTGRAM_CACHE_DIR", str(tmp_path))
    files = [default_rules_dir() / "topology.vgr"]
    checked = load_rulebook(files, vault_functions())
    cached = bookcache.load(files, vault_functions())
    assert cached is not None and cached is not checked and cached.summary() == checked.summary()
    sk = plan_skeleton(load_domain(EXAMPLES / f"{name}.json"))
    a, b = (block_decomposition(sk, book, check_invariants=True) for book in (checked, cached))
    assert a.to_json() == b.to_json() and a.patches_json() == b.patches_json()
