"""The package runs on Python 3.9 (Rhino 8's CPython, Grasshopper's script components): ``vermin``
finds nothing that needs a newer Python.

No 3.9 interpreter can be installed here, so the check is static. ``vermin``'s detection of ``X | Y``
unions is marked unstable and also reports unions in function annotations, which
``from __future__ import annotations`` leaves unevaluated (legal on 3.9); those, and only those, are
set aside -- a union evaluated at run time (a type alias, ``isinstance(x, A | B)``) fails the test.
"""

from __future__ import annotations

import ast
import builtins
import functools
import importlib
import runpy
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from paths import REPO

pytest.importorskip("vermin")  # the test extra installs it

ROOTS = {"vaultgram": REPO / "src" / "vaultgram", "vaultgram.engine": REPO / "engine",
         "vaultgram.grammar": REPO / "grammar", "vaultgram.rules": REPO / "rules"}
SOURCES = list(ROOTS.values())
TARGET = "3.9"


def _vermin(*args: str) -> list[str]:
    """vermin's parsable report (``file:line:col:py2:py3:feature`` lines, then the summary ``:::py2:py3:``)."""
    exe = Path(sys.executable).with_name("vermin")
    cmd = [str(exe) if exe.exists() else shutil.which("vermin"), "--no-tips", "--format", "parsable",
           "--no-parse-comments", f"-t={TARGET}-", "--violations", *args]
    lines = subprocess.run(cmd, capture_output=True, text=True, check=False).stdout.splitlines()
    assert any(x.startswith(":::") for x in lines), lines  # vermin ran and summed up
    return lines


def _violations(lines: list[str]) -> list[tuple[str, int, str]]:
    """(file, line, feature) of each reported use of something newer than the target."""
    out = []
    for line in lines:
        parts = line.rsplit(":", 5)
        if len(parts) == 6 and parts[0] and parts[1] and parts[5]:
            out.append((parts[0], int(parts[1]), parts[5]))
    return out


def _annotations(tree: ast.Module) -> list[ast.expr]:
    """Every annotation of a module: function arguments and returns, annotated assignments."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            args = node.args
            out += [a.annotation for a in [*args.posonlyargs, *args.args, *args.kwonlyargs,
                                            *filter(None, [args.vararg, args.kwarg])] if a.annotation]
            out += [node.returns] if node.returns else []
        elif isinstance(node, ast.AnnAssign):
            out.append(node.annotation)
    return out


def _is_type(node: ast.expr, namespace: dict) -> bool:
    """Whether an operand of ``|`` is a type (or None) in the module's namespace or the builtins."""
    if isinstance(node, ast.Constant):
        return node.value is None
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitOr):
        return _is_type(node.left, namespace) or _is_type(node.right, namespace)
    if isinstance(node, ast.Name):
        value = namespace.get(node.id, getattr(builtins, node.id, None))
        return isinstance(value, type) or getattr(value, "__module__", None) == "typing"
    return False


@functools.lru_cache(maxsize=None)
def _evaluated_unions(path: str) -> dict:
    """Line -> the ``|`` operations of a module outside the annotations that
    ``from __future__ import annotations`` leaves unevaluated."""
    tree = ast.parse(Path(path).read_text())
    future = any(isinstance(n, ast.ImportFrom) and n.module == "__future__" and
                 any(a.name == "annotations" for a in n.names) for n in tree.body)
    lazy = {id(n) for a in (_annotations(tree) if future else []) for n in ast.walk(a)}
    out: dict = {}
    for n in ast.walk(tree):
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.BitOr) and id(n) not in lazy:
            out.setdefault(n.lineno, []).append(n)
    return out


def _runtime_unions(path: str, line: int, namespace: dict) -> list[int]:
    """The lines of ``X | Y`` of types evaluated at run time at ``line`` of a module."""
    return [n.lineno for n in _evaluated_unions(path).get(line, []) if _is_type(n, namespace)]


def _namespace(path: str) -> dict:
    """The globals of the package module at ``path`` (imported by its dotted name)."""
    for prefix, root in ROOTS.items():
        if Path(path).is_relative_to(root):
            parts = [p for p in Path(path).relative_to(root).with_suffix("").parts if p != "__init__"]
            return vars(importlib.import_module(".".join([prefix, *parts])))
    return runpy.run_path(path)


@pytest.fixture(scope="module")
def reported():
    """What vermin reports over the package, its (unstable) check of ``X | Y`` unions on."""
    return _violations(_vermin("--feature", "union-types", *map(str, SOURCES)))


def test_nothing_needs_more_than_python_3_9(reported):
    assert [v for v in reported if not v[2].startswith("union types")] == []


def test_no_union_type_is_evaluated_at_run_time(reported):
    assert reported, "vermin reported no union at all: the check would not see one"  # the annotations
    runtime = [(f, n) for f, line, _ in reported for n in _runtime_unions(f, line, _namespace(f))]
    assert runtime == []


def test_the_checks_see_a_runtime_union(tmp_path):
    """The filter keeps what matters: a type alias ``A | B`` in a module with the future import."""
    bad = tmp_path / "alias.py"
    bad.write_text("from __future__ import annotations\n\n\ndef f(x: int | None) -> None:\n    pass\n\n\n"
                   "Alias = int | str\nflags = {1} | {2}\n")
    found = _violations(_vermin("--feature", "union-types", str(bad)))
    assert [n for f, line, _ in found for n in _runtime_unions(f, line, _namespace(f))] == [8]
    assert 4 in [n for _, n, _ in found]  # the annotation vermin reports, which the filter sets aside
