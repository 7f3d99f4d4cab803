"""COMPAS, compas_tna and RhinoVAULT: vaultgram's meshes and thrust networks as COMPAS data, and
COMPAS meshes as patterns for form finding (optional extra ``vaultgram[compas]``).

* :func:`to_compas_mesh` -- a pattern mesh (:class:`~vaultgram.meshing.quadmesh.QuadMesh`) or a thrust
  network (:class:`~vaultgram.formfinding.thrust.ThrustNetwork`) as a ``compas.datastructures.Mesh``,
  with vertex attributes ``is_support``, ``is_boundary``, ``z``, ``load``, ``pz`` and edge attributes
  ``q``, ``_f``, ``_h``, ``_is_edge``;
* :func:`to_formdiagram` -- the thrust network's form diagram as compas_tna's ``FormDiagram``: the
  opening faces unloaded (``_is_loaded`` False), the fully supported edges not edges (``_is_edge``
  False), the scaled force densities ``q``, and the final loads as ``pz`` (compas_tna's sign: positive
  downwards; self-weight at the final
  geometry plus the point loads; compas_tna's ``vertical_from_q(form, density=0)`` then gives back
  vaultgram's heights);
* :func:`from_compas_mesh` -- vertices, faces (n-gons too) and supports of a COMPAS mesh (an object,
  its JSON data or a file), for ``vaultgram formfind``.

Files are written with compas' own JSON encoder (``Mesh.from_json`` reads them), without guid, so the
same result gives the same bytes.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from vaultgram.errors import VaultgramError

__all__ = ["to_compas_mesh", "to_formdiagram", "from_compas_mesh", "compas_json", "read_compas_mesh",
           "require_compas"]


def _compas(what: str = "COMPAS data"):
    """The ``compas`` package, or an error saying which extra installs it."""
    try:
        import compas
        import compas.datastructures  # noqa: F401
    except ImportError:
        raise VaultgramError(f"{what} needs the compas package: pip install 'vaultgram[compas]'") from None
    return compas


def require_compas(what: str = "--format compas") -> None:
    """Check that compas and compas_tna can be imported (before a run computes anything)."""
    _compas(what)
    try:
        import compas_tna  # noqa: F401
    except ImportError:
        raise VaultgramError(f"{what} needs the compas_tna package: pip install 'vaultgram[compas]'") from None


def _is_network(item) -> bool:
    return hasattr(item, "q") and hasattr(item, "anchors")


def to_compas_mesh(item, supports=None):
    """A pattern mesh, a thrust network or voussoirs as a ``compas.datastructures.Mesh``.

    Parameters
    ----------
    item : QuadMesh, ThrustNetwork or Tessellation
        A tessellation gives its voussoirs' solids, each on its own vertices, as one mesh of triangles
        (face attribute ``voussoir``).
    supports : sequence of int, optional
        For a pattern mesh: the vertices that bear thrust (``is_support``). A thrust network has its own.

    Returns
    -------
    compas.datastructures.Mesh
        Vertex keys are vaultgram's vertex indices.

    Examples
    --------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.pipeline import form_find
    >>> network = form_find(*grid_mesh(4), zmax=1.0)
    >>> mesh = to_compas_mesh(network)
    >>> mesh.number_of_vertices(), len(list(mesh.edges_where(_is_edge=True))) == len(network.edges)
    (21, True)
    >>> round(max(mesh.vertices_attribute("z")), 9), sum(mesh.vertices_attribute("is_support"))
    (1.0, 12)
    """
    Mesh = _compas("a COMPAS mesh").datastructures.Mesh
    if _is_network(item):
        return _network_mesh(Mesh, item)
    if hasattr(item, "solids"):
        return _voussoir_mesh(Mesh, item)
    x = np.asarray(item.vertices, dtype=float)
    xyz = np.column_stack([x[:, :2], x[:, 2] if x.shape[1] == 3 else np.zeros(len(x))])
    mesh = Mesh.from_vertices_and_faces(xyz.tolist(), [list(map(int, f)) for f in item.faces])
    mesh.update_default_vertex_attributes(is_support=False, is_boundary=False, is_feature=False)
    support = np.zeros(len(x), dtype=bool)
    if supports is not None:
        support[np.asarray(supports, dtype=np.int64)] = True
    for key, (s, b, f) in enumerate(zip(support.tolist(), item.boundary.tolist(), item.feature.tolist())):
        mesh.vertex_attributes(key, ["is_support", "is_boundary", "is_feature"], [s, b, f])
    mesh.attributes.update(name="vaultgram pattern", info=_plain(dict(item.info)))
    return mesh


def _network_mesh(Mesh, network):
    """The thrust network's loaded faces as a COMPAS mesh, with its equilibrium as attributes."""
    mesh = Mesh.from_vertices_and_faces(network.vertices.tolist(), [list(map(int, f)) for f in network.faces])
    mesh.update_default_vertex_attributes(is_support=False, load=0.0, pz=0.0, mesh_vertex=-1)
    mesh.update_default_edge_attributes(q=0.0, _f=0.0, _h=0.0, _l=0.0, _is_edge=False)
    _vertex_equilibrium(mesh, network)
    _edge_forces(mesh, network)
    mesh.attributes.update(name="vaultgram thrust network", summary=_plain(network.summary))
    return mesh


