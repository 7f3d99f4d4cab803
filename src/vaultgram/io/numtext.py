"""Lines of numbers as text, a whole array at once: the bytes that ``%.12g`` and ``%d`` give for every
element, as Python's ``%`` operator writes them (issue 15: formatting the numbers of a 10^5-face
design's OBJ files one at a time took most of its 4-5 s of writing).

orjson writes a numpy array in C, a number in its shortest form that reads back the same
(:func:`vaultgram.io.files.write_json`); the rows become lines by replacing its brackets and commas.
That is ``%d`` already. For ``%.12g`` each float is first rounded to its twelve significant digits
``d`` (the float scaled by an exact power of ten and rounded to an integer, then scaled back in one
correctly rounded step): the shortest form of the float nearest to ``d`` is ``d`` without its
trailing zeros, as ``%.12g`` writes it, but for the ``.0`` of whole numbers, which is dropped. A row
holding a number whose scaled value lies too close to a rounding tie, one that ``%.12g`` writes with
an exponent (below 10^-4 or from 10^12 on), or one that is not finite, is formatted by Python itself,
so every byte is the one ``%`` writes.

>>> import numpy as np
>>> float_lines(b"v ", np.array([[0.1, -2.5, 1.0], [1e-5, 123456789012345.0, -0.0], [1 / 3, 0.0, 7e3]]))
b'v 0.1 -2.5 1\\nv 1e-05 1.23456789012e+14 -0\\nv 0.333333333333 0 7000\\n'
>>> int_lines(b"f ", np.array([[1, 2, 3], [40, 50, 60]]))
b'f 1 2 3\\nf 40 50 60\\n'
"""

from __future__ import annotations

from typing import Iterator

import numpy as np

__all__ = ["float_lines", "int_lines", "headed_lines", "rounded_g12", "PAD", "ROWS"]

PAD = 0  # the byte that pads the digits of a number in :func:`_digit_table`, dropped from the text
#: Lines formatted at a time: a piece's arrays (1.7 MB of OBJ faces) are reused memory and stay in the caches.
ROWS = 1 << 16
DIGITS = 12  # significant digits of %.12g
# a scaled value this close to an integer and a half is left to Python: scaled values are below 2^40, so
# the product's rounding error is at most half a unit in the last place, 2^-14 (6.1e-5)
_TIE = 1e-4


def int_lines(prefix: bytes, values: np.ndarray) -> bytes:
    """One line per row of the integer matrix ``values``: ``prefix``, the row's numbers (``%d``)
    separated by spaces, a newline. Indices (no negative number, none above eight times their count)
    are looked up in a table of their digits (:func:`headed_lines`); other numbers go through orjson.

    >>> int_lines(b"l ", np.array([[7, -1]]))
    b'l 7 -1\\n'
    >>> int_lines(b"f ", np.array([[1, 20, 3], [300, 0, 9]]))
    b'f 1 20 3\\nf 300 0 9\\n'
    """
    v = np.ascontiguousarray(values, dtype=np.int64)
    if not v.size or v.min() < 0 or v.max() > 8 * v.size + 1000:
        return _lines(prefix, v)
    return b"".join(headed_lines(prefix, v))


