"""Max-min optimisation of the worst elements (vaultgram.meshing.optimise), the fan bound
(vaultgram.meshing.fans), and the quality floors they give on the shared plans and examples."""

from __future__ import annotations

import math

import numpy as np
import pytest

from vaultgram.domain import domain_from_dict
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.meshing.fans import fan_bounds
from vaultgram.meshing.optimise import OPTIMISE_TARGET, maximise_min_quality
from vaultgram.meshing.quadmesh import SlideConstraint
from vaultgram.meshing.quality import face_scaled_jacobians, mesh_stats
from vaultgram.pipeline import mesh_domain

#: Issue 12's floors at the default settings.
MIN_FLOOR, MEAN_FLOOR = 0.3, 0.9

# Plans below the min floor, with the reason; FAN: the fan bound proves no smoothing can reach it.
FAN = "a pole's fan of triangles: its fan bound (the best any placement can do) is below 0.3"
MIN_MISSES: dict = {}
# Inner point features keep their fans (vaultgram.meshing.splits.inner_point_feature: the tessellation
# follows their radial force flow); split, rv_lips reached 0.562, square_point_loads 0.337 and
# two_holes_five_points 0.228, but square_point_loads' joints turned 11.4 degrees from the force flow.
# fig5_boundary_points was bound by its fans (0.151) until thin fans became three quads.
MIN_PASS = ["armadillo_vault", "armadillo_vault_plan", "british_museum_map", "hiroshi_senju_museum",
            "mexico_airport", "rv_quad_pattern", "rv_ring_pattern",
            "rv_star_pattern", "l_shape", "quad_with_hole", "fig5_boundary_points",
            # since a patch corner on a bend of the outline slides (vaultgram.meshing.fidelity): a row
            # of skewed quads beside a bay (0.233) and beside the outline (0.224) before
            "multiple_lobes", "rolex_learning_centre",
            # since a plan without corners whose skeleton is one singularity is an O-grid (rules/topology.vgr):
            # 44 triangles in the 180 degrees of its centre pole before (0.085)
            "rv_pillow_pattern",
            # since the fans round a pole are evened (vaultgram.meshing.fans.even_fans): 10 to 32 degree
            # corners round its point features before (0.242)
            "fig6_inner_points",
            # since a point feature in a cusp keeps one quad (rules/patching.vgr: 7 triangles in 30 degrees
            # before, 0.047) and a pole of triangles only is evened when its own triangles get better
            # (vaultgram.meshing.fans.even_fans: the feature (7.09, 5.56), 0.251 before)
            "two_holes_five_points",
            # since the triangle wrapped under a curve's free end is split to its opposite side (rules/
            # curves.vgr: the fan at the end (5, 7.5), 0.25 above the branch round it, was 0.250)
            "features_combined",
            # since a refused pole that holds the worst face is evened regardless, and again after smoothing
            # (vaultgram.meshing.fans.poles_to_retry, vaultgram.meshpipeline._evened_again): the fan at the
            # curve end (1, 1) was 0.196
            "fig7_curves",
            # since a point load's fans get at most the triangles that can reach the floor in its patches'
            # angles (vaultgram.meshing.densities.point_load_caps), evened: 39 triangles round each load
            # (fan bound 0.185, 0.093) and 27 round rv_lips' (0.266, 0.239) before
            "square_point_loads", "rv_lips_pattern"]
# Since the mean-quality pass (vaultgram.meshing.orthogonalise), two_holes_five_points reaches the mean
# floor (0.891 -> 0.901); since its size term holds the jumps in size between neighbouring quads (not each
# quad's own area) and its angle term weighs each quad's worst corner, fig7_curves (0.876 -> 0.886 ->
# 0.9005) and square_point_loads (0.892 -> 0.8996 -> 0.914) reach it too; since the pass descends along
# conjugate directions, multiple_lobes (0.874 -> 0.902). mexico_airport's pass ended at 0.8915 however long
# it ran (its 232 faces at the 40 valence-6 and 2 valence-8 vertices between its 21 holes cannot have a
# corner over 60 / 45 degrees on average there) until a group with a side on a hole the target length
# cannot resolve took its count from its longest side (vaultgram.meshing.densities.group_length: 0.849 ->
# 0.877 before the pass, 0.904 after; benchmarks/README.md, session 22).
MEAN_MISSES: dict = {}
MEAN_PASS = [n for n in MIN_PASS + sorted(MIN_MISSES) if n not in MEAN_MISSES]
#: Shortest edge over median edge (issue 12 What 4, "well-shaped quads"; the scaled Jacobian does not see a
#: side vanish). Main b86dd39, before the optimiser's length factor: multiple_lobes 0.00002,
#: features_combined 0.00016, rolex_learning_centre 0.00065, fig7_curves 0.00072, square_point_loads 0.0045.
EDGE_FLOOR = 0.05
#: Plans under EDGE_FLOOR, with the floor they keep and why.
EDGE_MISSES = {
    # smoothing leaves 0.006 (the optimiser 0.009): rows of 1 m by 0.03 m quads into a 0.6 m stretch of
    # outline at (20.5, 18)
    "multiple_lobes": 0.005,
    # smoothing leaves 0.012 (the optimiser 0.023 / 0.012): the strips wrapped under the curve's free end
    # (5, 7.5), 0.5 above the hole, in a patch whose side there is 0.08 long
    "features_combined": 0.01, "fig7_curves": 0.01,
    # smoothing leaves 0.050, the optimiser 0.037: it narrows the strip of quads along x = 2.1 between
    # y = 5.5 and 6.05 to the SIDE_SHARE of its far side, which keeps the worst face at 0.500
    "rolex_learning_centre": 0.03,
}


