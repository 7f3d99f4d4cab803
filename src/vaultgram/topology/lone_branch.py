"""A skeleton that is one branch between two corners, cut in three (issue 12).

Where the plan has two sharp corners and no other feature of its outline (a half disc, a lens, a
D-shaped apse), the medial axis is a single branch from one corner to the other, without a
junction: a half disc's is the parabola of the centres of the circles touching both its diameter and
its arc. The paper's rules (Figure 2d, 2e) find no singularity to prune or rebranch from, so the
branch cuts the plan into two faces of two corners each, which no pattern meshes (``vaultgram
decompose`` refused such a plan with "patch ... has 2 sides").

Cut at a third and two thirds of its length, each cut point linked to the two boundary points its
maximal circle touches (the nearest of each chain of the ring between the corners), the middle third
kept and the end thirds dropped (they would run into the corners, as pruned corner branches do), the
plan is four quads: one at each corner (its only face there: valence 2, regular at a sharp corner)
and two along the middle, one on each side. The cut points are the only singular vertices (three
patches each, valence 3), and the index theorem's sum is met: two corners of one face and two
interior vertices of three, 4 for a disc. ``rules/topology.vgr`` draws it (rule
``cut_lone_branch``) with these helpers.
"""

from __future__ import annotations

import weakref

import numpy as np

from vaultgram.geometry.polylines import arc_lengths, point_at_length
from vaultgram.topology.corners import graph_rings
from vaultgram.topology.patches import half_edge_polyline
from vaultgram.topology.statecache import memo_at

__all__ = ["branch_cut", "branch_piece", "branch_foot", "register_lone_branch_helpers"]

#: The helpers' answers, per state of the rule graph (the rule asks for the same feet at every
#: boundary point it tries).
_ANSWERS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _polyline(graph, b: int) -> np.ndarray:
    """Branch ``b``'s points from its source."""
    return np.asarray(half_edge_polyline(graph, b, graph.ends(b)[0]), dtype=float)


def branch_cut(graph, b: int, t: float) -> tuple[float, float]:
    """The point of branch ``b`` at the fraction ``t`` of its length from its source."""
    pts = _polyline(graph, b)
    p = point_at_length(pts, t * arc_lengths(pts)[-1])
    return float(p[0]), float(p[1])


def branch_piece(graph, b: int, t0: float, t1: float) -> tuple:
    """The part of branch ``b`` between the fractions ``t0 < t1`` of its length from its source, as a
    polyline (its points in between, and the two cut points)."""
    pts = _polyline(graph, b)
    s = arc_lengths(pts)
    inside = pts[(s > t0 * s[-1]) & (s < t1 * s[-1])]
    piece = np.vstack([point_at_length(pts, t0 * s[-1]), inside, point_at_length(pts, t1 * s[-1])])
    return tuple((float(x), float(y)) for x, y in piece)


def branch_foot(graph, b: int, t: float, side: int) -> int:
    """Where the maximal circle at :func:`branch_cut` ``(b, t)`` touches the boundary on one side of
    the branch: the ring point nearest to it among those strictly between the branch's two ends,
    following the ring from the source to the target (``side`` 0) or from the target to the source
    (1). The branch's source itself where its ends are not on one ring or that stretch is empty."""
    return memo_at(_ANSWERS, graph, (b, t, side), lambda: _foot(graph, b, t, side))


def _foot(graph, b: int, t: float, side: int) -> int:
    """:func:`branch_foot`, computed."""
    source, target = graph.ends(b)
    for ring, nodes in zip(*graph_rings(graph)):
        if source in nodes and target in nodes:
            i, j = nodes.index(source), nodes.index(target)
            first, last = (i, j) if side == 0 else (j, i)
            chain = (np.arange(first + 1, first + (last - first) % len(nodes)) % len(nodes))
            if len(chain) == 0:
                break
            d = np.hypot(*(ring[chain] - np.asarray(branch_cut(graph, b, t))).T)
            return nodes[int(chain[int(np.argmin(d))])]
    return source


def register_lone_branch_helpers(f) -> None:
    """Register :func:`branch_cut`, :func:`branch_piece` and :func:`branch_foot` for the rules."""
    f.register("branch_cut", branch_cut, ("edge", "number"), "vec2", uses_graph=True, local=False)
    f.register("branch_piece", branch_piece, ("edge", "number", "number"), "list", uses_graph=True, local=False)
    f.register("branch_foot", branch_foot, ("edge", "number", "int"), "node", uses_graph=True, local=False)
