"""The meshing stages' corner geometry computed a cache-sized piece at a time, and the per-vertex minima
taken by one grouping: the same numbers, bit for bit, as the whole-array computations they replace."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vaultgram.geometry.arrays import PIECE
from vaultgram.geometry.meshes import Faces, corner_arrays, corner_vectors, grid_mesh
from vaultgram.geometry.polygons import cross_z, signed_angles
from vaultgram.meshing import optimise, smoothing, untangle
from vaultgram.meshing.fans import fan_bounds
from vaultgram.meshing.quality import face_scaled_jacobians


@pytest.fixture(scope="module", params=[0.0, 0.3])
def jittered(request):
    """A 100 x 100 grid (40000 corners: several pieces) with every seventh quad cut into two triangles,
    its vertices jittered by ``param`` of the spacing (0.3 folds some faces), one side collapsed."""
    v, quads = grid_mesh(100)
    faces = []
    for k, (a, b, c, d) in enumerate(quads):
        faces += [(a, b, c), (a, c, d)] if k % 7 == 0 else [(a, b, c, d)]
    x = v[:, :2] + np.random.default_rng(5).uniform(-request.param, request.param, (len(v), 2))
    x[202] = x[203]
    assert 3 * len(faces) > 2 * PIECE
    return x, Faces(faces)


def _touch_reference(values, u, v, p, n):
    """Per vertex, the least of the values of the corners having it as vertex, next or previous vertex."""
    out = np.full(n, np.inf)
    for ends in (u, v, p):
        np.minimum.at(out, ends, values)
    return out


def test_valid_faces_in_pieces(jittered):
    x, faces = jittered
    face_of, u, v, p = corner_arrays(faces)
    e1, e2 = corner_vectors(x, u, v, p)
    scale = e1[:, 0] * e1[:, 0] + e1[:, 1] * e1[:, 1] + (e2[:, 0] * e2[:, 0] + e2[:, 1] * e2[:, 1])
    bad = np.zeros(len(faces), dtype=bool)
    bad[face_of[cross_z(e1, e2) <= 1e-9 * scale]] = True
    assert np.array_equal(smoothing._valid_faces(x, smoothing._FaceCorners(face_of, u, v, p, len(faces))), ~bad)


def test_face_scaled_jacobians_in_pieces(jittered):
    x, faces = jittered
    face_of, u, v, p = corner_arrays(faces)
    e1, e2 = corner_vectors(x, u, v, p)
    norm = np.hypot(*e1.T) * np.hypot(*e2.T)
    sj = np.where(norm > 0, cross_z(e1, e2) / np.where(norm > 0, norm, 1.0), -1.0)
    tri = np.bincount(face_of)[face_of] == 3
    sj = np.where(tri, np.minimum(sj * 2.0 / math.sqrt(3.0), 1.0), sj)
    expected = np.full(len(faces), np.inf)
    np.minimum.at(expected, face_of, sj)
    assert np.array_equal(face_scaled_jacobians(x, faces), expected)


def test_fan_bounds_bisect_only_where_the_angle_limits(jittered):
    x, faces = jittered
    face_of, u, v, p = corner_arrays(faces)
    angle = signed_angles(*corner_vectors(x, u, v, p))
    theta = np.bincount(u, weights=np.where(angle < 0, angle + 2 * math.pi, angle), minlength=len(x))
    tri = (np.bincount(face_of) == 3)[face_of]
    n_tri, n_quad = np.bincount(u, weights=tri, minlength=len(x)), np.bincount(u, weights=~tri, minlength=len(x))
    lo, hi = np.zeros(len(x)), np.ones(len(x))
    for _ in range(50):
        s = 0.5 * (lo + hi)
        fits = n_tri * np.arcsin(np.minimum(1.0, s * math.sqrt(3.0) / 2)) + n_quad * np.arcsin(s) <= theta
        lo, hi = np.where(fits, s, lo), np.where(fits, hi, s)
    bounds = fan_bounds(x, faces)
    assert np.array_equal(bounds, lo)
    assert 0 < (bounds < lo.max()).sum() < len(x)  # some vertices limited, most not


def test_vertex_minima_and_goals_by_one_grouping(jittered):
    x, faces = jittered
    face_of, u, v, p = corner_arrays(faces)
    table = optimise.corner_table(faces)
    xy = x[:, :2]
    sj = optimise.corner_quality(xy[u], xy[v], xy[p], table.factor)
    assert np.array_equal(optimise._vertex_minima(x, table), _touch_reference(sj, u, v, p, len(x)))
    values = np.random.default_rng(2).normal(size=len(u))
    assert np.array_equal(optimise._touching(values, table, len(x), np.inf), _touch_reference(values, u, v, p, len(x)))
    # the length factor: each side against SIDE_SHARE of its opposite side (a triangle's: the mean of its
    # other two) as on entry, here a mesh ten times the size, so that most factors are below 1
    ref1, ref2 = [], []
    for f in faces:
        n = len(f)
        side = [math.dist(x[f[i]], x[f[(i + 1) % n]]) for i in range(n)]
        ref = [side[(i + 2) % 4] if n == 4 else (side[(i + 1) % 3] + side[(i + 2) % 3]) / 2 for i in range(n)]
        ref1 += ref
        ref2 += [ref[i - 1] for i in range(n)]
    ref1, ref2 = 10 * optimise.SIDE_SHARE * np.array(ref1), 10 * optimise.SIDE_SHARE * np.array(ref2)
    with np.errstate(divide="ignore", invalid="ignore"):
        factor = np.minimum(1.0, np.minimum(np.hypot(*(xy[v] - xy[u]).T) / ref1, np.hypot(*(xy[p] - xy[u]).T) / ref2))
    expected = np.where(sj > 0, sj * factor, sj)
    assert (factor < 1).mean() > 0.9
    assert np.allclose(optimise._vertex_minima(x, optimise.corner_table(faces, 10 * x)),
                       _touch_reference(expected, u, v, p, len(x)), rtol=1e-12, atol=0)


def test_untangling_targets_and_scaled_jacobians_in_pieces(jittered):
    x, faces = jittered
    _, u, v, p = corner_arrays(faces)
    assert np.array_equal(untangle._scaled_jacobians(x, u, v, p), untangle._corners(x, u, v, p).sj)
    angle = np.abs(signed_angles(*corner_vectors(x, u, v, p)))
    mean = np.bincount(u, weights=angle)[u] / np.bincount(u)[u]
    expected = np.minimum(0.1, 0.5 * np.sin(np.minimum(mean, np.pi / 2)))
    assert np.array_equal(untangle._corner_targets(x, u, v, p, len(x), 0.1), expected)
