"""The one style of vaultgram's figures, and the drawing primitives every figure uses.

Every figure draws with collections (one artist per kind of element, never one per line), so a
figure of 10^5 faces costs about what a figure of 10^2 does; above :data:`DENSE` elements the edge
lines of faces drop out (the shading carries the picture). A figure is drawn once, by Agg: its SVG
holds its PNG (:func:`save_png_and_svg`; drawing it again as vector SVG took as long as the PNG, and
an SVG of 10^5 vector polygons would weigh tens of megabytes). Artists carry a ``gid`` naming what
they show (``"supports"``, ``"faces"``...): the tests count what was drawn through it, and the SVG
keeps it as the element's id.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from vaultgram.geometry.meshes import corner_arrays

#: Above this many elements a collection draws no edge lines (the shading carries the picture).
DENSE = 20000

#: Colours shared by all figures.
COLOURS = {
    "boundary": "black", "support": "black", "hole": "0.25", "point": "tab:red", "curve": "tab:purple",
    "branch": "tab:blue", "rebranch": "tab:orange", "diagonal": "tab:green", "singular": "tab:red",
    "quad": "#cfe2f3", "triangle": "#f9cb9c", "pole": "tab:red", "mesh": "0.35", "keystone": "tab:red",
    "face_regular": "#e8e8e8", "face_singular": "tab:red", "face_corner": "tab:blue", "face_isolated": "0.5",
}
#: Line widths: supports thick (as the paper's Figure 9a), the rest thin.
WIDTHS = {"support": 3.0, "boundary": 1.0, "curve": 2.0, "branch": 1.0, "mesh": 0.3}
HEIGHT_MAP = "viridis"
COURSE_MAP = "viridis"
FIGSIZE = (7.0, 7.0)
DPI = 100
#: Fixed margins (a constrained layout costs more than the drawing itself, at every save).
MARGINS = dict(left=0.02, right=0.98, bottom=0.02, top=0.93, wspace=0.05, hspace=0.12)
#: Deterministic SVG (fixed ids) with real text (smaller and faster than text as paths); titles at a
#: fixed height (placing them automatically measures every axis, at every save).
RC = {"svg.hashsalt": "vaultgram", "svg.fonttype": "none", "axes.titley": 1.0}


def new_figure(shape=(1, 1), size=FIGSIZE, projection: str | None = None):
    """A figure (no pyplot: no global state, no screen) and its axes (an array for ``shape`` other than
    (1, 1))."""
    fig = blank_figure(size)
    with matplotlib_rc():
        axes = fig.subplots(*shape, subplot_kw={"projection": projection} if projection else None, squeeze=False)
    return fig, axes[0, 0] if shape == (1, 1) else axes


def matplotlib_rc():
    """The context of every figure's axes and saves (:data:`RC`)."""
    import matplotlib

    return matplotlib.rc_context(RC)


