"""Form finding on fine meshes (issue 18): shared plans meshed at about 10^4 faces converge with the
defaults -- compression only, max angle below the tolerance -- where the pattern as meshed has no
compression-only reciprocal (every boundary supported) or the openings' arches fold it: the pattern is
relaxed with equal force densities (and arches in the openings), unequal where equal ones fold it."""

from __future__ import annotations

import numpy as np
import pytest
from formfinding.cases import holed_grid

from vaultgram.domain import load_domain
from vaultgram.formfinding.formdiagram import form_diagram
from vaultgram.formfinding.horizontal import horizontal
from vaultgram.pipeline import mesh_domain, thrust_of_mesh


#: rv_quad_pattern asks for 12,000 faces: since its chamfer's corners are smooth points (issue 12) it is one
#: structured grid whose quads are skewed (mean scaled Jacobian 0.945), of less area than a square of the
#: target length, so it gets 7,462 (8,000 asked gave 6,606 before, 5,066 now).
@pytest.mark.parametrize("plan, faces, openings", [("rv_quad_pattern", 12000, False),
                                                   ("armadillo_vault", 10000, True)])
def test_plan_at_ten_thousand_faces_converges_in_compression(architecture_dir, plan, faces, openings):
    domain = load_domain(architecture_dir / f"{plan}.json")
    mesh = mesh_domain(domain, 0.02, target_length=float(np.sqrt(domain.area / faces)))
    assert len(mesh.faces) > 0.6 * faces
    tn = thrust_of_mesh(mesh, domain.supports, domain)
    s = tn.summary
    assert s["max_angle_deg"] < 0.5
    assert np.all(tn.q[tn.form.active] > 0)                 # compression only
    assert s["relax_mode"] == "all"                           # the pattern as meshed had none
    assert s["horizontal_iterations"] == 0                    # the relaxation's densities: reciprocal at once
    if not openings:                                          # every free vertex at the mean of its neighbours
        form = tn.form
        nbr_sum = np.zeros_like(form.xy)
        np.add.at(nbr_sum, form.edges[:, 0], form.xy[form.edges[:, 1]])
        np.add.at(nbr_sum, form.edges[:, 1], form.xy[form.edges[:, 0]])
        mean = nbr_sum / np.bincount(form.edges.ravel(), minlength=form.n_vertices)[:, None]
        assert np.allclose(mean[form.free], form.xy[form.free], atol=1e-9)


def test_without_the_lp_a_hopeless_iteration_gives_up_early():
    """Straight open edges flip for good: without the LP rescue (too many edges) the iteration stops once
    an edge has stayed flipped for 10 iterations, instead of waiting for the 50-iteration stall."""
    v, f, outer = holed_grid()
    form = form_diagram(v, f, supports=outer)
    quick = horizontal(form, lp_max_edges=0, raise_on_failure=False)
    slow = horizontal(form, raise_on_failure=False, stall_window=10 ** 6, kmax=60)   # the LP: no such test
    assert not quick.converged and quick.iterations == 10
    assert min(quick.history[1:]) > 90.0
    assert slow.iterations == 60 and min(slow.history[1:61]) > 90.0      # it would not have recovered


