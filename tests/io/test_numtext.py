"""Numbers as text a whole array at once (vaultgram.io.numtext) and the OBJ writers built on it: the
bytes are exactly those of Python's ``%.12g`` and ``%d``, the edge cases of the shortcut included."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.io.files import write_obj, write_obj_groups
from vaultgram.io.numtext import float_lines, int_lines

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


def test_int_lines_are_percent_d():
    rows = np.array([[0, 1, 9], [10, 99, 100], [-5, 123456789012, 7]])
    assert int_lines(b"f ", rows) == python_lines("f ", rows, "%d")
    assert int_lines(b"f ", np.zeros((0, 3), dtype=int)) == b""
    indices = np.random.default_rng(2).integers(0, 12000, (3000, 4))  # looked up in a table of digits
    assert int_lines(b"f ", indices) == python_lines("f ", indices, "%d")


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
