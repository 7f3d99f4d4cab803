"""Boundary singular vertices by cause (issue 12, What 1-3; results in benchmarks/README.md).

Run: ``python benchmarks/boundary_causes.py [--plans-file /work/plans700.json] [--first N] [--only I ...]
[--jagged] [--json FILE]``

Each plan is decomposed and meshed as ``vaultgram mesh`` does (:func:`vaultgram.meshpipeline.decompose`,
:func:`~vaultgram.meshpipeline.mesh_decomposition`); every boundary singular vertex of the mesh
(:func:`vaultgram.meshing.quality.mesh_stats` with the domain: faces other than the regular number for
its angle in the mesh, issue 12's rule) is matched to the nearest boundary point of the final
decomposition graph and described by: its angle class, its faces against the regular number, hole or
outer ring, polygon corner or not, the number of patches it is the corner of, and, for a corner of
225-360 degrees with too few faces, the first reason the reflex rules refused it
(:func:`why_reflex`, the tests of ``topology.reflex.choose_chord`` and ``choose_cut`` redone with the refusal
kept). The table counts the vertices by (class, faces, patches, reason).
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


def angle_class(theta: float) -> str:
    """Issue 12's classes of a boundary vertex by its interior angle (degrees)."""
    for limit, name in ((135, "<135"), (165, "135-165"), (195, "165-195"), (225, "195-225"), (315, "225-315")):
        if theta < limit:
            return name
    return ">=315"


def _chord_refusal(graph, r: int) -> str:
    """Why no chord of the corner ``r`` of two or more patches qualified (``reflex.widest_chord``'s
    tests in order over every candidate, those into a feature's fan too, the most advanced refusal):
    ``ratio`` (a candidate passed the angles, the edge group was uneven: beyond ``reflex.MAX_RATIO``,
    or ``HOLE_MAX_RATIO`` at a hole corner), ``pole`` (the triangle's angle too wide for its split),
    ``angle W`` (the widest worst angle W, in 5 degree bins), ``no candidate`` (no target: every
    strip refused or the chord leaves the quad) or ``not quads`` (a patch not found or no quad)."""
    from vaultgram.topology import reflex
    from vaultgram.topology.corners import boundary_angle
    from vaultgram.topology.strips import patch_sides
    from vaultgram.topology.types import PATCH_CORNER

    patches = sorted({graph.ends(e)[0] for e in graph.incident(r, [PATCH_CORNER])})
    found = [patch_sides(graph, p) for p in patches]
    if any(f is None for f in found):
        return "patch not found"
    angles = [reflex.patch_corner(graph, s, s.corners.index(r))[2] for s in found]
    theta = boundary_angle(graph, r)
    best_angle, ratio, pole, targets = -1.0, False, False, 0
    for i, (p, sides) in enumerate(zip(patches, found)):
        if len(sides.corners) != 4:
            continue
        k = sides.corners.index(r)
        other = reflex.other_angle(theta, angles, i)
        for j in (1, 2):
            candidates = reflex.chord_targets(graph, p, sides, k, j) + reflex.chord_targets(graph, p, sides, k, j,
                                                                                  fans=reflex.MIN_FAN_HALF)
            for kind, target, point, tangent, fraction in candidates:
                targets += 1
                worst, pole_angle = reflex.chord_angles(graph, sides, k, j, point, tangent, other)
                least = reflex.MIN_ANGLE if fraction in (0.5, None) else reflex.MIN_CUT_ANGLE
                if worst < least:
                    best_angle = max(best_angle, worst)
                elif pole_angle > reflex.MAX_POLE_ANGLE:
                    pole = True
                else:
                    ratio = True
    if ratio:
        return "ratio"
    if pole:
        return "pole"
    if targets:
        return f"angle {5 * math.floor(best_angle / 5):.0f}-{5 * math.floor(best_angle / 5) + 5:.0f}"
    return "no candidate" if any(len(s.corners) == 4 for s in found) else "no quad"


def _cut_refusal(graph, r: int) -> str:
    """Why the reflex corner ``r`` inside a patch side got no cut (``reflex.choose_cut``'s tests in order)."""
    from vaultgram.topology import reflex
    from vaultgram.topology.strips import patch_across, patch_sides, side_edge, strip_walk

    at = reflex.on_side(graph, r)
    if at is None:
        return "side not found"
    patch, i = at
    found = patch_sides(graph, patch)
    if len(found.corners) != 4:
        return "side of a triangle"
    edge = side_edge(graph, patch, found.corners[(i + 2) % 4])
    if edge < 0:
        return "opposite side not one edge"
    if reflex.strip_beyond(graph, patch, edge) is None:
        beyond = patch_across(graph, patch, edge)
        walk = None if beyond is None else strip_walk(graph, beyond[0], beyond[1], frozenset([patch]))
        if walk is None:
            return "strip walk fails"
        end = walk.end
        if graph.get(end, "feature"):
            return "strip ends at a feature"
        return f"strip ends at a {graph.node_type(end)}"
    return "cut angle"


