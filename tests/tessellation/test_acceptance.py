"""The whole pipeline (domain -> mesh -> thrust network -> voussoirs, §3-§5) against the tessellation's
acceptance properties, on the bundled examples, the Armadillo Vault (the paper's case study, §5) and
random domains.

The thresholds are what the tessellation achieves now (measured, see MEASURED), with a small margin,
so that a regression shows up; where they are below the issue's targets the test says so.
"""

from __future__ import annotations

import json
from functools import lru_cache

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from vaultgram.cli import main
from vaultgram.domain import load_domain
from vaultgram.errors import VaultgramError
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.pipeline import TessellationOptions, design, form_find, tessellate
from vaultgram.tessellation.solids import solid_volumes
from vaultgram.tessellation.surface import surface_from_network
from vaultgram.tessellation.voussoirs import MAX_CONCAVITY, max_corner_angles

from paths import ARCHITECTURE, EXAMPLES
from strategies.domains import convex_domains

#: Measured on each input at rhythm 2 and rhythm 4: the share of inner meeting points joining three
#: voussoirs, the coefficient of variation of the voussoir areas, and the median angle (degrees)
#: between the joints in regular areas and the force flow across them.
MEASURED = {
    "features_combined": {"of_3": (0.967, 0.970), "cv": (0.393, 0.427), "force": (5.77, 5.80)},
    "fig5_boundary_points": {"of_3": (0.979, 1.000), "cv": (0.382, 0.340), "force": (4.32, 4.22)},
    "fig6_inner_points": {"of_3": (0.959, 0.956), "cv": (0.448, 0.463), "force": (2.73, 2.72)},
    "fig7_curves": {"of_3": (0.975, 0.974), "cv": (0.462, 0.474), "force": (5.35, 5.27)},
    "l_shape": {"of_3": (0.990, 0.996), "cv": (0.307, 0.282), "force": (6.80, 6.42)},
    "quad_with_hole": {"of_3": (1.000, 1.000), "cv": (0.308, 0.278), "force": (1.43, 1.37)},
    "square_point_loads": {"of_3": (0.992, 0.992), "cv": (0.358, 0.299), "force": (9.26, 9.19)},
    "armadillo_vault": {"of_3": (0.969, 0.988), "cv": (0.391, 0.378), "force": (9.99, 9.61)},
}
# square_point_loads was at 0.984/0.992, 0.352/0.298 and 8.30/8.41 degrees until its point loads' fans
# got at most the triangles that reach the mesh's floor (vaultgram.meshing.densities.point_load_caps:
# 23 instead of 39 round each load, evened; its worst face 0.093 -> 0.312): the joints 1 degree further
# from the force flow, under the 10.
# The area CVs of fig7_curves and features_combined were 0.435/0.437 and 0.386/0.415 before the
# strips under their curve ends (rules/curves.vgr, split_triangle_under_curve_tip): a column of
# quads more from each end to the boundary.
#: Margins on the measurements: share of points of three, area CV, force angle (degrees).
OF_3_MARGIN, CV_MARGIN, FORCE_MARGIN = 0.02, 0.03, 0.75
# The targets, at least 95% of meeting points of three voussoirs, an area CV of at most 0.5
# and a median joint-to-force angle of at most 10 degrees in regular areas, are met on every input
# at both rhythms, and asserted as such. The Armadillo is closest on the force angle (9.99 degrees
# at rhythm 2; its thrust network's own quads are skewed 10.2 degrees at the median). The tests also
# assert the measured levels, so that a regression shows.
#: rhythm 4 against rhythm 2, mean voussoir area; the issue says "about twice". Where courses are
#: long, it is: 1.98 on a regular 64 x 64 grid (:func:`test_rhythm_four_doubles_the_voussoirs_on_long_courses`),
#: 1.79 on quad_with_hole at 10^4 faces. On the examples' coarse meshes it is 1.26 (fig6) to 1.54
#: (quad_with_hole): a course of k quads holds about k / 4 rhythm-4 voussoirs but k / 2 rhythm-2
#: ones only when k is even and the neighbours' joints allow it; a short or odd course takes a
#: voussoir of three quads at rhythm 2 (a single quad would leave its neighbours no staggered
#: choice), and a course of three to five quads is one voussoir at either rhythm. fig6 was at 1.37
#: until the fans round its point features were evened (vaultgram.meshing.fans.even_fans: its worst
#: scaled Jacobian 0.242 -> 0.395, its joints 2.96 -> 2.73 degrees from the force flow; 394 and 313
#: voussoirs at rhythms 2 and 4, 386 and 281 before).
RHYTHM_4_RATIO = 1.25

