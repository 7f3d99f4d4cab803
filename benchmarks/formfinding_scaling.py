"""Scaling of TNA form finding on regular n x n grids (every boundary vertex supported).

Run:  python benchmarks/formfinding_scaling.py [n ...] [--quick] [--peer-max-n N] [--no-peer]
                                               [--peer-horizontal nodal|sparse] [--peer-tight]
                                               [--plans [PLAN ...]] [--plan-faces N ...]

``1000`` among the sizes is the 10^6-face grid (floor: under 15 s and 4 GB; growth exponent from
n = 100 to the largest at most 1.1); ``--plans`` form-finds shared plans at several resolutions and
compares their heights (acceptance: within 2% of zmax), also within 0.5 m of the outline's reflex
corners and beyond 1.5 m.

Prints, per grid: vertices, time to build the form diagram, force diagram, horizontal and vertical
equilibrium (self-weight, zmax = n/4, loads and scale iterated to 1e-12), iterations and the final max
angle deviation. Floor: the full n = 100 form finding (10,201 mesh vertices) under 1 s.

Optional peer: if ``compas_tna`` (tested with 0.9.0 on compas 2.15.1) is importable, the same grids are
form-found with it in the same run -- FormDiagram.from_vertices_and_faces on the same vertices and faces,
every boundary vertex ``is_support``, ``update_boundaries()``, ForceDiagram.from_formdiagram,
``horizontal_nodal_numpy`` (or ``horizontal_numpy`` with ``--peer-horizontal sparse``) with kmax=100 and
``vertical_from_zmax(form, n/4)`` -- and a second table compares times, angle deviations and heights.
Grids larger than ``--peer-max-n`` (default 100) skip the peer: its horizontal step is a Python loop over
the vertices and n = 200 takes minutes.

Differences between the two set-ups that the comparison cannot remove (see benchmarks/README.md):

* iterations: compas_tna always runs kmax = 100 parallelisation iterations (it has no angle tolerance);
  vaultgram stops as soon as the max angle is below 0.5 deg, which on these grids is before the first
  iteration, because its least-squares force diagram is already reciprocal. Column ``vg h@100`` times
  vaultgram's horizontal step forced through 100 iterations, for a per-iteration comparison;
* initial force diagram: compas_tna uses the dual of face centroids (not reciprocal at the cut corner
  triangles, so its angle starts above zero), vaultgram a least-squares reciprocal;
* vertical tolerances: compas_tna's ``vertical_from_zmax`` defaults stop at |zmax error| < 1e-2 and
  residual norm < 1e-3 (absolute); vaultgram iterates loads and scale to 1e-12 (relative).
  ``--peer-tight`` passes xtol = 1e-9 and rtol = 1e-9 x total load to the peer instead;
* loads, supports and boundary handling are the same: self-weight from 3D tributary areas (thickness 1,
  density 1, the LoadUpdater convention), every boundary vertex supported at z = 0, fully supported
  boundary edges removed and the four corner vertices deleted (10,197 vertices at n = 100).
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time
from pathlib import Path

import numpy as np
from benchpaths import ARCHITECTURE

from vaultgram.formfinding.forcediagram import force_diagram
from vaultgram.formfinding.formdiagram import form_diagram
from vaultgram.formfinding.horizontal import angle_deviations, horizontal
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.pipeline import form_find

DEFAULT_SIZES = [10, 20, 50, 100, 200]
QUICK_SIZES = [10, 20]
PEER_KMAX = 100


def _growth(results: dict) -> None:
    """The time's growth exponent between the smallest and the largest grid of at least 10^4 faces
    (acceptance: at most 1.1 from 10^4 to 10^6 faces)."""
    big = sorted(n for n in results if n >= 100)
    if len(big) >= 2:
        a, b = results[big[0]], results[big[-1]]
        def exponent(key: str) -> float:
            return float(np.log(b[key] / a[key]) / np.log(b["vertices"] / a["vertices"]))

        print(f"     growth exponent n = {big[0]} -> {big[-1]}: {exponent('total'):.2f} wall, "
              f"{exponent('cpu'):.2f} CPU (floor: at most 1.1; CPU time is what other sessions leave alone)")


def run_vaultgram(n: int) -> dict:
    v, f = grid_mesh(n)
    timings: dict = {}
    t, cpu = time.perf_counter(), time.process_time()
    tn = form_find(v, f, zmax=n / 4.0, timings=timings)
    total, cpu = time.perf_counter() - t, time.process_time() - cpu
    s = tn.summary
    return {"n": n, "vertices": len(v), "total": total, "cpu": cpu, **timings,
            "h_iter": s["horizontal_iterations"], "v_iter": s["vertical_iterations"],
            "angle": s["max_angle_deg"], "residual": s["vertical_residual"] / s["total_load"],
            "n_form": s["n_vertices"], "scale": s["scale"], "zmax": s["zmax"],
            "z": dict(zip(tn.vertex_ids.tolist(), tn.vertices[:, 2].tolist())),
            "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}


def vaultgram_horizontal_fixed_iterations(n: int, kmax: int = PEER_KMAX) -> float:
    """Seconds for vaultgram's horizontal step forced through exactly ``kmax`` iterations (as the peer)."""
    v, f = grid_mesh(n)
    form = form_diagram(v, f)
    force = force_diagram(form)
    t = time.perf_counter()
    h = horizontal(form, force, kmax=kmax, tol_deg=-1.0, stall_window=10 ** 9, rescue=False,
                   raise_on_failure=False)
    seconds = time.perf_counter() - t
    assert h.iterations == kmax, h.iterations
    return seconds


