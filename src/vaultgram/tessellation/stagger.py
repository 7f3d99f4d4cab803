"""The staggered bond (paper §5, Figure 11a): which edges of the thrust network stop being joints.

"A staggered pattern along the unsupported boundaries can be achieved by removing every second edge
in a preferential direction of the mesh [...]. The closest boundary serves as this locally
preferential direction." (§5) The bond is laid in four steps:

1. **Preferential directions.** At every edge, the direction of the closest unsupported boundary
   edge (of the closest boundary edge if every boundary bears thrust).
2. **Courses.** A strip of quads (:mod:`vaultgram.tessellation.strips`) whose rungs run along the
   preferential direction is a *course*: its rungs are joints parallel to the force flow along the
   free edges, which a bond may stagger, while the other strips' rungs, joints across that flow, stay
   continuous. Every quad should lie on exactly one course (then it joins one voussoir): strips start
   as courses when their rungs make less than 45 degrees with the preferential direction on average,
   and a local search then turns strips into courses or back where that puts more quads on exactly
   one course (:func:`choose_courses`, a max-cut of the strips' crossings weighed with the
   alignment).
3. **Joints along each course.** Each course is cut into voussoirs of consecutive quads, by
   keeping some of its rungs: about ``rhythm`` quads each (every second or every fourth rung on a
   mesh of even faces), more where the faces are small and fewer where they are large, so that
   voussoirs have about ``rhythm`` times the median face's area -- "shape and size uniformity
   between the voussoirs is preferred" (§5). A kept rung must not meet a kept rung of a course laid
   before at the same vertex: that would be a point of four voussoirs, joints in line instead of
   staggered. The cut of each course is the cheapest by dynamic programming over its rungs
   (:func:`course_joints`), where a kept rung also costs its angle to the force flow across it
   (force-aware: of two cuts of about the same sizes, the one whose joints cross the thrust
   network's flow squarely); courses are laid one after the other, each next to one already laid,
   so that the alternation runs consistently from course to course -- a two-colouring of the strips
   for rhythm 2 on an even mesh. Where no staggered choice exists the joints line up; they are
   counted.
4. **One voussoir per quad.** A quad that a course crossing it has already joined to a voussoir
   ends the runs of the next course there; those rungs are kept and counted.

Concavities are checked afterwards, on the voussoirs (:mod:`vaultgram.tessellation.voussoirs`).
"""

from __future__ import annotations

import operator
from array import array
from collections import deque
from dataclasses import dataclass

import numpy as np

from vaultgram.geometry.arrays import distinct, nearest, plan_rows, row_dot, steady, unit_rows
from vaultgram.geometry.halfedges import MeshEdges
from vaultgram.tessellation.metrics import force_angles
from vaultgram.tessellation.strips import Strip, strip_directions

__all__ = ["Bond", "staggered_bond", "preferential_directions", "quad_directions", "course_runs", "course_joints",
           "cheapest_cut", "size_costs"]

#: A strip starts as a course when its rungs make at most 45 degrees with the preferential direction.
COURSE_ALIGNMENT = float(np.cos(np.radians(45.0)))
#: A quad whose two pairs of sides are within this (in mean |cos| with the preferential direction) of
#: each other follows its neighbours' courses, over this many rounds.
AMBIGUITY = 0.25
SMOOTHING = 3
#: Cost of a kept rung meeting a kept rung of a neighbouring course (a point of four voussoirs), in
#: units of the size cost ``log(area / target) ** 2`` of one voussoir.
ALIGNED_COST = 2.0
#: Cost of a voussoir of one quad in a course (its two joints leave the neighbours no staggered choice).
SINGLE_COST = 2.0
#: Cost of keeping a rung at right angles to the force flow (scaled by its angle to it, over 90 deg,
#: less the course's mean: see :func:`_skew_costs`).
SKEW_COST = 6.0


@dataclass(frozen=True)
class Bond:
    """The rungs the bond removes, and what it could not do.

    Attributes
    ----------
    removed : ndarray (m,) bool
        Per edge of the mesh: no longer a joint.
    courses : int
        Strips laid as courses.
    kept_taken : int
        Rungs kept because a quad beside them already belongs to a voussoir of a crossing course.
    aligned : int
        Kept rungs meeting a kept rung of a neighbouring course (joints in line).
    target : float
        The voussoir area aimed at: ``rhythm`` times the median area of the quads.
    """

    removed: np.ndarray
    courses: int
    kept_taken: int
    aligned: int
    target: float


