"""An on-disk cache of checked rulebooks, keyed by the rule files' contents and the engine's code
(issue 18).

Checking a rulebook compiles every condition, expression and statement to a closure; the vault
rulebook takes some 250 million instructions to check and 120 to read back from here (about half of
a command's start-up share of it). Pickle stores functions by name only, so this module's pickler
stores a closure by its code object (``marshal``), the name of the module whose globals it reads and
the contents of its cells; the registry's functions are not stored at all: they are referenced by
name and taken from the registry the caller passes, so a host function's implementation never comes
from the cache.

An entry is used only when everything it was computed from is unchanged: its key is a hash of the
Python version, the engine's and the grammar's source files, the rulebook files' paths as given and
resolved, and the registry's signatures (names, parameter and result types, where each function is
defined); the entry lists every file the rulebook read (its includes too) with a hash of its bytes,
and is read only if each still matches. Only classes and code of the engine and the grammar, and a few
standard modules, are stored or read; anything else makes the entry not be written. Like the parse
cache (:mod:`vaultgram.grammar.cache`, whose folder it shares), nothing here may fail a run: a
missing, stale, corrupt or unwritable entry means checking the files as before.
"""

from __future__ import annotations

import functools
import hashlib
import importlib
import io
import marshal
import os
import pickle
import sys
import tempfile
import types
from pathlib import Path

from vaultgram.grammar import cache

__all__ = ["load", "store"]

_ENGINE = Path(__file__).resolve().parent
#: The packages whose classes and code an entry may hold (their sources are part of every key), and
#: the standard modules whose functions and classes it may name.
_OWN = ("vaultgram.engine", "vaultgram.grammar")
_STANDARD = frozenset({"builtins", "operator", "_operator", "math", "copyreg", "marshal", "functools",
                       "collections", "types", __name__})


