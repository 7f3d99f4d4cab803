"""The decomposition as a resumable program: run the rulebook up to its next choice point, and on.

:func:`~vaultgram.topology.decomposition.block_decomposition` runs the ``topology`` strategy, turns
the faces into ``Patch`` nodes, then runs the patching strategies, asking its chooser at every
``choose`` step. Here the same sequence is a flat list of :class:`Instruction` (each strategy step,
``run`` steps expanded in place, and the host's patch step between them), and a :class:`Stepper`
runs it on one graph until the chooser is asked to pick among two or more options: there it stops
(:meth:`Stepper.advance` returns the options) and :meth:`Stepper.take` resumes with the option
chosen. A choice with a single option is taken without stopping. Every answer the chooser gave is
kept (:attr:`Stepper.answers`), so :class:`Scripted` with those answers makes ``block_decomposition``
take the same path from scratch.

A step that stopped is run again from its start when resumed: ``once`` and ``all`` steps choose
before applying anything, and a ``fixpoint`` step is a loop whose state is the graph, so the options
offered again are the same.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

from vaultgram.engine.graph import HostGraph
from vaultgram.engine.memo import TableMemo
from vaultgram.engine.rulebook import Rulebook, describe_step
from vaultgram.engine.strategy import Option, Runner
from vaultgram.engine.trace import Trace
from vaultgram.grammar import ast
from vaultgram.topology.decomposition import final_patches, patch_strategies_of, start_patching
from vaultgram.topology.discretise import Discretisation
from vaultgram.topology.patches import Patch
from vaultgram.topology.types import TOPOLOGY_STRATEGY

PATCH_STEP = "patch nodes"  # the host's step between the topology and the patching strategies


@dataclass(frozen=True)
class Instruction:
    """One strategy step (``step``), or the host's patch step (``step`` None). ``noop_by_default``:
    a ``choose ... once`` step whose first option is a rule that changes nothing (``leave``), so
    the default chooser leaves the graph as it is (:func:`noop_by_default`)."""

    strategy: str
    step: ast.Step | None
    noop_by_default: bool = False


def noop_by_default(rulebook: Rulebook, step: ast.Step) -> bool:
    """Whether a step, run with the default chooser (the first option), certainly changes nothing:
    a ``choose ... once`` step whose first rule (by priority, then by order) has an empty pattern,
    no condition and no statement. Its one match, the empty one, is then the first option: applying
    it leaves the graph as it was. :meth:`Stepper.complete` skips such steps instead of matching
    every other option only to take the first (the optional rules' steps in patching.vgr)."""
    if not (step.choose and step.mode == "once" and step.rules):
        return False
    order = {ref.name: i for i, ref in reversed(list(enumerate(step.rules)))}
    first = min(step.rules, key=lambda ref: (-rulebook.rules[ref.name].priority, order[ref.name]))
    rule = rulebook.rules[first.name]
    pattern = rule.pattern
    return not (pattern.nodes or pattern.edges or pattern.conditions or rule.nacs or rule.statements or rule.params)


def instructions(rulebook: Rulebook, strategy: str) -> list[Instruction]:
    """The steps of a strategy in the order they run, ``run`` steps replaced by their strategy's."""
    out = []
    for step in rulebook.strategies[strategy].steps:
        if isinstance(step, ast.Run):
            out.extend(instructions(rulebook, step.strategy))
        else:
            out.append(Instruction(strategy, step, noop_by_default(rulebook, step)))
    return out


def decomposition_program(rulebook: Rulebook) -> list[Instruction]:
    """The instructions :func:`block_decomposition` runs: topology, the patch step, the patching."""
    patching = patch_strategies_of(rulebook)
    program = instructions(rulebook, TOPOLOGY_STRATEGY) + [Instruction(PATCH_STEP, None)]
    for name in patching:
        program.extend(instructions(rulebook, name))
    return program


def choice_steps(rulebook: Rulebook) -> list[str]:
    """The ``choose`` steps of the decomposition program, as written (empty: nothing to explore)."""
    return [describe_step(i.step) for i in decomposition_program(rulebook) if i.step is not None and i.step.choose]


class Scripted:
    """A chooser that gives ``answers`` in order, then the first option (as the default chooser).

    >>> chooser = Scripted([1, 0, 2])
    >>> [chooser(["a", "b", "c"]) for _ in range(5)]
    [1, 0, 2, 0, 0]
    """

    def __init__(self, answers: Sequence[int]):
        self.answers = list(answers)
        self.calls = 0

    def __call__(self, options) -> int:
        k = self.answers[self.calls] if self.calls < len(self.answers) else 0
        self.calls += 1
        if not 0 <= k < len(options):
            raise IndexError(f"choice {k} at choice point {self.calls - 1}, which has {len(options)} options")
        return k


class _Suspend(Exception):
    """Raised by the stepper's chooser to stop a run at a choice point."""

    def __init__(self, options: Sequence[Option] | None):
        super().__init__("choice point")
        self.options = None if options is None else list(options)


@dataclass
class Stepper:
    """Runs the decomposition program on ``graph`` between choice points (see the module docstring).

    ``pc`` is the instruction to run next (the one that stopped, at a choice point) and ``answers``
    the chooser's answers so far; both are plain values, so a caller that rolls the graph back to an
    earlier state restores them with it.

    ``defer_options``: stop at a ``choose`` step as soon as it is known to offer two options or more
    (:meth:`Runner.offers_choice`, which stops searching at the second match), without finding them
    all; :meth:`advance` then returns None, and :meth:`options` finds them later, if they are
    wanted (a search finds them only for the states it expands). It stops at the same step, with
    the same answers, as finding them all would.
    """

    rulebook: Rulebook
    graph: HostGraph
    disc: Discretisation
    pc: int = 0
    answers: list = field(default_factory=list)
    defer_options: bool = False

    def __post_init__(self):
        self.program = decomposition_program(self.rulebook)
        # the memo: a step run again at a state (each option of a choice point, the completion from
        # it) looks its searches up instead of repeating them
        self.runner = Runner(self.rulebook, self.graph, self._choose, memo=TableMemo())
        self._pending: int | None = None
        self._default = False

    def _choose(self, options: Sequence[Option]) -> int:
        """The runner's chooser: the pending answer, the only option, the default, or stop here."""
        if self._pending is not None:
            k, self._pending = self._pending, None
        elif len(options) == 1 or self._default:
            k = 0
        else:
            raise _Suspend(options)
        self.answers.append(k)
        return k

    def advance(self, answer: int | None = None) -> list[Option] | None:
        """Run on (the stopped step first answering ``answer``) until the next choice point: its
        options (None: not found yet, ``defer_options``), or ``[]`` when the program has ended."""
        self._pending = answer
        while self.pc < len(self.program):
            try:
                self._execute(self.program[self.pc])
            except _Suspend as stop:
                return stop.options
            self.pc += 1
        return []

    def take(self, k: int) -> list[Option] | None:
        """Resume at the current choice point with option ``k``; the next choice point's options."""
        return self.advance(k)

    def options(self) -> list[Option]:
        """The options of the choice point the stepper stopped at (its step run to find them all)."""
        defer, self.defer_options = self.defer_options, False
        try:
            return self.advance()
        finally:
            self.defer_options = defer

    def complete(self) -> list[Patch]:
        """Run to the end with the first option at every choice point; the checked patches
        (raises like ``block_decomposition`` when the rules leave a face that is no patch)."""
        self._default = True
        try:
            self.advance()
        finally:
            self._default = False
        return final_patches(self.graph, self.disc, bool(patch_strategies_of(self.rulebook)))

    def _execute(self, instruction: Instruction) -> None:
        if self._default and instruction.noop_by_default:
            return  # the default option changes nothing: no need to match the others (complete)
        step = instruction.step
        if step is None:
            start_patching(self.graph, self.disc, self.runner.trace, bool(patch_strategies_of(self.rulebook)))
            return
        if (self.defer_options and step.choose and self._pending is None and not self._default
                and self.runner.offers_choice(step)):
            raise _Suspend(None)  # the choice point: its options are found if they are asked for
        self.runner.run_step(step)

    def records(self) -> list[dict]:
        """What the runner applied since :meth:`clear_records`, as trace records (for replay)."""
        return self.runner.trace.to_json()

    def clear_records(self) -> None:
        self.runner.trace = Trace()
