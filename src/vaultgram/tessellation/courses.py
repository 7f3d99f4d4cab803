"""Construction order: courses and names of the voussoirs (paper §5, construction-aware tessellation).

A masonry vault is built from its supports up: the voussoirs resting on a support are course 0, those
joined to course 0 by a joint course 1, and so on (a breadth-first search over the voussoirs'
joints from every support at once). Each support (a connected run of supported vertices) is a
*zone*, lettered A, B, C...; a voussoir belongs to the zone of the support it is reached from
first, and is named by zone, course and its number in that course: ``B3.7`` -- as the built
Armadillo Vault's stones are named by zone and course.
"""

from __future__ import annotations

import string

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components, dijkstra

__all__ = ["support_zones", "voussoir_courses", "voussoir_names"]


def support_zones(edges: np.ndarray, supported: np.ndarray) -> np.ndarray:
    """Per vertex, the zone of the support it lies on (runs of supported vertices joined by edges,
    numbered by their smallest vertex), -1 where it is not supported."""
    n = len(supported)
    both = supported[edges[:, 0]] & supported[edges[:, 1]]
    e = edges[both]
    graph = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    zone = np.full(n, -1, dtype=np.int64)
    ids = np.flatnonzero(supported)
    _, first = np.unique(label[ids], return_index=True)
    rank = {int(label[ids[i]]): k for k, i in enumerate(sorted(first.tolist()))}
    zone[ids] = [rank[int(label[i])] for i in ids]
    return zone


def voussoir_courses(neighbours: np.ndarray, n_voussoirs: int, resting: np.ndarray, zone_of: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """Course (joints away from a support) and zone of every voussoir.

    ``neighbours`` are pairs of voussoirs sharing a joint, ``resting`` the voussoirs touching a
    support and ``zone_of`` their zones. A voussoir no support reaches gets course -1, zone -1.
    """
    n = n_voussoirs
    if not len(resting):
        return np.full(n, -1, dtype=np.int64), np.full(n, -1, dtype=np.int64)
    graph = coo_matrix((np.ones(len(neighbours)), (neighbours[:, 0], neighbours[:, 1])), shape=(n, n)).tocsr()
    dist, _, source = dijkstra(graph, directed=False, indices=resting, unweighted=True, min_only=True,
                               return_predecessors=True)
    reached = np.isfinite(dist)
    course = np.where(reached, dist, -1).astype(np.int64)
    zone_by_source = np.full(n, -1, dtype=np.int64)
    zone_by_source[resting] = zone_of
    zone = np.where(reached, zone_by_source[np.maximum(source, 0)], -1)
    return course, zone


def _letters(k: int) -> str:
    """Zone letters A..Z, then AA, AB..."""
    letters = string.ascii_uppercase
    return letters[k] if k < 26 else _letters(k // 26 - 1) + letters[k % 26]


def voussoir_names(course: np.ndarray, zone: np.ndarray) -> list[str]:
    """``<zone letter><course>.<number in that zone and course, from 1>``, in voussoir order; ``X`` for
    voussoirs no support reaches.

    >>> voussoir_names(np.array([0, 0, 1, 0]), np.array([0, 0, 0, 1]))
    ['A0.1', 'A0.2', 'A1.1', 'B0.1']
    """
    seen: dict[tuple[int, int], int] = {}
    out = []
    for c, z in zip(course.tolist(), zone.tolist()):
        seen[(z, c)] = seen.get((z, c), 0) + 1
        out.append(f"{_letters(z) if z >= 0 else 'X'}{c if c >= 0 else ''}.{seen[(z, c)]}")
    return out
