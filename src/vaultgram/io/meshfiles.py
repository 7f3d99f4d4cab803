"""Mesh files: ``mesh.json`` (vertices, faces, labels, edge groups) and ``mesh.obj``.

:func:`write_mesh` writes both atomically; :func:`read_mesh` reads ``mesh.json`` back, and
:func:`mesh_from_json` accepts any ``{"vertices", "faces"}`` object (a mesh made elsewhere).
:func:`read_pattern` reads a pattern for form finding made anywhere: a ``mesh.json``, a Wavefront OBJ
(:func:`read_obj`, n-gon faces kept) or a COMPAS mesh (:mod:`vaultgram.io.compasfiles`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from vaultgram.errors import VaultgramError
from vaultgram.geometry.arrays import json_array
from vaultgram.geometry.frames import local_origin, to_local
from vaultgram.geometry.meshcheck import check_plan_mesh
from vaultgram.geometry.meshes import Faces
from vaultgram.io import strict
from vaultgram.io.files import read_json, write_json, write_obj
from vaultgram.meshing.quadmesh import QuadMesh

__all__ = ["mesh_to_json", "mesh_from_json", "write_mesh", "read_mesh", "read_obj", "read_pattern",
           "PATTERN_FORMATS"]


def mesh_to_json(mesh: QuadMesh, supports=None, arrays: bool = False) -> dict:
    """``{"vertices": [[x, y, z], ...], "faces": [...], "labels": {...}, "turning": [[v, deg], ...],
    "face_patch": [...], "edge_groups": [...], "info": {...}}``, and ``"supports"`` (the indices of the
    vertices that bear thrust) when given: ``vaultgram formfind mesh.json`` then supports the mesh as
    the domain did. In the plan's coordinates (:meth:`QuadMesh.in_frame`). With ``arrays`` the
    vertices, faces and per-vertex and per-face lists stay numpy arrays and tuples, for
    :func:`vaultgram.io.files.write_json` (orjson writes them as the same bytes, without first making
    10^5 Python lists)."""
    mesh = mesh.in_frame()
    x = np.asarray(mesh.vertices, dtype=float)
    if x.shape[1] == 2:
        x = np.column_stack([x, np.zeros(len(x))])
    tv = np.flatnonzero(mesh.turning != 0)
    return {
        "vertices": json_array(x, arrays),
        "faces": list(mesh.faces) if arrays else [list(f) for f in mesh.faces],
        "labels": mesh.labels_json(),
        "ring": json_array(mesh.ring, arrays),
        "turning": [[int(k), float(mesh.turning[k])] for k in tv],
        "node": json_array(mesh.node, arrays),
        "face_patch": json_array(mesh.face_patch, arrays),
        "curves": [{"vertices": np.asarray(c).tolist(), "polyline": np.asarray(p).tolist()}
                   for c, p in zip(mesh.curves, mesh.curve_lines)],
        "edge_groups": list(mesh.groups),
        "info": dict(mesh.info),
        **({"supports": np.asarray(supports, dtype=np.int64).tolist()} if supports is not None else {}),
    }


def mesh_from_json(data: dict, where: str = "mesh", polygons: bool = False) -> QuadMesh:
    """A :class:`QuadMesh` from :func:`mesh_to_json` output (or any ``{"vertices", "faces"}`` dict); with
    ``polygons``, faces of any number of sides (a pattern for form finding), else triangles and quads.

    Validated before use (:mod:`vaultgram.io.strict`, :func:`vaultgram.geometry.meshcheck.check_plan_mesh`):
    strict types (an index is an integer, a coordinate a finite number), indices in range, faces of
    distinct vertices, a manifold and consistently oriented mesh; the error names ``where``, the
    element and its index. A mesh far from the origin comes in its local frame
    (:mod:`vaultgram.geometry.frames`): its ``origin`` says where.
    """
    try:
        return _mesh_from_json(data, polygons)
    except VaultgramError as exc:
        raise VaultgramError(f"{where}: {exc}") from None


def _mesh_from_json(data, polygons: bool) -> QuadMesh:
    """:func:`mesh_from_json` without the file name on errors."""
    data = strict.json_object(data, "mesh")
    for key in ("vertices", "faces"):
        if key not in data:
            raise VaultgramError(f"not a mesh: needs 'vertices' and 'faces' (no '{key}')")
    x = strict.points(data["vertices"], "vertices")
    origin = local_origin(x)  # a mesh in site coordinates is worked on in its local frame
    x = to_local(x, origin)
    n = len(x)
    faces = [tuple(strict.indices(f, n, f"faces[{k}]").tolist())
             for k, f in enumerate(strict.json_list(data["faces"], "faces"))]
    for k, f in enumerate(faces):
        if not polygons and len(f) not in (3, 4):
            raise VaultgramError(f"faces[{k}]: expected a triangle or a quad, got {len(f)} vertices")
    check_plan_mesh(x, faces)
    labels = strict.json_object(data.get("labels", {}), "labels")

    def mask(name):
        m = np.zeros(n, dtype=bool)
        m[strict.indices(labels.get(name, []), n, f"labels.{name}")] = True
        return m

    corner = np.zeros(n, dtype=np.int8)
    corner[mask("corner")] = 1
    corner[mask("reflex_corner")] = -1
    turning = np.zeros(n)
    for k, pair in enumerate(strict.json_list(data.get("turning", []), "turning")):
        if not isinstance(pair, list) or len(pair) != 2:
            raise VaultgramError(f"turning[{k}]: expected [vertex, degrees], got {pair!r}")
        turning[strict.indices(pair[:1], n, f"turning[{k}]")[0]] = strict.finite_number(pair[1], f"turning[{k}][1]")
    ring = _per_item(data, "ring", n, "vertices")
    node = _per_item(data, "node", n, "vertices")
    fp = _per_item(data, "face_patch", len(faces), "faces")
    chains, lines = _curves(data, n)
    curve = np.full(n, -1, dtype=np.int64)
    for c, chain in enumerate(chains):
        curve[chain] = c
    if "supports" in data:
        strict.indices(data["supports"], n, "supports")
    return QuadMesh(x[:, :2].copy(), Faces(faces), fp, mask("boundary"), ring, corner, turning, mask("fixed"),
                    mask("pole"), mask("feature"), node, mask("singular_node"),
                    tuple(strict.json_list(data.get("edge_groups", []), "edge_groups")), (),
                    dict(strict.json_object(data.get("info", {}), "info")), curve, mask("curve_extremity"),
                    chains, tuple(to_local(line, origin) for line in lines), origin)


def _per_item(data: dict, key: str, n: int, of: str) -> np.ndarray:
    """An optional list of one integer per vertex (or face) under ``key``; -1 each when absent."""
    if key not in data:
        return np.full(n, -1, dtype=np.int64)
    values = strict.json_list(data[key], key)
    if len(values) != n:
        raise VaultgramError(f"{key}: expected one integer per {of[:-1]} ({n}), got {len(values)}")
    bad = [k for k, v in enumerate(values) if not strict.is_integer(v)]
    if bad:
        raise VaultgramError(f"{key}[{bad[0]}]: expected an integer, got {values[bad[0]]!r}")
    return np.asarray(values, dtype=np.int64)


def _curves(data: dict, n: int) -> tuple[tuple, tuple]:
    """The curve chains (vertex indices) and polylines of ``data["curves"]``."""
    chains, lines = [], []
    for k, c in enumerate(strict.json_list(data.get("curves", []), "curves")):
        c = strict.json_object(c, f"curves[{k}]")
        if "vertices" not in c or "polyline" not in c:
            raise VaultgramError(f"curves[{k}]: expected {{'vertices', 'polyline'}}")
        chains.append(strict.indices(c["vertices"], n, f"curves[{k}].vertices"))
        lines.append(strict.points(c["polyline"], f"curves[{k}].polyline", (2,)).reshape(-1, 2))
    return tuple(chains), tuple(lines)


def write_mesh(mesh: QuadMesh, out_dir: str | Path, supports=None) -> tuple[Path, Path]:
    """Write ``out_dir/mesh.json`` (with the supported vertices, if given) and ``out_dir/mesh.obj``
    (each to a temporary file, then renamed)."""
    out = Path(out_dir)
    paths = out / "mesh.json", out / "mesh.obj"
    write_json(paths[0], mesh_to_json(mesh, supports, arrays=True))
    write_obj(paths[1], mesh.in_frame().vertices, mesh.faces)
    return paths


def read_mesh(path: str | Path) -> QuadMesh:
    """Read a ``mesh.json`` (see :func:`mesh_to_json`)."""
    return mesh_from_json(read_json(path), str(path))


#: The pattern formats ``vaultgram formfind`` reads besides a domain: vaultgram's ``mesh.json``, OBJ, COMPAS.
PATTERN_FORMATS = ("mesh", "obj", "compas")


def read_obj(path: str | Path) -> tuple[np.ndarray, list]:
    """The vertices ``(n, 3)`` and faces (0-based, n-gons kept) of a Wavefront OBJ file: its ``v`` and
    ``f`` lines (``f 1/1/1 2/2/2 ...`` and negative indices too); other lines are ignored.

    Raises
    ------
    VaultgramError
        A malformed ``v`` or ``f`` line (named by its line number), or no face.
    """
    try:
        lines = Path(path).read_text().splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise VaultgramError(f"{path}: cannot read: {exc}") from None
    vertices, faces = [], []
    for number, line in enumerate(lines, 1):
        parts = line.split()
        try:
            if parts[:1] == ["v"]:
                vertices.append([float(c) for c in parts[1:4]] + [0.0] * (4 - len(parts)))
            elif parts[:1] == ["f"]:
                refs = [int(p.split("/")[0]) for p in parts[1:]]
                faces.append([r - 1 if r > 0 else len(vertices) + r for r in refs])
        except ValueError as exc:
            raise VaultgramError(f"{path}:{number}: not an OBJ '{parts[0]}' line: {exc}") from None
    if not faces:
        raise VaultgramError(f"{path}: no face ('f' line) in the OBJ file")
    return np.array(vertices, dtype=float).reshape(-1, 3), faces


def read_pattern(path: str | Path, input_format: str | None = None):
    """``(mesh, supports)`` of a pattern file for form finding, or None when the file is a domain.

    ``input_format`` is one of :data:`PATTERN_FORMATS`, else chosen by extension (``.obj``) and content
    (``json``, or a ``.json`` file: a JSON object with ``dtype`` is COMPAS data, one with ``vertices``
    and ``faces`` a mesh, anything else a domain). The
    supports are the file's (``mesh.json``'s ``supports``, a COMPAS mesh's ``is_support`` vertices) or
    None (the outer boundary).
    """
    from vaultgram.io.compasfiles import from_compas_mesh

    where = str(path)
    if input_format == "obj" or (input_format is None and where.lower().endswith(".obj")):
        x, faces = read_obj(path)
        return mesh_from_json({"vertices": x.tolist(), "faces": faces}, where, polygons=True), None
    by_content = input_format == "json" or (input_format is None and where.lower().endswith(".json"))
    if input_format not in PATTERN_FORMATS and not by_content:
        return None
    data = read_json(path)
    if input_format == "compas" or (isinstance(data, dict) and "dtype" in data):
        x, faces, supports = from_compas_mesh(data, where)
        mesh = mesh_from_json({"vertices": x.tolist(), "faces": faces}, where, polygons=True)
        return mesh, ({"vertices": supports} if supports else None)
    if input_format == "mesh" or (isinstance(data, dict) and "vertices" in data and "faces" in data):
        return mesh_from_json(data, where), data.get("supports") if isinstance(data, dict) else None
    return None
