"""vaultgram's quad meshes beside gmsh's on the same plans, at the same target edge length.

Run: ``python benchmarks/quality_vs_gmsh.py [--plans shared,examples,rectilinear,jagged,smooth] [--json FILE]``
(needs ``pip install 'vaultgram[gmsh]'``).

For each plan vaultgram meshes with its defaults (:func:`vaultgram.pipeline.mesh_domain`); gmsh then
meshes the same rings, with the point features embedded as mesh points and the curve features as
mesh lines (features on the boundary are left to the boundary's mesh), at vaultgram's mean edge
length, with two of its quad meshers (each run in a process of its own: QuadQS can abort the
process on a plan it cannot mesh, which is then reported as gmsh's failure):

* ``frontal``: Frontal-Delaunay for quads (``Mesh.Algorithm = 8``) and Blossom recombination;
* ``quadqs``: the quasi-structured quad mesher QuadQS (``Mesh.Algorithm = 11``).

Both meshes are measured by the same function, :func:`vaultgram.meshing.quality.mesh_stats` with
the domain (so boundary singularities count by the same corner-angle rule): interior and boundary
singular vertices (feature points, poles on purpose, counted apart), triangles left, min and mean
scaled Jacobian, and the meshing wall time (for vaultgram from the domain: topology, rules, Coons
patches and smoothing; for gmsh its ``generate(2)``). The summary checks the issue's floors:
vaultgram has fewer singular vertices (interior + boundary) than QuadQS on every plan, and at most
a third of QuadQS's total over all plans.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from benchpaths import ARCHITECTURE, EXAMPLES

from vaultgram.domain import domain_from_dict, load_domain
from vaultgram.errors import VaultgramError
from vaultgram.io.meshfiles import mesh_from_json
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import mesh_domain
from vaultgram.testing.jagged import jagged_plans
from vaultgram.testing.orthogonal import RECTILINEAR_PLANS
from vaultgram.testing.smooth import SMOOTH_PLANS

MESHERS = {"frontal": {"Mesh.Algorithm": 8, "Mesh.RecombinationAlgorithm": 1},
           "quadqs": {"Mesh.Algorithm": 11, "Mesh.RecombinationAlgorithm": 1}}


# ---------------------------------------------------------------------------------------------
# Plans
# ---------------------------------------------------------------------------------------------


def plans(kinds: list[str]) -> dict:
    """The plans by name: ``shared`` (every file of the shared architecture data), ``examples``,
    ``rectilinear`` (:data:`vaultgram.testing.orthogonal.RECTILINEAR_PLANS`), ``jagged``
    (:func:`vaultgram.testing.jagged.jagged_plans`) and ``smooth``
    (:data:`vaultgram.testing.smooth.SMOOTH_PLANS`: discs, ovals, an apse, a lens)."""
    out = {}
    if "shared" in kinds and ARCHITECTURE.is_dir():
        out.update({p.stem: load_domain(p) for p in sorted(ARCHITECTURE.glob("*.json"))})
    if "examples" in kinds:
        out.update({p.stem: load_domain(p) for p in sorted(EXAMPLES.glob("*.json"))
                    if not p.stem.startswith("skeleton_")})
    for kind, made in (("rectilinear", RECTILINEAR_PLANS), ("jagged", jagged_plans()), ("smooth", SMOOTH_PLANS)):
        if kind in kinds:
            out.update({name: domain_from_dict(data, name) for name, data in made.items()})
    return out


# ---------------------------------------------------------------------------------------------
# Meshing
# ---------------------------------------------------------------------------------------------


def mean_edge_length(x: np.ndarray, faces) -> float:
    """Mean length of the mesh's edges (each counted once)."""
    pairs = {tuple(sorted((f[i], f[(i + 1) % len(f)]))) for f in faces for i in range(len(f))}
    e = np.array(sorted(pairs))
    return float(np.linalg.norm(x[e[:, 0], :2] - x[e[:, 1], :2], axis=1).mean())


def vaultgram_mesh(domain):
    """vaultgram's mesh of ``domain`` with default options, and its wall time."""
    start = time.perf_counter()
    mesh = mesh_domain(domain)
    return mesh, time.perf_counter() - start


