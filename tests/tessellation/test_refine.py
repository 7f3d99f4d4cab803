"""Refinement of the strips of large quads before the bond (§5, "shape and size uniformity")."""

import numpy as np
import pytest

from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.meshes import Faces, boundary_loops, corner_arrays, with_midpoints
from vaultgram.geometry.surfaces import area_vectors, surface_areas
from vaultgram.tessellation.refine import (
    LARGE,
    _areas_after,
    _midpoints_inserted,
    _nodes_to_refine,
    _refined,
    refine_large_faces,
)
from vaultgram.tessellation.strips import strip_labels


def rect_mesh(xs, ys):
    """A planar quad mesh on the grid lines ``xs`` x ``ys``: vertex ``(i, j)`` is ``j * len(xs) + i``."""
    gx, gy = np.meshgrid(np.asarray(xs, dtype=float), np.asarray(ys, dtype=float))
    v = np.column_stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)])
    n = len(xs)
    faces = [(j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i)
             for j in range(len(ys) - 1) for i in range(n - 1)]
    return v, faces


def _areas(x, faces):
    return np.linalg.norm(area_vectors(x, faces), axis=1)


def _conforming(x, faces):
    """A manifold, consistently oriented mesh with one boundary loop and no vertex in the middle of a
    side (every vertex is a corner of each face whose sides pass through it)."""
    me = mesh_edges(faces, len(x))
    assert len(boundary_loops(faces)) == 1
    a, b = x[me.edges[:, 0]], x[me.edges[:, 1]]
    for p in x:
        t = ((p - a) * (b - a)).sum(axis=1) / ((b - a) ** 2).sum(axis=1)
        inside = (t > 1e-9) & (t < 1 - 1e-9)
        assert not (np.linalg.norm(a + t[:, None] * (b - a) - p, axis=1)[inside] < 1e-9).any()


def _aspect(x, face):
    p = x[list(face)]
    length = np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)
    return max(length[0] + length[2], length[1] + length[3]) / min(length[0] + length[2], length[1] + length[3])


def test_a_mesh_without_large_quads_is_left_as_it_is():
    v, f = rect_mesh(range(5), range(4))
    x, faces, parents, origin, refined = refine_large_faces(v, f)
    assert refined == 0 and parents == [] and x is v
    assert list(faces) == [tuple(q) for q in f] and origin.tolist() == list(range(len(f)))


def test_exactly_the_strip_of_the_quads_above_twice_the_median_is_cut_in_two():
    """Columns 2 and 3 wide among unit ones: only the column of area 3 (> 2 x median 1) is refined,
    not the one of area 2 (= 2 x median)."""
    v, f = rect_mesh([0, 1, 2, 3, 5, 8], range(5))
    area = _areas(v, f)
    big = np.flatnonzero(area > LARGE * np.median(area))
    assert len(big) == 4
    x, faces, parents, origin, refined = refine_large_faces(v, f)
    assert refined == 1
    pieces = np.bincount(origin, minlength=len(f))
    assert pieces[big].tolist() == [2] * 4 and (np.delete(pieces, big) == 1).all()
    new_area = _areas(x, faces)
    assert np.allclose(np.bincount(origin, weights=new_area), area)  # the pieces tile their quad
    assert np.allclose(new_area[np.isin(origin, big)], 1.5)
    # the cut runs between the midpoints of the long sides (the strip's rungs): squarer halves
    for k in np.flatnonzero(np.isin(origin, big)):
        assert _aspect(x, faces[k]) < _aspect(v, f[origin[k]])
    for k, p in enumerate(parents):
        assert np.allclose(x[len(v) + k], v[list(p)].mean(axis=0))
    assert len(x) == len(v) + 5  # the midpoints of the strip's five rungs
    assert all(len(q) == 4 for q in faces)
    _conforming(x, faces)


def test_a_strip_ending_at_a_triangle_puts_its_midpoint_in_the_triangle():
    v, f = rect_mesh([0, 1, 2, 3, 6], range(3))
    v = np.vstack([v, [4.5, 3.0, 0.0]])
    f = f + [(13, 14, 15)]  # on top of the wide column: its top rung is the triangle's side 13-14
    x, faces, parents, origin, refined = refine_large_faces(v, f)
    assert refined == 1
    (triangle,) = [q for q, o in zip(faces, origin) if o == len(f) - 1]
    assert len(triangle) == 4 and np.allclose(x[[p for p in triangle if p >= len(v)][0]], [4.5, 2.0, 0.0])
    _conforming(x, faces)
    assert _areas(x, faces).sum() == pytest.approx(_areas(v, f).sum())