def headed_lines(prefix: bytes, values: np.ndarray, head: bytes = b"", starts=(), offset: int = 0) -> Iterator[bytes]:
    """The lines of :func:`int_lines` of ``values + offset`` (non-negative integers), with a line ``head``
    ``k`` before row ``starts[k]`` for each ``k`` (``starts`` sorted; at ``len(values)``: after the
    last row), in pieces of about :data:`ROWS` lines: an OBJ file's named objects (``o name_k``) and
    their faces, streamed to the file (:func:`vaultgram.io.files.write_pieces`).

    Each number is looked up in a table of the digits of ``0 .. max`` (:func:`_digit_table`, made
    once), its row taken whole into a fixed-width record of each line; a piece's records are then
    joined and their :data:`PAD` bytes dropped (:func:`_piece`). A piece at a time, every buffer is
    reused memory of a few MB: on the 12 million faces of voussoirs.obj at 10^6 faces 0.4 s, where
    making the whole text at once, then finding the objects' places in it by its newlines, took 2.5
    s (most of it the kernel's, mapping the 300 MB arrays afresh).

    >>> b"".join(headed_lines(b"f ", np.array([[0, 1, 2], [2, 1, 3]]), b"o part_", [0, 1, 1, 2], offset=1))
    b'o part_0\\nf 1 2 3\\no part_1\\no part_2\\nf 3 2 4\\no part_3\\n'
    """
    v = np.asarray(values, dtype=np.int64)
    starts = np.asarray(starts, dtype=np.int64)
    if v.size and v.min() + offset < 0:
        raise ValueError("headed_lines: a negative number")
    table = _digit_table(max(int(v.max()) + offset if v.size else 0, len(starts) - 1) + 1)
    bounds = np.r_[np.arange(0, max(len(v), 1), ROWS), len(v)]  # [0, 0] for no rows: the heads alone
    heads = np.searchsorted(starts, bounds)
    heads[-1] = len(starts)
    for a, b, ha, hb in zip(bounds[:-1], bounds[1:], heads[:-1], heads[1:]):
        yield _piece(table, prefix, v[a:b] + offset, head, np.arange(ha, hb), starts[ha:hb] - a)


def _piece(table: np.ndarray, prefix: bytes, rows: np.ndarray, head: bytes, numbers: np.ndarray,
           at: np.ndarray) -> bytes:
    """The lines of ``rows`` (``prefix`` and each row's numbers, looked up in ``table``) with the line
    ``head`` ``numbers[i]`` inserted before row ``at[i]``: every line a record of one width
    (:func:`_records`), the :data:`PAD` bytes dropped at the end.

    >>> _piece(_digit_table(12), b"f ", np.array([[1, 2, 3], [10, 11, 1]]), b"o ", np.array([5, 6]), np.array([1, 2]))
    b'f 1 2 3\\no 5\\nf 10 11 1\\no 6\\n'
    """
    size = max(len(prefix) + rows.shape[1] * table.shape[1], len(head) + table.shape[1])
    lines = _records(table, prefix, rows, size).view(f"V{size}")[:, 0]
    heads = _records(table, head, numbers[:, None], size).view(f"V{size}")[:, 0]
    return np.insert(lines, at, heads).tobytes().translate(None, bytes([PAD]))


def _records(table: np.ndarray, prefix: bytes, rows: np.ndarray, size: int) -> np.ndarray:
    """Each row's line as ``size`` bytes: ``prefix``, the table's row of each number taken whole (one
    item of its width: one gather, not one per byte), the last number's space a newline, :data:`PAD`
    bytes to the end.

    >>> _records(_digit_table(12), b"f ", np.array([[1, 11]]), 9).tolist()
    [[102, 32, 0, 49, 32, 49, 49, 10, 0]]
    """
    width, (n, cols), p = table.shape[1], rows.shape, len(prefix)
    records = np.zeros((n, size), dtype=np.uint8)
    records[:, :p] = np.frombuffer(prefix, dtype=np.uint8)
    records[:, p:p + cols * width].view(f"V{width}")[...] = table.view(f"V{width}")[rows, 0]
    records[:, p + cols * width - 1] = ord("\n")
    return records


def _digit_table(n: int) -> np.ndarray:
    """Row ``k`` (0 <= k < n): :data:`PAD` bytes, the digits of ``k`` (right-aligned to the widest's
    width), a space; made a column at a time (``k`` below ``10^j`` has no digit for ``10^j``).

    >>> _digit_table(11)[[0, 10]].tolist()
    [[0, 48, 32], [49, 48, 32]]
    """
    width = len(str(max(n - 1, 0)))
    k = np.arange(n, dtype=np.int64)
    table = np.full((n, width + 1), ord(" "), dtype=np.uint8)
    for col in range(width):
        place = 10 ** (width - 1 - col)
        table[:, col] = k // place % 10 + ord("0")
        table[:place if place > 1 else 0, col] = PAD
    return table