def gmsh_mesh(domain, size: float, options: dict):
    """gmsh's mesh of ``domain``'s rings (features embedded) at element size ``size``: vertices,
    faces (quads and the triangles left) and the time of ``generate(2)``."""
    import gmsh

    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(domain.name)
        loops = [_curve_loop(gmsh, ring, size) for ring in (domain.outer, *domain.holes)]
        surface = gmsh.model.geo.addPlaneSurface(loops)
        inner_points, inner_curves = _inner_features(domain)
        points = [gmsh.model.geo.addPoint(*p, 0, size) for p in inner_points]
        lines = [_polyline(gmsh, c, size) for c in inner_curves]
        gmsh.model.geo.synchronize()
        _embed(gmsh, surface, points, [t for line in lines for t in line])
        for name, value in {"Mesh.RecombineAll": 1, "Mesh.MeshSizeFromCurvature": 0, **options}.items():
            gmsh.option.setNumber(name, value)
        start = time.perf_counter()
        gmsh.model.mesh.generate(2)
        seconds = time.perf_counter() - start
        return (*_mesh_arrays(gmsh), seconds)
    finally:
        gmsh.finalize()


def _inner_features(domain) -> tuple[list, list]:
    """The point features and curve features that do not touch the domain's boundary."""
    import shapely

    boundary = shapely.Polygon(domain.outer, list(domain.holes)).boundary
    tol = 1e-6 * domain.diagonal
    points = [tuple(map(float, p)) for p in np.asarray(domain.points).reshape(-1, 2)
              if shapely.Point(p).distance(boundary) > tol]
    curves = [c for c in domain.curves if shapely.LineString(c).distance(boundary) > tol]
    return points, curves


def gmsh_in_process(domain, size: float, options: dict):
    """:func:`gmsh_mesh` in a process of its own; ``None`` when gmsh fails or aborts."""
    from concurrent.futures import ProcessPoolExecutor
    from concurrent.futures.process import BrokenProcessPool

    with ProcessPoolExecutor(max_workers=1) as pool:
        try:
            result = pool.submit(gmsh_mesh, domain, size, options).result()
        except (BrokenProcessPool, Exception):  # gmsh raises plain Exceptions, or aborts the process
            return None
    return result if result[1] else None


def _curve_loop(gmsh, ring: np.ndarray, size: float) -> int:
    """A closed gmsh curve loop through the ring's vertices."""
    tags = [gmsh.model.geo.addPoint(float(x), float(y), 0, size) for x, y in ring]
    lines = [gmsh.model.geo.addLine(tags[i], tags[(i + 1) % len(tags)]) for i in range(len(tags))]
    return gmsh.model.geo.addCurveLoop(lines)


def _polyline(gmsh, curve: np.ndarray, size: float) -> list[int]:
    """The gmsh lines of an open polyline."""
    tags = [gmsh.model.geo.addPoint(float(x), float(y), 0, size) for x, y in curve]
    return [gmsh.model.geo.addLine(a, b) for a, b in zip(tags, tags[1:])]


def _embed(gmsh, surface: int, points: list[int], lines: list[int]) -> None:
    """Point and curve features become mesh points and mesh lines inside the surface."""
    if points:
        gmsh.model.mesh.embed(0, points, 2, surface)
    if lines:
        gmsh.model.mesh.embed(1, lines, 2, surface)


def _mesh_arrays(gmsh) -> tuple[np.ndarray, list]:
    """The 2D mesh's vertices (renumbered from 0) and its triangles and quads."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = {int(t): i for i, t in enumerate(tags)}
    x = np.asarray(coords).reshape(-1, 3)
    faces = []
    for kind, corners in ((2, 3), (3, 4)):  # gmsh element types: 3-node triangle, 4-node quad
        _, nodes = gmsh.model.mesh.getElementsByType(kind)
        faces += [tuple(index[int(t)] for t in f) for f in np.asarray(nodes).reshape(-1, corners)]
    return x, faces


# ---------------------------------------------------------------------------------------------
# Measures
# ---------------------------------------------------------------------------------------------


def measure(x: np.ndarray, faces, domain, seconds: float, feature_points=None) -> dict:
    """The compared metrics of one mesh (:func:`vaultgram.meshing.quality.mesh_stats`)."""
    mesh = mesh_from_json({"vertices": np.asarray(x)[:, :2].tolist(), "faces": [list(f) for f in faces],
                           "labels": {"feature": feature_points or []}})
    s = mesh_stats(mesh, domain)
    return {"faces": s["faces"], "triangles": s["triangles"], "interior": s["interior_singular"],
            "boundary": s["boundary_singular"], "singular": s["interior_singular"] + s["boundary_singular"],
            "min_sj": round(s["min_scaled_jacobian"], 3), "mean_sj": round(s["mean_scaled_jacobian"], 3),
            "seconds": round(seconds, 3)}


def _feature_vertices(x: np.ndarray, domain) -> list[int]:
    """The mesh vertices at the domain's point features (poles on purpose, counted apart)."""
    pts = np.asarray(domain.points).reshape(-1, 2)
    if not len(pts):
        return []
    d = np.linalg.norm(x[None, :, :2] - pts[:, None, :], axis=2)
    return sorted({int(i) for i in d.argmin(axis=1)})


