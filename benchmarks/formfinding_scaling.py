"""Scaling of TNA form finding on regular n x n grids (every boundary vertex supported).

Run:  python benchmarks/formfinding_scaling.py [n ...]

Prints, per grid: vertices, time to build the form diagram, force diagram, horizontal and vertical
equilibrium (self-weight, zmax = n/4, loads and scale iterated to 1e-12), iterations and the final max
angle deviation. Floor: the full n = 100 form finding (10,201 mesh vertices) under 1 s.
If compas_tna is importable it is timed on the same grids and the ratio printed (optional peer).
"""

from __future__ import annotations

import sys
import time

from vaultgram.equilibrium import form_find
from vaultgram.meshes import grid_mesh


def run_vaultgram(n: int) -> dict:
    v, f = grid_mesh(n)
    t = time.perf_counter()
    tn = form_find(v, f, zmax=n / 4.0)
    total = time.perf_counter() - t
    s = tn.summary
    return {"n": n, "vertices": len(v), "total": total, **s["timings"],
            "h_iter": s["horizontal_iterations"], "v_iter": s["vertical_iterations"],
            "angle": s["max_angle_deg"], "residual": s["vertical_residual"] / s["total_load"]}


def run_compas_tna(n: int) -> float | None:
    try:
        from compas.datastructures import Mesh  # noqa: F401
        from compas_tna.diagrams import ForceDiagram, FormDiagram
        from compas_tna.equilibrium import horizontal_nodal, vertical_from_zmax
    except ImportError:
        return None
    try:
        t = time.perf_counter()
        form = FormDiagram.from_meshgrid(dx=n, nx=n)
        form.vertices_attribute("is_support", True, keys=list(form.vertices_on_boundary()))
        form.edges_attribute("q", 1.0)
        force = ForceDiagram.from_formdiagram(form)
        horizontal_nodal(form, force, kmax=100)
        vertical_from_zmax(form, n / 4.0)
        return time.perf_counter() - t
    except Exception as exc:  # the peer's API changes between versions; report, do not fail
        print(f"  (compas_tna failed on n={n}: {type(exc).__name__}: {exc})")
        return None


def main(sizes) -> None:
    run_vaultgram(4)  # warm up imports
    head = (f"{'n':>4} {'verts':>7} {'form':>8} {'force':>8} {'horiz':>8} {'vert':>8} {'total':>8} "
            f"{'h_it':>5} {'v_it':>5} {'angle(deg)':>11} {'res/load':>9} {'compas_tna':>11}")
    print(head)
    print("-" * len(head))
    for n in sizes:
        r = run_vaultgram(n)
        peer = run_compas_tna(n)
        ratio = f"{peer / r['total']:.1f}x slower" if peer else "n/a"
        print(f"{n:>4} {r['vertices']:>7} {r['form'] * 1e3:>6.1f}ms {r['force'] * 1e3:>6.1f}ms "
              f"{r['horizontal'] * 1e3:>6.1f}ms {r['vertical'] * 1e3:>6.1f}ms {r['total'] * 1e3:>6.1f}ms "
              f"{r['h_iter']:>5} {r['v_iter']:>5} {r['angle']:>11.2e} {r['residual']:>9.1e} {ratio:>11}")
        if n == 100:
            print(f"     n = 100 floor (< 1 s): {'met' if r['total'] < 1.0 else 'MISSED'}")


if __name__ == "__main__":
    main([int(a) for a in sys.argv[1:]] or [10, 20, 50, 100, 200])
