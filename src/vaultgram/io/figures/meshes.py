"""Figures of the geometry stage (§3.2, the paper's Figure 2g-h): the welded Coons patches before
smoothing, the smoothed mesh with its singularities marked by valence, and the edge groups."""

from __future__ import annotations

import numpy as np

from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.io.figures.style import COLOURS, WIDTHS, face_fills, lines, plan, points

#: Marker colours of irregular interior vertices by valence (other valences: black).
VALENCE_COLOURS = {3: "tab:blue", 5: "tab:red", 6: "tab:purple"}


def vertex_valence(faces, n_vertices: int) -> np.ndarray:
    """How many edges meet at each vertex.

    >>> vertex_valence([(0, 1, 4, 3), (1, 2, 5, 4)], 6).tolist()
    [2, 3, 2, 2, 3, 2]
    """
    return np.bincount(mesh_edges(faces, n_vertices).edges.ravel(), minlength=n_vertices)


def singular_vertices(mesh) -> dict:
    """The interior vertices whose valence is not 4, by valence: ``{valence: indices}``."""
    valence = vertex_valence(mesh.faces, len(mesh.vertices))
    irregular = np.flatnonzero((valence != 4) & ~mesh.boundary)
    return {int(v): irregular[valence[irregular] == v] for v in np.unique(valence[irregular]).tolist()}


def draw_mesh(ax, mesh, title: str) -> None:
    """The quad mesh in plan (edges, or shading at 10^5 faces), its poles marked."""
    face_fills(ax, mesh.vertices, mesh.faces, "faces", "#f4f4f4", edgecolor=COLOURS["mesh"],
             width=WIDTHS["mesh"])
    points(ax, mesh.vertices[mesh.pole, :2], "poles", COLOURS["pole"], marker="^", size=16)
    plan(ax, f"{title}: {len(mesh.faces)} faces, {int(mesh.pole.sum())} pole(s)")


def draw_smoothed(ax, mesh) -> None:
    """Figure 2h: the smoothed mesh, each irregular interior vertex marked in its valence's colour."""
    face_fills(ax, mesh.vertices, mesh.faces, "faces", "#f4f4f4", edgecolor=COLOURS["mesh"],
             width=WIDTHS["mesh"])
    by_valence = singular_vertices(mesh)
    for valence, vertices in by_valence.items():
        points(ax, mesh.vertices[vertices, :2], f"valence-{valence}", VALENCE_COLOURS.get(valence, "black"),
               size=22, label=f"valence {valence} ({len(vertices)})")
    if by_valence:
        ax.legend(loc="lower left", fontsize=7, frameon=False)
    total = sum(len(v) for v in by_valence.values())
    plan(ax, f"smoothed: {len(mesh.faces)} faces, {total} singularities")


def draw_groups(ax, mesh, layout) -> None:
    """The edge groups (§3.2): every side of the patch layout in its group's colour (the sides of a
    group share one number of subdivisions), over the mesh in grey."""
    from matplotlib import colormaps

    face_fills(ax, mesh.vertices, mesh.faces, "faces", "white", edgecolor="0.8",
             width=WIDTHS["mesh"])
    cmap = colormaps["tab20"]
    colours = [cmap(layout.group_of[s.id] % 20) for s in layout.sides]
    lines(ax, [s.polyline for s in layout.sides], "sides", colours, 2.0, zorder=3)
    plan(ax, f"{layout.n_groups} edge groups over {len(layout.sides)} sides")