def float_lines(prefix: bytes, values: np.ndarray) -> bytes:
    """One line per row of the float matrix ``values``: ``prefix``, the row's numbers as ``%.12g``
    writes them, separated by spaces, a newline. The search for the ``.0`` of whole numbers in the
    text is skipped when there are none (a third of the time of 10^5 rows of coordinates)."""
    x = np.asarray(values, dtype=float)
    rounded, plain = rounded_g12(x)
    plain = plain.all(axis=1)
    whole = bool((rounded == np.trunc(rounded)).any())
    if plain.all():
        return _lines(prefix, rounded, whole)
    # the rows Python formats cut the others into runs, each written at once
    line = prefix.decode() + " ".join(["%.12g"] * x.shape[1]) + "\n"
    odd = np.flatnonzero(~plain).tolist()
    parts, start = [], 0
    for k in odd:
        parts += [_lines(prefix, rounded[start:k], whole), (line % tuple(x[k].tolist())).encode()]
        start = k + 1
    return b"".join([*parts, _lines(prefix, rounded[start:], whole)])


def rounded_g12(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each float rounded to twelve significant digits (the float nearest to them), and whether that
    is certainly %.12g's rounding and written without an exponent: ``|x|`` from 10^-4 to below
    10^12, or zero, and not near a tie.

    >>> r, plain = rounded_g12(np.array([2 / 3, 1e-5, 0.5 + 5e-13, np.nan]))
    >>> r.tolist()[:1], plain.tolist()
    ([0.666666666667], [True, False, False, False])
    """
    a = np.abs(x)
    finite = np.isfinite(a) & (a > 0)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        exponent = np.floor(np.log10(np.where(finite, a, 1.0))).astype(np.int64)
        shift = np.clip(DIGITS - 1 - exponent, 0, 22)  # a power of ten up to 10^22 is exact
        scaled = a * 10.0 ** shift
        rounded = np.rint(scaled)
        digits_in_range = (rounded >= 10.0 ** (DIGITS - 1)) & (rounded <= 10.0 ** DIGITS)
        plain = finite & (np.abs(scaled - np.floor(scaled) - 0.5) > _TIE) & digits_in_range
        plain &= (exponent >= -4) & ((exponent < DIGITS - 1) | ((exponent == DIGITS - 1) & (rounded < 10.0 ** DIGITS)))
        back = np.copysign(np.where(plain, rounded, 0.0) / 10.0 ** shift, x)  # one correctly rounded step
    return np.where(plain, back, x), plain | (a == 0)


def _lines(prefix: bytes, matrix: np.ndarray, whole: bool = False) -> bytes:
    """orjson's ``[[a,b],[c,d]]`` of a C-contiguous matrix as lines ``prefix a b``; with ``whole``,
    the ``.0`` of whole floats dropped. One translation of every byte (:data:`_BRACKETS`) gives
    ``a b\\n c d\\n\\n``: each line after the first starts with the space of the comma between
    the rows, which becomes the prefix (one pass where replacing the commas, then the brackets, then
    the newlines took three).

    >>> _lines(b"x ", np.array([[1.0, 2.5], [3.0, -4.0]]), whole=True)
    b'x 1 2.5\\nx 3 -4\\n'
    """
    import orjson

    if not len(matrix):
        return b""
    body = orjson.dumps(matrix, option=orjson.OPT_SERIALIZE_NUMPY).translate(_BRACKETS, b"[")[:-1]
    if whole:
        body = body.replace(b".0 ", b" ").replace(b".0\n", b"\n")
    return prefix + body.replace(b"\n ", b"\n" + prefix)


#: orjson's commas as spaces and its closing brackets as newlines (the opening ones are deleted).
_BRACKETS = bytes.maketrans(b",]", b" \n")
