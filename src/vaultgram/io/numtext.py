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

Indices (non-negative integers) are looked up in a table of their digits instead, each line a
record of fixed width with its numbers' digits in slots, the padding dropped at the end
(:func:`headed_lines`, :func:`int_records`). Large outputs are made in pieces of :data:`ROWS` rows,
to be written one after the other (:func:`vaultgram.io.files.write_pieces`): the arrays of a piece
are reused memory that stays in the caches, where a 10^6-face design's 300 MB arrays made at once
were fresh pages for the kernel to map.

>>> import numpy as np
>>> float_lines(b"v ", np.array([[0.1, -2.5, 1.0], [1e-5, 123456789012345.0, -0.0], [1 / 3, 0.0, 7e3]]))
b'v 0.1 -2.5 1\\nv 1e-05 1.23456789012e+14 -0\\nv 0.333333333333 0 7000\\n'
>>> int_lines(b"f ", np.array([[1, 2, 3], [40, 50, 60]]))
b'f 1 2 3\\nf 40 50 60\\n'
"""

from __future__ import annotations

from typing import Iterator

import numpy as np

__all__ = ["float_lines", "int_lines", "headed_lines", "int_records", "rounded_g12", "PAD", "ROWS"]

PAD = 0  # the byte that pads the digits of a number in :func:`_digit_table`, dropped from the text
#: Lines formatted at a time: a piece's arrays (1.7 MB of OBJ faces) are reused memory and stay in the caches.
ROWS = 1 << 16
DIGITS = 12  # significant digits of %.12g
# a scaled value this close to an integer and a half is left to Python: scaled values are below 2^40, so
# the product's rounding error is at most half a unit in the last place, 2^-14 (6.1e-5)
_TIE = 1e-4
#: The exact powers of ten, 10^0 to 10^22, looked up (raising ten to each power took five times as long).
_POWERS = 10.0 ** np.arange(23)


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
    last row), in pieces of :data:`ROWS` lines: an OBJ file's named objects (``o name_k``) and their
    faces, streamed to the file (:func:`vaultgram.io.files.write_pieces`).

    Each line is a record of fixed width (:func:`_records`); the heads' records are inserted among
    the rows', and the :data:`PAD` bytes dropped (:func:`_piece`). A piece at a time, every buffer
    is reused memory of a few MB: the 12 million faces of voussoirs.obj at 10^6 faces take 0.5 s,
    where making the whole text at once, then finding the objects' places in it by its newlines,
    took 2.5 s (much of it the kernel's, mapping the 300 MB arrays afresh).

    >>> b"".join(headed_lines(b"f ", np.array([[0, 1, 2], [2, 1, 3]]), b"o part_", [0, 1, 1, 2], offset=1))
    b'o part_0\\nf 1 2 3\\no part_1\\no part_2\\nf 3 2 4\\no part_3\\n'
    """
    v = np.asarray(values, dtype=np.int64)
    starts = np.asarray(starts, dtype=np.int64)
    table = _digit_table(max(_top(v, offset), len(starts) - 1) + 1)
    parts, heads = [prefix, *[b" "] * (v.shape[1] - 1), b"\n"], [head, b"\n"]
    bounds = np.r_[np.arange(0, max(len(v), 1), ROWS), len(v)]  # [0, 0] for no rows: the heads alone
    first = np.searchsorted(starts, bounds)
    first[-1] = len(starts)
    for a, b, ha, hb in zip(bounds[:-1], bounds[1:], first[:-1], first[1:]):
        yield _piece(_records(table, parts, v[a:b] + offset), _records(table, heads, np.arange(ha, hb)[:, None]),
                     starts[ha:hb] - a)


def int_records(parts: list[bytes], *values: np.ndarray) -> Iterator[bytes]:
    """Each row of the matrices (or columns) ``values`` (non-negative integers; as many rows each,
    their numbers side by side) as ``parts[0]``, its first number (``%d``), ``parts[1]``, ..., its
    last, ``parts[-1]``, in pieces of :data:`ROWS` rows: records of JSON as :func:`_records` makes
    lines, the matrices put side by side a piece at a time (never a copy of them all).

    >>> b"".join(int_records([b'{"a":[', b",", b'],"b":', b"},"], np.array([[1, 20], [300, 0]]), np.array([[7], [8]])))
    b'{"a":[1,20],"b":7},{"a":[300,0],"b":8},'
    """
    v = [np.asarray(m, dtype=np.int64) for m in values]
    table = _digit_table(max(_top(m) for m in v) + 1)
    for a in range(0, len(v[0]), ROWS):
        yield _packed(_records(table, parts, np.column_stack([m[a:a + ROWS] for m in v])))


def _top(values: np.ndarray, offset: int = 0) -> int:
    """The largest of ``values + offset`` (0 if none), none of which may be negative: the numbers of
    a table of digits."""
    if values.size and values.min() + offset < 0:
        raise ValueError("a negative number where indices were expected")
    return int(values.max()) + offset if values.size else 0


def _piece(lines: np.ndarray, heads: np.ndarray, at: np.ndarray) -> bytes:
    """The records ``lines`` with ``heads[i]`` inserted before line ``at[i]``, as text (:func:`_packed`);
    the narrower records padded to the wider's width.

    >>> table = _digit_table(12)
    >>> lines = _records(table, [b"f ", b"\\n"], np.array([[1], [10]]))
    >>> _piece(lines, _records(table, [b"o", b"\\n"], np.array([[5]])), np.array([1]))
    b'f 1\\no5\\nf 10\\n'
    """
    size = max(lines.shape[1], heads.shape[1])
    lines, heads = (np.pad(r, ((0, 0), (0, size - r.shape[1])), constant_values=PAD) if r.shape[1] < size else r
                    for r in (lines, heads))
    return _packed(np.insert(lines.view(f"V{size}")[:, 0], at, heads.view(f"V{size}")[:, 0]))