@pytest.fixture(scope="module")
def default_mesh(cached_examples):
    """``default_mesh(name)``: the mesh of an example or shared plan at the default settings, with its
    statistics (cached)."""
    def make(domain):
        mesh = mesh_domain(domain, allow_folds=True)
        return mesh, mesh_stats(mesh, domain)

    return cached_examples(make)


def _dragged_grid():
    v, f = grid_mesh(3)
    fixed = np.zeros(len(v), bool)
    fixed[[0, 3, 12, 15]] = True  # the corners
    v[5, :2] = [1.9, 1.8]  # an inner vertex pushed onto its neighbour: folded faces
    v[10, :2] += [0.4, -0.3]
    return v, f, fixed


def test_optimising_unfolds_and_raises_the_worst_corner_to_the_target():
    v, f, fixed = _dragged_grid()
    x = maximise_min_quality(v, f, fixed)
    before, after = face_scaled_jacobians(v, f), face_scaled_jacobians(x, f)
    assert before.min() < 0 and after.min() >= OPTIMISE_TARGET
    assert np.array_equal(x[fixed], v[fixed])


def test_sliding_vertices_stay_on_their_polyline():
    v, f, fixed = _dragged_grid()
    bottom = np.array([1, 2])  # the bottom side between the corners 0 and 3
    v[1, :2] = [2.6, 0.0]  # pushed past its neighbour along the side: a folded face
    line = np.array([[0.0, 0.0], [3.0, 0.0]])
    x = maximise_min_quality(v, f, fixed, (SlideConstraint(bottom, line),))
    assert np.allclose(x[bottom, 1], 0.0) and (0 < x[bottom, 0]).all() and (x[bottom, 0] < 3).all()
    assert face_scaled_jacobians(x, f).min() >= OPTIMISE_TARGET


def test_the_worst_face_gets_better_on_a_jittered_grid():
    """Each move raises the moved vertex's worst corner and touches no corner of another moved
    vertex, so the mesh's worst face never gets worse."""
    v, f = grid_mesh(6)
    rng = np.random.default_rng(12)
    inner = (v[:, 0] % 6 != 0) & (v[:, 1] % 6 != 0)
    v[inner, :2] += rng.uniform(-0.45, 0.45, (int(inner.sum()), 2))
    before = face_scaled_jacobians(v, f)
    after = face_scaled_jacobians(maximise_min_quality(v, f, ~inner), f)
    assert after.min() > before.min() and after.min() >= min(OPTIMISE_TARGET, before.min())


def test_a_restart_from_moved_vertices_works_only_round_them():
    """Two dents in a 12 x 12 grid; told only vertex 14's was just made, the sweeps mend that one and
    leave the far one (vertex 128) for lack of a moved neighbour within MOVED_RINGS rings."""
    v, f = grid_mesh(12)
    inner = (v[:, 0] % 12 != 0) & (v[:, 1] % 12 != 0)
    v[14, :2] += [0.9, 0.8]
    v[128, :2] += [0.9, 0.8]
    x = maximise_min_quality(v, f, ~inner, moved=[14])
    far = np.hypot(*(v[:, :2] - v[128, :2]).T) < 2
    assert np.array_equal(x[far], v[far]) and not np.array_equal(x[14], v[14])
    assert face_scaled_jacobians(x, f)[[0, 12, 13]].min() > face_scaled_jacobians(v, f)[[0, 12, 13]].min()
    assert not np.array_equal(maximise_min_quality(v, f, ~inner)[far], v[far])  # a full run mends both


#: Saved random plan 48 (benchmarks/reliability.py's 700 plans, session 25), rounded: a triangular hole
#: whose corner (2.43, 0) is a 300 degree corner of the domain.
TRIANGLE_HOLE = {"outer": [[6.633, 1.875], [1.67, 6.589], [-5.179, 5.04], [-8.851, -2.502], [-2.25, -8.881],
                           [6.963, -6.775]],
                 "holes": [[[2.43, 0.0], [0.386, -1.18], [0.386, 1.18]]]}


