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
from vaultgram.formfinding.relaxation import _NOTCH_REACH
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
    the notches); before, the descent alone changed under 5% of them. All within 1.25 times that reach
    of a reflex corner of the meshed plan (2.6 m; the relaxation moves the vertices by up to 2.2 m, so in
    the relaxed diagram they reach 3.8 m). The bound is a length because the notch densities' reach is
    one: it was 8 median edges until session 28, which main itself failed at 12,000 faces asked (2.05 m
    against 2.00, the same spot on the left notch's chord as its 2.31 m here), and layouts that mesh the
    plan finer at the same faces asked with it; layouts whose unequal densities really spread reach
    5.2-11.1 m (benchmarks/README.md, sessions 27-28)."""
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
    reach = _NOTCH_REACH * float(np.hypot(*np.ptp(meshed, axis=0)))
    assert distance.max() < 1.25 * reach


def _reflex_corners(domain, origin) -> np.ndarray:
    """The outline's corners turning inwards by more than 20 degrees (in the mesh's frame)."""
    outer = np.asarray(domain.outer, dtype=float) - np.asarray(origin)[:2]
    a, b = outer - np.roll(outer, 1, axis=0), np.roll(outer, -1, axis=0) - outer
    return outer[np.degrees(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(1))) < -20]


#: Three neighbouring pairs of resolutions around 10^4 faces (faces asked, each pair a factor 2), centred on the
#: one pair the test had before session 27, on which it decided between layouts whose means are equal (session
#: 26: of six such pairs from 9,000 to 12,000 faces asked main passed the old single-pair bounds at 3, a layout
#: that failed at the old pair passed at 2 others). Six pairs cost 45 s of CPU, three about 23 s.
LOBES_PAIRS = ((9500, 19000), (10000, 20000), (10500, 21000))


def _lobes_pair_differences(domain, coarse_faces: int, fine_faces: int) -> tuple[np.ndarray, np.ndarray, int]:
    """|finer height (linear interpolation) - coarser height| / the finer zmax at the coarser network's vertices
    inside the finer one, the same at those farther than 1.5 m from the outline's reflex corners, and the
    coarser network's vertex count; both networks converged in compression (issue 18)."""
    from scipy.interpolate import LinearNDInterpolator
    from scipy.spatial import cKDTree

    networks = []
    for faces in (coarse_faces, fine_faces):
        mesh = mesh_domain(domain, 0.02, target_length=float(np.sqrt(domain.area / faces)))
        tn = thrust_of_mesh(mesh, domain.supports, domain)
        assert tn.summary["max_angle_deg"] < 0.5 and np.all(tn.q[tn.form.active] > 0)
        networks.append(tn.vertices)
    coarse, fine = networks
    z = LinearNDInterpolator(fine[:, :2], fine[:, 2])(coarse[:, :2])
    inside = np.isfinite(z)
    d = np.abs(z[inside] - coarse[inside, 2]) / fine[:, 2].max()
    distance, _ = cKDTree(_reflex_corners(domain, mesh.origin)).query(coarse[inside, :2])
    return d, d[distance > 1.5], len(coarse)


def test_lobes_heights_agree_between_resolutions_away_from_the_notches(architecture_dir):
    """Issue 18's heights floor on the multiple-lobes plan (§5: the relaxation of mode "all"), as a statistic over
    the neighbouring pairs of :data:`LOBES_PAIRS` (7,954 -> 15,618, 8,159 -> 16,298 and 8,526 -> 17,280 faces): at
    the coarser network's vertices, per pair max < 4% of zmax and, farther than 1.5 m from the outline's reflex
    corners (where the unfolding's bands do not reach), max < 2% (the issue's bound); over the pairs, mean of the
    max < 3.3%, of the 99th percentile < 1%, of the far median < 0.25%. Main af3c82e (session 27): max 3.70 /
    2.61 / 2.16%, 99th 0.88 / 0.59 / 0.77%, far max 1.04 / 0.70 / 0.93%, far median 0.168 / 0.145 / 0.158%
    (means 2.82 / 0.75 / 0.157%). The bounds fail for the layouts session 26 measured as worse at the notches:
    the left notch's chord into the upper lobe (max 3.52 / 4.56 / 3.90%, mean 3.99%, 99th mean 1.07%), its
    chord towards the skeleton (99th 1.29 / 1.22 / 1.54%, far median 0.451 / 0.425 / 0.116%). Nearer the
    notches the heights still change with the resolution (session 27: 0.5 m from the top and bottom notches'
    corners the finer vault is higher at every step, by 0.8-1.3% of zmax from 82,399 to 832,000 faces). History:
    with the boundary pieces rounded one by one (before session 16) the boundary vertices drifted by up to an edge
    and the middle pair's heights by 4.88% (max), 2.71% (99th percentile), 0.43% (median); from equal densities
    near the notches (before session 17) 5.81% and 1.51% (cumulative counts in
    :func:`vaultgram.geometry.polylines.resample_polyline`; the plan's own densities near the reflex corners,
    :func:`vaultgram.formfinding.relaxation.notch_densities`)."""
    domain = load_domain(architecture_dir / "multiple_lobes.json")
    stats = []
    for coarse_faces, fine_faces in LOBES_PAIRS:
        d, far, n_coarse = _lobes_pair_differences(domain, coarse_faces, fine_faces)
        assert len(d) > 0.99 * n_coarse and len(far) > 0.75 * n_coarse
        assert d.max() < 0.04 and far.max() < 0.02, (coarse_faces, d.max(), far.max())
        stats.append((d.max(), np.percentile(d, 99), np.median(far)))
    mean_max, mean_p99, mean_far_median = np.mean(stats, axis=0)
    assert mean_max < 0.033 and mean_p99 < 0.01 and mean_far_median < 0.0025, stats
