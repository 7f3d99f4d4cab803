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
