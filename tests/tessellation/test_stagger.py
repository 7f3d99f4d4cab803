"""The staggered bond (paper §5, Figure 11a): courses along the free edges, joints cut by dynamic
programming, consecutive courses' joints staggered."""

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.geometry.arrays import row_dot, steady, unit_rows
from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.geometry.surfaces import area_vectors
from vaultgram.pipeline import tessellate
from vaultgram.tessellation.metrics import force_angles, inner_vertices
from vaultgram.tessellation.stagger import (
    ALIGNED_COST,
    AMBIGUITY,
    SINGLE_COST,
    SKEW_COST,
    SMOOTHING,
    _rung_skews,
    cheapest_cut,
    course_joints,
    course_runs,
    preferential_directions,
    quad_directions,
    size_costs,
    staggered_bond,
)
from vaultgram.tessellation.strips import quad_strips
from vaultgram.tessellation.voussoirs import face_groups, voussoirs_at_vertices


def _pattern(keep) -> str:
    return "".join("|" if k else "." for k in keep)


def _plan_directions(x, me, edges):
    d = x[me.edges[edges, 1], :2] - x[me.edges[edges, 0], :2]
    return d / np.linalg.norm(d, axis=1)[:, None]


def _areas(surface):
    return np.linalg.norm(area_vectors(surface.vertices, surface.faces), axis=1)


def _inner(surface):
    """Vertices off the surface's boundary."""
    inner = np.ones(len(surface.vertices), dtype=bool)
    inner[surface.edges.edges[surface.edges.boundary].ravel()] = False
    return inner


def _courses(surface):
    x, me = surface.vertices, surface.edges
    pref = preferential_directions(x, me, surface.supported)
    is_quad = np.diff(me.face_start) == 4
    return course_runs(me, quad_strips(me, surface.faces), quad_directions(x, me, pref, is_quad))


# ---------------------------------------------------------------------------------------------
# Joints along one course
# ---------------------------------------------------------------------------------------------


def _none(k):
    return np.zeros(k, dtype=bool)


@pytest.mark.parametrize("areas, target, longest, expected", [
    (np.ones(6), 2.0, 4, "|.|.|.|"),  # rhythm 2 on equal quads: every second rung
    (np.ones(8), 4.0, 8, "|...|...|"),  # rhythm 4: every fourth
    (np.full(8, 0.5), 2.0, 4, "|...|...|"),  # small quads make longer voussoirs of the target area
    (np.array([0.5, 0.5, 0.5, 0.5, 1.0, 1.0]), 2.0, 4, "|...|.|"),  # sizes follow the faces
])
def test_a_course_is_cut_into_voussoirs_of_the_target_area(areas, target, longest, expected):
    k = len(areas)
    assert _pattern(course_joints(areas, _none(k + 1), _none(k + 1), target, longest)) == expected


def test_a_rung_in_line_with_a_neighbours_joint_is_avoided():
    aligned = _none(7)
    aligned[[2, 4]] = True
    keep = course_joints(np.ones(6), _none(7), aligned, 2.0, 4)
    assert _pattern(keep) == "|..|..|"
    assert not (keep & aligned).any()


def test_a_forced_rung_is_kept_and_never_passed():
    forced = _none(7)
    forced[1] = True
    keep = course_joints(np.ones(6), forced, _none(7), 2.0, 4)
    assert keep[1] and keep[0] and keep[-1]
    assert np.diff(np.flatnonzero(keep)).max() <= 3


def _cost(areas, forced, aligned, target, keep, skew) -> float:
    """The cost the bond minimises (stagger module docstring): ``log(area / target) ** 2`` per voussoir,
    SINGLE_COST per one-quad voussoir not held alone by forced rungs, ALIGNED_COST per kept inner
    rung in line with a neighbour's joint, SKEW_COST x (skew - the inner rungs' mean) / 90 per kept
    inner rung."""
    kept = np.flatnonzero(keep)
    total = 0.0
    for a, b in zip(kept[:-1], kept[1:]):
        total += math.log(areas[a:b].sum() / target) ** 2
        if b - a == 1 and not (forced[a] and forced[b]):
            total += SINGLE_COST
    inner = kept[(kept > 0) & (kept < len(areas))]
    relative = skew - (skew[1:len(areas)].mean() if len(areas) > 1 else 0.0)
    return total + ALIGNED_COST * aligned[inner].sum() + SKEW_COST * relative[inner].sum() / 90.0


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.integers(1, 8).flatmap(lambda k: st.tuples(
    st.lists(st.floats(0.3, 3.0), min_size=k, max_size=k),
    st.lists(st.booleans(), min_size=k + 1, max_size=k + 1),
    st.lists(st.booleans(), min_size=k + 1, max_size=k + 1),
    st.lists(st.floats(0.0, 90.0), min_size=k + 1, max_size=k + 1))),
    st.sampled_from([(2.0, 4), (4.0, 8), (1.5, 3)]))
