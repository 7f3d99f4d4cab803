"""Plans far from the origin (site coordinates): worked on in a local frame, written back in the plan's
coordinates (issue 17, What 4; :mod:`vaultgram.geometry.frames`).

The plan at the origin and the same plan moved to (1e9, 1e9) must give the same result up to the
move. "The same plan": the far file is written first, and the near one is that file moved back, which
is exact, so that both describe one shape to the bit."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.cli import main
from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.errors import DomainError
from vaultgram.geometry.frames import FAR as FAR_DIAGONALS
from vaultgram.geometry.frames import NO_ORIGIN, local_origin, to_local, to_plan
from vaultgram.io.meshfiles import mesh_from_json, mesh_to_json
from vaultgram.io.outputs import write_design
from vaultgram.meshing.densities import densities_from_dict
from vaultgram.pipeline import TessellationOptions, design, mesh_domain

from paths import EXAMPLES

FAR = (1e9, 1e9)


def _moved(plan: dict, dx: float, dy: float) -> dict:
    """The plan's rings, features and support polylines moved by (dx, dy)."""
    def move(points):
        return [[x + dx, y + dy] for x, y in points]

    out = {**plan, "outer": move(plan["outer"])}
    for key in ("holes", "curves"):
        if key in plan:
            out[key] = [move(p) for p in plan[key]]
    if "points" in plan:
        out["points"] = move(plan["points"])
    if isinstance(plan.get("supports"), dict) and "polylines" in plan["supports"]:
        out["supports"] = {"polylines": [move(p) for p in plan["supports"]["polylines"]]}
    return out


def _pair(name: str) -> tuple[dict, dict]:
    """The example moved far, and that far plan moved back (the same shape, to the bit)."""
    far = _moved(json.loads((EXAMPLES / f"{name}.json").read_text()), *FAR)
    return _moved(far, -FAR[0], -FAR[1]), far


@pytest.fixture(scope="module")
def designs(tmp_path_factory):
    """The quad with a hole and its far copy designed and written (no figures)."""
    out = {}
    for which, plan in zip(("near", "far"), _pair("quad_with_hole")):
        result = design(domain_from_dict(plan), 0.05, zmax=3.0, tessellation=TessellationOptions())
        folder = tmp_path_factory.mktemp(which)
        write_design(result, folder, ("json", "obj"), plots=False, report=False)
        out[which] = result, folder
    return out


@settings(max_examples=60, deadline=None)
@given(st.floats(1.0, 1e4), st.floats(-1e12, 1e12), st.floats(-1e12, 1e12))
def test_the_local_frame_is_exact_both_ways(size, x0, y0):
    pts = np.array([[x0, y0], [x0 + size, y0], [x0 + size, y0 + 0.7 * size], [x0 + 0.3 * size, y0 + size]])
    origin = local_origin(pts)
    local = to_local(pts, origin)
    assert np.array_equal(to_plan(local, origin), pts)
    assert np.abs(local).max() <= FAR_DIAGONALS * np.hypot(size, size)  # near the origin for its size
    assert (origin == NO_ORIGIN) == (np.abs(pts).max() <= FAR_DIAGONALS * np.hypot(size, size))


def test_a_far_plan_is_worked_on_near_the_origin():
    near, far = (domain_from_dict(p) for p in _pair("quad_with_hole"))
    assert near.origin == NO_ORIGIN and far.origin == FAR
    for a, b in zip(near.rings, far.rings):
        assert np.array_equal(a, b)
    assert far.area == near.area > 0  # at (1e9, 1e9) the shoelace formula kept no digit of it


def test_the_stages_give_the_same_bits_in_the_local_frame(designs):
    (near, _), (far, _) = designs["near"], designs["far"]
    assert np.array_equal(near.mesh.vertices, far.mesh.vertices) and near.mesh.faces == far.mesh.faces
    assert np.array_equal(near.network.vertices, far.network.vertices)
    assert np.array_equal(near.tessellation.solids.vertices, far.tessellation.solids.vertices)
    assert far.mesh.origin == far.network.origin == far.tessellation.origin == FAR


