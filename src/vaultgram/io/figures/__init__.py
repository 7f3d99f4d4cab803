"""Figures of every stage of a design, in one style (matplotlib; no screen, no pyplot state).

:data:`CATALOGUE` lists them in the order of the paper: the topology stage (Figure 2a-f), the mesh
before and after smoothing (2g, 2h) and its edge groups, the eight of Figure 2 as one panel, the form
and force diagrams (Figure 10), the thrust network in space (13a) and the tessellation in plan and in
space (12b, 13b). :func:`write_figures` writes each as ``figures/NAME.png`` and ``figures/NAME.svg``
(the report inlines the SVG, :mod:`vaultgram.io.report`). The drawing functions take a matplotlib
axes and a stage's value, so the panel and the single figures share them.

Example
-------
>>> from vaultgram.domain import load_domain
>>> from vaultgram.pipeline import design
>>> data = Stages.of(design(load_domain("examples/l_shape.json"), spacing=0.05, tessellation=None))
>>> [spec.name for spec in CATALOGUE if spec.available(data)][:3]
['boundaries', 'delaunay', 'skeleton']
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Callable

import numpy as np

from vaultgram.io.figures import meshes, style, thrust, topology

__all__ = ["Stages", "FigureSpec", "CATALOGUE", "PANEL", "BESIDE", "figure", "write_figures"]


@dataclass(frozen=True, eq=False)
class Stages:
    """What the figures draw: a design's stage values (later stages None when not run)."""

    domain: object
    decomposition: object
    mesh: object = None
    supports: np.ndarray | None = None
    network: object = None
    tessellation: object = None
    rendered: dict = field(default_factory=dict, repr=False)  # figure name -> its pixels, once written

    @classmethod
    def of(cls, design) -> Stages:
        """The stages of a :class:`vaultgram.pipeline.Design`."""
        return cls(design.domain, design.decomposition, design.mesh, design.supports, design.network,
                   design.tessellation)

    @cached_property
    def layout(self):
        """The patch layout and its edge groups (:func:`vaultgram.meshing.layout.edge_groups`)."""
        from vaultgram.meshing.layout import edge_groups

        return edge_groups(self.decomposition)

    @cached_property
    def coons(self):
        """The welded Coons patches before smoothing: the mesh's own counts per edge group, welded
        again (:func:`vaultgram.meshing.weld.weld`), so that the pipeline keeps no second mesh."""
        from vaultgram.meshing.weld import weld

        return weld(self.layout, np.array([g["count"] for g in self.mesh.groups], dtype=np.int64))

    @cached_property
    def support_segments(self) -> np.ndarray:
        """The mesh's boundary edges with both ends supported, as segments (k, 2, 2)."""
        from vaultgram.geometry.halfedges import mesh_edges

        if self.mesh is None or self.supports is None:
            return np.zeros((0, 2, 2))
        me = mesh_edges(self.mesh.faces, len(self.mesh.vertices))
        held = np.zeros(len(self.mesh.vertices), dtype=bool)
        held[np.asarray(self.supports, dtype=np.int64)] = True
        edges = me.edges[me.boundary & held[me.edges].all(axis=1)]
        return self.mesh.vertices[edges][:, :, :2]


@dataclass(frozen=True)
class FigureSpec:
    """One figure: its file name, its caption, the stage it needs and how it draws on one axes."""

    name: str
    caption: str
    needs: str  # the Stages attribute that must not be None
    draw: Callable  # (axes, Stages) -> None
    projection: str | None = None
    final: str | None = None  # a later Stages attribute the drawing shows when there (the supports)

    def available(self, data: Stages) -> bool:
        return getattr(data, self.needs) is not None

    def ready(self, data: Stages) -> bool:
        """Whether every stage the figure shows is there: it will not change as later stages arrive
        (:mod:`vaultgram.io.figures.worker` draws it then)."""
        return self.available(data) and (self.final is None or getattr(data, self.final) is not None)


def _spec(name, caption, needs, draw, projection=None, final=None) -> FigureSpec:
    return FigureSpec(name, caption, needs, draw, projection, final)


#: The eight steps of the paper's Figure 2, (a) to (h).
PANEL = (
    _spec("boundaries", "Boundaries, supports thick, holes, point and curve features (Figure 2a, 9a)",
          "decomposition", lambda ax, d: topology.draw_boundaries(ax, d.domain, d.support_segments),
          final="supports"),
    _spec("delaunay", "Delaunay mesh: regular, singular and corner faces (Figure 2b)", "decomposition",
          lambda ax, d: topology.draw_delaunay(ax, d.decomposition.skeleton.triangulation)),
    _spec("skeleton", "Raw topological skeleton (Figure 2c)", "decomposition",
          lambda ax, d: topology.draw_skeleton(ax, d.decomposition.skeleton)),
    _spec("pruned", "Skeleton after pruning the corner branches (Figure 2d)", "decomposition",
          lambda ax, d: topology.draw_pruned(ax, d.decomposition)),
    _spec("rebranched", "Skeleton after rebranching (Figure 2e)", "decomposition",
          lambda ax, d: topology.draw_rebranched(ax, d.decomposition)),
    _spec("patches", "Patches: four- and three-sided, poles and ids (Figure 2f)", "decomposition",
          lambda ax, d: topology.draw_patches(ax, d.decomposition, d.layout)),
    _spec("mesh_coons", "Mesh before smoothing: the welded Coons patches (Figure 2g)", "mesh",
          lambda ax, d: meshes.draw_mesh(ax, d.coons, "before smoothing")),
    _spec("mesh_smoothed", "Mesh after smoothing, singularities by valence (Figure 2h)", "mesh",
          lambda ax, d: meshes.draw_smoothed(ax, d.mesh)),
)


