"""The form diagram of Thrust Network Analysis, built from a planar quad-dominant mesh (§5).

The paper (§5, Armadillo Vault): "To convert this mesh into a proper form diagram ... we simply remove
the mesh edges that are fully supported, i.e. edges with both end points bearing thrust." This module
does that and the bookkeeping TNA needs afterwards (Block & Ochsendorf 2007; Rippmann, Lachauer &
Block 2012, RhinoVAULT):

* edges with both ends supported are removed, vertices left without edges (the corners of a fully
  supported boundary) are deleted and dropped from their faces (a corner quad becomes a triangle that
  still carries its self-weight) -- the convention of compas_tna's ``update_boundaries``, which the
  reference figures use;
* every opening gets an *unloaded* face so that the reciprocal (dual) force diagram is well defined:
  a hole with no support becomes one closed opening face, an unsupported boundary stretch between two
  supports (a "run") one open face. Without these faces the force polygons of the vertices along an
  opening could not close;
* faces must be counter-clockwise: a clockwise face is an error naming the face, never folded silently;
* every connected part of the network must reach a support.

The result is an immutable :class:`FormDiagram` of plain arrays plus the sparse branch-node
connectivity matrix ``C`` (m x n, -1 at the edge's first vertex and +1 at its second).
:func:`form_diagram` runs these steps as named phases, in this order: check the mesh, check its
orientation, mark the supports, drop the fully supported edges, renumber, add the opening faces, find
the faces on either side of every edge, and check the network.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Iterable, NamedTuple, Sequence

import numpy as np
import scipy.sparse as sp

from vaultgram.errors import FormFindingError
from vaultgram.formfinding.diagrams import Diagram, connectivity_matrix
from vaultgram.formfinding.supports import largest_loop, manifold_loops
from vaultgram.geometry.arrays import json_array, lookup
from vaultgram.geometry.halfedges import MeshEdges, SortedSides, edges_of_sides, repeated_sides, sorted_sides
from vaultgram.geometry.meshes import Faces, corner_arrays, corners_of_flat, loops_of, shoelace_areas

__all__ = ["FormDiagram", "form_diagram", "connectivity_matrix"]


@dataclass(frozen=True, eq=False)
class FormDiagram(Diagram):
    """A TNA form diagram: the horizontal projection of the thrust network.

    Attributes
    ----------
    xy : ndarray (n, 2)
        Vertex positions in plan.
    edges : ndarray (m, 2) int
        Edges ``(u, v)`` with ``u < v`` (sorted lexicographically).
    faces : tuple of tuples
        Loaded mesh faces first, then opening faces (counter-clockwise where the notion applies).
        An open opening face (a boundary run between supports) lists its vertices from one support to
        the other; its closing chord is not an edge.
    loaded : ndarray (F,) bool
        True for mesh faces (they carry self-weight), False for opening faces.
    anchors : ndarray (n,) bool
        Supported vertices (they take reactions; their position and height are fixed).
    vertex_ids : ndarray (n,) int
        Index of each vertex in the input mesh.
    edge_faces : ndarray (m, 2) int
        ``(left, right)`` face of each edge ``(u, v)``: ``left`` contains the halfedge ``u -> v``;
        -1 where there is no face (only for edges between two anchors kept with
        ``update_boundaries=False``).
    C : scipy.sparse.csr_matrix (m, n)
        Branch-node connectivity matrix (see :func:`connectivity_matrix`).

    Sizes, edge vectors and lengths, components and :meth:`with_xy` come from
    :class:`vaultgram.formfinding.diagrams.Diagram`.
    """

    xy: np.ndarray
    edges: np.ndarray
    faces: tuple[tuple[int, ...], ...]
    loaded: np.ndarray
    anchors: np.ndarray
    vertex_ids: np.ndarray
    edge_faces: np.ndarray
    C: sp.csr_matrix = field(repr=False)

    @property
    def n_faces(self) -> int:
        return len(self.faces)

    @cached_property
    def free(self) -> np.ndarray:
        """Indices of the unsupported vertices (their equilibrium is solved for)."""
        return np.flatnonzero(~self.anchors)

    @cached_property
    def fixed(self) -> np.ndarray:
        """Indices of the anchors."""
        return np.flatnonzero(self.anchors)

    @cached_property
    def active(self) -> np.ndarray:
        """Edges with at least one free end: the ones that have a force-diagram edge."""
        return ~(self.anchors[self.edges[:, 0]] & self.anchors[self.edges[:, 1]])

    @cached_property
    def loaded_faces(self) -> Faces:
        """The mesh faces (the first ones of :attr:`faces`), their corner arrays cut from those of all."""
        fid, vert, _, _ = corner_arrays(self.faces)
        k = int(self.loaded.sum())
        lens = np.bincount(fid, minlength=self.n_faces)[:k]
        return Faces.from_flat(vert[: int(lens.sum())], lens, self.faces[:k])

    @cached_property
    def opening_faces(self) -> tuple[tuple[int, ...], ...]:
        return tuple(f for f, ld in zip(self.faces, self.loaded) if not ld)

    def edge_name(self, e: int) -> str:
        """An edge named by its input-mesh vertex indices, e.g. ``'edge 12 (mesh vertices 3-4)'``."""
        u, v = self.edges[e]
        return f"edge {e} (mesh vertices {self.vertex_ids[u]}-{self.vertex_ids[v]})"

    def to_json(self, arrays: bool = False) -> dict:
        """JSON-serialisable description (for ``form.json``); ``arrays``: numpy arrays and tuples kept as
        they are, for :func:`vaultgram.io.files.write_json` (:func:`~vaultgram.geometry.arrays.json_array`)."""
        return {
            "vertices": json_array(self.xy, arrays),
            "vertex_ids": json_array(self.vertex_ids, arrays),
            "anchors": json_array(self.fixed, arrays),
            "edges": json_array(self.edges, arrays),
            "faces": list(self.faces) if arrays else [list(f) for f in self.faces],
            "loaded": json_array(self.loaded, arrays),
        }


def form_diagram(vertices, faces: Sequence[Sequence[int]], supports: Iterable[int] | np.ndarray | None = None,
                 update_boundaries: bool = True) -> FormDiagram:
    """Build the form diagram of a planar mesh (§5; Block & Ochsendorf 2007).

    Parameters
    ----------
    vertices : array (n, 2) or (n, 3)
        Mesh vertices; z is ignored (the form diagram is planar).
    faces : sequence of vertex-index sequences
        Counter-clockwise faces (mostly quads).
    supports : iterable of vertex indices, boolean mask, or None
        Supported vertices; default: the vertices of the outer boundary loop (holes are open).
    update_boundaries : bool
        True (default, as in the paper): remove edges with both ends supported, delete vertices left
        without edges and drop them from their faces (faces left with fewer than 3 vertices go). False
        keeps them (anchor-anchor edges then carry a force density but have no force-diagram edge).

    Returns
    -------
    FormDiagram

    Raises
    ------
    FormFindingError
        clockwise or degenerate face (named), inconsistent orientation or non-manifold edge, no
        supports, an unsupported island (a connected part of the network without anchor), a free
        vertex with a single edge, or a pinched boundary vertex.

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> v, f = grid_mesh(4)
    >>> form = form_diagram(v, f)
    >>> form.n_vertices, form.n_edges, int(form.loaded.sum()), int((~form.loaded).sum())
    (21, 24, 16, 0)
    """
    xy0, faces, mesh = _checked_mesh(vertices, faces)
    scale = max(float(np.ptp(xy0, axis=0).max()), 1e-300)
    sides = _check_orientation(xy0, faces, mesh, scale)
    anchors0 = _anchor_mask(supports, xy0, mesh, sides)
    mesh, sides = _drop_bare_vertices(xy0, faces, mesh, sides, anchors0, update_boundaries, scale)
    edges = edges_of_sides(mesh.face, mesh.vert, mesh.nxt, mesh.lens, sides, len(xy0))
    keep, degree = _kept_edges(edges, anchors0, update_boundaries)
    net = _renumbered(xy0, anchors0, edges, keep, degree)
    openings = _opening_faces(net)
    form = _assembled(net, openings)
    _check_network(form, scale)
    return form


# ---- phase 1: the mesh as given ------------------------------------------------------------------


class _Corners(NamedTuple):
    """Faces as corner arrays, never as tuples: corner ``k`` is the side ``vert[k] -> nxt[k]`` of face
    ``face[k]``; ``lens`` the face sizes, ``index`` each face's index in the input mesh (for errors)."""

    face: np.ndarray
    vert: np.ndarray
    nxt: np.ndarray
    lens: np.ndarray
    index: np.ndarray


