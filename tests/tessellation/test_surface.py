"""The thrust surface read for tessellation: bad networks are one clear error naming the element."""

import json

import numpy as np
import pytest
from click.testing import CliRunner

from vaultgram.cli import main
from vaultgram.errors import TessellationError
from vaultgram.geometry.meshes import Faces, corner_arrays
from vaultgram.tessellation.surface import _checked_faces, surface_from_json

SQUARE = {"vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 1], [0, 1, 0], [2, 0, 0], [2, 1, 0]],
          "faces": [[0, 1, 2, 3], [1, 4, 5, 2]], "anchors": [0, 3, 4, 5]}


def test_a_valid_network_reads_with_its_supports_and_holes():
    s = surface_from_json(SQUARE)
    assert s.supported.tolist() == [True, False, False, True, True, True]
    assert s.holes == 0 and s.edges.n_edges == 7


@pytest.mark.parametrize("change, message", [
    ({"vertices": [[0, 0], [1, 0], [1, 1], [0, 1], [2, 0], [2, 1]]}, "no heights"),
    ({"faces": [[0, 1, 2, 3], [1, 4, 5, 9]]}, "face 1 names vertex 9"),
    ({"faces": [[0, 1, 2, 3], [1, 4, 4, 2]]}, "face 1 repeats a vertex"),
    ({"faces": [[0, 1, 2, 3], [2, 5, 4, 1]]}, "traversed in the same direction by faces 0 and 1"),
    ({"faces": [[0, 1]]}, "face 0 has 2 vertices"),
    ({"anchors": [7]}, "support names a vertex outside"),
    ({"vertices": [[0, 0, 0], [1, 0, 0], [1, 1, float("nan")], [0, 1, 0], [2, 0, 0], [2, 1, 0]]}, "vertex 2"),
])
def test_bad_networks_are_named(change, message):
    with pytest.raises(TessellationError, match=message):
        surface_from_json({**SQUARE, **change})


def test_a_pinched_mesh_is_not_manifold():
    data = {"vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [2, 1, 0], [2, 2, 0], [1, 2, 0], [0, 1, 0]],
            "faces": [[0, 1, 2, 6], [2, 3, 4, 5]]}
    with pytest.raises(TessellationError, match="manifold"):
        surface_from_json(data)


@pytest.mark.parametrize("args, message", [
    ([], "no heights"),
    (["--rhythm", "3"], "'3' is not one of '2', '4'"),
    (["--thickness", "-1"], "-1"),
    (["--max-concavity", "170"], "170"),
])
def test_the_command_refuses_bad_input_in_one_line_and_writes_nothing(tmp_path, args, message):
    path = tmp_path / "thrust.json"
    data = SQUARE if args else {**SQUARE, "vertices": [p[:2] for p in SQUARE["vertices"]]}
    path.write_text(json.dumps(data))
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["tessellate", str(path), "--out", str(out), *args])
    assert result.exit_code == 2
    assert message in result.output
    assert not out.exists()
    if not args:
        assert len(result.output.strip().splitlines()) == 1 and "Traceback" not in result.output


def _faces_one_by_one(faces, n):
    """What ``_checked_faces`` gives for plain lists (its face-by-face check), or the error's text."""
    try:
        return _checked_faces([list(f) for f in faces], n, "net")
    except TessellationError as exc:
        return str(exc)


@pytest.mark.parametrize("seed", range(6))
def test_faces_checked_at_once_are_the_faces_checked_one_by_one(seed):
    """A thrust network's :class:`Faces` are checked as arrays: on random faces, some with a repeated,
    a missing or an out-of-range vertex, the same tuples of Python ints (or the same error) as the
    check face by face."""
    rng = np.random.default_rng(seed)
    n = 12
    faces = [tuple(int(v) for v in rng.choice(n, size=int(rng.integers(3, 6)), replace=False)) for _ in range(40)]
    bad = [faces, faces[:5] + [(1, 2, 1)] + faces[5:], faces + [(0, 1)], faces[:7] + [(3, 4, n)], [(0, -1, 2)]]
    for case in bad[seed % len(bad):] + bad[:seed % len(bad)]:
        expected = _faces_one_by_one(case, n)
        try:
            got = _checked_faces(Faces(case), n, "net")
        except TessellationError as exc:
            got = str(exc)
        assert got == expected
        if not isinstance(got, str):
            assert isinstance(got, Faces) and all(type(v) is int for f in got for v in f)
            assert np.array_equal(corner_arrays(got)[1], corner_arrays(list(case))[1])
    assert not isinstance(_faces_one_by_one(faces, n), str)  # the valid case was one of them
