"""COMPAS and compas_tna round trips (vaultgram.io.compasfiles, public as vaultgram.compas), with the
real packages."""

from __future__ import annotations

import numpy as np
import pytest

from paths import EXAMPLES

compas = pytest.importorskip("compas")
compas_tna = pytest.importorskip("compas_tna")

from compas.datastructures import Mesh  # noqa: E402
from compas_tna.diagrams import FormDiagram  # noqa: E402
from compas_tna.equilibrium import vertical_from_q  # noqa: E402

from vaultgram.compas import from_compas_mesh, to_compas_mesh, to_formdiagram  # noqa: E402
from vaultgram.domain import load_domain  # noqa: E402
from vaultgram.errors import VaultgramError  # noqa: E402
from vaultgram.formfinding.supports import support_vertices  # noqa: E402
from vaultgram.io.compasfiles import compas_json  # noqa: E402
from vaultgram.pipeline import mesh_domain, thrust_of_mesh  # noqa: E402


@pytest.fixture(scope="module")
def pattern():
    """The quad with a hole, meshed coarsely, its outer boundary supported (the hole open)."""
    domain = load_domain(EXAMPLES / "quad_with_hole.json")
    mesh = mesh_domain(domain, 0.04, target_length=1.0)
    return mesh, support_vertices(mesh.vertices, mesh.faces, None, domain)


@pytest.fixture(scope="module")
def network(pattern):
    mesh, supports = pattern
    return thrust_of_mesh(mesh, {"vertices": supports.tolist()}, zmax=3.0, point_load=0.0)


def reloaded(obj, cls, tmp_path):
    """The object written to a file by vaultgram and read back by compas' own loader."""
    path = tmp_path / "data.json"
    path.write_text(compas_json(obj))
    return cls.from_json(str(path))


def test_pattern_mesh_round_trip(pattern, tmp_path):
    mesh, supports = pattern
    m = reloaded(to_compas_mesh(mesh, supports), Mesh, tmp_path)
    assert (m.number_of_vertices(), m.number_of_faces()) == (len(mesh.vertices), len(mesh.faces))
    assert sorted(m.vertices_where(is_support=True)) == supports.tolist()
    assert sorted(m.vertices_where(is_boundary=True)) == np.flatnonzero(mesh.boundary).tolist()
    x, faces, back = from_compas_mesh(m)
    np.testing.assert_array_equal(x[:, :2], mesh.vertices)
    assert faces == [list(f) for f in mesh.faces] and back == supports.tolist()


def test_thrust_network_round_trip(network, tmp_path):
    m = reloaded(to_compas_mesh(network), Mesh, tmp_path)
    assert m.number_of_vertices() == len(network.vertices) and m.number_of_faces() == len(network.faces)
    edges = list(m.edges_where(_is_edge=True))
    assert len(edges) == len(network.edges)
    q = {tuple(sorted(e)): m.edge_attribute(e, "q") for e in edges}
    assert [q[tuple(e)] for e in network.edges.tolist()] == network.q.tolist()
    np.testing.assert_array_equal(m.vertices_attribute("z"), network.vertices[:, 2])
    np.testing.assert_array_equal(m.vertices_attribute("pz"), network.loads)
    assert sorted(m.vertices_where(is_support=True)) == np.flatnonzero(network.anchors).tolist()


def test_compas_tna_vertical_equilibrium_gives_vaultgrams_heights(network, tmp_path):
    """The exported form diagram loads as compas_tna's FormDiagram; its vertical equilibrium from the
    force densities and the loads, heights of the free vertices reset, reproduces vaultgram's."""
    form = reloaded(to_formdiagram(network), FormDiagram, tmp_path)
    assert form.number_of_vertices() == len(network.vertices)
    assert form.number_of_faces() == len(network.form.faces)
    assert len(list(form.faces_where(_is_loaded=False))) == len(network.form.opening_faces) == 1
    assert len(list(form.edges_where(_is_edge=True))) == len(network.edges)
    free = list(form.vertices_where(is_support=False))
    form.vertices_attribute("z", 0.0, keys=free)
    vertical_from_q(form, scale=1.0, density=0.0)
    z = np.array([form.vertex_attribute(k, "z") for k in range(len(network.vertices))])
    assert np.abs(z - network.vertices[:, 2]).max() <= 1e-9 * network.vertices[:, 2].max()
    assert np.abs(z[free]).min() > 0  # they were recomputed
    x, faces, supports = from_compas_mesh(form)  # as a pattern: its loaded faces, its supports
    assert faces == [list(f) for f in network.faces] and supports == np.flatnonzero(network.anchors).tolist()


def test_same_object_same_json(network):
    assert compas_json(to_compas_mesh(network)) == compas_json(to_compas_mesh(network))
    assert '"guid"' not in compas_json(to_formdiagram(network))


def test_not_a_mesh_is_an_error():
    from compas.datastructures import Graph

    graph = {"dtype": "compas.datastructures/Graph", "data": Graph().__data__}
    with pytest.raises(VaultgramError, match=r"plan.json: not a COMPAS mesh \(Graph\)"):
        from_compas_mesh(graph, "plan.json")
    with pytest.raises(VaultgramError, match=r"not a COMPAS mesh \(a JSON object without 'dtype'\)"):
        from_compas_mesh({"vertices": []})
