"""``vaultgram explore`` and ``vaultgram replay``: search, evaluate, rank, write; rebuild one variant.

:func:`explore` searches the choice points of the rulebook on a domain (:mod:`.search`), evaluates
every distinct variant (:mod:`.evaluate`, in parallel by :mod:`.parallel`), scores them and marks the
Pareto front (:mod:`.ranking`). :func:`write_exploration` writes, inside an output folder:

* ``state_space.json``: the options, the choice steps, every state (its parent, depth, the chooser's
  answers, its hash and variant, or why it is invalid), every edge (the rule, the match and the
  choice taken) and every variant (its hash, the states that reach it, its metrics, score and
  whether it is on the Pareto front), with the search's counts;
* ``variants/vNNN/``: each variant's ``decomposition.json``, ``patches.json`` and ``mesh.json``;
* ``variants.json``: ``{"states_visited", "seconds", "variants": [{"id", "decomposition",
  "metrics"}]}`` (``seconds`` is the one value that differs between runs);
* ``index.html``: the gallery (:mod:`.gallery`).

:func:`replay_variant` rebuilds one variant from the domain and the state space: the same files.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from vaultgram.domain import Domain
from vaultgram.errors import VaultgramError
from vaultgram.exploration.evaluate import FILES, Evaluation, Job, evaluate
from vaultgram.exploration.gallery import gallery_html
from vaultgram.exploration.parallel import evaluate_all
from vaultgram.exploration.program import choice_steps
from vaultgram.exploration.ranking import DEFAULT_PARETO, pareto_front, score
from vaultgram.exploration.search import SearchResult, check_bounds, search
from vaultgram.io.files import read_json, write_json, write_text
from vaultgram.topology.decomposition import decomposition_graph
from vaultgram.topology.rulebook import load_vault_rulebook

STATE_SPACE = "state_space.json"


@dataclass(frozen=True)
class ExploreOptions:
    """What an exploration depends on (recorded in the state space, for replay)."""

    spacing: float = 0.02
    rules_dir: str | None = None
    limit: int = 100
    depth: int = 8
    seed: int | None = None
    target_length: float | None = None
    smooth: int = 20
    pareto: tuple = DEFAULT_PARETO
    formfind: bool = False
    order: str = "breadth"  # of the search: "breadth" or "best" (first), exploration.search

    def to_json(self) -> dict:
        return {"spacing": self.spacing, "rules": self.rules_dir, "limit": self.limit, "depth": self.depth,
                "seed": self.seed, "target_length": self.target_length, "smooth": self.smooth,
                "pareto": list(self.pareto), "formfind": self.formfind, "order": self.order}


@dataclass(frozen=True)
class Exploration:
    """A search, the evaluations of its variants (by variant id) and the ranking."""

    domain: Domain
    options: ExploreOptions
    choice_steps: tuple
    result: SearchResult
    evaluations: tuple
    front: frozenset

    def rows(self) -> list[dict]:
        """One row per variant: id, folder, metrics (with its score), Pareto flag, paths, answers."""
        rows = []
        for v, ev in zip(self.result.variants, self.evaluations):
            first = self.result.states[v.states[0]]
            rows.append({"id": v.id, "folder": variant_folder(v.id), "hash": v.hash, "states": list(v.states),
                         "answers": list(first.answers), "metrics": {**ev.metrics, "score": score(ev.metrics)},
                         "pareto": v.id in self.front})
        return rows


def variant_folder(variant: int) -> str:
    """Where a variant's files go, relative to the output folder."""
    return f"variants/v{variant:03d}"


def explore(domain: Domain, options: ExploreOptions, workers: int = 1, client=None) -> Exploration:
    """Search, evaluate and rank the variants of ``domain`` (see the module docstring)."""
    check_bounds(options.limit, options.depth)
    rulebook = load_vault_rulebook(options.rules_dir)
    from vaultgram.meshpipeline import plan_skeleton  # as evaluate does: the mesh path's modules on use

    sk = plan_skeleton(domain, options.spacing, options.rules_dir)
    result = search(rulebook, decomposition_graph(sk, rulebook), sk.triangulation.disc, options.limit,
                    options.depth, options.seed, options.order)
    jobs = [_job(domain, options, result, v.id) for v in result.variants]
    evaluations = tuple(evaluate_all(jobs, workers, client))
    rows = [{"id": e.variant, "metrics": {**e.metrics, "score": score(e.metrics)}} for e in evaluations]
    front = frozenset(pareto_front([r for r in rows if "error" not in r["metrics"]], options.pareto))
    return Exploration(domain, options, tuple(choice_steps(rulebook)), result, evaluations, front)


