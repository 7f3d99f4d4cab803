"""The tessellation's values: the voussoir layout (faces, outlines, joints) and tessellation.json."""

import json

import numpy as np
import orjson
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.geometry.surfaces import area_vectors
from vaultgram.io import numtext
from vaultgram.pipeline import tessellate
from vaultgram.tessellation.keystones import CutMesh
from vaultgram.tessellation.model import _joint_records, voussoir_layout


def test_joints_are_the_inner_edges_between_two_voussoirs():
    v, f = grid_mesh(3, 2)  # faces 0 1 2 below, 3 4 5 above
    v[:, 2] = 0.1 * v[:, 0] * v[:, 1]
    cut = CutMesh(v, tuple(f), np.array([4]), np.arange(len(v)), ())
    me = mesh_edges(f)
    lay = voussoir_layout(cut, me, np.array([0, 0, 1, 2, 3, 1]))
    assert lay.n_voussoirs == 4 and lay.keystones.tolist() == [3]
    pairs = lay.joint_voussoirs()
    assert (pairs[:, 0] != pairs[:, 1]).all()
    assert sorted(map(sorted, pairs.tolist())) == [[0, 1], [0, 2], [0, 3], [1, 3], [2, 3]]
    assert not me.boundary[lay.joints].any()
    area = np.linalg.norm(area_vectors(v, f), axis=1)
    assert lay.areas(v) == pytest.approx([area[0] + area[1], area[2] + area[5], area[3], area[4]])


@pytest.fixture(scope="module")
def tessellation(arch_grid):
    return tessellate(arch_grid, thickness=0.3)


def test_the_json_of_arrays_is_the_json_of_lists(tessellation):
    """``to_json(arrays=True)`` keeps numpy arrays for orjson, which writes them as the same bytes as
    the lists of ``to_json()``: the tessellation, the thrust network and its form and force diagrams."""
    import orjson

    from vaultgram.pipeline import form_find

    network = form_find(*grid_mesh(6), zmax=1.5)
    option = orjson.OPT_SORT_KEYS | orjson.OPT_NON_STR_KEYS | orjson.OPT_SERIALIZE_NUMPY
    for item in (tessellation, network, network.form, network.force):
        arrays = item.to_json(arrays=True)
        assert any(isinstance(v, np.ndarray) for v in arrays.values())
        assert orjson.dumps(arrays, option=option) == orjson.dumps(item.to_json(), option=option)


def test_tessellation_json_is_plain_json_that_describes_the_layout(tessellation):
    data = json.loads(json.dumps(tessellation.to_json()))
    lay = tessellation.layout
    n = lay.n_voussoirs
    assert len(data["voussoirs"]) == len(data["names"]) == len(data["courses"]) == len(data["areas"]) == n
    assert len(data["faces"]) == len(data["face_voussoir"]) == len(lay.mesh.faces)
    assert np.array(data["vertices"]).shape == tessellation.vertices.shape
    assert sum(data["areas"]) == pytest.approx(float(lay.areas(tessellation.vertices).sum()))
    # neighbours are symmetric and are exactly the voussoirs across the joints
    nbrs = data["neighbours"]
    assert all(k in nbrs[o] for k in range(n) for o in nbrs[k])
    across = {tuple(j["voussoirs"]) for j in data["joints"]}
    assert across == {(a, b) for a in range(n) for b in nbrs[a] if a < b}
    for j in data["joints"]:
        a, b = j["voussoirs"]
        for k in (a, b):  # a joint is a side of the outline of both its voussoirs
            loop = data["voussoirs"][k]
            sides = {frozenset(p) for p in zip(loop, loop[1:] + loop[:1])}
            assert frozenset(j["vertices"]) in sides
    assert data["summary"]["voussoirs"] == n


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 40), st.integers(0, 10**7), st.integers(0, 2**31))
def test_joint_records_as_one_fragment_are_the_bytes_of_the_dicts(n, top, seed):
    """tessellation.json's joints written from the arrays (an orjson fragment) are byte for byte the
    records' JSON, numbers of any width, and no joint at all."""
    rng = np.random.default_rng(seed)
    vertices, voussoirs = (rng.integers(0, top + 1, size=(n, 2)) for _ in range(2))
    records = _joint_records(vertices, voussoirs)
    assert orjson.dumps(_joint_records(vertices, voussoirs, arrays=True)) == orjson.dumps(records)
    keyed = [{"joints": j, "a": 1} for j in (_joint_records(vertices, voussoirs, arrays=True), records)]
    assert orjson.dumps(keyed[0], option=orjson.OPT_SORT_KEYS) == orjson.dumps(keyed[1], option=orjson.OPT_SORT_KEYS)


@pytest.mark.parametrize("n", [1, 3, 4, 10])
def test_joint_records_over_several_pieces_are_the_bytes_of_the_dicts(monkeypatch, n):
    """Records made three rows at a time (numtext.ROWS) join into the same JSON."""
    monkeypatch.setattr(numtext, "ROWS", 3)
    rng = np.random.default_rng(n)
    vertices, voussoirs = rng.integers(0, 10**6, size=(n, 2)), rng.integers(0, 12, size=(n, 2))
    records = _joint_records(vertices, voussoirs)
    assert orjson.dumps(_joint_records(vertices, voussoirs, arrays=True)) == orjson.dumps(records)