def preferential_directions(x: np.ndarray, me: MeshEdges, supported: np.ndarray, rings=()) -> np.ndarray:
    """Per edge, the unit plan direction of the unsupported boundary edge closest to the edge's
    midpoint (of the closest boundary edge when the whole boundary is supported). The edges
    ``rings`` (the keystones' outlines) count as free edges too: courses ring a keystone as they ring
    an opening."""
    edges = me.edges
    boundary = np.flatnonzero(me.boundary)
    free = boundary[~(supported[edges[boundary, 0]] & supported[edges[boundary, 1]])]
    ref = free if len(free) else boundary
    ref = np.concatenate([ref, np.asarray(rings, dtype=np.int64)])
    a, b = plan_rows(x, edges[ref, 0]), plan_rows(x, edges[ref, 1])
    return unit_rows(b - a)[nearest(0.5 * (a + b), 0.5 * (plan_rows(x, edges[:, 0]) + plan_rows(x, edges[:, 1])))]


def quad_directions(x: np.ndarray, me: MeshEdges, pref: np.ndarray, is_quad: np.ndarray) -> np.ndarray:
    """Per face, the direction of its course (0: sides 0 and 2 are rungs, 1: sides 1 and 3; -1 for a
    face that is not a quad): the pair of opposite sides that runs closer to the preferential
    direction. Where both run about as close (within :data:`AMBIGUITY`), the quad follows the
    majority of its neighbours, :data:`SMOOTHING` times, so courses do not fray along the diagonals
    (only the ambiguous quads' corners vote: the others never flip)."""
    d = plan_rows(x, me.edges[:, 1]) - plan_rows(x, me.edges[:, 0])
    align = np.abs(row_dot(unit_rows(d), pref))
    quad_corner = is_quad[me.corner_face]
    c = np.flatnonzero(quad_corner)
    f, side = me.corner_face[c], me.corner_side[c]
    n = len(is_quad)
    score = np.bincount(2 * f + side % 2, align[me.corner_edge[c]], 2 * n).reshape(n, 2)
    choice = np.where(is_quad, np.argmax(steady(score), axis=1), -1)
    ambiguous = is_quad & (np.abs(score[:, 0] - score[:, 1]) < 2 * AMBIGUITY)
    twin = me.corner_twin[c]
    ok = (twin >= 0) & quad_corner[np.maximum(twin, 0)] & ambiguous[f]
    f, side, twin = f[ok], side[ok] % 2, twin[ok]
    g, other_side = me.corner_face[twin], me.corner_side[twin] % 2
    voters = np.flatnonzero(ambiguous)
    for _ in range(SMOOTHING):
        # the neighbour's course, seen from this quad: the same strip if it runs through the shared side
        seen = np.where(choice[g] == other_side, side, 1 - side)
        votes = np.bincount(2 * f + seen, minlength=2 * n).reshape(n, 2)[voters]
        flip = votes.max(axis=1) > votes.min(axis=1)
        choice[voters[flip]] = np.argmax(votes[flip], axis=1)
    return choice


def course_runs(me: MeshEdges, strips: list[Strip], choice: np.ndarray) -> list[Strip]:
    """The courses: the runs of consecutive quads of each strip whose chosen direction is the strip's."""
    out = []
    for s in strips:
        along = choice[s.quads] == strip_directions(me, s)
        if s.cyclic and along.all():
            out.append(s)
            continue
        edges = np.diff(np.concatenate([[0], along.astype(np.int8), [0]]))
        for i, j in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)):
            out.append(Strip(s.quads[i:j], s.rungs[i:j + 1], False))
    return out


def course_joints(areas: np.ndarray, forced: np.ndarray, aligned: np.ndarray, target: float, longest: int,
                  skew: np.ndarray | None = None) -> np.ndarray:
    """The rungs to keep inside one course, by dynamic programming.

    Parameters
    ----------
    areas : ndarray (k,)
        Areas of the course's quads, in order.
    forced, aligned : ndarray (k + 1,) bool
        Per rung (``0`` and ``k`` are the ends): must be kept; would line up with a kept rung of a
        neighbouring course.
    target : float
        The voussoir area aimed at; a run of quads costs ``log(area / target) ** 2``.
    longest : int
        At most this many quads per voussoir.
    skew : ndarray (k + 1,), optional
        Per rung, the angle (degrees) between it and the force flow across it; a kept rung costs
        :data:`SKEW_COST` times its excess over the course's mean, over 90 (force-aware: keep the
        joints that cross the flow squarely).

    Returns
    -------
    ndarray (k + 1,) bool
        Kept rungs (the ends always).

    Example
    -------
    >>> course_joints(np.ones(6), np.zeros(7, bool), np.zeros(7, bool), 2.0, 4).astype(int).tolist()
    [1, 0, 1, 0, 1, 0, 1]
    """
    k = len(areas)
    penalty = np.where(aligned, ALIGNED_COST, 0.0) + _skew_costs(skew, k)
    return cheapest_cut(size_costs(areas, target, longest), forced, penalty.tolist(), longest)


