"""The figures of every stage (vaultgram.io.figures): what each draws is the model's content --
as many segments, polygons and markers as the stage has elements, supports and keystones drawn --
and the files are PNG and well-formed SVG, byte-identical on reruns."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.path import Path as MPath

from vaultgram.domain import load_domain
from vaultgram.geometry.meshes import grid_mesh
from vaultgram.io.figures import BAND, CATALOGUE, PANEL, TILE, Stages, figure, style, write_figures
from vaultgram.io.figures.meshes import draw_mesh, singular_vertices
from vaultgram.io.figures.topology import graph_polylines
from vaultgram.pipeline import design

from paths import EXAMPLES


@pytest.fixture(scope="module")
def data():
    """One design of a plan with a hole, two curves and three-sided patches, shared by the module."""
    return Stages.of(design(load_domain(EXAMPLES / "fig7_curves.json"), spacing=0.03))


def drawn(fig, gid: str):
    """The artist of ``fig`` with this gid (exactly one)."""
    found = [a for a in fig.findobj() if a.get_gid() == gid]
    assert len(found) == 1, (gid, len(found))
    return found[0]


def count(fig, gid: str) -> int:
    """How many segments, polygons or markers the artist ``gid`` draws."""
    from matplotlib.collections import LineCollection, PathCollection

    artist = drawn(fig, gid)
    if isinstance(artist, LineCollection):
        return len(artist.get_segments())
    if isinstance(artist, PathCollection):  # a scatter: one offset per marker
        return len(artist.get_offsets())
    return len(artist.get_paths())


def spec(name: str):
    return next(s for s in CATALOGUE if s.name == name)


def test_boundaries_draw_every_ring_segment_supports_and_features(data):
    fig = figure(spec("boundaries"), data)
    domain = data.domain
    assert count(fig, "boundaries") == len(domain.outer) + sum(len(h) for h in domain.holes)
    assert count(fig, "supports") == len(data.support_segments) > 0
    assert drawn(fig, "supports").get_linewidths()[0] > drawn(fig, "boundaries").get_linewidths()[0]
    assert count(fig, "curves") == sum(len(c) - 1 for c in domain.curves) > 0


def test_delaunay_colours_each_face_by_its_class(data):
    tri = data.decomposition.skeleton.triangulation
    faces = drawn(figure(spec("delaunay"), data), "faces")
    assert len(faces.get_paths()) == tri.n_faces
    colours = faces.get_facecolors()
    red = np.isclose(colours[:, :3], (0.839, 0.153, 0.157), atol=0.01).all(axis=1)
    assert red.sum() == (tri.kind == 3).sum() > 0


def test_skeleton_pruned_and_rebranched_draw_the_graphs_edges(data):
    dec = data.decomposition
    sk = dec.skeleton
    raw = figure(spec("skeleton"), data)
    assert count(raw, "skeleton") == sum(len(b.polyline) - 1 for b in sk.branches) + sum(
        len(lp.polyline) - 1 for lp in sk.loops)
    assert count(raw, "singularities") == len(sk.singularities())
    branch_segments = sum(len(p) - 1 for p in graph_polylines(dec.graph, "Branch"))
    pruned = figure(spec("pruned"), data)
    assert count(pruned, "branches") == branch_segments
    assert not [a for a in pruned.findobj() if a.get_gid() == "rebranches"]
    rebranched = figure(spec("rebranched"), data)
    assert count(rebranched, "rebranches") == sum(len(p) - 1 for p in graph_polylines(dec.graph, "Rebranch")) > 0


def test_patches_one_polygon_each_poles_and_ids(data):
    dec = data.decomposition
    fig = figure(spec("patches"), data)
    assert count(fig, "patches") == len(dec.patches)
    triangles = sum(p.pole is not None for p in data.layout.patterns)
    assert count(fig, "poles") == triangles > 0
    texts = {t.get_text() for t in fig.axes[0].texts}
    assert texts == {str(p.id) for p in dec.patches}


def test_meshes_before_and_after_smoothing(data):
    before = figure(spec("mesh_coons"), data)
    after = figure(spec("mesh_smoothed"), data)
    assert count(before, "faces") == count(after, "faces") == len(data.mesh.faces)
    assert not np.allclose(data.coons.vertices, data.mesh.vertices)  # smoothing moved them
    marked = sum(count(after, f"valence-{v}") for v in singular_vertices(data.mesh))
    assert marked == sum(len(v) for v in singular_vertices(data.mesh).values()) > 0


def test_edge_groups_colour_every_side_by_group(data):
    fig = figure(spec("edge_groups"), data)
    sides = drawn(fig, "sides")
    assert len(sides.get_segments()) == len(data.layout.sides)
    colours = {tuple(c) for c in sides.get_colors()}
    assert len(colours) == min(data.layout.n_groups, 20)


def test_form_and_force_widths_follow_the_forces(data):
    fig = figure(spec("form_force"), data)
    network = data.network
    form = drawn(fig, "form")
    assert len(form.get_segments()) == network.form.n_edges
    widths = np.asarray(form.get_linewidths())
    assert widths[np.argmax(network.horizontal_forces)] == pytest.approx(widths.max())
    assert len(drawn(fig, "force").get_segments()) == network.force.n_edges


def test_thrust_and_tessellation_in_space_and_plan(data):
    thrust = figure(spec("thrust_3d"), data)
    assert len(drawn(thrust, "faces").get_facecolor()) == len(data.network.faces)  # one colour per face
    assert len(drawn(thrust, "supports")._offsets3d[0]) == int(data.network.anchors.sum())
    t = data.tessellation
    for name in ("tessellation_plan", "tessellation_3d"):
        fig = figure(spec(name), data)
        n = (lambda a: len(a.get_facecolor())) if name.endswith("3d") else (lambda a: len(a.get_paths()))
        assert n(drawn(fig, "voussoirs")) == t.layout.n_voussoirs
        assert n(drawn(fig, "keystones")) == len(t.layout.keystones) > 0


def test_panel_has_the_eight_steps_of_figure_2(data):
    fig = figure(spec("panel"), data)
    titles = [text.get_text() for text in fig.texts]
    assert titles == [f"({letter}) {s.name.replace('_', ' ')}" for letter, s in zip("abcdefgh", PANEL)]
    grid = fig.images[0].get_array()  # each step's own figure, halved, in its tile
    step = style.pixels(figure(PANEL[5], data))[::2, ::2].astype(float)
    tile = grid[BAND + TILE + BAND:, TILE:2 * TILE].astype(float)  # (f) patches: second row, second column
    assert tile.shape == (TILE, TILE, 4) and abs(tile[..., :3].mean() - step[..., :3].mean()) < 2
    assert tile[..., :3].std() > 2  # not blank


def test_dense_meshes_are_shaded_not_lined_and_drawn_once(tmp_path):
    v, f = grid_mesh(150)  # 22500 faces
    mesh = SimpleNamespace(vertices=v, faces=f, pole=np.zeros(len(v), dtype=bool))
    fig, ax = style.new_figure()
    draw_mesh(ax, mesh, "dense")
    faces = drawn(fig, "faces")
    assert len(faces.get_paths()) == 1  # one colour: one compound path, a closed polygon per face
    codes = faces.get_paths()[0].codes
    assert (codes == MPath.MOVETO).sum() == (codes == MPath.CLOSEPOLY).sum() == len(f)
    assert not np.asarray(faces.get_linewidths()).any()
    style.save_png_and_svg(fig, tmp_path / "a.png", tmp_path / "a.svg")
    svg = ET.parse(tmp_path / "a.svg").getroot()  # the PNG, wrapped
    assert [child.tag.rsplit("}", 1)[1] for child in svg] == ["image"]


def test_written_figures_are_png_and_well_formed_svg_byte_identical(data, tmp_path):
    small = Stages(data.domain, data.decomposition)  # the topology figures only: quick
    written = write_figures(small, tmp_path / "a")
    write_figures(small, tmp_path / "b")
    assert [s.name for s in written] == [s.name for s in PANEL[:6]]
    for s in written:
        png = (tmp_path / "a" / "figures" / f"{s.name}.png").read_bytes()
        assert png.startswith(b"\x89PNG")
        svg = tmp_path / "a" / "figures" / f"{s.name}.svg"
        assert ET.parse(svg).getroot().tag.endswith("svg")
        for suffix in ("png", "svg"):
            name = f"figures/{s.name}.{suffix}"
            assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes(), name


def test_dense_fills_by_colour_give_the_pixels_of_one_polygon_per_face():
    """Above DENSE faces, the faces of each colour are one compound path: at every face's centre the
    picture has the colour the colour map gives its value, as with one polygon per face."""
    from matplotlib import colormaps

    v, f = grid_mesh(150)
    values = np.arange(len(f)) // 150 % 7  # rows of seven colours
    centres = v[np.asarray(f)].mean(axis=1)[:, :2]
    expected = colormaps["viridis"](values / 6, bytes=True)[:, :3]
    for dense in (False, True):
        fig, ax = style.new_figure()
        if dense:
            style.face_fills(ax, v, f, "faces", values=values, cmap="viridis")
            assert len(drawn(fig, "faces").get_paths()) == 7
        else:
            style.polygons(ax, style.face_polygons(v, f), "faces", values=values, cmap="viridis", width=0)
        style.plan(ax)
        picture = style.pixels(fig)
        px = np.rint(ax.transData.transform(centres)).astype(int)
        seen = picture[picture.shape[0] - 1 - px[:, 1], px[:, 0], :3]
        assert (np.abs(seen.astype(int) - expected).max(axis=1) <= 1).mean() > 0.99


def test_dense_surfaces_leave_out_straight_corners():
    """Faces in space whose loops run through a point on a straight side lose that point above DENSE
    faces (STRAIGHT): the padded polygons are as wide as the faces' real corners, and as many."""
    from matplotlib.figure import Figure

    from vaultgram.io.figures.thrust import STRAIGHT, surface

    v, f = grid_mesh(150)
    v[:, 2] = np.hypot(v[:, 0] - 75, v[:, 1] - 75) / 10  # a cone: every face turns at its corners
    corners, n = np.asarray(f), len(v)
    v = np.vstack([v, (v[corners[:, 0]] + v[corners[:, 1]]) / 2])  # each face's first side halved
    loops = [(a, m, b, c, d) for (a, b, c, d), m in zip(corners.tolist(), range(n, len(v)))]
    assert style.padded_faces(v, loops).shape == (len(loops), 5, 3)
    assert style.padded_faces(v, loops, STRAIGHT).shape == (len(loops), 4, 3)
    ax = Figure().add_subplot(projection="3d")
    assert len(surface(ax, v, loops, np.zeros(len(loops)), "viridis", "faces", True).get_facecolor()) == len(loops)
