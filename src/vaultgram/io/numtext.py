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

import numpy as np

__all__ = ["float_lines", "int_lines", "rounded_g12", "PAD"]

PAD = 0  # the byte that pads the digits of a number in :func:`_digit_table`, dropped from the text
DIGITS = 12  # significant digits of %.12g
# a scaled value this close to an integer and a half is left to Python: scaled values are below 2^40, so
# the product's rounding error is at most half a unit in the last place, 2^-14 (6.1e-5)
_TIE = 1e-4


def int_lines(prefix: bytes, values: np.ndarray) -> bytes:
    """One line per row of the integer matrix ``values``: ``prefix``, the row's numbers (``%d``)
    separated by spaces, a newline. Indices (no negative number, none above eight times their count)
    are looked up in a table of their digits (:func:`_digit_table`), 1.7 times faster than orjson on
    the 4 million of voussoirs.obj at 10^5 faces; other numbers go through orjson. The table's rows
    are gathered as whole items into the lines (not byte by byte, then joined to the prefix): on the
    10^7 rows of voussoirs.obj at 10^6 faces 1.5 s instead of 6.0.

    >>> int_lines(b"l ", np.array([[7, -1]]))
    b'l 7 -1\\n'
    >>> int_lines(b"f ", np.array([[1, 20, 3], [300, 0, 9]]))
    b'f 1 20 3\\nf 300 0 9\\n'
    """
    v = np.ascontiguousarray(values, dtype=np.int64)
    if not v.size or v.min() < 0 or v.max() > 8 * v.size + 1000:
        return _lines(prefix, v)
    table = _digit_table(int(v.max()) + 1)
    rows, cols, width, p = v.shape[0], v.shape[1], table.shape[1], len(prefix)
    lines = np.empty((rows, p + cols * width), dtype=np.uint8)
    lines[:, :p] = np.frombuffer(prefix, dtype=np.uint8)
    # each table row one opaque item (a row of bytes taken whole), gathered straight into the lines
    cells = [("p", f"V{p}")] if p else []
    lines.view(np.dtype([*cells, ("c", f"V{width}", (cols,))]))[:, 0]["c"] = table.view(f"V{width}")[:, 0][v]
    lines[:, -1] = ord("\n")  # the last number's space
    flat = lines.ravel()
    return flat[flat != PAD].tobytes()


def _digit_table(n: int) -> np.ndarray:
    """Row ``k`` (0 <= k < n): the digits of ``k``, :data:`PAD` bytes up to the widest's width, a space.

    >>> _digit_table(11)[[0, 10]].tolist()
    [[48, 0, 32], [49, 48, 32]]
    """
    width = len(str(max(n - 1, 0)))
    k = np.arange(n, dtype=np.int64)
    size = np.floor(np.log10(np.maximum(k, 1))).astype(np.int64) + 1  # digits of k
    table = np.full((n, width + 1), ord(" "), dtype=np.uint8)
    for col in range(width):
        place = size - 1 - col  # the power of ten of the digit in this column
        table[:, col] = np.where(place >= 0, k // 10 ** np.maximum(place, 0) % 10 + ord("0"), PAD)
    return table


def float_lines(prefix: bytes, values: np.ndarray) -> bytes:
    """One line per row of the float matrix ``values``: ``prefix``, the row's numbers as ``%.12g``
    writes them, separated by spaces, a newline."""
    x = np.asarray(values, dtype=float)
    rounded, plain = rounded_g12(x)
    plain = plain.all(axis=1)
    if plain.all():
        return _lines(prefix, rounded, whole=True)
    # the rows Python formats cut the others into runs, each written at once
    line = prefix.decode() + " ".join(["%.12g"] * x.shape[1]) + "\n"
    odd = np.flatnonzero(~plain).tolist()
    parts, start = [], 0
    for k in odd:
        parts += [_lines(prefix, rounded[start:k], whole=True), (line % tuple(x[k].tolist())).encode()]
        start = k + 1
    return b"".join([*parts, _lines(prefix, rounded[start:], whole=True)])


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
    the ``.0`` of whole floats dropped."""
    import orjson

    if not len(matrix):
        return b""
    body = orjson.dumps(matrix, option=orjson.OPT_SERIALIZE_NUMPY)[2:-2] + b"],["
    body = body.replace(b",", b" ").replace(b"] [", b"\n")
    if whole:
        body = body.replace(b".0 ", b" ").replace(b".0\n", b"\n")
    body = prefix + body.replace(b"\n", b"\n" + prefix)
    return body[:len(body) - len(prefix)]
