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


def test_keys_and_bindings_are_the_rows_of_the_matches(monkeypatch):
    monkeypatch.setattr(Matches, "BATCH", 3)                 # across batch boundaries
    found = Matcher(BOOK.rules["pair"], path(5)).all()
    assert list(found.keys()) == [m.key for m in found]
    bindings = list(found.bindings())
    assert bindings == [m.binding for m in found] and len({id(b) for b in bindings}) == len(found) == 8
    assert list(Matcher(BOOK.rules["pair"], path(1)).all().bindings()) == []


def test_all_applies_the_rows_without_match_objects(monkeypatch):
    from vaultgram.engine.strategy import Runner

    book = rulebook_from_text("schema s { node A  edge E (A -- A)  edge F (A -- A) }\n"
                              "rule mark { match { a: A  b: A  a -E- b } not { a -F- b } create a -F- b }")
    made = []
    monkeypatch.setattr(matcher_module, "Match", lambda *a: made.append(a) or Match(*a))
    g = HostGraph(book.schema)
    g.add_nodes("A", range(6))
    g.add_edges("E", [(i, i + 1) for i in range(5)])
    apps = Runner(book, g).apply_all("mark")
    # (a, b) and (b, a) both match each E edge; the first F edge makes the NAC of the second hold
    assert made == [] and [(a.binding["a"], a.binding["b"]) for a in apps] == [(i, i + 1) for i in range(5)]
    assert g.num_edges == 5 + 5 and all(g.degree(n, ["F"]) == (1 if n in (0, 5) else 2) for n in g.nodes())