def _checked_mesh(vertices, faces) -> tuple[np.ndarray, Sequence, _Corners]:
    """Plan positions (n, 2), the faces as given (indexable, to name them in errors) and their corner
    arrays, after checking shapes and indices."""
    V = np.asarray(vertices, dtype=float)
    if V.ndim != 2 or V.shape[1] not in (2, 3):
        raise FormFindingError(f"vertices must have shape (n, 2) or (n, 3), got {V.shape}")
    faces = faces if isinstance(faces, (list, tuple)) else list(faces)
    if not faces:
        raise FormFindingError("the mesh has no faces")
    face, vert, nxt, _ = corner_arrays(faces)
    mesh = _Corners(face, vert, nxt, np.bincount(face, minlength=len(faces)), np.arange(len(faces)))
    bad = _first_bad_face(mesh, len(V))
    if bad is not None:
        _check_face(bad, _face_tuple(faces, bad), len(V))
    return V[:, :2], faces, mesh


def _face_tuple(faces: Sequence, k: int) -> tuple[int, ...]:
    """Input face ``k`` as a tuple of Python ints (to name it in an error)."""
    return tuple(int(w) for w in faces[k])


def _first_bad_face(mesh: _Corners, n: int) -> int | None:
    """The first face that :func:`_check_face` rejects (None if none), found on the corner arrays
    without a Python loop over the faces."""
    fid, vert, lens = mesh.face, mesh.vert, mesh.lens
    bad = (lens < 3) | (np.bincount(fid, weights=((vert < 0) | (vert >= n)), minlength=len(lens)) > 0)
    m = max(n, int(vert.max()) + 1 if len(vert) else 1, 1)  # every index below m, bad ones too
    # (face, vertex) pairs, already in face order: a repeat is a pair twice (a stable sort: timsort
    # only sorts within the faces here)
    codes = np.sort(fid * m + np.where(vert < 0, m - 1, vert), kind="stable")
    bad[codes[1:][np.diff(codes) == 0] // m] = True
    return int(np.argmax(bad)) if bad.any() else None


def _check_face(k: int, f: tuple[int, ...], n: int) -> None:
    """Face ``k`` has at least 3 distinct vertices of the mesh."""
    if len(f) < 3:
        raise FormFindingError(f"face {k} has {len(f)} vertices; faces need at least 3")
    if min(f) < 0 or max(f) >= n:
        raise FormFindingError(f"face {k} refers to vertex {max(f) if max(f) >= n else min(f)}, "
                               f"but the mesh has {n} vertices")
    if len(set(f)) != len(f):
        raise FormFindingError(f"face {k} repeats a vertex: {list(f)}")


def _not_counter_clockwise(xy: np.ndarray, mesh: _Corners, scale: float) -> tuple[np.ndarray, np.ndarray]:
    """Signed face areas and the indices of faces that are clockwise or (relative to ``scale``) flat."""
    area = shoelace_areas(xy, mesh.face, mesh.vert, mesh.nxt, len(mesh.lens))
    return area, np.flatnonzero(area <= 1e-14 * scale * scale)


def _check_orientation(xy: np.ndarray, faces: Sequence, mesh: _Corners, scale: float) -> SortedSides:
    """Every face is counter-clockwise seen from +z and every halfedge belongs to one face only; the
    mesh's sides sorted by edge (:func:`~vaultgram.geometry.halfedges.sorted_sides`)."""
    area, bad = _not_counter_clockwise(xy, mesh, scale)
    if len(bad):
        k = int(bad[0])
        kind = "clockwise" if area[k] < 0 else "degenerate (zero area)"
        raise FormFindingError(
            f"face {k} {list(_face_tuple(faces, k))} is {kind} (signed area {area[k]:.6g}); faces must be "
            f"counter-clockwise seen from +z" + (f" ({len(bad)} such faces)" if len(bad) > 1 else ""))
    sides = sorted_sides(mesh.vert, mesh.nxt, len(xy))
    repeated = repeated_sides(sides)
    if len(repeated):
        a, b = repeated[0]
        raise FormFindingError(
            f"halfedge {mesh.vert[a]}->{mesh.nxt[a]} is used by faces {mesh.face[a]} and {mesh.face[b]}: "
            f"inconsistent face orientation or non-manifold edge")
    return sides


def _boundary_sides(edges: MeshEdges) -> tuple[np.ndarray, np.ndarray]:
    """The halfedges ``u -> v`` that have no twin, in corner order (those of
    :func:`~vaultgram.geometry.meshes.boundary_halfedges`)."""
    corners = np.sort(edges.corners_of[edges.boundary].max(axis=1))
    return edges.corner_vertex[corners], edges.corner_next[corners]


def _lone_sides(mesh: _Corners, sides: SortedSides) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_boundary_sides` of a mesh without repeated sides, from its sorted sides: the sides
    alone on their edge."""
    pair = sides.key >> 1
    alone = np.ones(len(pair), dtype=bool)
    same = pair[1:] == pair[:-1]
    alone[1:] &= ~same
    alone[:-1] &= ~same
    corners = np.sort(sides.order[alone])
    return mesh.vert[corners], mesh.nxt[corners]


def _anchor_mask(supports, xy: np.ndarray, mesh: _Corners, sides: SortedSides) -> np.ndarray:
    """The supported vertices as a boolean mask (default: the outer boundary loop; holes are open)."""
    n = len(xy)
    anchors = np.zeros(n, dtype=bool)
    if supports is None:
        anchors[largest_loop(xy, manifold_loops(*_lone_sides(mesh, sides)))] = True
    else:
        idx = np.asarray(list(supports) if not isinstance(supports, np.ndarray) else supports)
        if idx.dtype == bool:
            if idx.shape != (n,):
                raise FormFindingError(f"a boolean support mask must have one entry per vertex ({n}), got {idx.shape}")
            anchors = idx.copy()
        else:
            idx = idx.astype(np.int64).ravel()
            bad = idx[(idx < 0) | (idx >= n)]
            if len(bad):
                raise FormFindingError(f"support vertex {int(bad[0])} does not exist (the mesh has {n} vertices)")
            anchors[idx] = True
    if not anchors.any():
        raise FormFindingError("no supports: a thrust network needs at least one supported vertex")
    return anchors


# ---- phase 2: remove what is fully supported (§5) -------------------------------------------------


def _kept_edges(edges: MeshEdges, anchors: np.ndarray, drop_supported: bool) -> tuple[np.ndarray, np.ndarray]:
    """Which edges stay (not those joining two anchors when ``drop_supported``) and the kept edges per
    vertex."""
    keep = ~(anchors[edges.edges[:, 0]] & anchors[edges.edges[:, 1]]) if drop_supported else \
        np.ones(edges.n_edges, dtype=bool)
    return keep, np.bincount(edges.edges[keep].ravel(), minlength=len(anchors))


def _bare_vertices(mesh: _Corners, anchors: np.ndarray, drop_supported: bool) -> np.ndarray:
    """The vertices of faces that keep no edge (:func:`_kept_edges`): an edge is some face's side, so
    these are the vertices that end no kept side."""
    kept = ~(anchors[mesh.vert] & anchors[mesh.nxt]) if drop_supported else np.ones(len(mesh.vert), dtype=bool)
    has_edge = np.zeros(len(anchors), dtype=bool)
    has_edge[mesh.vert[kept]] = True
    has_edge[mesh.nxt[kept]] = True
    in_faces = np.zeros(len(anchors), dtype=bool)
    in_faces[mesh.vert] = True
    return in_faces & ~has_edge


def _drop_bare_vertices(xy: np.ndarray, faces: Sequence, mesh: _Corners, sides: SortedSides, anchors: np.ndarray,
                        drop: bool, scale: float) -> tuple[_Corners, SortedSides]:
    """Once the edges with both ends supported are removed (when ``drop``), delete the vertices left
    without edges from their faces (a supported corner quad becomes a triangle; faces left with fewer
    than 3 vertices go), until every vertex of a face has an edge: compas_tna's ``update_boundaries``.
    Returns the faces left and their sorted sides (``sides`` if no vertex went): the edges are made
    once, of the faces left."""
    while True:
        dead = _bare_vertices(mesh, anchors, drop)
        if not dead.any():
            return mesh, sides
        mesh, changed = _without_vertices(mesh, dead)
        _, bad = _not_counter_clockwise(xy, _faces_among(mesh, changed), scale)
        if len(bad):
            k = int(changed[bad[0]])
            now = mesh.vert[np.flatnonzero(mesh.face == k)].tolist()
            raise FormFindingError(
                f"face {mesh.index[k]} {list(_face_tuple(faces, mesh.index[k]))} becomes {now}, which is not "
                f"counter-clockwise, once its supported vertices without edges are removed; support fewer "
                f"vertices or use update_boundaries=False")
        sides = sorted_sides(mesh.vert, mesh.nxt, len(xy))


def _without_vertices(mesh: _Corners, dead: np.ndarray) -> tuple[_Corners, np.ndarray]:
    """The faces (and their input indices) with the ``dead`` vertices dropped, faces left with < 3
    going, and the faces that lost a vertex (to check their orientation again)."""
    fid, vert, old, index = mesh.face, mesh.vert, mesh.lens, mesh.index
    alive = ~dead[vert]
    lens = np.bincount(fid[alive], minlength=len(old))
    kept = lens >= 3
    if not kept.any():
        raise FormFindingError("every edge joins two supports: nothing is left to form-find")
    corners = alive & kept[fid]
    face, vert, nxt, _ = corners_of_flat(vert[corners], lens[kept])
    changed = np.flatnonzero((lens != old)[kept])
    return _Corners(face, vert, nxt, lens[kept], index[kept]), changed


def _faces_among(mesh: _Corners, faces: np.ndarray) -> _Corners:
    """The corner arrays of some of the faces (sorted indices), numbered from 0 in that order."""
    rank = np.full(len(mesh.lens), -1, dtype=np.int64)
    rank[faces] = np.arange(len(faces))
    at = rank[mesh.face] >= 0
    return _Corners(rank[mesh.face[at]], mesh.vert[at], mesh.nxt[at], mesh.lens[faces], mesh.index[faces])


class _Network(NamedTuple):
    """The kept vertices and edges, renumbered (``vertex_ids`` maps back to the input mesh)."""

    xy: np.ndarray
    anchors: np.ndarray
    vertex_ids: np.ndarray
    edges: np.ndarray       # (m, 2), u < v, sorted
    face_vertices: np.ndarray   # the loaded faces' vertices end to end,
    face_sizes: np.ndarray      # and their sizes
    edge_faces: np.ndarray  # (m, 2): the loaded faces left and right of each edge (-1: none)
    boundary: tuple[np.ndarray, np.ndarray]   # the boundary halfedges u -> v, in corner order


def _renumbered(xy0: np.ndarray, anchors0: np.ndarray, edges: MeshEdges, keep: np.ndarray,
                degree: np.ndarray) -> _Network:
    """Keep the vertices that have an edge and number them consecutively (in their order, so the sorted
    edges stay sorted)."""
    used = degree > 0
    new = np.full(len(xy0), -1, dtype=np.int64)
    new[used] = np.arange(int(used.sum()))
    vertex_ids = np.flatnonzero(used)
    anchors = anchors0[vertex_ids].copy()
    if not anchors.any():
        raise FormFindingError("no supports left after removing fully supported edges")
    starts, ends = _boundary_sides(edges)
    return _Network(xy0[vertex_ids].copy(), anchors, vertex_ids, new[edges.edges[keep]], new[edges.corner_vertex],
                    np.diff(edges.face_start), edges.faces_of[keep], (new[starts], new[ends]))


# ---- phase 3: opening faces, so that the reciprocal diagram exists -------------------------------


class _Opening(NamedTuple):
    """An unloaded face along an opening: a hole, or a boundary run between two supports (``open``:
    listed from one support to the other, its closing chord is not an edge)."""

    vertices: tuple[int, ...]
    open: bool


def _opening_faces(net: _Network) -> list[_Opening]:
    """One opening face per unsupported hole and per boundary run between supports.

    An opening lies beyond the boundary: it is traversed along the twins of the boundary halfedges,
    i.e. each boundary loop reversed (from the end of its first halfedge), then cut at its anchors.
    """
    starts, ends = net.boundary
    _check_not_pinched(ends, net.vertex_ids)
    openings: list[_Opening] = []
    for loop in loops_of(starts, ends):
        openings += _cut_at_anchors([loop[1], loop[0], *loop[:1:-1]], net.anchors)
    return openings


def _check_not_pinched(ends: np.ndarray, vertex_ids: np.ndarray) -> None:
    """No vertex ends two boundary halfedges (two boundary loops touching there)."""
    if len(ends) == 0 or np.bincount(ends).max() < 2:
        return
    again = np.ones(len(ends), dtype=bool)
    again[np.unique(ends, return_index=True)[1]] = False
    if again.any():
        raise FormFindingError(
            f"mesh vertex {vertex_ids[ends[np.argmax(again)]]} is a pinched boundary vertex (two boundary loops "
            f"touch there); split it or support it")


def _cut_at_anchors(loop: list[int], anchors: np.ndarray) -> list[_Opening]:
    """A loop with at most one anchor is one closed opening (starting at its anchor); otherwise each run
    between consecutive anchors is an open one (a run of one edge joins two anchors: not an opening)."""
    at = [k for k in range(len(loop)) if anchors[loop[k]]]
    if len(at) <= 1:
        s = at[0] if at else 0
        return [_Opening(tuple(loop[s:] + loop[:s]), False)]
    s = at[0]
    loop = loop[s:] + loop[:s] + [loop[s]]
    runs, run = [], [loop[0]]
    for w in loop[1:]:
        run.append(w)
        if anchors[w]:
            if len(run) >= 3:
                runs.append(_Opening(tuple(run), True))
            run = [w]
    return runs


# ---- phase 4: the diagram -------------------------------------------------------------------------


def _with_openings(net: _Network, openings: list[_Opening]) -> np.ndarray:
    """``(left, right)`` face of every edge ``(u, v)`` with the opening faces (numbered after the loaded
    ones) beside the boundary edges: an opening's side ``a -> b`` is left of the edge when ``a < b``.
    An open opening face has no side on its closing chord."""
    edge_faces = net.edge_faces.copy()
    if not openings:
        return edge_faces
    sides = [(k, o.vertices[i], o.vertices[(i + 1) % len(o.vertices)])
             for k, o in enumerate(openings) for i in range(len(o.vertices) - o.open)]
    k, a, b = (np.array(c, dtype=np.int64) for c in zip(*sides))
    n = len(net.xy)
    pos, found = lookup(net.edges[:, 0] * n + net.edges[:, 1], np.minimum(a, b) * n + np.maximum(a, b))
    edge_faces[pos[found], (a > b)[found].astype(np.int64)] = len(net.face_sizes) + k[found]
    return edge_faces


def _assembled(net: _Network, openings: list[_Opening]) -> FormDiagram:
    """The frozen diagram: loaded faces, then opening faces (their tuples and corner arrays made once,
    from the arrays), and the faces beside every edge."""
    opening_vertices = [np.asarray(o.vertices, dtype=np.int64) for o in openings]
    lens = np.concatenate([net.face_sizes, np.array([len(o) for o in opening_vertices], dtype=np.int64)])
    faces = Faces.from_flat(np.concatenate([net.face_vertices, *opening_vertices]), lens)
    loaded = np.zeros(len(faces), dtype=bool)
    loaded[: len(net.face_sizes)] = True
    n = len(net.xy)
    edge_faces = _with_openings(net, openings)
    for arr in (net.xy, net.edges, loaded, net.anchors, net.vertex_ids, edge_faces):
        arr.setflags(write=False)
    return FormDiagram(xy=net.xy, edges=net.edges, faces=faces, loaded=loaded, anchors=net.anchors,
                       vertex_ids=net.vertex_ids, edge_faces=edge_faces, C=connectivity_matrix(net.edges, n))


# ---- phase 5: can the network be in equilibrium? --------------------------------------------------


def _check_network(form: FormDiagram, scale: float) -> None:
    """Every part reaches a support, every free vertex has two edges, no edge has zero length, and every
    edge with a free end has a face on both sides."""
    _check_anchored(form)
    lonely = np.flatnonzero((np.bincount(form.edges.ravel(), minlength=form.n_vertices) < 2) & ~form.anchors)
    if len(lonely):
        raise FormFindingError(
            f"free mesh vertex {form.vertex_ids[lonely[0]]} has only one edge and cannot be in equilibrium "
            f"({len(lonely)} such vertices); support it or remove it")
    short = np.flatnonzero(form.edge_lengths() <= 1e-12 * scale)
    if len(short):
        raise FormFindingError(f"edge between {_mesh_vertices(form, int(short[0]))} has zero length")
    missing = np.flatnonzero(form.active & ((form.edge_faces[:, 0] < 0) | (form.edge_faces[:, 1] < 0)))
    if len(missing):  # pragma: no cover - guarded by the construction above
        raise FormFindingError(f"edge between {_mesh_vertices(form, int(missing[0]))} has no face on one side")


def _check_anchored(form: FormDiagram) -> None:
    """Every connected part of the network has an anchor (it would float away otherwise)."""
    ncomp, labels = form.components
    anchored = np.bincount(labels, weights=form.anchors.astype(float), minlength=ncomp) > 0
    if not anchored.all():
        members = np.flatnonzero(labels == int(np.flatnonzero(~anchored)[0]))
        raise FormFindingError(
            f"unsupported island: {len(members)} vertices (mesh vertices {form.vertex_ids[members[:8]].tolist()}"
            f"{' ...' if len(members) > 8 else ''}) are connected to no support; support one of them or "
            f"join them to the rest")


def _mesh_vertices(form: FormDiagram, e: int) -> str:
    """``'mesh vertices i and j'``: the input-mesh ends of edge ``e``."""
    return f"mesh vertices {form.vertex_ids[form.edges[e, 0]]} and {form.vertex_ids[form.edges[e, 1]]}"
