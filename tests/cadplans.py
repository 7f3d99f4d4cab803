"""One small plan drawn four ways for the CAD and COMPAS tests: vaultgram JSON, DXF (ezdxf) and Rhino
.3dm (rhino3dm) -- a 12 x 10 outline, a circular hole, a point feature and a curve feature."""

from __future__ import annotations

import numpy as np

from vaultgram.domain import domain_from_dict

OUTER = [[0, 0], [12, 0], [12, 10], [0, 10]]
CENTRE, RADIUS = (8.0, 5.0), 1.5
POINT = (3.0, 7.5)
CURVE = [[1.5, 3], [2.5, 4], [3.5, 4.4], [4.5, 4.5]]


def json_plan():
    """The test plan in vaultgram JSON: its hole a 48-gon."""
    t = np.linspace(0, 2 * np.pi, 48, endpoint=False)
    hole = np.c_[CENTRE[0] + RADIUS * np.cos(t), CENTRE[1] + RADIUS * np.sin(t)]
    return domain_from_dict({"outer": OUTER, "holes": [hole.tolist()], "points": [POINT], "curves": [CURVE]})


def dxf_plan(path, extra=None, units=6):
    """The test plan as a DXF: LWPOLYLINE outline, CIRCLE hole, POINT, SPLINE curve."""
    import ezdxf

    doc = ezdxf.new()
    doc.header["$INSUNITS"] = units
    msp = doc.modelspace()
    msp.add_lwpolyline(OUTER, close=True)
    msp.add_circle(CENTRE, RADIUS)
    msp.add_point(POINT)
    msp.add_spline(fit_points=[(x, y, 0) for x, y in CURVE])
    if extra:
        extra(doc, msp)
    doc.saveas(path)
    return path


def rhino_plan(path, layered=True, outline_open=False):
    """The test plan in a .3dm: closed polyline outline (open with ``outline_open``), circle hole, point,
    open NURBS curve; on the role layers, or all on one layer."""
    import rhino3dm

    model = rhino3dm.File3dm()
    model.Settings.ModelUnitSystem = rhino3dm.UnitSystem.Meters
    names = ["outer", "holes", "points", "curves"] if layered else ["Default"] * 4
    index = {name: model.Layers.AddLayer(name, (0, 0, 0, 255)) for name in dict.fromkeys(names)}

    def on(layer):
        attributes = rhino3dm.ObjectAttributes()
        attributes.LayerIndex = index[layer]
        return attributes

    outline = rhino3dm.Point3dList()
    for x, y in OUTER if outline_open else [*OUTER, OUTER[0]]:
        outline.Add(x, y, 0)
    model.Objects.AddPolyline(outline, on(names[0]))
    model.Objects.AddCircle(rhino3dm.Circle(rhino3dm.Point3d(*CENTRE, 0), RADIUS), on(names[1]))
    model.Objects.AddPoint(rhino3dm.Point3d(*POINT, 0), on(names[2]))
    curve = rhino3dm.Curve.CreateControlPointCurve([rhino3dm.Point3d(x, y, 0) for x, y in CURVE], 3)
    model.Objects.AddCurve(curve, on(names[3]))
    model.Write(str(path), 7)
    return path
