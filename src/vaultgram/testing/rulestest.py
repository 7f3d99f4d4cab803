"""Property-based testing of a vault rulebook (``vaultgram rules test``).

Hypothesis draws random valid domains (:func:`vaultgram.testing.domains.vault_domains`) and runs each
through the topology stage with the rulebook, its invariants checked after every rule application
or at the end of a strategy (:mod:`vaultgram.engine.invariants`), and the stage's own checks (every
patch 3- or 4-sided, Patch nodes in step with the faces, no patch enclosing a hole). A domain the
stages before the rules refuse (too tight for its spacing) is not an example. Any failure from the
rules on is a counterexample; hypothesis shrinks it to a small domain, which :func:`write_failure`
saves with the broken invariant (or stage error), the rule and its match, figures of the graph
before and after that application, and the command that replays it.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from hypothesis import HealthCheck, Phase, given, reject, settings
from hypothesis import seed as hypothesis_seed

from vaultgram.domain import check_feature_spacing, domain_from_dict
from vaultgram.engine.invariants import InvariantError
from vaultgram.errors import VaultgramError
from vaultgram.testing.domains import vault_domains
from vaultgram.topology.discretise import discretise
from vaultgram.topology.skeleton import skeleton
from vaultgram.topology.triangulation import triangulate

__all__ = ["Failure", "Summary", "check_rulebook", "write_failure"]


@dataclass
class Failure:
    """A counterexample: the domain and spacing, what broke and, for an invariant, the application."""

    domain: dict
    spacing: float
    message: str
    invariant: str | None = None
    rule: str | None = None
    binding: dict | None = None
    strategy: str | None = None
    rules_run: dict = field(default_factory=dict)
    graph: object = None  # the host graph when it broke (for the figures)
    mark: int | None = None  # its journal position before the failing application
    matched: tuple = ((), ())  # the node and the edge ids of the failing application's match

    def boundary_vertices(self) -> int:
        """The vertices of the domain's outline and holes (how small the counterexample is)."""
        return len(self.domain["outer"]) + sum(len(h) for h in self.domain.get("holes", []))


@dataclass
class Summary:
    """What a run did: examples tried, domains refused before the rules, rule applications, invariant
    checks, seconds, and the (shrunk) failure if there was one."""

    examples: int = 0
    refused: int = 0
    applications: int = 0
    invariant_checks: int = 0
    seconds: float = 0.0
    failure: Failure | None = None

    def text(self) -> str:
        return (f"{self.examples} examples ({self.refused} domains refused before the rules), "
                f"{self.applications} rule applications, {self.invariant_checks} invariant checks, "
                f"{self.seconds:.1f} s")


def run_example(data: dict, spacing: float, rulebook) -> tuple[object | None, Failure | None]:
    """One example: the decomposition (None when the domain is refused before the rules) or the failure."""
    from vaultgram.topology.decomposition import block_decomposition

    try:
        domain = domain_from_dict(data)
        check_feature_spacing(domain, spacing)
        sk = skeleton(triangulate(discretise(domain, spacing)))
    except VaultgramError:
        return None, None
    try:
        return block_decomposition(sk, rulebook, check_invariants=True), None
    except InvariantError as exc:
        app = exc.application
        failure = Failure(data, spacing, str(exc), exc.invariant, exc.rule, None, exc.strategy, exc.rules_run,
                          exc.graph)
        if app is not None:
            node_vars = rulebook.rules[app.rule].pattern.nodes
            failure.binding, failure.mark = app.binding, app.mark
            failure.matched = ([i for v, i in app.binding.items() if v in node_vars],
                               [i for v, i in app.binding.items() if v not in node_vars])
        return None, failure
    except VaultgramError as exc:
        return None, Failure(data, spacing, str(exc))


