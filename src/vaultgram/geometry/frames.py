"""The plan's frame: a plan far from the origin is worked on near it.

Site coordinates (a 30 m vault at easting 500,000 m, or a plan at (1e9, 1e9)) leave double precision
few digits for the plan's shape: a shoelace area, a Delaunay predicate or a scaled Jacobian at 1e9
loses half of its digits to the offset. So every stage works in a *local frame*: the plan moved by
its :func:`local_origin`, which is (0, 0) for a plan near the origin (so nothing changes for it,
bit for bit) and the rounded centre of its bounding box for a far one. Objects that hold local
coordinates carry their ``origin``; the writers add it back (:func:`to_plan`), so every file, and
every error message (:func:`vaultgram.geometry.text.fmt_point`), is in the plan's own coordinates.

The origin is rounded to a multiple of a power of two no smaller than the plan's diagonal: then
``x - origin`` is exact for every coordinate of the plan, and ``(x - origin) + origin == x``
(:func:`local_origin`).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["FAR", "NO_ORIGIN", "between", "local_origin", "to_local", "to_plan"]

#: A plan whose bounding box lies more than ``FAR`` of its diagonals from the origin is moved to a
#: local frame; nearer ones keep their coordinates.
FAR = 10.0
#: The origin of a plan that keeps its coordinates.
NO_ORIGIN = (0.0, 0.0)


def local_origin(points: np.ndarray) -> tuple[float, float]:
    """Where the local frame of a plan with these ``(n, 2+)`` points starts: (0, 0) when the plan is
    within :data:`FAR` diagonals of the origin, else the centre of its bounding box rounded to a
    multiple of the power of two just above its diagonal, along each axis on which it lies farther
    (a coordinate that far is at least 5 such steps away, so its difference to the origin is exact).

    >>> local_origin(np.array([[0.0, 0.0], [30.0, 20.0]]))
    (0.0, 0.0)
    >>> local_origin(np.array([[1e9, 1e9], [1e9 + 10, 1e9 + 10]]))
    (1000000000.0, 1000000000.0)
    """
    xy = np.asarray(points, dtype=float)[:, :2]
    if len(xy) == 0 or not np.isfinite(xy).all():
        return NO_ORIGIN
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    diagonal = float(np.hypot(*(hi - lo)))
    far = np.maximum(np.abs(lo), np.abs(hi)) > FAR * diagonal  # per axis: a near one is not moved
    if diagonal == 0.0 or not far.any():
        return NO_ORIGIN
    step = 2.0 ** math.ceil(math.log2(diagonal))
    centre = np.where(far, np.round((lo + hi) / 2 / step) * step, 0.0)
    return float(centre[0]), float(centre[1])


def to_local(points, origin) -> np.ndarray:
    """``points`` (``(n, 2)`` or ``(n, 3)``, or one point) moved into the frame starting at ``origin``
    (heights unchanged); the array itself when ``origin`` is (0, 0).

    >>> to_local(np.array([[1e9 + 1.5, 1e9 - 2.0, 3.0]]), (1e9, 1e9)).tolist()
    [[1.5, -2.0, 3.0]]
    """
    return _moved(points, origin, -1.0)


def to_plan(points, origin) -> np.ndarray:
    """``points`` of the frame starting at ``origin`` back in the plan's coordinates (heights
    unchanged); the array itself when ``origin`` is (0, 0), so that near plans keep every bit.

    >>> to_plan(np.array([[1.5, -2.0]]), (1e9, 1e9)).tolist()
    [[1000000001.5, 999999998.0]]
    """
    return _moved(points, origin, 1.0)


def between(origin, target) -> tuple[float, float]:
    """The offset that :func:`to_plan` adds to move points of the frame starting at ``origin`` into
    the frame starting at ``target`` (how an object's ``in_frame`` moves its arrays).

    >>> between((1e9, 0.0), (0.0, 0.0)), to_plan(np.array([[0.5, 1.0]]), between((4.0, 2.0), (1.0, 2.0))).tolist()
    ((1000000000.0, 0.0), [[3.5, 1.0]])
    """
    return (origin[0] - target[0], origin[1] - target[1])


def _moved(points, origin, sign: float) -> np.ndarray:
    x = np.asarray(points, dtype=float)
    if origin[0] == 0.0 and origin[1] == 0.0:
        return x
    out = x.copy()
    out[..., 0] += sign * origin[0]
    out[..., 1] += sign * origin[1]
    return out