def blank_figure(size=FIGSIZE):
    """A figure with the fixed margins and no axes yet."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=size)
    fig.subplots_adjust(**MARGINS)
    return fig


def plan(ax, title: str = "") -> None:
    """Equal aspect, no axes, limits from what was drawn."""
    ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_axis_off()
    if title:
        ax.set_title(title, fontsize=9)


#: Above :data:`DENSE` segments of one colour, the line widths drawn (per-line widths rounded to these).
WIDTH_CLASSES = 12


def lines(ax, segments, gid: str, color="black", width=1.0, zorder=2):
    """One ``LineCollection`` of ``segments`` ((k, 2, 2) or a list of polylines); ``width`` may be per line.
    Above :data:`DENSE` segments of one colour, the segments of each width are one path
    (:func:`merged_by_width`): Agg draws a path of 10^4 pieces in the time of a few separate ones."""
    from matplotlib.collections import LineCollection

    if isinstance(segments, np.ndarray) and len(segments) > DENSE and isinstance(color, str):
        segments, width = merged_by_width(segments, width)
    collection = LineCollection(segments, colors=color, linewidths=width, zorder=zorder, gid=gid,
                                capstyle="round")
    ax.add_collection(collection)
    return collection


def merged_by_width(segments: np.ndarray, width) -> tuple[list, list]:
    """The segments (k, 2, 2) as one polyline per width (NaN rows between the pieces: a break in the
    line), the per-line widths first rounded to :data:`WIDTH_CLASSES` steps; the polylines and their widths.

    >>> lines_, widths = merged_by_width(np.zeros((3, 2, 2)), [1.0, 3.0, 1.0])
    >>> [len(p) for p in lines_], widths
    ([5, 2], [1.0, 3.0])
    """
    w = np.broadcast_to(np.asarray(width, dtype=float), (len(segments),))
    lo, hi = float(w.min()), float(w.max())
    step = (hi - lo) / (WIDTH_CLASSES - 1) if hi > lo else 1.0
    level = np.rint((w - lo) / step).astype(np.int64)
    gap = np.full((len(segments), 1, 2), np.nan)
    pieces = np.concatenate([segments, gap], axis=1)  # each segment, then a break
    out, widths = [], []
    for k in np.unique(level).tolist():
        out.append(pieces[level == k].reshape(-1, 2)[:-1])
        widths.append(lo + k * step)
    return out, widths


def polygons(ax, polys, gid: str, facecolors="none", values=None, cmap=None, edgecolor="0.35", width=0.3,
             zorder=1):
    """One ``PolyCollection``: ``facecolors`` given, or ``values`` through ``cmap``; the edge lines drop
    out above :data:`DENSE` polygons."""
    from matplotlib.collections import PolyCollection

    dense = len(polys) > DENSE
    collection = PolyCollection(polys, facecolors=facecolors if values is None else None,
                                edgecolors="none" if dense else edgecolor, linewidths=0 if dense else width,
                                cmap=cmap, zorder=zorder, gid=gid)
    if values is not None:
        collection.set_array(np.asarray(values, dtype=float))
    ax.add_collection(collection)
    return collection


def face_fills(ax, vertices, faces, gid: str, facecolors="none", values=None, cmap=None, edgecolor="0.35",
               width=0.3, zorder=1):
    """The ``faces`` of a mesh in plan as :func:`polygons` draws them; above :data:`DENSE` faces (no
    edge lines) the faces of each colour as one compound path, all in one ``PathCollection``. Agg fills
    a path of many polygons in one pass where it takes a path per face one by one: the plan of the
    400,000 voussoirs of a 10^6-face design 4.1 -> 1.2 s. A colour map looks values up in a table of
    ``cmap.N`` colours, so grouping the faces by their colour changes no pixel's colour; the
    collection keeps ``cmap`` and the values' range for a colour bar.

    >>> import matplotlib; from matplotlib.figure import Figure
    >>> ax = Figure().subplots()
    >>> v = np.array([[0.0, 0], [1, 0], [1, 1], [0, 1], [2, 0], [2, 1]])
    >>> f = [(0, 1, 2, 3), (1, 4, 5, 2)] * (DENSE // 2 + 1)
    >>> c = face_fills(ax, v, f, "faces", values=np.arange(len(f)) % 2, cmap="viridis")
    >>> len(c.get_paths()), int((c.get_paths()[0].codes == 1).sum())  # two colours, a MOVETO per face
    (2, 10001)
    """
    if len(faces) <= DENSE:
        return polygons(ax, face_polygons(vertices, faces), gid, facecolors, values, cmap, edgecolor, width, zorder)
    from matplotlib import colormaps
    from matplotlib.collections import PathCollection
    from matplotlib.colors import Normalize, to_rgba_array

    if values is None:
        colour, rgba = np.zeros(len(faces), dtype=np.int64), to_rgba_array(facecolors)[:1]
    else:
        values = np.asarray(values, dtype=float)
        norm = Normalize(values.min(), values.max())
        looked_up = colormaps[cmap](norm(values), bytes=True)  # (faces, 4) bytes: the table's colour
        _, first, colour = np.unique(looked_up.view(np.uint32).ravel(), return_index=True, return_inverse=True)
    collection = PathCollection(_compound_paths(np.asarray(vertices, dtype=float)[:, :2], faces, colour),
                                edgecolors="none", linewidths=0, zorder=zorder, gid=gid)
    if values is None:
        collection.set_facecolor(rgba)
    else:  # each path's colour from the value of its first face
        collection.set(cmap=cmap, norm=norm, array=values[first])
    ax.add_collection(collection)
    return collection


def _compound_paths(x: np.ndarray, faces, colour: np.ndarray) -> list:
    """One path per colour (``colour`` numbers the faces' colours from 0): each face of that colour
    a closed polygon of it, in face order."""
    from matplotlib.path import Path as MPath

    sizes, flat = _flat_faces(faces)
    order = np.argsort(colour, kind="stable")
    first = np.concatenate([[0], np.cumsum(sizes)[:-1]])[order]
    length = sizes[order] + 1  # the corners and the closing vertex
    end = np.cumsum(length)
    start = end - length
    k = np.arange(int(end[-1])) - np.repeat(start, length)  # the corner's place in its face
    k[end - 1] = 0  # closing: the first corner again
    verts = x[flat[np.repeat(first, length) + k]]
    codes = np.full(len(verts), MPath.LINETO, dtype=MPath.code_type)
    codes[start], codes[end - 1] = MPath.MOVETO, MPath.CLOSEPOLY
    cut = np.concatenate([[0], end])[np.searchsorted(colour[order], np.arange(int(colour.max()) + 2))]
    return [MPath(verts[a:b], codes[a:b]) for a, b in zip(cut[:-1].tolist(), cut[1:].tolist())]


def points(ax, xy, gid: str, color="tab:red", marker="o", size=20.0, zorder=4, label=None):
    """One scatter of the rows of ``xy`` (nothing for none)."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    return ax.scatter(xy[:, 0], xy[:, 1], s=size, c=color, marker=marker, zorder=zorder, gid=gid, label=label,
                      linewidths=0)


def polyline_segments(polylines) -> np.ndarray:
    """The segments (k, 2, 2) of polylines, in order.

    >>> polyline_segments([np.array([[0, 0], [1, 0], [1, 1]])]).shape
    (2, 2, 2)
    """
    parts = [np.stack([p[:-1], p[1:]], axis=1) for p in (np.asarray(q, dtype=float)[:, :2] for q in polylines)
             if len(p) > 1]
    return np.concatenate(parts) if parts else np.zeros((0, 2, 2))


def face_polygons(vertices, faces) -> np.ndarray:
    """Each face's corners in plan, as one array (faces, most corners, 2): shorter faces repeat their
    last corner. matplotlib builds the paths of an array of polygons in one go, and of a list of
    polygons one by one (seconds at 10^5 faces).

    >>> face_polygons(np.array([[0, 0], [1, 0], [1, 1], [0, 1]]), [(0, 1, 2, 3), (0, 1, 2)])[1].tolist()
    [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0, 1.0]]
    """
    return padded_faces(np.asarray(vertices, dtype=float)[:, :2], faces)


def face_means(values: np.ndarray, faces) -> np.ndarray:
    """The mean of ``values`` over each face's corners.

    >>> face_means(np.array([0.0, 1.0, 2.0, 3.0]), [(0, 1, 2, 3), (0, 1, 2)]).tolist()
    [1.5, 1.0]
    """
    sizes, flat = _flat_faces(faces)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]]) if len(sizes) else sizes
    return np.add.reduceat(values[flat], starts) / sizes if len(sizes) else np.zeros(0)


