"""Option types of the command line that refuse what would fail much later, or never end.

click's ``float`` and ``FloatRange`` take ``nan`` and ``inf`` (a NaN compares false with every bound,
so it passes any range): ``--zmax nan`` failed 500 iterations later, ``--sag nan`` exited 0. Every
numeric option of vaultgram is finite (:class:`Finite`). ``--spacing`` is held to the documented
range (paper §3.1, 1% to 5% of the diagonal) unless ``--any-spacing`` is given (then the library's
(0, 0.2]); iteration counts have an upper bound (:data:`MAX_ITERATIONS`).
"""

from __future__ import annotations

import math

import click

from vaultgram.limits import MAX_FACES, MAX_ITERATIONS, SPACING_MAX, SPACING_RANGE

__all__ = ["Finite", "FINITE", "POSITIVE", "ITERATIONS", "spacing_option", "max_faces_option"]


class Finite(click.FloatRange):
    """A float range that refuses NaN and infinities.

    >>> Finite(min=0.0, min_open=True).convert("2.5", None, None)
    2.5
    >>> Finite().convert("nan", None, None)
    Traceback (most recent call last):
    ...
    click.exceptions.BadParameter: 'nan' is not a finite number.
    """

    name = "finite float"

    def _describe_range(self) -> str:
        """The range for ``--help``: click's own shows ``x<=None`` for a float range without bounds.

        >>> Finite()._describe_range(), Finite(min=0.0, min_open=True)._describe_range()
        ('finite', 'x>0.0')
        """
        if self.min is None and self.max is None:
            return "finite"
        return super()._describe_range()

    def convert(self, value, param, ctx):
        number = super().convert(value, param, ctx)
        if not math.isfinite(number):
            self.fail(f"{value!r} is not a finite number.", param, ctx)
        return number


FINITE = Finite()
POSITIVE = Finite(min=0.0, min_open=True)
ITERATIONS = click.IntRange(0, MAX_ITERATIONS)


def _any_spacing(ctx, param, value) -> None:
    if value:
        ctx.meta["vaultgram.any_spacing"] = True


def _checked_spacing(ctx, param, value: float) -> float:
    """The spacing in the documented range, or anywhere in (0, SPACING_MAX] with ``--any-spacing``."""
    low, high = (0.0, SPACING_MAX) if ctx.meta.get("vaultgram.any_spacing") else SPACING_RANGE
    if not (low < value <= high if low == 0.0 else low <= value <= high):
        hint = "" if low == 0.0 else " (--any-spacing allows (0, 0.2]: a small spacing can take very long)"
        raise click.BadParameter(f"{value:g} is outside {low:g} to {high:g}{hint}.", ctx, param)
    return value


def spacing_option(command):
    """``--spacing`` (finite, in :data:`SPACING_RANGE`) and ``--any-spacing`` (read first, not passed on)."""
    command = click.option("--spacing", default=0.02, show_default=True, type=FINITE, callback=_checked_spacing,
                           help=f"Boundary spacing as a fraction of the bounding-box diagonal "
                                f"({SPACING_RANGE[0]} to {SPACING_RANGE[1]}, the paper's range).")(command)
    return click.option("--any-spacing", is_flag=True, is_eager=True, expose_value=False, callback=_any_spacing,
                        help=f"Allow a --spacing outside the usual range, up to {SPACING_MAX}.")(command)


def max_faces_option(command):
    """``--max-faces``: the size guard of :mod:`vaultgram.meshing.guards`."""
    return click.option("--max-faces", type=click.IntRange(min=1), default=MAX_FACES, show_default=True,
                        help="Refuse, before meshing, densities that would make more faces than this.")(command)
