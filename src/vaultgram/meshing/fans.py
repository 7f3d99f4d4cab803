"""How good the corners round a vertex can be at all, whatever smoothing does: the fan bound.

A pole of a three-sided patch (§3.2, Figure 3) gets one triangle per subdivision of the side opposite
it, so a pole with many triangles has narrow corners however its neighbours are placed: its faces
share the pole's angle in the mesh (360 degrees inside, the domain's corner angle on the boundary).
A corner of angle ``a`` has the scaled Jacobian ``sin(a)`` in a quad and ``min(1, sin(a) 2 / sqrt(3))``
in a triangle (:func:`vaultgram.meshing.quality.face_scaled_jacobians`), so reaching ``s`` at every
corner of the vertex needs ``a >= asin(s)`` per quad corner and ``a >= asin(s sqrt(3) / 2)`` per
triangle corner, and these must fit in the vertex's angle. :func:`fan_bounds` is the largest such
``s``: an upper bound no placement of the other vertices can beat; only fewer faces at the vertex
(another pattern, or a finer split of its angle) can.

Coons interpolation shares a pole's angle among its triangles unequally; :func:`even_fans` spreads
them evenly before smoothing, where that lets the pole reach the floor :data:`FAN_FLOOR`, and on a
retry (:func:`poles_to_retry`) where it does not but the pole's fans hold the mesh's worst face.
"""

from __future__ import annotations

import math

import numpy as np

from vaultgram.geometry.arrays import distinct
from vaultgram.geometry.meshes import corner_angles, corner_arrays
from vaultgram.geometry.polygons import signed_angles
from vaultgram.meshing.quadmesh import SlideConstraint
from vaultgram.meshing.quality import face_scaled_jacobians

__all__ = ["FAN_FLOOR", "fan_bounds", "even_fans", "poles_to_retry", "poles_to_widen", "held_vertices", "sector_needs",
           "point_loads"]

#: The worst scaled Jacobian a mesh should keep (issue 12's floor): a fan whose triangles would be
#: thinner is split (:mod:`vaultgram.meshing.splits`), evened where that reaches it
#: (:func:`even_fans`; below it only on a retry), and left alone by the optimiser where nothing can
#: (:mod:`vaultgram.meshing.optimise`).
FAN_FLOOR = 0.3
_BISECTIONS = 50
#: The last trial of :func:`_bisected` where every trial fits (each trial halves the distance to 1).
_TOP = 1.0 - 0.5 ** _BISECTIONS


def fan_bounds(vertices: np.ndarray, faces) -> np.ndarray:
    """Per vertex, the largest scaled Jacobian all its corners could reach together, given its
    number of triangle and quad corners and its angle in the mesh (the sum of its corners' angles);
    1 where that is no limit, ``inf`` at vertices without faces.

    Example
    -------
    A vertex with 24 triangles round it (15 degrees each) can reach ``sin(15) 2 / sqrt(3)``:

    >>> ring = np.column_stack([np.cos(np.arange(24) * np.pi / 12), np.sin(np.arange(24) * np.pi / 12)])
    >>> v = np.vstack([[0.0, 0.0], ring])
    >>> f = [(0, 1 + k, 1 + (k + 1) % 24) for k in range(24)]
    >>> round(float(fan_bounds(v, f)[0]), 4), round(math.sin(math.pi / 12) * 2 / math.sqrt(3), 4)
    (0.2989, 0.2989)
    """
    x = np.asarray(vertices, dtype=float)
    face_of, u, v, p = corner_arrays(faces)
    n = len(x)
    angle = corner_angles(x, u, v, p)
    theta = np.bincount(u, weights=np.where(angle < 0, angle + 2 * math.pi, angle), minlength=n)
    tri = (np.bincount(face_of, minlength=len(faces)) == 3)[face_of]
    n_tri = np.bincount(u, weights=tri, minlength=n)
    n_quad = np.bincount(u, weights=~tri, minlength=n)
    top = np.full(n, _TOP)
    bound = top.copy()
    limited = ~(_angle_needed(top, n_tri, n_quad) <= theta)
    bound[limited] = _bisected(n_tri[limited], n_quad[limited], theta[limited])
    return np.where(n_tri + n_quad > 0, bound, np.inf)


