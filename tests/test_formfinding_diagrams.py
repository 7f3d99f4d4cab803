"""Form and force diagrams, horizontal and vertical equilibrium on grids and a grid with a hole."""

from __future__ import annotations

import json

import numpy as np
import pytest

from vaultgram.formfinding.forcediagram import force_diagram
from vaultgram.formfinding.formdiagram import form_diagram
from vaultgram.formfinding.horizontal import angle_deviations, horizontal, relax_openings
from vaultgram.formfinding.loads import tributary_areas
from vaultgram.formfinding.vertical import vertical
from vaultgram.geometry.meshes import boundary_loops, grid_index, grid_mesh, remove_faces
from vaultgram.io.files import write_obj
from vaultgram.pipeline import form_find


def holed_grid(n=20, lo=7, hi=13):
    """An n x n grid with the central block of faces [lo, hi) x [lo, hi) removed; outer loop supported."""
    v, f = grid_mesh(n)
    drop = [j * n + i for i in range(lo, hi) for j in range(lo, hi)]
    v2, f2, _ = remove_faces(v, f, drop)
    outer = max(boundary_loops(f2), key=len)
    return v2, f2, outer


def assert_network_ok(tn, tol_deg=0.5):
    s = tn.summary
    assert s["max_angle_deg"] < tol_deg
    assert np.all(tn.q > 0), "compression only"
    assert s["vertical_residual"] < 1e-8 * s["total_load"]
    assert s["reaction_sum"] == pytest.approx(s["total_load"], rel=1e-9)
    assert np.all(np.isfinite(tn.vertices))


def test_grid_form_diagram_counts():
    v, f = grid_mesh(10)
    form = form_diagram(v, f)
    assert form.n_vertices == 121 - 4          # corners deleted
    assert form.n_edges == 220 - 40            # supported boundary edges removed
    assert form.n_faces == 100 and form.loaded.all()     # corner quads became triangles
    assert sum(len(fc) == 3 for fc in form.faces) == 4
    assert form.anchors.sum() == 40 - 4
    assert form.C.shape == (180, 117)
    assert np.allclose(form.C @ np.ones(117), 0)
    kept = form_diagram(v, f, update_boundaries=False)
    assert kept.n_vertices == 121 and kept.n_edges == 220 and kept.active.sum() == 180


def test_reciprocal_counts_and_parallel_edges_on_grid():
    v, f = grid_mesh(8)
    form = form_diagram(v, f)
    force = force_diagram(form)
    assert force.n_vertices == form.n_faces
    assert force.n_edges == form.n_edges
    h = horizontal(form, force)
    ang = angle_deviations(form.edge_vectors()[h.force.form_edge], h.force.edge_vectors())
    assert ang.max() < 1e-6          # stored force diagram is parallel (not perpendicular) to the form
    assert np.all(h.q > 0)


def test_hole_gets_an_opening_face_and_is_relaxed():
    v, f, outer = holed_grid()
    form = form_diagram(v, f, supports=outer)
    assert (~form.loaded).sum() == 1
    opening = form.opening_faces[0]
    assert len(opening) == 24
    assert not form.anchors[list(opening)].any()
    relaxed = relax_openings(form, sag=0.1)
    moved = np.linalg.norm(relaxed.xy - form.xy, axis=1)
    on_hole = np.zeros(form.n_vertices, dtype=bool)
    on_hole[list(opening)] = True
    assert moved[~on_hole].max() == 0.0                     # mode "boundary" keeps the pattern
    assert moved[on_hole].max() == pytest.approx(0.1 * 6, rel=1e-3)   # sag x span (side of the square hole)
    # the sides bow away from the hole (arches around it): the opening grows and gets rounder
    centre = np.array([10.0, 10.0])
    d0 = np.linalg.norm(form.xy[list(opening)] - centre, axis=1)
    d1 = np.linalg.norm(relaxed.xy[list(opening)] - centre, axis=1)
    mid_sides = np.isclose(d0, 3.0)
    assert np.all(d1[mid_sides] == pytest.approx(3.6, rel=1e-3))
    assert d1.std() < d0.std()

    def area(p):
        return 0.5 * abs(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]))

    assert area(relaxed.xy[list(opening)]) > area(form.xy[list(opening)])


