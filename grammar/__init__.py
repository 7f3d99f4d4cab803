"""The rule language: ``rules.lark`` (the grammar), :mod:`.ast` (dataclasses) and :mod:`.parser`.

``parse_text``, ``parse_file`` and ``load_files`` turn ``.vgr`` text into
:class:`~vaultgram.grammar.ast.RuleFile` values; every syntax error is a
:class:`~vaultgram.errors.RuleSyntaxError` with file, line, column and a hint. The language is
described in ``docs/language.md``.
"""

from vaultgram.grammar.parser import load_files, parse_file, parse_text

__all__ = ["parse_text", "parse_file", "load_files"]