def test_no_move_collapses_a_side(monkeypatch):
    """The scaled Jacobian sees directions, not lengths: without the length factor (SIDE_SHARE 0) the
    search slides the boundary vertex beside the hole's 300 degree corner into it (a side of 0.035% of
    the median edge: a quad that is a triangle) at no gain in the worst face; with it the side keeps
    7.6% and the worst face is the same."""
    import vaultgram.meshing.optimise as optimise

    domain = domain_from_dict(TRIANGLE_HOLE)
    stats = mesh_stats(mesh_domain(domain), domain)
    assert stats["shortest_over_median_edge"] > EDGE_FLOOR
    monkeypatch.setattr(optimise, "SIDE_SHARE", 0.0)
    collapsed = mesh_stats(mesh_domain(domain), domain)
    assert collapsed["shortest_over_median_edge"] < 0.001
    assert stats["min_scaled_jacobian"] >= collapsed["min_scaled_jacobian"] - 1e-6 > 0.5


def test_a_good_mesh_is_left_alone():
    v, f = grid_mesh(3)
    assert np.array_equal(maximise_min_quality(v, f), v)


def test_fan_bound_of_a_boundary_fan_and_a_regular_grid():
    """Six triangles in a right angle: each at most 15 degrees; a grid's vertices are unlimited."""
    a = np.linspace(0, math.pi / 2, 7)
    v = np.vstack([[0.0, 0.0], np.column_stack([np.cos(a), np.sin(a)])])
    f = [(0, 1 + k, 2 + k) for k in range(6)]
    assert fan_bounds(v, f)[0] == pytest.approx(math.sin(math.pi / 12) * 2 / math.sqrt(3), abs=1e-9)
    g, gf = grid_mesh(2)
    assert np.allclose(fan_bounds(g, gf), 1.0)


def test_fan_bound_bounds_the_real_mesh(default_mesh):
    """No corner of a vertex is better than its fan bound allows: the worst corner at each vertex is
    at most the bound (the bound is an upper bound, attained by equal corners)."""
    mesh, _ = default_mesh("fig6_inner_points")
    bound = fan_bounds(mesh.vertices, mesh.faces)
    sj = face_scaled_jacobians(mesh.vertices, mesh.faces)
    pole = int(np.argmin(bound))
    assert mesh.pole[pole]
    assert min(sj[k] for k, face in enumerate(mesh.faces) if pole in face) <= bound[pole] + 1e-9


@pytest.mark.parametrize("name", MIN_PASS + sorted(MIN_MISSES))
def test_min_scaled_jacobian_floor(default_mesh, name):
    """Issue 12: min scaled Jacobian at least 0.3 and no fold, at the default settings; where a plan
    misses, the listed reason (for a fan: its bound is below the floor, so the miss is not smoothing's)
    and a strict xfail."""
    mesh, stats = default_mesh(name)
    assert stats["inverted_faces"] == 0
    if name in MIN_MISSES:
        if MIN_MISSES[name].startswith(FAN):
            assert fan_bounds(mesh.vertices, mesh.faces).min() < MIN_FLOOR
        if stats["min_scaled_jacobian"] < MIN_FLOOR:
            pytest.xfail(MIN_MISSES[name])
        pytest.fail(f"{name} now reaches the floor: move it to MIN_PASS")
    assert stats["min_scaled_jacobian"] >= MIN_FLOOR


@pytest.mark.parametrize("name", MEAN_PASS + sorted(MEAN_MISSES))
def test_mean_scaled_jacobian_floor(default_mesh, name):
    """Issue 12: mean scaled Jacobian at least 0.9 at the default settings (strict xfail where not)."""
    _, stats = default_mesh(name)
    if name in MEAN_MISSES:
        if stats["mean_scaled_jacobian"] < MEAN_FLOOR:
            pytest.xfail(MEAN_MISSES[name])
        pytest.fail(f"{name} now reaches the mean floor: move it to MEAN_PASS")
    assert stats["mean_scaled_jacobian"] >= MEAN_FLOOR


@pytest.mark.parametrize("name", MIN_PASS + sorted(MIN_MISSES))
def test_shortest_edge_floor(default_mesh, name):
    """No side all but vanished (a quad that is a triangle scores well on the scaled Jacobian): the
    shortest edge at least EDGE_FLOOR of the median edge, or the listed plan's own floor, which its
    smoothing or its strips leave (and the optimiser then kept)."""
    _, stats = default_mesh(name)
    assert stats["shortest_over_median_edge"] >= EDGE_MISSES.get(name, EDGE_FLOOR)
    if name in EDGE_MISSES:
        assert stats["shortest_over_median_edge"] < EDGE_FLOOR, f"{name} now reaches EDGE_FLOOR: unlist it"
