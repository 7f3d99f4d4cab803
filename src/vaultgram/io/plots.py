"""The single PNG figures the commands write beside their files (``decomposition.png``, ``mesh.png``,
``thrust.png``, ``tessellation.png``) and the figure of a decomposition graph mid-rewrite (the rule
traces): each draws with :mod:`vaultgram.io.figures`' functions and style. matplotlib is imported
only when a figure is drawn, so the command line starts fast."""

from __future__ import annotations

from pathlib import Path

from vaultgram.io.figures import style

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
    from vaultgram.topology.patches import half_edge_polyline

    for e in g.edges():
        line = EDGE_STYLE.get(g.edge_type(e))
        if line:
            xy = half_edge_polyline(g, e, g.ends(e)[0])
            if e in created or e in highlight:
                line = dict(line, color="limegreen" if e in created else "red", lw=2.5)
            ax.plot(xy[:, 0], xy[:, 1], **line)


def _mark_nodes(ax, g, nodes, color: str) -> None:
    """Dots at the positions of ``nodes`` (those still in the graph and placed)."""
    marked = [g.get(n, "pos") for n in nodes if g.has_node(n) and "pos" in g.node_attrs(n)]
    if marked:
        style.points(ax, marked, "nodes", color, size=36)


def plot_graph(g, path: str | Path, nodes=(), edges=(), title: str = "", created=((), ())) -> None:
    """A decomposition graph as it is (mid-rewrite, say): its plan edges, the ``nodes`` and ``edges``
    given (a rule's match) in red and the ``created`` (nodes, edges) in green; written atomically as
    PNG."""
    fig, ax = style.new_figure()
    _plan_edges(ax, g, {e for e in edges if g.has_edge(e)}, set(created[1]))
    _mark_nodes(ax, g, nodes, "red")
    _mark_nodes(ax, g, created[0], "limegreen")
    style.plan(ax, title)
    style.save(fig, Path(path))


def plot_decomposition(decomposition, path: str | Path) -> None:
    """The patches (Figure 2f: three- and four-sided, poles, ids); written atomically as PNG."""
    from vaultgram.io.figures.topology import draw_patches
    from vaultgram.meshing.layout import edge_groups

    fig, ax = style.new_figure()
    draw_patches(ax, decomposition, edge_groups(decomposition))
    style.save(fig, Path(path))


def plot_mesh(mesh, path: str | Path) -> None:
    """The quad mesh in plan, poles marked; written atomically as PNG."""
    from vaultgram.io.figures.meshes import draw_mesh

    fig, ax = style.new_figure()
    draw_mesh(ax, mesh, "mesh")
    style.save(fig, Path(path))


def plot_thrust(network, path: str | Path) -> None:
    """The thrust network in plan, faces shaded by height; written atomically as PNG."""
    from vaultgram.io.figures.thrust import draw_thrust_plan

    fig, ax = style.new_figure()
    draw_thrust_plan(ax, network)
    style.save(fig, Path(path))


def plot_tessellation(tessellation, path: str | Path) -> None:
    """The voussoirs in plan (Figure 12b), coloured by construction course, keystones marked; PNG."""
    from vaultgram.io.figures.thrust import draw_tessellation_plan

    fig, ax = style.new_figure()
    draw_tessellation_plan(ax, tessellation)
    style.save(fig, Path(path))
