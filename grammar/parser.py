"""Parse rule files (``.vgr``) into the AST of :mod:`vaultgram.grammar.ast`.

The syntax is defined by ``rules.lark`` next to this module (LALR(1), contextual lexer); this module
(with :mod:`.lalr`, imported only when a file is not in the parse cache) only turns lark's
parse trees into AST dataclasses and lark's errors into
:class:`~vaultgram.grammar.errors.RuleSyntaxError` with a position and a hint. It gives no meaning to
what it reads: unknown types (attribute types included), duplicate names and misplaced ``next(v)``
are for the engine's checker.

Public API
----------
``parse_text(text, filename="<string>") -> RuleFile``
    Parse one file's text; its ``include`` lines are recorded in ``RuleFile.includes``, not resolved.
``parse_file(path) -> RuleFile``
    Read and parse one file.
``load_files(paths) -> list[RuleFile]``
    Parse files and, recursively, the files they include (each once): included files come before
    the files that include them, then the command-line order.

Source positions
----------------
Every AST node has ``pos`` (file, 1-based line and column). It is where the construct starts, except
for :class:`~vaultgram.grammar.ast.Binary` (the operator) and :class:`~vaultgram.grammar.ast.Attr`
(the attribute name), which is where a type error in them is best shown.

Example
-------
>>> rf = parse_text("rule drop { match { a: Corner } delete a }")
>>> rf.rules[0].statements[0].vars
('a',)
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Iterable

from vaultgram.grammar import cache
from vaultgram.grammar.ast import Include, RuleFile
from vaultgram.grammar.errors import RuleSyntaxError

__all__ = ["parse_text", "parse_file", "load_files"]


def __getattr__(name: str):
    """``KEYWORDS`` and ``CONTEXTUAL_KEYWORDS``, from :mod:`.lalr` (imported on first use)."""
    if name in ("KEYWORDS", "CONTEXTUAL_KEYWORDS"):
        from vaultgram.grammar import lalr

        return getattr(lalr, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


# --------------------------------------------------------------------------------------------
# Public API
# --------------------------------------------------------------------------------------------


def parse_text(text: str, filename: str = "<string>") -> RuleFile:
    """Parse the text of one rule file.

    Parameters
    ----------
    text : the file's contents.
    filename : the name used in source positions and as ``RuleFile.path``.

    Returns
    -------
    RuleFile, with ``includes`` recorded but not resolved.

    Raises
    ------
    RuleSyntaxError : with the file, line and column of the offending token and a hint.
    """
    cached = cache.load("ast", filename, text)
    if isinstance(cached, RuleFile):
        return cached
    rule_file = _parsed(text, filename)
    cache.store(rule_file, "ast", filename, text)
    return rule_file

def _parsed(text: str, filename: str) -> RuleFile:
    """:func:`parse_text` without the cache (lark is imported here, on a miss)."""
    from vaultgram.grammar import lalr

    return lalr.parsed(text, filename)


def parse_file(path: str | os.PathLike) -> RuleFile:
    """Read and parse one rule file (UTF-8); ``RuleFile.path`` is ``str(path)``."""
    name = str(path)
    return parse_text(_read(Path(path), name, None), name)


def load_files(paths: Iterable[str | os.PathLike]) -> list[RuleFile]:
    """Parse rule files and, recursively, the files they ``include``.

    An ``include "x.vgr"`` is resolved relative to the directory of the including file. Each file is
    parsed once (files are identified by their resolved path). The result lists included files
    before the files that include them, and otherwise follows the order of ``paths``.

    Raises
    ------
    RuleSyntaxError : for a syntax error, a missing file (at the ``include`` that names it, or naming
        the path for a file given in ``paths``), or an include cycle (at the ``include`` that closes it).
    """
    loaded: list[RuleFile] = []
    done: set[Path] = set()
    stack: list[tuple[Path, str]] = []

    def visit(path: Path, shown: str, at: Include | None) -> None:
        key = path.resolve()
        if any(key == k for k, _ in stack):
            start = next(i for i, (k, _) in enumerate(stack) if k == key)
            chain = " -> ".join([s for _, s in stack[start:]] + [shown])
            raise RuleSyntaxError(
                f"include cycle: {chain}",
                at.pos if at else None,
                "a file cannot include itself, directly or through other files",
            )
        if key in done:
            return
        rule_file = parse_text(_read(path, shown, at), shown)
        stack.append((key, shown))
        for include in rule_file.includes:
            child = os.path.normpath(os.path.join(os.path.dirname(shown), include.path))
            visit(Path(child), child, include)
        stack.pop()
        done.add(key)
        loaded.append(rule_file)

    for p in paths:
        visit(Path(p), str(p), None)
    return loaded


def _read(path: Path, shown: str, at: Include | None) -> str:
    """The text of a rule file, or a RuleSyntaxError at the include naming it (or naming the path)."""
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        reason = "no such file"
    except IsADirectoryError:
        reason = "it is a directory"
    except UnicodeDecodeError:
        reason = "it is not UTF-8 text"
    except OSError as exc:
        reason = exc.strerror or str(exc)
    if at is not None:
        raise RuleSyntaxError(
            f"cannot include {at.path!r}: {shown}: {reason}",
            at.pos,
            "an include path is relative to the directory of the file that includes it",
        )
    raise RuleSyntaxError(f"cannot read rule file {shown}: {reason}")
