"""The cache of checked rulebooks (engine/bookcache.py, issue 18): a rulebook read back rewrites as
the checked one does, with the caller's functions; a changed file or registry misses; what an entry may
not hold is not written; a broken entry is checked again."""

from __future__ import annotations

import pytest

from vaultgram.engine import bookcache
from vaultgram.engine.expressions import Functions
from vaultgram.engine.graph import HostGraph
from vaultgram.engine.rulebook import load_rulebook
from vaultgram.engine.strategy import Runner

SCHEMA = "schema s { node A { w: int = 0 } }\n"
RULES = ('include "schema.vgr"\nrule bump { match { a: A { w < 5 } } set a.w = step(a.w) }\n'
         "strategy grow { bump fixpoint }\n")


def _registry(k: int) -> Functions:
    """Functions with ``step``: a closure adding ``k`` (one definition, so one signature, for every k)."""
    f = Functions()
    f.register("step", lambda w: w + k, ("int",), "int")
    return f


def _grown(book) -> int:
    """The weight of one node after the ``grow`` strategy."""
    g = HostGraph(book.schema)
    n = g.add_node("A")
    Runner(book, g).run("grow")
    return g.get(n, "w")


@pytest.fixture
def files(tmp_path, monkeypatch):
    monkeypatch.setenv("VAULTGRAM_CACHE_DIR", str(tmp_path / "cache"))
    (tmp_path / "schema.vgr").write_text(SCHEMA)
    (tmp_path / "main.vgr").write_text(RULES)
    return [tmp_path / "main.vgr"]


def test_a_cached_rulebook_rewrites_as_the_checked_one_with_the_callers_functions(files):
    checked = load_rulebook(files, _registry(1))
    cached = bookcache.load(files, _registry(1))
    assert cached is not None and cached is not checked
    assert cached.summary() == checked.summary() and _grown(cached) == _grown(checked) == 5
    other = _registry(3)  # same signature, another function: the cache never supplies a function
    assert _grown(bookcache.load(files, other)) == 6 and bookcache.load(files, other).functions is other


def test_an_edited_include_or_another_signature_misses(files):
    load_rulebook(files, _registry(1))
    assert bookcache.load(files, _registry(1)) is not None
    f = Functions()
    f.register("step", lambda w: w * 2, ("int",), "int")  # defined elsewhere: another signature
    assert bookcache.load(files, f) is None
    (files[0].parent / "schema.vgr").write_text("schema s { node A { w: int = 1 } }\n")
    assert bookcache.load(files, _registry(1)) is None
    assert _grown(load_rulebook(files, _registry(1))) == 5 and bookcache.load(files, _registry(1)) is not None


class _Foreign:
    files: list = []


def test_what_an_entry_may_not_hold_is_not_written(files, tmp_path):
    bookcache.store(_Foreign(), files, _registry(1))
    assert not (tmp_path / "cache").exists() or not list((tmp_path / "cache").glob("rulebook-*"))


def test_a_broken_entry_is_checked_again(files, tmp_path):
    load_rulebook(files, _registry(1))
    (entry,) = (tmp_path / "cache").glob("rulebook-*")
    entry.write_bytes(entry.read_bytes()[:1000])
    assert bookcache.load(files, _registry(1)) is None
    assert _grown(load_rulebook(files, _registry(1))) == 5


def test_no_cache_folder_means_checking(files, monkeypatch):
    monkeypatch.setenv("VAULTGRAM_CACHE_DIR", "")
    assert _grown(load_rulebook(files, _registry(1))) == 5 and bookcache.load(files, _registry(1)) is None


def _pickled_and_back(obj):
    """``obj`` through the cache's pickler and unpickler (no registry)."""
    import io

    buffer = io.BytesIO()
    bookcache._Pickler(buffer, Functions()).dump(obj)
    buffer.seek(0)
    return bookcache._Unpickler(buffer, Functions()).load()


def test_closures_come_back_with_their_cells_shared_and_a_closure_holding_itself():
    """Two closures over one variable keep sharing its cell, an empty cell stays empty, and a closure
    that calls itself (its cell holds it) comes back calling itself: cells are made empty and filled
    after (pickle's memo closes the cycle)."""
    def made():
        shared = [0]

        def bump():
            shared[0] += 1
            return shared[0]

        def read():
            return shared[0]

        def count(n):
            return 0 if n == 0 else count(n - 1) + 1

        def unset():
            return later  # noqa: F821 -- bound after, never here

        if False:
            later = None
        return bump, read, count, unset

    functions = made()
    for f in functions:
        f.__module__ = "vaultgram.engine.expressions"  # code an entry may hold
    bump, read, count, unset = _pickled_and_back(functions)
    assert (bump(), bump(), read()) == (1, 2, 2)
    assert count(5) == 5 and count.__closure__[0].cell_contents is count
    with pytest.raises(NameError):
        unset()
