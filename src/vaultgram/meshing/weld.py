"""Meshing the patches and welding them into one quad mesh (paper §3.2, Figure 2g).

"Now that a proper number of subdivisions has been assigned to each edge of each patch, these
patches can be separately meshed, using discrete Coons patches. [...] The resulting set of meshes is
welded to obtain a mesh that complies with our requirements: a fully structured quad mesh with a
small number of singularities and no boundary singularities." (§3.2)

Welding is exact by construction, not by a distance tolerance: every patch corner (a node of the
decomposition graph) is one vertex, and every atomic side (:class:`vaultgram.meshing.layout.Side`) is
resampled once, at its group's count, into vertices that both patches along it index. Each patch
then adds only its interior grid points (:func:`vaultgram.meshing.coons.coons_grid`). Faces are
counter-clockwise because patches are and the grid's ``(i, j)`` axes follow the patch's corners.

Resampling is uniform in arc length; on a boundary side, the domain's corners lying inside the side
(ring points whose turning angle makes them corners) are made samples when the count allows, so the
mesh keeps the domain's corners (they stay fixed in smoothing).
"""

from __future__ import annotations

import numpy as np

from vaultgram.errors import VaultgramError
from vaultgram.geometry.polylines import resample_polyline
from vaultgram.meshing.coons import coons_grid, grid_faces
from vaultgram.meshing.layout import Layout, is_feature_node, kept_points, side_anchors
from vaultgram.meshing.quadmesh import QuadMesh, SlideConstraint

__all__ = ["weld"]


