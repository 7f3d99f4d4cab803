"""The layout's promises, read from the source with ``ast``: short functions, no import cycles.

(That the engine and the grammar import nothing of the vault package is tests/engine/test_standalone.py.)
"""

from __future__ import annotations

import ast
from pathlib import Path

import networkx as nx
import pytest

from paths import REPO

ROOTS = {"vaultgram": REPO / "src" / "vaultgram", "vaultgram.engine": REPO / "engine",
         "vaultgram.grammar": REPO / "grammar", "vaultgram.rules": REPO / "rules"}


def _modules() -> dict[str, Path]:
    """Every module of the package, by dotted name."""
    out = {}
    for prefix, root in ROOTS.items():
        for path in sorted(root.rglob("*.py")):
            rel = path.relative_to(root).with_suffix("")
            parts = [p for p in rel.parts if p != "__init__"]
            out[".".join([prefix, *parts])] = path
    return out


MODULES = _modules()


def _imports(name: str, path: Path) -> set[str]:
    """The package modules ``name`` imports anywhere in its body (function-level imports too)."""
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(
                    package.split(".")[: len(package.split(".")) - node.level + 1] + ([base] if base else [])
                )
            for a in node.names:
                out.add(f"{base}.{a.name}" if f"{base}.{a.name}" in MODULES else base)
    return {m for m in out if m in MODULES and m != name}


def test_no_function_is_longer_than_80_lines():
    long = []
    for name, path in MODULES.items():
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.end_lineno - node.lineno + 1 > 80:
                long.append(f"{path.relative_to(REPO)}:{node.lineno} {node.name}")
    assert not long


def test_modules_import_each_other_without_cycles():
    graph = nx.DiGraph()
    for name, path in MODULES.items():
        graph.add_node(name)
        graph.add_edges_from((name, other) for other in _imports(name, path))
    # a package's __init__ re-exporting its own modules is not a cycle through them
    for name in [n for n in graph if MODULES[n].name == "__init__.py"]:
        graph.remove_edges_from([(m, name) for m in list(graph.predecessors(name)) if m.startswith(name + ".")])
    assert list(nx.simple_cycles(graph)) == []


def test_every_package_is_installed():
    """pyproject.toml lists every package folder, so a non-editable install (CI's) ships them all."""
    tomllib = pytest.importorskip("tomllib")  # Python 3.11+
    listed = set(tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"])
    folders = {name for name, path in MODULES.items() if path.name == "__init__.py"}
    assert folders == listed