def test_passes_repeat_until_no_quad_is_large():
    """A 3 x 3 corner quad among unit ones: its row and its column are refined, then again, until no
    quad is more than twice the median of the input."""
    v, f = rect_mesh([0, 1, 2, 3, 6], [0, 1, 2, 3, 6])
    median = np.median(_areas(v, f))
    x, faces, parents, origin, refined = refine_large_faces(v, f)
    area = _areas(x, faces)
    assert refined > 2 and area.max() <= LARGE * median
    assert area.sum() == pytest.approx(_areas(v, f).sum())
    assert np.allclose(np.bincount(origin, weights=area), _areas(v, f))
    _conforming(x, faces)
    # one pass is not enough
    x1, faces1, *_ = refine_large_faces(v, f, passes=1)
    assert _areas(x1, faces1).max() > LARGE * median


def test_faces_left_as_they_were_are_the_input_tuples():
    """Over two passes, a refined face that is its input face as it was is that very tuple (shared, not
    made again); every other one differs from its input face (cut, or given a midpoint)."""
    v, f = rect_mesh([0, 1, 2, 3, 6], [0, 1, 2, 3, 6])
    v = np.vstack([v, [[4.5, -1.0, 0.0]]])
    f = f + [(4, 3, 25)]  # a triangle below the large column: its strip ends there
    x, faces, parents, origin, refined = refine_large_faces(v, f)
    same = [faces[k] is f[o] for k, o in enumerate(origin.tolist())]
    assert refined > 2 and any(same) and not all(same)
    assert all(faces[k] != f[o] for k, o in enumerate(origin.tolist()) if not same[k])
    assert any(len(faces[k]) == 4 and o == len(f) - 1 for k, o in enumerate(origin.tolist()))  # the triangle's midpoint


def test_refined_points_of_a_curved_surface_are_means_of_network_vertices():
    v, f = rect_mesh([0, 1, 2, 3, 6], range(4))
    v[:, 2] = 0.1 * v[:, 0] ** 2 + 0.05 * v[:, 1]
    x, faces, parents, origin, refined = refine_large_faces(v, f)
    assert refined == 1 and len(parents) == len(x) - len(v)
    for k, p in enumerate(parents):
        assert len(p) in (2, 4) and np.allclose(x[len(v) + k], v[list(p)].mean(axis=0))
    _conforming(x, faces)


def _cut_of(n_faces, nodes):
    cut = np.zeros((n_faces, 2), dtype=bool)
    cut[nodes >> 1, nodes & 1] = True
    return cut


def _random_mesh(rng):
    """Random column widths and row heights, a random curved surface, and triangles on top of some
    columns (strips end at them)."""
    xs, ys = np.cumsum(rng.uniform(0.2, 3.0, 12)), np.cumsum(rng.uniform(0.2, 3.0, 9))
    v, f = rect_mesh(xs, ys)
    v[:, 2] = rng.normal(size=len(v)) * 0.3
    top = (len(ys) - 1) * len(xs)
    tips = [i for i in range(len(xs) - 1) if rng.random() < 0.3]
    v = np.vstack([v, [[0.5 * (xs[i] + xs[i + 1]), ys[-1] + 1.0, 0.0] for i in tips]])
    return v, f + [(top + i, top + i + 1, len(xs) * len(ys) + k) for k, i in enumerate(tips)]


@pytest.mark.parametrize("seed", range(4))
def test_areas_kept_through_a_pass_equal_every_face_measured_again(seed):
    """The areas a pass keeps for its unchanged faces and measures for the others are bit for bit the
    areas of the whole refined mesh (random widths and heights, a random curved surface)."""
    rng = np.random.default_rng(seed)
    v, f = rect_mesh(np.cumsum(rng.uniform(0.2, 3.0, 12)), np.cumsum(rng.uniform(0.2, 3.0, 9)))
    v[:, 2] = rng.normal(size=len(v)) * 0.3
    faces = Faces(f)
    area = surface_areas(v, faces)
    me = mesh_edges(faces, len(v))
    nodes, strips = _nodes_to_refine(v, me, np.flatnonzero(area > LARGE * np.median(area)))
    x, flat, sizes, _, origin, changed = _refined(v, me, _cut_of(len(faces), nodes))
    assert strips and changed.any() and not changed.all()
    assert np.array_equal(_areas_after(x, flat, sizes, area[origin], changed),
                          surface_areas(x, Faces.from_flat(flat, sizes)))


