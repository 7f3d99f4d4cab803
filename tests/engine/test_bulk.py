"""Bulk construction of a host graph (issue 18): the garbage collector is paused while the arrays
are added, and left as it was, also when the addition is refused."""

from __future__ import annotations

import gc

import pytest

from vaultgram.engine.errors import SchemaError
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.rulebook import rulebook_from_text

SCHEMA = rulebook_from_text("schema s { node A  edge E (A -- A) }").schema


@pytest.mark.parametrize("enabled", [True, False])
def test_bulk_additions_pause_the_collector_and_restore_it(monkeypatch, enabled):
    seen = []
    real = HostGraph._index_edges
    monkeypatch.setattr(HostGraph, "_index_edges", lambda *a: (seen.append(gc.isenabled()), real(*a))[1])
    (gc.enable if enabled else gc.disable)()
    try:
        g = HostGraph(SCHEMA)
        g.add_nodes("A", range(4))
        g.add_edges("E", [(0, 1), (1, 2), (2, 3)])
        assert seen == [False] and gc.isenabled() == enabled
        with pytest.raises(SchemaError):
            g.add_edges("E", [(0, 9)])                      # node 9 does not exist
        assert gc.isenabled() == enabled
        assert sorted(g.incident(1)) == [0, 1] and g.num_edges == 3
    finally:
        gc.enable()
