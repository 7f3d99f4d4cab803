"""Generated bad inputs for the command line: domains, options, mesh files, GeoJSON, DXF, density and
support files. Each case is ``(name, args, files)``: ``files`` maps file names to their bytes, written
into a fresh folder; ``args`` may name them and ``OUT`` (the output folder, which must stay absent).
Every case must give exit code 2, exactly one line on stderr and no traceback (tests/test_bad_inputs.py).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import NamedTuple

SQUARE = [[0, 0], [30, 0], [30, 30], [0, 30]]
RULES = str(Path(__file__).resolve().parents[1] / "rules" / "topology.vgr")
HOLE = [[12, 12], [18, 12], [18, 18], [12, 18]]
OUT = "@OUT"


class Case(NamedTuple):
    name: str
    args: list
    files: dict


def _json(data) -> bytes:
    return json.dumps(data).encode()


def _domain(name: str, data, command: str = "mesh", raw: bytes | None = None) -> Case:
    return Case(f"domain/{name}", [command, "plan.json", "--out", OUT],
                {"plan.json": raw if raw is not None else _json(data)})


BAD_VALUES = [1.5, "1", True, None, {}, [], "abc", float("nan"), -1, [1], [[1]], [None, None], ["a", "b"],
              [True, False], [1e309, 0], [[0, 0]]]


def domain_cases() -> list[Case]:
    """Domains: wrong types for every member, bad coordinates, bad geometry, bad files."""
    cases = [
        _domain("not-json", None, raw=b"{outer: ["),
        _domain("empty-file", None, raw=b""),
        _domain("truncated", None, raw=_json({"outer": SQUARE})[:-5]),
        _domain("non-utf8", None, raw=b'{"outer": "\xff\xfe"}'),
        _domain("deep-nesting", None, raw=b"[" * 100_000 + b"]" * 100_000),
        _domain("top-list", SQUARE), _domain("top-string", "square"), _domain("top-null", None, raw=b"null"),
        _domain("no-outer", {"holes": []}),
        _domain("one-followed-by-309-zeros", None, raw=b'{"outer": [[0, 0], [1' + b"0" * 309 + b', 0], [0, 5]]}'),
        _domain("far-from-origin", {"outer": [[1e13 + x, 1e13 + y] for x, y in SQUARE]}),
        _domain("huge-plan-1e200", {"outer": [[0, 0], [1e200, 0], [1e200, 1e200], [0, 1e200]]}),
        _domain("nan-literal", None, raw=b'{"outer": [[0, 0], [NaN, 0], [30, 30]]}'),
        _domain("infinity-literal", None, raw=b'{"outer": [[0, 0], [Infinity, 0], [30, 30]]}'),
        _domain("two-vertices", {"outer": [[0, 0], [1, 0]]}),
        _domain("collinear", {"outer": [[0, 0], [1, 0], [2, 0]]}),
        _domain("bow-tie", {"outer": [[0, 0], [30, 30], [30, 0], [0, 30]]}),
        _domain("duplicate-vertex", {"outer": [[0, 0], [30, 0], [30, 0], [0, 30]]}),
        _domain("zero-area", {"outer": [[0, 0], [0, 0], [0, 0]]}),
        _domain("hole-outside", {"outer": SQUARE, "holes": [[[40, 40], [50, 40], [50, 50]]]}),
        _domain("hole-crossing", {"outer": SQUARE, "holes": [[[20, 20], [40, 20], [40, 25], [20, 25]]]}),
        _domain("point-outside", {"outer": SQUARE, "points": [[50, 50]]}),
        _domain("point-in-hole", {"outer": SQUARE, "holes": [HOLE], "points": [[15, 15]]}),
        _domain("curve-outside", {"outer": SQUARE, "curves": [[[40, 40], [50, 50]]]}),
        _domain("curve-one-vertex", {"outer": SQUARE, "curves": [[[10, 10]]]}),
        _domain("curve-through-hole", {"outer": SQUARE, "holes": [HOLE], "curves": [[[5, 15], [25, 15]]]}),
        _domain("name-number", {"outer": SQUARE, "name": 5}),
        _domain("supports-bad", {"outer": SQUARE, "supports": {"bogus": 1}}),
        _domain("supports-string", {"outer": SQUARE, "supports": "outer"}),
    ]
    for k, value in enumerate(BAD_VALUES):
        cases.append(_domain(f"outer-{k}", {"outer": value}))
        for member in ("holes", "points", "curves"):
            if value in ([],) or value is None or (member == "points" and value == [[0, 0]]):
                continue  # an empty or absent list is valid, and so is a point feature at a corner
            cases.append(_domain(f"{member}-{k}", {"outer": SQUARE, member: value}))
            cases.append(_domain(f"{member}-item-{k}", {"outer": SQUARE, member: [value]}))
        cases.append(_domain(f"vertex-{k}", {"outer": [[0, 0], [30, 0], value, [0, 30]]}))
        if not isinstance(value, (int, float)) or isinstance(value, bool) or value != value:
            cases.append(_domain(f"coordinate-{k}", {"outer": [[0, 0], [30, value], [30, 30], [0, 30]]}))
    return cases


def option_cases() -> list[Case]:
    """Option values: non-numbers, NaN, infinities, out of range, unknown options and commands."""
    plan = {"plan.json": _json({"outer": SQUARE})}
    cases = []
    numeric = {
        "mesh": ["--spacing", "--target-length", "--smooth", "--max-faces"],
        "design": ["--spacing", "--zmax", "--thickness", "--density", "--point-load", "--tol-deg", "--sag",
                   "--max-concavity", "--surface-smooth", "--target-length", "--smooth", "--max-faces"],
        "decompose": ["--spacing"],
        "formfind": ["--zmax", "--sag", "--tol-deg", "--spacing"],
    }
    for command, options in numeric.items():
        for option in options:
            for value in ("nan", "inf", "-inf", "abc", "-1", "1e400", ""):
                if option == "--point-load" and value == "-1":
                    continue  # an upward point load is allowed
                cases.append(Case(f"option/{command}{option}={value}",
                                  [command, "plan.json", "--out", OUT, option, value], plan))
    for command in ("mesh", "design", "decompose", "formfind", "stats", "tessellate", "trace"):
        cases.append(Case(f"option/{command}-unknown", [command, "plan.json", "--out", OUT, "--bogus"], plan))
        cases.append(Case(f"option/{command}-missing-file", [command, "absent.json", "--out", OUT], {}))
    cases += [
        Case("option/unknown-command", ["bogus"], {}),
        Case("option/mesh-no-out", ["mesh", "plan.json"], plan),
        Case("option/mesh-spacing-below", ["mesh", "plan.json", "--out", OUT, "--spacing", "1e-5"], plan),
        Case("option/mesh-smooth-huge", ["mesh", "plan.json", "--out", OUT, "--smooth", "100000"], plan),
        Case("option/mesh-tiny-target", ["mesh", "plan.json", "--out", OUT, "--target-length", "1e-3"], plan),
        Case("option/design-relax-mode", ["design", "plan.json", "--out", OUT, "--relax-mode", "x"], plan),
        Case("option/mesh-format", ["mesh", "plan.json", "--out", OUT, "--format", "png"], plan),
        Case("option/mesh-layer", ["mesh", "plan.json", "--out", OUT, "--layer", "outer"], plan),
    ]
    return cases


def _mesh(faces, vertices=None, **extra) -> dict:
    grid = [[x, y, 0.0] for y in range(3) for x in range(3)]
    return {"vertices": grid if vertices is None else vertices, "faces": faces, **extra}


GOOD_FACES = [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]]


def mesh_cases() -> list[Case]:
    """Mesh files for ``formfind MESH`` and ``stats``: wrong types, bad indices, bad topology."""
    bad = {
        "index-float": [[0, 1.5, 4, 3]], "index-string": [[0, "1", 4, 3]], "index-bool": [[0, True, 4, 3]],
        "index-null": [[0, None, 4, 3]], "index-negative": [[0, -1, 4, 3]], "index-out-of-range": [[0, 1, 4, 99]],
        "face-string": ["0123"], "face-number": [5], "face-object": [{}], "faces-object": {},
        "faces-string": "0 1 4 3", "two-vertices": [[0, 1]], "repeated-vertex": [[0, 1, 1, 3]],
        "flipped-face": [[0, 1, 4, 3], [1, 4, 5, 2], [3, 4, 7, 6], [4, 5, 8, 7]],
        "interior-edge-triangle": GOOD_FACES + [[1, 4, 0]],
        "pinched-vertex": [[0, 1, 4, 3], [4, 5, 8, 7]],
        "duplicate-face": GOOD_FACES + [[0, 1, 4, 3]],
        "no-faces": [],
    }
    meshes = {name: _mesh(faces) for name, faces in bad.items()}
    meshes.update({
        "vertices-object": _mesh(GOOD_FACES, {}), "vertices-string": _mesh(GOOD_FACES, "abc"),
        "vertex-nan": _mesh(GOOD_FACES, [[0, 0, 0]] * 8 + [[float("nan"), 0, 0]]),
        "vertex-short": _mesh(GOOD_FACES, [[0]] * 9), "vertex-bool": _mesh(GOOD_FACES, [[True, 0, 0]] * 9),
        "vertex-strings": _mesh(GOOD_FACES, [["0", "0", "0"]] * 9),
        "coincident-vertices": _mesh(GOOD_FACES, [[0, 0, 0]] * 9),
        "labels-list": _mesh(GOOD_FACES, labels=[1]), "labels-bad-index": _mesh(GOOD_FACES, labels={"boundary": [99]}),
        "supports-out-of-range": _mesh(GOOD_FACES, supports=[99]), "supports-float": _mesh(GOOD_FACES, supports=[1.5]),
        "turning-bad": _mesh(GOOD_FACES, turning=[["a", 1]]), "ring-short": _mesh(GOOD_FACES, ring=[0]),
    })
    cases = []
    for name, data in meshes.items():
        files = {"mesh.json": _json(data)}
        cases.append(Case(f"mesh/formfind/{name}", ["formfind", "mesh.json", "--out", OUT, "--zmax", "1"], files))
        cases.append(Case(f"mesh/stats/{name}", ["stats", "mesh.json"], files))
    for name, text in {"obj-bad-index": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "obj-no-face": "v 0 0 0\n",
                       "obj-bad-vertex": "v a b c\nf 1 2 3\n", "obj-repeated": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n",
                       "obj-non-utf8": "v 0 0 0\xff\n"}.items():
        cases.append(Case(f"mesh/{name}", ["formfind", "mesh.obj", "--out", OUT],
                          {"mesh.obj": text.encode("latin-1")}))
    return cases


def _geojson(name: str, data) -> Case:
    return Case(f"geojson/{name}", ["mesh", "plan.geojson", "--out", OUT], {"plan.geojson": _json(data)})


def geojson_cases() -> list[Case]:
    ring = SQUARE + [SQUARE[0]]
    poly = {"type": "Polygon", "coordinates": [ring]}
    feature = {"type": "Feature", "properties": {}, "geometry": poly}
    cases = [
        _geojson("properties-list", {**feature, "properties": [1]}),
        _geojson("coordinates-number", {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon",
                                                                                          "coordinates": 5}}),
        _geojson("geometries-null", {"type": "GeometryCollection", "geometries": None}),
        _geojson("geometries-object", {"type": "GeometryCollection", "geometries": {}}),
        _geojson("features-null", {"type": "FeatureCollection", "features": None}),
        _geojson("features-object", {"type": "FeatureCollection", "features": {}}),
        _geojson("features-numbers", {"type": "FeatureCollection", "features": [1, 2]}),
        _geojson("geometry-null", {"type": "Feature", "properties": {}, "geometry": None}),
        _geojson("geometry-list", {"type": "Feature", "properties": {}, "geometry": []}),
        _geojson("type-unknown", {"type": "Bogus"}),
        _geojson("type-number", {"type": 5}),
        _geojson("polygon-empty", {"type": "Polygon", "coordinates": []}),
        _geojson("polygon-ring-number", {"type": "Polygon", "coordinates": [5]}),
        _geojson("polygon-point-strings", {"type": "Polygon", "coordinates": [[["a", "b"]] * 4]}),
        _geojson("polygon-nan", {"type": "Polygon", "coordinates": [[[0, 0], [float("nan"), 0], [1, 1], [0, 0]]]}),
        _geojson("multipolygon-two", {"type": "MultiPolygon",
                                      "coordinates": [[ring], [[[p[0] + 50, p[1]] for p in ring]]]}),
        _geojson("role-unknown", {**feature, "properties": {"role": "bogus"}}),
        _geojson("role-number", {**feature, "properties": {"role": 5}}),
        _geojson("point-coordinates-object", {"type": "FeatureCollection", "features": [
            feature, {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": {}}}]}),
        _geojson("line-coordinates-number", {"type": "FeatureCollection", "features": [
            feature, {"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": 3}}]}),
        _geojson("no-polygon", {"type": "FeatureCollection", "features": []}),
        _geojson("supports-number", {**feature, "supports": 5}),
    ]
    return cases


def _dxf(name: str, text: bytes) -> Case:
    return Case(f"dxf/{name}", ["mesh", "plan.dxf", "--out", OUT], {"plan.dxf": text})


def _lwpolyline(points, layer="outer", closed=True) -> str:
    body = "".join(f" 10\n{x}\n 20\n{y}\n" for x, y in points)
    return (f"  0\nLWPOLYLINE\n  8\n{layer}\n 90\n{len(points)}\n 70\n{1 if closed else 0}\n" + body)


def _dxf_doc(*entities: str) -> bytes:
    return ("  0\nSECTION\n  2\nENTITIES\n" + "".join(entities) + "  0\nENDSEC\n  0\nEOF\n").encode()


def dxf_cases() -> list[Case]:
    good = _dxf_doc(_lwpolyline(SQUARE))
    return [
        _dxf("one-vertex-polyline", _dxf_doc(_lwpolyline([[0, 0]]))),
        _dxf("two-vertex-outer", _dxf_doc(_lwpolyline([[0, 0], [1, 0]]))),
        _dxf("truncated", good[: len(good) // 2]),
        _dxf("non-utf8", b"  0\nSECTION\n\xff\xfe\x00garbage"),
        _dxf("empty", b""),
        _dxf("garbage", b"this is not a dxf file\n"),
        _dxf("no-entities", _dxf_doc()),
        _dxf("bow-tie", _dxf_doc(_lwpolyline([[0, 0], [30, 30], [30, 0], [0, 30]]))),
        _dxf("coordinate-text", _dxf_doc("  0\nLWPOLYLINE\n  8\nouter\n 90\n3\n 70\n1\n 10\nabc\n 20\n0\n")),
        _dxf("hole-outside", _dxf_doc(_lwpolyline(SQUARE), _lwpolyline([[40, 40], [50, 40], [50, 50]], "holes"))),
        _dxf("open-outer-only", _dxf_doc(_lwpolyline([[0, 0], [30, 0], [30, 30]], closed=False))),
        _dxf("huge-coordinates", _dxf_doc(_lwpolyline([[0, 0], [1e200, 0], [1e200, 1e200]]))),
    ]


def density_cases() -> list[Case]:
    plan = _json({"outer": SQUARE})
    bad = [[], "x", 5, None, {"min_count": 1_000_000}, {"min_count": "2"}, {"min_count": 1.5}, {"min_count": True},
           {"min_count": 0}, {"target_length": "a"}, {"target_length": -1}, {"target_length": True},
           {"target_length": 0}, {"length_mode": "median"}, {"length_mode": 5}, {"groups": []}, {"groups": 5},
           {"groups": {"x": 3}}, {"groups": {"0": 0}}, {"groups": {"0": 1.5}}, {"groups": {"0": "3"}},
           {"groups": {"0": {"count": 3, "length": 1}}}, {"groups": {"0": {"length": -1}}},
           {"groups": {"999": 3}}, {"groups": {"0": 200_000}}, {"regions": {}}, {"regions": [1]},
           {"regions": [{"polygon": 5, "count": 2}]}, {"regions": [{"polygon": [[0, 0], [1, 1]], "count": 2}]},
           {"regions": [{"polygon": [["a", 0], [1, 0], [1, 1]], "count": 2}]},
           {"regions": [{"polygon": [[0, 0], [1, 0], [1, 1]]}]}, {"bogus": 1}]
    cases = [Case(f"densities/{k}", ["mesh", "plan.json", "--out", OUT, "--densities", "d.json"],
                  {"plan.json": plan, "d.json": _json(value)}) for k, value in enumerate(bad)]
    cases.append(Case("densities/not-json", ["mesh", "plan.json", "--out", OUT, "--densities", "d.json"],
                      {"plan.json": plan, "d.json": b"{"}))
    return cases


def support_cases() -> list[Case]:
    plan = _json({"outer": SQUARE})
    bad = [[], "x", 5, {}, {"rings": "a"}, {"rings": [5]}, {"rings": ["bogus"]}, {"vertices": [1.5]},
           {"vertices": [-1]}, {"vertices": ["1"]}, {"vertices": [True]}, {"vertices": {}}, {"vertices": 10**9},
           {"polylines": 5}, {"polylines": [[[1000, 1000], [2000, 1000]]]}, {"polylines": [[["a", 0], [1, 0]]]},
           {"polylines": [[[0, 0]]]}, {"polylines": {}}, {"rings": [], "vertices": []}, {"bogus": []}]
    cases = []
    for k, value in enumerate(bad):
        files = {"plan.json": plan, "s.json": _json(value)}
        cases.append(Case(f"supports/mesh/{k}", ["mesh", "plan.json", "--out", OUT, "--supports", "s.json"], files))
        cases.append(Case(f"supports/domain/{k}", ["mesh", "p.json", "--out", OUT],
                          {"p.json": _json({"outer": SQUARE, "supports": value})}))
    return cases


def graph_cases() -> list[Case]:
    """Host graphs for ``rules run --graph``: wrong types, unknown types, dangling edges."""
    corner = {"id": 0, "type": "Corner", "pos": [0, 0]}
    bad = {"list": [], "nodes-object": {"nodes": {}, "edges": []}, "id-float": {"nodes": [{**corner, "id": 1.5}]},
           "id-string": {"nodes": [{**corner, "id": "a"}]}, "id-bool": {"nodes": [{**corner, "id": True}]},
           "type-unknown": {"nodes": [{**corner, "type": "Bogus"}]},
           "pos-missing": {"nodes": [{"id": 0, "type": "Corner"}]},
           "pos-strings": {"nodes": [{**corner, "pos": ["a", 1]}]},
           "dangling-edge": {"nodes": [corner], "edges": [{"id": 0, "type": "Branch", "source": 0, "target": 5}]},
           "edges-object": {"nodes": [corner], "edges": {}}, "node-number": {"nodes": [1]},
           "edge-list": {"nodes": [corner], "edges": [[0, 0]]}, "string": "graph", "empty-object": {}}
    return [Case(f"graph/{name}", ["rules", "run", RULES, "--graph", "g.json", "--strategy", "topology", "--out", OUT],
                 {"g.json": _json(data)}) for name, data in bad.items()]


def all_cases() -> list[Case]:
    return [*domain_cases(), *option_cases(), *mesh_cases(), *geojson_cases(), *dxf_cases(), *density_cases(),
            *support_cases(), *graph_cases()]
