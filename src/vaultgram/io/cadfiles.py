"""Results as CAD drawings: Rhino ``.3dm`` (rhino3dm, optional extra ``vaultgram[rhino]``) and DXF (ezdxf).

:func:`drawing` turns the stages a run computed into :class:`Item` s on one layer per stage (the names
in :data:`LAYERS`, in pipeline order); :func:`write_3dm` and :func:`write_dxf` draw the same items:

* ``patches`` -- one closed polyline per patch of the decomposition (user strings ``patch``, ``sides``);
* ``mesh`` -- the pattern mesh as one mesh;
* ``form diagram`` -- one line per edge of the thrust network in plan (``q``, ``force``);
* ``force diagram`` -- one line per force-diagram edge, beside the plan (``form_edge``);
* ``thrust network`` -- its loaded faces as one mesh;
* ``thrust edges`` -- one 3D line per edge (``q``, ``force``, ``horizontal_force``);
* ``supports`` -- one point per support on the network (``rx``, ``ry``, ``rz``: the reaction);
* ``voussoirs`` -- one closed mesh per voussoir (``name``, ``course``), and ``voussoir outlines``
  their outlines in plan.

User strings are Rhino user strings in a .3dm and XDATA of the application ``VAULTGRAM`` in a DXF.
Both files record the plan's units when the domain has them. Files are written to a temporary name and
renamed. A DXF is the same bytes for the same result; a .3dm has the same layer and object ids, but
records the time it was written (rhino3dm sets it).
"""

from __future__ import annotations

import os
import uuid
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from vaultgram.errors import VaultgramError
from vaultgram.geometry.frames import to_plan

__all__ = ["Item", "drawing", "write_3dm", "write_dxf", "voussoir_solids", "LAYERS"]

#: The layers of a result drawing, in pipeline order, and their colours (RGB).
LAYERS = {"patches": (128, 128, 128), "mesh": (0, 0, 0), "form diagram": (0, 114, 178),
          "force diagram": (213, 94, 0), "thrust network": (0, 158, 115), "thrust edges": (0, 158, 115),
          "supports": (204, 121, 167), "voussoirs": (230, 159, 0), "voussoir outlines": (86, 180, 233)}


@dataclass(frozen=True, eq=False)
class Item:
    """One object of a result drawing.

    Attributes
    ----------
    kind : str
        ``"mesh"``, ``"polyline"`` or ``"point"``.
    xyz : ndarray (n, 3)
        Its vertices (one for a point).
    faces : tuple
        A mesh's faces (vertex-index sequences; n-gons are split into triangles where a format needs it).
    closed : bool
        A closed polyline (its first vertex is not repeated in ``xyz``).
    strings : tuple of (str, str)
        User strings.
    """

    kind: str
    xyz: np.ndarray
    faces: tuple = ()
    closed: bool = False
    strings: tuple = ()


def _xyz(xy: np.ndarray) -> np.ndarray:
    x = np.asarray(xy, dtype=float)
    return x if x.shape[1] == 3 else np.column_stack([x, np.zeros(len(x))])


def _lines(xyz: np.ndarray, edges: np.ndarray, strings) -> list[Item]:
    return [Item("polyline", xyz[[u, v]], strings=s) for (u, v), s in zip(edges.tolist(), strings)]


def _fmt(value: float) -> str:
    return f"{value:.12g}"


def drawing(decomposition=None, mesh=None, network=None, tessellation=None) -> dict:
    """The layers (name -> list of :class:`Item`) of the stages given, in pipeline order, in the plan's
    coordinates (:mod:`vaultgram.geometry.frames`).

    Examples
    --------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.pipeline import form_find
    >>> layers = drawing(network=form_find(*grid_mesh(3), zmax=1.0))
    >>> {name: len(items) for name, items in layers.items()}
    {'form diagram': 12, 'force diagram': 12, 'thrust network': 1, 'thrust edges': 12, 'supports': 8}
    """
    layers: dict = {}
    if decomposition is not None:
        layers["patches"] = [Item("polyline", _xyz(to_plan(p.polygon(), decomposition.origin)), closed=True,
                                  strings=(("patch", str(p.id)), ("sides", str(len(p.sides)))))
                             for p in decomposition.patches]
    if mesh is not None:
        layers["mesh"] = [Item("mesh", _xyz(mesh.in_frame().vertices), tuple(tuple(f) for f in mesh.faces))]
    if network is not None:
        layers.update(_network_layers(network.in_frame()))
    if tessellation is not None:
        layers.update(_voussoir_layers(tessellation.in_frame()))
    return layers