def cheapest_cut(sizes: list, forced: np.ndarray, penalty: list, longest: int) -> np.ndarray:
    """The dynamic programme of :func:`course_joints`: ``sizes[b][d]`` the size cost of the ``d``
    quads before rung ``b`` (:func:`size_costs`), ``penalty[b]`` the cost of keeping inner rung ``b``;
    a single quad costs :data:`SINGLE_COST` more unless forced rungs hold it on both sides
    (:func:`_cut` on the rows of :func:`_programme_rows`)."""
    sizes = np.asarray(sizes, dtype=float).reshape(len(sizes), -1)
    return _cut(*_programme_rows(sizes), forced, penalty, longest)


def _programme_rows(sizes: np.ndarray) -> tuple[array, np.ndarray]:
    """The size costs as :func:`_cut` reads them: per rung ``b`` the costs of runs of ``1 .. longest``
    quads before it, the single quad's with :data:`SINGLE_COST` added (as the programme adds it, so
    the same sums), rung after rung in one flat array of doubles (its values become Python floats
    only as the programme reads them: 1.6 million lists of the rows, held by the 5,000 courses of a
    10^6-face bond, took 1.6 s to make, most of it the garbage collector going through them); and the
    single quad's own cost, for a quad held alone."""
    rows = sizes[:, 1:].copy()
    rows[:, 0] += SINGLE_COST
    return array("d", rows.tobytes()), sizes[:, 1].copy()


def _cut(rows: array, singles: np.ndarray, forced: np.ndarray, penalty: list, longest: int) -> np.ndarray:
    """The programme of :func:`cheapest_cut` on :func:`_programme_rows`, forced rung to forced rung:
    a run cannot pass a forced rung, so each stretch starts from the best cost of its first rung
    alone in the window, and a single quad costs :data:`SINGLE_COST` more (its rows hold that
    already) except alone between two forced rungs. The best costs a run may start from are kept
    nearest first in the window, so each rung's choices are one ``map`` over it; no per-rung checks
    of forced rungs or of the end are left in the loop, only the choice and the next best cost are
    kept: the same sums in the same order as rung by rung, a third less time."""
    k = len(forced) - 1
    ends = [0, *(np.flatnonzero(forced[1:k]) + 1).tolist(), k]  # the stretches' ends
    steps = [0]  # per rung, the cheapest run's length less one (the shortest of the cheapest)
    append = steps.append
    best = 0.0
    for f, g in zip(ends[:-1], ends[1:]):
        if g == f + 1 and forced[f] and forced[g]:  # a quad held alone by forced rungs
            append(0)
            best = best + float(singles[g]) + penalty[g]
            continue
        window = deque([best], maxlen=longest)
        appendleft = window.appendleft
        stretch = iter(rows[(f + 1) * longest:(g + 1) * longest])
        for row, pen in zip(zip(*[stretch] * longest), penalty[f + 1:g + 1]):  # the stretch's rows, in turn
            cost = [*map(operator.add, window, row)]
            here = min(cost)
            append(cost.index(here))
            appendleft(here + pen)
        best = window[0]
    keep = np.zeros(k + 1, dtype=bool)
    b = k
    while b > 0:
        keep[b] = True
        b -= 1 + steps[b]
    keep[0] = True
    return keep


def _skew_costs(skew: np.ndarray | None, k: int) -> np.ndarray | float:
    """Per rung of a course of ``k`` quads, :data:`SKEW_COST` times its angle to the force flow over
    90 degrees, less the course's mean over its inner rungs: the rungs that cross the flow more
    squarely are kept, without favouring fewer or more rungs where every angle is the same."""
    if skew is None or k < 2:
        return 0.0
    return SKEW_COST * (skew - skew[1:k].mean()) / 90.0