def weld(layout: Layout, counts) -> QuadMesh:
    """Mesh every patch with a discrete Coons patch and weld them into one :class:`QuadMesh`.

    Parameters
    ----------
    layout : Layout
        Patches, patterns, sides and groups (:func:`vaultgram.meshing.layout.edge_groups`).
    counts : sequence of int
        Subdivisions per edge group (:func:`vaultgram.meshing.densities.group_counts`).

    Raises
    ------
    VaultgramError
        If a count is not a positive integer or the number of counts is not the number of groups.
    """
    counts = np.asarray(counts)
    if counts.shape != (layout.n_groups,) or not np.issubdtype(counts.dtype, np.integer) or (counts < 1).any():
        raise VaultgramError(f"need one positive integer count per edge group ({layout.n_groups} groups)")
    dec = layout.decomposition
    graph, disc = dec.graph, dec.disc
    side_count = counts[layout.group_of]
    keep_point = kept_points(disc)

    # 1. patch corners: one vertex per decomposition node
    corner_nodes = sorted({c for p in layout.patterns for c in p.corners})
    vid_of_node = {n: k for k, n in enumerate(corner_nodes)}
    pos = [np.array([graph.get(n, "pos") for n in corner_nodes], dtype=float).reshape(-1, 2)]
    n_vert = len(corner_nodes)
    disc_point = [n if 0 <= n < disc.n_points and graph.schema.is_subtype(graph.node_type(n), "BoundaryVertex") else -1
                  for n in corner_nodes]
    vert_disc = [np.array(disc_point, dtype=np.int64)]  # disc point index of each vertex, or -1
    node_arr = [np.array(corner_nodes, dtype=np.int64)]

    # 2. atomic sides: shared samples, stored direction
    side_ids: list[np.ndarray] = []
    side_pts: list[np.ndarray] = []
    side_anchor: list[tuple] = []  # (dense index, sample index) of honoured anchors
    curve_anchor: list[int] = []  # vertices at input vertices of curve features
    for side in layout.sides:
        n = int(side_count[side.id])
        anchors = side_anchors(side, keep_point, disc)
        pts, hit = resample_polyline(side.polyline, n, anchors)
        if side.curve >= 0 and anchors and not hit:
            raise VaultgramError(
                f"curve feature {side.curve}: a side with {len(anchors)} input vertices inside needs at least "
                f"{len(anchors) + 1} subdivisions, got {n} (see edge_groups.curve_min_counts)"
            )
        ids = np.arange(n_vert, n_vert + n - 1)
        n_vert += n - 1
        pos.append(pts[1:-1])
        d = np.full(n - 1, -1, dtype=np.int64)
        for a, h in zip(anchors if hit else (), hit):
            if side.curve >= 0:
                curve_anchor.append(ids[h - 1])
            else:
                d[h - 1] = side.nodes[a]
        vert_disc.append(d)
        node_arr.append(np.full(n - 1, -1, dtype=np.int64))
        side_ids.append(np.concatenate([[vid_of_node[side.start]], ids, [vid_of_node[side.end]]]))
        side_pts.append(pts)
        side_anchor.append(tuple(zip(anchors if hit else (), hit)))

    def oriented(ref):
        s, rev = ref
        return (side_ids[s][::-1], side_pts[s][::-1]) if rev else (side_ids[s], side_pts[s])

    # 3. patches: Coons grids, interior vertices, faces
    quads, tris, quad_patch, tri_patch = [], [], [], []
    for pat in layout.patterns:
        if pat.pole is None:
            (bi, bp), (ri, rp), (ti, tp), (li, lp) = (oriented(r) for r in pat.sides)
            ti, tp, li, lp = ti[::-1], tp[::-1], li[::-1], lp[::-1]
        else:
            k = pat.pole
            (bi, bp), (ri, rp), (ti, tp) = (oriented(pat.sides[(k + j) % 3]) for j in range(3))
            ti, tp = ti[::-1], tp[::-1]
            li = np.full(len(ri), bi[0])
            lp = np.repeat(bp[:1], len(ri), axis=0)
        if len(bi) != len(ti) or len(li) != len(ri):
            raise VaultgramError(f"patch {pat.patch}: opposite sides have different counts (internal error)")
        grid = coons_grid(bp, rp, tp, lp)
        m, n = len(bi) - 1, len(li) - 1
        ids = np.empty((m + 1, n + 1), dtype=np.int64)
        ids[1:-1, 1:-1] = np.arange(n_vert, n_vert + (m - 1) * (n - 1)).reshape(m - 1, n - 1)
        n_vert += (m - 1) * (n - 1)
        pos.append(grid[1:-1, 1:-1].reshape(-1, 2))
        vert_disc.append(np.full((m - 1) * (n - 1), -1, dtype=np.int64))
        node_arr.append(np.full((m - 1) * (n - 1), -1, dtype=np.int64))
        ids[:, 0], ids[:, -1], ids[0, :], ids[-1, :] = bi, ti, li, ri
        q, t = grid_faces(ids, pole=pat.pole is not None)
        quads.append(q)
        tris.append(t)
        quad_patch.append(np.full(len(q), pat.patch))
        tri_patch.append(np.full(len(t), pat.patch))

    vertices = np.vstack(pos)
    vdisc = np.concatenate(vert_disc)
    node = np.concatenate(node_arr)
    q = np.vstack(quads) if quads else np.zeros((0, 4), dtype=np.int64)
    t = np.vstack(tris) if tris else np.zeros((0, 3), dtype=np.int64)
    faces = [tuple(f) for f in q.tolist()] + [tuple(f) for f in t.tolist()]
    face_patch = np.concatenate(quad_patch + tri_patch).astype(np.int64)

    # 4. labels
    nv = len(vertices)
    boundary = np.zeros(nv, dtype=bool)
    ring = np.full(nv, -1, dtype=np.int64)
    for side in layout.sides:
        if side.boundary:
            boundary[side_ids[side.id]] = True
            ring[side_ids[side.id]] = side.ring
    on_disc = vdisc >= 0
    corner = np.zeros(nv, dtype=np.int8)
    turning = np.zeros(nv)
    corner[on_disc] = disc.corner_kind[vdisc[on_disc]]
    turning[on_disc] = disc.turning[vdisc[on_disc]]
    feature = np.zeros(nv, dtype=bool)
    singular = np.zeros(nv, dtype=bool)
    for n, v in vid_of_node.items():
        feature[v] = is_feature_node(dec, n) and graph.node_type(n) != "CurveExtremity"
        singular[v] = graph.node_type(n) in ("Singularity", "LoopVertex")
        if graph.node_type(n) == "Corner" and corner[v] == 0:
            corner[v] = 1
    is_fp = np.zeros(disc.n_points, dtype=bool)
    is_fp[np.asarray(disc.feature_points, dtype=np.int64)] = True
    feature[on_disc] |= is_fp[vdisc[on_disc]]  # a boundary point feature inside a side (not a corner)
    fixed = (corner != 0) | feature
    fixed[on_disc] |= keep_point[vdisc[on_disc]]
    pole = np.zeros(nv, dtype=bool)
    for pat in layout.patterns:
        if pat.pole is not None:
            pole[vid_of_node[pat.corners[pat.pole]]] = True
    curve = np.full(nv, -1, dtype=np.int64)
    for side in layout.sides:
        if side.curve >= 0:
            curve[side_ids[side.id]] = side.curve
    extremity = np.zeros(nv, dtype=bool)
    for n, v in vid_of_node.items():
        extremity[v] = graph.node_type(n) == "CurveExtremity"
    fixed[np.asarray(curve_anchor, dtype=np.int64)] = True
    for n, v in vid_of_node.items():  # patch corners at input vertices of a curve (its bends)
        if 0 <= n < disc.n_points and curve[v] >= 0 and disc.is_input_vertex[n]:
            fixed[v] = True
    fixed |= extremity  # "point and curve constraints are added" (§4.2, Figure 7d)
    chains = _curve_chains(layout, side_ids, vid_of_node)

    constraints = _boundary_constraints(layout, side_ids, side_anchor, fixed)
    constraints += _curve_constraints(disc, chains, node, vertices, fixed)
    groups = tuple(
        {"id": g.id, "count": int(counts[g.id]), "sides": len(g.sides),
         "mean_length": g.mean_length, "max_length": g.max_length}
        for g in layout.groups
    )
    curve_lines = tuple(np.asarray(disc.points[c], dtype=float) for c in disc.curves)
    return QuadMesh(vertices, faces, face_patch, boundary, ring, corner, turning, fixed, pole, feature,
                    node, singular, groups, constraints, {}, curve, extremity, chains, curve_lines)