def test_lobes_at_ten_thousand_faces_unfold_at_the_notches(architecture_dir):
    """The multiple-lobes plan (every boundary supported) has no compression-only reciprocal as meshed,
    and equal densities fold about 40 faces at the notches between its lobes (the grid lines along the
    boundary pull straight over the reflex corners): the densities become unequal there, and only
    there, until nothing is folded; reciprocal at once, compression only. Since session 17 the
    densities within about 2 m of the reflex corners are the plan's own (dual over primal length,
    :func:`~vaultgram.formfinding.relaxation.notch_densities`) before the descent, which are more than
    a factor 2 from the median on about an eighth of the edges (the meshed quads' aspect ratios near
    the notches); before, the descent alone changed under 5% of them. All within 8 median edges of a
    reflex corner of the meshed plan (1.9 m; the relaxation moves the vertices by up to 2.2 m, so in the
    relaxed diagram they reach 3.8 m)."""
    from scipy.spatial import cKDTree

    from vaultgram.geometry.meshes import face_areas

    domain = load_domain(architecture_dir / "multiple_lobes.json")
    mesh = mesh_domain(domain, 0.02, target_length=float(np.sqrt(domain.area / 8000)))
    assert len(mesh.faces) > 0.7 * 8000
    tn = thrust_of_mesh(mesh, domain.supports, domain)
    s, form = tn.summary, tn.form
    assert s["max_angle_deg"] < 0.5
    assert np.all(tn.q[form.active] > 0)
    assert s["relax_mode"] == "all" and s["horizontal_iterations"] == 0
    assert face_areas(form.xy, form.loaded_faces).min() > 0
    outer = np.asarray(domain.outer, dtype=float) - np.asarray(mesh.origin)[:2]
    a, b = outer - np.roll(outer, 1, axis=0), np.roll(outer, -1, axis=0) - outer
    reflex = outer[np.degrees(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(1))) < -20]
    q = tn.q / np.median(tn.q[form.active])
    unequal = form.active & ((q > 2) | (q < 0.5))
    assert 10 < unequal.sum() < 0.15 * form.active.sum()
    meshed = np.asarray(mesh.vertices)[np.asarray(form.vertex_ids), :2]        # where the densities are set
    distance, _ = cKDTree(reflex).query(meshed[form.edges[unequal]].mean(axis=1))
    assert distance.max() < 8 * np.median(np.linalg.norm(meshed[form.edges[:, 1]] - meshed[form.edges[:, 0]], axis=1))


def _reflex_corners(domain, origin) -> np.ndarray:
    """The outline's corners turning inwards by more than 20 degrees (in the mesh's frame)."""
    outer = np.asarray(domain.outer, dtype=float) - np.asarray(origin)[:2]
    a, b = outer - np.roll(outer, 1, axis=0), np.roll(outer, -1, axis=0) - outer
    return outer[np.degrees(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(1))) < -20]


def test_lobes_heights_agree_between_resolutions_away_from_the_notches(architecture_dir):
    """Issue 18's heights floor on the multiple-lobes plan at 8,159 and 16,298 faces, at the coarser
    network's vertices farther than 1.5 m from the outline's reflex corners (nearer, the unfolding's
    bands differ: not met there yet): within 2% of zmax, median within 0.3%. The relaxation places
    every free vertex by the supports' spacing in index space, so the boundary vertices between kept
    outline points must sit where a uniform subdivision of the side puts them at every resolution
    (cumulative counts in :func:`vaultgram.geometry.polylines.resample_polyline`); with the pieces
    rounded one by one (largest remainders, before session 16) they drifted by up to an edge, and the
    heights by 4.88% (max), 2.71% (99th percentile) and 0.43% (median); with cumulative counts 1.59%,
    0.99% and 0.16%. At all the coarser vertices, near the notches too: within 3%, 99th percentile
    within 1% since the relaxation starts from the plan's own densities near the reflex corners
    (session 17: 2.59% and 0.66%; from equal densities 5.81% and 1.51%)."""
    from scipy.interpolate import LinearNDInterpolator
    from scipy.spatial import cKDTree

    domain = load_domain(architecture_dir / "multiple_lobes.json")
    networks = []
    for faces in (10000, 20000):
        mesh = mesh_domain(domain, 0.02, target_length=float(np.sqrt(domain.area / faces)))
        tn = thrust_of_mesh(mesh, domain.supports, domain)
        assert tn.summary["max_angle_deg"] < 0.5 and np.all(tn.q[tn.form.active] > 0)
        networks.append(tn.vertices)
    coarse, fine = networks
    distance, _ = cKDTree(_reflex_corners(domain, mesh.origin)).query(coarse[:, :2])
    z = LinearNDInterpolator(fine[:, :2], fine[:, 2])(coarse[:, :2])
    far = (distance > 1.5) & np.isfinite(z)
    d = np.abs(z[far] - coarse[far, 2]) / fine[:, 2].max()
    assert far.sum() > 0.75 * len(coarse)
    assert d.max() < 0.02 and np.median(d) < 0.003
    inside = np.isfinite(z)
    d = np.abs(z[inside] - coarse[inside, 2]) / fine[:, 2].max()
    assert inside.sum() > 0.99 * len(coarse)
    assert d.max() < 0.03 and np.percentile(d, 99) < 0.01
