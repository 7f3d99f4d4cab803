"""Plans whose skeleton degenerates, for the tests of the O-grid and lone-branch rules
(``rules/topology.vgr``) and the quality benchmarks.

A plan without corners sharper than 135 degrees (a disc, an oval, a regular polygon of 8 sides or
more, a stadium, a disc cut by a wall at such corners) has a skeleton of one singularity without a
branch (or of one branch between its two corners), made an O-grid, as is a teardrop (one sharp
corner, the corner of a sixth patch of the O-grid); a plan with two sharp corners and a smooth
outline between them (a half disc, a lens, a D-shaped apse) has a skeleton of one branch from corner
to corner. :data:`SMOOTH_PLANS` names one of each kind; :func:`oval`, :func:`apse` and :func:`lens`
draw them.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["oval", "apse", "cut_disc", "teardrop", "stadium", "lens", "SMOOTH_PLANS"]


def oval(n: int, radius: float = 5.0, centre=(0.0, 0.0), turn: float = 0.0, squash: float = 1.0,
         wobble: float = 0.0) -> list:
    """``n`` points counter-clockwise round an ellipse of axes ``radius`` and ``squash * radius`` (a
    regular ``n``-gon at 1), turned by ``turn`` radians about ``centre``; ``wobble`` adds a three-lobed
    wave to the radius.

    >>> np.round(oval(4), 9).tolist()
    [[5.0, 0.0], [0.0, 5.0], [-5.0, 0.0], [-0.0, -5.0]]
    """
    t = 2 * math.pi * np.arange(n) / n
    r = radius * (1 + wobble * np.cos(3 * t))
    x, y = r * np.cos(t), squash * r * np.sin(t)
    c, s = math.cos(turn), math.sin(turn)
    return np.column_stack([centre[0] + c * x - s * y, centre[1] + s * x + c * y]).tolist()


def apse(depth: float = 0.0, radius: float = 5.0, n: int = 24, turn: float = 0.0, centre=(0.0, 0.0)) -> list:
    """A half circle of radius ``radius`` (``n`` points) in front of a straight wall from
    ``(0, radius)`` to ``(0, -radius)``, its centre ``depth`` in front of the wall (0: a half disc),
    turned by ``turn`` radians about the origin and moved by ``centre``.

    >>> len(apse()), len(apse(depth=2.0))
    (24, 26)
    """
    t = np.linspace(-math.pi / 2, math.pi / 2, n)
    pts = np.column_stack([depth + radius * np.cos(t), radius * np.sin(t)])
    if depth > 0:
        pts = np.vstack([pts, [[0.0, radius], [0.0, -radius]]])
    c, s = math.cos(turn), math.sin(turn)
    return (pts @ np.array([[c, s], [-s, c]]) + centre).tolist()


def cut_disc(start: float = -60.0, stop: float = 240.0, radius: float = 5.0, n: int = 48) -> list:
    """A disc cut by a wall: ``n`` points of the circle from ``start`` to ``stop`` degrees, closed by
    the straight chord between them (its corners 90 + (360 - stop + start) / 4 degrees: 150 here).

    >>> len(cut_disc())
    48
    """
    t = np.radians(np.linspace(start, stop, n))
    return np.column_stack([radius * np.cos(t), radius * np.sin(t)]).tolist()


def teardrop(radius: float = 4.0, tip: float = 9.0, n: int = 40) -> list:
    """A circle of radius ``radius`` from -140 to 140 degrees (``n`` points) closed at a tip ``tip``
    from its centre on the negative x axis: one sharp corner (about 47 degrees), smooth elsewhere.

    >>> len(teardrop()), teardrop()[-1]
    (41, [-9.0, 0.0])
    """
    t = np.radians(np.linspace(-140.0, 140.0, n))
    return np.vstack([np.column_stack([radius * np.cos(t), radius * np.sin(t)]), [[-tip, 0.0]]]).tolist()


def stadium(length: float = 20.0, radius: float = 2.0, n: int = 24) -> list:
    """Two half circles of ``n`` points and radius ``radius`` joined by straight sides ``length`` long.

    >>> pts = np.array(stadium()); np.round(pts.min(axis=0), 1).tolist(), np.round(pts.max(axis=0), 1).tolist()
    ([-12.0, -2.0], [12.0, 2.0])
    """
    t = np.linspace(-math.pi / 2, math.pi / 2, n)
    right = np.column_stack([length / 2 + radius * np.cos(t), radius * np.sin(t)])
    return np.vstack([right, -right]).tolist()


def lens(bulge: float = 0.5, n: int = 24) -> list:
    """Two parabolic arcs of ``n`` points from (-5, 0) to (5, 0), ``5 * bulge`` high in the middle.

    >>> len(lens()), max(y for _, y in lens(n=5)), min(y for _, y in lens(bulge=1.0, n=5))
    (46, 2.5, -5.0)
    """
    x = np.linspace(-5, 5, n)
    top = np.column_stack([x, bulge * (25 - x ** 2) / 5])
    bottom = np.column_stack([x, -bulge * (25 - x ** 2) / 5])
    return np.vstack([top[::-1], bottom[1:-1]]).tolist()


#: Plans of a degenerate skeleton by name, as domain dicts: one singularity without a branch (an
#: O-grid) or one branch between two corners (cut in three).
SMOOTH_PLANS = {
    "disc": {"outer": oval(48)},
    "octagon": {"outer": oval(8)},
    "ellipse": {"outer": oval(64, squash=0.5, turn=0.3)},
    "egg": {"outer": oval(64, squash=0.7, wobble=0.1)},
    "stadium": {"outer": stadium()},
    "cut_disc": {"outer": cut_disc()},
    "teardrop": {"outer": teardrop()},
    "half_disc": {"outer": apse()},
    "apse": {"outer": apse(depth=3.0)},
    "lens": {"outer": lens()},
}
