"""Figures of form finding and tessellation (§5, the paper's Figures 10, 12 and 13): the form and
force diagrams side by side with the horizontal forces as line widths, the thrust network in an
axonometric view shaded by height with its supports, and the voussoirs in plan and in space,
coloured by construction course with the keystones marked."""

from __future__ import annotations

import numpy as np

from vaultgram.io.figures.style import (
    COLOURS,
    COURSE_MAP,
    DENSE,
    HEIGHT_MAP,
    face_fills,
    face_means,
    lines,
    padded_faces,
    plan,
    points,
)

#: Line widths of the diagrams' edges: from the thinnest to the thickest (the largest force).
FORCE_WIDTHS = (0.2, 3.0)


def force_widths(forces: np.ndarray) -> np.ndarray:
    """Line widths proportional to the forces (the thinnest for none).

    >>> force_widths(np.array([0.0, 1.0, 2.0])).round(6).tolist()
    [0.2, 1.6, 3.0]
    """
    f = np.abs(np.asarray(forces, dtype=float))
    top = f.max() if len(f) and f.max() > 0 else 1.0
    return FORCE_WIDTHS[0] + (FORCE_WIDTHS[1] - FORCE_WIDTHS[0]) * f / top


def draw_form(ax, network) -> None:
    """Figure 10a: the form diagram after horizontal equilibrium, line widths by horizontal force,
    supports marked."""
    form = network.form
    lines(ax, form.xy[form.edges], "form", "black", force_widths(network.horizontal_forces))
    points(ax, form.xy[form.anchors], "supports", COLOURS["support"], marker="s", size=10)
    plan(ax, f"form diagram: {form.n_edges} edges, {int(form.anchors.sum())} supports")


def draw_force(ax, network) -> None:
    """Figure 10b: the reciprocal force diagram (turned parallel to the form), line widths by force."""
    force = network.force
    lines(ax, force.xy[force.edges], "force", "tab:blue", force_widths(network.horizontal_forces[force.form_edge]))
    plan(ax, f"force diagram: {force.n_edges} edges, max angle {network.summary['max_angle_deg']:.3g} deg")


def axonometric(ax, xyz: np.ndarray) -> None:
    """An orthographic (axonometric) view of ``xyz``'s box with true proportions, no panes or grid."""
    ax.set_proj_type("ortho")
    ax.view_init(elev=35, azim=-60)
    lo, hi = xyz.min(axis=0), xyz.max(axis=0)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], max(hi[2], lo[2] + 1e-9))
    ax.set_box_aspect(np.maximum(hi - lo, 1e-9 * max(np.ptp(xyz, axis=0).max(), 1.0)))
    ax.set_axis_off()


#: Above :data:`DENSE` faces in space, a face's corners where it turns by no more than this (degrees)
#: are left out of the drawing: the projection's cost grows with the most corners of any face, and
#: a voussoir's loop keeps every mesh vertex of its sides (34 corners at most at 10^6 faces, 7.5 on
#: average; none over 10 without these), a deviation of under 1% of a side, below a pixel there.
STRAIGHT = 1.0


def surface(ax, xyz: np.ndarray, faces, values, cmap: str, gid: str, edge: bool):
    """One ``Poly3DCollection`` of ``faces``, coloured by ``values`` through ``cmap``; above
    :data:`DENSE` faces without edge lines and without their straight corners (:data:`STRAIGHT`)."""
    from matplotlib import colormaps
    from matplotlib.colors import Normalize
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    values = np.asarray(values, dtype=float)
    colours = colormaps[cmap](Normalize(values.min(), max(values.max(), values.min() + 1e-12))(values))
    many = len(faces) > DENSE
    polys = padded_faces(xyz, faces, STRAIGHT if many else 0.0)
    dense = many or not edge
    collection = Poly3DCollection(polys, facecolors=colours, edgecolors="none" if dense else "0.2",
                                  linewidths=0 if dense else 0.2, gid=gid)
    ax.add_collection3d(collection, autolim=False)  # the limits are the axonometric's
    return collection


def draw_thrust_3d(ax, network) -> None:
    """Figure 13a: the thrust network in space, shaded by height, supports marked."""
    xyz = network.vertices
    heights = face_means(xyz[:, 2], network.faces)
    surface(ax, xyz, network.faces, heights, HEIGHT_MAP, "faces", edge=True)
    s = xyz[network.anchors]
    ax.scatter(s[:, 0], s[:, 1], s[:, 2], s=6, c=COLOURS["support"], marker="s", gid="supports", depthshade=False)
    axonometric(ax, xyz)
    ax.set_title(f"thrust network: {len(network.faces)} faces, z max {xyz[:, 2].max():.4g}", fontsize=9)


def draw_thrust_plan(ax, network) -> None:
    """The thrust network in plan, faces shaded by height (the legacy ``thrust.png``)."""
    xyz = network.vertices
    collection = face_fills(ax, xyz, network.faces, "faces",
                          values=face_means(xyz[:, 2], network.faces), cmap=HEIGHT_MAP)
    ax.figure.colorbar(collection, ax=ax, shrink=0.7, label="height z")
    plan(ax, f"thrust network: z max {xyz[:, 2].max():.4g}")


def draw_tessellation_plan(ax, tessellation) -> None:
    """Figure 12b: the voussoirs in plan, coloured by construction course, keystones in red."""
    x, layout = tessellation.vertices, tessellation.layout
    collection = face_fills(ax, x, layout.loops, "voussoirs", values=tessellation.courses,
                          cmap=COURSE_MAP, edgecolor="black", width=0.4)
    face_fills(ax, x, [layout.loops[k] for k in layout.keystones.tolist()], "keystones",
             COLOURS["keystone"], edgecolor="black", width=0.6, zorder=2)
    ax.figure.colorbar(collection, ax=ax, shrink=0.7, label="course (voussoirs from a support)")
    plan(ax, f"{layout.n_voussoirs} voussoirs, {len(layout.keystones)} keystones (red)")


def draw_tessellation_3d(ax, tessellation) -> None:
    """Figure 13b: the voussoirs in space (their intrados faces), coloured by course, keystones red."""
    x, layout = tessellation.vertices, tessellation.layout
    surface(ax, x, layout.loops, tessellation.courses, COURSE_MAP, "voussoirs", edge=True)
    keystones = [layout.loops[k] for k in layout.keystones.tolist()]
    if keystones:
        surface(ax, x, keystones, np.zeros(len(keystones)), "autumn", "keystones", edge=True)
    axonometric(ax, x)
    ax.set_title(f"{layout.n_voussoirs} voussoirs in space, {len(keystones)} keystones (red)", fontsize=9)