@pytest.mark.parametrize("mode", ["boundary", "all"])
def test_hole_converges_in_compression(mode):
    v, f, outer = holed_grid()
    tn = form_find(v, f, supports=outer, zmax=4.0, relax_mode=mode)
    assert_network_ok(tn)
    assert tn.summary["n_openings"] == 1
    assert abs(tn.vertices[:, 2].max() - 4.0) < 1e-6
    assert tn.force.n_vertices == tn.form.n_faces
    assert tn.force.n_edges == tn.form.n_edges
    ang = angle_deviations(tn.form.edge_vectors()[tn.force.form_edge], tn.force.edge_vectors())
    assert ang.max() < 0.5


def test_grid_form_find_with_point_loads():
    v, f = grid_mesh(10)
    centre = grid_index(5, 5, 10)
    tn = form_find(v, f, zmax=3.0, point_loads={centre: 10.0})
    assert_network_ok(tn)
    plain = form_find(v, f, zmax=3.0)
    selfweight = tributary_areas(tn.vertices, tn.faces).sum()
    assert tn.summary["total_load"] == pytest.approx(selfweight + 10.0, rel=1e-12)   # point load counted
    assert tn.summary["scale"] > plain.summary["scale"]      # more load, more thrust for the same rise
    k = int(np.flatnonzero(tn.vertex_ids == centre)[0])
    assert tn.loads[k] > plain.loads[k] + 9.99


def test_partially_supported_grid_has_run_openings():
    """Supports on two opposite sides: the two free sides are runs between supports (barrel vault)."""
    v, f = grid_mesh(10)
    sup = [grid_index(0, j, 10) for j in range(11)] + [grid_index(10, j, 10) for j in range(11)]
    form = form_diagram(v, f, supports=sup)
    assert (~form.loaded).sum() == 2
    for op in form.opening_faces:
        assert form.anchors[op[0]] and form.anchors[op[-1]] and not form.anchors[list(op[1:-1])].any()
    tn = form_find(v, f, supports=sup, zmax=3.0, sag=0.1)
    assert_network_ok(tn)


def test_alpha_blend_moves_both_diagrams():
    v, f = grid_mesh(6)
    rng = np.random.default_rng(1)
    inner = (v[:, 0] > 0) & (v[:, 0] < 6) & (v[:, 1] > 0) & (v[:, 1] < 6)
    v[inner, :2] += rng.uniform(-0.2, 0.2, (inner.sum(), 2))
    form = form_diagram(v, f)
    h = horizontal(form, alpha=50)
    assert h.max_angle < 0.5 and h.converged
    assert not np.allclose(h.form.xy, form.xy)
    assert np.allclose(h.form.xy[form.fixed], form.xy[form.fixed])   # anchors stay


def test_tributary_areas_sum_to_face_areas():
    rng = np.random.default_rng(3)
    v, f = grid_mesh(5)
    xyz = v.copy()
    xyz[:, 2] = rng.uniform(0, 2, len(v))
    a = tributary_areas(xyz, f)
    total = 0.0
    for face in f:
        p = xyz[list(face)]
        c = p.mean(axis=0)
        for i in range(len(face)):
            total += 0.5 * np.linalg.norm(np.cross(p[i] - c, p[(i + 1) % len(face)] - c))
    assert a.sum() == pytest.approx(total, rel=1e-12)


