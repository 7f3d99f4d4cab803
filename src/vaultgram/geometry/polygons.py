"""Polygons: signed area, bounding boxes, corner angles, orientation and elongation.

A polygon is an ``(n, 2)`` array of its vertices without the closing one; counter-clockwise
polygons have positive area (the domain lies to the left of every ring, §3.1).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["signed_area", "bbox_diagonal", "interior_angle", "direction", "ccw_degrees", "regular_valence", "cross_z",
           "signed_angles", "triangle_areas", "elongation"]


def signed_area(poly: np.ndarray) -> float:
    """Shoelace area: positive for a counter-clockwise polygon.

    >>> signed_area(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]))
    2.0
    """
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def bbox_diagonal(points: np.ndarray) -> float:
    """Length of the diagonal of the bounding box of ``points`` (0 for no points).

    >>> bbox_diagonal(np.array([[0.0, 0.0], [3.0, 4.0], [1.0, 1.0]]))
    5.0
    """
    if len(points) == 0:
        return 0.0
    return float(np.hypot(*(points.max(axis=0) - points.min(axis=0))))


def interior_angle(before, corner, after) -> float:
    """The angle inside a counter-clockwise polygon at ``corner`` (degrees in [0, 360)): the turn from
    the direction towards the next corner (``after``) to the direction towards the previous one.

    >>> interior_angle((0, 1), (0, 0), (1, 0)), interior_angle((1, 0), (0, 0), (0, 1))
    (90.0, 270.0)
    """
    a = math.atan2(after[1] - corner[1], after[0] - corner[0])
    b = math.atan2(before[1] - corner[1], before[0] - corner[0])
    return math.degrees((b - a) % (2 * math.pi))


def direction(a, b) -> float:
    """The direction (radians, counter-clockwise from the x axis) from point ``a`` to point ``b``:
    the angles of chords and sides at a layout's corners are measured between such directions
    (:func:`ccw_degrees`; §3.1's corner angles, the chords of issue 12).

    >>> round(math.degrees(direction((1, 1), (1, 3))), 6), round(math.degrees(direction((0, 0), (-1, 0))), 6)
    (90.0, 180.0)
    """
    return math.atan2(float(b[1]) - float(a[1]), float(b[0]) - float(a[0]))


def ccw_degrees(start: float, end: float) -> float:
    """Degrees turning counter-clockwise from the direction ``start`` to ``end`` (radians), in
    [0, 360): the angle a polygon's interior spans at a corner from its leaving side to another ray,
    as :func:`interior_angle` measures it.

    >>> ccw_degrees(0.0, math.pi / 2), ccw_degrees(math.pi / 2, 0.0)
    (90.0, 270.0)
    """
    return math.degrees(end - start) % 360.0


def regular_valence(theta) -> np.ndarray:
    """The regular valence of a boundary vertex of a quad mesh whose interior angle is ``theta``
    (degrees): ``1 + max(1, round(theta / 90))``, the usual quad-layout rule. Its number of faces is
    one less: 1 below 135 degrees (a convex corner, valence 2), 2 from 135 to 225 (a smooth
    boundary point, 3), 3 from 225 to 315 (a reflex corner, 4), 4 beyond (5). A tie goes up (135 is
    smooth, 225 reflex), within 1e-9 degrees (a polygon's 135 degree corner computed in floating point).

    >>> regular_valence(np.array([90.0, 134.0, 135.0, 180.0, 224.0, 270.0, 320.0])).tolist()
    [2, 2, 3, 3, 3, 4, 5]
    """
    q = np.asarray(theta, dtype=float) / 90.0
    return 1 + np.maximum(1, np.floor(q + 0.5 + 1e-11)).astype(np.int64)


def cross_z(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise z component of the cross product of 2D vectors ``a`` and ``b`` (``(k, 2)`` arrays):
    positive where ``b`` lies counter-clockwise of ``a``, as at every corner of a counter-clockwise
    polygon or face.

    >>> cross_z(np.array([[1.0, 0.0], [1.0, 0.0]]), np.array([[0.0, 1.0], [0.0, -2.0]])).tolist()
    [1.0, -2.0]
    """
    return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]


def signed_angles(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise signed angle (radians, in [-pi, pi]) from the 2D vectors ``a`` to ``b``: a polygon's
    turning angle from one side to the next, a face corner's angle between its two sides (positive
    counter-clockwise). The dot product by columns: the same bits as ``(a * b).sum(axis=1)``.

    >>> signed_angles(np.array([[1.0, 0.0], [1.0, 0.0]]), np.array([[0.0, 1.0], [-1.0, -1.0]])).round(4).tolist()
    [1.5708, -2.3562]
    """
    return np.arctan2(cross_z(a, b), a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1])


def triangle_areas(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Signed area of each triangle ``points[triangles[k]]`` (vectorised): positive when counter-clockwise.

    >>> p = np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]])
    >>> triangle_areas(p, np.array([[0, 1, 2], [0, 2, 1]])).tolist()
    [1.0, -1.0]
    """
    a, b, c = points[triangles[:, 0]], points[triangles[:, 1]], points[triangles[:, 2]]
    return 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


def elongation(ring: np.ndarray) -> float:
    """How elongated the area inside a ring is: the square root of the ratio of its principal second
    moments of area (1 for a disc or a regular polygon, 2 for an ellipse of axes 2:1). Of the area,
    not of the ring's points (as :func:`vaultgram.topology.ogrid.principal_axes`), so that it does not
    depend on how the outline is sampled: rv_pillow_pattern, a 24-gon on a circle with uneven angles,
    gives 1.001 (its points' spreads differ by 3%). The O-grid's corners depend on it (paper §3.1).

    >>> t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    >>> round(elongation(np.column_stack([2 * np.cos(t), np.sin(t)])), 3)
    2.0
    >>> elongation(np.array([[0, 0], [1, 0], [1, 1], [0, 1]]))
    1.0
    """
    p = np.asarray(ring, dtype=float)[:, :2]
    p = p - p.mean(axis=0)
    (x, y), (x1, y1) = p.T, np.roll(p, -1, axis=0).T
    cross = x * y1 - x1 * y
    area = cross.sum() / 2
    cx, cy = ((x + x1) * cross).sum() / (6 * area), ((y + y1) * cross).sum() / (6 * area)
    x, y, x1, y1 = x - cx, y - cy, x1 - cx, y1 - cy
    ixx, iyy = ((x * x + x * x1 + x1 * x1) * cross).sum(), ((y * y + y * y1 + y1 * y1) * cross).sum()
    ixy = ((x * y1 + 2 * x * y + 2 * x1 * y1 + x1 * y) * cross).sum() / 2
    low, high = np.linalg.eigvalsh([[ixx, ixy], [ixy, iyy]])
    return float(math.sqrt(high / low))
