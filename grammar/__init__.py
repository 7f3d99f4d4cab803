"""The rule language: ``rules.lark`` (the grammar), :mod:`.ast` (dataclasses), :mod:`.parser` and
:mod:`.errors`.

``parse_text``, ``parse_file`` and ``load_files`` turn ``.vgr`` text into
:class:`~vaultgram.grammar.ast.RuleFile` values; every syntax error is a
:class:`~vaultgram.grammar.errors.RuleSyntaxError` with file, line, column and a hint. The language is
described in ``docs/language.md``.

The parser (and lark) is imported on first use of one of these names, so that importing the errors
alone stays cheap.
"""

from __future__ import annotations

__all__ = ["parse_text", "parse_file", "load_files"]


def __getattr__(name: str):
    if name in __all__:
        from vaultgram.grammar import parser

        return getattr(parser, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
