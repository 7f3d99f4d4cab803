"""The bounded search over the rulebook's choice points (breadth-first), with undo, de-duplicated.

A *state* is a path through the choice points: the options taken at the first ``d`` choice points
(its ``depth``), and the first option at every later one. Its decomposition is the graph the
rulebook leaves when run that way (:meth:`~.program.Stepper.complete`). The root is the path of no
choices: today's decomposition. The children of a state are the options of its next choice point;
the first one has the same decomposition as its parent (the default takes the first option), the
others are new.

**Breadth-first**: states are visited in order of depth, and at each depth in the order of their
parents and their options (``seed`` shuffles the options of each choice point, reproducibly, for
another sample of a large space); the search stops after ``limit`` states or at ``depth``.

**Best-first** (``order="best"``): the next state expanded is the one whose decomposition has the
lowest :func:`layout_cost` (ties: the state found first), so a small ``limit`` spends its states
below the most regular layouts. The cost is read from the layout alone (no meshing): ten for each
boundary point that is a corner of a number of patches other than two (a boundary singularity,
what the paper's section 3.1 avoids; polygon corners aside), one for each other point that is the
corner of a number of patches other than four (a singularity of the layout), one for each
three-sided patch (a pole). A state without a valid decomposition is expanded last.

**Stepping with the journal**: the search keeps one graph. Going from one state to another rolls the
graph back (:meth:`HostGraph.rollback`) to their deepest common ancestor and re-applies the rule
applications recorded on the way down (:func:`vaultgram.engine.trace.replay`, which checks they
create the same ids); a state's decomposition is made from its choice point, hashed and rolled back.
No graph is copied. A state's options are found when it is expanded, not when it is made (the
stepper's ``defer_options``): most states are only hashed.

**De-duplication**: each valid decomposition's :class:`~.layout.PatchLayout` is hashed; a hash seen
before is confirmed by :func:`~.layout.same_layout`, so two states are one *variant* exactly when
their layouts are isomorphic. Every state keeps its variant, so every path to a variant is kept. A
decomposition the rules leave invalid (a face that is no 3- or 4-sided patch, a hole inside a
patch) is a state without variant, with the reason.
"""

from __future__ import annotations

import heapq
import random
import time
from dataclasses import dataclass, field

import numpy as np

from vaultgram.engine.graph import HostGraph
from vaultgram.engine.rulebook import Rulebook
from vaultgram.engine.strategy import Option
from vaultgram.engine.trace import replay
from vaultgram.errors import VaultgramError
from vaultgram.exploration.layout import PatchLayout, layout_of, same_layout
from vaultgram.exploration.program import Stepper
from vaultgram.topology.discretise import Discretisation


@dataclass
class State:
    """One state of the search (see the module docstring)."""

    id: int
    parent: int | None
    depth: int
    answers: tuple  # the chooser's answers up to this state's choice point (Scripted replays them)
    option: dict | None  # the option taken at the parent's choice point: rule, match, choice
    pc: int = 0
    options: list | None = field(default_factory=list)  # of its choice point (empty: the program ended;
    # None: not found yet -- they are found when the state is expanded)
    redo: list = field(default_factory=list)  # trace records from the parent's choice point to its own
    hash: str | None = None
    variant: int | None = None
    invalid: str | None = None  # why its decomposition is not valid


@dataclass
class Variant:
    """A distinct layout: the states that reach it (the first is the one replayed)."""

    id: int
    hash: str
    layout: PatchLayout
    states: list = field(default_factory=list)


@dataclass
class SearchResult:
    """What the search visited and found."""

    states: list[State]
    variants: list[Variant]
    hashes: int = 0  # layouts hashed
    exact_checks: int = 0  # hash matches confirmed or refuted by the exact check
    collisions: int = 0  # equal hashes of layouts that are not isomorphic
    seconds: float = 0.0
    by_hash: dict = field(default_factory=dict)  # hash -> ids of the variants with it
    expanded: list = field(default_factory=list)  # (state id, states made so far) per expansion, in order


@dataclass
class _Walker:
    """The one graph of the search, and the path of states applied to it (with the journal marks)."""

    stepper: Stepper
    rulebook: Rulebook
    path: list = field(default_factory=list)  # [(state, mark before its redo)]

    def go(self, chain: list[State]) -> None:
        """Bring the graph to the last state of ``chain`` (root first): undo, then redo."""
        common = 0
        while common < min(len(chain), len(self.path)) and self.path[common][0] is chain[common]:
            common += 1
        if common < len(self.path):
            self.stepper.graph.rollback(self.path[common][1])
            del self.path[common:]
        for state in chain[common:]:
            mark = self.stepper.graph.mark()
            replay(state.redo, self.rulebook, self.stepper.graph)
            self.path.append((state, mark))
        state = chain[-1]
        self.stepper.pc, self.stepper.answers = state.pc, list(state.answers)


def option_json(option: Option, k: int) -> dict:
    """An option as the state space records it: the rule, its match (variable -> element id), k."""
    return {"rule": option.rule, "match": {v: int(i) for v, i in sorted(option.match.binding.items())}, "choice": k}


ORDERS = ("breadth", "best")


def layout_cost(layout: PatchLayout) -> int:
    """The best-first search's cost of a layout (module docstring): lower is more regular.

    >>> import numpy as np
    >>> quad = PatchLayout(("Corner", "BoundaryVertex", "Singularity", "BoundaryVertex"), (4,),
    ...                    np.arange(4), np.zeros(4, int), np.r_[1, 2, 3, 0], np.zeros(4, bool))
    >>> layout_cost(quad)  # two boundary points with one patch: boundary singularities; one singularity
    21
    """
    count = np.bincount(layout.dart_point, minlength=layout.size())
    labels = np.array([label.rstrip("*") for label in layout.point_labels])
    boundary = labels == "BoundaryVertex"
    other = ~boundary & (labels != "Corner")
    sides = np.asarray(layout.patch_sides)
    return int(10 * np.sum(boundary & (count != 2)) + np.sum(other & (count != 4)) + np.sum(sides == 3))


