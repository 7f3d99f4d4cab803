"""The errors of the engine: schema violations and failed rewrites, beside the rule-language errors.

All of them derive from :class:`~vaultgram.grammar.errors.InputError`, the root of every error
caused by input; the rule-file errors are re-exported from :mod:`vaultgram.grammar.errors` so that
engine code and its callers find every error here.
"""

from __future__ import annotations

from vaultgram.grammar.errors import InputError, RuleError, RuleSyntaxError, RuleTypeError, SourcePos, did_you_mean

__all__ = [
    "InputError",
    "RuleError",
    "RuleSyntaxError",
    "RuleTypeError",
    "SourcePos",
    "did_you_mean",
    "SchemaError",
    "RewriteError",
    "TraceError",
    "SelfLoop",
]


class SchemaError(InputError):
    """A host graph change would break the type schema (unknown type, bad edge endpoints)."""


class RewriteError(InputError):
    """A rule application or strategy failed (step limit breached, bad replay, failed function call)."""


class SelfLoop(RewriteError):
    """An application would create an edge from a node to itself: the rule does not apply at that
    match (the graph is left as it was); strategies skip the match and count it."""


class TraceError(RewriteError):
    """A trace file cannot be read as JSON."""