def why_reflex(graph, r: int) -> str:
    """The reflex rules' refusal at the boundary point ``r`` (see :func:`_chord_refusal`)."""
    from vaultgram.topology.types import PATCH_CORNER

    if graph.get(r, "feature"):
        return "feature"
    if graph.degree(r, [PATCH_CORNER]) == 0:
        return "on side: " + _cut_refusal(graph, r)
    return "chord: " + _chord_refusal(graph, r)


def _graph_points(graph):
    """The boundary points of the decomposition graph: ids, positions, ring index."""
    from vaultgram.topology.corners import ring_place
    from vaultgram.topology.types import BOUNDARY_VERTEX

    ids = [n for n in graph.nodes() if graph.schema.is_subtype(graph.node_type(n), BOUNDARY_VERTEX)]
    pos = np.array([graph.get(n, "pos") for n in ids], dtype=float)
    return ids, pos, [ring_place(graph, n)[0] for n in ids]


def plan_rows(domain, spacing: float) -> tuple[dict, list]:
    """Mesh one plan; its stats and one row per boundary singular vertex."""
    from vaultgram.geometry.polygons import regular_valence
    from vaultgram.meshing.quality import mesh_stats
    from vaultgram.meshpipeline import decompose, mesh_decomposition
    from vaultgram.topology.corners import boundary_angle
    from vaultgram.topology.types import PATCH_CORNER

    dec = decompose(domain, spacing)
    mesh = mesh_decomposition(dec)
    stats = mesh_stats(mesh, domain)
    graph = dec.graph
    ids, pos, rings = _graph_points(graph)
    x = np.asarray(mesh.vertices, dtype=float)[:, :2]
    rows = []
    for v, theta, val, reg in zip(stats["boundary_singular_vertices"], stats["boundary_singular_angles"],
                                  stats["boundary_singular_valences"], stats["boundary_singular_regular_valences"]):
        d = np.hypot(*(pos - x[v]).T)
        n = ids[int(d.argmin())]
        plan_angle = boundary_angle(graph, n)
        corner = abs(plan_angle - 180.0) > 15.0 and d.min() < 1e-6 * domain.diagonal + 1e-9
        faces, regular = val - 1, reg - 1
        row = {"angle": round(theta, 1), "plan_angle": round(plan_angle, 1), "class": angle_class(theta),
               "faces": faces, "regular": regular, "ring": "hole" if rings[int(d.argmin())] else "outer",
               "corner": bool(corner), "patches": graph.degree(n, [PATCH_CORNER]) if corner else -1}
        if corner and faces < regular and regular_valence(plan_angle) >= 4:  # the rules' tie: 225 is reflex
            row["why"] = why_reflex(graph, n)
        rows.append(row)
    return stats, rows


def key(row: dict) -> tuple:
    """The table's grouping of a row."""
    few = "few" if row["faces"] < row["regular"] else "many"
    where = f"{row['patches']} patches" if row["corner"] else "not a corner"
    return row["class"], few, row["ring"], where, row.get("why", "")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plans-file", type=Path, default=Path("/work/plans700.json"))
    ap.add_argument("--first", type=int, default=None)
    ap.add_argument("--only", type=int, nargs="+", default=None, help="these plan indices only")
    ap.add_argument("--jagged", action="store_true", help="the four jagged plans instead")
    ap.add_argument("--json", type=Path, default=None, help="write every row (with its plan) here")
    args = ap.parse_args()
    sys.path.insert(0, str(REPO / "src"))
    from vaultgram.domain import domain_from_dict
    from vaultgram.errors import VaultgramError
    from vaultgram.testing.jagged import jagged_plans

    if args.jagged:
        plans = [(name, data, 0.02) for name, data in jagged_plans().items()]
    else:
        plans = [(str(i), d, s) for i, (d, s) in enumerate(json.loads(args.plans_file.read_text()))]
    plans = plans[:args.first] if args.first else plans
    plans = [plans[i] for i in args.only] if args.only else plans
    table, every, worst = collections.Counter(), [], []
    for name, data, spacing in plans:
        try:
            stats, rows = plan_rows(domain_from_dict(data), spacing)
        except VaultgramError as exc:
            print(f"{name}: {str(exc)[:100]}", file=sys.stderr)
            continue
        if stats["inverted_faces"]:
            continue
        worst.append(stats["min_scaled_jacobian"])
        for row in rows:
            table[key(row)] += 1
            every.append({"plan": name, **row})
        print(f"{name}: bs {stats['boundary_singular']} min {stats['min_scaled_jacobian']:.3f}", file=sys.stderr)
    for k, c in sorted(table.items(), key=lambda kc: -kc[1]):
        print(f"{c:4d}  " + " | ".join(k))
    w = np.array(worst)
    print(f"total {sum(table.values())}, plans with any {len({r['plan'] for r in every})}, valid {len(w)}, "
          f"under 0.1 {(w < 0.1).sum()}, under 0.3 {(w < 0.3).sum()}, mean min {w.mean():.4f}")
    if args.json:
        args.json.write_text(json.dumps(every, indent=0))


if __name__ == "__main__":
    main()
