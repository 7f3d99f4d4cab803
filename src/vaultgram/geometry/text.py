"""Points in messages: every error that names a place prints its coordinates the same way."""

from __future__ import annotations

__all__ = ["fmt_point"]


def fmt_point(p, digits: int = 6) -> str:
    """``(x, y)`` with ``digits`` significant digits, for error messages.

    >>> fmt_point((1 / 3, 2.0)), fmt_point((1 / 3, 2.0), digits=10)
    ('(0.333333, 2)', '(0.3333333333, 2)')
    """
    return f"({float(p[0]):.{digits}g}, {float(p[1]):.{digits}g})"
