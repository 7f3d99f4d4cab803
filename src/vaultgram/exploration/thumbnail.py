"""A variant's thumbnail: its mesh and its patch layout as a small inline SVG (for the gallery).

The mesh's edges are drawn thin, the patch outlines thick, the poles of triangle patches as dots;
the plan is fitted in a square of :data:`SIZE` units with y upwards. Coordinates are rounded to 0.1
unit, so the same variant gives the same text. (A small drawing of its own: ``io/plots.py`` draws
with matplotlib, which embeds its version in every file.)
"""

from __future__ import annotations

import numpy as np

from vaultgram.meshing.layout import choose_pole

SIZE = 200.0
MARGIN = 6.0


def _transform(points: np.ndarray, low: np.ndarray, scale: float) -> np.ndarray:
    """Plan coordinates to SVG units (y flipped)."""
    x = (points[:, 0] - low[0]) * scale + MARGIN
    y = SIZE - MARGIN - (points[:, 1] - low[1]) * scale
    return np.column_stack([x, y])


def _path(polylines, closed: bool) -> str:
    """An SVG path's ``d`` for polylines of SVG points."""
    parts = []
    for poly in polylines:
        pts = " L".join(f"{x:.1f} {y:.1f}" for x, y in poly)
        parts.append(f"M{pts}{' Z' if closed else ''}")
    return " ".join(parts)


def _mesh_edges(faces) -> np.ndarray:
    """The distinct edges of a polygon mesh, as (n, 2) vertex pairs sorted."""
    pairs = {tuple(sorted((int(f[i]), int(f[(i + 1) % len(f)])))) for f in faces for i in range(len(f))}
    return np.array(sorted(pairs), dtype=np.int64).reshape(-1, 2)


def thumbnail_svg(dec, mesh) -> str:
    """The SVG text of a variant's thumbnail (see the module docstring).

    Example
    -------
    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.pipeline import decompose, mesh_decomposition
    >>> dec = decompose(load_domain("examples/l_shape.json"), 0.05)
    >>> svg = thumbnail_svg(dec, mesh_decomposition(dec, smooth=0))
    >>> svg.startswith("<svg"), svg.count('class="patches"')
    (True, 1)
    """
    rings = [np.asarray(p.polygon(), dtype=float) for p in dec.patches]
    allpts = np.vstack(rings)
    low, high = allpts.min(axis=0), allpts.max(axis=0)
    scale = (SIZE - 2 * MARGIN) / max(float((high - low).max()), 1e-12)
    x = _transform(np.asarray(mesh.vertices, dtype=float)[:, :2], low, scale)
    edges = _mesh_edges(mesh.faces)
    mesh_d = " ".join(f"M{x[a, 0]:.1f} {x[a, 1]:.1f} L{x[b, 0]:.1f} {x[b, 1]:.1f}" for a, b in edges)
    patch_d = _path([_transform(r, low, scale) for r in rings], closed=True)
    poles = sorted({choose_pole(dec, p) for p in dec.patches if p.n_sides == 3})
    dots = "".join(
        f'<circle cx="{c[0]:.1f}" cy="{c[1]:.1f}" r="2.5"/>'
        for c in _transform(np.array([dec.graph.get(n, "pos") for n in poles], dtype=float).reshape(-1, 2), low, scale)
    )
    return (f'<svg xmlns="http://www.w3.org/2000/svg" class="thumbnail" viewBox="0 0 {SIZE:.0f} {SIZE:.0f}" '
            f'width="{SIZE:.0f}" height="{SIZE:.0f}">'
            f'<path class="mesh" d="{mesh_d}" fill="none" stroke="#9aa5b1" stroke-width="0.5"/>'
            f'<path class="patches" d="{patch_d}" fill="none" stroke="#1f3b57" stroke-width="1.6"/>'
            f'<g class="poles" fill="#c0392b">{dots}</g></svg>')
