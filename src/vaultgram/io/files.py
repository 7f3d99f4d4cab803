"""Reading input files with clear errors, and writing outputs (JSON, OBJ) atomically.

Outputs are written to a temporary file in the destination folder and renamed into place, so a
failed or interrupted run never leaves a half-written file behind; JSON is written with sorted keys
so the same result gives byte-identical files. A command writes all its files in a staging folder
(:func:`output_folder`) and moves them into the output folder only once every one is written: the
output folder is complete or untouched.
"""

from __future__ import annotations

import gc
import json
import math
import os
import shutil
import signal
import tempfile
import threading
from contextlib import contextmanager
from itertools import chain
from pathlib import Path
from typing import TYPE_CHECKING, Iterable, Iterator, Sequence

from vaultgram.errors import VaultgramError
from vaultgram.interrupts import deferred

if TYPE_CHECKING:  # numpy is imported where it is used: `vaultgram --help` does not need it
    import numpy as np


def read_json(path: str | Path):
    """Read a JSON file, turning every failure into a VaultgramError that names the file and place."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise VaultgramError(f"{path}: cannot read: {exc.strerror}") from None
    except UnicodeDecodeError as exc:
        raise VaultgramError(f"{path}: not UTF-8 text (byte {exc.start}): not a JSON file") from None
    return parse_json(text, path)


def parse_json(text: str, path, error: type = VaultgramError):
    """The JSON document in ``text``, or an ``error`` naming ``path`` and the place: invalid JSON (line
    and column), ``NaN`` or ``Infinity`` (not JSON numbers), nesting too deep to read.

    >>> parse_json('{"a": [1, 2]}', "x.json")
    {'a': [1, 2]}
    >>> parse_json('[NaN]', "x.json")
    Traceback (most recent call last):
    ...
    vaultgram.grammar.errors.InputError: x.json: invalid JSON: NaN is not a JSON number
    """
    try:
        return json.loads(text, parse_constant=_no_constant)
    except json.JSONDecodeError as exc:
        raise error(f"{path}:{exc.lineno}:{exc.colno}: invalid JSON: {exc.msg}") from None
    except RecursionError:
        raise error(f"{path}: invalid JSON: nested too deeply") from None
    except ValueError as exc:  # NaN or Infinity
        raise error(f"{path}: invalid JSON: {exc}") from None


def _no_constant(name: str):
    raise ValueError(f"{name} is not a JSON number")


@contextmanager
def output_folder(path: str | Path) -> Iterator[Path]:
    """A staging folder beside ``path`` to write a run's files in; when the block ends normally they
    are moved into ``path`` (made if need be; files of the same names replaced), with interrupts
    held off while they move. If the block fails or is interrupted, the staging folder is removed
    and ``path`` is untouched.

    >>> import tempfile
    >>> out = Path(tempfile.mkdtemp()) / "out"
    >>> with output_folder(out) as stage:
    ...     write_text(stage / "a.txt", "a")
    ...     out.exists()
    False
    >>> sorted(p.name for p in out.iterdir())
    ['a.txt']
    """
    path = Path(path)
    try:
        stage = _make_stage(path)
    except OSError as exc:
        raise _output_error(path, exc) from None
    try:
        with _terminate_unwinds():
            yield stage
            _check_targets(stage, path)
            _move_into(stage, path)
    except OSError as exc:
        raise _output_error(path, exc) from None
    finally:
        shutil.rmtree(stage, ignore_errors=True)


@contextmanager
def _terminate_unwinds() -> Iterator[None]:
    """SIGTERM raises SystemExit(143) in the block (as SIGINT raises KeyboardInterrupt), so that the
    staging folder is removed on the way out rather than left behind by the default handler, which
    ends the process at once; never inside the import system (:func:`vaultgram.interrupts.deferred`).
    The handler is set only in the main thread (elsewhere it cannot be)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, deferred(_raise_exit))
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _raise_exit(signum) -> None:
    raise SystemExit(128 + signum)


def _make_stage(path: Path) -> Path:
    """The staging folder beside ``path`` (its parent made if need be)."""
    if path.exists() and not path.is_dir():
        raise VaultgramError(f"{path}: the output folder is a file")
    for parent in path.parents:
        if parent.exists() and not parent.is_dir():
            raise VaultgramError(f"{path}: the output folder is below a file ({parent})")
    path.parent.mkdir(parents=True, exist_ok=True)
    return Path(tempfile.mkdtemp(prefix=f".{path.name}.", dir=path.parent))