def _voussoir_mesh(Mesh, tessellation):
    """The voussoirs' closed solids, each on its own vertices, as one COMPAS mesh of triangles, each
    face's ``voussoir`` its index."""
    from vaultgram.io.cadfiles import voussoir_solids

    solids = voussoir_solids(tessellation)
    starts = np.cumsum([0] + [len(x) for x, _ in solids])
    x = np.vstack([x for x, _ in solids])
    triangles = np.vstack([t + s for (_, t), s in zip(solids, starts)])
    mesh = Mesh.from_vertices_and_faces(x.tolist(), triangles.tolist())
    owner = np.repeat(np.arange(len(solids)), [len(t) for _, t in solids])
    mesh.update_default_face_attributes(voussoir=-1)
    for face, k in zip(mesh.faces(), owner.tolist()):
        mesh.face_attribute(face, "voussoir", k)
    mesh.attributes.update(name="vaultgram voussoirs", names=list(tessellation.names),
                           courses=tessellation.courses.tolist())
    return mesh


def _vertex_equilibrium(mesh, network) -> None:
    """Supports, loads (``load`` and ``pz``, both positive downwards as in compas_tna), input-mesh indices
    and reactions of the vertices."""
    names = ["is_support", "load", "pz", "mesh_vertex"]
    for key, values in enumerate(zip(network.anchors.tolist(), network.loads.tolist(), network.loads.tolist(),
                                     network.vertex_ids.tolist())):
        mesh.vertex_attributes(key, names, list(values))
    for key, r in zip(np.flatnonzero(network.anchors).tolist(), network.reactions.tolist()):
        mesh.vertex_attributes(key, ["_rx", "_ry", "_rz"], r)


def _edge_forces(mesh, network) -> None:
    """Force densities, forces, horizontal forces and lengths of the network's edges (``_is_edge``)."""
    names = ["q", "_f", "_h", "_l", "_is_edge"]
    lengths = np.linalg.norm(network.vertices[network.edges[:, 1]] - network.vertices[network.edges[:, 0]], axis=1)
    for (u, v), q, f, h, length in zip(network.edges.tolist(), network.q.tolist(), network.forces.tolist(),
                                       network.horizontal_forces.tolist(), lengths.tolist()):
        mesh.edge_attributes((u, v), names, [q, f, h, length, True])