def test_vertical_reactions_and_thickness():
    v, f = grid_mesh(6)
    form = form_diagram(v, f)
    q = np.ones(form.n_edges)
    thin = vertical(form, q, thickness=0.5, zmax=2.0)
    thick = vertical(form, q, thickness=1.0, zmax=2.0)
    assert thick.scale == pytest.approx(2 * thin.scale, rel=1e-9)     # same shape, twice the thrust
    assert np.allclose(thick.z, thin.z, atol=1e-9)
    assert thick.reactions[:, 2].sum() == pytest.approx(thick.total_load, rel=1e-12)
    assert np.all(thick.reactions[:, 2] > 0)
    # horizontal reactions of a symmetric vault cancel
    assert np.abs(thick.reactions[:, :2].sum(axis=0)).max() < 1e-9


def test_outputs_are_json_and_obj(tmp_path):
    v, f = grid_mesh(4)
    tn = form_find(v, f, zmax=1.0)
    for obj in (tn.to_json(), tn.form.to_json(), tn.force.to_json()):
        json.loads(json.dumps(obj))
    path = tmp_path / "thrust.obj"
    write_obj(path, tn.vertices, tn.faces)
    lines = path.read_text().splitlines()
    assert sum(ln.startswith("v ") for ln in lines) == tn.vertices.shape[0]
    assert sum(ln.startswith("f ") for ln in lines) == len(tn.faces)
    write_obj(tmp_path / "form.obj", tn.form.xy, tn.form.loaded_faces)
    assert "max angle deviation" in tn.summary_text()


def test_deterministic():
    v, f, outer = holed_grid(12, 4, 8)
    a = form_find(v, f, supports=outer, zmax=2.0)
    b = form_find(v, f, supports=outer, zmax=2.0)
    for name in ("vertices", "q", "forces", "loads", "reactions", "edges"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert np.array_equal(a.force.xy, b.force.xy)


def test_weighted_fit_with_unit_weight_is_the_plain_fit():
    from vaultgram.formfinding.forcediagram import PinnedLaplacian, WeightedFit

    v, f, outer = holed_grid(10, 3, 7)
    form = form_diagram(v, f, supports=outer)
    force = force_diagram(form)
    rng = np.random.default_rng(0)
    t = rng.normal(size=(force.n_edges, 2))
    frame = rng.normal(size=(force.n_edges, 2))
    frame /= np.linalg.norm(frame, axis=1)[:, None]
    x0 = rng.normal(size=(force.n_vertices, 2))
    plain = PinnedLaplacian(force.C, force.pins).solve(t, x0)
    assert np.allclose(WeightedFit(force.C, force.pins, frame, 1.0).solve(t, x0), plain, atol=1e-10)
    # with mu < 1 it minimises the weighted objective: its gradient vanishes at the free vertices
    mu = 0.01
    x = WeightedFit(force.C, force.pins, frame, mu).solve(t, x0)
    assert np.array_equal(x[force.pins], x0[force.pins])
    r = force.C @ x - t
    n = np.column_stack([-frame[:, 1], frame[:, 0]])
    wr = n * (n * r).sum(1)[:, None] + mu * frame * (frame * r).sum(1)[:, None]
    grad = force.C.T @ wr
    free = np.setdiff1d(np.arange(force.n_vertices), force.pins)
    assert np.abs(grad[free]).max() < 1e-9


def test_weighted_accelerated_iteration_keeps_the_guarantees_in_fewer_iterations():
    """Default (mu = 0.01, Anderson 5) and the plain compas_tna update reach the same stopping test."""
    v, f, outer = holed_grid(24, 8, 16)
    v[:, :2] += 0.02 * np.sin(v[:, [1, 0]])         # break the symmetry
    form = relax_openings(form_diagram(v, f, supports=outer), 0.1)
    fast = horizontal(form)
    plain = horizontal(form, length_weight=1.0, anderson=0)   # stalls here; the LP rescue finishes it
    assert fast.method == "parallelisation"
    for h in (fast, plain):
        assert h.converged and h.max_angle < 0.5
        assert np.all(h.q[form.active] > 0)
    assert fast.iterations < plain.iterations
    assert np.array_equal(fast.form.xy, form.xy)           # alpha = 100 keeps the plan