def _output_error(path: Path, exc: OSError) -> VaultgramError:
    """An operating-system error while writing as one line naming the file (permission, disk full...)."""
    where = exc.filename if exc.filename else path
    if isinstance(where, str) and Path(where).parent.name.startswith(f".{path.name}."):
        where = path / Path(where).name  # a file of the staging folder: name it by where it was going
    return VaultgramError(f"{where}: cannot write: {exc.strerror or exc}")


def _check_targets(stage: Path, path: Path) -> None:
    """Refuse, before anything moves, a staged file whose place in ``path`` is taken by a folder (or a
    staged folder whose place is a file): the output folder is complete or untouched."""
    for item in sorted(stage.iterdir()):
        target = path / item.name
        if target.exists() and target.is_dir() != item.is_dir():
            kind = "a folder" if target.is_dir() else "a file"
            raise VaultgramError(f"{target}: cannot write: {kind} is in the way")


def _move_into(stage: Path, path: Path) -> None:
    """Move the staged files into ``path`` by renames, SIGINT and SIGTERM held until all have moved."""
    held = {signal.SIGINT, signal.SIGTERM}
    signal.pthread_sigmask(signal.SIG_BLOCK, held)
    try:
        path.mkdir(exist_ok=True)
        for item in sorted(stage.iterdir()):
            target = path / item.name
            if target.is_dir() and not target.is_symlink():
                shutil.rmtree(target)
            os.replace(item, target)
    finally:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, held)


@contextmanager
def collector_paused() -> Iterator[None]:
    """Python's cyclic garbage collector paused for the block (restored as it was). A step that
    keeps hundreds of thousands of small objects alive while it allocates more would have the
    collector walk them again and again, for nothing: reference counting frees them. Turning
    10^5-face arrays into lists for JSON is one (every collection walks the lists made so far); the
    tessellation is another (the rulebook's host graph of the network, the faces as tuples, the
    courses' cost tables; the engine's graphs hold no reference cycles): at 10^5 faces its
    collections took about 0.4 s."""
    was_enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was_enabled:
            gc.enable()


#: glibc's ``mallopt`` parameters, and the values :func:`freed_memory_kept` leaves them at: no more
#: mappings than glibc's default, and the thresholds its own rule settles at once blocks of 32 MB
#: have been freed (``DEFAULT_MMAP_THRESHOLD_MAX``, and twice that for trimming).
M_TRIM_THRESHOLD, M_MMAP_THRESHOLD, M_MMAP_MAX = -1, -3, -4
AFTER = {M_MMAP_MAX: 65536, M_MMAP_THRESHOLD: 32 * 2**20, M_TRIM_THRESHOLD: 64 * 2**20}


@contextmanager
def freed_memory_kept() -> Iterator[None]:
    """Large blocks freed in the block are kept by the C allocator for the next ones, and what is
    left free goes back to the system at its end. glibc maps every block over 32 MB afresh and
    unmaps it when freed, so each large numpy temporary has its pages faulted in and zeroed by the
    kernel again: a step that makes and drops thousands of 10^6-row arrays (the tessellation at
    10^6 faces) spent a fifth of its time there. Inside, nothing is mapped (``M_MMAP_MAX`` 0) or
    trimmed; after, :data:`AFTER`, and ``malloc_trim`` gives the free pages back. Elsewhere than
    glibc nothing changes. Results are the same bits: only where the arrays live changes. Setting the
    thresholds turns glibc's own adjustment of them off for the rest of the process; the values set
    are those it settles at."""
    libc = _glibc()
    if libc is None:
        yield
        return
    libc.mallopt(M_TRIM_THRESHOLD, -1)  # read as the largest size_t: never
    libc.mallopt(M_MMAP_MAX, 0)
    try:
        yield
    finally:
        for parameter, value in AFTER.items():
            libc.mallopt(parameter, value)
        libc.malloc_trim(0)


def _glibc():
    """The process's C library if it is glibc (``gnu_get_libc_version``, ``mallopt``, ``malloc_trim``),
    else None."""
    import ctypes

    try:
        libc = ctypes.CDLL(None)
    except (OSError, TypeError):  # TypeError: Windows wants a name
        return None
    return libc if all(hasattr(libc, f) for f in ("gnu_get_libc_version", "mallopt", "malloc_trim")) else None


