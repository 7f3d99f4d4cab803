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