# ---------------------------------------------------------------------------------------------------
# optional peer: compas_tna
# ---------------------------------------------------------------------------------------------------

def import_peer():
    """The compas_tna entry points, or a message saying why they are not available."""
    try:
        import compas
        import compas_tna
        from compas_tna.diagrams import ForceDiagram, FormDiagram
        from compas_tna.equilibrium import horizontal_nodal_numpy, horizontal_numpy, vertical_from_zmax
    except ImportError as exc:
        return None, f"compas_tna not importable ({exc}); peer comparison skipped"
    version = f"compas_tna {getattr(compas_tna, '__version__', '?')} on compas {getattr(compas, '__version__', '?')}"
    return {"FormDiagram": FormDiagram, "ForceDiagram": ForceDiagram, "nodal": horizontal_nodal_numpy,
            "sparse": horizontal_numpy, "vertical_from_zmax": vertical_from_zmax, "version": version}, None


def peer_max_angle(form, force) -> float:
    """Max angle (degrees, 0..180) between each form edge and its force edge turned by 90 degrees.

    Recomputed from the final diagram coordinates with vaultgram's ``angle_deviations``, so both columns
    use one formula; it agrees with the max of compas_tna's own ``_a`` edge attribute.
    """
    k_i = form.vertex_index()
    f_i = force.vertex_index()
    xy = np.array(form.vertices_attributes("xy"), dtype=float)
    fxy = np.array(force.vertices_attributes("xy"), dtype=float)
    u_rows, d_rows = [], []
    for a, b in form.edges_where(_is_edge=True):
        f1, f2 = form.halfedge[a][b], form.halfedge[b][a]
        u_rows.append((k_i[a], k_i[b]))
        d_rows.append((f_i[f1], f_i[f2]))
    u_rows, d_rows = np.array(u_rows), np.array(d_rows)
    u = xy[u_rows[:, 1]] - xy[u_rows[:, 0]]
    d = fxy[d_rows[:, 1]] - fxy[d_rows[:, 0]]
    d = np.column_stack([-d[:, 1], d[:, 0]])  # rot90 CCW, as compas_tna does before parallelising
    return float(angle_deviations(u, d).max())


def clear_compas_lu_cache() -> None:
    """Empty compas' ``lufactorized`` memo before each peer run.

    ``compas.linalg.lufactorized`` memoises factorisations by the caller's key only (``horizontal_numpy``
    passes the constant strings "CtC" and "_Ct_C"), so a second ``horizontal_numpy`` call in the same
    process reuses the first diagram's factorisation: "ValueError: b is of incompatible size" on a
    larger grid, silently wrong results on one of the same size.
    """
    from compas import linalg
    for cell in getattr(linalg.lufactorized, "__closure__", None) or ():
        if isinstance(cell.cell_contents, dict):
            cell.cell_contents.clear()


