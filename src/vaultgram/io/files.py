"""Reading input files with clear errors, and writing outputs atomically.

Outputs are written to a temporary file in the destination folder and renamed into place, so a
failed or interrupted run never leaves a half-written file behind; JSON is written with sorted keys
so the same result gives byte-identical files.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

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
