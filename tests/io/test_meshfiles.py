"""Pattern files for form finding (vaultgram.io.meshfiles): OBJ with n-gons, and the format by
extension, content or name."""

from __future__ import annotations

import json

import pytest

from vaultgram.errors import VaultgramError
from vaultgram.io.meshfiles import read_obj, read_pattern


def test_obj_faces_with_slashes_negative_indices_and_ngons(tmp_path):
    path = tmp_path / "p.obj"
    path.write_text("# a pentagon and a triangle\nv 0 0 0\nv 1 0 0\nv 1.5 1 0\nv 0.5 1.5 0\nv -0.5 1 0\n"
                    "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4//1 5//1\nv 2 0\nf 2 -1 3\n")
    x, faces = read_obj(path)
    assert x.shape == (6, 3) and x[5].tolist() == [2.0, 0.0, 0.0]
    assert faces == [[0, 1, 2, 3, 4], [1, 5, 2]]
    mesh, supports = read_pattern(path)
    assert [len(f) for f in mesh.faces] == [5, 3] and supports is None


def test_bad_obj_line_is_named(tmp_path):
    path = tmp_path / "bad.obj"
    path.write_text("v 0 0 0\nv 1 x 0\n")
    with pytest.raises(VaultgramError, match=r"bad.obj:2: not an OBJ 'v' line"):
        read_obj(path)
    path.write_text("v 0 0 0\n")
    with pytest.raises(VaultgramError, match="no face"):
        read_obj(path)


def test_json_patterns_by_content_or_name(tmp_path):
    mesh = {"vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "faces": [[0, 1, 2, 3]], "supports": [0, 1]}
    path = tmp_path / "pattern.data"
    path.write_text(json.dumps(mesh))
    assert read_pattern(path) is None  # not .json, no format named: a domain
    for fmt in ("json", "mesh"):
        m, supports = read_pattern(path, fmt)
        assert len(m.faces) == 1 and supports == [0, 1]
    (tmp_path / "plan.json").write_text(json.dumps({"outer": [[0, 0], [1, 0], [1, 1]]}))
    assert read_pattern(tmp_path / "plan.json") is None and read_pattern(tmp_path / "plan.json", "json") is None