EXAMPLE_NAMES = sorted(p.stem for p in EXAMPLES.glob("*.json") if not p.stem.startswith("skeleton_"))
NAMES = EXAMPLE_NAMES + ["armadillo_vault"]
RHYTHMS = (2, 4)


def _path(name: str):
    return EXAMPLES / f"{name}.json" if name in EXAMPLE_NAMES else ARCHITECTURE / f"{name}.json"


@lru_cache(maxsize=None)
def _designed(name: str):
    """The design of ``name`` (tessellated at rhythm 2) and its thrust surface, computed once per session."""
    path = _path(name)
    if not path.is_file():
        pytest.skip(f"{path} not found (the shared data lives beside the checkout)")
    d = design(load_domain(path))
    return d, surface_from_network(d.network)


@lru_cache(maxsize=None)
def _rhythm_4(name: str):
    d, surface = _designed(name)
    return tessellate(surface, rhythm=4, thickness=1.0)  # design's thickness: as design(rhythm=4) would


@pytest.fixture(scope="module")
def tessellated():
    """``tessellated(name, rhythm)``: the domain and its tessellation."""
    def get(name: str, rhythm: int):
        d, _ = _designed(name)
        return d.domain, (d.tessellation if rhythm == 2 else _rhythm_4(name))
    return get


def test_every_bundled_example_has_measurements():
    assert set(EXAMPLE_NAMES) <= set(MEASURED)


# ---------------------------------------------------------------------------------------------
# Properties of one tessellation (shared with the random domains)
# ---------------------------------------------------------------------------------------------


def _euler(loops) -> int:
    """V - E + F of voussoir outlines, counted here independently of the metrics."""
    edges = {frozenset(p) for loop in loops for p in zip(loop.tolist(), np.roll(loop, -1).tolist())}
    return len({int(v) for loop in loops for v in loop}) - len(edges) + len(loops)


def _directed_edges(triangles, owner):
    t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    a, b = t.ravel(), np.roll(t, -1, axis=1).ravel()
    return np.repeat(np.asarray(owner, dtype=np.int64), 3), a, b


def closed_oriented(triangles, owner) -> np.ndarray:
    """Per solid (triangles by ``owner``): every directed edge once and its reverse once, that is
    closed and consistently oriented."""
    k, a, b = _directed_edges(triangles, owner)
    n = int(max(a.max(), b.max())) + 1
    key, back = (k * n + a) * n + b, (k * n + b) * n + a
    unique, count = np.unique(key, return_counts=True)
    ok_edge = (count[np.searchsorted(unique, key)] == 1) & np.isin(back, unique)
    return np.bincount(k, weights=~ok_edge, minlength=int(k.max()) + 1) == 0


def shared_faces(vertices, triangles, owner) -> tuple[int, int]:
    """How many triangle copies appear, by vertex coordinates, in exactly two solids with opposite
    orientations (a joint quad gives two triangles, so four copies); and how many triangles appear
    otherwise more than once (never)."""
    _, ids = np.unique(np.round(vertices, 9), axis=0, return_inverse=True)
    t = ids.ravel()[np.asarray(triangles, dtype=np.int64)]
    first = np.argmin(t, axis=1)
    t = np.stack([t[np.arange(len(t)), (first + r) % 3] for r in range(3)], axis=1)  # smallest first
    parity = t[:, 1] < t[:, 2]
    key = np.sort(t, axis=1)
    _, group, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    group = group.ravel()
    twice = np.flatnonzero(count == 2)
    order = np.argsort(group, kind="stable")
    start = np.searchsorted(group[order], twice)
    i, j = order[start], order[start + 1]
    good = (np.asarray(owner)[i] != np.asarray(owner)[j]) & (parity[i] != parity[j])
    return int(2 * good.sum()), int((~good).sum() + (count > 2).sum())