#: The panel's tiles: each step's figure at half its size (pixels), under a band for its title.
TILE = int(style.FIGSIZE[0] * style.DPI) // 2
BAND = 30


def _draw_panel(fig, data: Stages) -> None:
    """The eight steps of Figure 2 as one image: each step's own figure (the image :func:`write_figures`
    has just written, or drawn now) halved by averaging its pixels 2 by 2, titled (a) to (h). The
    panel draws nothing of its own but the titles (resampling eight images in axes took 0.5 s)."""
    grid = np.full((2 * (TILE + BAND), 4 * TILE, 4), 255, dtype=np.uint8)
    for k, (spec, letter) in enumerate(zip(PANEL, "abcdefgh")):
        row, col = divmod(k, 4)
        top = row * (TILE + BAND) + BAND
        grid[top:top + TILE, col * TILE:(col + 1) * TILE] = _halved(_step_image(spec, data))
        fig.text((col + 0.5) / 4, 1 - (top - BAND / 2) / len(grid), f"({letter}) {spec.name.replace('_', ' ')}",
                 ha="center", va="center", fontsize=10, gid=f"title-{spec.name}")
    fig.figimage(grid, origin="upper")


def _step_image(spec: FigureSpec, data: Stages) -> np.ndarray:
    """The RGBA pixels (bytes) of one step's figure: written already, or drawn now."""
    image = data.rendered.get(spec.name)
    return style.pixels(figure(spec, data)) if image is None else image


def _halved(image: np.ndarray) -> np.ndarray:
    """``image`` (bytes) at half its size (:data:`TILE` square), each pixel the mean of four, rounded.

    >>> _halved(np.full((2 * TILE, 2 * TILE, 4), 7, dtype=np.uint8))[0, 0].tolist()
    [7, 7, 7, 7]
    """
    a = np.asarray(image)[:2 * TILE, :2 * TILE, :4].astype(np.uint16)
    return ((a[0::2, 0::2] + a[1::2, 0::2] + a[0::2, 1::2] + a[1::2, 1::2] + 2) // 4).astype(np.uint8)


def _draw_pair(fig, data: Stages) -> None:
    left, right = fig.subplots(1, 2)
    thrust.draw_form(left, data.network)
    thrust.draw_force(right, data.network)


#: Every figure, in the order of the report. The panel and the form-force pair draw on a whole figure.
CATALOGUE = (
    *PANEL,
    _spec("edge_groups", "Edge groups: the sides sharing a number of subdivisions (§3.2)", "mesh",
          lambda ax, d: meshes.draw_groups(ax, d.mesh, d.layout)),
    _spec("panel", "The eight steps as in the paper's Figure 2 (a)-(h)", "mesh", _draw_panel, "figure",
          final="supports"),
    _spec("form_force", "Form and force diagrams, line widths by horizontal force (Figure 10)", "network",
          _draw_pair, "figure"),
    _spec("thrust_plan", "Thrust network in plan, shaded by height", "network",
          lambda ax, d: thrust.draw_thrust_plan(ax, d.network)),
    _spec("thrust_3d", "Thrust network, axonometric, shaded by height, supports marked (Figure 13a)", "network",
          lambda ax, d: thrust.draw_thrust_3d(ax, d.network), "3d"),
    _spec("tessellation_plan", "Voussoirs in plan by course, keystones red (Figure 12b)", "tessellation",
          lambda ax, d: thrust.draw_tessellation_plan(ax, d.tessellation)),
    _spec("tessellation_3d", "Voussoirs in space by course, keystones red (Figure 13b)", "tessellation",
          lambda ax, d: thrust.draw_tessellation_3d(ax, d.tessellation), "3d"),
)

#: Figure sizes (inches) of the whole-figure drawings.
SIZES = {"panel": (4 * TILE / style.DPI, 2 * (TILE + BAND) / style.DPI), "form_force": (12.0, 6.0)}


def figure(spec: FigureSpec, data: Stages):
    """The matplotlib figure of ``spec`` for ``data``."""
    if spec.projection == "figure":
        fig = style.blank_figure(SIZES[spec.name])
        with style.matplotlib_rc():
            spec.draw(fig, data)
        return fig
    fig, ax = style.new_figure(projection=spec.projection)
    spec.draw(ax, data)
    return fig


#: The single figures each command writes beside its files, and the figure each is.
BESIDE = {"decomposition.png": "patches", "mesh.png": "mesh_smoothed", "thrust.png": "thrust_plan",
          "tessellation.png": "tessellation_plan"}


def write_figures(data: Stages, out: Path, specs=CATALOGUE) -> list[FigureSpec]:
    """``out/figures/NAME.png`` and ``.svg`` of every figure of ``specs`` that ``data`` has the stages
    for; the specs written."""
    written = []
    for spec in specs:
        if not spec.available(data):
            continue
        fig = figure(spec, data)
        png = out / "figures" / f"{spec.name}.png"
        style.save_png_and_svg(fig, png, png.with_suffix(".svg"))
        if spec in PANEL:
            from matplotlib.image import imread

            data.rendered[spec.name] = (imread(png) * 255).round().astype(np.uint8)
        written.append(spec)
    return written