def compare(name: str, domain) -> dict:
    """One plan: vaultgram's mesh, then gmsh's two at vaultgram's mean edge length."""
    row = {"plan": name}
    try:
        mesh, seconds = vaultgram_mesh(domain)
    except VaultgramError as exc:
        return {**row, "vaultgram_error": str(exc)}
    x = np.asarray(mesh.vertices, dtype=float)
    size = mean_edge_length(x, mesh.faces)
    row["target_length"] = round(size, 4)
    row["vaultgram"] = measure(x, mesh.faces, domain, seconds, np.flatnonzero(mesh.feature).tolist())
    for label, options in MESHERS.items():
        meshed = gmsh_in_process(domain, size, options)
        if meshed is None:
            row[label] = {"error": "gmsh failed"}
            continue
        gx, gfaces, gseconds = meshed
        row[label] = measure(gx, gfaces, domain, gseconds, _feature_vertices(gx, domain))
    return row


def summary(rows: list[dict]) -> dict:
    """Totals over the plans that every mesher meshed, and the issue's floors against QuadQS
    (fewer singular vertices on every plan, where QuadQS has any; at most a third of its total)."""
    names = ("vaultgram", *MESHERS)
    done = [r for r in rows if all("singular" in r.get(k, {}) for k in names)]
    total = {k: sum(r[k]["singular"] for r in done) for k in names}
    v, q = (lambda r: r["vaultgram"]["singular"]), (lambda r: r["quadqs"]["singular"])
    behind = [r["plan"] for r in done if v(r) > q(r) or (v(r) == q(r) and q(r) > 0)]
    return {"plans": len(rows), "compared": len(done),
            "failed": {k: [r["plan"] for r in rows if "singular" not in r.get(k, {})] for k in names},
            "singular_total": total, "not_fewer_than_quadqs": behind, "floor_every_plan": not behind,
            "floor_third": 3 * total["vaultgram"] <= total["quadqs"],
            "seconds": {k: round(sum(r[k]["seconds"] for r in done), 2) for k in names}}


def _cell(label: str, m: dict) -> str:
    if "singular" not in m:
        return f"{label[:5]} failed"
    return (f"{label[:5]} {m['interior']:3d}+{m['boundary']:<3d} sj {m['min_sj']:.2f}/{m['mean_sj']:.2f}"
            f" t{m['triangles']:<3d} {m['seconds']:6.2f}s")


def _line(r: dict) -> str:
    if "vaultgram" not in r:
        return f"{r['plan']:24s} vaultgram error: {r['vaultgram_error']}"
    return f"{r['plan']:24s} " + " | ".join(_cell(k, r[k]) for k in ("vaultgram", *MESHERS))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plans", default="shared,examples,rectilinear,jagged")
    parser.add_argument("--json", type=Path, help="write the rows and the summary here")
    args = parser.parse_args(argv)
    try:
        import gmsh  # noqa: F401
    except ImportError:
        print("quality_vs_gmsh: gmsh is not installed (pip install 'vaultgram[gmsh]')", file=sys.stderr)
        return 2
    rows = []
    for name, domain in plans(args.plans.split(",")).items():
        rows.append(compare(name, domain))
        print(_line(rows[-1]), flush=True)
    result = summary(rows)
    print(json.dumps(result, indent=1))
    if args.json:
        args.json.write_text(json.dumps({"rows": rows, "summary": result}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