def solid_failures(t) -> list[str]:
    """What is wrong with the solids of tessellation ``t``: each closed, outward (positive volume), the
    joint faces shared by the two voussoirs either side, by vertex coordinates."""
    out = []
    n = t.layout.n_voussoirs
    solids = t.solids
    if not (len(np.unique(solids.owner)) == n and closed_oriented(solids.triangles, solids.owner).all()):
        out.append("a solid is not closed and consistently oriented")
    if not (solid_volumes(solids, n) > 0).all():
        out.append("a solid has no positive volume")
    shared, bad = shared_faces(solids.vertices, solids.triangles, solids.owner)
    if shared != 4 * len(t.layout.joints) or bad:
        out.append(f"{shared} shared joint triangles for {len(t.layout.joints)} joints, {bad} bad")
    return out


def test_the_solid_checks_find_open_flipped_and_unshared_faces():
    """The checks above on two tetrahedra sharing the face 0 1 2 (by coordinates, not by index)."""
    x = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, -1], [0, 0, 0], [1, 0, 0], [0, 1, 0]])
    up = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]])
    down = np.array([[5, 6, 7], [5, 4, 6], [6, 4, 7], [7, 4, 5]])
    both, owner = np.vstack([up, down]), np.repeat([0, 1], 4)
    assert closed_oriented(both, owner).tolist() == [True, True]
    assert shared_faces(x, both, owner) == (2, 0)
    flipped = both.copy()
    flipped[1] = flipped[1, ::-1]
    assert closed_oriented(flipped, owner).tolist() == [False, True]
    assert closed_oriented(both[1:], owner[1:]).tolist() == [False, True]
    same_way = both.copy()
    same_way[4] = same_way[4, ::-1]  # both solids' copies of the shared face turn the same way
    assert shared_faces(x, same_way, owner) == (0, 1)


def max_meeting(t) -> int:
    return max((int(k) for k in t.summary["meeting_points"]), default=0)