def write_text(path: str | Path, text: str) -> None:
    """Write text atomically, as UTF-8 (:func:`write_bytes`)."""
    write_bytes(path, text.encode("utf-8"))


def write_bytes(path: str | Path, data: bytes) -> None:
    """Write bytes atomically (:func:`write_pieces`)."""
    write_pieces(path, [data])


def write_pieces(path: str | Path, pieces: Iterable[bytes]) -> None:
    """Write the ``pieces`` one after the other, atomically: to a temporary file in the same folder
    (removed if a piece fails), then renamed. A large file is made and written a piece at a time,
    never held whole (voussoirs.obj at 10^6 faces is 440 MB).

    >>> import tempfile
    >>> path = Path(tempfile.mkdtemp()) / "a.txt"
    >>> write_pieces(path, (b"%d " % k for k in range(3)))
    >>> path.read_bytes(), [p.name for p in path.parent.iterdir()]
    (b'0 1 2 ', ['a.txt'])
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(tmp, "wb") as file:
            file.writelines(pieces)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    tmp.replace(path)


def write_json(path: str | Path, data) -> None:
    """Write JSON atomically, keys sorted (deterministic bytes), compact, by orjson: about 15 times
    faster than the json module's compact C encoder and 50 times its indented one (a 10^5-face design
    took 10 s to write). Numbers read back the same; a float is written in its shortest form
    (``0.00001``, not ``1e-05``), NaN as null. Written a piece at a time (:func:`_json_pieces`).

    >>> import tempfile
    >>> path = Path(tempfile.mkdtemp()) / "a.json"
    >>> write_json(path, {"b": [0.1, 2], "a": {3: "x"}})
    >>> path.read_text()
    '{"a":{"3":"x"},"b":[0.1,2]}'
    """
    write_pieces(path, _json_pieces(data))


#: Items of a list or array that :func:`_json_pieces` writes at a time.
JSON_ITEMS = 1 << 16


def _json_pieces(data) -> Iterator[bytes]:
    """The bytes of :func:`_dumps` of ``data`` in pieces: a dict with string keys a value at a time, in
    orjson's order of the keys (sorted by code point), and a list or array of more than
    :data:`JSON_ITEMS` items that many at a time: the text of a 10^6-face tessellation (244 MB) is
    never made whole, its pieces are reused memory (made whole, it took the kernel 0.1-0.4 s to map
    afresh, and added its size to the process's peak).

    >>> b"".join(_json_pieces({"b": [0.5, 2], "a": {"c": (1, 2)}, "": None}))
    b'{"":null,"a":{"c":[1,2]},"b":[0.5,2]}'
    """
    if isinstance(data, dict) and data and all(isinstance(key, str) for key in data):
        for i, key in enumerate(sorted(data)):
            yield (b"," if i else b"{") + _dumps(key) + b":"
            yield from _json_pieces(data[key])
        yield b"}"
    elif isinstance(data, (list, tuple)) or getattr(data, "ndim", 0) > 0:
        if len(data) <= JSON_ITEMS:
            yield _dumps(data)
            return
        for start in range(0, len(data), JSON_ITEMS):
            yield (b"," if start else b"[") + _dumps(data[start:start + JSON_ITEMS])[1:-1]
        yield b"]"
    else:
        yield _dumps(data)


def _dumps(data) -> bytes:
    """orjson's compact text of ``data``: keys sorted, other keys than strings written as strings,
    numpy arrays taken whole (:func:`_listed` for those it cannot take)."""
    import orjson

    return orjson.dumps(data, default=_listed, option=orjson.OPT_SORT_KEYS | orjson.OPT_NON_STR_KEYS
                        | orjson.OPT_SERIALIZE_NUMPY)


def _listed(value):
    """What orjson does not write itself: a numpy array it cannot take whole (not C-contiguous, or of
    another type) as its list; anything else is not JSON."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not JSON serialisable")


