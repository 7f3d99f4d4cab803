"""The designer's formats on the command line: a .3dm plan designed into result.3dm, DXF and COMPAS
outputs, formfind on COMPAS and OBJ patterns, and bad CAD files as one line with exit code 2."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from vaultgram.cli import main

from cadplans import dxf_plan, rhino_plan  # isort: skip
from paths import EXAMPLES  # isort: skip

rhino3dm = pytest.importorskip("rhino3dm")
ezdxf = pytest.importorskip("ezdxf")
pytest.importorskip("compas_tna")

FAST = ["--spacing", "0.04", "--target-length", "1.0"]


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def layer_objects(path):
    """Layer name -> the geometry of its objects, of a .3dm file read back with rhino3dm."""
    model = rhino3dm.File3dm.Read(str(path))
    names = [layer.Name for layer in model.Layers]
    out = {name: [] for name in names}
    for obj in model.Objects:
        out[names[obj.Attributes.LayerIndex]].append(obj)
    return out, model


@pytest.fixture(scope="module")
def designed(tmp_path_factory):
    """``vaultgram design`` on a .3dm plan drawn with rhino3dm, every format written."""
    tmp = tmp_path_factory.mktemp("design3dm")
    plan = rhino_plan(tmp / "plan.3dm")
    out = tmp / "out"
    result = run("design", plan, "--out", out, *FAST, "--format", "json,obj,compas,3dm,dxf", "--no-plots")
    assert result.exit_code == 0, result.output
    return out


def test_design_of_a_3dm_plan_writes_a_3dm_with_one_layer_per_stage(designed):
    layers, model = layer_objects(designed / "result.3dm")
    assert list(layers) == ["patches", "mesh", "form diagram", "force diagram", "thrust network", "thrust edges",
                            "supports", "voussoirs", "voussoir outlines"]
    mesh = json.loads((designed / "mesh.json").read_text())
    thrust = json.loads((designed / "thrust.json").read_text())
    voussoirs = json.loads((designed / "tessellation.json").read_text())
    patches = json.loads((designed / "patches.json").read_text())
    (m,) = [o.Geometry for o in layers["mesh"]]
    assert (len(m.Vertices), len(m.Faces)) == (len(mesh["vertices"]), len(mesh["faces"]))
    (t,) = [o.Geometry for o in layers["thrust network"]]
    assert len(t.Vertices) == len(thrust["vertices"])
    assert len(layers["thrust edges"]) == len(layers["form diagram"]) == len(thrust["edges"])
    assert len(layers["supports"]) == len(thrust["anchors"])
    assert len(layers["patches"]) == len(patches["patches"])
    assert len(layers["voussoirs"]) == len(layers["voussoir outlines"]) == len(voussoirs["voussoirs"])
    q = [float(o.Attributes.GetUserString("q")) for o in layers["form diagram"]]
    np.testing.assert_allclose(q, thrust["q"], rtol=1e-11)
    z = [o.Geometry.Location.Z for o in layers["supports"]]
    assert max(abs(v) for v in z) < 1e-12
    assert model.Settings.ModelUnitSystem == rhino3dm.UnitSystem.Meters


def test_design_writes_dxf_and_compas(designed):
    doc = ezdxf.readfile(designed / "result.dxf")
    thrust = json.loads((designed / "thrust.json").read_text())
    msp = doc.modelspace()
    assert len(msp.query('POLYLINE[layer=="thrust edges"]')) == len(thrust["edges"])
    assert len(msp.query('POINT[layer=="supports"]')) == len(thrust["anchors"])
    assert doc.header["$INSUNITS"] == 6
    data = json.loads((designed / "thrust.compas.json").read_text())
    assert data["dtype"] == "compas.datastructures/Mesh"
    assert json.loads((designed / "form.compas.json").read_text())["dtype"] == "compas_tna.diagrams/FormDiagram"
    assert {"mesh.compas.json", "voussoirs.compas.json"} <= {p.name for p in designed.iterdir()}


def test_formats_choose_the_files(tmp_path):
    result = run("formfind", EXAMPLES / "quad_with_hole.json", "--out", tmp_path, *FAST, "--zmax", "3",
                 "--format", "dxf")
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["result.dxf"]
    again = tmp_path / "again"
    run("formfind", EXAMPLES / "quad_with_hole.json", "--out", again, *FAST, "--zmax", "3", "--format", "dxf")
    assert (again / "result.dxf").read_bytes() == (tmp_path / "result.dxf").read_bytes()
    bad = run("formfind", EXAMPLES / "quad_with_hole.json", "--out", tmp_path / "x", "--format", "json,stl")
    assert bad.exit_code == 2 and "unknown format 'stl'" in bad.output and not (tmp_path / "x").exists()


@pytest.fixture(scope="module")
def patterns(tmp_path_factory):
    """A pattern mesh written as mesh.json, mesh.obj and mesh.compas.json by ``vaultgram mesh``."""
    out = tmp_path_factory.mktemp("patterns")
    result = run("mesh", EXAMPLES / "quad_with_hole.json", "--out", out, *FAST, "--format", "json,obj,compas")
    assert result.exit_code == 0, result.output
    return out


def thrust_of(pattern, out, *extra):
    result = run("formfind", pattern, "--out", out, "--zmax", "3", *extra)
    assert result.exit_code == 0, result.output
    return json.loads((out / "thrust.json").read_text())


@pytest.mark.parametrize("name, tol", [("mesh.compas.json", 0.0), ("mesh.obj", 1e-9)])
def test_formfind_on_compas_and_obj_patterns_gives_the_mesh_json_network(patterns, tmp_path, name, tol):
    reference = thrust_of(patterns / "mesh.json", tmp_path / "ref")
    other = thrust_of(patterns / name, tmp_path / "other")
    assert other["faces"] == reference["faces"] and other["edges"] == reference["edges"]
    assert other["anchors"] == reference["anchors"]
    np.testing.assert_allclose(other["vertices"], reference["vertices"], rtol=0, atol=tol * 3)
    np.testing.assert_allclose(other["q"], reference["q"], rtol=max(tol, 1e-15) * 10, atol=0)


def test_formfind_on_an_obj_with_ngons(tmp_path):
    """Two quads of a grid joined into a hexagon: formfind reads the n-gon and keeps it a face."""
    from vaultgram.geometry.meshes import grid_mesh

    v, f = grid_mesh(4)
    faces = [list(x) for k, x in enumerate(f) if k not in (5, 6)] + [[6, 7, 8, 13, 12, 11]]
    lines = [f"v {x} {y} 0" for x, y in v[:, :2].tolist()] + ["f " + " ".join(str(i + 1) for i in x) for x in faces]
    (tmp_path / "grid.obj").write_text("\n".join(lines) + "\n")
    thrust = thrust_of(tmp_path / "grid.obj", tmp_path / "out")
    assert len(thrust["faces"]) == len(faces) - 4 + 4  # corner quads lose their corner, stay faces
    assert max(len(x) for x in thrust["faces"]) == 6


def one_line_error(result, out, *names):
    assert result.exit_code == 2, result.output
    lines = [x for x in result.output.splitlines() if x.startswith("error:")]
    assert len(lines) == 1 and "Traceback" not in result.output
    assert not out.exists()
    for name in names:
        assert name in lines[0], lines[0]


def test_bad_cad_and_compas_files(tmp_path):
    out = tmp_path / "out"
    model = rhino3dm.File3dm()
    model.Objects.AddLine(rhino3dm.Point3d(0, 0, 0), rhino3dm.Point3d(1, 0, 0))
    model.Write(str(tmp_path / "open.3dm"), 7)
    one_line_error(run("design", tmp_path / "open.3dm", "--out", out), out, "open.3dm", "no closed curve")
    open_outer = rhino_plan(tmp_path / "open_outer.3dm", outline_open=True)
    one_line_error(run("design", open_outer, "--out", out), out, "open curve object 0 (PolylineCurve)",
                   "layer 'outer'")
    doc = ezdxf.new()
    doc.modelspace().add_text("plan")
    doc.saveas(tmp_path / "empty.dxf")
    one_line_error(run("mesh", tmp_path / "empty.dxf", "--out", out), out, "nothing usable", "TEXT #")
    (tmp_path / "graph.json").write_text(json.dumps({"dtype": "compas.datastructures/Graph", "data": {
        "attributes": {}, "default_node_attributes": {}, "default_edge_attributes": {}, "node": {}, "edge": {},
        "max_node": -1}}))
    one_line_error(run("formfind", tmp_path / "graph.json", "--out", out), out, "graph.json",
                   "not a COMPAS mesh (Graph)")


def test_dxf_warning_is_one_line(tmp_path):
    def extra(doc, msp):
        msp.add_text("plan")

    plan = dxf_plan(tmp_path / "plan.dxf", extra)
    result = run("mesh", plan, "--out", tmp_path / "out", *FAST)
    assert result.exit_code == 0, result.output
    warned = [x for x in result.output.splitlines() if x.startswith("warning:")]
    assert len(warned) == 1 and "TEXT #" in warned[0]


def test_tessellate_writes_voussoirs_to_dxf_and_compas(designed, tmp_path):
    result = run("tessellate", designed / "thrust.json", "--out", tmp_path, "--format", "dxf,compas")
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["result.dxf", "voussoirs.compas.json"]
    n = len(json.loads((designed / "tessellation.json").read_text())["voussoirs"])
    msp = ezdxf.readfile(tmp_path / "result.dxf").modelspace()
    assert len(msp.query('POLYLINE[layer=="voussoirs"]')) == len(msp.query('POLYLINE[layer=="voussoir outlines"]')) == n
    from compas.datastructures import Mesh

    solids = Mesh.from_json(str(tmp_path / "voussoirs.compas.json"))
    assert len(set(solids.faces_attribute("voussoir"))) == n and solids.is_manifold()


def test_decompose_writes_the_patches_to_a_dxf(tmp_path):
    plan = dxf_plan(tmp_path / "plan.dxf")
    result = run("decompose", plan, "--out", tmp_path / "out", "--format", "json,dxf")
    assert result.exit_code == 0, result.output
    patches = json.loads((tmp_path / "out" / "patches.json").read_text())["patches"]
    doc = ezdxf.readfile(tmp_path / "out" / "result.dxf")
    assert [layer.dxf.name for layer in doc.layers if layer.dxf.name in ("patches", "mesh")] == ["patches"]
    assert len(doc.modelspace().query('POLYLINE[layer=="patches"]')) == len(patches)
