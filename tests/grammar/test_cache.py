"""The on-disk cache of parsed rule files and of lark's tables (vaultgram.grammar.cache): a warm parse
reads the entry, an edited file misses, and a cache that cannot be written or read changes nothing."""

from __future__ import annotations

from vaultgram.grammar import cache
from vaultgram.grammar.parser import _parsed, parse_text

TEXT = "rule drop { match { a: Corner } delete a }"


def test_parse_is_cached_by_contents(tmp_path, monkeypatch):
    monkeypatch.setenv("VAULTGRAM_CACHE_DIR", str(tmp_path))
    first = parse_text(TEXT, "a.vgr")
    assert first == _parsed(TEXT, "a.vgr")
    entries = sorted(p.name for p in tmp_path.glob("ast-*"))
    assert len(entries) == 1
    assert cache.load("ast", "a.vgr", TEXT) == first
    assert parse_text(TEXT, "a.vgr") == first                      # warm: from the entry
    edited = TEXT.replace("drop", "remove")
    assert parse_text(edited, "a.vgr").rules[0].name == "remove"   # an edited file misses
    assert len(list(tmp_path.glob("ast-*"))) == 2


def test_a_corrupt_entry_is_parsed_again(tmp_path, monkeypatch):
    monkeypatch.setenv("VAULTGRAM_CACHE_DIR", str(tmp_path))
    parse_text(TEXT, "a.vgr")
    (entry,) = tmp_path.glob("ast-*")
    entry.write_bytes(b"not a pickle")
    assert parse_text(TEXT, "a.vgr") == _parsed(TEXT, "a.vgr")


def test_an_unwritable_cache_is_no_cache(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    monkeypatch.setenv("VAULTGRAM_CACHE_DIR", str(blocker / "cache"))   # cannot be created
    assert cache.cache_dir() is None and cache.lark_cache() is False
    assert parse_text(TEXT, "a.vgr") == _parsed(TEXT, "a.vgr")
    monkeypatch.setenv("VAULTGRAM_CACHE_DIR", "")                      # turned off
    assert cache.cache_dir() is None


def test_the_cache_lives_outside_the_package(monkeypatch, tmp_path):
    monkeypatch.delenv("VAULTGRAM_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert cache.cache_dir() == tmp_path / "vaultgram"
    assert cache.lark_cache().startswith(str(tmp_path / "vaultgram"))
