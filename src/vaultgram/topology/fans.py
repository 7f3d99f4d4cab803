"""Whether a triangle meshed as a fan round its pole can be meshed without a fold (§4.1, Figure 4).

A three-sided patch with a marked pole is meshed as a fan of quads round the pole: rows of quads
run from the pole to its opposite side, spread over the pole's angle. A split by a diagonal that
has to bend round a curved side (a skeleton branch bulging towards the pole,
:func:`~vaultgram.topology.functions.diagonal_path`) can leave a crescent: a triangle whose
outline, seen from the pole, turns back by as much as the pole's whole angle in it, so that the
rows of the fan have to cross (saved random plan 78: a boundary point feature split from a skeleton
vertex whose branch bulged to it, 19 inverted faces between the branch and the bent diagonal at any
density or spacing). A slight turn back is no such wrap: a side through the pole that sags into the
patch (a concave arc of the boundary) or a diagonal bent by a few degrees hides a sliver from the
pole that the fan's curved rows and the smoothing absorb (two_holes_five_points' boundary point at
a 58.5 degree corner: 1.2 degrees hidden in each half, meshed well). So a part is refused only where
its outline turns back about the pole by more than :data:`HIDDEN_SHARE` of its angle there: one
pass over the outline.
"""

from __future__ import annotations

import numpy as np

__all__ = ["HIDDEN_SHARE", "hidden_turn", "seen_from_pole", "fan_parts_seen"]

#: The share of a fan part's angle at its pole by which its outline may turn back about the pole.
#: Measured over the 700 saved random plans of session 24 (Figure 4 splits whose parts turn back at
#: all): bent diagonals and sagging sides turn back by 0.2 to 0.4 of the part's angle at most,
#: crescents by 0.63 to 1.8 (plan 78: 29 degrees in a part of 23, a fold; plans 31-33: 16 in 24).
HIDDEN_SHARE = 0.5


def hidden_turn(outline, pole) -> tuple[float, float]:
    """How far (radians) the points of ``outline`` (counter-clockwise, from the point after the
    pole to the point before it) turn back about ``pole`` at the deepest (the largest drop of their
    angle below the furthest one reached before), and how far they turn in all, first to last (the
    pole's angle in the polygon they close with it).

    >>> [round(float(np.degrees(t)), 1) for t in hidden_turn([(1, 0), (1, 1), (0, 1)], (0, 0))]
    [0.0, 90.0]
    >>> [round(float(np.degrees(t)), 1) for t in hidden_turn([(1, 0), (1, 1), (3, 1), (3, 3), (0, 3)], (0, 0))]
    [26.6, 90.0]
    """
    d = np.asarray(outline, dtype=float) - np.asarray(pole, dtype=float)
    d = d[np.hypot(d[:, 0], d[:, 1]) > 0]
    angle = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    return float(np.max(np.maximum.accumulate(angle) - angle)), float(angle[-1] - angle[0])


def seen_from_pole(outline, pole) -> bool:
    """Whether the polygon that the points of ``outline`` (as :func:`hidden_turn`'s) close with
    ``pole`` meshes as a fan round it: its outline turns about the pole by less than a full turn,
    and turns back by at most :data:`HIDDEN_SHARE` of that (not a crescent).

    >>> seen_from_pole([(1, 0), (1, 1), (0, 1)], (0, 0))
    True
    >>> seen_from_pole([(1, 0), (1, 1), (3, 1), (3, 3), (0, 3)], (0, 0))  # (3, 1): 27 of 90 degrees hidden
    True
    >>> seen_from_pole([(2, 0), (2, 2), (1, 0.05), (0.3, 1)], (0, 0))  # a crescent: 42 of 73 hidden
    False
    """
    hidden, whole = hidden_turn(outline, pole)
    return whole < 2 * np.pi and hidden <= HIDDEN_SHARE * whole


def fan_parts_seen(outline, at: int, path) -> bool:
    """Whether both parts into which the polyline ``path`` (from the patch's corner ``outline[0]``
    to its corner ``outline[at]``) cuts a patch of closed counter-clockwise ``outline`` (first point
    = last point) mesh as fans round ``outline[0]`` (:func:`seen_from_pole`): the split of Figure 4
    leaves no crescent.

    >>> square = [(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)]
    >>> fan_parts_seen(square, 2, [(0, 0), (1, 1)])
    True
    >>> fan_parts_seen(square, 2, [(0, 0), (0.1, 0.9), (1, 1)])  # bent far into the first part
    False
    """
    outline, path = np.asarray(outline, dtype=float), np.asarray(path, dtype=float)
    pole = outline[0]
    first = np.concatenate([outline[1: at + 1], path[::-1][1:-1]])
    second = np.concatenate([path[1:-1], outline[at:-1]])
    return seen_from_pole(first, pole) and seen_from_pole(second, pole)
