"""The mean-quality pass (vaultgram.meshing.orthogonalise; issue 12, What 4: mean scaled Jacobian
at least 0.9): it raises the mean, keeps every face at least as good as its floor (so the worst face
and every orientation), moves no held vertex and keeps the boundary on the plan."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings

from vaultgram import meshpipeline
from vaultgram.domain import domain_from_dict
from vaultgram.geometry.fidelity import boundary_distance
from vaultgram.geometry.meshes import corner_arrays, face_areas, grid_mesh
from vaultgram.geometry.polylines import project_to_polyline
from vaultgram.meshing import orthogonalise as ortho
from vaultgram.meshing.orthogonalise import MEAN_AIM, MEAN_FLOOR, MEAN_MAX_FACES, MEAN_TARGET, orthogonalise
from vaultgram.meshing.quadmesh import SlideConstraint
from vaultgram.meshing.quality import face_scaled_jacobians
from vaultgram.pipeline import mesh_domain

from strategies.meshes import perturbed_grids


def _wavy_strip(points=()) -> dict:
    """A strip 12 long and 4 wide whose long sides follow one sine wave (amplitude 1): long curved
    patches whose Coons maps shear their quads along the waves (a mean scaled Jacobian of 0.874)."""
    t = np.linspace(0.0, 12.0, 49)
    top, bottom = np.column_stack([t, 4 + np.sin(t)]), np.column_stack([t, np.sin(t)])
    return {"name": "wavy", "outer": np.vstack([bottom, top[::-1]]).tolist(), "points": list(points)}


@pytest.fixture(scope="module")
def unsquared():
    """``unsquared(plan)``: the domain of a plan and its mesh from the pipeline without the pass."""
    def make(plan):
        domain = domain_from_dict(plan)
        kept, meshpipeline.orthogonalise = meshpipeline.orthogonalise, lambda x, *a, **k: x
        try:
            return domain, mesh_domain(domain)
        finally:
            meshpipeline.orthogonalise = kept

    return make


def test_a_sheared_grid_becomes_square(monkeypatch):
    """A 4 x 4 grid whose inner vertices are sheared (x + 0.6 (y - 2)) inside its fixed square outline,
    the descent run on past the issue's mean (aim 1): the mean rises (0.857 -> 1.000 when written;
    0.901 while each quad's own area was held: the shear made them unequal), the worst face does not
    fall, the outline does not move."""
    monkeypatch.setattr(ortho, "MEAN_AIM", 1.0)
    v, f = grid_mesh(4)
    inner = (v[:, 0] % 4 != 0) & (v[:, 1] % 4 != 0)
    v[inner, 0] += 0.6 * (v[inner, 1] - 2)
    before = face_scaled_jacobians(v, f)
    x = orthogonalise(v, f, fixed=~inner)
    after = face_scaled_jacobians(x, f)
    assert before.mean() < 0.86 < 0.99 < after.mean()
    assert after.min() >= before.min()
    assert np.array_equal(x[~inner], v[~inner])


@settings(max_examples=25, deadline=None)
@given(perturbed_grids())
def test_no_face_falls_below_its_floor_and_the_sliding_side_stays_straight(grid):
    """Random valid perturbed grids, the bottom side sliding on its line: no face ends below the
    smaller of its scaled Jacobian and the floor (the worst face kept, nothing inverted), the sum the
    pass descends does not rise, held vertices stay and sliding ones stay on y = 0."""
    v, f = grid
    n = int(round(v[:, 0].max()))
    before = face_scaled_jacobians(v, f)
    if before.min() <= 0:
        return  # untangling comes first: the pass returns such meshes as they are
    bottom = np.flatnonzero((v[:, 1] == 0) & (v[:, 0] > 0) & (v[:, 0] < n))
    held = ((v[:, 0] % n == 0) | (v[:, 1] % n == 0)) & ~np.isin(np.arange(len(v)), bottom)
    slide = [SlideConstraint(bottom, np.array([[0.0, 0.0], [n, 0.0]]))]
    x = orthogonalise(v, f, held, slide)
    after = face_scaled_jacobians(x, f)
    assert (after >= np.minimum(before, max(MEAN_FLOOR, before.min())) - 1e-12).all()
    region = ortho._region(v, f, held, slide, None)
    if region is not None:  # None: nothing to move, the grid comes back as it is
        def total(y):
            return ortho._state(len(y), region, ortho._geometry(y, region)).total

        assert total(x) <= total(v) + 1e-9
    assert np.array_equal(x[held], v[held])
    assert np.allclose(x[bottom, 1], 0.0)


def test_a_curved_plan_gains_mean_and_keeps_its_boundary(unsquared):
    """The wavy strip meshed without the pass, then passed: the mean scaled Jacobian reaches the
    issue's floor (0.874 -> 0.902 when written; 0.893 down the scaled gradient alone, 0.885 while each
    quad's own area was held), the worst face does not fall, the fixed vertices stay, the sliding
    ones stay on their polylines and the boundary is no farther from the plan."""
    domain, mesh = unsquared(_wavy_strip())
    x = orthogonalise(mesh.vertices, mesh.faces, mesh.fixed, mesh.constraints, still=mesh.feature)
    before, after = face_scaled_jacobians(mesh.vertices, mesh.faces), face_scaled_jacobians(x, mesh.faces)
    assert before.mean() < 0.88 and after.mean() >= MEAN_TARGET
    assert after.min() >= before.min()
    assert np.array_equal(x[mesh.fixed], mesh.vertices[mesh.fixed])
    for c in mesh.constraints:
        on = project_to_polyline(x[c.vertices, :2], np.asarray(c.polyline)[:, :2], c.closed)
        assert np.allclose(on, x[c.vertices, :2], atol=1e-9 * domain.diagonal)
    assert (boundary_distance(x, mesh.faces, domain.rings)
            <= boundary_distance(mesh.vertices, mesh.faces, domain.rings) + 1e-12)


def test_fans_and_the_rings_of_point_features_stay(unsquared):
    """A point feature in the wavy strip: its fan of triangles and the faces round it (the point
    loads' force flow into the tessellation) keep their vertices; the pass still raises the mean."""
    _, mesh = unsquared(_wavy_strip(points=[[6.0, 2.0]]))
    x = orthogonalise(mesh.vertices, mesh.faces, mesh.fixed, mesh.constraints, still=mesh.feature)
    face, u, _, _ = corner_arrays(mesh.faces)
    sizes = np.bincount(face)
    near = np.zeros(len(mesh.faces), dtype=bool)
    near[face[mesh.feature[u]]] = True
    kept = np.unique(u[(sizes[face] == 3) | near[face]])
    assert len(kept) > 1
    assert np.array_equal(x[kept], mesh.vertices[kept])
    assert face_scaled_jacobians(x, mesh.faces).mean() > face_scaled_jacobians(mesh.vertices, mesh.faces).mean()


def test_good_folded_and_fine_meshes_are_left_alone():
    """A square grid (its mean above the issue's floor), a folded one (untangling comes first) and a
    sheared grid of more than MEAN_MAX_FACES faces (the steps shrink with the edges: little gain for
    the time) come back as they are, while the same shear on a coarse grid is worked on."""
    v, f = grid_mesh(3)
    assert np.array_equal(orthogonalise(v, f), v)
    v[5, :2] = [3.5, 3.5]
    assert np.array_equal(orthogonalise(v, f), v)
    for n in (8, int(np.sqrt(MEAN_MAX_FACES)) + 1):
        v, f = grid_mesh(n)
        inner = (v[:, 0] % n != 0) & (v[:, 1] % n != 0)
        v[inner, 0] += 0.6 * (v[inner, 1] % 2 - 0.5)  # rows zigzag: parallelograms of 0.857
        assert face_scaled_jacobians(v, f).mean() < MEAN_TARGET
        assert np.array_equal(orthogonalise(v, f, ~inner), v) == (len(f) > MEAN_MAX_FACES)


def _graded_wave(n: int = 8) -> tuple[np.ndarray, list, np.ndarray]:
    """An n x n grid whose columns widen by 1.25 from left to right (sizes graded 1 to 4.8) and whose
    inner vertices follow a sine wave across (amplitude 0.7): a mean scaled Jacobian of 0.873; its
    inner vertices."""
    v, f = grid_mesh(n)
    columns = np.cumsum(np.r_[0.0, 1.25 ** np.arange(n)])
    v[:, 0] = columns[np.round(v[:, 0]).astype(int)] * n / columns[-1]
    inner = (v[:, 0] > 0) & (v[:, 0] < n - 1e-9) & (v[:, 1] % n != 0)
    v[inner, 1] += 0.7 * np.sin(1.3 * v[inner, 0])
    return v, f, inner


def _size_jumps(x: np.ndarray, faces) -> np.ndarray:
    """Per side shared by two quads, |log| of the ratio of their areas (in the order of
    :func:`~vaultgram.meshing.orthogonalise._side_pairs`)."""
    face, u, v, _ = corner_arrays(faces)
    pairs = ortho._side_pairs(u, v, face, np.ones(len(u), dtype=bool), len(x))
    area = face_areas(x[:, :2], faces)
    return np.abs(np.log(area[pairs[:, 0]] / area[pairs[:, 1]]))


def test_sizes_may_even_out_and_grade_but_not_jump(monkeypatch):
    """The graded, waved grid, the descent run on past the issue's mean (aim 1): the pass squares it
    (mean 0.873 -> 0.999 when written) and the jumps in size between neighbouring quads even out (the
    largest, in log area, 1.03 -> 0.32) but none grows by more than 0.1 (0.076); without the size term
    one grows by 0.19 (the voussoirs would follow; 0.54 where the descent went down the scaled
    gradient alone and stopped far from the square grid)."""
    monkeypatch.setattr(ortho, "MEAN_AIM", 1.0)
    v, f, inner = _graded_wave()
    before, jumps = face_scaled_jacobians(v, f), _size_jumps(v, f)
    x = orthogonalise(v, f, ~inner)
    after = face_scaled_jacobians(x, f)
    assert before.mean() < 0.89 and after.mean() > 0.99 and after.min() >= before.min()
    assert (_size_jumps(x, f) - jumps).max() < 0.1 and _size_jumps(x, f).max() < 0.5 * jumps.max()
    monkeypatch.setattr(ortho, "GRADE_WEIGHT", 0.0)
    assert (_size_jumps(orthogonalise(v, f, ~inner), f) - jumps).max() > 0.15


def test_the_descent_stops_at_the_aim(monkeypatch):
    """The sheared 4 x 4 grid at the default aim: the mean passes the aim and stops short of the
    square grid the descent reaches when run on (0.909 against 1.000 when written): beyond the issue's
    mean the angles gain only what the evenness of the voussoirs' sizes pays for."""
    v, f = grid_mesh(4)
    inner = (v[:, 0] % 4 != 0) & (v[:, 1] % 4 != 0)
    v[inner, 0] += 0.6 * (v[inner, 1] - 2)
    stopped = face_scaled_jacobians(orthogonalise(v, f, fixed=~inner), f).mean()
    monkeypatch.setattr(ortho, "MEAN_AIM", 1.0)
    assert ortho.MEAN_TARGET < MEAN_AIM <= stopped < face_scaled_jacobians(orthogonalise(v, f, ~inner), f).mean() - 0.05


def test_conjugate_directions_bend_the_rows_of_a_long_patch_sooner(unsquared, monkeypatch):
    """The wavy strip (long curved patches, as multiple_lobes'), the descent run on (aim 1) for 60
    steps: along the conjugate directions the mean reaches 0.904 when written, down the scaled gradient
    alone (every direction a restart) 0.888; the sum falls further too."""
    _, mesh = unsquared(_wavy_strip())
    monkeypatch.setattr(ortho, "MEAN_AIM", 1.0)

    def passed():
        x = orthogonalise(mesh.vertices, mesh.faces, mesh.fixed, mesh.constraints, still=mesh.feature, steps=60)
        region = ortho._region(mesh.vertices, mesh.faces, mesh.fixed, mesh.constraints, mesh.feature)
        total = ortho._state(len(x), region, ortho._geometry(x, region)).total
        return face_scaled_jacobians(x, mesh.faces).mean(), total

    conjugate = passed()
    monkeypatch.setattr(ortho, "_direction", lambda grad, down, *_: down)
    steepest = passed()
    assert conjugate[0] > MEAN_TARGET > steepest[0] and conjugate[1] < steepest[1]


def test_the_descent_follows_the_derivative_of_its_sum():
    """The gradient the descent steps along is the derivative of its sum (angle term at the soft worst
    corners and size term), by central differences on a randomly moved graded grid."""
    v, f, inner = _graded_wave(5)
    region = ortho._region(v, f, ~inner, (), None)
    x = v.copy()
    x[inner, :2] += np.random.default_rng(0).uniform(-0.1, 0.1, (int(inner.sum()), 2))
    grad = ortho._state(len(x), region, ortho._geometry(x, region)).grad
    h, diff = 1e-6, np.zeros_like(grad)
    for i in np.flatnonzero(inner):
        for k in range(2):
            y, z = x.copy(), x.copy()
            y[i, k] += h
            z[i, k] -= h
            diff[i, k] = (ortho._state(len(x), region, ortho._geometry(y, region)).total
                          - ortho._state(len(x), region, ortho._geometry(z, region)).total) / (2 * h)
    assert np.abs(diff - grad)[inner].max() < 1e-6 * np.abs(grad[inner]).max()
    assert ortho._size_term(region, ortho._geometry(x, region).area)[0] > 0  # both terms in the test
