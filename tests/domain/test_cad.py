"""CAD plans: DXF (ezdxf) and Rhino .3dm (rhino3dm) read into domains, layers giving roles, nothing
dropped silently (vaultgram.domain.dxf, .rhino, .shapes)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from vaultgram.domain import load_domain
from vaultgram.errors import DomainError, VaultgramWarning
from vaultgram.pipeline import decompose

ezdxf = pytest.importorskip("ezdxf")

from cadplans import CENTRE, CURVE, OUTER, RADIUS, dxf_plan, json_plan, rhino_plan  # noqa: E402


def load_quietly(path, **kw):
    """load_domain, and the messages of the warnings it gave."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        d = load_domain(path, **kw)
    return d, [str(w.message) for w in caught if issubclass(w.category, VaultgramWarning)]


def layout(domain):
    dec = decompose(domain, 0.02)
    return dec.patches_json()["counts"], len(dec.singularities())


def test_dxf_plan_gives_the_json_plans_patch_layout(tmp_path):
    d, warned = load_quietly(dxf_plan(tmp_path / "plan.dxf"))
    assert warned == []
    assert (len(d.holes), len(d.points), len(d.curves), d.units) == (1, 1, 1, "m")
    hole = d.holes[0]
    np.testing.assert_allclose(np.hypot(*(hole - CENTRE).T), RADIUS, rtol=1e-6)  # on the circle
    assert len(hole) >= 32
    np.testing.assert_allclose(d.curves[0][[0, -1]], np.array(CURVE)[[0, -1]], atol=1e-9)  # the spline's ends
    assert layout(d) == layout(json_plan())


def test_text_and_hatch_are_named_in_a_warning(tmp_path):
    def extra(doc, msp):
        msp.add_text("plan", dxfattribs={"layer": "notes"})
        msp.add_hatch().paths.add_polyline_path([(0, 0), (1, 0), (1, 1)])

    d, warned = load_quietly(dxf_plan(tmp_path / "plan.dxf", extra))
    assert len(d.holes) == 1
    assert len(warned) == 1 and "2 entities not used" in warned[0]
    assert "TEXT #" in warned[0] and "on layer 'notes'" in warned[0] and "HATCH #" in warned[0]


def test_arcs_lines_ellipses_and_blocks(tmp_path):
    """A LINE + ARC outline joined into a ring, an ELLIPSE hole, a hole in an exploded block on the
    reference's layer, a LINE chain as a curve; no units."""
    doc = ezdxf.new(units=0)
    msp = doc.modelspace()
    for a, b in [((0, 0), (10, 0)), ((10, 0), (10, 10)), ((0, 10), (0, 0))]:
        msp.add_line(a, b)
    msp.add_arc((5, 10), 5, 0, 180)  # the top: a half circle from (10, 10) to (0, 10)
    msp.add_ellipse((3, 5), major_axis=(1, 0), ratio=0.5)
    block = doc.blocks.new("window")
    block.add_circle((0, 0), 0.5)
    msp.add_blockref("window", (7, 5), dxfattribs={"layer": "holes"})
    msp.add_line((2, 12), (5, 12.5))
    msp.add_line((5, 12.5), (8, 12))
    doc.saveas(tmp_path / "arcs.dxf")
    d, warned = load_quietly(tmp_path / "arcs.dxf")
    assert warned == [] and d.units is None
    assert d.area == pytest.approx(100 + np.pi * 25 / 2 - np.pi * 0.5 - np.pi * 0.25, rel=1e-3)
    assert len(d.holes) == 2 and len(d.curves) == 1 and len(d.curves[0]) == 3
    centres = sorted(np.round(h.mean(axis=0), 6).tolist() for h in d.holes)
    assert centres == [[3.0, 5.0], [7.0, 5.0]]


def test_layers_give_roles(tmp_path):
    """A closed curve on 'supports' supports the boundary it lies on; 'points' and 'curves' as named;
    layer names are configurable."""
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline(OUTER, close=True, dxfattribs={"layer": "Plan"})
    msp.add_line((0, 0), (12, 0), dxfattribs={"layer": "WALLS"})
    msp.add_point((6, 5), dxfattribs={"layer": "points"})
    doc.saveas(tmp_path / "roles.dxf")
    d, _ = load_quietly(tmp_path / "roles.dxf", layers={"outer": "plan", "supports": "walls"})
    assert d.supports == {"polylines": [[[0.0, 0.0], [12.0, 0.0]]]}
    assert len(d.points) == 1 and d.area == 120


@pytest.mark.parametrize("draw, message", [
    (lambda msp: msp.add_lwpolyline([(0, 0), (5, 0), (5, 5)], dxfattribs={"layer": "outer"}),
     r"open curve LWPOLYLINE #\w+ on layer 'outer': the outline must be a closed curve"),
    (lambda msp: msp.add_text("nothing"), r"nothing usable .*: only TEXT #\w+ on layer '0'"),
    (lambda msp: msp.add_line((0, 0), (1, 1)), r"no closed curve: the outline must be a closed curve"),
    (lambda msp: [msp.add_circle((0, 0), 1), msp.add_circle((5, 0), 1)],
     r"closed curve CIRCLE #\w+ on layer '0' is not inside the outline CIRCLE #\w+"),
])
def test_bad_dxf_is_one_error_naming_the_entity(tmp_path, draw, message):
    doc = ezdxf.new()
    draw(doc.modelspace())
    doc.saveas(tmp_path / "bad.dxf")
    with pytest.raises(DomainError, match=message) as err:
        load_quietly(tmp_path / "bad.dxf")
    assert str(err.value).startswith(str(tmp_path / "bad.dxf")) and "\n" not in str(err.value)


# --- Rhino .3dm ------------------------------------------------------------------------------------

rhino3dm = pytest.importorskip("rhino3dm")


@pytest.mark.parametrize("layered", [True, False])
def test_3dm_plan(tmp_path, layered):
    d, warned = load_quietly(rhino_plan(tmp_path / "plan.3dm", layered))
    assert warned == []
    assert (len(d.outer), len(d.holes), len(d.points), len(d.curves), d.units) == (4, 1, 1, 1, "m")
    np.testing.assert_allclose(np.hypot(*(d.holes[0] - CENTRE).T), RADIUS, rtol=1e-9)
    seg = np.hypot(*np.diff(d.curves[0], axis=0).T)
    assert seg.max() <= 0.02 * np.hypot(12, 10) + 1e-9 and seg.max() / seg.min() < 1.01  # equal arc lengths
    assert layout(d) == layout(json_plan())


def test_3dm_without_a_closed_curve(tmp_path):
    model = rhino3dm.File3dm()
    model.Objects.AddLine(rhino3dm.Point3d(0, 0, 0), rhino3dm.Point3d(1, 0, 0))
    model.Objects.AddSphere(rhino3dm.Sphere(rhino3dm.Point3d(0, 0, 0), 1.0))
    model.Write(str(tmp_path / "open.3dm"), 7)
    with pytest.raises(DomainError, match=r"open.3dm: no closed curve: .*1 open curve"):
        with pytest.warns(VaultgramWarning, match=r"object 1 \(\w+\)"):
            load_domain(tmp_path / "open.3dm")


def test_not_a_3dm_file(tmp_path):
    (tmp_path / "plan.3dm").write_text("not a model")
    with pytest.raises(DomainError, match="not a readable .3dm file"):
        load_domain(tmp_path / "plan.3dm")