def _curve_chains(layout: Layout, side_ids, vid_of_node) -> tuple:
    """For each curve feature, its mesh vertices in order along the curve (the curve sides, joined)."""
    disc = layout.decomposition.disc
    out = []
    for c, pts in enumerate(disc.curves):
        where = {int(p): k for k, p in enumerate(pts)}
        pieces = []
        for side in layout.sides:
            if side.curve != c:
                continue
            a, b = where.get(side.start), where.get(side.end)
            if a is None or b is None:
                raise VaultgramError(f"curve feature {c}: a side ends off the curve (internal error)")
            ids = side_ids[side.id]
            pieces.append((min(a, b), ids if a < b else ids[::-1]))
        pieces.sort(key=lambda t: t[0])
        if not pieces:
            out.append(np.zeros(0, dtype=np.int64))
            continue
        chain = [pieces[0][1]]
        for _, ids in pieces[1:]:
            if ids[0] != chain[-1][-1]:
                raise VaultgramError(f"curve feature {c}: its sides do not join into one chain (internal error)")
            chain.append(ids[1:])
        out.append(np.concatenate(chain))
    return tuple(out)


def _curve_constraints(disc, chains, node, vertices, fixed) -> tuple:
    """Split each curve chain at its fixed vertices (extremities, input vertices of the curve, boundary
    ends) into stretches that slide on the piece of the curve between them (§4.2, Figure 7d)."""
    out = []
    for c, chain in enumerate(chains):
        if len(chain) < 3:
            continue
        line = np.asarray(disc.points[disc.curves[c]], dtype=float)
        stops = [0] + [k for k in range(1, len(chain) - 1) if fixed[chain[k]]] + [len(chain) - 1]
        for i, j in zip(stops[:-1], stops[1:]):
            if j - i < 2:
                continue
            a, b = _curve_index(line, vertices[chain[i]]), _curve_index(line, vertices[chain[j]])
            out.append(SlideConstraint(chain[i + 1:j].copy(), line[min(a, b):max(a, b) + 1], closed=False))
    return tuple(out)


def _curve_index(line: np.ndarray, p: np.ndarray) -> int:
    """Index of the point of ``line`` at ``p`` (a mesh vertex standing for a curve point)."""
    return int(np.argmin(np.hypot(*(line - p).T)))


def _boundary_constraints(layout: Layout, side_ids, side_anchor, fixed) -> tuple:
    """Split every ring's chain of boundary sides at fixed vertices into sliding stretches."""
    by_start = {}
    for side in layout.sides:
        if side.boundary:
            by_start[side.start] = side
    seen: set[int] = set()
    out = []
    for side in layout.sides:
        if not side.boundary or side.id in seen:
            continue
        chain = []
        s = side
        while s.id not in seen:
            seen.add(s.id)
            chain.append(s)
            s = by_start.get(s.end)
            if s is None:
                raise VaultgramError(f"boundary ring {side.ring} is not closed by patch sides (internal error)")
        verts, dense, fixed_at = [], [], []  # vertex ids; dense polyline; (position in verts, dense index)
        for s in chain:
            off = len(dense)
            ids = side_ids[s.id][:-1]
            anchor_of_sample = {h: a for a, h in side_anchor[s.id]}
            for k, v in enumerate(ids):
                if fixed[v]:
                    if k == 0:
                        fixed_at.append((len(verts), off))
                    elif k in anchor_of_sample:
                        fixed_at.append((len(verts), off + anchor_of_sample[k]))
                verts.append(v)
            dense.extend(s.polyline[:-1])
        verts = np.asarray(verts, dtype=np.int64)
        dense = np.asarray(dense, dtype=float)
        if not fixed_at:
            out.append(SlideConstraint(verts, dense, closed=True))
            continue
        for (i, a), (j, b) in zip(fixed_at, fixed_at[1:] + fixed_at[:1]):
            if j <= i:
                j += len(verts)
            if b <= a:
                b += len(dense)
            inner = np.take(verts, np.arange(i + 1, j), mode="wrap")
            if len(inner) == 0:
                continue
            poly = np.take(dense, np.arange(a, b + 1), axis=0, mode="wrap")
            out.append(SlideConstraint(inner, poly, closed=False))
    return tuple(out)