def _network_layers(network) -> dict:
    """The form and force diagrams, the thrust network and its supports."""
    forces = [(("q", _fmt(q)), ("force", _fmt(f))) for q, f in zip(network.q.tolist(), network.forces.tolist())]
    form_xyz = _xyz(network.form.xy)
    force = network.force
    span = np.ptp(network.form.xy, axis=0)
    shift = np.array([network.form.xy[:, 0].max() + 0.2 * span[0] - force.xy[:, 0].min(),
                      network.form.xy[:, 1].min() - force.xy[:, 1].min()])
    anchors = np.flatnonzero(network.anchors)
    return {
        "form diagram": _lines(form_xyz, network.edges, forces),
        "force diagram": _lines(_xyz(force.xy + shift), force.edges,
                                [(("form_edge", str(e)),) for e in force.form_edge.tolist()]),
        "thrust network": [Item("mesh", network.vertices, tuple(tuple(f) for f in network.faces))],
        "thrust edges": _lines(network.vertices, network.edges,
                               [(*s, ("horizontal_force", _fmt(h)))
                                for s, h in zip(forces, network.horizontal_forces.tolist())]),
        "supports": [Item("point", network.vertices[[v]], strings=tuple(zip(("rx", "ry", "rz"), map(_fmt, r))))
                     for v, r in zip(anchors.tolist(), network.reactions.tolist())],
    }


def voussoir_solids(tessellation) -> list[tuple[np.ndarray, np.ndarray]]:
    """Each voussoir's closed solid on its own vertices: ``(vertices (p, 3), triangles (t, 3))``
    (neighbours share joint faces in :class:`~vaultgram.tessellation.solids.Solids`; a drawing's meshes
    and a COMPAS mesh's faces must not)."""
    solids = tessellation.solids
    out = []
    for k in range(tessellation.layout.n_voussoirs):
        used, local = np.unique(solids.of(k), return_inverse=True)
        out.append((solids.vertices[used], local.reshape(-1, 3)))
    return out


def _voussoir_layers(tessellation) -> dict:
    """Each voussoir's solid (its own vertices) and its outline in plan."""
    layout = tessellation.layout
    meshes = [Item("mesh", x, tuple(map(tuple, tris.tolist())),
                   strings=(("name", tessellation.names[k]), ("course", str(tessellation.courses[k]))))
              for k, (x, tris) in enumerate(voussoir_solids(tessellation))]
    outlines = [Item("polyline", _xyz(tessellation.vertices[loop, :2]), closed=True,
                     strings=(("name", tessellation.names[k]),)) for k, loop in enumerate(layout.loops)]
    return {"voussoirs": meshes, "voussoir outlines": outlines}


# --------------------------------------------------------------------------------------------
# Rhino
# --------------------------------------------------------------------------------------------

#: Unit symbols (:attr:`vaultgram.domain.Domain.units`) and the names of Rhino's and DXF's units.
UNIT_NAMES = {"mm": "Millimeters", "cm": "Centimeters", "dm": "Decimeters", "m": "Meters", "km": "Kilometers",
              "in": "Inches", "ft": "Feet", "yd": "Yards", "mi": "Miles"}


def write_3dm(path: str | Path, layers: dict, units: str | None = None) -> None:
    """Write the layers of a result drawing to a Rhino .3dm file (version 7)."""
    from vaultgram.domain.rhino import rhino3dm_module

    r = rhino3dm_module(str(path))
    model = r.File3dm()
    model.Settings.ModelUnitSystem = getattr(r.UnitSystem, UNIT_NAMES.get(units or "", "None"))
    for name, items in layers.items():
        layer = r.Layer()
        layer.Name, layer.Color, layer.Id = name, (*LAYERS.get(name, (0, 0, 0)), 255), _uuid(name)
        index = model.Layers.Add(layer)
        for k, item in enumerate(items):
            attributes = r.ObjectAttributes()
            attributes.LayerIndex, attributes.Id = index, _uuid(f"{name}/{k}")
            for key, value in item.strings:
                attributes.SetUserString(key, value)
            _add_3dm(r, model, item, attributes)
    _atomic(Path(path), lambda tmp: model.Write(str(tmp), 7))


