"""Feature layouts the rulebook cannot decompose yet, refused up front with the feature and the reason.

The bundled rules (rules/curves.vgr, §4.2) cut the skeleton along each curve feature on its own;
where features meet *inside* the plan the cut leaves patches of 5 to 13 sides, which no rule splits,
and the run ended with an internal message ("patch has 13 sides", "a patching rule must replace the
Patch nodes it splits"). Until rules for those junctions exist, these layouts are a documented
restriction (docs/formats.md), each named:

* two curve features sharing an end inside the plan (join them into one curve; sharing an end on the
  boundary is fine);
* a curve feature ending on another curve away from its ends (a T of curves);
* a point feature on a curve away from its ends (at a curve's end it is fine).

Bends of any angle, curves ending on the outline or on a hole, and point features at curve ends are
decomposed (tests/domain/test_layouts.py).

>>> from vaultgram.domain import domain_from_dict
>>> square = [[0, 0], [30, 0], [30, 30], [0, 30]]
>>> check_feature_layout(domain_from_dict({"outer": square, "curves": [[[8, 8], [20, 8], [20, 20]]]}))
"""

from __future__ import annotations

import shapely

from vaultgram.errors import DomainError
from vaultgram.geometry.text import fmt_point

__all__ = ["check_feature_layout"]


def check_feature_layout(domain) -> None:
    """Raise a :class:`DomainError` naming the features of a layout the rules cannot decompose (see
    the module docstring)."""
    tol = domain.tolerance
    boundary = domain.polygon().boundary
    lines = [shapely.LineString(c) for c in domain.curves]
    for k, curve in enumerate(domain.curves):
        for end in (curve[0], curve[-1]):
            if shapely.distance(shapely.Point(end), boundary) <= tol:
                continue
            for j, other in enumerate(domain.curves):
                if j != k:
                    _check_end_on_curve(k, end, j, other, lines[j], tol)
    for i, p in enumerate(domain.points):
        for j, other in enumerate(domain.curves):
            at_end = min(_dist(p, other[0]), _dist(p, other[-1])) <= tol
            if not at_end and shapely.distance(shapely.Point(p), lines[j]) <= tol:
                raise DomainError(
                    f"point feature {i} at {fmt_point(p)} lies on curve feature {j} away from its ends: the "
                    "rules cannot decompose a point on a curve yet; move it off the curve or to one of its ends")


def _check_end_on_curve(k: int, end, j: int, other, line, tol: float) -> None:
    """Curve ``k``'s inner end ``end`` against curve ``j``: a shared end or a T is refused."""
    if min(_dist(end, other[0]), _dist(end, other[-1])) <= tol:
        if k < j:
            raise DomainError(
                f"curve features {k} and {j} share an end at {fmt_point(end)} inside the plan: the rules "
                "cannot decompose curves meeting inside the plan yet; join them into one curve feature")
    elif shapely.distance(shapely.Point(end), line) <= tol:
        raise DomainError(
            f"curve feature {k} ends on curve feature {j} at {fmt_point(end)}, away from its ends (a T of "
            "curves): the rules cannot decompose it yet; end it short of the other curve, or split that curve there")


def _dist(a, b) -> float:
    return float(((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2) ** 0.5)