def run_compas_tna(peer: dict, n: int, solver: str = "nodal", tight: bool = False) -> dict | None:
    v, f = grid_mesh(n)
    zmax = n / 4.0
    try:
        t0 = time.perf_counter()
        form = peer["FormDiagram"].from_vertices_and_faces(v.tolist(), [list(face) for face in f])
        form.vertices_attribute("is_support", True, keys=list(form.vertices_on_boundary()))
        form.update_boundaries()  # drop fully supported boundary edges and the corner vertices
        force = peer["ForceDiagram"].from_formdiagram(form)
        if solver == "sparse":
            clear_compas_lu_cache()
        t1 = time.perf_counter()
        peer[solver](form, force, kmax=PEER_KMAX)
        t2 = time.perf_counter()
        kw = {"xtol": 1e-9, "rtol": 1e-9 * float(n * n)} if tight else {}
        form, scale = peer["vertical_from_zmax"](form, zmax, **kw)
        t3 = time.perf_counter()
    except Exception as exc:  # the peer's API changes between versions; report, do not fail
        print(f"  (compas_tna failed on n={n}: {type(exc).__name__}: {exc})")
        return None
    z = {int(k): float(form.vertex_attribute(k, "z")) for k in form.vertices()}
    return {"setup": t1 - t0, "horizontal": t2 - t1, "vertical": t3 - t2, "total": t3 - t0,
            "angle": peer_max_angle(form, force), "scale": float(scale), "zmax": max(z.values()),
            "n_form": form.number_of_vertices(), "z": z}


# ---------------------------------------------------------------------------------------------------

def run_meshes(face_counts) -> None:
    """Form finding on the meshed quad-with-hole example (outer boundary supported, hole open)."""
    from vaultgram.domain import load_domain
    from vaultgram.formfinding.supports import support_vertices
    from vaultgram.pipeline import form_find, mesh_domain

    domain = load_domain(Path(__file__).resolve().parents[1] / "examples" / "quad_with_hole.json")
    print("\nquad_with_hole meshes (vaultgram mesh, then form_find with zmax 3); times in seconds")
    head = (f"{'faces':>8} {'verts':>7} {'form':>7} {'relax':>7} {'force':>7} {'horiz':>7} {'vert':>7} "
            f"{'total':>7} {'h_it':>5} {'v_it':>5} {'angle(deg)':>10} {'min q':>8}")
    print(head)
    print("-" * len(head))
    for faces in face_counts:
        mesh = mesh_domain(domain, 0.02, target_length=float(np.sqrt(domain.area / faces)))
        supports = support_vertices(mesh.vertices, mesh.faces, None, domain)
        t: dict = {}
        tn = form_find(mesh.vertices, mesh.faces, supports, zmax=3.0, timings=t)
        t["total"] = sum(t.values())
        sm = tn.summary
        act = tn.form.active
        qrel = tn.q[act].min() / np.median(tn.q[act])
        print(f"{len(mesh.faces):>8} {len(mesh.vertices):>7} {t['form']:>7.3f} {t['relax']:>7.3f} {t['force']:>7.3f} "
              f"{t['horizontal']:>7.3f} {t['vertical']:>7.3f} {t['total']:>7.3f} {sm['horizontal_iterations']:>5} "
              f"{sm['vertical_iterations']:>5} {sm['max_angle_deg']:>10.2e} {qrel:>8.1e}", flush=True)
    print("min q = smallest force density / median (all q > 0: compression only)")


def _by_corner_distance(domain, mesh, points: np.ndarray, signed: np.ndarray) -> str:
    """The largest ``|signed|`` at ``points`` within 0.5 m of a reflex corner of the plan's outline (turning
    inwards by more than 20 degrees, where a membrane's slope is unbounded) and beyond 1.5 m of every one,
    and the mean of ``signed`` (finer minus coarser) within 0.5 m: a drift of one sign near the notches
    that does not shrink from pair to pair is a vault that changes with the resolution there (issue 18)."""
    outer = np.asarray(domain.outer, dtype=float) - np.asarray(mesh.origin)[:2]
    a, b = outer - np.roll(outer, 1, axis=0), np.roll(outer, -1, axis=0) - outer
    corners = outer[np.degrees(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(axis=1))) < -20]
    if not len(corners):
        return ""
    from scipy.spatial import cKDTree

    r = cKDTree(corners).query(points[:, :2])[0]
    near, far = signed[r < 0.5], np.abs(signed[r > 1.5])
    drift = f" (mean signed {near.mean():+.2%})" if len(near) else ""
    return (f"; {len(corners)} reflex corners: within 0.5 m {np.abs(near).max(initial=0.0):.2%}{drift}, "
            f"beyond 1.5 m {far.max(initial=0.0):.2%}")