# ---------------------------------------------------------------------------------------------
# Examples and the Armadillo Vault
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("rhythm", RHYTHMS)
@pytest.mark.parametrize("name", NAMES)
def test_meeting_points_join_at_most_four_voussoirs_mostly_three(tessellated, name, rhythm):
    _, t = tessellated(name, rhythm)
    assert max_meeting(t) <= 4
    # the floor (95%), and the level measured on each input
    assert t.summary["meeting_points_of_3"] >= MEASURED[name]["of_3"][rhythm // 4] - OF_3_MARGIN
    assert t.summary["meeting_points_of_3"] >= 0.95


@pytest.mark.parametrize("rhythm", RHYTHMS)
@pytest.mark.parametrize("name", NAMES)
def test_no_corner_above_the_concavity_threshold_but_in_concave_faces(tessellated, name, rhythm):
    """The summary's concave voussoirs (largest corner in their best-fit plane above the threshold) are
    only single faces of the cut mesh that are concave themselves (a keystone, a face of the thrust
    network): the bond never makes one. Measured: none at 190 degrees."""
    _, t = tessellated(name, rhythm)
    assert _concave_merges(t, MAX_CONCAVITY) == []
    assert t.summary["concave_voussoirs"] == 0 and t.summary["largest_corner_deg"] <= MAX_CONCAVITY


def _concave_merges(t, max_angle: float) -> list[int]:
    """Voussoirs with a corner above ``max_angle`` that are not one concave face."""
    lay = t.layout
    angle, _ = max_corner_angles(t.vertices, list(lay.loops))
    face_angle, _ = max_corner_angles(t.vertices, list(lay.mesh.faces))
    size = np.bincount(lay.group)
    first = np.full(lay.n_voussoirs, -1)
    first[lay.group[::-1]] = np.arange(len(lay.group))[::-1]
    eps = 1e-9  # corners of exactly 180 degrees carry rounding noise
    return [k for k in np.flatnonzero(angle > max_angle + eps).tolist()
            if not (size[k] == 1 and face_angle[first[k]] > max_angle + eps)]


@pytest.mark.parametrize("name", ["quad_with_hole", "features_combined", "armadillo_vault"])
def test_a_tighter_concavity_threshold_is_kept_too(name):
    _, surface = _designed(name)
    t = tessellate(surface, thickness=1.0, max_concavity=185.0)
    assert _concave_merges(t, 185.0) == []
    assert max_meeting(t) <= 4


@pytest.mark.parametrize("name", ["armadillo_vault", "fig6_inner_points", "quad_with_hole"])
def test_smoothing_on_the_surface_keeps_voussoirs_convex_and_joints_normal(name):
    """``--surface-smooth 5``: the Laplacian steps that would push a voussoir corner past the threshold
    are undone; the joints stay normal to the surface and follow the force flow better (measured on
    the Armadillo: 9.99 -> 9.45 degrees; 7.95 -> 7.43 in session 16). On the Armadillo the change of the
    median is a draw from a spread, not a constant: over ten target lengths 0.3-0.6 (230-1,000 faces)
    it is -0.20 degrees on average, standard deviation 0.37, from -0.89 to +0.52 (the per-joint changes
    are +-2 degrees and more, both ways, all over the vault), so a new mesh can cross the 0.1 bound
    without anything being wrong in the smoothing (session 15's 1924157 with cumulative boundary
    counts: 8.20 -> 8.62); benchmarks/README, session 16 s16-heights."""
    d, surface = _designed(name)
    t = tessellate(surface, thickness=1.0, surface_smooth=5)
    assert _concave_merges(t, MAX_CONCAVITY) == [] and solid_failures(t) == []
    assert t.summary["joint_tilt_deg"]["p95"] <= 3.5
    before = d.tessellation.summary["joint_force_angle_regular_deg"]["median"]
    assert t.summary["joint_force_angle_regular_deg"]["median"] <= before + 0.1


@pytest.mark.parametrize("rhythm", RHYTHMS)
@pytest.mark.parametrize("name", NAMES)
def test_euler_characteristic_counts_every_hole_of_the_domain(tessellated, name, rhythm):
    """Open and supported holes alike are holes of the voussoir outlines: V - E + F = 1 - holes."""
    domain, t = tessellated(name, rhythm)
    holes = len(domain.holes)
    assert t.summary["euler_characteristic"] == _euler(t.layout.loops) == 1 - holes
    assert t.summary["openings"] == holes


@pytest.mark.parametrize("rhythm", RHYTHMS)
@pytest.mark.parametrize("name", NAMES)
def test_solids_are_closed_outward_and_share_their_joints(tessellated, name, rhythm):
    _, t = tessellated(name, rhythm)
    assert solid_failures(t) == []


@pytest.mark.parametrize("rhythm", RHYTHMS)
@pytest.mark.parametrize("name", NAMES)
def test_joints_are_normal_to_the_surface(tessellated, name, rhythm):
    """Measured: medians 0.09-0.34 degrees, 95th percentiles 0.6-2.0 degrees (l_shape)."""
    _, t = tessellated(name, rhythm)
    tilt = t.summary["joint_tilt_deg"]
    assert tilt["median"] <= 1.0 and tilt["p95"] <= 3.5


@pytest.mark.parametrize("rhythm", RHYTHMS)
@pytest.mark.parametrize("name", NAMES)
def test_joints_follow_the_force_flow_in_regular_areas(tessellated, name, rhythm):
    _, t = tessellated(name, rhythm)
    angle = t.summary["joint_force_angle_regular_deg"]["median"]
    assert angle <= MEASURED[name]["force"][rhythm // 4] + FORCE_MARGIN and angle <= 10.0  # the floor


@pytest.mark.parametrize("rhythm", RHYTHMS)
@pytest.mark.parametrize("name", NAMES)
def test_voussoir_areas_are_even(tessellated, name, rhythm):
    # the floor (0.5), and the level measured on each input
    _, t = tessellated(name, rhythm)
    areas = t.layout.areas(t.vertices)
    cv = float(areas.std() / areas.mean())
    assert cv == pytest.approx(t.summary["areas"]["cv"])
    assert cv <= MEASURED[name]["cv"][rhythm // 4] + CV_MARGIN
    assert cv <= 0.5


@pytest.mark.parametrize("name", NAMES)
def test_rhythm_four_makes_larger_voussoirs(tessellated, name):
    _, t2 = tessellated(name, 2)
    _, t4 = tessellated(name, 4)
    assert t4.summary["areas"]["mean"] > RHYTHM_4_RATIO * t2.summary["areas"]["mean"]
    assert t4.layout.n_voussoirs < t2.layout.n_voussoirs
    total = [t.layout.areas(t.vertices).sum() for t in (t2, t4)]
    assert total[1] == pytest.approx(total[0], rel=1e-9)  # the same surface, cut differently


def test_rhythm_four_doubles_the_voussoirs_on_long_courses():
    # a regular grid: its rings of courses are 16 to 64 quads long, where rhythm 4 has room
    ratios = []
    for n in (16, 64):
        v, f = grid_mesh(n)
        surface = surface_from_network(form_find(v, f, zmax=2.0))
        t2, t4 = (tessellate(surface, rhythm=r, thickness=0.2) for r in RHYTHMS)
        ratios.append(t4.summary["areas"]["mean"] / t2.summary["areas"]["mean"])
    assert ratios[1] >= 1.9  # "about twice": measured 1.98
    assert ratios[1] > ratios[0]  # courses four times longer: closer to twice (1.65 at 16 x 16)


@pytest.mark.parametrize("name", NAMES)
def test_every_voussoir_is_reached_from_a_support_and_named_once(tessellated, name):
    _, t = tessellated(name, 2)
    assert (t.courses >= 0).all() and (t.zones >= 0).all()
    assert len(set(t.names)) == t.layout.n_voussoirs


@pytest.mark.parametrize("name", NAMES)
def test_the_same_surface_gives_the_same_tessellation(name):
    d, surface = _designed(name)
    again = tessellate(surface, thickness=1.0)
    assert json.dumps(again.to_json()) == json.dumps(d.tessellation.to_json())


def test_the_same_domain_gives_the_same_design():
    d, _ = _designed("quad_with_hole")
    again = design(load_domain(_path("quad_with_hole")))
    assert json.dumps(again.tessellation.to_json()) == json.dumps(d.tessellation.to_json())


def _obj_objects(path):
    """Vertices and per object its triangles (0-based) from an OBJ file of named objects."""
    vertices, objects = [], []
    for line in path.read_text().splitlines():
        kind, *rest = line.split() or [""]
        if kind == "v":
            vertices.append([float(c) for c in rest])
        elif kind == "o":
            objects.append([])
        elif kind == "f":
            objects[-1].append([int(i) - 1 for i in rest])
    return np.array(vertices), [np.array(o, dtype=np.int64).reshape(-1, 3) for o in objects]


def test_the_command_writes_the_same_closed_solids(tmp_path):
    """``vaultgram tessellate thrust.json``: tessellation.json is the design's, and voussoirs.obj holds
    one closed, outward solid per voussoir, neighbours sharing their joint faces."""
    d, _ = _designed("quad_with_hole")
    thrust = tmp_path / "thrust.json"
    thrust.write_text(json.dumps(d.network.to_json()))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["tessellate", str(thrust), "--out", str(out)])
    assert result.exit_code == 0, result.output
    t = d.tessellation
    assert json.loads((out / "tessellation.json").read_text()) == json.loads(json.dumps(t.to_json()))
    vertices, objects = _obj_objects(out / "voussoirs.obj")
    assert len(objects) == t.layout.n_voussoirs
    triangles = np.concatenate(objects)
    owner = np.repeat(np.arange(len(objects)), [len(o) for o in objects])
    assert closed_oriented(triangles, owner).all()
    p = vertices[triangles]
    six = np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2]))
    assert (np.bincount(owner, weights=six) > 0).all()
    assert shared_faces(vertices, triangles, owner) == (4 * len(t.layout.joints), 0)


# ---------------------------------------------------------------------------------------------
# Random domains
# ---------------------------------------------------------------------------------------------


@settings(max_examples=6, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(convex_domains(), st.sampled_from(RHYTHMS))
def test_random_domains_tessellate_or_fail_clearly(domain, rhythm):
    try:
        d = design(domain, target_length=0.05 * domain.diagonal, tessellation=TessellationOptions(rhythm=rhythm))
    except VaultgramError as exc:
        assert str(exc).strip()
        return
    t = d.tessellation
    assert max_meeting(t) <= 4
    assert t.summary["euler_characteristic"] == _euler(t.layout.loops) == 1 - len(domain.holes)
    assert solid_failures(t) == []
    assert _concave_merges(t, MAX_CONCAVITY) == []
