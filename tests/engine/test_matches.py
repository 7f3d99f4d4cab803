"""``Matcher.all`` returns the matches as a sequence over the match table (issue 18): each Match is
made when it is read, and the sequence reads as the sorted list of matches it stands for."""

from __future__ import annotations

import pytest

from vaultgram.engine import matcher as matcher_module
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.matcher import Match, Matcher, Matches
from vaultgram.engine.rulebook import rulebook_from_text

BOOK = rulebook_from_text("schema s { node A  edge E (A -- A) }\nrule pair { match { a: A  b: A  a -E- b } }")


def path(n: int) -> HostGraph:
    g = HostGraph(BOOK.schema)
    g.add_nodes("A", range(n))
    g.add_edges("E", [(i, i + 1) for i in range(n - 1)])
    return g


def test_the_matches_read_as_their_sorted_list(monkeypatch):
    monkeypatch.setattr(Matches, "BATCH", 3)                 # iterate across batch boundaries
    found = Matcher(BOOK.rules["pair"], path(5)).all()
    keys = [(0, 1, 0), (1, 0, 0), (1, 2, 1), (2, 1, 1), (2, 3, 2), (3, 2, 2), (3, 4, 3), (4, 3, 3)]
    listed = [Match("pair", found.vars, k) for k in keys]
    assert len(found) == 8 and list(found) == listed and found == listed and found != listed[:-1]
    assert found[0] == listed[0] and found[-1] == listed[-1] and found[2:4] == listed[2:4]
    assert found[0].binding == {"a": 0, "b": 1, found.vars[2]: 0} and isinstance(found[0].key[0], int)
    with pytest.raises(IndexError):
        found[8]
    assert Matcher(BOOK.rules["pair"], path(1)).all() == [] and not Matcher(BOOK.rules["pair"], path(1)).all()


def test_first_makes_one_match_object(monkeypatch):
    made = []
    monkeypatch.setattr(matcher_module, "Match", lambda *a: made.append(a) or Match(*a))
    first = Matcher(BOOK.rules["pair"], path(50)).first()
    assert first.key == (0, 1, 0) and len(made) == 1