def _packed(records: np.ndarray) -> bytes:
    """The bytes of ``records`` without their :data:`PAD` bytes."""
    return records.tobytes().translate(None, bytes([PAD]))


def _records(table: np.ndarray, parts: list[bytes], rows: np.ndarray) -> np.ndarray:
    """Each row as one record of fixed width: ``parts[0]``, a slot for its first number, ``parts[1]``,
    ..., ``parts[-1]``. The parts' bytes are written a column at a time; each slot takes the number's
    row of ``table`` (its digits) whole, one item of the table's width: a gather per column, not one
    per byte.

    >>> _records(_digit_table(12), [b"f ", b",", b"\\n"], np.array([[1, 11]])).tolist()
    [[102, 32, 0, 49, 44, 49, 49, 10]]
    """
    width, template, slots = table.shape[1], bytearray(parts[0]), []
    for part in parts[1:]:
        slots.append(len(template))
        template += bytes([PAD]) * width + part
    records = np.zeros((len(rows), len(template)), dtype=np.uint8)
    for i in np.flatnonzero(np.frombuffer(template, dtype=np.uint8) != PAD).tolist():
        records[:, i] = template[i]
    cells = table.view(f"V{width}")[:, 0]
    for col, at in enumerate(slots):
        records[:, at:at + width].view(f"V{width}")[:, 0] = cells[rows[:, col]]
    return records


def _digit_table(n: int) -> np.ndarray:
    """Row ``k`` (0 <= k < n): :data:`PAD` bytes, then the digits of ``k``; as wide as a power of two
    (numpy copies items of 8 bytes four times as fast as of 7), made a column at a time (``k``
    below ``10^j`` has no digit for ``10^j``).

    >>> _digit_table(11)[[0, 10]].tolist()
    [[0, 48], [49, 48]]
    >>> _digit_table(1000).shape
    (1000, 4)
    """
    digits = len(str(max(n - 1, 0)))
    width = 1 << (digits - 1).bit_length()
    k = np.arange(n, dtype=np.min_scalar_type(max(n - 1, 0)))  # the narrowest integers divide fastest
    table = np.full((n, width), PAD, dtype=np.uint8)
    for col in range(width - digits, width):
        place = 10 ** (width - 1 - col)
        first = place if place > 1 else 0  # the first number with a digit in this place
        table[first:, col] = k[first:] // place % 10 + ord("0")
    return table


def float_lines(prefix: bytes, values: np.ndarray) -> bytes:
    """One line per row of the float matrix ``values``: ``prefix``, the row's numbers as ``%.12g``
    writes them, separated by spaces, a newline. The search for the ``.0`` of whole numbers in the
    text is skipped when there are none (0.24 s on the 3 million vertices of voussoirs.obj at 10^6
    faces, which have none)."""
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
        power = _POWERS[np.clip(DIGITS - 1 - exponent, 0, 22)]  # a power of ten up to 10^22 is exact
        scaled = a * power
        rounded = np.rint(scaled)
        digits_in_range = (rounded >= 10.0 ** (DIGITS - 1)) & (rounded <= 10.0 ** DIGITS)
        plain = finite & (np.abs(scaled - np.floor(scaled) - 0.5) > _TIE) & digits_in_range
        plain &= (exponent >= -4) & ((exponent < DIGITS - 1) | ((exponent == DIGITS - 1) & (rounded < 10.0 ** DIGITS)))
        back = np.copysign(np.where(plain, rounded, 0.0) / power, x)  # one correctly rounded step
    return np.where(plain, back, x), plain | (a == 0)


def _lines(prefix: bytes, matrix: np.ndarray, whole: bool = False) -> bytes:
    """orjson's ``[[a,b],[c,d]]`` of a C-contiguous matrix as lines ``prefix a b``; with ``whole``,
    the ``.0`` of whole floats dropped. One translation of every byte (:data:`_BRACKETS`) gives
    ``a b\\n c d\\n\\n``: each line after the first starts with the space of the comma between the
    rows, which a prefix ending in a space keeps as its own last byte (a search for the newlines
    alone is five times as fast as for a newline and a space).

    >>> _lines(b"x ", np.array([[1.0, 2.5], [3.0, -4.0]]), whole=True), _lines(b"x", np.array([[1], [2]]))
    (b'x 1 2.5\\nx 3 -4\\n', b'x1\\nx2\\n')
    """
    import orjson

    if not len(matrix):
        return b""
    body = orjson.dumps(matrix, option=orjson.OPT_SERIALIZE_NUMPY).translate(_BRACKETS, b"[")
    if whole:
        body = body.replace(b".0 ", b" ").replace(b".0\n", b"\n")
    if prefix.endswith(b" "):
        return prefix + body[:-2].replace(b"\n", b"\n" + prefix[:-1]) + b"\n"
    return prefix + body[:-1].replace(b"\n ", b"\n" + prefix)


#: orjson's commas as spaces and its closing brackets as newlines (the opening ones are deleted).
_BRACKETS = bytes.maketrans(b",]", b" \n")