def test_the_cut_of_a_course_is_the_cheapest(course, target_longest):
    """Against every admissible cut (ends and forced rungs kept, runs of at most ``longest`` quads)."""
    areas, forced, aligned, skew = (np.array(v) for v in course)
    target, longest = target_longest
    k = len(areas)
    forced[[0, -1]] = True
    keep = course_joints(areas, forced, aligned, target, longest, skew)
    assert keep[forced].all()
    assert np.diff(np.flatnonzero(keep)).max() <= longest
    best = math.inf
    for inner in itertools.product([False, True], repeat=k - 1):
        candidate = np.array([True, *inner, True])
        if candidate[forced].all() and np.diff(np.flatnonzero(candidate)).max() <= longest:
            best = min(best, _cost(areas, forced, aligned, target, candidate, skew))
    assert _cost(areas, forced, aligned, target, keep, skew) == pytest.approx(best, abs=1e-9)


def _cut_by_slices(sizes, forced, penalty, longest):
    """The programme as the bond first ran it (each rung's choices as a reversed slice of the best
    costs joined to the single quad's): the reference of the windowed :func:`cheapest_cut`."""
    k = len(forced) - 1
    forced = forced.tolist()
    best, back, last = [0.0] * (k + 1), [0] * (k + 1), 0
    for b in range(1, k + 1):
        if forced[b - 1]:
            last = b - 1
        d, row = min(longest, b - last), sizes[b]
        single = row[1] if forced[b - 1] and forced[b] else row[1] + SINGLE_COST
        cost = [best[b - 1] + single] + [x + y for x, y in zip(best[b - d:b - 1][::-1], row[2:d + 1])]
        here = min(cost)
        back[b] = b - 1 - cost.index(here)
        best[b] = here + penalty[b] if b < k else here
    keep, b = np.zeros(k + 1, dtype=bool), k
    while b > 0:
        keep[b], b = True, back[b]
    keep[0] = True
    return keep


@pytest.mark.parametrize("seed", range(4))
def test_the_windowed_programme_keeps_the_rungs_the_sliced_one_kept(seed):
    """On 300 random courses of up to 400 quads (equal areas with their ties, forced rungs from none
    to half, penalties in line and skewed), exactly the rungs of the reference programme."""
    rng = np.random.default_rng(seed)
    for _ in range(300):
        k = int(rng.integers(1, 400))
        areas = rng.uniform(0.5, 1.5, k) if rng.random() < 0.7 else np.ones(k)
        forced = rng.random(k + 1) < rng.choice([0.0, 0.01, 0.1, 0.5])
        forced[[0, -1]] = True
        penalty = (ALIGNED_COST * (rng.random(k + 1) < 0.2) + rng.normal(0, 0.1, k + 1) * (rng.random() < 0.5))
        longest = int(rng.choice([4, 8]))
        sizes = size_costs(areas, longest / 2.0, longest)
        keep = cheapest_cut(sizes, forced, penalty.tolist(), longest)
        assert np.array_equal(keep, _cut_by_slices(sizes, forced, penalty.tolist(), longest))
        assert keep[forced].all() and np.diff(np.flatnonzero(keep)).max() <= longest


def test_a_rung_along_the_force_flow_is_not_kept_when_another_cut_costs_little_more():
    """Six even quads, target two: the bond cuts 2 + 2 + 2; with rung 2 along the flow (skew 90 deg,
    cost SKEW_COST) it cuts 3 + 3 at rung 3 instead (size cost 2 log(1.5)^2 = 0.33)."""
    none = _none(7)
    assert course_joints(np.ones(6), none, none, 2.0, 4).astype(int).tolist() == [1, 0, 1, 0, 1, 0, 1]
    skew = np.array([0.0, 0.0, 90.0, 0.0, 0.0, 0.0, 0.0])
    assert course_joints(np.ones(6), none, none, 2.0, 4, skew).astype(int).tolist() == [1, 0, 0, 1, 0, 0, 1]


# ---------------------------------------------------------------------------------------------
# Directions and courses
# ---------------------------------------------------------------------------------------------