def _angle_needed(s: np.ndarray, n_tri: np.ndarray, n_quad: np.ndarray) -> np.ndarray:
    """The angle that ``n_tri`` triangle and ``n_quad`` quad corners need to reach the scaled Jacobian
    ``s`` each."""
    return n_tri * np.arcsin(np.minimum(1.0, s * math.sqrt(3.0) / 2)) + n_quad * np.arcsin(s)


def _bisected(n_tri: np.ndarray, n_quad: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """The largest scaled Jacobian whose :func:`_angle_needed` fits in ``theta``, by :data:`_BISECTIONS`
    bisections of [0, 1]. A vertex where every trial fits ends at :data:`_TOP`, the last trial (the
    angle needed grows with ``s``, by far more than round-off between trials): :func:`fan_bounds`
    bisects only the others (4 of the 10^6 vertices of quad_with_hole meshed at 10^6 faces)."""
    lo, hi = np.zeros(len(theta)), np.ones(len(theta))
    for _ in range(_BISECTIONS):
        s = 0.5 * (lo + hi)
        fits = _angle_needed(s, n_tri, n_quad) <= theta
        lo, hi = np.where(fits, s, lo), np.where(fits, hi, s)
    return lo


#: A pole's ring vertex slides on its ray between these multiples of its distance from the pole.
RAY_SPAN = (0.05, 4.0)


def even_fans(vertices: np.ndarray, faces, face_patch: np.ndarray, pole: np.ndarray, held: np.ndarray,
              regardless: frozenset = frozenset(), wide: bool = False, radial=None) -> tuple[np.ndarray, tuple, tuple]:
    """The poles' fans made even: the vertices round each pole between two of its triangles turned to
    equal angles about it, the rays from the pole along which smoothing then lets them slide, and the
    poles left for a retry: those whose evening the check below refused, those under the floor, and
    those evened here with the check (not in ``regardless``), whose evening smoothing may undo.

    Coons interpolation (§3.2) spaces a fan's spokes by the arc length of the side opposite the pole,
    and a patch's share of its pole's angle comes from the decomposition, so the triangles round a pole
    get unequal corners there (10 to 32 degrees round an inner point feature of
    ``fig6_inner_points``) that Laplacian smoothing does not even out: the worst of them bounds the
    mesh's scaled Jacobian well below what the pole's number of faces allows (:func:`fan_bounds`).
    Here the spokes of each run of triangles round a pole, between two spokes that stay (``held``
    vertices, such as boundary and curve vertices, the sides of the pole's quads, and the far sides
    of its fans' patches, ``face_patch``, where a fan is one face deep), share the run's angle
    equally; round a pole of triangles only, the whole turn, rotated as little as possible. Each
    spoke keeps its distance from the pole and gets a
    :class:`~vaultgram.meshing.quadmesh.SlideConstraint` on its ray: smoothing finds its distance,
    keeps its angle, and turns the rest of the patches with it. (Turning them at once, by the
    harmonic interpolation of the spokes' turns, skewed more quads than it evened: the mean scaled
    Jacobian of ``features_combined`` fell from 0.903 to 0.899.)

    Only poles whose :func:`fan_bounds` reaches :data:`FAN_FLOOR` are evened, and only where that
    does not make the worst corner of the spokes' faces worse before smoothing (a fan pressed
    against its far side, as at the curve's end (5, 7.5) of ``features_combined``: evened regardless,
    its worst scaled Jacobian was 0.225 instead of 0.250, and ``rv_star_pattern``'s 0.501 instead of
    0.538). Round a pole of triangles only, whose whole turn may move a spoke by tens of degrees,
    only the fan's own corners count: the quads behind the spokes may fold before smoothing, which
    turns them with the spokes (the inner point feature (7.09, 5.56) of ``two_holes_five_points``,
    20 triangles whose patches share 62 to 112 degrees: 0.302 after smoothing, 0.251 left as it was).
    A pole under the floor is not evened at first but returned with the refused ones: the caller
    smooths again with it evened (``regardless``) where its patches hold the mesh's worst face
    (:func:`poles_to_retry`) and keeps the better mesh: of the 305 saved random plans under 0.3 (most
    of them with a fan under the floor as their worst face), 52 better, none worse, 57 -> 45 under 0.1
    (benchmarks/README.md, session 21). Except round a point load (an inner point feature, ``radial``,
    a mask of the vertices): below the floor evening turns the patches round it away from its radial
    force flow:
    ``square_point_loads`` (39 triangles round each load, bound 0.185) went from 0.093 to 0.185, but
    its voussoir joints from 8.2 to 11.0 degrees off the force flow (median; the tessellation's
    floor is 10), so its fans stay as the patches give them. The check only foresees smoothing: the
    poles in ``regardless`` are evened without it. An evened pole is left for a retry too: smoothing
    moves the spokes that stay (a quad's side beside the fan), so a run evened between them may end in
    a thin triangle after it, and only a retry evens it again after smoothing (the caller's
    ``_evened_again``). Saved random plan 111 of 700: round its curve's free end (bound 0.335), 19
    triangles and 2 quads, the triangles smoothed to 9.4 to 65.8 degrees (worst face 0.188); retried,
    17 of them 13.3 each (0.266; benchmarks/README.md, session 22, s22-curveloss).

    Example
    -------
    Six triangles round a pole at the origin, their spokes at uneven angles, become 60 degrees apart,
    turned by the mean of their moves:

    >>> a = np.radians([0, 20, 100, 180, 200, 300])
    >>> v = np.vstack([[0.0, 0.0], np.column_stack([np.cos(a), np.sin(a)])])
    >>> f = [(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)]
    >>> x, rays, refused = even_fans(v, f, np.zeros(6, int), np.arange(7) == 0, np.zeros(7, bool))
    >>> np.round(np.degrees(np.arctan2(x[1:, 1], x[1:, 0])) % 360, 6).tolist(), len(rays), refused
    ([343.333333, 43.333333, 103.333333, 163.333333, 223.333333, 283.333333], 6, (0,))
    """
    x = np.array(vertices, dtype=float)
    corners = corner_arrays(faces)
    at = np.flatnonzero(np.asarray(pole, dtype=bool)[corners[1]])
    if not len(at):
        return x, (), ()
    size = np.bincount(corners[0], minlength=len(faces))
    reach = fan_bounds(x, faces)
    kept = np.zeros(len(x), dtype=bool) if radial is None else np.asarray(radial, dtype=bool)
    rays, refused = [], []
    for c in distinct(corners[1][at]):
        if reach[c] < FAN_FLOOR and (kept[c] or int(c) not in regardless):  # below it: only on a retry
            refused += [] if kept[c] else [int(c)]
            continue
        turned = _even_pole(x, faces, int(c), corners, size, at[corners[1][at] == c], np.asarray(face_patch), held,
                            check=int(c) not in regardless, wide=wide)
        rays += turned or []
        refused += [] if int(c) in regardless else [int(c)]  # refused, or evened before smoothing only
    return x, tuple(rays), tuple(refused)


def poles_to_retry(x: np.ndarray, faces, face_patch: np.ndarray, refused) -> frozenset:
    """The ``refused`` poles (see :func:`even_fans`) to even regardless once the mesh is smoothed
    (``x``): those whose fans' patches hold its worst face, where that face is under the floor.

    Example
    -------
    The worst face (0) lies in the patch of pole 0's fan, not in pole 5's:

    >>> v = np.array([[0, 0], [1, 0], [0.5, 0.05], [2, 0], [2, 1], [3, 3.0]])
    >>> f = [(0, 1, 2), (1, 3, 4), (4, 3, 5)]
    >>> sorted(poles_to_retry(v, f, np.array([0, 1, 2]), (0, 5)))
    [0]
    """
    if not refused:
        return frozenset()
    sj = face_scaled_jacobians(x, faces)
    if sj.min() >= FAN_FLOOR:
        return frozenset()
    face_of, u, _, _ = corner_arrays(faces)
    patch = np.asarray(face_patch)
    worst = patch[int(np.argmin(sj))]
    return frozenset(c for c in refused if worst in patch[face_of[u == c]])


def poles_to_widen(x: np.ndarray, faces, pole: np.ndarray) -> frozenset:
    """The poles of the smoothed mesh's (``x``) worst face whose :func:`fan_bounds` reaches the floor,
    where that face is under it: their fans may be hemmed in by quads round the pole, whose sides
    :func:`even_fans` holds, and evened better with the quads' corners in the share (its ``wide``).

    Example
    -------
    Pole 0 has a thin triangle (0, 1, 2) beside a quad that takes most of its angle:

    >>> v = np.array([[0, 0], [1, 0], [1, 0.1], [-1, 0], [-1, -1], [1, -1.0]])
    >>> sorted(poles_to_widen(v, [(0, 1, 2), (0, 3, 4, 5)], np.arange(6) == 0))
    [0]
    """
    sj = face_scaled_jacobians(x, faces)
    worst = int(np.argmin(sj))
    if sj[worst] >= FAN_FLOOR:
        return frozenset()
    bound = fan_bounds(x, faces)
    return frozenset(int(c) for c in faces[worst] if pole[c] and bound[c] >= FAN_FLOOR)


def _even_pole(x: np.ndarray, faces, c: int, corners: tuple, size: np.ndarray, mine: np.ndarray,
               face_patch: np.ndarray, held: np.ndarray, check: bool = True, wide: bool = False) -> list | None:
    """Pole ``c``'s fans evened in place (its corners ``mine``; see :func:`even_fans`) unless, where
    ``check``, that makes the worst corner of its spokes' faces worse (of its own triangles, round a pole
    of triangles only); the rays of the spokes that turned, or None where the check refused."""
    face_of, u, v, p = corners
    tri = size[face_of[mine]] == 3
    region = np.isin(face_patch, face_patch[face_of[mine if wide else mine[tri]]])  # the patches of its fans
    stays = np.asarray(held, dtype=bool).copy()
    stays[u[~region[face_of]]] = True  # their far sides
    spokes, angles = _even_spokes(x[:, :2], c, v[mine], p[mine], tri, stays, wide)
    if not spokes:
        return []
    spokes = np.asarray(spokes)
    d = x[spokes, :2] - x[c, :2]
    turn = (np.asarray(angles) - np.arctan2(d[:, 1], d[:, 0]) + math.pi) % (2 * math.pi) - math.pi
    closed = len(spokes) == len(mine)  # every spoke turns: a pole of triangles only
    near, before = (u == c) if closed else np.isin(u, spokes), x[spokes].copy()
    worst = _worst_corner(x, faces, face_of, near)
    _turn_about(x, c, spokes, turn)
    if check and _worst_corner(x, faces, face_of, near) < worst:
        x[spokes] = before
        return None
    return [SlideConstraint(np.array([w]), x[c, :2] + np.outer(RAY_SPAN, x[w, :2] - x[c, :2])) for w in spokes]


def _worst_corner(x: np.ndarray, faces, face_of: np.ndarray, mask: np.ndarray) -> float:
    """The smallest scaled Jacobian of the faces of the ``mask`` ed corners."""
    return float(face_scaled_jacobians(x, [faces[f] for f in distinct(face_of[mask])]).min(initial=1.0))


def _even_spokes(x: np.ndarray, c: int, nxt: np.ndarray, prev: np.ndarray, tri: np.ndarray,
                 held: np.ndarray, wide: bool = False) -> tuple[list, list]:
    """The free spokes round pole ``c`` (its corners' next and previous vertices ``nxt``, ``prev``) and
    their even angles: sectors in turn from a spoke that starts a chain (a boundary pole) or from the
    lowest one (a closed fan)."""
    sector = {int(a): (int(b), bool(t)) for a, b, t in zip(nxt, prev, tri)}
    if len(sector) != len(nxt):
        return [], []
    ends = set(sector) - {b for b, _ in sector.values()}
    after = {b: t for b, t in sector.values()}
    stay = [a for a, (_, t) in sector.items() if held[a] or not t or not after.get(a, True)]
    start = min(ends) if ends else min(stay) if stay else min(sector)  # a closed fan's run from a spoke that stays
    chain, kinds = [start], []
    while chain[-1] in sector and (len(chain) == 1 or chain[-1] != start):
        b, t = sector[chain[-1]]
        chain.append(b)
        kinds.append(t)
    sides = x[chain] - x[c]
    angle = signed_angles(sides[:-1], sides[1:])
    turn = np.concatenate([[0.0], np.cumsum(np.where(angle <= 0, angle + 2 * math.pi, angle))])
    free = [0 < i < len(chain) - 1 and (wide or kinds[i - 1] and kinds[i]) and not held[chain[i]]
            for i in range(len(chain))]
    if not ends and all(kinds) and not any(held[chain[:-1]]):
        return _closed_fan(x, c, chain[:-1], turn)
    return _runs(x, c, chain, turn, free, kinds)


def _closed_fan(x: np.ndarray, c: int, spokes: list, turn: np.ndarray) -> tuple[list, list]:
    """A pole of triangles only: every spoke free, ``2 pi / n`` apart, rotated to move them least."""
    d = x[spokes[0]] - x[c]
    step = 2 * math.pi / len(spokes)
    offset = float(np.mean(turn[:-1] - step * np.arange(len(spokes))))
    return spokes, list(math.atan2(d[1], d[0]) + offset + step * np.arange(len(spokes)))


def _runs(x: np.ndarray, c: int, chain: list, turn: np.ndarray, free: list, kinds: list) -> tuple[list, list]:
    """The free spokes of ``chain`` placed between the spokes that stay on either side, each run's
    angle shared among its faces by what each kind needs (:func:`sector_needs`: ``kinds`` tells the
    triangles from the quads)."""
    d = x[chain[0]] - x[c]
    base = math.atan2(d[1], d[0])
    spokes, angles, last = [], [], 0
    for i in range(1, len(chain)):
        if free[i]:
            continue
        need = sector_needs(np.asarray(kinds[last:i], dtype=bool), turn[i] - turn[last])
        cumulative = np.cumsum(need)
        for j in range(1, i - last):
            spokes.append(chain[last + j])
            angles.append(base + turn[last] + cumulative[j - 1] * (turn[i] - turn[last]) / cumulative[-1])
        last = i
    return spokes, angles


def sector_needs(tri: np.ndarray, total: float) -> np.ndarray:
    """The angles that the faces of a run round a pole (triangles where ``tri``) need for the best
    scaled Jacobian all of them can reach together in the run's ``total`` (radians; :func:`_bisected`),
    relative to the least of them: a run shares its angle in these proportions. A quad needs more
    than a triangle for the same quality (``asin(s)`` against ``asin(s sqrt(3) / 2)``); faces of one
    kind need the same (exactly 1 each, so that a run of triangles is divided exactly evenly).

    >>> need = sector_needs(np.array([True, True, False]), math.pi / 2)
    >>> np.round(np.degrees(need / need.sum() * math.pi / 2), 3).tolist()  # degrees of the 90
    [28.365, 28.365, 33.27]
    >>> sector_needs(np.array([True, True]), math.pi / 2).tolist()
    [1.0, 1.0]
    """
    n_tri, n_quad = np.array([tri.sum()], dtype=float), np.array([(~tri).sum()], dtype=float)
    s = _bisected(n_tri, n_quad, np.array([total]))
    need = np.where(tri, np.arcsin(np.minimum(1.0, s * math.sqrt(3.0) / 2)), np.arcsin(s))
    return need / need.min()


def _turn_about(x: np.ndarray, c: int, moving: np.ndarray, turn: np.ndarray) -> None:
    """The ``moving`` vertices turned about vertex ``c`` by their ``turn`` (radians), in place."""
    d = x[moving, :2] - x[c, :2]
    cos, sin = np.cos(turn), np.sin(turn)
    x[moving, 0] = x[c, 0] + cos * d[:, 0] - sin * d[:, 1]
    x[moving, 1] = x[c, 1] + sin * d[:, 0] + cos * d[:, 1]


def held_vertices(fixed: np.ndarray, boundary: np.ndarray, constraints) -> np.ndarray:
    """The vertices whose place :func:`even_fans` keeps: fixed, on the boundary or sliding on a polyline.

    >>> c = SlideConstraint(np.array([2]), np.zeros((2, 2)))
    >>> held_vertices(np.array([1, 0, 0, 0], bool), np.array([0, 1, 0, 0], bool), [c]).tolist()
    [True, True, True, False]
    """
    held = np.asarray(fixed, dtype=bool) | np.asarray(boundary, dtype=bool)
    for c in constraints:
        held[np.asarray(c.vertices, dtype=np.int64)] = True
    return held


def point_loads(feature: np.ndarray, boundary: np.ndarray, extremity: np.ndarray) -> np.ndarray:
    """The inner point features (§4.1: point loads, columns) among the mesh's vertices: point features
    neither on the boundary nor a curve's free end, whose fans :func:`even_fans` keeps radial below
    the floor (its ``radial``).

    >>> f, b, e = np.array([1, 1, 1, 0], bool), np.array([0, 1, 0, 0], bool), np.array([0, 0, 1, 0], bool)
    >>> point_loads(f, b, e).tolist()
    [True, False, False, False]
    """
    return np.asarray(feature, dtype=bool) & ~np.asarray(boundary, dtype=bool) & ~np.asarray(extremity, dtype=bool)
