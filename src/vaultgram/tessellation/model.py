"""The tessellation: voussoirs on the thrust surface, their joints, solids, courses and names (§5).

:class:`VoussoirLayout` is what the bond and the keystones decide, in the cut mesh's terms: which
faces form each voussoir, its outline, and the joints between voussoirs. :class:`Tessellation` is the
stage's value: the layout's vertices (after the optional smoothing on the surface), solids, courses
and names, with a summary; :meth:`Tessellation.to_json` is ``tessellation.json``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from vaultgram.geometry.arrays import distinct, json_array
from vaultgram.geometry.frames import NO_ORIGIN, between, to_plan
from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.geometry.surfaces import surface_areas
from vaultgram.tessellation.keystones import CutMesh
from vaultgram.tessellation.solids import Solids
from vaultgram.tessellation.voussoirs import outlines

__all__ = ["VoussoirLayout", "voussoir_layout", "Tessellation"]


@dataclass(frozen=True, eq=False)
class VoussoirLayout:
    """Voussoirs as groups of faces of the cut mesh.

    Attributes
    ----------
    mesh : CutMesh
    edges : MeshEdges
        The cut mesh's edges.
    group : ndarray (f,)
        The voussoir of each face.
    loops : tuple of ndarray
        Each voussoir's outline, counter-clockwise in plan.
    keystones : ndarray
        Voussoirs that are keystones.
    joints : ndarray (j,)
        Edges of the cut mesh between two voussoirs.
    """

    mesh: CutMesh
    edges: MeshEdges
    group: np.ndarray
    loops: tuple
    keystones: np.ndarray
    joints: np.ndarray

    @property
    def n_voussoirs(self) -> int:
        return len(self.loops)

    def joint_voussoirs(self) -> np.ndarray:
        """The two voussoirs on either side of each joint."""
        return self.group[self.edges.faces_of[self.joints]]

    def areas(self, x: np.ndarray) -> np.ndarray:
        """Mid-surface area of each voussoir: the areas of its faces, on the surface ``x``."""
        a = surface_areas(x, self.mesh.faces)
        return np.bincount(self.group, weights=a, minlength=self.n_voussoirs)


def voussoir_layout(mesh: CutMesh, me: MeshEdges, group: np.ndarray) -> VoussoirLayout:
    """Voussoirs of the faces in each ``group``; joints are the inner edges between two groups."""
    loops = outlines(me, group)  # Faces, their corners made once
    inner = ~me.boundary
    sides = group[np.maximum(me.faces_of, 0)]
    joints = np.flatnonzero(inner & (sides[:, 0] != sides[:, 1]))
    keystones = distinct(group[mesh.keystones]) if len(mesh.keystones) else np.zeros(0, dtype=np.int64)
    return VoussoirLayout(mesh, me, group, loops, keystones, joints)


@dataclass(frozen=True, eq=False)
class Tessellation:
    """Voussoirs cut from a thrust surface.

    Attributes
    ----------
    layout : VoussoirLayout
    vertices : ndarray (n, 3)
        The layout's vertices on the thrust surface (smoothed on it if asked).
    normals : ndarray (n, 3)
        The surface's unit normals there.
    solids : Solids
    courses, zones : ndarray (v,)
        Construction course (voussoirs from a support) and support zone of each voussoir.
    names : tuple of str
    summary : dict
    origin : tuple of float
        Where the frame of the coordinates starts in the plan's (the thrust network's ``origin``,
        :mod:`vaultgram.geometry.frames`).
    """

    layout: VoussoirLayout
    vertices: np.ndarray
    normals: np.ndarray
    solids: Solids
    courses: np.ndarray
    zones: np.ndarray
    names: tuple
    summary: dict
    origin: tuple = NO_ORIGIN

    def in_frame(self, origin=NO_ORIGIN) -> "Tessellation":
        """The voussoirs in the frame starting at ``origin`` (by default the plan's own coordinates, as
        the files have them; itself when it is in that frame already)."""
        if self.origin == origin:
            return self
        o, lay = between(self.origin, origin), self.layout
        solids = replace(self.solids, vertices=to_plan(self.solids.vertices, o))
        layout = replace(lay, mesh=replace(lay.mesh, vertices=to_plan(lay.mesh.vertices, o)))
        return replace(self, vertices=to_plan(self.vertices, o), solids=solids, layout=layout, origin=origin)

    def to_json(self, arrays: bool = False) -> dict:
        """``tessellation.json``: vertices (in the plan's coordinates), voussoir loops, keystones,
        neighbours, joints, courses...; ``arrays``: numpy arrays kept as they are, for
        :func:`vaultgram.io.files.write_json` (:func:`~vaultgram.geometry.arrays.json_array`)."""
        lay = self.layout
        pairs = lay.joint_voussoirs()
        return {
            "vertices": json_array(to_plan(self.vertices, self.origin), arrays),
            "voussoirs": list(lay.loops) if arrays else _lists(lay.loops),  # orjson takes each loop's array
            "keystones": json_array(lay.keystones, arrays),
            "names": list(self.names),
            "courses": json_array(self.courses, arrays),
            "zones": json_array(self.zones, arrays),
            "areas": json_array(lay.areas(self.vertices), arrays),
            "faces": list(lay.mesh.faces),  # a list of its tuples (orjson writes no tuple subclass)
            "face_voussoir": json_array(lay.group, arrays),
            "joints": _joint_records(lay.edges.edges[lay.joints], np.sort(pairs, axis=1), arrays),
            "neighbours": _neighbours(pairs, lay.n_voussoirs),
            "summary": self.summary,
        }


def _joint_records(vertices: np.ndarray, voussoirs: np.ndarray, arrays: bool = False):
    """The joints as records ``{"vertices": [a, b], "voussoirs": [p, q]}``: a list of dicts, or with
    ``arrays`` the same JSON as one fragment for :func:`vaultgram.io.files.write_json`, its numbers
    set in the records' text a block of rows at a time (:func:`vaultgram.io.numtext.int_records`; 4 s
    of dicts for the 1.5 million joints of a 10^6-face design, 0.9 s by orjson's text of the arrays
    with its brackets replaced, 0.2 s so).

    >>> v, p = np.array([[3, 4], [5, 6]]), np.array([[0, 1], [1, 2]])
    >>> _joint_records(v, p)[1]
    {'vertices': [5, 6], 'voussoirs': [1, 2]}
    >>> import orjson
    >>> orjson.dumps(_joint_records(v, p, arrays=True)) == orjson.dumps(_joint_records(v, p))
    True
    >>> orjson.dumps(_joint_records(v[:0], p[:0], arrays=True))
    b'[]'
    """
    if not arrays:
        return [{"vertices": a, "voussoirs": b} for a, b in zip(vertices.tolist(), voussoirs.tolist())]
    import orjson

    from vaultgram.io.numtext import int_records

    parts = [b',{"vertices":[', b",", b'],"voussoirs":[', b",", b"]}"]  # each record after a comma
    pieces = list(int_records(parts, vertices, voussoirs))
    if pieces:
        pieces[0] = pieces[0][1:]  # no comma before the first record
    return orjson.Fragment(b"".join([b"[", *pieces, b"]"]))


def _lists(arrays) -> list[list]:
    """Arrays as lists: converted as one array and cut (10^5 small ``tolist`` calls took a second).

    >>> _lists([np.array([1, 2]), np.array([], dtype=int), np.array([3])])
    [[1, 2], [], [3]]
    """
    flat = np.concatenate(arrays).tolist() if len(arrays) else []
    return _cut(flat, np.cumsum([len(a) for a in arrays]).tolist())


def _cut(flat: list, ends: list) -> list[list]:
    """``flat`` cut into the lists that end at ``ends``."""
    return [flat[a:b] for a, b in zip([0, *ends[:-1]], ends)]


def _neighbours(pairs: np.ndarray, n: int) -> list[list[int]]:
    """Per voussoir, the voussoirs it shares a joint with, sorted: both directions of every pair as
    one key ``a * n + b``, made unique and sorted as one array (:func:`distinct`: ``np.unique`` hashes,
    some ten times slower on the 10^6 keys of a 10^6-face design).

    >>> _neighbours(np.array([[0, 1], [1, 2], [2, 1]]), 4)
    [[1], [0, 2], [1], []]
    """
    p = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    a, b = np.divmod(distinct(np.concatenate([p[:, 0] * n + p[:, 1], p[:, 1] * n + p[:, 0]])), max(n, 1))
    return _cut(b.tolist(), np.cumsum(np.bincount(a, minlength=n)).tolist())