def _directions_by_all_corners(x, me, pref, is_quad):
    """:func:`quad_directions` as it first ran: every quad corner votes in every round, the ambiguous
    quads follow the majority (the reference of the version where only the ambiguous quads' corners
    vote)."""
    d = x[me.edges[:, 1], :2] - x[me.edges[:, 0], :2]
    align = np.abs(row_dot(unit_rows(d), pref))
    quad_corner = is_quad[me.corner_face]
    c = np.flatnonzero(quad_corner)
    f, side, n = me.corner_face[c], me.corner_side[c], len(is_quad)
    score = np.bincount(2 * f + side % 2, align[me.corner_edge[c]], 2 * n).reshape(n, 2)
    choice = np.where(is_quad, np.argmax(steady(score), axis=1), -1)
    ambiguous = is_quad & (np.abs(score[:, 0] - score[:, 1]) < 2 * AMBIGUITY)
    twin = me.corner_twin[c]
    ok = (twin >= 0) & quad_corner[np.maximum(twin, 0)]
    f, side, twin = f[ok], side[ok], twin[ok]
    g, other_side = me.corner_face[twin], me.corner_side[twin]
    for _ in range(SMOOTHING):
        seen = np.where(choice[g] == other_side % 2, side % 2, 1 - side % 2)
        votes = np.bincount(2 * f + seen, minlength=2 * n).reshape(n, 2)
        flip = ambiguous & (votes.max(axis=1) > votes.min(axis=1))
        choice = np.where(flip, np.argmax(votes, axis=1), choice)
    return choice


@pytest.mark.parametrize("seed", range(6))
def test_quad_directions_equal_every_corner_voting(seed):
    """On jittered grids with random preferential directions near the diagonal (many ambiguous quads)
    and some faces not quads, the same course directions as the reference where every corner votes."""
    rng = np.random.default_rng(seed)
    v, f = grid_mesh(int(rng.integers(5, 30)), int(rng.integers(5, 30)))
    v[:, :2] += rng.uniform(-0.3, 0.3, (len(v), 2))
    me = mesh_edges(f, len(v))
    angle = np.pi / 4 + rng.normal(0, 0.3, me.n_edges)
    pref = np.column_stack([np.cos(angle), np.sin(angle)])
    is_quad = rng.random(len(f)) < 0.9
    expected = _directions_by_all_corners(v, me, pref, is_quad)
    assert np.array_equal(quad_directions(v, me, pref, is_quad), expected)


def test_the_preferential_direction_is_the_free_edge(arch_grid):
    """Only the arch along y = 12 is free: every edge takes its direction (x, give or take its sag)."""
    pref = preferential_directions(arch_grid.vertices, arch_grid.edges, arch_grid.supported)
    assert np.allclose(np.linalg.norm(pref, axis=1), 1.0)
    assert np.abs(pref[:, 0]).min() > 0.9


def test_with_every_boundary_supported_the_closest_boundary_is_the_direction(dome_grid):
    x, me = dome_grid.vertices, dome_grid.edges
    pref = preferential_directions(x, me, dome_grid.supported)
    mid = 0.5 * (x[me.edges[:, 0], :2] + x[me.edges[:, 1], :2])
    near_left = (mid[:, 0] < 1.0) & (mid[:, 1] > 2.0) & (mid[:, 1] < 8.0)
    near_bottom = (mid[:, 1] < 1.0) & (mid[:, 0] > 2.0) & (mid[:, 0] < 8.0)
    assert np.allclose(np.abs(pref[near_left]), [0.0, 1.0])
    assert np.allclose(np.abs(pref[near_bottom]), [1.0, 0.0])


