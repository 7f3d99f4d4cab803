"""Numbers as text a whole array at once (vaultgram.io.numtext) and the OBJ writers built on it: the
bytes are exactly those of Python's ``%.12g`` and ``%d``, the edge cases of the shortcut included."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.io import numtext
from vaultgram.io.files import write_obj, write_obj_groups, write_pieces
from vaultgram.io.numtext import float_lines, headed_lines, int_lines

#: Floats at the shortcut's edges: ties of the twelfth digit, powers of ten and their neighbours, the
#: bounds of %.12g's fixed notation (1e-4, 1e12), zeros of both signs, not finite.
EDGES = np.array([0.0, -0.0, np.nan, np.inf, -np.inf, 1e300, 5e-324, 1e-5, 1e-4, 9.99999999999949e-5,
                  9.99999999999951e-5, 99999999999.95, 999999999999.4, 999999999999.5, 9.999999999995,
                  1e12, 1e11, 123456789012.0, 0.5, 2.5, 1.05e-4, 0.1 + 0.2, 1 / 3, -2 / 3, 7e3, 1.25e-3,
                  *(10.0 ** np.arange(-8, 16)), *(10.0 ** np.arange(-8, 16) * (1 - 1e-13)),
                  *(10.0 ** np.arange(-8, 16) * (1 + 1e-13)), *(0.5 + np.arange(-3, 4) * 1e-12)])


def python_lines(prefix: str, rows: np.ndarray, spec: str) -> bytes:
    """The lines as Python's ``%`` writes them, one number at a time."""
    return "".join(prefix + " ".join(spec % v for v in row) + "\n" for row in rows.tolist()).encode()


def test_float_lines_are_percent_g12_at_the_edges_and_on_random_coordinates():
    rng = np.random.default_rng(5)
    random = np.concatenate([rng.uniform(-50, 50, 3000), np.round(rng.uniform(-9, 9, 3000), 3),
                             rng.normal(size=3000) * 10.0 ** rng.integers(-9, 15, 3000)])
    # twelve digits and a half, give or take less and more than the shortcut leaves to Python
    ties = ((rng.integers(10**11, 10**12, 3000) + rng.choice([0.5, 0.5 + 7e-5, 0.5 - 1.1e-4], 3000))
            / 10.0 ** rng.integers(0, 16, 3000))
    for x in (np.concatenate([EDGES, -EDGES]), random, np.concatenate([ties, np.nextafter(ties, 0)])):
        rows = rng.permutation(x)[: len(x) // 3 * 3].reshape(-1, 3)
        assert float_lines(b"v ", rows) == python_lines("v ", rows, "%.12g")
        assert float_lines(b"x", rows[:, :1]) == python_lines("x", rows[:, :1], "%.12g")


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=1, max_size=40))
def test_float_lines_are_percent_g12_for_any_float(values):
    rows = np.array(values, dtype=float)[:, None]
    assert float_lines(b"v ", rows) == python_lines("v ", rows, "%.12g")


def test_float_lines_without_whole_numbers_are_percent_g12():
    """No ``.0`` to drop: the search for it is skipped."""
    rows = np.random.default_rng(3).uniform(-9, 9, (500, 3)) + 1e-9
    assert float_lines(b"v ", rows) == python_lines("v ", rows, "%.12g")
    assert float_lines(b"v ", rows[:, :1]) == python_lines("v ", rows[:, :1], "%.12g")