@pytest.mark.parametrize("name, key", [("mesh.json", "vertices"), ("thrust.json", "vertices"),
                                       ("form.json", "vertices"), ("tessellation.json", "vertices")])
def test_the_files_are_in_the_plan_coordinates(designs, name, key):
    (near, a), (_, b) = designs["near"], designs["far"]
    x = np.array(json.loads((a / name).read_text())[key])
    y = np.array(json.loads((b / name).read_text())[key])
    moved = x.copy()
    moved[:, :2] += FAR
    assert np.abs(y - moved).max() <= 1e-6 * near.domain.diagonal


def test_the_decomposition_and_the_obj_files_are_in_the_plan_coordinates(designs):
    (near, a), (_, b) = designs["near"], designs["far"]
    tol = 1e-6 * near.domain.diagonal
    dec_a, dec_b = (json.loads((d / "decomposition.json").read_text()) for d in (a, b))
    pos_a = np.array([n["pos"] for n in dec_a["nodes"] if "pos" in n])
    pos_b = np.array([n["pos"] for n in dec_b["nodes"] if "pos" in n])
    assert np.abs(pos_b - pos_a - FAR).max() <= tol
    sides_a, sides_b = (np.vstack([np.array(s) for p in json.loads((d / "patches.json").read_text())["patches"]
                                   for s in p["sides"]]) for d in (a, b))
    assert np.abs(sides_b - sides_a - FAR).max() <= tol
    for name in ("mesh.obj", "voussoirs.obj"):
        va, vb = (np.array([[float(c) for c in line.split()[1:]] for line in (d / name).read_text().splitlines()
                            if line.startswith("v ")]) for d in (a, b))
        assert np.abs(vb[:, :2] - va[:, :2] - FAR).max() <= tol and np.abs(vb[:, 2] - va[:, 2]).max() <= tol


def test_the_same_files_apart_from_the_coordinates(designs):
    """Force diagram, summaries and counts do not depend on where the plan lies."""
    (_, a), (_, b) = designs["near"], designs["far"]
    for name in ("force.json",):
        assert (a / name).read_bytes() == (b / name).read_bytes()
    sa, sb = (json.loads((d / "summary.json").read_text()) for d in (a, b))
    assert sa["thrust"] == sb["thrust"] and sa["tessellation"] == sb["tessellation"]


def test_a_far_mesh_file_comes_back_in_its_frame(designs):
    (near, _), (_, b) = designs["near"], designs["far"]
    mesh = mesh_from_json(json.loads((b / "mesh.json").read_text()))
    assert mesh.origin == FAR
    assert np.abs(mesh.vertices - near.mesh.vertices).max() <= 1e-6 * near.domain.diagonal
    again = mesh_to_json(mesh)["vertices"]
    assert np.abs(np.array(again) - np.array(json.loads((b / "mesh.json").read_text())["vertices"])).max() == 0


def test_formfind_of_a_far_mesh_writes_the_network_in_its_place(designs, tmp_path):
    (near, a), (_, b) = designs["near"], designs["far"]
    for which, folder in (("near", a), ("far", b)):
        run = CliRunner().invoke(main, ["formfind", str(folder / "mesh.json"), "--out", str(tmp_path / which),
                                        "--zmax", "3"])
        assert run.exit_code == 0, run.output
    x, y = (np.array(json.loads((tmp_path / w / "thrust.json").read_text())["vertices"]) for w in ("near", "far"))
    assert np.abs(y[:, :2] - x[:, :2] - FAR).max() <= 1e-6 * near.domain.diagonal
    assert np.abs(y[:, 2] - x[:, 2]).max() <= 1e-6 * near.domain.diagonal