def size_costs(areas: np.ndarray, target: float, longest: int) -> list:
    """``cost[b][d]``: the size cost ``log(area / target) ** 2`` of a voussoir of the ``d`` quads
    before rung ``b`` of a course with quad areas ``areas`` (plain floats, for the programme)."""
    return _size_matrix(areas, target, longest).tolist()


def _size_matrix(areas: np.ndarray, target: float, longest: int) -> np.ndarray:
    """:func:`size_costs` as an array ``(k + 1, longest + 1)``."""
    k = len(areas)
    prefix = np.concatenate([[0.0], np.cumsum(areas)])
    b = np.arange(k + 1)[:, None]
    d = np.arange(longest + 1)[None, :]
    a = np.maximum(b - d, 0)
    with np.errstate(divide="ignore"):
        return (np.log(np.maximum(prefix[b] - prefix[a], 1e-300)) - np.log(target)) ** 2


def _course_order(strips: list[Strip], me: MeshEdges) -> list[int]:
    """Courses in the order they are laid: the longest first, then always one beside a laid one."""
    n = len(strips)
    owner = np.full(len(me.face_start) - 1, -1, dtype=np.int64)
    for k, s in enumerate(strips):
        owner[s.quads] = k  # a quad on two courses: either will do for adjacency
    a, b = owner[me.faces_of[~me.boundary]].T
    ok = (a >= 0) & (b >= 0) & (a != b)
    rank = np.lexsort((np.arange(n), -np.array([len(s) for s in strips], dtype=np.int64)))  # longest first
    position = np.empty(n, dtype=np.int64)
    position[rank] = np.arange(n)
    pairs = distinct(np.concatenate([position[a[ok]] * n + position[b[ok]], position[b[ok]] * n + position[a[ok]]]))
    start = np.searchsorted(pairs // n, np.arange(n + 1)).tolist()
    beside = rank[pairs % n].tolist()  # by position of the course, its neighbours longest first
    position = position.tolist()
    order, placed = [], np.zeros(n, dtype=bool)
    for seed in rank.tolist():
        if placed[seed]:
            continue
        queue = deque([seed])
        placed[seed] = True
        while queue:
            k = queue.popleft()
            order.append(k)
            for o in beside[start[position[k]]:start[position[k] + 1]]:
                if not placed[o]:
                    placed[o] = True
                    queue.append(o)
    return order


@dataclass(frozen=True)
class _Course:
    """What laying a course needs that never changes: its quads, the two ends of each rung, its inner
    rungs, the size costs of its runs (:func:`size_costs` as :func:`_programme_rows`) and its rungs'
    skew costs."""

    quads: np.ndarray
    a: np.ndarray
    b: np.ndarray
    inner: np.ndarray
    rows: array
    singles: np.ndarray
    skews: np.ndarray


class _Laying:
    """The bond being laid: who owns each quad, how many kept rungs meet at each vertex, what is removed.

    A course can be taken up again (:meth:`lift`) and laid anew with all its neighbours known
    (:meth:`lay`), which is how the sweeps after the first laying settle the joints."""

    def __init__(self, me: MeshEdges, strips: list[Strip], areas: np.ndarray, joined: np.ndarray,
                 target: float, longest: int, skew: np.ndarray):
        self.courses = [_Course(s.quads, me.edges[s.rungs, 0], me.edges[s.rungs, 1], s.rungs[1:-1],
                                *_programme_rows(_size_matrix(areas[s.quads], target, longest)),
                                _skew_costs(skew[s.rungs], len(s)) + np.zeros(len(s.rungs))) for s in strips]
        self.longest = longest
        self.removed = joined.copy()
        self.owner = np.full(len(areas), -1, dtype=np.int64)
        self.owner[me.faces_of[joined].ravel()] = len(strips)  # joined before the bond: nobody's course
        self.joints = np.zeros(int(me.edges.max()) + 1 if len(me.edges) else 0, dtype=np.int64)
        self.kept: dict[int, np.ndarray] = {}
        self.inputs: dict[int, tuple] = {}  # per course, what it was last laid with, and its cut

    def lift(self, k: int) -> None:
        """Take course ``k`` up: its joints, its removed rungs and its quads are free again."""
        c, keep = self.courses[k], self.kept.pop(k)
        np.subtract.at(self.joints, c.a[keep], 1)
        np.subtract.at(self.joints, c.b[keep], 1)
        self.removed[c.inner[~keep[1:-1]]] = False  # an inner rung is this course's alone
        self.owner[c.quads[self.owner[c.quads] == k]] = -1

    def lay(self, k: int) -> tuple[int, int]:
        """Lay course ``k`` (:func:`course_joints`); returns rungs kept because a quad was taken, and
        kept rungs lined up with a neighbour's."""
        c = self.courses[k]
        lined_up = (self.joints[c.a] > 0) | (self.joints[c.b] > 0)
        owner = self.owner[c.quads]
        taken = (owner >= 0) & (owner != k)
        forced = np.ones(len(c.a), dtype=bool)
        forced[1:-1] = taken[1:] | taken[:-1]
        seen, last = forced.tobytes() + lined_up.tobytes(), self.inputs.get(k)
        if last is not None and last[0] == seen:
            keep = last[1]  # nothing around the course changed since it was last laid
        else:
            penalty = (np.where(lined_up, ALIGNED_COST, 0.0) + c.skews).tolist()
            keep = _cut(c.rows, c.singles, forced, penalty, self.longest)
            self.inputs[k] = (seen, keep)
        self.removed[c.inner[~keep[1:-1]]] = True
        runs = np.cumsum(keep[:-1])  # quads between kept rungs form a voussoir
        self.owner[c.quads[np.bincount(runs)[runs] > 1]] = k
        np.add.at(self.joints, c.a[keep], 1)
        np.add.at(self.joints, c.b[keep], 1)
        self.kept[k] = keep
        kept, held = keep[1:-1], forced[1:-1]
        return int(np.count_nonzero(kept & held)), int(np.count_nonzero(kept & lined_up[1:-1] & ~held))


def _rung_skews(x: np.ndarray, me: MeshEdges, courses: list[Strip], normals: np.ndarray | None) -> np.ndarray:
    """Per edge, the angle (degrees) between it and the force flow across it, measured from the faces'
    unit ``normals`` (:func:`~vaultgram.tessellation.metrics.force_angles`) at the inner edges that
    are rungs of ``courses``, the only ones the bond weighs (half the inner edges: half the time of
    measuring them all); 0 elsewhere, and everywhere without ``normals``."""
    skew = np.zeros(me.n_edges)
    if normals is None or not courses:
        return skew
    rungs = np.concatenate([s.rungs for s in courses])
    rungs = distinct(rungs[~me.boundary[rungs]])
    skew[rungs] = force_angles(x, me, normals, rungs)
    return skew


#: A voussoir of a course is at most this many times ``rhythm`` quads long (small faces make longer ones).
LONGEST = 4

#: Sweeps over the courses after the first laying, each course laid again beside all its neighbours.
SWEEPS = 1


def staggered_bond(x: np.ndarray, me: MeshEdges, strips: list[Strip], supported: np.ndarray, areas: np.ndarray,
                   rhythm: int = 2, joined: np.ndarray | None = None, rings=(), normals: np.ndarray | None = None
                   ) -> Bond:
    """The rungs a staggered bond of about ``rhythm`` quads per voussoir removes (module docstring),
    besides the edges ``joined`` already (whose faces no course takes again); ``rings`` are the
    keystones' outline edges (see :func:`preferential_directions`), ``normals`` the faces' unit
    normals, from which the force flow across the rungs is measured (:func:`_rung_skews`; without
    them no rung is cheaper to keep for its angle)."""
    pref = preferential_directions(x, me, supported, rings)
    is_quad = np.diff(me.face_start) == 4
    strips = course_runs(me, strips, quad_directions(x, me, pref, is_quad))
    quads = np.concatenate([s.quads for s in strips]) if strips else np.zeros(0, dtype=np.int64)
    target = rhythm * float(np.median(areas[quads])) if len(quads) else 1.0
    joined = np.zeros(me.n_edges, dtype=bool) if joined is None else joined
    skew = _rung_skews(x, me, strips, normals)
    laying = _Laying(me, strips, areas, joined, target, LONGEST * rhythm, skew)
    order = _course_order(strips, me)
    counts = [laying.lay(k) for k in order]
    for _ in range(SWEEPS):
        counts = []
        for k in order:
            laying.lift(k)
            counts.append(laying.lay(k))
    kept_taken, aligned = (sum(c[i] for c in counts) for i in (0, 1))  # what the last sweep could not do
    return Bond(laying.removed, len(strips), kept_taken, aligned, target)
