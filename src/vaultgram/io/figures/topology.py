"""Figures of the topology stage (§3.1, the paper's Figure 2a-f): the boundaries with their
supports and features, the Delaunay mesh with its classes of faces, the raw skeleton, the skeleton
after pruning and after rebranching, and the patches."""

from __future__ import annotations

import numpy as np

from vaultgram.io.figures.style import COLOURS, WIDTHS, lines, plan, points, polygons, polyline_segments
from vaultgram.topology.patches import half_edge_polyline
from vaultgram.topology.triangulation import KIND_CORNER, KIND_REGULAR, KIND_SINGULAR

#: The decomposition graph's plan edges drawn in the skeleton figures, and their colours.
PLAN_STYLE = {"Boundary": ("boundary", COLOURS["boundary"]), "Curve": ("curves", COLOURS["curve"]),
              "Branch": ("branches", COLOURS["branch"]), "Rebranch": ("rebranches", COLOURS["rebranch"]),
              "Diagonal": ("diagonals", COLOURS["diagonal"])}


def rings(domain) -> list:
    """The domain's rings as closed polylines, outer first."""
    return [np.vstack([r, r[:1]]) for r in (domain.outer, *domain.holes)]


def draw_boundaries(ax, domain, support_segments) -> None:
    """Figure 2a / 9a: outer and inner boundaries, the supported stretches thick, point and curve
    features."""
    lines(ax, polyline_segments(rings(domain)), "boundaries", COLOURS["boundary"], WIDTHS["boundary"])
    lines(ax, support_segments, "supports", COLOURS["support"], WIDTHS["support"], zorder=3)
    lines(ax, polyline_segments(domain.curves), "curves", COLOURS["curve"], WIDTHS["curve"])
    points(ax, domain.points, "points", COLOURS["point"])
    plan(ax, f"boundaries: {len(domain.holes)} hole(s), {len(domain.points)} point(s), "
             f"{len(domain.curves)} curve(s); supports thick")


def draw_delaunay(ax, tri) -> None:
    """Figure 2b: the Delaunay mesh, corner (one neighbour), regular (two) and singular (three) faces
    in their colours."""
    colour = np.array([COLOURS["face_isolated"], COLOURS["face_corner"], COLOURS["face_regular"],
                       COLOURS["face_singular"]], dtype=object)
    polygons(ax, tri.points[tri.triangles], "faces", list(colour[tri.kind]), edgecolor="0.4")
    counts = np.bincount(tri.kind, minlength=4)
    plan(ax, f"Delaunay: {counts[KIND_REGULAR]} regular, {counts[KIND_SINGULAR]} singular (red), "
             f"{counts[KIND_CORNER]} corner (blue)")


def draw_skeleton(ax, sk) -> None:
    """Figure 2c: the raw skeleton, its branches and loops, singularities marked."""
    domain = sk.triangulation.disc.domain
    lines(ax, polyline_segments(rings(domain)), "boundaries", COLOURS["boundary"], WIDTHS["boundary"])
    lines(ax, polyline_segments([b.polyline for b in sk.branches] + [lp.polyline for lp in sk.loops]),
          "skeleton", COLOURS["branch"], WIDTHS["branch"])
    singular = [n.pos for n in sk.singularities()]
    points(ax, singular, "singularities", COLOURS["singular"], size=14)
    plan(ax, f"skeleton: {len(sk.branches)} branches, {len(sk.loops)} loop(s), {len(singular)} singularities")


def graph_polylines(graph, edge_type: str) -> list:
    """The polylines of the decomposition graph's edges of ``edge_type``."""
    return [half_edge_polyline(graph, e, graph.ends(e)[0]) for e in graph.edges() if graph.edge_type(e) == edge_type]


def draw_plan_graph(ax, dec, edge_types, title: str) -> None:
    """The decomposition graph's edges of ``edge_types``, one collection per type (``gid`` of
    :data:`PLAN_STYLE`), singularities marked."""
    for edge_type in edge_types:
        gid, colour = PLAN_STYLE[edge_type]
        width = WIDTHS["curve"] if edge_type == "Curve" else WIDTHS["branch"]
        lines(ax, polyline_segments(graph_polylines(dec.graph, edge_type)), gid, colour, width)
    singular = [dec.graph.get(n, "pos") for n in dec.singularities()]
    points(ax, singular, "singularities", COLOURS["singular"], size=14)
    plan(ax, title)


def draw_pruned(ax, dec) -> None:
    """Figure 2d: the skeleton after the branches to corner faces were pruned."""
    n = sum(dec.graph.edge_type(e) == "Branch" for e in dec.graph.edges())
    draw_plan_graph(ax, dec, ("Boundary", "Curve", "Branch"), f"pruned: {n} branches")


def draw_rebranched(ax, dec) -> None:
    """Figure 2e: the skeleton with the new branches from each singularity to its dual face's vertices."""
    n = sum(dec.graph.edge_type(e) == "Rebranch" for e in dec.graph.edges())
    draw_plan_graph(ax, dec, ("Boundary", "Curve", "Branch", "Rebranch", "Diagonal"), f"rebranched: {n} new branches")


def draw_patches(ax, dec, layout) -> None:
    """Figure 2f: the patches, four-sided and three-sided in two colours, the poles of the triangles
    marked and every patch numbered."""
    colour = {4: COLOURS["quad"], 3: COLOURS["triangle"]}
    polygons(ax, [p.polygon() for p in dec.patches], "patches",
             [colour.get(p.n_sides, "white") for p in dec.patches], edgecolor="black", width=0.8)
    poles = [dec.graph.get(p.corners[p.pole], "pos") for p in layout.patterns if p.pole is not None]
    points(ax, poles, "poles", COLOURS["pole"], marker="^", size=30)
    if len(dec.patches) <= 400:  # beyond, numbers are unreadable
        for p in dec.patches:
            cx, cy = p.polygon().mean(axis=0)
            ax.text(cx, cy, str(p.id), ha="center", va="center", fontsize=6, color="0.3")
    counts = dec.patches_json()["counts"]
    plan(ax, f"{len(dec.patches)} patches: {counts['4']} four-sided (blue), {counts['3']} three-sided "
             f"(orange), {len(poles)} pole(s)")
