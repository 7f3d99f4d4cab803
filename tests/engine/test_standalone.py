"""The engine and the grammar stand alone: they import nothing of vaultgram but themselves.

``engine/`` may import ``vaultgram.engine`` and ``vaultgram.grammar``; ``grammar/`` only
``vaultgram.grammar``. Checked on the source, with ``ast``, so that an import inside a function counts
too.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from paths import REPO

ALLOWED = {"engine": ("vaultgram.engine", "vaultgram.grammar"), "grammar": ("vaultgram.grammar",)}


def imported_modules(path: Path) -> list[tuple[int, str]]:
    """(line, absolute module name) of every import in a module (relative imports resolved)."""
    package = "vaultgram." + path.parent.name
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            out.extend((node.lineno, alias.name) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.rsplit(".", node.level - 1)[0]
                out.append((node.lineno, f"{base}.{node.module}" if node.module else base))
            else:
                out.append((node.lineno, node.module))
    return out


def _inside(module: str, packages) -> bool:
    return any(module == p or module.startswith(p + ".") for p in packages)


@pytest.mark.parametrize("folder", sorted(ALLOWED))
def test_imports_nothing_of_vaultgram_outside_itself(folder):
    sources = sorted((REPO / folder).glob("*.py"))
    assert sources, f"no modules found in {folder}/"
    wrong = [
        f"{path.relative_to(REPO)}:{line}: {module}"
        for path in sources
        for line, module in imported_modules(path)
        if _inside(module, ("vaultgram",)) and not _inside(module, ALLOWED[folder])
    ]
    assert not wrong, "imports outside the package:\n" + "\n".join(wrong)


def test_the_check_sees_relative_and_function_level_imports(tmp_path):
    module = tmp_path / "grammar" / "m.py"
    module.parent.mkdir()
    module.write_text(
        "from .ast import Rule\n\ndef f():\n    from vaultgram.errors import X\n    import vaultgram.files\n"
    )
    assert imported_modules(module) == [
        (1, "vaultgram.grammar.ast"),
        (4, "vaultgram.errors"),
        (5, "vaultgram.files"),
    ]