def _obj_vertices(vertices: np.ndarray) -> Iterator[bytes]:
    """``v`` lines (``%.12g``, a 2D point's z ``0``), :data:`~vaultgram.io.numtext.ROWS` at a time,
    each piece's numbers formatted at once (:func:`vaultgram.io.numtext.float_lines`); site coordinates
    with the digits their offset takes on top (:func:`_obj_digits`), formatted by Python."""
    import numpy as np

    from vaultgram.io.numtext import ROWS, float_lines

    v = np.asarray(vertices, dtype=float)
    if v.shape[1] == 2:
        v = np.column_stack([v, np.zeros(len(v))])
    digits = _obj_digits(v)
    number = f"%.{digits}g"
    line = f"v {number} {number} {number}\n"
    for a in range(0, len(v), ROWS):
        rows = v[a:a + ROWS]
        yield float_lines(b"v ", rows) if digits == 12 else ((line * len(rows)) % tuple(rows.ravel().tolist())).encode()


def _obj_digits(v: np.ndarray) -> int:
    """Significant digits that keep 12 of the shape: 12, and those the offset takes on top when the
    points lie farther from the origin than 10 times their extent (:mod:`vaultgram.geometry.frames`).
    The bounds are taken a column at a time: numpy's reductions over the rows of the (n, 2) view
    took ten times as long (0.18 s on the 3 million vertices of voussoirs.obj at 10^6 faces).

    >>> import numpy as np
    >>> _obj_digits(np.array([[0.0, 0, 0], [10, 10, 0]])), _obj_digits(np.array([[1e9, 1e9, 0], [1e9 + 10, 1e9, 0]]))
    (12, 17)
    """
    import numpy as np

    if not len(v):
        return 12
    low, high = np.array([v[:, 0].min(), v[:, 1].min()]), np.array([v[:, 0].max(), v[:, 1].max()])
    extent, far = float((high - low).max()), float(np.maximum(-low, high).max())
    if extent == 0.0 or far <= 10 * extent:
        return 12
    return min(17, 12 + math.ceil(math.log10(far / extent)))


def _obj_faces(faces) -> bytes:
    """``f`` lines, 1-based: the indices shifted in one array, the lines of a run of faces of one size
    formatted at once (:func:`vaultgram.io.numtext.int_lines`)."""
    import numpy as np

    from vaultgram.io.numtext import int_lines

    if isinstance(faces, np.ndarray) and faces.ndim == 2:
        return int_lines(b"f ", faces + 1)
    sizes = np.fromiter((len(f) for f in faces), dtype=np.int64, count=len(faces))
    flat = np.fromiter(chain.from_iterable(faces), dtype=np.int64, count=int(sizes.sum())) + 1
    cuts = np.flatnonzero(np.diff(sizes)) + 1
    starts, stops = np.concatenate([[0], cuts]).tolist(), np.concatenate([cuts, [len(sizes)]]).tolist()
    ends = np.concatenate([[0], np.cumsum(sizes)]).tolist()
    return b"".join(int_lines(b"f ", flat[ends[a]:ends[b]].reshape(b - a, -1)) if sizes[a] else b"f\n" * (b - a)
                    for a, b in zip(starts, stops) if b > a)


def write_obj(path: str | Path, vertices: np.ndarray, faces: Sequence[Sequence[int]],
              edges: Sequence[Sequence[int]] | None = None) -> None:
    """Write a Wavefront OBJ file (1-based indices); ``edges`` become ``l`` lines if given."""
    import numpy as np

    from vaultgram.io.numtext import int_lines

    lines = [int_lines(b"l ", np.asarray(edges, dtype=np.int64).reshape(-1, 2) + 1)] if edges is not None else []
    write_pieces(path, chain([b"# vaultgram\n"], _obj_vertices(vertices), [_obj_faces(faces)], lines))


def write_obj_groups(path: str | Path, vertices: np.ndarray, triangles: np.ndarray, owner: np.ndarray,
                     prefix: str = "object_") -> None:
    """Write an OBJ file of named objects over one vertex list: the ``triangles`` (t, 3), sorted by
    their ``owner`` object ``k``, each object an ``o {prefix}{k}`` line followed by its faces
    (1-based); objects ``0 .. owner.max()`` all named, those without triangles too. Streamed, a piece
    of lines at a time (:func:`vaultgram.io.numtext.headed_lines`)."""
    import numpy as np

    from vaultgram.io.numtext import headed_lines

    owner = np.asarray(owner, dtype=np.int64)
    faces = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    first = np.searchsorted(owner, np.arange(int(owner.max()) + 1 if len(owner) else 0))  # each object's first face
    objects = headed_lines(b"f ", faces, f"o {prefix}".encode(), first, offset=1)
    write_pieces(path, chain([b"# vaultgram\n"], _obj_vertices(vertices), objects))
