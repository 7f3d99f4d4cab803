"""One exception hierarchy for everything a user can get wrong.

Every message names *where* the problem is (file:line:col for rule files, ring and vertex index for
geometry, rule and bindings for rewriting) so that the command line can print it as one readable line
and exit with code 2, without a traceback.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass


@dataclass(frozen=True)
class SourcePos:
    """A position in a rule file (1-based line and column)."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


class VaultgramError(Exception):
    """Base class of every error caused by input (files, options, rules), not by a bug."""


class RuleError(VaultgramError):
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


class SchemaError(VaultgramError):
    """A host graph change would break the type schema (unknown type, bad edge endpoints)."""


class RewriteError(VaultgramError):
    """A rule application or strategy failed (step limit breached, bad replay, failed function call)."""


class DomainError(VaultgramError):
    """The domain (boundaries and features) is invalid: the message names the ring or feature and vertex."""


class MeshFoldError(DomainError):
    """The quad mesh still has inverted faces after smoothing and untangling: features, curves or
    boundaries too close together for the mesh density, or a patch layout that cannot be meshed
    there. The message says where."""


class FormFindingError(VaultgramError):
    """The input cannot be form-found: bad mesh, bad supports, or no compression-only equilibrium."""


class HorizontalEquilibriumError(FormFindingError):
    """The form diagram admits no compression-only horizontal equilibrium (edges flip or vanish).

    ``edges`` lists form-edge indices, ``angles`` their angle deviations in degrees, ``result`` the
    last state of the iteration.
    """

    def __init__(self, message: str, edges=(), angles=(), result=None):
        super().__init__(message)
        self.edges = list(edges)
        self.angles = list(angles)
        self.result = result


class ConvergenceError(VaultgramError):
    """An iterative method did not reach its tolerance within its iteration cap."""


def did_you_mean(name: str, candidates) -> str | None:
    """A hint naming the closest known name, or None."""
    close = difflib.get_close_matches(name, [str(c) for c in candidates], n=1)
    return f"did you mean '{close[0]}'?" if close else None


class TessellationError(VaultgramError):
    """The thrust network cannot be tessellated: no heights, a non-manifold or inconsistently oriented
    mesh, bad options. The message names the element (face, edge, vertex) and its index."""


class MeshError(VaultgramError, ValueError):
    """A mesh, or a parameter of a mesh function, that the kernel cannot work with.

    Also a ``ValueError``, which these functions raised before: callers that catch ``ValueError``
    keep working.
    """


class NonManifoldVertexError(MeshError):
    """A vertex where the boundary of a mesh pinches (it starts two boundary halfedges).

    ``vertex`` is its index.
    """

    def __init__(self, message: str, vertex: int):
        super().__init__(message)
        self.vertex = vertex