def test_int_lines_are_percent_d():
    rows = np.array([[0, 1, 9], [10, 99, 100], [-5, 123456789012, 7]])
    assert int_lines(b"f ", rows) == python_lines("f ", rows, "%d")
    assert int_lines(b"f ", np.zeros((0, 3), dtype=int)) == b""
    indices = np.random.default_rng(2).integers(0, 12000, (3000, 4))  # looked up in a table of digits
    assert int_lines(b"f ", indices) == python_lines("f ", indices, "%d")
    assert int_lines(b"", indices[:, :1]) == python_lines("", indices[:, :1], "%d")
    for top in (1, 9, 10, 11, 99, 100, 10**6, 10**6 + 1):  # every width, and the widest number alone
        column = np.array([[0], [top], [top // 2], [1]])
        assert int_lines(b"l ", np.tile(column, (1, 3))) == python_lines("l ", np.tile(column, (1, 3)), "%d")


def headed_python(prefix: str, rows: np.ndarray, head: str, starts, offset: int) -> bytes:
    """:func:`headed_lines`'s text as Python's ``%`` writes it, a line at a time."""
    lines = [prefix + " ".join("%d" % (v + offset) for v in row) + "\n" for row in rows.tolist()]
    for k, at in reversed(list(enumerate(starts))):  # later heads first: each goes before the ones after it
        lines.insert(at, "%s%d\n" % (head, k))
    return "".join(lines).encode()


@pytest.mark.parametrize("rows", [1, 2, 3, 7, 1 << 16])
def test_headed_lines_are_percent_d_with_every_head_in_place(monkeypatch, rows):
    """Heads before the first row, several before one row, on the pieces' bounds, after the last row;
    wide numbers, a head wider than the rows' lines; pieces of ``rows`` lines."""
    monkeypatch.setattr(numtext, "ROWS", rows)
    rng = np.random.default_rng(rows)
    values = rng.integers(0, 3 * 10**6, (40, 3))
    values[::7] = rng.integers(0, 10, (6, 3))
    starts = [0, 0, 1, 3, 3, 3, 6, 7, 14, 21, 39, 40, 40]
    for prefix, head in ((b"f ", b"o voussoir_"), (b"", b"g"), (b"f ", b"o a_name_longer_than_any_line_")):
        text = b"".join(headed_lines(prefix, values, head, starts, offset=1))
        assert text == headed_python(prefix.decode(), values, head.decode(), starts, 1)
        assert b"".join(headed_lines(prefix, values[:, :1], head, starts)) == headed_python(
            prefix.decode(), values[:, :1], head.decode(), starts, 0)


def test_headed_lines_without_rows_or_heads():
    none = np.zeros((0, 3), dtype=np.int64)
    assert b"".join(headed_lines(b"f ", none, b"o x", [0, 0, 0])) == b"o x0\no x1\no x2\n"
    assert b"".join(headed_lines(b"f ", none)) == b""
    assert b"".join(headed_lines(b"f ", np.array([[5, 12, 0]]), b"o ", [1])) == b"f 5 12 0\no 0\n"
    assert b"".join(headed_lines(b"f ", np.array([[5, 12, 0]]), b"o ", [0], offset=1)) == b"o 0\nf 6 13 1\n"
    with pytest.raises(ValueError):
        next(headed_lines(b"f ", np.array([[0, -1, 2]])))


def test_obj_files_hold_every_line_in_order(tmp_path):
    """Mixed triangles and quads, 2D vertices (z written 0), edges; named objects, one without faces."""
    x = np.array([[0.0, 0.0], [1.5, 0.0], [1.5, 1 / 3], [0.0, 1e-7]])
    write_obj(tmp_path / "a.obj", x, [(0, 1, 2), (0, 2, 3), (0, 1, 2, 3)], edges=[(0, 1)])
    assert (tmp_path / "a.obj").read_text() == ("# vaultgram\nv 0 0 0\nv 1.5 0 0\nv 1.5 0.333333333333 0\n"
                                                "v 0 1e-07 0\nf 1 2 3\nf 1 3 4\nf 1 2 3 4\nl 1 2\n")
    write_obj_groups(tmp_path / "b.obj", np.column_stack([x, np.ones(4)]), np.array([[0, 1, 2], [0, 2, 3], [1, 2, 3]]),
                     np.array([0, 0, 2]), "piece_")
    assert (tmp_path / "b.obj").read_text().split("\n")[5:] == [
        "o piece_0", "f 1 2 3", "f 1 3 4", "o piece_1", "o piece_2", "f 2 3 4", ""]
    write_obj_groups(tmp_path / "c.obj", x, np.zeros((0, 3), dtype=int), np.zeros(0, dtype=int))
    assert (tmp_path / "c.obj").read_text() == "# vaultgram\nv 0 0 0\nv 1.5 0 0\nv 1.5 0.333333333333 0\nv 0 1e-07 0\n"


def test_obj_groups_are_percent_formatted_across_pieces(tmp_path, monkeypatch):
    """Objects without triangles first, between, many at once; pieces of 5 lines that cut objects."""
    monkeypatch.setattr(numtext, "ROWS", 5)
    rng = np.random.default_rng(4)
    x = rng.uniform(-20, 20, (1200, 3))
    owner = np.sort(rng.integers(2, 30, 57))
    triangles = rng.integers(0, len(x), (57, 3))
    write_obj_groups(tmp_path / "g.obj", x, triangles, owner, "voussoir_")
    faces = ["f %d %d %d\n" % tuple(t) for t in (triangles + 1).tolist()]
    objects = "".join(f"o voussoir_{k}\n" + "".join(f for f, o in zip(faces, owner) if o == k)
                      for k in range(owner.max() + 1))
    assert (tmp_path / "g.obj").read_bytes() == b"# vaultgram\n" + python_lines("v ", x, "%.12g") + objects.encode()


def test_written_pieces_are_the_file_or_nothing(tmp_path):
    path = tmp_path / "a.txt"
    write_pieces(path, [b"old"])

    def failing():
        yield b"new "
        raise OSError("disk full")

    with pytest.raises(OSError):
        write_pieces(path, failing())
    assert path.read_bytes() == b"old" and [p.name for p in tmp_path.iterdir()] == ["a.txt"]
    write_pieces(path, iter([b"new ", memoryview(b"text"), b""]))
    assert path.read_bytes() == b"new text"


def test_obj_digits_from_each_columns_bounds():
    """The site's extent and distance from the origin, taken a column at a time: as from the rows."""
    from vaultgram.io.files import _obj_digits

    rng = np.random.default_rng(6)
    for centre in (0.0, 5.0, -3e4, 2e6, -7e8, 1e12):
        for size in (1e-3, 1.0, 40.0):
            v = np.column_stack([rng.uniform(-size, size, (50, 2)) + [centre, -centre / 3], np.zeros(50)])
            extent, far = float(np.ptp(v[:, :2], axis=0).max()), float(np.abs(v[:, :2]).max())
            expected = 12 if far <= 10 * extent else min(17, 12 + int(np.ceil(np.log10(far / extent))))
            assert _obj_digits(v) == expected
    assert _obj_digits(np.zeros((0, 3))) == _obj_digits(np.ones((3, 3))) == 12


def test_digit_tables_hold_each_numbers_digits():
    """Tables 1, 2, 4 and 8 bytes wide, of integers of 8, 16 and 32 bits."""
    for n in (1, 2, 10, 11, 256, 257, 1000, 10**4 + 1, 65537, 2 * 10**5):
        table = numtext._digit_table(n)
        digits = len(str(n - 1))
        assert table.shape[1] in (1, 2, 4, 8) and digits <= table.shape[1] < 2 * digits
        assert [row.tobytes().replace(b"\0", b"") for row in table] == [b"%d" % k for k in range(n)]


def test_int_records_are_percent_d_in_their_parts(monkeypatch):
    monkeypatch.setattr(numtext, "ROWS", 2)
    a, b = np.array([[0, 12], [345, 6], [7, 8]]), np.array([9, 10**7, 11])
    text = b"".join(numtext.int_records([b"(", b"-", b"|", b");"], a, b))
    assert text == b"".join(b"(%d-%d|%d);" % (*r, s) for r, s in zip(a.tolist(), b.tolist()))
    assert b"".join(numtext.int_records([b"<", b">"], np.zeros((0, 1), dtype=int))) == b""
    with pytest.raises(ValueError):
        next(numtext.int_records([b"", b""], np.array([[-1]])))