def check_rulebook(rules_dir, examples: int = 100, seed: int | None = None) -> Summary:
    """Run ``examples`` random domains through the rulebook in ``rules_dir``; derandomised (the same
    examples every run) unless a ``seed`` is given. The summary's ``failure`` is the shrunk one."""
    from vaultgram.topology.rulebook import load_vault_rulebook

    rulebook = load_vault_rulebook(rules_dir)
    summary = Summary()
    start = time.perf_counter()

    @settings(max_examples=examples, deadline=None, database=None, derandomize=seed is None,
              suppress_health_check=list(HealthCheck), report_multiple_bugs=False, print_blob=False,
              phases=(Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink))
    @given(vault_domains())
    def check(drawn):
        data, spacing = drawn
        summary.examples += 1
        dec, failure = run_example(data, spacing, rulebook)
        if failure is not None:
            summary.failure = failure  # the last one recorded is the shrunk one hypothesis replays
            raise AssertionError(failure.message)
        if dec is None:
            summary.refused += 1
            reject()
        summary.applications += len(dec.trace)
        summary.invariant_checks += dec.invariant_checks

    if seed is not None:
        check = hypothesis_seed(seed)(check)
    try:
        with _draws_from_the_seed_alone():
            check()
    except AssertionError:
        if summary.failure is None:  # pragma: no cover - an assertion of hypothesis itself
            raise
    summary.seconds = time.perf_counter() - start
    return summary


@contextmanager
def _draws_from_the_seed_alone():
    """hypothesis (6.1xx) also draws constants it finds in the source of *local* modules (those not
    in site-packages): an editable install of vaultgram would then draw other domains than an
    installed one, and any new module would change them. rules test draws without those constants,
    so that its examples depend on the seed (and hypothesis's version) alone. This reaches into
    hypothesis's internals; with a hypothesis that lacks them the draws are left as they are."""
    try:
        from hypothesis.internal.conjecture import providers
        from hypothesis.internal.constants_ast import Constants
        saved = providers._get_local_constants
        cache = providers.CONSTANTS_CACHE
    except (ImportError, AttributeError):  # another hypothesis
        yield
        return
    providers.CONSTANTS_CACHE = type(cache)(1024)  # not the choices already made from local constants
    providers._get_local_constants = Constants
    try:
        yield
    finally:
        providers._get_local_constants, providers.CONSTANTS_CACHE = saved, cache


def write_failure(failure: Failure, rules_dir, out: Path, stage: Path | None = None) -> list[str]:
    """Write the counterexample for folder ``out`` (into ``stage``, the staging folder the command
    moves into ``out``, if given): ``counterexample.json`` (the domain), ``failure.json`` (what
    broke, the rule, its match, the replay command) and, for a broken invariant after an
    application, ``before.png`` and ``after.png`` (the graph around it). Returns the lines to print."""
    from vaultgram.io.files import write_json
    from vaultgram.io.plots import plot_graph

    replay = (f"vaultgram decompose {out / 'counterexample.json'} --spacing {failure.spacing} "
              f"--rules {rules_dir} --invariants --out {out / 'replay'}")
    report = {"message": failure.message, "invariant": failure.invariant, "rule": failure.rule,
              "binding": failure.binding, "strategy": failure.strategy, "rules_run": failure.rules_run,
              "spacing": failure.spacing, "boundary_vertices": failure.boundary_vertices(), "replay": replay}
    into = out if stage is None else stage
    write_json(into / "counterexample.json", failure.domain)
    write_json(into / "failure.json", report)
    if failure.graph is not None:
        nodes, edges = failure.matched
        plot_graph(failure.graph, into / "after.png", nodes, edges, f"after {failure.rule or failure.strategy}")
        if failure.mark is not None:
            failure.graph.rollback(failure.mark)
            plot_graph(failure.graph, into / "before.png", nodes, edges, f"before {failure.rule}")
    applied = ", ".join(f"{k} x{v}" for k, v in failure.rules_run.items())
    culprit = (f"rule {failure.rule} at {failure.binding}" if failure.rule
               else f"strategy {failure.strategy} (rules applied so far: {applied})" if failure.strategy
               else "the stage checks")
    return [f"FAILED: {failure.message}", f"culprit: {culprit}",
            f"counterexample: {out / 'counterexample.json'} ({failure.boundary_vertices()} boundary vertices, "
            f"spacing {failure.spacing})", f"replay: {replay}"]