def test_supports_polylines_and_stats_of_a_far_plan(tmp_path):
    """Support polylines are in the plan's coordinates; ``stats --domain`` measures a far mesh against
    its far domain."""
    near, far = _pair("quad_with_hole")
    near["supports"], far["supports"] = ({"polylines": [[[x0, y0], [x0 + 10, y0]]]}
                                         for x0, y0 in ((0.0, 0.0), FAR))
    meshes = {}
    for which, plan in (("near", near), ("far", far)):
        path = tmp_path / f"{which}.json"
        path.write_text(json.dumps(plan))
        run = CliRunner().invoke(main, ["mesh", str(path), "--out", str(tmp_path / which), "--spacing", "0.05"])
        assert run.exit_code == 0, run.output
        meshes[which] = json.loads((tmp_path / which / "mesh.json").read_text())
        stats = CliRunner().invoke(main, ["stats", str(tmp_path / which / "mesh.json"), "--domain", str(path),
                                          "--json"])
        assert stats.exit_code == 0, stats.output
        meshes[which]["stats"] = json.loads(stats.output)
    assert meshes["near"]["supports"] == meshes["far"]["supports"] and len(meshes["far"]["supports"]) > 2
    for key in ("vertices", "interior_singular", "boundary_singular", "min_scaled_jacobian"):
        assert meshes["near"]["stats"][key] == pytest.approx(meshes["far"]["stats"][key], rel=1e-6)


def test_messages_about_a_far_plan_name_its_own_coordinates():
    plan = _moved({"outer": [[0, 0], [30, 0], [30, 30], [0, 30]], "curves": [[[8, 8], [20, 8]]],
                   "points": [[14, 8]]}, *FAR)
    with pytest.raises(DomainError, match=r"point feature 0 at \(1000000014, 1000000008\)"):
        mesh_domain(domain_from_dict(plan), 0.05)


def test_a_plan_too_far_for_its_size_is_still_refused():
    with pytest.raises(DomainError, match="from the origin"):
        domain_from_dict({"outer": [[1e13, 1e13], [1e13 + 30, 1e13], [1e13 + 30, 1e13 + 30]]})


def test_near_plans_keep_their_coordinates():
    assert load_domain(EXAMPLES / "quad_with_hole.json").origin == NO_ORIGIN


def test_density_regions_of_a_far_plan_are_in_its_coordinates():
    """A region refining the left half gives the far plan the mesh it gives the near one."""
    counts = []
    for plan, (x0, y0) in zip(_pair("quad_with_hole"), ((0.0, 0.0), FAR)):
        spec = densities_from_dict({"regions": [{"polygon": [[x0 - 1, y0 - 1], [x0 + 4, y0 - 1], [x0 + 4, y0 + 11],
                                                             [x0 - 1, y0 + 11]], "count": 12}]})
        counts.append(len(mesh_domain(domain_from_dict(plan), 0.05, densities=spec).faces))
    plain = len(mesh_domain(domain_from_dict(_pair("quad_with_hole")[0]), 0.05).faces)
    assert counts[0] == counts[1] > plain


def test_coordinates_below_the_plans_precision_are_zero():
    """A coordinate smaller than double precision's step at the plan's size carries no shape (moved by
    a metre, the plan loses it): it is zero, and the plan meshes as the one that says zero (saved random
    plan 183 had a hole corner at y = -2.2e-311, and a boundary vertex slid to (x, 0) beside it)."""
    square = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]
    hole = [[4.0, 5.0], [5.0, 4.0], [6.0, 5.0], [5.0, 6.0]]
    tiny = {"outer": [[0.0, -2.2e-311], *square[1:]], "holes": [[[4.0, 5.0 + 1e-17], *hole[1:]]],
            "points": [[3e-16, 2.0]]}
    domain = domain_from_dict(tiny)
    assert domain.outer.min() == 0.0 and not np.signbit(domain.outer).any() and domain.points[0, 0] == 0.0
    assert domain.holes[0][np.argmin(domain.holes[0][:, 0]), 1] == 5.0
    plain = domain_from_dict({"outer": square, "holes": [hole], "points": [[0.0, 2.0]]})
    assert np.array_equal(mesh_domain(domain).vertices, mesh_domain(plain).vertices)
