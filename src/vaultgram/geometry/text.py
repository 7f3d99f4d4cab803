"""Points in messages: every error that names a place prints its coordinates the same way, in the
plan's own coordinates also while the stages work in a local frame (:mod:`vaultgram.geometry.frames`)."""

from __future__ import annotations

import math
from contextlib import contextmanager
from contextvars import ContextVar
from typing import Iterator

__all__ = ["fmt_point", "plan_frame"]

#: The local frame the stages work in, as ``(origin, extra digits)``; None in the plan's own frame.
_FRAME: ContextVar = ContextVar("vaultgram_plan_frame", default=None)


def fmt_point(p, digits: int = 6) -> str:
    """``(x, y)`` with ``digits`` significant digits, for error messages; inside :func:`plan_frame`,
    the local point in the plan's coordinates, with the digits the offset takes on top.

    >>> fmt_point((1 / 3, 2.0)), fmt_point((1 / 3, 2.0), digits=10)
    ('(0.333333, 2)', '(0.3333333333, 2)')
    >>> with plan_frame((1e9, 1e9), 10.0):
    ...     fmt_point((1 / 3, 2.0))
    '(1000000000.3333, 1000000002)'
    """
    frame = _FRAME.get()
    if frame is not None:
        (ox, oy), extra = frame
        p, digits = (float(p[0]) + ox, float(p[1]) + oy), digits + extra
    return f"({float(p[0]):.{digits}g}, {float(p[1]):.{digits}g})"


@contextmanager
def plan_frame(origin, diagonal: float) -> Iterator[None]:
    """Within the ``with`` block, :func:`fmt_point` names local points of a plan of this
    ``diagonal`` whose frame starts at ``origin`` in the plan's coordinates (nothing changes for the
    origin (0, 0))."""
    if origin[0] == 0.0 and origin[1] == 0.0:
        yield
        return
    far = max(abs(origin[0]), abs(origin[1]))
    token = _FRAME.set(((float(origin[0]), float(origin[1])), max(0, math.ceil(math.log10(far / diagonal)))))
    try:
        yield
    finally:
        _FRAME.reset(token)
