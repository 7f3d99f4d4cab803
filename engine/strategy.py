"""Running rules and strategies: ``once``, ``all``, ``fixpoint``, rule groups, choice points, traces.

* ``once`` applies the first match (smallest key) of the first rule of the group, by priority, that
  has one.
* ``all`` applies, for each rule of the group by priority, a maximal set of *parallel-independent*
  matches in key order: a match is taken unless it reads an element (node or edge it binds) that an
  already taken match deletes or changes, or deletes or changes an element an already taken match
  reads. Each taken match is checked again just before it is applied (an earlier application may
  have made a NAC or condition fail) and skipped if it no longer holds.
* ``fixpoint`` repeats: apply the first match of the highest-priority rule that has one, until no
  rule of the group matches. Match sets are kept current incrementally (:mod:`.incremental`).
  Exceeding the step limit raises a :class:`RewriteError` naming the rules still firing.
* ``choose`` marks a choice point: where a plain step takes the first option, a chooser (a function
  given to the :class:`Runner`) picks among the options (rule, match) -- exploration uses it.

Every application is appended to the runner's :class:`~.trace.Trace`.
"""

from __future__ import annotations

import time
from collections import Counter
from dataclasses import dataclass, field
from typing import Callable, Mapping, NamedTuple, Sequence

from vaultgram.grammar import ast

from .errors import RewriteError, SelfLoop
from .graph import HostGraph, _collector_paused
from .incremental import MatchSet
from .invariants import InvariantError
from .matcher import Match, Matcher, Matches
from .memo import TableMemo
from .rewriter import Application, apply_rule, footprint, only_creates
from .rulebook import Rulebook, describe_step
from .trace import Trace

DEFAULT_MAX_STEPS = 10_000


class Option(NamedTuple):
    """What a chooser chooses among: a rule and one of its matches."""

    rule: str
    match: Match


Chooser = Callable[[Sequence[Option]], int]


def first_option(options: Sequence[Option]) -> int:
    """The default chooser: the first option (highest priority, smallest key)."""
    return 0


@dataclass
class StepReport:
    """What one strategy step did."""

    step: str
    applications: int
    seconds: float
    by_rule: dict[str, int] = field(default_factory=dict)