def _refined_quad_by_quad(x, faces, cut):
    """The cut made quad by quad, as the refinement once did: each cut quad (in face order) makes its
    centre if cut both ways, then the midpoints of its halved sides (a side's once), and is replaced
    by its pieces; the faces with a halved side then get its midpoint (:func:`with_midpoints`)."""
    points, parents, index, out, origin = [], [], {}, [], []

    def mid(a, b):
        if (min(a, b), max(a, b)) not in index:
            index[min(a, b), max(a, b)] = len(x) + len(points)
            points.append(0.5 * (x[a] + x[b]))
            parents.append((min(a, b), max(a, b)))
        return index[min(a, b), max(a, b)]

    for f, face in enumerate(faces):
        d = {k for k in (0, 1) if cut[f, k]}
        if not d:
            out.append(tuple(face))
            origin.append(f)
            continue
        a, b, c, e = face
        o = len(x) + len(points)
        if len(d) == 2:
            points.append(x[list(face)].mean(axis=0))
            parents.append(tuple(face))
        m = {k: mid(face[k], face[(k + 1) % 4]) for k in ((0, 2) if d == {0} else (1, 3) if d == {1} else range(4))}
        pieces = ([(a, m[0], m[2], e), (m[0], b, c, m[2])] if d == {0} else [(a, b, m[1], m[3]), (m[3], m[1], c, e)]
                  if d == {1} else [(a, m[0], o, m[3]), (m[0], b, m[1], o), (o, m[1], c, m[2]), (m[3], o, m[2], e)])
        out += pieces
        origin += [f] * len(pieces)
    touched = [any((min(p, q), max(p, q)) in index for p, q in zip(face, face[1:] + face[:1])) for face in faces]
    out = [with_midpoints(face, index) for face in out]
    return np.vstack([x, *points]), out, parents, np.array(origin), np.array(touched)[origin]


@pytest.mark.parametrize("seed", range(6))
def test_refined_all_at_once_equals_quad_by_quad(seed):
    """Cutting random strips of a random mesh (some ending at triangles) all at once gives, bit for bit,
    the vertices, faces, parents, origins and changed faces of the cut made quad by quad."""
    rng = np.random.default_rng(seed)
    v, f = _random_mesh(rng)
    faces = Faces(f)
    me = mesh_edges(faces, len(v))
    label = strip_labels(me)
    chosen = rng.choice(label.max() + 1, 6, replace=False)
    cut = _cut_of(len(faces), np.flatnonzero(np.isin(label, chosen) & (label >= 0)))
    x, flat, sizes, parents, origin, changed = _refined(v, me, cut)
    new_faces = Faces.from_flat(flat, sizes)
    rx, r_faces, r_parents, r_origin, r_changed = _refined_quad_by_quad(v, f, cut)
    assert cut.all(axis=1).any() and len(x) > len(v)
    assert np.array_equal(x, rx) and list(new_faces) == r_faces and parents == r_parents
    assert np.array_equal(origin, r_origin) and np.array_equal(changed, r_changed)
    _conforming(x, new_faces)


@pytest.mark.parametrize("seed", range(5))
def test_midpoints_inserted_at_once_equal_face_by_face(seed):
    """On random faces of 3-6 vertices and random cut sides (some midpoints already corners of a
    face, as in the cut quads' pieces), the faces :func:`with_midpoints` gives one by one."""
    rng = np.random.default_rng(seed)
    n = 40
    faces = [tuple(rng.choice(n, int(rng.integers(3, 7)), replace=False).tolist()) for _ in range(200)]
    sides = {tuple(sorted(p)) for p in rng.integers(0, n, (150, 2)).tolist() if p[0] != p[1]}
    index = {side: int(m) for side, m in zip(sorted(sides), rng.integers(0, n + 30, len(sides)))}
    expected = [with_midpoints(f, index) for f in faces]
    assert sum(len(e) for e in expected) > sum(len(f) for f in faces)
    face, u, v, _ = corner_arrays(faces)
    flat, lens = _midpoints_inserted(face, u, v, np.array(list(index)), np.array(list(index.values())), n + 30)
    assert list(Faces.from_flat(flat, lens)) == expected
