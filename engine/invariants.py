"""Invariants: named conditions on the whole host graph, checked while strategies run.

``invariant name after each|at end [in s1, s2] { condition }`` declares a boolean expression with
no pattern variables: it reads the graph through quantifiers (``forall p: Patch { ... }``,
``exists``, ``count``, ``sum``) and functions. An ``after each`` invariant is checked after every
rule application made while one of its strategies runs (any strategy when it names none), an
``at end`` one when such a strategy has finished. A broken invariant is an :class:`InvariantError`
naming the invariant, the part of its condition that is false (the first false operand of a chain
of ``and``), the element a ``forall`` fails at, and the application after which it broke.

The engine checks invariants only when asked (``Runner(check_invariants=True)``): an ``after each``
check is a pass over the graph per application. ``vaultgram rules test`` asks.

>>> from vaultgram.engine.graph import HostGraph
>>> from vaultgram.engine.rulebook import rulebook_from_text
>>> from vaultgram.engine.strategy import Runner
>>> book = rulebook_from_text('''
... schema s { node A { w: int = 0 } }
... invariant small after each { forall a: A { a.w < 2 } }
... rule bump { match { a: A } set a.w = a.w + 1 }
... strategy grow { bump fixpoint max 5 }
... ''')
>>> g = HostGraph(book.schema)
>>> n = g.add_node("A")
>>> try:
...     Runner(book, g, check_invariants=True).run("grow")
... except InvariantError as exc:
...     print(exc.invariant, exc.rule, exc.reason)
small bump a.w < 2 is false for a = 0 (A)
"""

from __future__ import annotations

from dataclasses import dataclass

from vaultgram.grammar import ast

from .checker import RuleChecker, conjuncts, describe
from .errors import RewriteError, RuleTypeError
from .expressions import Compiled, Symbol, VType


@dataclass(frozen=True)
class Part:
    """One operand of an invariant's chain of ``and``; for a ``forall``, its body and variable too, so
    that a failure names the element."""

    text: str
    fn: Compiled
    body: Compiled | None = None
    var: str = ""
    types: frozenset = frozenset()
    body_text: str = ""

    def failure(self, graph) -> str | None:
        """Why this part is false on ``graph`` (None: it holds)."""
        if self.body is None:
            return None if self.fn(graph, {}) else f"{self.text} is false"
        binding: dict = {}
        for x in sorted(graph.of_types(self.types)):
            binding[self.var] = x
            if not self.body(graph, binding):
                kind = graph.node_type(x) if graph.has_node(x) else graph.edge_type(x)
                return f"{self.body_text} is false for {self.var} = {x} ({kind})"
        return None


@dataclass(frozen=True)
class CompiledInvariant:
    """A checked invariant: when it is checked, for which strategies, and its parts."""

    name: str
    when: str  # "each" or "end"
    strategies: frozenset[str]
    parts: tuple[Part, ...]
    source: ast.Invariant

    def concerns(self, running: list[str]) -> bool:
        """Whether it is checked while the strategies ``running`` (outermost first) run."""
        return not self.strategies or any(s in self.strategies for s in running)

    def failure(self, graph) -> str | None:
        """Why the invariant is broken on ``graph`` (None: it holds)."""
        for part in self.parts:
            reason = part.failure(graph)
            if reason:
                return reason
        return None


class InvariantError(RewriteError):
    """An invariant is broken: after an application (``rule``, ``binding``), or at a strategy's end."""

    def __init__(self, invariant: CompiledInvariant, reason: str, application=None, strategy: str | None = None):
        self.invariant = invariant.name
        self.reason = reason
        self.application = application
        self.rule = application.rule if application is not None else None
        self.strategy = strategy
        self.graph = None  # the graph it broke on, and the rules applied in the strategy (set by the runner)
        self.rules_run: dict[str, int] = {}
        where = (f"after rule {application.rule} at {application.binding}" if application is not None
                 else f"at the end of strategy {strategy}")
        super().__init__(f"invariant {invariant.name} ({invariant.source.pos}) broken {where}: {reason}")


def compile_invariant(checker: RuleChecker, inv: ast.Invariant) -> CompiledInvariant:
    """Type-check an invariant: a boolean condition over the graph (no pattern variables)."""
    parts = tuple(_part(checker, expr) for expr in conjuncts(inv.condition))
    return CompiledInvariant(inv.name, inv.when, frozenset(inv.strategies), parts, inv)


def _part(checker: RuleChecker, expr) -> Part:
    compiled = checker.compiler.compile(expr, checker.type_symbols)
    if compiled.type.kind != "value" or compiled.type.name not in ("bool", "any"):
        raise RuleTypeError(f"an invariant must be a condition (bool), not {compiled.type}", expr.pos)
    if isinstance(expr, ast.Quantifier) and expr.kind == "forall":
        kind = "node" if checker.schema.is_node_type(expr.type) else "edge"
        scope = {**checker.type_symbols, expr.var: Symbol(VType(kind, expr.type))}
        body = checker.compiler.compile(expr.body, scope)
        return Part(describe(expr), compiled.fn, body.fn, expr.var, checker.schema.subtypes(expr.type),
                    describe(expr.body))
    return Part(describe(expr), compiled.fn)
