"""``vaultgram rules check``'s result, cached by the contents of everything it depends on (issue 18).

Checking the bundled rulebook needs the rule language's parser (lark), the engine's checker and the
registries of the stages' functions, whose modules import numpy, scipy, shapely and networkx: over a
second of imports for a summary that only changes when a file changes. A warm ``rules check`` reads
its summaries from :mod:`vaultgram.grammar.cache` and imports none of that.

An entry is found by the rule files' names and texts, the working folder (relative includes) and a
fingerprint of the code that checks them (:func:`code_fingerprint`); it records every file the check
read, includes too, with a hash of its text, and is used only while all of them are unchanged. Only
successful checks are cached: an error is found, and reported, by checking again.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Sequence

from vaultgram.grammar import cache

__all__ = ["CODE_PACKAGES", "Checked", "code_fingerprint", "checked_summaries"]

#: The packages whose code decides what a check finds: the language, the engine's checker and the
#: stages that register the functions rules may call (their signatures).
CODE_PACKAGES = ("vaultgram.grammar", "vaultgram.engine", "vaultgram.topology", "vaultgram.tessellation")


@dataclass(frozen=True)
class Checked:
    """A cached check: the summaries it printed, and each file it read with the hash of its text."""

    summaries: list
    files: tuple[tuple[str, str], ...]

    def current(self) -> bool:
        """Whether every file the check read still has the text it had."""
        return all(_file_hash(path) == digest for path, digest in self.files)


def _file_hash(path: str | Path) -> str | None:
    """The sha256 of a file's bytes, or None if it cannot be read."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return None


def code_fingerprint(packages: Sequence[str] = CODE_PACKAGES) -> str:
    """A hash of the source files (``.py``, ``.lark``) of ``packages``, found without importing them.

    >>> code_fingerprint() == code_fingerprint() and len(code_fingerprint())
    64
    """
    digest = hashlib.sha256()
    for name in packages:
        spec = importlib.util.find_spec(name)
        for folder in (spec.submodule_search_locations or []) if spec else []:
            for path in sorted(p for p in Path(folder).rglob("*") if p.suffix in (".py", ".lark")):
                digest.update(str(path.relative_to(folder)).encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


def checked_summaries(files: Sequence[str], check: Callable[[], list]) -> list:
    """The summaries of ``rules check FILES``: cached ones if nothing they depend on changed, else
    ``check()``'s, which returns the rulebooks (each with ``summary()`` and ``files``), stored for the
    next run."""
    parts = [os.getcwd(), code_fingerprint(), *(f"{f}\0{_file_hash(f)}" for f in files)]
    hit = cache.load("check", *parts)
    if isinstance(hit, Checked) and hit.current():
        return hit.summaries
    books = check()
    summaries = [book.summary() for book in books]
    read = sorted({str(p) for book in books for p in book.files} | {str(f) for f in files})
    cache.store(Checked(summaries, tuple((p, _file_hash(p)) for p in read)), "check", *parts)
    return summaries