def _flat_faces(faces, x: np.ndarray | None = None, straight: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Each face's number of corners, and all the corners in one array: the faces' corner arrays
    (:func:`~vaultgram.geometry.meshes.corner_arrays`, kept by a ``Faces``; the 400,000 voussoir loops
    of a 10^6-face design were read number by number, 1.2 s a figure); with ``straight`` (degrees),
    without the corners where the loop through ``x`` turns by no more than that."""
    face, vert, nxt, prev = corner_arrays(faces)
    if straight > 0:
        a, b = x[vert] - x[prev], x[nxt] - x[vert]
        with np.errstate(invalid="ignore", divide="ignore"):
            cos = np.einsum("ij,ij->i", a, b) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
        bent = ~(cos >= np.cos(np.radians(straight)))  # a zero-length side keeps its corner
        face, vert = face[bent], vert[bent]
    return np.bincount(face, minlength=len(faces)), vert


def padded_faces(x: np.ndarray, faces, straight: float = 0.0) -> np.ndarray:
    """``x`` at the corners of every face, as one array (faces, most corners, dims), shorter faces
    repeating their last corner; with ``straight`` (degrees), the corners where a face turns by no
    more than that left out (:func:`_flat_faces`).

    >>> square = np.array([[0, 0], [0.5, 0.001], [1, 0], [1, 1], [0, 1]])
    >>> padded_faces(square, [(0, 1, 2, 3, 4)], straight=1.0).tolist()
    [[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]]
    """
    sizes, flat = _flat_faces(faces, x, straight)
    if not len(sizes):
        return np.zeros((0, 3, x.shape[1]))
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    k = np.arange(sizes.max())
    index = starts[:, None] + np.minimum(k[None, :], sizes[:, None] - 1)
    return x[flat[index]]


def save(fig, path: Path) -> None:
    """Write ``fig`` to ``path`` (PNG or SVG by its suffix) atomically and byte-identically on reruns
    (no timestamps or version metadata, fixed SVG ids)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    svg = path.suffix == ".svg"
    options = dict(metadata={"Date": None, "Creator": None}) if svg else dict(
        metadata={"Software": None}, pil_kwargs={"compress_level": 1})  # the default 6 takes 4 times longer
    with matplotlib_rc():
        fig.savefig(tmp, dpi=DPI, **options)
    tmp.replace(path)


def pixels(fig) -> np.ndarray:
    """``fig`` drawn as it would be saved, as an RGBA array."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    with matplotlib_rc():
        fig.set_dpi(DPI)
        canvas.draw()
    return np.asarray(canvas.buffer_rgba())


def save_png_and_svg(fig, png: Path, svg: Path) -> None:
    """Write ``fig`` as PNG, and as an SVG that holds that PNG: one drawing serves both (the report
    inlines the SVG, :mod:`vaultgram.io.report`)."""
    save(fig, png)
    import base64

    width, height = fig.get_size_inches() * 72
    data = base64.b64encode(png.read_bytes()).decode("ascii")
    write_svg = svg.with_name(f".{svg.stem}.{os.getpid()}.tmp{svg.suffix}")
    write_svg.write_text(
        "<?xml version='1.0' encoding='utf-8'?>\n"
        f"<svg xmlns='http://www.w3.org/2000/svg' xmlns:xlink='http://www.w3.org/1999/xlink' "
        f"width='{width:g}pt' height='{height:g}pt' viewBox='0 0 {width:g} {height:g}' version='1.1'>"
        f"<image width='{width:g}' height='{height:g}' xlink:href='data:image/png;base64,{data}'/></svg>\n")
    write_svg.replace(svg)