def run_plans(plans, face_counts) -> None:
    """Shared plans at several resolutions with the defaults of ``vaultgram design`` (supports of the
    plan, default rise, automatic relaxation): convergence, time, peak memory, and how far the heights
    of each resolution are from the next coarser one at its plan points (linear interpolation of the
    finer network), as a fraction of zmax (acceptance: below 2%)."""
    import resource

    from scipy.interpolate import LinearNDInterpolator

    from vaultgram.domain import load_domain
    from vaultgram.geometry.text import fmt_point
    from vaultgram.pipeline import mesh_domain, thrust_of_mesh

    folder = ARCHITECTURE
    print("\nshared plans, defaults of vaultgram design; times in seconds, dz = max height difference to the "
          "previous resolution / zmax, at the previous one's vertices")
    head = (f"{'plan':>16} {'faces':>8} {'mesh':>7} {'form find':>9} {'relax':>6} {'h_it':>5} {'angle':>9} "
            f"{'q>0':>4} {'dz':>7} {'peak MB':>8}")
    print(head)
    print("-" * len(head))
    for plan in plans:
        domain, previous = load_domain(folder / f"{plan}.json"), None
        for faces in face_counts:
            t0 = time.perf_counter()
            mesh = mesh_domain(domain, 0.02, target_length=float(np.sqrt(domain.area / faces)))
            t1 = time.perf_counter()
            try:
                tn = thrust_of_mesh(mesh, domain.supports, domain)
            except Exception as exc:  # a failure is a result of the benchmark, reported
                print(f"{plan:>16} {len(mesh.faces):>8} {t1 - t0:>7.2f} failed: {str(exc)[:90]}", flush=True)
                continue
            t2 = time.perf_counter()
            s, xyz = tn.summary, tn.vertices
            dz = where = ""
            if previous is not None:
                z = LinearNDInterpolator(xyz[:, :2], xyz[:, 2])(previous[:, :2])
                ok = np.flatnonzero(np.isfinite(z))
                signed = (z[ok] - previous[ok, 2]) / s["zmax"]
                d = np.abs(signed)
                dz, p99 = f"{d.max():.2%}", f"{np.percentile(d, 99):.2%}"
                where = (f"  (99th percentile {p99}, median {np.median(d):.2%}; largest at "
                         f"{fmt_point(previous[ok[np.argmax(d)], :2])}"
                         f"{_by_corner_distance(domain, mesh, previous[ok], signed)})")
            previous = xyz
            peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
            compression = str(bool(np.all(tn.q[tn.form.active] > 0)))
            print(f"{plan:>16} {len(mesh.faces):>8} {t1 - t0:>7.2f} {t2 - t1:>9.2f} {s['relax_mode']:>6} "
                  f"{s['horizontal_iterations']:>5} {s['max_angle_deg']:>9.2e} {compression:>4} "
                  f"{dz:>7} {peak:>8.0f}{where}", flush=True)


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("sizes", nargs="*", type=int, help=f"grid sizes n (default {DEFAULT_SIZES})")
    p.add_argument("--quick", action="store_true", help=f"only n = {QUICK_SIZES}")
    p.add_argument("--peer-max-n", type=int, default=100,
                   help="largest n on which compas_tna is run (default 100; n = 200 takes minutes)")
    p.add_argument("--no-peer", action="store_true", help="do not run compas_tna even if importable")
    p.add_argument("--no-meshes", action="store_true", help="skip the quad_with_hole meshes")
    p.add_argument("--mesh-faces", type=int, nargs="+", default=[1_000, 10_000, 100_000],
                   help="approximate face counts of the quad_with_hole meshes (default 10^3, 10^4, 10^5; "
                        "10^5 takes about 10 s to mesh and form-find)")
    p.add_argument("--plans", nargs="*", default=None, metavar="PLAN",
                   help="shared plans to form-find at --plan-faces (default with no names: armadillo_vault, "
                        "multiple_lobes, rv_quad_pattern)")
    p.add_argument("--plan-faces", type=int, nargs="+", default=[10_000, 100_000],
                   help="approximate face counts of the plans (default 10^4 and 10^5; add 1000000 for 10^6)")
    p.add_argument("--peer-horizontal", choices=("nodal", "sparse"), default="nodal",
                   help="compas_tna horizontal solver: horizontal_nodal_numpy (default) or horizontal_numpy")
    p.add_argument("--peer-tight", action="store_true",
                   help="tight vertical tolerances for compas_tna (xtol 1e-9, rtol 1e-9 x load)")
    a = p.parse_args(argv)
    if a.quick and a.sizes:
        p.error("give either sizes or --quick")
    a.sizes = QUICK_SIZES if a.quick else (a.sizes or DEFAULT_SIZES)
    return a