def check_bounds(limit: int, depth: int) -> None:
    """``limit`` (states) must be at least 1 and ``depth`` (choice points) at least 0."""
    if limit < 1:
        raise VaultgramError(f"--limit must be at least 1 (the states to visit), got {limit}")
    if depth < 0:
        raise VaultgramError(f"--depth must be at least 0 (the choice points to explore), got {depth}")


def search(rulebook: Rulebook, graph: HostGraph, disc: Discretisation, limit: int = 100, depth: int = 8,
           seed: int | None = None, order: str = "breadth") -> SearchResult:
    """Breadth-first or best-first search (``order``) from ``graph`` (the decomposition graph before
    the rules); see the module docstring. The graph is left as it was given (everything is rolled back)."""
    check_bounds(limit, depth)
    if order not in ORDERS:
        raise VaultgramError(f"--order must be one of {', '.join(ORDERS)}, got {order!r}")
    start = time.perf_counter()
    graph.forget()
    walker = _Walker(Stepper(rulebook, graph, disc, defer_options=True), rulebook)
    result = SearchResult([], [])
    frontier = _Frontier(order == "best", result)
    frontier.push(_new_state(walker, result, None, None, None))
    while frontier and len(result.states) < limit:
        state = frontier.pop()
        if state.depth >= depth or state.options == []:
            continue
        if state.options is None:
            walker.go(_chain(result, state))
            state.options = walker.stepper.options()
        result.expanded.append((state.id, len(result.states)))
        for k in _order(state, seed):
            if len(result.states) >= limit:
                break
            frontier.push(_new_state(walker, result, state, k, _chain(result, state)))
    graph.rollback(0)
    result.seconds = time.perf_counter() - start
    return result


@dataclass
class _Frontier:
    """The states still to expand: first in, first out (breadth-first), or by least
    :func:`layout_cost`, then by id (best-first)."""

    best: bool
    result: SearchResult
    items: list = field(default_factory=list)
    head: int = 0

    def __bool__(self) -> bool:
        return self.head < len(self.items)

    def push(self, state: State) -> None:
        if not self.best:
            self.items.append(state)
            return
        cost = float("inf") if state.variant is None else layout_cost(self.result.variants[state.variant].layout)
        heapq.heappush(self.items, (cost, state.id, state))

    def pop(self) -> State:
        if not self.best:
            self.head += 1
            return self.items[self.head - 1]
        return heapq.heappop(self.items)[2]


def _order(state: State, seed: int | None) -> list[int]:
    """The options of a state's choice point in the order they are visited (shuffled by ``seed``)."""
    order = list(range(len(state.options)))
    if seed is not None:
        random.Random(f"{seed}:{state.answers}").shuffle(order)
    return order


def _chain(result: SearchResult, state: State) -> list[State]:
    """The states from the root to ``state``."""
    chain = [state]
    while chain[-1].parent is not None:
        chain.append(result.states[chain[-1].parent])
    return chain[::-1]


def _new_state(walker: _Walker, result: SearchResult, parent: State | None, k: int | None,
               chain: list[State] | None) -> State:
    """Make the state reached from ``parent`` by option ``k`` (the root when ``parent`` is None):
    run to its choice point recording the applications, then make, hash and classify its
    decomposition (a first option inherits its parent's), rolling the graph back to the parent."""
    stepper = walker.stepper
    if parent is not None:
        walker.go(chain)
    mark = stepper.graph.mark()
    stepper.clear_records()
    options = stepper.take(k) if parent is not None else stepper.advance()
    state = State(len(result.states), None if parent is None else parent.id, 0 if parent is None else parent.depth + 1,
                  tuple(stepper.answers), None if parent is None else option_json(parent.options[k], k),
                  stepper.pc, options, stepper.records())
    result.states.append(state)
    if parent is not None and k == 0:
        state.hash, state.variant, state.invalid = parent.hash, parent.variant, parent.invalid
        if state.variant is not None:
            result.variants[state.variant].states.append(state.id)
    else:
        _classify(walker, result, state)
    stepper.graph.rollback(mark)
    return state


def _classify(walker: _Walker, result: SearchResult, state: State) -> None:
    """Complete the state's decomposition from its choice point; hash it and find its variant."""
    stepper = walker.stepper
    mark = stepper.graph.mark()
    answers = list(stepper.answers)
    try:
        patches = stepper.complete()
    except VaultgramError as exc:  # the rules left a face that is no patch: not a valid decomposition
        state.invalid = str(exc)
    else:
        layout = layout_of(stepper.graph, patches)
        result.hashes += 1
        state.hash = layout.hash
        state.variant = _variant_of(result, layout)
        result.variants[state.variant].states.append(state.id)
    stepper.graph.rollback(mark)
    stepper.pc, stepper.answers = state.pc, answers


def _variant_of(result: SearchResult, layout: PatchLayout) -> int:
    """The variant of a layout: an earlier one it is isomorphic to, else a new one."""
    known = result.by_hash.setdefault(layout.hash, [])
    for v in known:
        result.exact_checks += 1
        if same_layout(result.variants[v].layout, layout):
            return v
        result.collisions += 1
    known.append(len(result.variants))
    result.variants.append(Variant(len(result.variants), layout.hash, layout))
    return known[-1]
