"""vaultgram's quad meshes beside gmsh's on the same plans (the issue "pattern quality on real plans").

Run: ``pip install '.[gmsh]'`` then ``python benchmarks/quality_vs_gmsh.py [NAME ...]``. For every
shared plan (``../shared/data/architecture``), example and rectilinear plan of
:data:`vaultgram.testing.orthogonal.RECTILINEAR_PLANS`, meshes the domain's rings

* with vaultgram at the default settings (target edge length 2.5% of the bounding-box diagonal);
* with gmsh at the same target length (``Mesh.MeshSizeMin = MeshSizeMax``), Frontal-Delaunay for
  quads (``Mesh.Algorithm = 8``) with Blossom recombination (``Mesh.RecombinationAlgorithm = 1``);
* with gmsh's quasi-structured quad mesher QuadQS (``Mesh.Algorithm = 11``);

and prints for each: interior and boundary singular vertices (vaultgram's :func:`mesh_stats` on every
mesh, so the same counting rule: the regular valence of the angle), min and mean scaled Jacobian and
the meshing time. gmsh sees the rings only (point and curve features are left out: it has no
counterpart of vaultgram's poles), so plans with features compare the boundary alone. A gmsh mesh
read with inverted or degenerate faces (QuadQS on plans with holes, as this script reads it: the
faces are not those of one consistent surface mesh -- to be checked) is shown as unread, and the
totals are over the plans where all three meshes were read. Timings are wall-clock and noisy on a
shared machine: note the load printed.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
from pattern_quality import plans

from vaultgram.domain import Domain
from vaultgram.errors import VaultgramError
from vaultgram.io.meshfiles import mesh_from_json
from vaultgram.meshing.densities import TARGET_FRACTION
from vaultgram.meshing.quality import mesh_stats
from vaultgram.pipeline import mesh_domain

MESHERS = {"gmsh-blossom": (8, 1), "gmsh-quadqs": (11, 1)}  # Mesh.Algorithm, Mesh.RecombinationAlgorithm


def gmsh_mesh(domain: Domain, size: float, algorithm: int, recombination: int) -> tuple[np.ndarray, list]:
    """The domain's rings meshed by gmsh with quads at the target ``size``: vertices (n, 2) and faces
    (counter-clockwise index lists)."""
    import gmsh

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Verbosity", 0)
        loops = []
        for ring in domain.rings:
            pts = [gmsh.model.occ.addPoint(float(x), float(y), 0.0) for x, y in ring]
            lines = [gmsh.model.occ.addLine(pts[k], pts[(k + 1) % len(pts)]) for k in range(len(pts))]
            loops.append(gmsh.model.occ.addCurveLoop(lines))
        gmsh.model.occ.addPlaneSurface(loops)
        gmsh.model.occ.synchronize()
        for name, value in (("Mesh.MeshSizeMin", size), ("Mesh.MeshSizeMax", size), ("Mesh.Algorithm", algorithm),
                            ("Mesh.RecombinationAlgorithm", recombination), ("Mesh.RecombineAll", 1)):
            gmsh.option.setNumber(name, value)
        gmsh.model.mesh.generate(2)
        return _mesh_arrays(gmsh)
    finally:
        gmsh.finalize()


def _mesh_arrays(gmsh) -> tuple[np.ndarray, list]:
    """The generated 2D mesh: used nodes renumbered from 0, triangles and quads turned counter-clockwise."""
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = {int(t): k for k, t in enumerate(tags)}
    x = np.asarray(coords, dtype=float).reshape(-1, 3)[:, :2]
    faces = []
    for etype, _, nodes in zip(*gmsh.model.mesh.getElements(2)):
        width = {2: 3, 3: 4}.get(int(etype))
        if width:
            faces += [[index[int(n)] for n in row] for row in np.asarray(nodes).reshape(-1, width)]
    faces = [f if _area(x[f]) > 0 else f[::-1] for f in faces]
    return x, faces


def _area(p: np.ndarray) -> float:
    """Signed area of a polygon."""
    return 0.5 * float(np.dot(p[:, 0], np.roll(p[:, 1], -1)) - np.dot(np.roll(p[:, 0], -1), p[:, 1]))


def row(stats: dict, seconds: float) -> str:
    """Interior / boundary singular vertices, min and mean scaled Jacobian, time."""
    return (f"{stats['interior_singular']:4d} {stats['boundary_singular']:4d} {stats['min_scaled_jacobian']:6.3f} "
            f"{stats['mean_scaled_jacobian']:6.3f} {seconds:6.2f}")


def compare(domain: Domain) -> list[str]:
    """The table cells of one plan: vaultgram, then each gmsh mesher."""
    start = time.perf_counter()
    mesh = mesh_domain(domain, allow_folds=True)
    cells = [row(mesh_stats(mesh, domain), time.perf_counter() - start)]
    size = TARGET_FRACTION * domain.diagonal
    for algorithm, recombination in MESHERS.values():
        start = time.perf_counter()
        x, faces = gmsh_mesh(domain, size, algorithm, recombination)
        seconds = time.perf_counter() - start
        other = mesh_from_json({"vertices": np.column_stack([x, np.zeros(len(x))]).tolist(), "faces": faces})
        stats = mesh_stats(other, domain)
        cells.append(row(stats, seconds) if stats["min_scaled_jacobian"] > 0 else f"{'unread':^30s}")
    return cells


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("names", nargs="*", help="plans to compare (default all)")
    args = ap.parse_args()
    print(f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    cell = " int  bnd  minSJ meanSJ time s "
    print(f"{'':28s}|" + "|".join(f"{m:^{len(cell)}s}" for m in ["vaultgram", *MESHERS]))
    print(f"{'plan':28s}|" + "|".join([cell] * (1 + len(MESHERS))))
    totals = np.zeros(3, dtype=int)
    for name, domain in plans().items():
        if args.names and name not in args.names:
            continue
        try:
            cells = compare(domain)
        except VaultgramError as exc:
            print(f"{name:28s}| error: {str(exc).splitlines()[0][:80]}")
            continue
        if not any("unread" in c for c in cells):
            totals += [sum(int(v) for v in c.split()[:2]) for c in cells]
        print(f"{name:28s}|" + "|".join(f" {c} " for c in cells), flush=True)
    print("singular vertices in total (interior + boundary, plans where all were read): "
          + ", ".join(f"{m} {t}" for m, t in zip(["vaultgram", *MESHERS], totals)))


if __name__ == "__main__":
    main()
