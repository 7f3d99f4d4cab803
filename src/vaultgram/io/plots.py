"""Quick figures of the pipeline's stages (matplotlib, no screen needed)."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

from vaultgram.topology.patches import half_edge_polyline  # noqa: E402

EDGE_STYLE = {
    "Boundary": dict(color="black", lw=1.2),
    "Branch": dict(color="tab:blue", lw=1.0),
    "Rebranch": dict(color="tab:orange", lw=1.0),
    "Diagonal": dict(color="tab:green", lw=1.0),
    "Curve": dict(color="tab:purple", lw=2.0),
}


def _plan_edges(ax, g, highlight=frozenset(), created=frozenset()) -> None:
    """The plan's edges of a decomposition graph, in their styles; edges in ``highlight`` in red,
    in ``created`` in green."""
    for e in g.edges():
        style = EDGE_STYLE.get(g.edge_type(e))
        if style:
            xy = half_edge_polyline(g, e, g.ends(e)[0])
            if e in created or e in highlight:
                style = dict(style, color="limegreen" if e in created else "red", lw=2.5)
            ax.plot(xy[:, 0], xy[:, 1], **style)


def _mark_nodes(ax, g, nodes, color: str) -> None:
    """Dots at the positions of ``nodes`` (those still in the graph and placed)."""
    marked = [g.get(n, "pos") for n in nodes if g.has_node(n) and "pos" in g.node_attrs(n)]
    if marked:
        ax.plot(*np.array(marked).T, "o", color=color, ms=6)


def plot_graph(g, path: str | Path, nodes=(), edges=(), title: str = "", created=((), ())) -> None:
    """A decomposition graph as it is (mid-rewrite, say): its plan edges, the ``nodes`` and ``edges``
    given (a rule's match) in red and the ``created`` (nodes, edges) in green; written atomically as
    PNG."""
    fig, ax = plt.subplots(figsize=(7, 7))
    _plan_edges(ax, g, {e for e in edges if g.has_edge(e)}, set(created[1]))
    _mark_nodes(ax, g, nodes, "red")
    _mark_nodes(ax, g, created[0], "limegreen")
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(title)
    save_figure(fig, Path(path))


def plot_decomposition(decomposition, path: str | Path) -> None:
    """Boundaries, branches, rebranches, singularities and patch numbers; written atomically as PNG."""
    g = decomposition.graph
    fig, ax = plt.subplots(figsize=(7, 7))
    _plan_edges(ax, g)
    for n in decomposition.singularities():
        x, y = g.get(n, "pos")
        ax.plot(x, y, "o", color="tab:red", ms=5)
    for patch in decomposition.patches:
        cx, cy = patch.polygon().mean(axis=0)
        ax.text(cx, cy, str(patch.id), ha="center", va="center", fontsize=7, color="gray")
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(f"{len(decomposition.patches)} patches, {len(decomposition.singularities())} singularities")
    save_figure(fig, Path(path))


def plot_mesh(mesh, path: str | Path) -> None:
    """The quad mesh in plan, poles and feature vertices marked; written atomically as PNG."""
    fig, ax = plt.subplots(figsize=(7, 7))
    _faces(ax, mesh.vertices, mesh.faces, None)
    poles = np.flatnonzero(mesh.pole)
    ax.plot(mesh.vertices[poles, 0], mesh.vertices[poles, 1], "o", color="tab:red", ms=3)
    ax.set_title(f"{len(mesh.faces)} faces, {len(poles)} poles")
    save_figure(fig, Path(path))


def plot_thrust(network, path: str | Path) -> None:
    """The thrust network in plan, faces shaded by height; written atomically as PNG."""
    fig, ax = plt.subplots(figsize=(7, 7))
    collection = _faces(ax, network.vertices, network.faces, network.vertices[:, 2])
    fig.colorbar(collection, ax=ax, shrink=0.7, label="height z")
    ax.set_title(f"thrust network: z max {network.vertices[:, 2].max():.4g}")
    save_figure(fig, Path(path))


def plot_tessellation(tessellation, path: str | Path) -> None:
    """The voussoirs in plan (Figure 12b), coloured by construction course, keystones marked; PNG."""
    x = tessellation.vertices
    layout = tessellation.layout
    fig, ax = plt.subplots(figsize=(7, 7))
    polygons = [x[loop, :2] for loop in layout.loops]
    collection = PolyCollection(polygons, edgecolors="black", linewidths=0.4, cmap="viridis")
    collection.set_array(np.asarray(tessellation.courses, dtype=float))
    ax.add_collection(collection)
    for k in layout.keystones.tolist():
        ax.fill(*x[layout.loops[k], :2].T, color="tab:red")
    fig.colorbar(collection, ax=ax, shrink=0.7, label="course (voussoirs from a support)")
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(f"{layout.n_voussoirs} voussoirs, {len(layout.keystones)} keystones")
    save_figure(fig, Path(path))


def _faces(ax, vertices, faces, heights):
    polygons = [np.asarray(vertices)[list(f), :2] for f in faces]
    collection = PolyCollection(polygons, facecolors="none" if heights is None else None,
                                edgecolors="black", linewidths=0.3, cmap="viridis")
    if heights is not None:
        collection.set_array(np.array([np.mean(heights[list(f)]) for f in faces]))
    ax.add_collection(collection)
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_axis_off()
    return collection


def save_figure(fig, path: Path) -> None:
    """Save without timestamps or version metadata (byte-identical reruns), via a temporary file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    fig.savefig(tmp, dpi=120, metadata={"Software": None})
    plt.close(fig)
    tmp.replace(path)
