"""Chunked whole-graph search (issue 18): a table of partial matches larger than the chunk size is
cut into chunks that each run the rest of the plan, so memory stays bounded; the matches, and their
order, are those of a single pass."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.engine import columnar
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.matcher import Matcher
from vaultgram.engine.rulebook import rulebook_from_text

RULES = """
schema s { node A { w: int = 0 }  node B  edge E (Node -- Node)  edge F (A -- B) }
rule square { match { a: A  b: B  c: A  d: B  a -E- b  b -E- c  c -E- d  d -E- a } }
rule unmarked { match { a: A { w < 3 }  b: B  a -E- b } not { a -F- b } }
"""


def checkerboard(book, side: int) -> HostGraph:
    """A side x side grid, nodes alternating A and B, edges E; every third A-B edge also has an F."""
    g = HostGraph(book.schema)
    ids = np.arange(side * side)
    i, j = np.divmod(ids, side)
    g.add_nodes("A", ids[(i + j) % 2 == 0], {"w": (ids[(i + j) % 2 == 0] % 5).tolist()})
    g.add_nodes("B", ids[(i + j) % 2 == 1])
    right, down = ids[j + 1 < side], ids[i + 1 < side]
    ends = np.vstack([np.column_stack([right, right + 1]), np.column_stack([down, down + side])])
    g.add_edges("E", ends)
    a_first = np.where(((ends[:, 0] // side + ends[:, 0] % side) % 2 == 0)[:, None], ends, ends[:, ::-1])
    g.add_edges("F", a_first[::3])
    return g


@pytest.mark.parametrize("rule", ["square", "unmarked"])
def test_chunks_find_the_same_matches_in_the_same_order(monkeypatch, rule):
    book = rulebook_from_text(RULES)
    g = checkerboard(book, 9)
    whole = [m.key for m in Matcher(book.rules[rule], g).all()]
    monkeypatch.setattr(columnar, "CHUNK_ROWS", 3)
    chunked = [m.key for m in Matcher(book.rules[rule], g).all()]
    assert chunked == whole and len(whole) > 3 * 10


def test_a_square_grid_has_four_four_cycle_matches_per_square(monkeypatch):
    book = rulebook_from_text(RULES)
    monkeypatch.setattr(columnar, "CHUNK_ROWS", 5)
    keys = [m.key for m in Matcher(book.rules["square"], checkerboard(book, 7)).all()]
    assert len(keys) == 4 * 6 * 6 and len(set(keys)) == len(keys)
    assert keys == sorted(keys)


DEGREE_RULES = """
schema s { node A { w: int = 0 }  node B  edge E (Node -- Node)  edge F (A -- B) }
rule hub { match { a: A } where degree(a, E) >= 3 }
"""


def test_degrees_are_kept_per_graph_version_and_counted_again_after_a_change(monkeypatch):
    """The degrees a column test reads are counted once per graph version (every chunk of a scan
    reads the same array), equal the graph's own, and are counted again when an edge is added."""
    book = rulebook_from_text(DEGREE_RULES)
    g = checkerboard(book, 6)
    monkeypatch.setattr(columnar, "CHUNK_ROWS", 4)
    hubs = [m.key for m in Matcher(book.rules["hub"], g).all()]
    kept = columnar._degrees(g, frozenset({"E"}))
    assert kept is columnar._degrees(g, frozenset({"E"}))
    assert kept.tolist() == [g.degree(n, ("E",)) for n in range(36)]
    assert sorted(k[0] for k in hubs) == [n for n in range(36) if g.node_type(n) == "A" and g.degree(n, ("E",)) >= 3]
    g.add_edge("E", 0, 35)  # a corner of the grid (degree 2) becomes a hub
    assert columnar._degrees(g, frozenset({"E"}))[0] == 3
    assert (0,) in [m.key for m in Matcher(book.rules["hub"], g).all()]