def test_a_keystone_ring_edge_is_its_own_preferential_direction(dome_grid):
    x, me = dome_grid.vertices, dome_grid.edges
    ring = int(np.flatnonzero(~me.boundary)[len(me.edges) // 2])
    pref = preferential_directions(x, me, dome_grid.supported, rings=[ring])
    assert np.allclose(np.abs(pref[ring]), np.abs(_plan_directions(x, me, [ring])[0]))


def test_on_an_arch_every_quad_lies_on_one_course_whose_rungs_follow_the_free_edge(arch_grid):
    courses = _courses(arch_grid)
    quads = np.concatenate([c.quads for c in courses])
    is_quad = np.diff(arch_grid.edges.face_start) == 4
    assert sorted(quads.tolist()) == np.flatnonzero(is_quad).tolist()
    for c in courses:
        assert np.abs(_plan_directions(arch_grid.vertices, arch_grid.edges, c.rungs)[:, 0]).min() > 0.9
    assert len(courses) == 12  # the columns of the 12 x 12 grid


# ---------------------------------------------------------------------------------------------
# The bond
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("rhythm", [2, 4])
def test_on_an_arch_consecutive_courses_stagger_their_joints(arch_grid, rhythm):
    x, me = arch_grid.vertices, arch_grid.edges
    bond = staggered_bond(x, me, quad_strips(me, arch_grid.faces), arch_grid.supported, _areas(arch_grid), rhythm)
    assert bond.aligned == 0 and bond.kept_taken == 0
    courses = _courses(arch_grid)
    kept_at = np.zeros(len(x), dtype=int)  # kept inner rungs (joints across a course) at each vertex
    for c in courses:
        keep = ~bond.removed[c.rungs]
        assert keep[0] and keep[-1]
        gaps = np.diff(np.flatnonzero(keep))
        # every rhythm-th rung inside a course; the runs at its ends take the odd quad
        if rhythm == 2:
            assert (gaps[1:-1] == 2).all() and gaps.max() <= 3
        else:
            assert (np.abs(gaps - 4) <= 1).all()
        np.add.at(kept_at, me.edges[c.rungs[1:-1][keep[1:-1]]].ravel(), 1)
    # joints never line up across two courses: at most one kept rung at any vertex
    assert kept_at.max() == 1
    count = voussoirs_at_vertices(me, face_groups(me, bond.removed), len(x))
    assert count[_inner(arch_grid)].max() == 3


def test_rhythm_four_makes_voussoirs_of_about_four_quads(arch_grid):
    x, me = arch_grid.vertices, arch_grid.edges
    areas = _areas(arch_grid)
    sizes = {}
    for rhythm in (2, 4):
        bond = staggered_bond(x, me, quad_strips(me, arch_grid.faces), arch_grid.supported, areas, rhythm)
        assert bond.target == pytest.approx(rhythm * np.median(areas[np.diff(me.face_start) == 4]))
        sizes[rhythm] = np.bincount(face_groups(me, bond.removed))
    assert np.median(sizes[2]) == 2 and np.median(sizes[4]) == 4
    assert sizes[4].max() <= 8  # LONGEST x rhythm


def test_faces_joined_before_the_bond_are_no_course_s(arch_grid):
    """A pair joined beforehand (a pinwheel round a keystone) stays one voussoir of two faces: the
    courses through it keep their rungs around it."""
    x, me = arch_grid.vertices, arch_grid.edges
    mid = 0.5 * (x[me.edges[:, 0], :2] + x[me.edges[:, 1], :2])
    e = int(np.argmin(np.linalg.norm(mid - [6.0, 5.5], axis=1)))  # the vertical edge x = 6, y in [5, 6]
    joined = np.zeros(me.n_edges, dtype=bool)
    joined[e] = True
    bond = staggered_bond(x, me, quad_strips(me, arch_grid.faces), arch_grid.supported, _areas(arch_grid),
                          joined=joined)
    assert bond.removed[e]
    group = face_groups(me, bond.removed)
    pair = group[me.faces_of[e]]
    assert pair[0] == pair[1] and (group == pair[0]).sum() == 2


def test_a_dome_has_almost_only_points_of_three_voussoirs(dome_grid):
    """Supported all round, the courses ring the dome and meet at its diagonals, where a joint may line
    up (measured: one point of four among 67)."""
    t = tessellate(dome_grid, thickness=0.3)
    meet = t.summary["meeting_points"]
    assert set(meet) <= {"3", "4"} and meet.get("4", 0) <= 1
    assert t.summary["edges_kept"]["aligned"] <= 1
    count = voussoirs_at_vertices(t.layout.edges, t.layout.group, len(t.vertices))
    assert count[inner_vertices(t.layout, len(t.vertices))].min() >= 2


def test_rung_skews_are_the_force_angles_of_the_courses_inner_rungs(arch_grid):
    """Measured at the inner rungs of the courses only, the angles to the force flow are those of all the
    inner edges measured at once, bit for bit; the other edges (boundary, not a course's rung) have 0."""
    x, me = arch_grid.vertices, arch_grid.edges
    normals = unit_rows(area_vectors(x, arch_grid.faces))
    courses = _courses(arch_grid)
    skew = _rung_skews(x, me, courses, normals)
    inside = np.flatnonzero(~me.boundary)
    every = np.zeros(me.n_edges)
    every[inside] = force_angles(x, me, normals, inside)
    rung = np.zeros(me.n_edges, dtype=bool)
    rung[np.concatenate([c.rungs for c in courses])] = True
    assert (rung & ~me.boundary).any() and (~rung & ~me.boundary).any()
    assert np.array_equal(skew[rung], every[rung]) and not skew[~rung].any()
    assert not _rung_skews(x, me, courses, None).any()
