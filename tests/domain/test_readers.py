"""Reading domains (vaultgram.domain.readers): formats, normalisation, file and structure errors."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from vaultgram.domain import domain_from_dict, domain_from_geojson, load_domain
from vaultgram.errors import DomainError

SQUARE = [[0, 0], [10, 0], [10, 10], [0, 10]]
HOLE = [[4, 4], [6, 4], [6, 6], [4, 6]]


def signed_area(r):
    x, y = r[:, 0], r[:, 1]
    return 0.5 * (np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def err(d) -> str:
    with pytest.raises(DomainError) as e:
        domain_from_dict(d)
    return str(e.value)


# --- formats and normalisation ---------------------------------------------------------------


def test_examples_load(examples_dir):
    q = load_domain(examples_dir / "quad_with_hole.json")
    assert q.name == "quad_with_hole"
    assert len(q.outer) == 4 and len(q.holes) == 1 and len(q.holes[0]) == 64
    assert q.area == pytest.approx(100 - 64 * 0.5 * 4 * math.sin(2 * math.pi / 64), rel=1e-12)
    lsh = load_domain(examples_dir / "l_shape.json")
    assert lsh.area == pytest.approx(75.0)


def test_normalisation_orientation_and_closing_vertex():
    d = domain_from_dict({"outer": SQUARE[::-1] + [SQUARE[::-1][0]], "holes": [HOLE]})
    assert len(d.outer) == 4
    assert signed_area(d.outer) > 0  # outer ccw
    assert signed_area(d.holes[0]) < 0  # holes cw
    assert d.outer.dtype == np.float64
    assert d.area == pytest.approx(96.0)
    with pytest.raises(ValueError):
        d.outer[0, 0] = 1.0  # immutable


def test_extra_keys_and_defaults():
    d = domain_from_dict({"outer": SQUARE, "source": "somewhere", "supports": {"rings": ["outer"]}})
    assert d.holes == () and d.points.shape == (0, 2) and d.curves == ()
    assert d.supports == {"rings": ["outer"]}


def test_geojson(tmp_path):
    gj = {
        "type": "FeatureCollection",
        "features": [
            {"type": "Feature", "properties": {"name": "g"},
             "geometry": {"type": "Polygon", "coordinates": [SQUARE + [SQUARE[0]], HOLE + [HOLE[0]]]}},
            {"type": "Feature", "geometry": {"type": "Point", "coordinates": [2, 2]}},
            {"type": "Feature", "geometry": {"type": "LineString", "coordinates": [[1, 5], [3, 5]]}},
        ],
    }
    p = tmp_path / "d.geojson"
    p.write_text(json.dumps(gj))
    d = load_domain(p)
    assert d.name == "g" and len(d.outer) == 4 and len(d.holes) == 1
    np.testing.assert_allclose(d.points, [[2, 2]])
    assert len(d.curves) == 1


def test_geojson_two_polygons_rejected(tmp_path):
    f = {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [SQUARE]}}
    p = tmp_path / "d.geojson"
    p.write_text(json.dumps({"type": "FeatureCollection", "features": [f, f]}))
    with pytest.raises(DomainError, match="exactly one Polygon"):
        load_domain(p)


def test_dxf(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline(HOLE, close=True)
    msp.add_lwpolyline(SQUARE, close=True)
    msp.add_point((2, 2))
    msp.add_lwpolyline([(1, 8), (3, 8), (3, 9)])
    p = tmp_path / "plan.dxf"
    doc.saveas(p)
    d = load_domain(p)
    assert d.name == "plan"
    assert d.area == pytest.approx(96.0)
    assert len(d.holes) == 1 and len(d.points) == 1 and len(d.curves) == 1


def test_dxf_outer_must_enclose(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline(SQUARE, close=True)
    msp.add_lwpolyline([(20, 0), (22, 0), (22, 2)], close=True)
    p = tmp_path / "bad.dxf"
    doc.saveas(p)
    with pytest.raises(DomainError, match="LWPOLYLINE #.* on layer '0' is not inside the outline"):
        load_domain(p)


def test_point_just_outside_is_snapped_onto_boundary():
    d = domain_from_dict({"outer": SQUARE, "points": [[10.05, 5.0]]})
    np.testing.assert_allclose(d.points, [[10.0, 5.0]], atol=1e-12)


# --- file errors ---------------------------------------------------------------------------------


def test_missing_and_empty_file(tmp_path):
    with pytest.raises(DomainError, match="file not found"):
        load_domain(tmp_path / "nope.json")
    p = tmp_path / "empty.json"
    p.write_text("  \n")
    with pytest.raises(DomainError, match="empty"):
        load_domain(p)


def test_json_syntax_error_has_line_and_column(tmp_path):
    p = tmp_path / "bad.json"
    p.write_text('{\n  "outer": [[0, 0], [1, 0]\n  "holes": []\n}')
    with pytest.raises(DomainError, match=r"bad\.json:3:3: invalid JSON"):
        load_domain(p)


def test_missing_outer_key():
    assert "missing required key 'outer'" in err({"holes": []})


def test_malformed_vertex():
    msg = err({"outer": [[0, 0], [1, 0], [1, "a"]]})
    assert "outer ring, vertex 2" in msg and "expected [x, y]" in msg
    msg = err({"outer": SQUARE, "holes": "nope"})
    assert "holes: expected a list" in msg


def test_supports_shape():
    assert "supports.rings[1]" in err({"outer": SQUARE, "supports": {"rings": ["outer", "x"]}})
    assert "supports: expected exactly one" in err({"outer": SQUARE, "supports": {"foo": 1}})
    assert "supports.polylines[0]" in err({"outer": SQUARE, "supports": {"polylines": [[[0, 0]]]}})


def test_schema_documents_format():
    from importlib import resources

    schema = json.loads(resources.files("vaultgram.domain").joinpath("domain.schema.json").read_text())
    assert schema["$schema"].endswith("2020-12/schema")
    assert schema["required"] == ["outer"]
    assert {"name", "outer", "holes", "points", "curves", "supports"} <= set(schema["properties"])
    jsonschema = pytest.importorskip("jsonschema")
    for ex in schema["examples"]:
        jsonschema.validate(ex, schema)


# --- GeoJSON roles ---------------------------------------------------------------------------------


def _feature(geometry, coordinates, **properties):
    return {"type": "Feature", "properties": properties, "geometry": {"type": geometry, "coordinates": coordinates}}


def test_geojson_roles():
    hole = [[4, 4], [6, 4], [6, 6], [4, 6], [4, 4]]
    d = domain_from_geojson({"type": "FeatureCollection", "features": [
        _feature("Polygon", [SQUARE + [SQUARE[0]]], role="outer"),
        _feature("Polygon", [hole], role="hole"),
        _feature("LineString", [[0, 0], [10, 0]], role="support"),
        _feature("Point", [2, 2], role="point"),
        _feature("LineString", [[1, 8], [3, 8]], role="curve")]})
    assert len(d.holes) == 1 and d.area == pytest.approx(96.0)
    assert d.supports == {"polylines": [[[0, 0], [10, 0]]]}
    assert len(d.points) == 1 and len(d.curves) == 1


def test_geojson_role_must_fit_the_geometry():
    with pytest.raises(DomainError, match=r"features\[1\]: a Point cannot have the role 'hole'"):
        domain_from_geojson({"type": "FeatureCollection", "features": [
            _feature("Polygon", [SQUARE + [SQUARE[0]]]), _feature("Point", [2, 2], role="hole")]})
    with pytest.raises(DomainError, match=r"features\[0\].properties.role: expected one of outer, hole"):
        domain_from_geojson(_feature("Polygon", [SQUARE + [SQUARE[0]]], role="wall"))


def test_geojson_multipolygon_parts_other_than_the_largest_are_an_error():
    small = [[20, 0], [21, 0], [21, 1], [20, 0]]
    with pytest.raises(DomainError, match=r"MultiPolygon of 2 parts: .* the largest is part 1 \(area 100\), the "
                                          r"other 1 would be lost"):
        domain_from_geojson(_feature("MultiPolygon", [[small], [SQUARE + [SQUARE[0]]]]))
    assert domain_from_geojson(_feature("MultiPolygon", [[SQUARE + [SQUARE[0]]]])).area == 100