def main(argv=None) -> None:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    run_vaultgram(4)  # warm up imports
    print(f"start-up, imports and the n = 4 warm-up: {time.process_time():.2f} s CPU of this process")
    head = (f"{'n':>4} {'verts':>7} {'form':>8} {'force':>8} {'horiz':>8} {'vert':>8} {'total':>8} {'cpu':>8} "
            f"{'h_it':>5} {'v_it':>5} {'angle(deg)':>11} {'res/load':>9}")
    print("vaultgram")
    print(head)
    print("-" * len(head))
    results = {}
    for n in args.sizes:
        r = run_vaultgram(n)
        results[n] = r
        print(f"{n:>4} {r['vertices']:>7} {r['form'] * 1e3:>6.1f}ms {r['force'] * 1e3:>6.1f}ms "
              f"{r['horizontal'] * 1e3:>6.1f}ms {r['vertical'] * 1e3:>6.1f}ms {r['total'] * 1e3:>6.1f}ms "
              f"{r['cpu']:>7.2f}s "
              f"{r['h_iter']:>5} {r['v_iter']:>5} {r['angle']:>11.2e} {r['residual']:>9.1e}", flush=True)
        if n == 100:
            print(f"     n = 100 floor (< 1 s): {'met' if r['total'] < 1.0 else 'MISSED'}")

        if n >= 1000:
            met = r["total"] < 15.0 and r["peak_mb"] < 4096
            print(f"     n = {n} floor (< 15 s, < 4 GB peak): {'met' if met else 'MISSED'}"
                  f" ({r['total']:.1f} s wall, {r['cpu']:.1f} s CPU of this process, {r['peak_mb']:.0f} MB;"
                  f" load average {os.getloadavg()[0]:.1f})")
    _growth(results)
    if not args.no_meshes:
        run_meshes(args.mesh_faces)
    if args.plans is not None:
        run_plans(args.plans or ["armadillo_vault", "multiple_lobes", "rv_quad_pattern"], args.plan_faces)
    if args.no_peer:
        print("\npeer comparison skipped (--no-peer)")
        return
    peer, why = import_peer()
    if peer is None:
        print(f"\n{why}")
        return
    solver = {"nodal": "horizontal_nodal_numpy", "sparse": "horizontal_numpy"}[args.peer_horizontal]
    tol = "xtol 1e-9, rtol 1e-9 x n^2" if args.peer_tight else "default tolerances"
    print(f"\npeer: {peer['version']}; {solver} kmax={PEER_KMAX}, vertical_from_zmax ({tol}); "
          f"zmax = n/4; times in seconds")
    head = (f"{'n':>4} {'verts':>6} | {'vg h':>7} {'vg v':>7} {'vg tot':>7} {'vg h@100':>8} | "
            f"{'tna set':>7} {'tna h':>7} {'tna v':>7} {'tna tot':>7} | {'tot x':>6} {'h x':>6} {'h@100 x':>7} | "
            f"{'vg angle':>8} {'tna angle':>9} | {'tna zmax':>9} {'max|dz|':>8} {'scale d':>8}")
    print(head)
    print("-" * len(head))
    for n in args.sizes:
        r = results[n]
        if n > args.peer_max_n:
            print(f"{n:>4} {r['n_form']:>6} | compas_tna skipped (n > --peer-max-n {args.peer_max_n})")
            continue
        h100 = vaultgram_horizontal_fixed_iterations(n)
        c = run_compas_tna(peer, n, args.peer_horizontal, args.peer_tight)
        if c is None:
            continue
        if c["n_form"] != r["n_form"]:
            print(f"     note: compas_tna has {c['n_form']} vertices, vaultgram {r['n_form']}")
        common = [k for k in r["z"] if k in c["z"]]
        dz = max(abs(r["z"][k] - c["z"][k]) for k in common)
        print(f"{n:>4} {r['n_form']:>6} | {r['horizontal']:>7.4f} {r['vertical']:>7.4f} {r['total']:>7.4f} "
              f"{h100:>8.4f} | {c['setup']:>7.3f} {c['horizontal']:>7.3f} {c['vertical']:>7.3f} {c['total']:>7.3f} | "
              f"{c['total'] / r['total']:>5.0f}x {c['horizontal'] / r['horizontal']:>5.0f}x "
              f"{c['horizontal'] / h100:>6.0f}x | {r['angle']:>8.1e} {c['angle']:>9.1e} | "
              f"{c['zmax']:>9.5f} {dz:>8.1e} {c['scale'] / r['scale'] - 1:>8.1e}", flush=True)
    print("vg = vaultgram (form_find, stops at angle < 0.5 deg); tna = compas_tna; verts = form-diagram "
          "vertices (corners removed);\nvg h@100 = vaultgram horizontal forced through 100 iterations; "
          "'x' columns = compas_tna time / vaultgram time;\nmax|dz| = largest height difference between the "
          "two networks (vaultgram zmax = n/4 exactly); scale d = tna scale / vg scale - 1")


if __name__ == "__main__":
    main()
