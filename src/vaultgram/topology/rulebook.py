"""The vault rulebook: the rule files in ``rules/`` with the functions the pipeline registers (§3.1, §4).

:func:`load_vault_rulebook` reads ``topology.vgr`` (and what it includes) from a folder, default the
rulebook shipped with vaultgram, registers the geometric helper functions of
:mod:`vaultgram.topology.functions`, and checks that the schema declares every type the pipeline
builds its graph with (:data:`vaultgram.topology.types.PIPELINE_TYPES`).
"""

from __future__ import annotations

import functools
from pathlib import Path

from vaultgram.engine.rulebook import Rulebook, load_rulebook
from vaultgram.errors import RuleError
from vaultgram.topology.functions import vault_functions
from vaultgram.topology.types import PIPELINE_TYPES, TOPOLOGY_STRATEGY

__all__ = ["load_vault_rulebook", "default_rules_dir"]


def default_rules_dir() -> Path:
    """The folder of the rulebook shipped with vaultgram (the package data ``vaultgram.rules``): its
    package's folder (``importlib.resources`` would import some 4 ms of modules to say the same)."""
    from vaultgram import rules

    return Path(rules.__file__).parent


def load_vault_rulebook(rules_dir: str | Path | None = None) -> Rulebook:
    """The rulebook in ``rules_dir`` (default: the one shipped with vaultgram), with vault functions.

    Loaded rulebooks are kept for the life of the process, keyed by the folder and the modification
    times of its rule files, so a changed file is read again.

    Raises
    ------
    RuleError
        If the folder has no ``topology.vgr``, a rule file is wrong (:class:`RuleSyntaxError`,
        :class:`RuleTypeError`), or the rulebook lacks a type or strategy the pipeline needs.

    Example
    -------
    >>> book = load_vault_rulebook()
    >>> "topology" in book.strategies
    True
    """
    directory = Path(rules_dir) if rules_dir is not None else default_rules_dir()
    path = directory / "topology.vgr"
    if not path.is_file():
        raise RuleError(f"{directory}: no topology.vgr rule file there")
    stamp = tuple(sorted((f.name, f.stat().st_mtime_ns) for f in directory.glob("*.vgr")))
    return _load_checked(path.resolve(), stamp)


@functools.lru_cache(maxsize=8)
def _load_checked(path: Path, stamp: tuple) -> Rulebook:
    """The rulebook at ``path`` with the vault functions, checked to declare the pipeline's types and
    the topology strategy (``stamp``, the files' modification times, only keys the cache)."""
    book = load_rulebook([path], vault_functions())
    missing = [t for t in PIPELINE_TYPES if t not in book.schema.node_types and t not in book.schema.edge_types]
    if missing:
        raise RuleError(
            f"{path}: the rulebook's schema lacks the type(s) {', '.join(missing)} that the pipeline builds "
            "its graph with (see rules/schema.vgr)"
        )
    if TOPOLOGY_STRATEGY not in book.strategies:
        raise RuleError(f"the rulebook ({', '.join(book.files)}) has no strategy '{TOPOLOGY_STRATEGY}'")
    return book
