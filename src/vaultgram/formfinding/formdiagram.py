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
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Iterable, Sequence

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from vaultgram.errors import FormFindingError
from vaultgram.formfinding.supports import outer_loop
from vaultgram.geometry.meshes import corner_arrays

__all__ = ["FormDiagram", "form_diagram", "connectivity_matrix"]


def connectivity_matrix(edges: np.ndarray, n: int) -> sp.csr_matrix:
    """Branch-node matrix ``C`` (m x n): row ``e = (u, v)`` has -1 at ``u`` and +1 at ``v``.

    ``C @ x`` gives the edge vectors ``x[v] - x[u]``; ``C.T @ diag(q) @ C`` is the force-density
    stiffness of Schek's force density method used for vertical equilibrium.
    """
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    m = len(edges)
    rows = np.repeat(np.arange(m), 2)
    data = np.tile([-1.0, 1.0], m)
    return sp.csr_matrix((data, (rows, edges.ravel())), shape=(m, n))


@dataclass(frozen=True, eq=False)
class FormDiagram:
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
    """

    xy: np.ndarray
    edges: np.ndarray
    faces: tuple[tuple[int, ...], ...]
    loaded: np.ndarray
    anchors: np.ndarray
    vertex_ids: np.ndarray
    edge_faces: np.ndarray
    C: sp.csr_matrix = field(repr=False)

    # ---- sizes and index sets ------------------------------------------------------------
    @property
    def n_vertices(self) -> int:
        return len(self.xy)

    @property
    def n_edges(self) -> int:
        return len(self.edges)

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
    def loaded_faces(self) -> tuple[tuple[int, ...], ...]:
        return tuple(f for f, ld in zip(self.faces, self.loaded) if ld)

    @cached_property
    def opening_faces(self) -> tuple[tuple[int, ...], ...]:
        return tuple(f for f, ld in zip(self.faces, self.loaded) if not ld)

    def edge_vectors(self) -> np.ndarray:
        """``xy[v] - xy[u]`` per edge, shape (m, 2)."""
        return self.C @ self.xy

    def edge_lengths(self) -> np.ndarray:
        return np.hypot(*self.edge_vectors().T)

    def with_xy(self, xy: np.ndarray) -> "FormDiagram":
        """The same diagram with new plan positions (topology unchanged)."""
        xy = np.array(xy, dtype=float, copy=True)
        if xy.shape != self.xy.shape:
            raise ValueError(f"xy has shape {xy.shape}, expected {self.xy.shape}")
        xy.setflags(write=False)
        return replace(self, xy=xy)

    def edge_name(self, e: int) -> str:
        """An edge named by its input-mesh vertex indices, e.g. ``'edge 12 (mesh vertices 3-4)'``."""
        u, v = self.edges[e]
        return f"edge {e} (mesh vertices {self.vertex_ids[u]}-{self.vertex_ids[v]})"

    def to_json(self) -> dict:
        """JSON-serialisable description (for ``form.json``)."""
        return {
            "vertices": self.xy.tolist(),
            "vertex_ids": self.vertex_ids.tolist(),
            "anchors": self.fixed.tolist(),
            "edges": self.edges.tolist(),
            "faces": [list(f) for f in self.faces],
            "loaded": self.loaded.tolist(),
        }


def _supports_array(supports, n: int, vertices, faces) -> np.ndarray:
    anchors = np.zeros(n, dtype=bool)
    if supports is None:  # the outer boundary bears thrust, holes are open
        anchors[outer_loop(vertices, faces)] = True
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
    return anchors


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
        without edges and drop them from their faces (faces left with fewer than 3 vertices go). False keeps them (anchor-anchor edges then carry a
        force density but have no force-diagram edge).

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
    V = np.asarray(vertices, dtype=float)
    if V.ndim != 2 or V.shape[1] not in (2, 3):
        raise FormFindingError(f"vertices must have shape (n, 2) or (n, 3), got {V.shape}")
    n0 = len(V)
    faces = [tuple(int(i) for i in f) for f in faces]
    if not faces:
        raise FormFindingError("the mesh has no faces")
    for k, f in enumerate(faces):
        if len(f) < 3:
            raise FormFindingError(f"face {k} has {len(f)} vertices; faces need at least 3")
        if min(f) < 0 or max(f) >= n0:
            raise FormFindingError(f"face {k} refers to vertex {max(f) if max(f) >= n0 else min(f)}, "
                                   f"but the mesh has {n0} vertices")
        if len(set(f)) != len(f):
            raise FormFindingError(f"face {k} repeats a vertex: {list(f)}")
    xy0 = V[:, :2]
    fid, u, v, _ = corner_arrays(faces)
    # orientation: signed areas by the shoelace formula
    cross = xy0[u, 0] * xy0[v, 1] - xy0[v, 0] * xy0[u, 1]
    area = 0.5 * np.bincount(fid, weights=cross, minlength=len(faces))
    scale = max(float(np.ptp(xy0, axis=0).max()), 1e-300)
    bad = np.flatnonzero(area <= 1e-14 * scale * scale)
    if len(bad):
        k = int(bad[0])
        kind = "clockwise" if area[k] < 0 else "degenerate (zero area)"
        raise FormFindingError(
            f"face {k} {list(faces[k])} is {kind} (signed area {area[k]:.6g}); faces must be counter-clockwise "
            f"seen from +z" + (f" ({len(bad)} such faces)" if len(bad) > 1 else ""))
    codes = u * n0 + v
    order = np.argsort(codes, kind="stable")
    dup = np.flatnonzero(np.diff(codes[order]) == 0)
    if len(dup):
        a, b = order[dup[0]], order[dup[0] + 1]
        raise FormFindingError(
            f"halfedge {u[a]}->{v[a]} is used by faces {fid[a]} and {fid[b]}: inconsistent face orientation "
            f"or non-manifold edge")

    anchors0 = _supports_array(supports, n0, vertices, faces)
    if not anchors0.any():
        raise FormFindingError("no supports: a thrust network needs at least one supported vertex")

    # ---- remove anchor-anchor edges; delete vertices left without edges (drop them from their faces,
    # e.g. a supported corner quad becomes a triangle, and faces left with < 3 vertices) -------------
    cur = faces
    face_index = list(range(len(faces)))
    while True:
        fid, u, v, _ = corner_arrays(cur)
        a, b = np.minimum(u, v), np.maximum(u, v)
        und = np.unique(a * n0 + b)
        eu, ev = und // n0, und % n0
        if update_boundaries:
            keep = ~(anchors0[eu] & anchors0[ev])
            eu, ev = eu[keep], ev[keep]
        deg = np.bincount(np.concatenate([eu, ev]), minlength=n0)
        used = np.zeros(n0, dtype=bool)
        used[u] = True
        dead = used & (deg == 0)
        if not dead.any():
            break
        shrunk = [(k, tuple(i for i in f if not dead[i])) for k, f in zip(face_index, cur)]
        shrunk = [(k, f) for k, f in shrunk if len(f) >= 3]
        if not shrunk:
            raise FormFindingError("every edge joins two supports: nothing is left to form-find")
        face_index = [k for k, _ in shrunk]
        cur = [f for _, f in shrunk]
        fid, u, v, _ = corner_arrays(cur)
        cross = xy0[u, 0] * xy0[v, 1] - xy0[v, 0] * xy0[u, 1]
        area = 0.5 * np.bincount(fid, weights=cross, minlength=len(cur))
        bad = np.flatnonzero(area <= 1e-14 * scale * scale)
        if len(bad):
            k = face_index[int(bad[0])]
            raise FormFindingError(
                f"face {k} {list(faces[k])} becomes {list(cur[int(bad[0])])}, which is not counter-clockwise, "
                f"once its supported vertices without edges are removed; support fewer vertices or "
                f"use update_boundaries=False")

    keepv = deg > 0
    new = np.full(n0, -1, dtype=np.int64)
    new[keepv] = np.arange(int(keepv.sum()))
    vertex_ids = np.flatnonzero(keepv)
    n = len(vertex_ids)
    xy = xy0[vertex_ids].copy()
    anchors = anchors0[vertex_ids].copy()
    if not anchors.any():
        raise FormFindingError("no supports left after removing fully supported edges")
    edges = np.stack([new[eu], new[ev]], axis=1)
    edges = edges[np.lexsort((edges[:, 1], edges[:, 0]))]
    loaded_faces = [tuple(int(new[i]) for i in f) for f in cur]

    # ---- opening faces: twins of boundary halfedges, split at anchors -----------------------------
    lf, lu, lv, _ = corner_arrays(loaded_faces)
    hcode = lu * n + lv
    has_twin = np.isin(lv * n + lu, hcode)
    bu, bv = lv[~has_twin], lu[~has_twin]          # twin halfedges, traversing the opening
    nxt: dict[int, int] = {}
    for a_, b_ in zip(bu.tolist(), bv.tolist()):
        if a_ in nxt:
            raise FormFindingError(
                f"mesh vertex {vertex_ids[a_]} is a pinched boundary vertex (two boundary loops touch there); "
                f"split it or support it")
        nxt[a_] = b_
    opening_faces: list[tuple[int, ...]] = []
    opening_open: list[bool] = []
    seen: set[int] = set()
    for start in bu.tolist():
        if start in seen:
            continue
        loop = [start]
        seen.add(start)
        w = nxt[start]
        while w != start:
            loop.append(w)
            seen.add(w)
            w = nxt[w]
        anchor_pos = [k for k in range(len(loop)) if anchors[loop[k]]]
        if len(anchor_pos) <= 1:
            # a hole (or an opening touching one support): one closed opening face
            if anchor_pos:
                s = anchor_pos[0]
                loop = loop[s:] + loop[:s]
            opening_faces.append(tuple(loop))
            opening_open.append(False)
            continue
        # rotate so that the loop starts at an anchor, then cut it at every anchor into runs; a run of
        # one edge joins two anchors and is not part of the network
        s = anchor_pos[0]
        loop = loop[s:] + loop[:s] + [loop[s]]
        run = [loop[0]]
        for w in loop[1:]:
            run.append(w)
            if anchors[w]:
                if len(run) >= 3:
                    opening_faces.append(tuple(run))
                    opening_open.append(True)
                run = [w]
    all_faces = tuple(loaded_faces) + tuple(opening_faces)
    loaded = np.zeros(len(all_faces), dtype=bool)
    loaded[: len(loaded_faces)] = True

    # ---- edge -> (left, right) face --------------------------------------------------------------
    af, au, av, _ = corner_arrays(all_faces)
    # an open opening face has no halfedge on its closing chord
    is_open = np.concatenate([np.zeros(len(loaded_faces), dtype=bool), np.array(opening_open, dtype=bool)])
    ends = np.concatenate([[0], np.cumsum([len(f) for f in all_faces])])
    last_corner = ends[1:] - 1
    real = np.ones(len(af), dtype=bool)
    real[last_corner[is_open]] = False
    af, au, av = af[real], au[real], av[real]
    hc = au * n + av
    srt = np.argsort(hc)
    hc_sorted, hf_sorted = hc[srt], af[srt]

    def lookup(codes_: np.ndarray) -> np.ndarray:
        pos = np.searchsorted(hc_sorted, codes_)
        pos = np.minimum(pos, len(hc_sorted) - 1)
        found = hc_sorted[pos] == codes_
        return np.where(found, hf_sorted[pos], -1)

    left = lookup(edges[:, 0] * n + edges[:, 1])
    right = lookup(edges[:, 1] * n + edges[:, 0])
    edge_faces = np.stack([left, right], axis=1)

    # ---- validation -------------------------------------------------------------------------------
    C = connectivity_matrix(edges, n)
    adj = sp.csr_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
    ncomp, labels = connected_components(adj, directed=False)
    anchored = np.bincount(labels, weights=anchors.astype(float), minlength=ncomp) > 0
    if not anchored.all():
        c = int(np.flatnonzero(~anchored)[0])
        members = np.flatnonzero(labels == c)
        raise FormFindingError(
            f"unsupported island: {len(members)} vertices (mesh vertices {vertex_ids[members[:8]].tolist()}"
            f"{' ...' if len(members) > 8 else ''}) are connected to no support; support one of them or "
            f"join them to the rest")
    deg = np.bincount(edges.ravel(), minlength=n)
    lonely = np.flatnonzero((deg < 2) & ~anchors)
    if len(lonely):
        raise FormFindingError(
            f"free mesh vertex {vertex_ids[lonely[0]]} has only one edge and cannot be in equilibrium "
            f"({len(lonely)} such vertices); support it or remove it")
    lengths = np.hypot(*(C @ xy).T)
    short = np.flatnonzero(lengths <= 1e-12 * scale)
    if len(short):
        e = int(short[0])
        raise FormFindingError(f"edge between mesh vertices {vertex_ids[edges[e, 0]]} and "
                               f"{vertex_ids[edges[e, 1]]} has zero length")
    active = ~(anchors[edges[:, 0]] & anchors[edges[:, 1]])
    missing = np.flatnonzero(active & ((left < 0) | (right < 0)))
    if len(missing):  # pragma: no cover - guarded by the construction above
        e = int(missing[0])
        raise FormFindingError(f"edge between mesh vertices {vertex_ids[edges[e, 0]]} and "
                               f"{vertex_ids[edges[e, 1]]} has no face on one side")

    for arr in (xy, edges, loaded, anchors, vertex_ids, edge_faces):
        arr.setflags(write=False)
    return FormDiagram(xy=xy, edges=edges, faces=all_faces, loaded=loaded, anchors=anchors,
                       vertex_ids=vertex_ids, edge_faces=edge_faces, C=C)
