"""Boundary recovery by local refinement (paper §3.1, step 3 of :mod:`vaultgram.topology.triangulation`).

The discretisation is usually dense enough for every boundary and curve segment to be an edge of the
Delaunay triangulation; where it is not (a sample of another ring, a hole or a feature lies in the
segment's circumcircle: a thin part of the plan, a hole near the outline), the plan is not refused:
the midpoint of each missing segment becomes a vertex of its ring or curve (the geometry is the
same: the point lies on the segment), the plan is discretised again and triangulated again. Each
round halves the sample segments where they failed (a conforming Delaunay refinement, local to
where it is needed); after :data:`MAX_ROUNDS` rounds the error names the place, as before.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from vaultgram.topology.discretise import Discretisation, discretise
from vaultgram.topology.triangulation import BoundaryRecoveryError, Triangulation, triangulate

__all__ = ["MAX_ROUNDS", "triangulate_recovering"]

#: Rounds of refinement before a missing segment is an error (each halves the sampling there).
MAX_ROUNDS = 8


def triangulate_recovering(disc: Discretisation, rounds: int = MAX_ROUNDS) -> Triangulation:
    """:func:`~vaultgram.topology.triangulation.triangulate` ``disc``, refining where a boundary or
    curve segment is not an edge of the Delaunay triangulation (see the module docstring). The
    triangulation's ``disc`` is the refined discretisation, of the plan with the inserted vertices;
    a plan that needs none gets exactly the triangulation ``triangulate`` gives.

    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.topology.discretise import discretise
    >>> triangulate_recovering(discretise(load_domain("examples/quad_with_hole.json"), 0.05))
    Triangulation(124 points, 124 faces: 4 corner, 116 regular, 4 singular; 116 cells)
    """
    for k in range(rounds + 1):
        try:
            return triangulate(disc)
        except BoundaryRecoveryError as exc:
            if k == rounds:
                raise
            disc = discretise(with_midpoints(disc.domain, exc.segments), disc.spacing, chamfers=disc.chamfers,
                             smooth_at=disc.smooth_at)
    raise AssertionError("unreachable")  # pragma: no cover


def with_midpoints(domain, segments: np.ndarray):
    """``domain`` with the midpoint of each segment ``(k, 2, 2)`` inserted as a vertex into the ring
    or curve it lies on (the one closest to it)."""
    lines = {("outer", 0): domain.outer, **{("hole", k): h for k, h in enumerate(domain.holes)},
             **{("curve", k): c for k, c in enumerate(domain.curves)}}
    inserts: dict = {key: [] for key in lines}
    for m in 0.5 * (segments[:, 0] + segments[:, 1]):
        key, seg = min(((key, *_closest_segment(line, m, key[0] != "curve")) for key, line in lines.items()),
                       key=lambda hit: hit[2])[:2]
        inserts[key].append((seg, m))
    new = {key: _inserted(lines[key], inserts[key], key[0] != "curve") for key in lines}
    return dataclasses.replace(
        domain, outer=new[("outer", 0)], holes=tuple(new[("hole", k)] for k in range(len(domain.holes))),
        curves=tuple(new[("curve", k)] for k in range(len(domain.curves))))


def _closest_segment(line: np.ndarray, p: np.ndarray, closed: bool) -> tuple[int, float]:
    """The segment of a polyline (closed for a ring) closest to ``p``, and its distance."""
    a = line if closed else line[:-1]
    b = np.roll(line, -1, axis=0) if closed else line[1:]
    d = b - a
    t = np.clip(((p - a) * d).sum(axis=1) / np.maximum((d * d).sum(axis=1), 1e-300), 0.0, 1.0)
    dist = np.hypot(*(a + t[:, None] * d - p).T)
    k = int(np.argmin(dist))
    return k, float(dist[k])


def _inserted(line: np.ndarray, inserts: list, closed: bool) -> np.ndarray:
    """``line`` with each ``(segment, point)`` inserted after the segment's first vertex, in order
    along the segment; read-only like the domain's arrays."""
    if not inserts:
        return line
    rows = [(k, 0.0, line[k]) for k in range(len(line))]
    for seg, p in inserts:
        rows.append((seg, 1.0 + float(np.hypot(*(p - line[seg]))), p))
    rows.sort(key=lambda r: (r[0], r[1]))
    out = np.array([r[2] for r in rows], dtype=np.float64)
    out.setflags(write=False)
    return out