@functools.lru_cache(maxsize=1)
def _code_key() -> str:
    """Hash of the Python version and of the engine's and the grammar's code (the grammar's own key,
    :func:`vaultgram.grammar.cache.source_key`, and every module of the engine)."""
    digest = hashlib.sha256(f"{sys.version}\0{marshal.version}\0{cache.source_key()}".encode())
    for path in sorted(_ENGINE.glob("*.py")):
        digest.update(b"\0" + path.name.encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


def _signature(functions) -> list[str]:
    """The registry as the checker sees it: each function's name, parameter and result types, flags
    and where it is defined (not what it does: that is taken from the live registry)."""
    return [f"{f.name}:{','.join(f.params)}:{f.returns}:{f.uses_graph}:{f.local}:"
            f"{getattr(f.fn, '__module__', '')}.{getattr(f.fn, '__qualname__', repr(f.fn))}"
            for f in functions.table.values()]


def _entry(paths: list[Path], functions) -> Path | None:
    """The entry file for these rule files and registry (None without a cache folder)."""
    base = cache.cache_dir()
    if base is None:
        return None
    digest = hashlib.sha256(_code_key().encode())
    for part in [*(f"{p}\0{p.resolve()}" for p in paths), *_signature(functions)]:
        digest.update(b"\0" + part.encode("utf-8", "surrogatepass"))
    return base / f"rulebook-{digest.hexdigest()[:32]}.pickle"


def _file_hashes(shown: list[str]) -> list[tuple[str, str]] | None:
    """Each rule file as the rulebook names it, with a hash of its bytes now (None if one is unreadable)."""
    try:
        return [(name, hashlib.sha256(Path(name).read_bytes()).hexdigest()) for name in shown]
    except OSError:
        return None


def load(paths: list[Path], functions):
    """The cached rulebook of these files checked with this registry (its functions those of
    ``functions``), or None: no cache, no entry, a changed file, an unreadable entry."""
    path = _entry(paths, functions)
    if path is None:
        return None
    try:
        with open(path, "rb") as f:
            files = _Unpickler(f, functions).load()
            if not isinstance(files, list) or _file_hashes([name for name, _ in files]) != files:
                return None
            return _Unpickler(f, functions).load()
    except Exception:  # a missing, truncated or foreign entry: check the files again
        return None


def store(book, paths: list[Path], functions) -> None:
    """Cache ``book`` (checked from ``paths`` with ``functions``), atomically; nothing is written when
    it holds what an entry may not (:data:`_OWN`, :data:`_STANDARD`) or on any error."""
    path = _entry(paths, functions)
    files = _file_hashes(book.files)
    if path is None or files is None:
        return
    buffer = io.BytesIO()
    try:
        pickle.dump(files, buffer, protocol=pickle.HIGHEST_PROTOCOL)
        _Pickler(buffer, functions).dump(book)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")
    except Exception:  # something of the host's, or an unpicklable object: run without the cache
        return
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(buffer.getvalue())
        os.replace(tmp, path)
    except OSError:
        Path(tmp).unlink(missing_ok=True)


# -- closures by their code -------------------------------------------------------------------


def _function(code, module: str, name: str, qualname: str, defaults, kwdefaults, closure):
    """A function rebuilt from its code, its module's globals, defaults and cells."""
    globals_ = (sys.modules.get(module) or importlib.import_module(module)).__dict__
    fn = types.FunctionType(code, globals_, name, defaults, closure)
    fn.__qualname__ = qualname
    fn.__kwdefaults__ = kwdefaults
    return fn


def _cell_type() -> type:
    """The type of cells, which pickle cannot name (``types.CellType`` is ``builtins.cell``, a name
    builtins does not have); read once per entry (pickle's memo), then every cell is made by calling
    it from C."""
    return types.CellType


def _allowed(module: str | None) -> bool:
    """Whether an entry may hold classes or code of this module."""
    return module is not None and (module in _STANDARD or module.startswith(_OWN))


class _Pickler(pickle.Pickler):
    """Pickles a rulebook: closures by their code, the registry and its functions as references."""

    def __init__(self, file, functions):
        super().__init__(file, protocol=pickle.HIGHEST_PROTOCOL)
        self._live = {id(functions): ("registry", "")}
        for name, f in functions.table.items():
            self._live[id(f)] = ("function", name)
            self._live.setdefault(id(f.fn), ("callable", name))

    def persistent_id(self, obj):
        return self._live.get(id(obj))

    def reducer_override(self, obj):
        if obj is types.CellType:
            return _cell_type, ()
        if isinstance(obj, (type, types.FunctionType, types.BuiltinFunctionType)):
            if not _allowed(getattr(obj, "__module__", None)):
                raise pickle.PicklingError(f"{obj!r}: not of the engine or the grammar")
            if isinstance(obj, types.FunctionType) and "<" in obj.__qualname__:
                if obj.__dict__:
                    raise pickle.PicklingError(f"{obj!r} has attributes")
                return _function, (obj.__code__, obj.__module__, obj.__name__, obj.__qualname__, obj.__defaults__,
                                   obj.__kwdefaults__, obj.__closure__)
            return NotImplemented
        if isinstance(obj, types.CodeType):
            return marshal.loads, (marshal.dumps(obj),)
        if isinstance(obj, types.CellType):  # empty, filled after (a closure may hold itself), by setattr
            try:
                return types.CellType, (), (None, {"cell_contents": obj.cell_contents})
            except ValueError:  # an empty cell
                return types.CellType, ()
        return NotImplemented


class _Unpickler(pickle.Unpickler):
    """Reads what :class:`_Pickler` wrote: the registry's functions from ``functions``, classes and
    functions only of the modules an entry may hold."""

    def __init__(self, file, functions):
        super().__init__(file)
        self._functions = functions

    def persistent_load(self, pid):
        kind, name = pid
        if kind == "registry":
            return self._functions
        f = self._functions.table[name]
        return f if kind == "function" else f.fn

    def find_class(self, module: str, name: str):
        if not _allowed(module):
            raise pickle.UnpicklingError(f"{module}.{name}: not of the engine or the grammar")
        return super().find_class(module, name)
