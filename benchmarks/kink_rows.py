"""How the mesh rows are spaced at a plan's reflex outline corners (issues 12 and 18; results in benchmarks/README.md).

Run: ``python benchmarks/kink_rows.py [PLAN] [--faces N ...] [--turn DEG] [--json FILE]``

``PLAN``: a shared plan's name or a JSON file (default ``multiple_lobes``); ``--faces``: the faces asked,
each meshed as ``mesh_domain(domain, 0.02, target_length=sqrt(area / N))`` (the heights test's
meshes; default 10,000 / 20,000 / 100,000). A reflex corner: an outline point turning inwards by more
than ``--turn`` degrees (20, as the heights test's notch corners).

Uniform smoothing pulls the rows of the welded Coons grid onto a reflex kink of a patch side (the
discrete harmonic map's corner singularity; s24-pinch), which ``smoothing.kink_offsets`` (s25-kink)
prevents. Per corner and mesh this prints, with ``L = sqrt(area / N)``: the nearest other mesh vertex
and nearest interior vertex over ``L``; the mesh edges (not at the corner's own vertex) that pass
within 1 cm / 1 mm of the corner (a pinch: rows converging onto it); and the face areas over the
median face area by the faces' centroid distance from the corner (0-0.1 / 0.1-0.25 / 0.25-0.5 /
0.5-1 m; min and mean); then the faces under a tenth of the median area, in all and within 1 m of
a reflex corner. A mesh whose rows do not pinch keeps the nearest interior vertex near ``0.5-0.9 L``
at every resolution and no edge within millimetres.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
#: The face centroids' distance bands from a corner, metres.
BANDS = ((0.0, 0.1), (0.1, 0.25), (0.25, 0.5), (0.5, 1.0))


def reflex_corners(outer, turn: float = 20.0) -> np.ndarray:
    """Indices of the points of the counter-clockwise ring ``outer`` where it turns inwards (clockwise)
    by more than ``turn`` degrees.

    >>> reflex_corners([(0, 0), (2, 0), (2, 2), (1, 2), (1, 1), (0, 1)]).tolist()   # an L
    [4]
    """
    o = np.asarray(outer, dtype=float)
    a, b = o - np.roll(o, 1, axis=0), np.roll(o, -1, axis=0) - o
    turning = np.degrees(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(axis=1)))
    return np.flatnonzero(turning < -turn)


def segment_distances(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from the point ``p`` to each segment ``a[i] b[i]``.

    >>> segment_distances(np.zeros(2), np.array([[1.0, -1.0], [2.0, 0.0]]), np.array([[1.0, 1.0], [3.0, 0.0]])).tolist()
    [1.0, 2.0]
    """
    d = b - a
    t = np.clip(((p - a) * d).sum(axis=1) / np.maximum((d * d).sum(axis=1), 1e-300), 0.0, 1.0)
    return np.linalg.norm(a + t[:, None] * d - p, axis=1)


def corner_rows(x: np.ndarray, faces, boundary: np.ndarray, corners: np.ndarray, length: float) -> list[dict]:
    """Per corner point (in the mesh's frame), the row measures of the module docstring, lengths over
    ``length``; plus the small faces' counts (last dict, key ``"small"``)."""
    from vaultgram.geometry.meshes import corner_arrays

    face, u, v, _ = corner_arrays(faces)
    n = len(faces)
    area = 0.5 * np.bincount(face, x[u, 0] * x[v, 1] - x[v, 0] * x[u, 1], minlength=n)
    centroid = np.column_stack([np.bincount(face, x[u, k], minlength=n) for k in (0, 1)])
    centroid /= np.bincount(face, minlength=n)[:, None]
    median = float(np.median(area))
    edges = np.unique(np.sort(np.column_stack([u, v]), axis=1), axis=0)
    rows = []
    for c in corners:
        gap = np.linalg.norm(x - c, axis=1)
        k = int(np.argmin(gap))
        other = edges[(edges[:, 0] != k) & (edges[:, 1] != k)]
        lines = segment_distances(c, x[other[:, 0]], x[other[:, 1]])
        gap[k] = np.inf
        far = np.linalg.norm(centroid - c, axis=1)
        bands = [area[(far >= lo) & (far < hi)] / median for lo, hi in BANDS]
        rows.append({"corner": c.round(3).tolist(), "nearest": float(gap.min() / length),
                     "nearest_interior": float(np.where(boundary, np.inf, gap).min() / length),
                     "lines_1cm": int((lines < 0.01).sum()), "lines_1mm": int((lines < 0.001).sum()),
                     "area_min": [float(b.min()) if len(b) else math.nan for b in bands],
                     "area_mean": [float(b.mean()) if len(b) else math.nan for b in bands]})
    small = area < 0.1 * median
    near = np.min(np.linalg.norm(centroid[:, None] - np.asarray(corners)[None], axis=2), axis=1) < 1.0
    rows.append({"small": int(small.sum()), "small_near": int((small & near).sum()), "faces": n})
    return rows


def _line(row: dict) -> str:
    bands = " ".join(f"{a:.2f}/{m:.2f}" for a, m in zip(row["area_min"], row["area_mean"]))
    return (f"  ({row['corner'][0]:7.2f}, {row['corner'][1]:7.2f})  nearest {row['nearest']:.3f} L, interior "
            f"{row['nearest_interior']:.3f} L; lines within 1 cm {row['lines_1cm']}, 1 mm {row['lines_1mm']}; "
            f"area/median min/mean by band {bands}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("plan", nargs="?", default="multiple_lobes")
    ap.add_argument("--faces", type=int, nargs="+", default=[10000, 20000, 100000])
    ap.add_argument("--turn", type=float, default=20.0)
    ap.add_argument("--json", type=Path, default=None, help="write every row here")
    args = ap.parse_args()
    sys.path.insert(0, str(REPO / "src"))
    sys.path.insert(0, str(REPO / "benchmarks"))
    from benchpaths import ARCHITECTURE

    from vaultgram.domain import load_domain
    from vaultgram.pipeline import mesh_domain

    path = Path(args.plan) if args.plan.endswith(".json") else ARCHITECTURE / f"{args.plan}.json"
    domain = load_domain(path)
    out = {}
    for asked in args.faces:
        length = math.sqrt(domain.area / asked)
        mesh = mesh_domain(domain, 0.02, target_length=length)
        outer = np.asarray(domain.outer, dtype=float)
        corners = outer[reflex_corners(outer, args.turn)] - np.asarray(mesh.origin)[:2]
        rows = corner_rows(np.asarray(mesh.vertices, dtype=float), mesh.faces, mesh.boundary, corners, length)
        for row in rows[:-1]:
            row["corner"] = (np.asarray(row["corner"]) + np.asarray(mesh.origin)[:2]).round(3).tolist()
        s = rows[-1]
        print(f"{path.stem} {asked} asked, {s['faces']} faces, L {length:.3f} m: faces under a tenth of the median "
              f"area {s['small']} ({s['small_near']} within 1 m of a reflex corner)")
        for row in rows[:-1]:
            print(_line(row))
        out[asked] = rows
    if args.json:
        args.json.write_text(json.dumps(out, indent=0))


if __name__ == "__main__":
    main()
