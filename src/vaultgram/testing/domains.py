"""Random plans for the property tests of the stages that take a domain (topology, meshing), and for
``vaultgram rules test``.

* ``vault_domains()`` -- ``(domain dict, spacing)``: non-convex star-shaped outlines with 0-3 holes,
  0-3 inner and 0-3 boundary point features and 0-2 curve features, kept apart, and a spacing in the
  documented range; what ``vaultgram rules test`` draws. Counts and vertex numbers shrink towards
  the smallest (a 4-gon, 3-gon holes), so a counterexample comes out small;

* ``star_polygons()`` -- counter-clockwise star-shaped polygons as (n, 2) arrays, anywhere in the plane:
  simple polygons of known orientation for the polygon kernel;
* ``polygons_with_holes()`` -- domain dicts: a star-shaped outer ring with 0 to 3 small round holes
  kept well inside it and apart, to decompose (§3.1);
* ``convex_domains()`` -- :class:`~vaultgram.domain.Domain` objects: perturbed regular polygons, maybe
  with a circular hole, whose meshes must have no boundary singularity (§3.2);
* ``feature_domains()`` -- domain dicts: rectangles, maybe with a hole, with point features inside
  and on the sides and short curve features (§4.1, §4.2);
* ``squares_with_curves()`` -- lists of 1 or 2 simple curves inside the 10 x 10 square :data:`SQUARE`,
  apart from each other; :func:`square_with` makes the domain.

The draws are kept as they were when each lived beside its tests, so the property tests explore the
same inputs (and reproduce the same failures) as before.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from hypothesis import strategies as st

from vaultgram.domain import domain_from_dict

#: The 10 x 10 square of the curve-feature tests.
SQUARE = [[0, 0], [10, 0], [10, 10], [0, 10]]

coordinates = st.floats(-100, 100, allow_nan=False, allow_infinity=False)
points = st.tuples(coordinates, coordinates)


def square_with(*curves):
    """The domain :data:`SQUARE` with the curve features ``curves``."""
    return domain_from_dict({"outer": SQUARE, "curves": [list(c) for c in curves]})


@st.composite
def star_polygons(draw):
    """Counter-clockwise star-shaped polygons: 3 to 12 vertices at increasing angles round a centre."""
    n = draw(st.integers(3, 12))
    radii = np.array(draw(st.lists(st.floats(0.5, 20.0), min_size=n, max_size=n)))
    centre = np.array(draw(points))
    t = np.sort(np.array(draw(st.lists(st.floats(0.0, 2 * math.pi), min_size=n, max_size=n, unique=True))))
    if np.diff(np.concatenate([t, [t[0] + 2 * math.pi]])).max() >= math.pi - 1e-3:
        t = 2 * math.pi * np.arange(n) / n  # a gap of half a turn or more: the centre would be outside
    return centre + np.column_stack([radii * np.cos(t), radii * np.sin(t)])


@st.composite
def polygons_with_holes(draw):
    """A random star-shaped outer ring with 0 to 3 random convex-ish holes placed inside it."""
    n = draw(st.integers(4, 9))
    radii = draw(st.lists(st.floats(6.0, 10.0), min_size=n, max_size=n))
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False) + draw(st.floats(0, 0.3))
    outer = np.c_[np.cos(angles) * radii, np.sin(angles) * radii]
    holes = []
    for _ in range(draw(st.integers(0, 3))):
        cx, cy = draw(st.floats(-4, 4)), draw(st.floats(-4, 4))
        r = draw(st.floats(0.4, 1.5))
        k = draw(st.integers(3, 12))
        t = np.linspace(0, 2 * np.pi, k, endpoint=False)
        hole = np.c_[cx + r * np.cos(t), cy + r * np.sin(t)]
        poly = shapely.Polygon(hole)
        if shapely.Polygon(outer).buffer(-0.5).contains(poly) and all(
            shapely.Polygon(h).distance(poly) > 0.5 for h in holes
        ):
            holes.append(hole)
    return {"name": "random", "outer": outer.tolist(), "holes": [h.tolist() for h in holes]}


@st.composite
def convex_domains(draw):
    """Convex polygons (rectangles or perturbed regular polygons), maybe with a circular hole."""
    n = draw(st.integers(4, 7))
    radii = draw(st.lists(st.floats(0.85, 1.15), min_size=n, max_size=n))
    phase = draw(st.floats(0, 2 * math.pi / n))
    t = phase + 2 * math.pi * np.arange(n) / n
    outer = np.column_stack([10 * np.array(radii) * np.cos(t), 10 * np.array(radii) * np.sin(t)])
    data = {"outer": outer.tolist()}
    if draw(st.booleans()):
        r = draw(st.floats(1.5, 3.5))
        c = np.array(draw(st.tuples(st.floats(-1.5, 1.5), st.floats(-1.5, 1.5))))
        s = np.linspace(0, 2 * math.pi, 40, endpoint=False)
        data["holes"] = [(c + r * np.column_stack([np.cos(s), np.sin(s)])).tolist()]
    return domain_from_dict(data)


@st.composite
def feature_domains(draw):
    """A rectangle, maybe with a round hole, with 0-3 inner points, 0-1 point on its sides and 0-2
    curve features inside. (Several boundary points crowded with inner ones into one corner can
    still leave a boundary point that is no pole, so there is at most one; two in one side are tested
    in tests/meshing/test_features.py, test_two_boundary_features_in_one_side.) The dict may be
    invalid (a curve leaving the rectangle, or crossing another): the caller validates it."""
    w = draw(st.floats(6.0, 14.0))
    h = draw(st.floats(6.0, 14.0))
    data = {"outer": [[0, 0], [w, 0], [w, h], [0, h]], "points": [], "curves": []}
    if draw(st.booleans()):
        t = np.linspace(0, 2 * np.pi, 24, endpoint=False)[::-1]
        r = 0.15 * min(w, h)
        data["holes"] = [np.column_stack([w / 2 + r * np.cos(t), h / 2 + r * np.sin(t)]).tolist()]
    frac = st.floats(0.05, 0.95)
    for _ in range(draw(st.integers(0, 3))):
        data["points"].append([draw(frac) * w, draw(frac) * h])
    for _ in range(draw(st.integers(0, 1))):  # on a side of the rectangle (§4.1 boundary features)
        t = draw(frac)
        data["points"].append(draw(st.sampled_from([[t * w, 0], [w, t * h], [t * w, h], [0, t * h]])))
    for _ in range(draw(st.integers(0, 2))):
        p = np.array([draw(st.floats(0.1, 0.9)) * w, draw(st.floats(0.1, 0.9)) * h])
        pts = [p]
        for _ in range(draw(st.integers(1, 2))):
            a = draw(st.floats(0.0, 2 * np.pi))
            length = draw(st.floats(0.1, 0.3)) * min(w, h)
            pts.append(pts[-1] + length * np.array([np.cos(a), np.sin(a)]))
        data["curves"].append(np.array(pts).tolist())
    return data


@st.composite
def squares_with_curves(draw):
    """1 or 2 curves of 2 or 3 points inside :data:`SQUARE` (at least 1.5 from its sides), each simple,
    at least 1.5 long and 1.0 from the others; a curve that is not is dropped, so the list may be
    empty (callers ``assume`` it is not). The domain is ``square_with(*curves)``."""
    curves = []
    for _ in range(draw(st.integers(1, 2))):
        k = draw(st.integers(2, 3))
        pts = [(draw(st.floats(1.5, 8.5)), draw(st.floats(1.5, 8.5))) for _ in range(k)]
        line = shapely.LineString(pts)
        if line.length < 1.5 or not line.is_simple or any(line.distance(shapely.LineString(c)) < 1.0 for c in curves):
            continue
        curves.append(pts)
    return curves


#: The spacings ``vault_domains`` draws (fractions of the bounding-box diagonal; the documented
#: range is 0.01 to 0.05, the finest left out to keep a run of hundreds of examples short).
SPACINGS = (0.04, 0.03, 0.05, 0.02)
GAP = 1.5  # features, holes and the boundary are kept this far apart (domain units; outline ~ 20 wide)
RESOLVED = 2.0  # a hole's circumradius and clearance, in sample spacings


@st.composite
def vault_domains(draw, max_holes: int = 3, max_points: int = 3, max_boundary_points: int = 3, max_curves: int = 2):
    """A random valid domain dict and a spacing (see the module docstring). Features that do not fit
    where they are drawn (too near the boundary, a hole or another feature) are left out, so the dict
    is valid; the caller still checks the spacing (``check_feature_spacing``). A hole is kept only when
    the spacing resolves it: its circumradius and its distance to everything else at least
    :data:`RESOLVED` sample spacings (``h = spacing x diagonal``); coarser, the discretised skeleton
    around it can cross the straight rebranches (found by ``vaultgram rules test``: a 3-gon hole of
    circumradius 1.7 h at spacing 0.03 gives a layout that is not planar, and decompose fails)."""
    spacing = draw(st.sampled_from(SPACINGS))
    n = draw(st.integers(4, 9))
    radii = draw(st.lists(st.floats(5.0, 10.0), min_size=n, max_size=n))
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) + draw(st.floats(0, 0.5))
    outer = np.c_[np.cos(t) * radii, np.sin(t) * radii]
    h = spacing * float(np.hypot(*np.ptp(outer, axis=0)))
    room = shapely.Polygon(outer).buffer(-GAP)
    taken: list = []
    data = {"name": "random", "outer": outer.tolist(), "holes": [], "points": [], "curves": []}
    for _ in range(draw(st.integers(0, max_holes))):
        hole, radius = _draw_hole(draw)
        resolved = radius >= RESOLVED * h and shapely.Polygon(outer).buffer(-RESOLVED * h).contains(
            shapely.Polygon(hole)) and all(shapely.Polygon(hole).distance(g) >= RESOLVED * h for g in taken)
        if resolved and _fits(shapely.Polygon(hole), room, taken):
            data["holes"].append(hole.tolist())
    for _ in range(draw(st.integers(0, max_points))):
        p = shapely.Point(draw(st.floats(-6, 6)), draw(st.floats(-6, 6)))
        if _fits(p, room, taken):
            data["points"].append([p.x, p.y])
    for _ in range(draw(st.integers(0, max_curves))):
        curve = _draw_curve(draw)
        if curve.is_simple and _fits(curve, room, taken):
            data["curves"].append([list(c) for c in curve.coords])
    data["points"] += _boundary_points(draw, outer, max_boundary_points)
    return data, spacing


def _draw_hole(draw) -> tuple[np.ndarray, float]:
    """A regular polygon of 3 to 8 vertices, clockwise (a hole keeps the domain on its left), and its
    circumradius."""
    k = draw(st.integers(3, 8))
    c, r = np.array([draw(st.floats(-5, 5)), draw(st.floats(-5, 5))]), draw(st.floats(0.6, 2.5))
    s = -np.linspace(0, 2 * np.pi, k, endpoint=False)
    return c + r * np.c_[np.cos(s), np.sin(s)], r


def _draw_curve(draw):
    """A curve of 1 or 2 segments, 1.5 to 3 long each."""
    pts = [np.array([draw(st.floats(-6, 6)), draw(st.floats(-6, 6))])]
    for _ in range(draw(st.integers(1, 2))):
        a = draw(st.floats(0, 2 * np.pi))
        pts.append(pts[-1] + draw(st.floats(1.5, 3.0)) * np.array([np.cos(a), np.sin(a)]))
    return shapely.LineString(pts)


def _fits(geom, room, taken: list) -> bool:
    """Whether ``geom`` lies in ``room`` and at least :data:`GAP` from everything ``taken`` (it is then
    taken too)."""
    if not room.contains(geom) or any(geom.distance(g) < GAP for g in taken):
        return False
    taken.append(geom)
    return True


def _boundary_points(draw, outer: np.ndarray, most: int) -> list:
    """Up to ``most`` points on distinct sides of the outline, in the middle half of each side."""
    sides = draw(st.lists(st.integers(0, len(outer) - 1), max_size=most, unique=True))
    out = []
    for i in sides:
        t = draw(st.floats(0.25, 0.75))
        out.append((outer[i] + t * (outer[(i + 1) % len(outer)] - outer[i])).tolist())
    return out
