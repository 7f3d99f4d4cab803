"""Regular polygons of many sides and boundaries much denser than the spacing (issue 17: a regular
100,000-gon meshes in seconds; its timing is in benchmarks/reliability.py ngon, never here)."""

from __future__ import annotations

import numpy as np
import shapely

from vaultgram.domain import domain_from_dict
from vaultgram.geometry.polylines import polyline_hausdorff
from vaultgram.topology import discretise as dmod
from vaultgram.topology.discretise import discretise
from vaultgram.topology.skeleton import skeleton
from vaultgram.topology.triangulation import triangulate


def _ngon(n, radius=10.0):
    t = 2 * np.pi * np.arange(n) / n
    return radius * np.column_stack([np.cos(t), np.sin(t)])


def test_a_regular_5000_gon_meshes_with_its_boundary_on_the_circle():
    """A valid quad mesh (no inverted face, manifold, one boundary loop) whose boundary vertices lie on
    the circle to within the thinning tolerance and the sagitta of the sampled chords; the same counts
    as the 500-gon, whose vertices are all kept: the dense vertices changed nothing but the work."""
    from vaultgram.meshing.quality import mesh_stats
    from vaultgram.pipeline import mesh_domain

    meshes = [mesh_domain(domain_from_dict({"outer": _ngon(n).tolist()})) for n in (500, 5000)]
    for mesh in meshes:
        stats = mesh_stats(mesh)
        assert stats["inverted_faces"] == 0 and stats["manifold"] and stats["boundary_loops"] == 1
        r = np.hypot(*mesh.vertices[mesh.boundary, :2].T)
        h = 0.02 * 20.0
        assert np.all(np.abs(r - 10.0) <= dmod.THINNING_TOLERANCE * h + h**2 / 80 + 1e-9)
    assert len(meshes[0].faces) == len(meshes[1].faces)
    assert meshes[0].boundary.sum() == meshes[1].boundary.sum()


def test_dense_runs_are_thinned_to_the_tolerance_and_corners_stay():
    """A square whose top side is a dense arc (20,000 vertices): the samples are a few hundred, lie
    within THINNING_TOLERANCE * h of the ring, and every corner of the square is a sample."""
    x = np.linspace(10.0, 0.0, 20000)
    top = np.column_stack([x, 10.0 + 0.5 * np.sin(np.pi * x / 10.0)])
    outer = np.vstack([[[0.0, 0.0], [10.0, 0.0]], top])
    disc = discretise(domain_from_dict({"outer": outer.tolist()}), 0.02)
    ring = disc.points[disc.rings[0]]
    assert len(ring) < 400
    assert polyline_hausdorff(np.vstack([ring, ring[:1]]), np.vstack([outer, outer[:1]])) <= (
        dmod.THINNING_TOLERANCE * disc.h + 1e-12)
    for corner in ([0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]):
        assert np.min(np.hypot(*(ring - corner).T)) < 1e-12
    assert np.isclose(triangulate(disc).areas.sum(), abs(shapely.Polygon(ring).area))


def test_a_plan_without_dense_runs_keeps_every_vertex():
    """Vertices a fifth of the spacing apart are not a dense run: every one is a sample."""
    outer = _ngon(300)  # edges 0.21 apart, h = 0.4
    disc = discretise(domain_from_dict({"outer": outer.tolist()}), 0.02)
    assert disc.is_input_vertex.sum() == 300


def test_the_centre_of_a_regular_polygon_links_three_points_a_third_apart():
    """All samples of a regular 3000-gon are on one circle, one skeleton cell: its centre's dual is
    three of them, 120 degrees apart (not three neighbours, which left regions without a corner)."""
    disc = discretise(domain_from_dict({"outer": _ngon(3000).tolist()}), 0.02)
    (node,) = skeleton(triangulate(disc)).nodes
    assert node.kind == "centre" and len(node.dual) == 3
    angles = np.sort(np.degrees(np.arctan2(*disc.points[list(node.dual)][:, ::-1].T)) % 360)
    assert np.allclose(np.diff(np.concatenate([angles, angles[:1] + 360])), 120.0, atol=1.0)
