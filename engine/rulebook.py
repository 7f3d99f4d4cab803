"""Loading a rulebook: parse rule files, build the schema, check every rule and strategy.

All errors are found here, before any graph is touched: syntax errors (from the parser, with
file:line:col and a hint), and type errors (unknown types, attributes, functions, variables; type
mismatches; duplicate names; strategies naming unknown rules or parameters).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable

from vaultgram.grammar import ast
from vaultgram.grammar.parser import load_files, parse_text

from . import bookcache
from .checker import CompiledRule, RuleChecker, describe
from .errors import RuleTypeError, did_you_mean
from .expressions import ExpressionCompiler, Functions
from .invariants import CompiledInvariant, compile_invariant
from .schema import TypeSchema, build_schema
from .values import value_conforms


@dataclass
class Rulebook:
    """A checked set of rule files: the schema, the rules and the strategies, by name in file order."""

    schema: TypeSchema
    rules: dict[str, CompiledRule]
    strategies: dict[str, ast.Strategy]
    functions: Functions
    files: list[str]
    checker: RuleChecker
    invariants: dict[str, CompiledInvariant] = field(default_factory=dict)

    def arguments(self, ref: ast.RuleRef) -> dict[str, object]:
        """The parameter values a strategy step gives a rule (constants, checked at load time)."""
        return {name: constant_value(expr, self.checker) for name, expr in ref.args}

    def summary(self) -> dict:
        """Types, rules and strategies, for ``vaultgram rules check``."""
        return {
            "files": self.files,
            "types": self.schema.summary(),
            "rules": {
                name: {
                    "params": [f"{p.name}: {p.type}" for p in r.source.params],
                    "priority": r.priority,
                    "nacs": len(r.nacs),
                }
                for name, r in self.rules.items()
            },
            "strategies": {
                name: [describe_step(step) for step in s.steps] for name, s in self.strategies.items()
            },
            "invariants": {name: describe_invariant(inv.source) for name, inv in self.invariants.items()},
        }


def load_rulebook(paths: Iterable[str | Path], functions: Functions | None = None) -> Rulebook:
    """Parse and check rule files (and their includes), or read the rulebook they gave last time with
    a registry of the same signatures from the cache (:mod:`.bookcache`; the functions are always
    ``functions``')."""
    paths, functions = [Path(p) for p in paths], functions or Functions()
    book = bookcache.load(paths, functions)
    if book is None:
        book = _build(load_files(paths), functions)
        bookcache.store(book, paths, functions)
    return book


def rulebook_from_text(text: str, functions: Functions | None = None, filename: str = "<string>") -> Rulebook:
    """Check a rulebook given as one string (includes are not allowed there)."""
    rule_file = parse_text(text, filename)
    if rule_file.includes:
        raise RuleTypeError("includes need a file on disk; use load_rulebook", rule_file.includes[0].pos)
    return _build([rule_file], functions or Functions())


def _build(files: list[ast.RuleFile], functions: Functions) -> Rulebook:
    schemas = [s for f in files for s in f.schemas]
    constant = ExpressionCompiler(build_schema([], None), functions)
    schema = build_schema(schemas, lambda expr: constant.compile(expr, {}).fn(None, {}))
    checker = RuleChecker(schema, ExpressionCompiler(schema, functions))

    rules: dict[str, CompiledRule] = {}
    for f in files:
        for rule in f.rules:
            if rule.name in rules:
                raise RuleTypeError(
                    f"rule '{rule.name}' is defined twice (first at {rules[rule.name].source.pos})", rule.pos
                )
            rules[rule.name] = checker.compile_rule(rule)

    strategies: dict[str, ast.Strategy] = {}
    for f in files:
        for strategy in f.strategies:
            if strategy.name in strategies or strategy.name in rules:
                raise RuleTypeError(f"strategy '{strategy.name}' reuses a rule or strategy name", strategy.pos)
            strategies[strategy.name] = strategy
    for strategy in strategies.values():
        _check_strategy(strategy, rules, strategies, checker)
    _check_no_recursion(strategies)
    invariants = _invariants(files, checker, rules, strategies)
    return Rulebook(schema, rules, strategies, functions, [f.path for f in files], checker, invariants)


def _invariants(files, checker: RuleChecker, rules, strategies) -> dict[str, CompiledInvariant]:
    """The files' invariants, checked: unique names, strategies that exist, boolean conditions."""
    out: dict[str, CompiledInvariant] = {}
    for inv in (i for f in files for i in f.invariants):
        if inv.name in out or inv.name in rules or inv.name in strategies:
            raise RuleTypeError(f"invariant '{inv.name}' reuses a rule, strategy or invariant name", inv.pos)
        for name in inv.strategies:
            if name not in strategies:
                raise RuleTypeError(f"invariant {inv.name}: unknown strategy '{name}'", inv.pos,
                                    did_you_mean(name, strategies))
        out[inv.name] = compile_invariant(checker, inv)
    return out


def describe_invariant(inv: ast.Invariant) -> str:
    """An invariant's header written back in the language's syntax: ``after each in s``."""
    when = "after each" if inv.when == "each" else "at end"
    return f"{when} in {', '.join(inv.strategies)}" if inv.strategies else when


def _check_strategy(strategy: ast.Strategy, rules, strategies, checker: RuleChecker) -> None:
    for step in strategy.steps:
        if isinstance(step, ast.Run):
            if step.strategy not in strategies:
                raise RuleTypeError(
                    f"unknown strategy '{step.strategy}'", step.pos, did_you_mean(step.strategy, strategies)
                )
            continue
        if step.mode not in ("once", "all", "fixpoint"):
            raise RuleTypeError(f"unknown mode '{step.mode}' (once, all or fixpoint)", step.pos)
        if step.max_steps is not None and step.max_steps <= 0:
            raise RuleTypeError("max must be a positive number of steps", step.pos)
        for ref in step.rules:
            rule = rules.get(ref.name)
            if rule is None:
                raise RuleTypeError(f"unknown rule '{ref.name}'", ref.pos, did_you_mean(ref.name, rules))
            given = {name for name, _ in ref.args}
            missing = [p for p in rule.params if p not in given | set(rule.defaults) | set(rule.node_params)]
            if missing:
                raise RuleTypeError(f"rule {ref.name} needs parameter(s) {', '.join(missing)} (no default)", ref.pos,
                                    f"give them in the strategy: {ref.name}({missing[0]} = ...)")
            for name, expr in ref.args:
                param = rule.params.get(name)
                if param is None:
                    raise RuleTypeError(
                        f"rule {ref.name} has no parameter '{name}'", expr.pos, did_you_mean(name, rule.params)
                    )
                if name in rule.node_params:
                    raise RuleTypeError(f"node parameter '{name}' cannot be given in a strategy", expr.pos)
                value = constant_value(expr, checker)
                if not value_conforms(value, param.type):
                    raise RuleTypeError(
                        f"parameter '{name}' of {ref.name} must be {param.type}, got {value!r}", expr.pos
                    )


def constant_value(expr, checker: RuleChecker):
    """The value of an expression with no variables (strategy arguments, defaults)."""
    return checker.compiler.compile(expr, checker.type_symbols).fn(None, {})


def _check_no_recursion(strategies: dict[str, ast.Strategy]) -> None:
    def visit(name, stack):
        if name in stack:
            cycle = " -> ".join([*stack[stack.index(name):], name])
            raise RuleTypeError(f"strategies run each other in a cycle: {cycle}", strategies[name].pos)
        for step in strategies[name].steps:
            if isinstance(step, ast.Run):
                visit(step.strategy, [*stack, name])

    for name in strategies:
        visit(name, [])


def _rule_ref(ref) -> str:
    """``name`` or ``name(arg = value, ...)`` as written in the strategy."""
    if not ref.args:
        return ref.name
    return f"{ref.name}({', '.join(f'{k} = {describe(v)}' for k, v in ref.args)})"


def describe_step(step) -> str:
    """A strategy step written back in the language's syntax."""
    if isinstance(step, ast.Run):
        return f"run {step.strategy}"
    names = ", ".join(_rule_ref(r) for r in step.rules)
    group = names if len(step.rules) == 1 else "{ " + names + " }"
    limit = f" max {step.max_steps}" if step.max_steps else ""
    return f"{'choose ' if step.choose else ''}{group} {step.mode}{limit}"
