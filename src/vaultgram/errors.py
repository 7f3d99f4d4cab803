"""One exception hierarchy for everything a user can get wrong.

Every message names *where* the problem is (file:line:col for rule files, ring and vertex index for
geometry, rule and bindings for rewriting) so that the command line can print it as one readable line
and exit with code 2, without a traceback.

The root class is the rule language's :class:`~vaultgram.grammar.errors.InputError`, named
``VaultgramError`` here, so that ``except VaultgramError`` catches every error of the grammar and the
engine too. The rule and rewriting errors live with the packages that raise them
(:mod:`vaultgram.grammar.errors`, :mod:`vaultgram.engine.errors`) and are re-exported here; the
errors of the vault pipeline are defined here.
"""

from __future__ import annotations

from vaultgram.engine.errors import RewriteError, SchemaError
from vaultgram.grammar.errors import InputError as VaultgramError
from vaultgram.grammar.errors import RuleError, RuleSyntaxError, RuleTypeError, SourcePos, did_you_mean

__all__ = [
    "VaultgramError",
    "SourcePos",
    "RuleError",
    "RuleSyntaxError",
    "RuleTypeError",
    "SchemaError",
    "RewriteError",
    "DomainError",
    "MeshFoldError",
    "FormFindingError",
    "HorizontalEquilibriumError",
    "ConvergenceError",
    "VerticalEquilibriumError",
    "TessellationError",
    "MeshError",
    "NonManifoldVertexError",
    "did_you_mean",
    "VaultgramWarning",
]


class VaultgramWarning(UserWarning):
    """Something in an input that vaultgram did not use (an entity of a CAD drawing it cannot place,
    ...): the message names it. The command line prints each as one ``warning:`` line."""


class _Placed:
    """An error that may know where in the plan it is: ``places``, when the raiser knows them, are the
    plan polygons (or segments) where the problem is, each a sequence of (x, y); ``vaultgram design``
    draws them in an error figure (:mod:`vaultgram.io.figures.errorplot`)."""

    def __init__(self, message: str, places=()):
        super().__init__(message)
        self.places = list(places)


class DomainError(_Placed, VaultgramError):
    """The domain (boundaries and features) is invalid: the message names the ring or feature and
    vertex, and ``places`` (:class:`_Placed`) may show it."""


class MeshFoldError(DomainError):
    """The quad mesh still has inverted faces after smoothing and untangling: features, curves or
    boundaries too close together for the mesh density, or a patch layout that cannot be meshed
    there. The message says where."""


class FormFindingError(_Placed, VaultgramError):
    """The input cannot be form-found: bad mesh, bad supports, or no compression-only equilibrium;
    ``places`` (:class:`_Placed`) may hold the plan segments of the edges that flipped or collapsed."""


class HorizontalEquilibriumError(FormFindingError):
    """The form diagram admits no compression-only horizontal equilibrium (edges flip or vanish).

    ``edges`` lists form-edge indices, ``angles`` their angle deviations in degrees, ``result`` the
    last state of the iteration.
    """

    def __init__(self, message: str, edges=(), angles=(), result=None, places=()):
        super().__init__(message, places)
        self.edges = list(edges)
        self.angles = list(angles)
        self.result = result


class ConvergenceError(VaultgramError):
    """An iterative method did not reach its tolerance within its iteration cap."""


class VerticalEquilibriumError(ConvergenceError):
    """Vertical equilibrium did not converge: the heights and the self-weight on them (or the scale for
    a given height) kept changing; a lower vault converges sooner."""


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
