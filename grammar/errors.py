"""The errors of the rule language, and the root of every error caused by input.

Every message names *where* the problem is (``file:line:col`` for rule files) so that a command line
can print it as one readable line, without a traceback. :class:`InputError` is the root class: an
application catches it to tell a mistake in its input from a bug (vaultgram re-exports it as
``VaultgramError``).

>>> err = RuleSyntaxError("unexpected 'x'", SourcePos("a.vgr", 2, 7), did_you_mean("Cornr", ["Corner"]))
>>> print(err)
a.vgr:2:7: unexpected 'x'
  hint: did you mean 'Corner'?
>>> isinstance(err, InputError)
True
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass

__all__ = ["SourcePos", "InputError", "RuleError", "RuleSyntaxError", "RuleTypeError", "did_you_mean"]


@dataclass(frozen=True)
class SourcePos:
    """A position in a rule file (1-based line and column)."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


class InputError(Exception):
    """Base class of every error caused by input (files, options, rules), not by a bug."""


class RuleError(InputError):
    """A problem in a rule file, reported with its source position and an optional hint."""

    def __init__(self, message: str, pos: SourcePos | None = None, hint: str | None = None):
        self.message = message
        self.pos = pos
        self.hint = hint
        text = f"{pos}: {message}" if pos else message
        if hint:
            text += f"\n  hint: {hint}"
        super().__init__(text)


class RuleSyntaxError(RuleError):
    """The rule file does not follow the grammar (grammar/rules.lark)."""


class RuleTypeError(RuleError):
    """The rule file parses but names unknown types, attributes, functions or variables, or mixes types."""


def did_you_mean(name: str, candidates) -> str | None:
    """A hint naming the closest known name, or None.

    >>> did_you_mean("valance", ["valence", "pos"])
    "did you mean 'valence'?"
    >>> did_you_mean("zzz", ["valence"]) is None
    True
    """
    close = difflib.get_close_matches(name, [str(c) for c in candidates], n=1)
    return f"did you mean '{close[0]}'?" if close else None
