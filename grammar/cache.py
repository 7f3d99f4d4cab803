"""An on-disk cache of what does not change between runs: lark's analysis of ``rules.lark`` and the
parsed form (AST) of each rule file, keyed by its contents.

Building the LALR tables takes about 100 ms and parsing the bundled rulebook about as much again, on
every command that reads rules; with the cache a warm run does neither. The cache lives in the user's
cache folder (``$VAULTGRAM_CACHE_DIR``, else ``$XDG_CACHE_HOME/vaultgram``, else
``~/.cache/vaultgram``), never in the package. An entry's key is a hash of everything its value is
computed from -- the file's name and text, the grammar, the parser (parser, lalr) and AST modules and lark's version
-- so an edited file, grammar or parser simply misses. Nothing here may fail a run: an unwritable or
missing folder, a corrupt or foreign entry all fall back to parsing (``VAULTGRAM_CACHE_DIR=""`` turns
the cache off).
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
import pickle
import tempfile
from pathlib import Path

__all__ = ["cache_dir", "source_key", "load", "store", "lark_cache"]

_HERE = Path(__file__).resolve().parent
#: The files whose contents every cached value depends on.
_SOURCES = ("rules.lark", "parser.py", "lalr.py", "ast.py", "cache.py")


def cache_dir() -> Path | None:
    """The cache folder, created if needed, or None when there is none that can be written.

    >>> folder = cache_dir()
    >>> folder is None or (folder.is_dir() and folder != _HERE)
    True
    """
    configured = os.environ.get("VAULTGRAM_CACHE_DIR")
    if configured is not None:
        base = Path(configured) if configured else None
    else:
        xdg = os.environ.get("XDG_CACHE_HOME")
        base = (Path(xdg) if xdg else Path.home() / ".cache") / "vaultgram"
    if base is None:
        return None
    try:
        base.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return base if os.access(base, os.W_OK | os.X_OK) else None


@functools.lru_cache(maxsize=1)
def source_key() -> str:
    """Hash of the grammar, the parser and AST modules and lark's version: part of every key."""
    digest = hashlib.sha256()
    spec = importlib.util.find_spec("lark")  # lark's own __init__ (it names the version), not imported
    for path in [*(_HERE / name for name in _SOURCES), *([Path(spec.origin)] if spec and spec.origin else [])]:
        digest.update(path.read_bytes())
    return digest.hexdigest()


def _entry(kind: str, *parts: str) -> Path | None:
    """The file of the entry of this kind for these key parts (None without a cache folder)."""
    base = cache_dir()
    if base is None:
        return None
    digest = hashlib.sha256(source_key().encode())
    for part in parts:
        digest.update(b"\0" + part.encode("utf-8", "surrogatepass"))
    return base / f"{kind}-{digest.hexdigest()[:32]}.pickle"


def load(kind: str, *parts: str):
    """The cached value for these key parts, or None (no cache, no entry, or an unreadable one)."""
    path = _entry(kind, *parts)
    if path is None:
        return None
    try:
        with open(path, "rb") as f:
            return pickle.load(f)
    except Exception:  # a missing, truncated or foreign entry: recompute
        return None


def store(value, kind: str, *parts: str) -> None:
    """Cache ``value`` under these key parts, atomically (a temporary file renamed); errors ignored."""
    path = _entry(kind, *parts)
    if path is None:
        return
    try:
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")
    except OSError:
        return
    try:
        with os.fdopen(fd, "wb") as f:
            pickle.dump(value, f, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, path)
    except Exception:  # full, or a value that does not pickle: run without the cache
        Path(tmp).unlink(missing_ok=True)


def lark_cache() -> str | bool:
    """Where lark keeps its analysis of the grammar (its ``cache`` option; False: no cache). lark
    checks the grammar and options it was built from itself."""
    path = _entry("lark")
    return str(path) if path is not None else False
