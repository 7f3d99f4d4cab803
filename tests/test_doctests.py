"""Every module of the package imports, and the examples in its docstrings run (doctest).

The doctests are collected here rather than by pytest's ``--doctest-modules``: that option names a
module after its directory, so it would import ``engine/`` and ``grammar/`` as top-level ``engine``
and ``grammar`` -- second copies of modules the package installs as ``vaultgram.engine`` and
``vaultgram.grammar``. Here each module is imported by its package name, and each docstring with
examples is one test, named after the object it documents (``vaultgram.pipeline.form_find``).
"""

from __future__ import annotations

import copy
import doctest
import importlib
import importlib.util
import pkgutil
from pathlib import Path

import pytest

from paths import REPO

#: The packages whose modules are tested: vaultgram and the three it installs from outside src/vaultgram.
PACKAGES = ("vaultgram", "vaultgram.engine", "vaultgram.grammar", "vaultgram.rules")
#: pytest's own default for ``doctest_optionflags``.
OPTIONFLAGS = doctest.ELLIPSIS


def _submodules(name: str, path: Path) -> list[str]:
    """Dotted names of the modules under the package directory ``path``, found without importing them."""
    out = []
    for info in pkgutil.iter_modules([str(path)]):
        out.append(f"{name}.{info.name}")
        if info.ispkg:
            out.extend(_submodules(f"{name}.{info.name}", path / info.name))
    return out


def package_modules() -> list[str]:
    """Every module of :data:`PACKAGES`, by dotted name (the packages themselves included)."""
    names = set()
    for package in PACKAGES:
        spec = importlib.util.find_spec(package)
        names.add(package)
        for path in spec.submodule_search_locations:
            names.update(_submodules(package, Path(path)))
    return sorted(names)


MODULES = package_modules()


def _doctests() -> list[doctest.DocTest]:
    """The docstrings with examples of every module that imports (one that does not fails
    :func:`test_module_imports`, not the collection)."""
    finder = doctest.DocTestFinder(exclude_empty=True)
    found = []
    for name in MODULES:
        try:
            module = importlib.import_module(name)
        except Exception:  # reported by test_module_imports
            continue
        found.extend(t for t in finder.find(module, name) if t.examples)
    return sorted(found, key=lambda t: t.name)


DOCTESTS = _doctests()


def test_the_package_has_its_modules():
    """The walk finds the stages' modules and those installed from engine/ and grammar/."""
    assert {"vaultgram.pipeline", "vaultgram.meshing.coons", "vaultgram.engine.graph", "vaultgram.grammar.parser",
            "vaultgram.tessellation.voussoirs"} <= set(MODULES)
    assert {t.name.split(".")[1] for t in DOCTESTS} >= {"engine", "grammar", "pipeline", "geometry", "topology"}


@pytest.mark.parametrize("name", MODULES)
def test_module_imports(name):
    module = importlib.import_module(name)
    assert module.__name__ == name


@pytest.mark.parametrize("test", DOCTESTS, ids=[t.name for t in DOCTESTS])
def test_docstring_examples(test, monkeypatch):
    """The examples of one docstring, run from the repository root (they read ``examples/...``)."""
    monkeypatch.chdir(REPO)
    test = copy.copy(test)
    test.globs = dict(test.globs)  # the runner clears the globals it is given
    report: list[str] = []
    runner = doctest.DocTestRunner(verbose=False, optionflags=OPTIONFLAGS)
    result = runner.run(test, out=report.append)
    assert result.failed == 0, "".join(report)