def _job(domain: Domain, options: ExploreOptions, result: SearchResult, variant: int) -> Job:
    v = result.variants[variant]
    first = result.states[v.states[0]]
    return Job(variant, tuple(first.answers), domain, options.spacing, options.rules_dir, options.target_length,
               options.smooth, v.hash, options.formfind)


def state_space_json(exp: Exploration) -> dict:
    """The state space (module docstring); no timings, so the same exploration gives the same file."""
    r = exp.result
    states = [{"id": s.id, "parent": s.parent, "depth": s.depth, "answers": list(s.answers), "hash": s.hash,
               "variant": s.variant, "invalid": s.invalid} for s in r.states]
    edges = [{"from": s.parent, "to": s.id, **s.option} for s in r.states if s.parent is not None]
    counts = {"states": len(r.states), "variants": len(r.variants), "hashes": r.hashes,
              "exact_checks": r.exact_checks, "collisions": r.collisions,
              "invalid": sum(s.invalid is not None for s in r.states)}
    return {"domain": exp.domain.name, "options": exp.options.to_json(), "choice_steps": list(exp.choice_steps),
            "counts": counts, "states": states, "edges": edges, "variants": exp.rows()}


def variants_json(exp: Exploration) -> dict:
    """``variants.json`` as the issue specifies it."""
    return {"states_visited": len(exp.result.states), "seconds": round(exp.result.seconds, 3),
            "variants": [{"id": row["id"], "decomposition": f"{row['folder']}/decomposition.json",
                          "metrics": row["metrics"]} for row in exp.rows()]}


def write_exploration(exp: Exploration, out: Path) -> None:
    """Every file of an exploration, into ``out`` (a staging folder)."""
    for row, ev in zip(exp.rows(), exp.evaluations):
        write_files(ev, out / row["folder"])
    write_json(out / STATE_SPACE, state_space_json(exp))
    write_json(out / "variants.json", variants_json(exp))
    write_text(out / "index.html", gallery_html(exp.domain.name, exp.rows(), [e.svg for e in exp.evaluations],
                                                exp.options.pareto))


def write_files(ev: Evaluation, folder: Path) -> None:
    """A variant's files (bytes from :func:`~.evaluate.evaluate`) into ``folder``."""
    folder.mkdir(parents=True, exist_ok=True)
    for name, data in sorted(ev.files.items()):
        (folder / name).write_bytes(data)


def replay_variant(domain: Domain, state_space_path: str | Path, variant: int) -> Evaluation:
    """Rebuild variant ``variant`` of a state space from ``domain``: the evaluation explore made."""
    space = read_json(state_space_path)
    try:
        options, rows = space["options"], {row["id"]: row for row in space["variants"]}
    except (KeyError, TypeError):
        raise VaultgramError(f"{state_space_path}: not a state space written by vaultgram explore") from None
    if variant not in rows:
        raise VaultgramError(f"{state_space_path}: no variant {variant} (it has {len(rows)}: 0 to {len(rows) - 1})")
    row = rows[variant]
    job = Job(variant, tuple(row["answers"]), domain, options["spacing"], options["rules"], options["target_length"],
              options["smooth"], row["hash"], bool(options.get("formfind")))
    try:
        return evaluate(job)
    except RuntimeError as exc:  # the domain is not the one explored (or the rules changed)
        raise VaultgramError(f"{state_space_path}: {exc}; replay with the domain and rules it was explored with")


__all__ = ["ExploreOptions", "Exploration", "explore", "write_exploration", "replay_variant", "FILES",
           "state_space_json", "variants_json"]
