"""Mesh files: ``mesh.json`` (vertices, faces, labels, edge groups) and ``mesh.obj``.

:func:`write_mesh` writes both atomically; :func:`read_mesh` reads ``mesh.json`` back, and
:func:`mesh_from_json` accepts any ``{"vertices", "faces"}`` object (a mesh made elsewhere).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from vaultgram.errors import VaultgramError
from vaultgram.io.files import read_json, write_json, write_obj
from vaultgram.meshing.quadmesh import QuadMesh

__all__ = ["mesh_to_json", "mesh_from_json", "write_mesh", "read_mesh"]


def mesh_to_json(mesh: QuadMesh, supports=None) -> dict:
    """``{"vertices": [[x, y, z], ...], "faces": [...], "labels": {...}, "turning": [[v, deg], ...],
    "face_patch": [...], "edge_groups": [...], "info": {...}}``, and ``"supports"`` (the indices of the
    vertices that bear thrust) when given: ``vaultgram formfind mesh.json`` then supports the mesh as
    the domain did."""
    x = np.asarray(mesh.vertices, dtype=float)
    if x.shape[1] == 2:
        x = np.column_stack([x, np.zeros(len(x))])
    tv = np.flatnonzero(mesh.turning != 0)
    return {
        "vertices": x.tolist(),
        "faces": [list(f) for f in mesh.faces],
        "labels": mesh.labels_json(),
        "ring": mesh.ring.tolist(),
        "turning": [[int(k), float(mesh.turning[k])] for k in tv],
        "node": mesh.node.tolist(),
        "face_patch": mesh.face_patch.tolist(),
        "curves": [{"vertices": np.asarray(c).tolist(), "polyline": np.asarray(p).tolist()}
                   for c, p in zip(mesh.curves, mesh.curve_lines)],
        "edge_groups": list(mesh.groups),
        "info": dict(mesh.info),
        **({"supports": np.asarray(supports, dtype=np.int64).tolist()} if supports is not None else {}),
    }


def mesh_from_json(data: dict, where: str = "mesh") -> QuadMesh:
    """A :class:`QuadMesh` from :func:`mesh_to_json` output (or any ``{"vertices", "faces"}`` dict)."""
    try:
        x = np.asarray(data["vertices"], dtype=float)
        faces = [tuple(int(i) for i in f) for f in data["faces"]]
    except (KeyError, TypeError, ValueError) as exc:
        raise VaultgramError(f"{where}: not a mesh (needs 'vertices' and 'faces'): {exc}") from None
    if x.ndim != 2 or x.shape[1] not in (2, 3):
        raise VaultgramError(f"{where}: vertices must be [x, y] or [x, y, z] points")
    n = len(x)
    if any(len(f) not in (3, 4) or min(f) < 0 or max(f) >= n for f in faces):
        raise VaultgramError(f"{where}: faces must be triangles or quads of valid vertex indices")
    labels = data.get("labels", {})

    def mask(name):
        m = np.zeros(n, dtype=bool)
        m[np.asarray(labels.get(name, []), dtype=np.int64)] = True
        return m

    corner = np.zeros(n, dtype=np.int8)
    corner[mask("corner")] = 1
    corner[mask("reflex_corner")] = -1
    turning = np.zeros(n)
    for k, a in data.get("turning", []):
        turning[int(k)] = float(a)
    ring = np.asarray(data.get("ring", [-1] * n), dtype=np.int64)
    node = np.asarray(data.get("node", [-1] * n), dtype=np.int64)
    fp = np.asarray(data.get("face_patch", [-1] * len(faces)), dtype=np.int64)
    try:
        chains = tuple(np.asarray(c["vertices"], dtype=np.int64) for c in data.get("curves", []))
        lines = tuple(np.asarray(c["polyline"], dtype=float).reshape(-1, 2) for c in data.get("curves", []))
    except (KeyError, TypeError, ValueError) as exc:
        raise VaultgramError(f"{where}: 'curves' must be a list of {{'vertices', 'polyline'}}: {exc}") from None
    curve = np.full(n, -1, dtype=np.int64)
    for c, chain in enumerate(chains):
        curve[chain] = c
    return QuadMesh(x[:, :2].copy(), faces, fp, mask("boundary"), ring, corner, turning, mask("fixed"),
                    mask("pole"), mask("feature"), node, mask("singular_node"),
                    tuple(data.get("edge_groups", ())), (), dict(data.get("info", {})),
                    curve, mask("curve_extremity"), chains, lines)


def write_mesh(mesh: QuadMesh, out_dir: str | Path, supports=None) -> tuple[Path, Path]:
    """Write ``out_dir/mesh.json`` (with the supported vertices, if given) and ``out_dir/mesh.obj``
    (each to a temporary file, then renamed)."""
    out = Path(out_dir)
    paths = out / "mesh.json", out / "mesh.obj"
    write_json(paths[0], mesh_to_json(mesh, supports))
    write_obj(paths[1], mesh.vertices, mesh.faces)
    return paths


def read_mesh(path: str | Path) -> QuadMesh:
    """Read a ``mesh.json`` (see :func:`mesh_to_json`)."""
    return mesh_from_json(read_json(path), str(path))