class Runner:
    """Applies the rules of a rulebook to a graph, recording a trace. With a ``memo``, whole-graph
    searches at graph states searched before are looked up (for callers that roll back and run
    again, like exploration)."""

    def __init__(self, rulebook: Rulebook, graph: HostGraph, chooser: Chooser = first_option,
                 check_invariants: bool = False, memo: TableMemo | None = None):
        self.rulebook = rulebook
        self.graph = graph
        self.chooser = chooser
        self.trace = Trace()
        self.reports: list[StepReport] = []
        self.check_invariants = check_invariants
        self.invariant_checks = 0  # how many times an invariant was evaluated
        self.self_loops = 0  # matches skipped because applying them would create a self-loop
        self.running: list[str] = []  # the strategies running, outermost first
        self.memo = memo

    def check(self, when: str, app: Application | None = None, strategy: str | None = None) -> None:
        """Check the invariants of kind ``when`` ("each", "end") that concern the running strategies;
        raise :class:`InvariantError` for the first broken one (in declaration order)."""
        running = self.running if strategy is None else [strategy]
        for inv in self.rulebook.invariants.values():
            if inv.when == when and inv.concerns(running):
                self.invariant_checks += 1
                reason = inv.failure(self.graph)
                if reason:
                    exc = InvariantError(inv, reason, app, strategy)
                    exc.graph = self.graph
                    exc.rules_run = dict(Counter(a.rule for a in self.trace.applications))
                    raise exc

    # -- single rules ----------------------------------------------------------------------------

    def matcher(self, rule_name: str, params: Mapping[str, object] | None = None) -> Matcher:
        rule = self.rulebook.rules.get(rule_name)
        if rule is None:
            raise RewriteError(f"unknown rule '{rule_name}'")
        return Matcher(rule, self.graph, params, self.memo)

    def apply(self, matcher: Matcher, match: Match) -> Application | None:
        """Apply one match and record it in the trace; None (counted in ``self_loops``) when the
        application would create a self-loop, so the rule does not apply there."""
        return self.apply_binding(matcher, match.binding)

    def apply_binding(self, matcher: Matcher, binding: dict[str, int]) -> Application | None:
        """:meth:`apply` for a match given as its binding (pattern variable -> id; the application
        record keeps this dict), so that ``all`` applies the rows of a match table without making a
        Match for each (issue 18)."""
        try:
            app = apply_rule(matcher.rule, self.graph, binding, matcher.values, {**matcher.values, **matcher.fixed})
        except SelfLoop:
            self.self_loops += 1
            return None
        self.trace.record(app)
        if self.check_invariants:
            self.check("each", app)
        return app

    def apply_once(self, rule_name: str, params=None) -> Application | None:
        matcher = self.matcher(rule_name, params)
        match = matcher.first()
        return self.apply(matcher, match) if match else None

    def apply_all(self, rule_name: str, params=None) -> list[Application]:
        return self._all([self.matcher(rule_name, params)], False)

    def fixpoint(self, rule_names: Sequence[str], max_steps: int = DEFAULT_MAX_STEPS, params=None) -> int:
        return self._fixpoint([self.matcher(n, (params or {}).get(n)) for n in rule_names], max_steps, False)

    # -- strategies ------------------------------------------------------------------------------

    def run(self, strategy_name: str) -> list[StepReport]:
        """Run a strategy of the rulebook; return a report per step."""
        strategy = self.rulebook.strategies.get(strategy_name)
        if strategy is None:
            raise RewriteError(f"unknown strategy '{strategy_name}'")
        self.running.append(strategy_name)
        try:
            for step in strategy.steps:
                self._run_step(step)
            if self.check_invariants:
                self.check("end", strategy=strategy_name)
        finally:
            self.running.pop()
        return self.reports

    def _run_step(self, step) -> None:
        """Run one step of a strategy (another strategy for ``run``) and report it."""
        if isinstance(step, ast.Run):
            self.run(step.strategy)
            return
        start, before = time.perf_counter(), len(self.trace)
        self.run_step(step)
        new = self.trace.applications[before:]
        by_rule = dict(Counter(app.rule for app in new))
        self.reports.append(StepReport(describe_step(step), len(new), time.perf_counter() - start, by_rule))

    def run_step(self, step: ast.Step) -> None:
        matchers = self._group(step)
        if step.mode == "once":
            self._once(matchers, step.choose)
        elif step.mode == "all":
            self._all(matchers, step.choose)
        else:
            self._fixpoint(matchers, step.max_steps or DEFAULT_MAX_STEPS, step.choose)

    def offers_choice(self, step: ast.Step) -> bool:
        """Whether running a ``choose`` step now would ask the chooser at once, before it applies
        anything: two options or more (``once``: matches of its rules together; ``all`` and
        ``fixpoint``: rules with a match). Found by depth-first searches that stop at the second
        match, not by finding every match: exploration stops there and finds the options only for
        the states it expands."""
        found = 0
        for matcher in self._group(step):
            found += matcher.count_upto(2 - found if step.mode == "once" else 1)
            if found >= 2:
                return True
        return False

    # -- modes -----------------------------------------------------------------------------------

    def _group(self, step: ast.Step) -> list[Matcher]:
        """The step's matchers, by priority (highest first), then in the order the step names them."""
        matchers = [
            Matcher(self.rulebook.rules[ref.name], self.graph, self.rulebook.arguments(ref), self.memo)
            for ref in step.rules
        ]
        order = {id(m): i for i, m in enumerate(matchers)}
        return sorted(matchers, key=lambda m: (-m.rule.priority, order[id(m)]))

    def _options(self, matchers: list[Matcher], first_only: bool) -> list[Option]:
        options = []
        for m in matchers:
            found = m.all()
            if found and first_only:
                return [Option(m.rule.name, found[0])]
            options.extend(Option(m.rule.name, match) for match in found)
        return options

    def _once(self, matchers: list[Matcher], choose: bool) -> None:
        options = self._options(matchers, first_only=not choose)
        if options:
            k = self.chooser(options) if choose else 0
            rule_name, match = options[k]
            app = self.apply(next(m for m in matchers if m.rule.name == rule_name), match)
            if app is not None:
                app.choice = k if choose else None

    def _all(self, matchers: list[Matcher], choose: bool) -> list[Application]:
        if choose:
            candidates = [m for m in matchers if m.first() is not None]
            if not candidates:
                return []
            options = [Option(m.rule.name, m.first()) for m in candidates]
            choice = self.chooser(options)
            matchers = [candidates[choice]]
        applied = self._apply_independent(matchers)
        if choose:
            for app in applied:
                app.choice = choice
        return applied

    @_collector_paused
    def _apply_independent(self, matchers: list[Matcher]) -> list[Application]:
        """``all`` without the choice: for each matcher in turn, its independent matches (module
        docstring), each checked again and applied. The collector is
        paused: the loop makes a few short-lived objects per match and none in a cycle, and a
        collection re-scans the whole graph (a third of the time at 10^4 nodes, issue 18)."""
        applied: list[Application] = []
        reads: set = set()
        writes: set = set()
        independent = all(only_creates(m.rule.statements) for m in matchers)  # no footprint to keep apart
        for matcher in matchers:
            if independent:
                selected = matcher.all()
            else:
                selected = []
                for match in matcher.all():
                    r = read_set(matcher, match)
                    w = footprint(matcher.rule, self.graph, matcher.scope(match)).writes()
                    if r & writes or w & reads:
                        continue
                    selected.append(match)
                    reads |= r
                    writes |= w
            applied.extend(self._apply_selected(matcher, selected, independent))
        return applied

    def _apply_selected(self, matcher: Matcher, selected, only_creations: bool) -> list[Application]:
        """Apply the selected matches in order, each checked again first (``only_creations``: the
        step only creates, so :meth:`Matcher.still_matches` checks what creations may change)."""
        applied = []
        check = matcher.still_matches if only_creations else matcher.check
        for binding in selected.bindings() if isinstance(selected, Matches) else (m.binding for m in selected):
            if check(binding):
                app = self.apply_binding(matcher, binding)
                if app is not None:
                    applied.append(app)
        return applied

    def _fixpoint(self, matchers: list[Matcher], max_steps: int, choose: bool) -> int:
        sets = [MatchSet(m, lazy=not choose) for m in matchers]  # a choice asks every set each step
        steps = 0
        while True:
            if choose:
                options = [Option(s.rule.name, s.first()) for s in sets if s.first() is not None]
                if not options:
                    return steps
                k = self.chooser(options)
                chosen = next(s for s in sets if s.rule.name == options[k].rule)
                match = options[k].match
            else:
                chosen = next((s for s in sets if s.first() is not None), None)
                if chosen is None:
                    return steps
                match = chosen.first()
            if steps >= max_steps:
                firing = [s.rule.name for s in sets if len(s)]
                raise RewriteError(
                    f"fixpoint did not terminate within {max_steps} steps; rules still firing: {', '.join(firing)}"
                )
            app = self.apply(chosen.matcher, match)
            if app is None:  # a self-loop: the match is dropped until a change near it re-matches it
                chosen.discard(match)
                continue
            app.choice = k if choose else None
            steps += 1
            changes = self.graph.changes_since(app.mark)
            for s in sets:
                s.update(changes)


def read_set(matcher: Matcher, match: Match) -> set[tuple[str, int]]:
    """The elements a match binds, tagged by kind (for parallel independence)."""
    nodes = matcher.rule.pattern.nodes
    return {("n" if v in nodes else "e", i) for v, i in match.binding.items()}
