"""The worst face of each plan's mesh and its cause (issue 12 What 4; results in benchmarks/README.md).

Run: ``python benchmarks/worst_faces.py [--plans-file /work/plans700.json] [--first N | --only I,J,...]
[--jagged] [--without-polish] [--under 0.3] [--json FILE]``

``--jagged`` takes the four jagged outlines of :mod:`vaultgram.testing.jagged` (at spacing 0.02, the
default length) instead of the saved plans; ``--only`` the saved plans of those indices;
``--without-polish`` meshes without :func:`vaultgram.meshing.polish.polish_worst` (as before session 29).

Each plan is meshed as ``reliability.py plans`` does (:func:`vaultgram.pipeline.mesh_domain` at the
plan's spacing). Its worst face (the least :func:`~vaultgram.meshing.quality.face_scaled_jacobians`)
and that face's worst corner are classified by :func:`cause`:

* a triangle by its pole (§3.2: triangles are the fans of three-sided patches round a pole): a fan at
  a curve's free end, at a curve bend or another curve point (§4.2), at an inner or a boundary point
  feature (§4.1), at a boundary or hole corner (with its angle in the mesh), or at an interior pole;
* a quad by its worst corner: at a boundary vertex (its angle and number of faces; a hole's or the
  outer ring's), at a curve point, at a point feature, at an interior singular vertex (its valence),
  or at a regular inner vertex (``skewed quad``; ``along the boundary`` where the face touches it).

Each row also gives :func:`~vaultgram.meshing.fans.fan_bounds` at the classified vertex: the best
scaled Jacobian any placement reaches round it. A worst face near that bound has a layout cause (too
many faces share the vertex's angle), one far below it a smoothing cause. The table counts the
plans under ``--under`` (and under 0.1) by cause, with the median scaled Jacobian and fan bound.
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
#: A curve point whose chain turns by more than this (degrees) is a bend.
BEND = 20.0


def vertex_angles(x: np.ndarray, faces) -> tuple[np.ndarray, np.ndarray]:
    """Per vertex, its angle in the mesh (degrees, the sum of its corners' angles) and its number of faces.

    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> v, f = grid_mesh(2)
    >>> a, n = vertex_angles(v, f)
    >>> a[[0, 1, 4]].round(6).tolist(), n[[0, 1, 4]].tolist()
    ([90.0, 180.0, 360.0], [1, 2, 4])
    """
    from vaultgram.geometry.meshes import corner_angles, corner_arrays

    _, u, v, p = corner_arrays(faces)
    angle = corner_angles(np.asarray(x, dtype=float)[:, :2], u, v, p)
    angle = np.where(angle < 0, angle + 2 * math.pi, angle)
    n = len(x)
    return np.degrees(np.bincount(u, weights=angle, minlength=n)), np.bincount(u, minlength=n)


def worst_corner(x: np.ndarray, face) -> int:
    """The vertex of ``face`` whose corner has the least scaled Jacobian (quads: sine of the angle;
    triangles: scaled so that 60 degrees is 1, the same order).

    >>> worst_corner(np.array([[0, 0], [2, 0], [2.5, 1], [0, 1.5]]), (0, 1, 2, 3))  # 116.6 degrees at 1
    1
    """
    p = np.asarray(x, dtype=float)[list(face), :2]
    e1, e2 = np.roll(p, -1, axis=0) - p, np.roll(p, 1, axis=0) - p
    sine = (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]) / (np.hypot(*e1.T) * np.hypot(*e2.T))
    return int(face[int(np.argmin(sine))])


def curve_turn(x: np.ndarray, chain: np.ndarray, c: int) -> float:
    """How much the curve's chain of mesh vertices turns at its vertex ``c`` (degrees; 0 at an end).

    >>> curve_turn(np.array([[0, 0], [1, 0], [2, 1.0]]), np.array([0, 1, 2]), 1)
    45.0
    """
    k = int(np.flatnonzero(np.asarray(chain) == c)[0])
    if k == 0 or k == len(chain) - 1:
        return 0.0
    a, b = x[chain[k]] - x[chain[k - 1]], x[chain[k + 1]] - x[chain[k]]
    return round(math.degrees(abs(math.atan2(a[0] * b[1] - a[1] * b[0], a @ b))), 6)


def _vertex_kind(mesh, x: np.ndarray, c: int, angle: np.ndarray, count: np.ndarray) -> str:
    """What vertex ``c`` of the mesh is: a curve end or point (a bend where its chain turns by more
    than :data:`BEND`), a point feature, a boundary vertex (hole or outer, with its angle and faces),
    or an inner vertex (with its valence)."""
    curve, extremity = mesh.curve_labels()
    if extremity[c]:
        return "curve free end"
    if curve[c] >= 0:
        chain = mesh.curves[curve[c]]
        if c in (chain[0], chain[-1]):
            return "curve end on the boundary"
        turn = curve_turn(x[:, :2], chain, c)
        return "curve bend" if turn > BEND else "curve point"
    if mesh.feature[c]:
        return "boundary point feature" if mesh.boundary[c] else "inner point feature"
    if mesh.boundary[c]:
        ring = "hole" if mesh.ring[c] > 0 else "outer"
        return f"{ring} {_angle_bin(angle[c])} deg, {count[c]} faces"
    return f"inner valence {count[c]}"


def _angle_bin(theta: float) -> str:
    """Issue 12's classes of a boundary vertex's angle (degrees).

    >>> _angle_bin(100.0), _angle_bin(270.0)
    ('<135', '225-315')
    """
    for limit, name in ((135, "<135"), (165, "135-165"), (195, "165-195"), (225, "195-225"), (315, "225-315")):
        if theta < limit:
            return name
    return ">=315"


def cause(mesh, face_sj: np.ndarray | None = None) -> dict:
    """The worst face of ``mesh`` and its cause (see the module's docstring): the face, its scaled
    Jacobian and size, the classified vertex (a triangle's pole, a quad's worst corner), its kind,
    angle in the mesh, number of faces and fan bound, and the cause's class."""
    from vaultgram.meshing.fans import fan_bounds
    from vaultgram.meshing.quality import face_scaled_jacobians

    x = np.asarray(mesh.vertices, dtype=float)[:, :2]
    sj = face_scaled_jacobians(x, mesh.faces) if face_sj is None else face_sj
    f = int(np.argmin(sj))
    face = tuple(int(v) for v in mesh.faces[f])
    poles = [v for v in face if mesh.pole[v]]
    c = poles[0] if len(face) == 3 and poles else worst_corner(x, face)
    angle, count = vertex_angles(x, mesh.faces)
    kind = _vertex_kind(mesh, x, c, angle, count)
    if len(face) == 3:
        klass = f"triangle: fan at {kind}" if mesh.pole[c] else f"triangle: {kind}"
    elif kind.startswith("inner valence 4"):
        klass = "quad: skewed along the boundary" if mesh.boundary[list(face)].any() else "quad: skewed inside"
    else:
        klass = f"quad: at {kind}"
    return {"face": f, "sj": float(sj[f]), "sides": len(face), "vertex": c, "xy": x[c].round(4).tolist(),
            "kind": kind, "angle": round(float(angle[c]), 2), "faces_at": int(count[c]),
            "worst_at_vertex": worst_corner(x, face) == c,
            "fan_bound": round(float(fan_bounds(x, mesh.faces)[c]), 4), "cause": klass}


def plan_rows(plans: list, first: int | None = None, only=None) -> list:
    """One row per plan (those of index in ``only`` where given; ``plans`` a list of ``(data, spacing)``
    or a dict of them by name): its index or name, spacing, and :func:`cause` of its mesh (or the
    refusal)."""
    from vaultgram.domain import domain_from_dict
    from vaultgram.errors import VaultgramError
    from vaultgram.pipeline import mesh_domain

    rows = []
    items = list(plans.items()) if isinstance(plans, dict) else list(enumerate(plans))
    for i, (data, spacing) in items[:first]:
        if only is not None and i not in only:
            continue
        try:
            rows.append({"plan": i, "spacing": spacing, **cause(mesh_domain(domain_from_dict(data), spacing))})
        except VaultgramError as exc:
            rows.append({"plan": i, "spacing": spacing, "error": str(exc)[:120]})
        print(i, rows[-1].get("sj", "error"), rows[-1].get("cause", ""), file=sys.stderr, flush=True)
    return rows


def table(rows: list, under: float) -> str:
    """The plans whose worst face is under ``under`` (and under 0.1) by cause, most first, with the
    median scaled Jacobian and fan bound of each cause, and how many are at their bound (the worst
    face within 0.05 of the fan bound: a layout cause)."""
    valid = [r for r in rows if "sj" in r and r["sj"] > 0]
    low = [r for r in valid if r["sj"] < under]
    groups = collections.defaultdict(list)
    for r in low:
        groups[r["cause"]].append(r)
    lines = [f"{len(valid)} valid plans; {len(low)} under {under}, {sum(r['sj'] < 0.1 for r in valid)} under 0.1",
             f"| cause | under {under} | under 0.1 | median SJ | median fan bound | at the bound |",
             "|---|---|---|---|---|---|"]
    for name, rs in sorted(groups.items(), key=lambda kv: (-len(kv[1]), kv[0])):
        sj, bound = np.array([r["sj"] for r in rs]), np.array([r["fan_bound"] for r in rs])
        lines.append(f"| {name} | {len(rs)} | {int((sj < 0.1).sum())} | {np.median(sj):.3f} | "
                     f"{np.median(bound):.3f} | {int((bound - sj < 0.05).sum())} |")
    return "\n".join(lines)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plans-file", type=Path, default=Path("/work/plans700.json"))
    parser.add_argument("--first", type=int, default=None)
    parser.add_argument("--under", type=float, default=0.3)
    parser.add_argument("--json", type=Path, default=None, help="write every row here")
    parser.add_argument("--only", type=lambda s: {int(k) for k in s.split(",")}, default=None,
                        help="only the saved plans of these indices (comma-separated)")
    parser.add_argument("--jagged", action="store_true", help="the four jagged outlines instead")
    parser.add_argument("--without-polish", action="store_true", help="mesh without polish_worst")
    args = parser.parse_args(argv)
    if args.without_polish:
        import vaultgram.meshpipeline as pipeline

        pipeline.POLISH_TARGET = 0.0  # a valid mesh's worst face is never under it: never polished
    if args.jagged:
        from vaultgram.testing.jagged import jagged_plans

        plans = {name: (data, 0.02) for name, data in jagged_plans().items()}
    else:
        plans = json.loads(args.plans_file.read_text())
    rows = plan_rows(plans, args.first, args.only)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=0))
    print(table(rows, args.under))


if __name__ == "__main__":
    main()
