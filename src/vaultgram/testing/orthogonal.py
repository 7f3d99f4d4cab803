"""Random rectilinear plans for the tests of the reflex-corner rules (``rules/corners.vgr``).

:data:`RECTILINEAR_PLANS` are named examples (an L, T, U, H, a comb of 5 teeth, a courtyard block
with an L-shaped court); ``orthogonal_domains()`` draws domain dicts: the outline of a random polyomino on a grid of
uneven integer widths (8 to 40 corners, all right angles, convex or reflex) with 0 to 2 rectangular
or L-shaped holes, each inside one cell that the polyomino surrounds. Grid lines at least 2 apart
and holes at least 1 from their cell's sides keep the plan resolvable at the default spacing.
"""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import assume
from hypothesis import strategies as st

__all__ = ["orthogonal_domains", "corner_count", "comb", "RECTILINEAR_PLANS"]

GRID = 6  # cells per side of the grid the polyomino grows on


def comb(teeth: int = 5) -> list:
    """A comb's outline: a base 4 high under ``teeth`` teeth 2 wide and 6 high, 2 apart.

    >>> len(comb(5)), corner_count(comb(5))
    (20, 20)
    """
    width = 4 * teeth - 2
    pts = [[0, 0], [width, 0]]
    for k in range(teeth):
        right = width - 4 * k
        pts += [[right, 10], [right - 2, 10]] + ([[right - 2, 4], [right - 4, 4]] if k < teeth - 1 else [])
    return pts


#: Rectilinear plans by name, as domain dicts.
RECTILINEAR_PLANS = {
    "L": {"outer": [[0, 0], [10, 0], [10, 5], [5, 5], [5, 10], [0, 10]]},
    "T": {"outer": [[0, 0], [4, 0], [4, 6], [10, 6], [10, 10], [-6, 10], [-6, 6], [0, 6]]},
    "U": {"outer": [[0, 0], [12, 0], [12, 10], [8, 10], [8, 4], [4, 4], [4, 10], [0, 10]]},
    "H": {"outer": [[0, 0], [4, 0], [4, 4], [8, 4], [8, 0], [12, 0], [12, 12], [8, 12], [8, 8], [4, 8], [4, 12],
                    [0, 12]]},
    "comb": {"outer": comb(5)},
    "courtyard": {"outer": [[0, 0], [20, 0], [20, 16], [0, 16]],  # a block round an L-shaped court
                  "holes": [[[5, 4], [5, 12], [9, 12], [9, 8], [15, 8], [15, 4]]]},
}


def corner_count(ring) -> int:
    """The number of corners of a ring (vertices where it turns).

    >>> corner_count([[0, 0], [1, 0], [2, 0], [2, 2], [0, 2]])
    4
    """
    r = np.asarray(ring, dtype=float)
    a, b = r - np.roll(r, 1, axis=0), np.roll(r, -1, axis=0) - r
    return int(np.count_nonzero(np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) > 1e-9))


def _grid_lines(draw) -> np.ndarray:
    """GRID + 1 increasing integer coordinates, consecutive ones 2 to 5 apart."""
    widths = draw(st.lists(st.integers(2, 5), min_size=GRID, max_size=GRID))
    return np.concatenate([[0], np.cumsum(widths)]).astype(float)


def _polyomino(draw) -> set:
    """A connected set of grid cells grown from the middle, one neighbour at a time."""
    cells = {(GRID // 2, GRID // 2)}
    for _ in range(draw(st.integers(3, 22))):
        frontier = sorted({(i + di, j + dj) for i, j in cells for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
                           if 0 <= i + di < GRID and 0 <= j + dj < GRID} - cells)
        cells.add(draw(st.sampled_from(frontier)))
    return cells


def _hole(draw, xs, ys, cell) -> list:
    """A rectangle or an L inside the cell, at least 1 from its sides, clockwise (domain on the left)."""
    i, j = cell
    x0, x1, y0, y1 = xs[i] + 1, xs[i + 1] - 1, ys[j] + 1, ys[j + 1] - 1
    if x1 - x0 < 0.5 or y1 - y0 < 0.5:
        x0, x1, y0, y1 = xs[i] + 0.75, xs[i + 1] - 0.75, ys[j] + 0.75, ys[j + 1] - 0.75
    box = shapely.box(x0, y0, x1, y1)
    if draw(st.booleans()) and x1 - x0 >= 1.5 and y1 - y0 >= 1.5:  # an L: a corner cut away
        box = box.difference(shapely.box((x0 + x1) / 2, (y0 + y1) / 2, x1, y1))
    ring = np.asarray(shapely.geometry.polygon.orient(box, -1.0).exterior.coords)[:-1]
    return ring.tolist()


@st.composite
def orthogonal_domains(draw, max_holes: int = 2):
    """A rectilinear plan as a domain dict (see the module docstring)."""
    xs, ys = _grid_lines(draw), _grid_lines(draw)
    cells = _polyomino(draw)
    shape = shapely.unary_union([shapely.box(xs[i], ys[j], xs[i + 1], ys[j + 1]) for i, j in cells])
    outline = shapely.Polygon(shapely.geometry.polygon.orient(shapely.Polygon(shape.exterior), 1.0).exterior)
    outer = np.asarray(shapely.simplify(outline, 0.0).exterior.coords)[:-1]
    assume(8 <= corner_count(outer) <= 40)
    inner = sorted(c for c in cells if all((c[0] + di, c[1] + dj) in cells
                                           for di in (-1, 0, 1) for dj in (-1, 0, 1)))
    n_holes = draw(st.integers(0, min(max_holes, len(inner))))
    chosen = draw(st.lists(st.sampled_from(inner), min_size=n_holes, max_size=n_holes, unique=True)) if inner else []
    return {"name": "orthogonal", "outer": outer.tolist(), "holes": [_hole(draw, xs, ys, c) for c in chosen]}
