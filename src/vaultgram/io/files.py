"""Reading input files with clear errors, and writing outputs (JSON, OBJ) atomically.

Outputs are written to a temporary file in the destination folder and renamed into place, so a
failed or interrupted run never leaves a half-written file behind; JSON is written with sorted keys
so the same result gives byte-identical files.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Sequence

import numpy as np

from vaultgram.errors import VaultgramError


def read_json(path: str | Path):
    """Read a JSON file, turning every failure into a VaultgramError that names the file and place."""
    try:
        text = Path(path).read_text()
    except OSError as exc:
        raise VaultgramError(f"{path}: cannot read: {exc.strerror}") from None
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise VaultgramError(f"{path}:{exc.lineno}:{exc.colno}: invalid JSON: {exc.msg}") from None


def write_text(path: str | Path, text: str) -> None:
    """Write text atomically: to a temporary file in the same folder, then rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text)
    tmp.replace(path)


def write_json(path: str | Path, data) -> None:
    """Write JSON atomically, keys sorted (deterministic bytes)."""
    write_text(path, json.dumps(data, indent=1, sort_keys=True))


def _obj_vertices(vertices: np.ndarray) -> list[str]:
    v = np.asarray(vertices, dtype=float)
    if v.shape[1] == 2:
        v = np.column_stack([v, np.zeros(len(v))])
    return [f"v {x:.12g} {y:.12g} {z:.12g}" for x, y, z in v.tolist()]


def _obj_faces(faces) -> list[str]:
    return ["f " + " ".join(str(int(i) + 1) for i in f) for f in faces]


def write_obj(path: str | Path, vertices: np.ndarray, faces: Sequence[Sequence[int]],
              edges: Sequence[Sequence[int]] | None = None) -> None:
    """Write a Wavefront OBJ file (1-based indices); ``edges`` become ``l`` lines if given."""
    lines = ["# vaultgram", *_obj_vertices(vertices), *_obj_faces(faces)]
    if edges is not None:
        lines += [f"l {int(a) + 1} {int(b) + 1}" for a, b in edges]
    write_text(path, "\n".join(lines) + "\n")


def write_obj_objects(path: str | Path, vertices: np.ndarray, objects) -> None:
    """Write an OBJ file of named objects over one vertex list: ``objects`` is a sequence of
    ``(name, faces)``, each object an ``o name`` line followed by its faces (1-based indices)."""
    lines = ["# vaultgram", *_obj_vertices(vertices)]
    for name, faces in objects:
        lines.append(f"o {name}")
        lines += _obj_faces(faces)
    write_text(path, "\n".join(lines) + "\n")