def _plain(value):
    """A summary as plain JSON values (numpy scalars and arrays made Python ones)."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    return value.item() if isinstance(value, np.generic) else value


def to_formdiagram(network):
    """The form diagram of a thrust network as compas_tna's ``FormDiagram`` (see the module's docstring).

    Raises
    ------
    VaultgramError
        compas or compas_tna is not installed.

    Examples
    --------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.pipeline import form_find
    >>> network = form_find(*grid_mesh(4), zmax=1.0)
    >>> form = to_formdiagram(network)
    >>> form.number_of_vertices(), len(list(form.edges_where(_is_edge=True))) == len(network.edges)
    (21, True)
    """
    _compas("a compas_tna form diagram")
    try:
        from compas_tna.diagrams import FormDiagram
    except ImportError:
        raise VaultgramError("a form diagram needs the compas_tna package: pip install 'vaultgram[compas]'") from None
    fd = network.form
    form = FormDiagram.from_vertices_and_faces(network.vertices.tolist(), [list(map(int, f)) for f in fd.faces])
    for face, loaded in zip(form.faces(), fd.loaded.tolist()):
        form.face_attribute(face, "_is_loaded", bool(loaded))
    form.edges_attribute("_is_edge", False)
    _vertex_equilibrium(form, network)
    _edge_forces(form, network)
    return form


def compas_json(obj) -> str:
    """COMPAS' JSON of a COMPAS object, without guid: the same object gives the same text (keys in the
    order they were made, so vertices and faces read back in index order, not sorted as strings)."""
    return _compas().json_dumps(obj, minimal=True)


def from_compas_mesh(obj, where: str = "COMPAS mesh") -> tuple[np.ndarray, list, list]:
    """The vertices ``(n, 3)``, faces (vertex-index lists, n-gons kept; a compas_tna form diagram's
    openings, ``_is_loaded`` false, left out) and supported vertex indices (``is_support``) of a COMPAS
    mesh, its vertices numbered in key order.

    ``obj`` is a ``compas.datastructures.Mesh`` (a compas_tna ``FormDiagram`` too) or COMPAS JSON data
    (a ``{"dtype", "data"}`` dict).

    Raises
    ------
    VaultgramError
        ``obj`` is not a COMPAS mesh (the message says what it is).

    Examples
    --------
    >>> from compas.datastructures import Mesh
    >>> m = Mesh.from_vertices_and_faces([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 1.5, 0]],
    ...                                  [[0, 1, 2, 4, 3]])
    >>> x, faces, supports = from_compas_mesh(m)
    >>> x.shape, faces, supports
    ((5, 3), [[0, 1, 2, 4, 3]], [])
    """
    compas = _compas(where)
    if isinstance(obj, dict):
        try:
            obj = compas.json_loads(compas.json_dumps(obj)) if "dtype" in obj else obj
        except Exception as exc:  # compas raises its own decoder errors and import errors for unknown dtypes
            raise VaultgramError(f"{where}: not COMPAS data ({type(exc).__name__}: {exc})") from None
    if not isinstance(obj, compas.datastructures.Mesh):
        kind = obj.get("dtype", "a JSON object without 'dtype'") if isinstance(obj, dict) else type(obj).__name__
        raise VaultgramError(f"{where}: not a COMPAS mesh ({kind})")
    keys = sorted(obj.vertices())
    index = {key: i for i, key in enumerate(keys)}
    x = np.array([obj.vertex_coordinates(v) for v in keys], dtype=float).reshape(-1, 3)
    faces = [[index[v] for v in obj.face_vertices(f)] for f in sorted(obj.faces())
             if obj.face_attribute(f, "_is_loaded") is not False]  # a compas_tna opening is not a face
    supports = [index[v] for v in keys if obj.vertex_attribute(v, "is_support")]
    return x, faces, supports


def read_compas_mesh(path: str | Path) -> tuple[np.ndarray, list, list]:
    """:func:`from_compas_mesh` of a COMPAS JSON file (``Mesh.to_json``)."""
    from vaultgram.io.files import read_json

    return from_compas_mesh(read_json(path), str(path))