def _uuid(name: str) -> uuid.UUID:
    """A layer's or an object's id, made from its name: the same result gives the same ids (the file
    still records the time it was written)."""
    return uuid.uuid5(uuid.NAMESPACE_URL, f"vaultgram:{name}")


def _add_3dm(r, model, item: Item, attributes) -> None:
    """Add one item to a rhino3dm model: a mesh, a polyline (closed by repeating its start) or a point."""
    if item.kind == "point":
        model.Objects.AddPoint(r.Point3d(*map(float, item.xyz[0])), attributes)
        return
    if item.kind == "polyline":
        points = r.Point3dList()
        for x, y, z in (np.vstack([item.xyz, item.xyz[:1]]) if item.closed else item.xyz).tolist():
            points.Add(x, y, z)
        model.Objects.AddPolyline(points, attributes)
        return
    mesh = r.Mesh()
    for x, y, z in item.xyz.tolist():
        mesh.Vertices.Add(x, y, z)
    for face in _faces_of_at_most_four(item.faces):
        mesh.Faces.AddFace(*face)
    model.Objects.AddMesh(mesh, attributes)


def _faces_of_at_most_four(faces) -> list:
    """Triangles and quads as they are, larger faces as triangle fans."""
    out = []
    for f in faces:
        f = [int(v) for v in f]
        out += [f] if len(f) <= 4 else [[f[0], f[k], f[k + 1]] for k in range(1, len(f) - 1)]
    return out


def _atomic(path: Path, write) -> None:
    """Call ``write(tmp)`` for a temporary file beside ``path``, then rename it into place."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    try:
        if write(tmp) is False:
            raise VaultgramError(f"{path}: could not be written")
        tmp.replace(path)
    finally:
        tmp.unlink(missing_ok=True)


# --------------------------------------------------------------------------------------------
# DXF
# --------------------------------------------------------------------------------------------

#: DXF ``$INSUNITS`` codes of the unit symbols.
DXF_UNITS = {"in": 1, "ft": 2, "mi": 3, "mm": 4, "cm": 5, "m": 6, "km": 7, "yd": 10, "dm": 14}
APP = "VAULTGRAM"


def write_dxf(path: str | Path, layers: dict, units: str | None = None) -> None:
    """Write the layers of a result drawing to a DXF file (R2010): meshes as polyface meshes, polylines as
    3D polylines, user strings as XDATA; the header's time stamps and ids fixed (the same bytes each run:
    ezdxf's own option for that, set while writing)."""
    import ezdxf

    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True  # ezdxf's constant dates, ids and marker
    try:
        _write_dxf(ezdxf, Path(path), layers, units)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed


def _write_dxf(ezdxf, path: Path, layers: dict, units: str | None) -> None:
    doc = ezdxf.new("R2010", units=DXF_UNITS.get(units or "", 0))
    doc.appids.add(APP)
    msp = doc.modelspace()
    for name, items in layers.items():
        doc.layers.add(name, true_color=ezdxf.rgb2int(LAYERS.get(name, (0, 0, 0))))
        for item in items:
            entity = _add_dxf(msp, item, {"layer": name})
            if item.strings:
                entity.set_xdata(APP, [(1000, f"{k}={v}") for k, v in item.strings])
    _atomic(path, lambda tmp: doc.saveas(tmp))


def _add_dxf(msp, item: Item, attribs: dict):
    """Add one item to a DXF modelspace; the entity added."""
    if item.kind == "point":
        return msp.add_point(tuple(map(float, item.xyz[0])), dxfattribs=attribs)
    if item.kind == "polyline":
        return msp.add_polyline3d(item.xyz.tolist(), close=item.closed, dxfattribs=attribs)
    face = msp.add_polyface(dxfattribs=attribs)
    face.append_faces([[tuple(item.xyz[v]) for v in f] for f in _faces_of_at_most_four(item.faces)])
    face.optimize()
    return face
