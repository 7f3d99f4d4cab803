"""The pipeline's first part, the plan to the quad mesh (§3): topology finding (:func:`decompose`: discretise,
triangulate, skeletonise, rewrite with the rules, patch) and geometry (:func:`mesh_decomposition`: edge groups,
Coons patches, welding, smoothing); :func:`mesh_domain` runs both.

It is a module of its own so that what needs only a mesh (``vaultgram mesh``, ``decompose``, the exploration)
imports neither form finding nor tessellation (issue 18); :mod:`vaultgram.pipeline` chains it with them and
names these functions too. As there, ``timings`` (a dict) gets the seconds of every stage.

Example
-------
>>> from vaultgram.domain import load_domain
>>> mesh = mesh_domain(load_domain("examples/quad_with_hole.json"))
>>> mesh.info["patches"], len(mesh.faces) > 500
(12, True)
"""

from __future__ import annotations

import dataclasses
from functools import partial
from pathlib import Path
from typing import NamedTuple

import numpy as np

from vaultgram import progress
from vaultgram.domain import Domain, check_feature_spacing
from vaultgram.domain.layouts import check_feature_layout
from vaultgram.engine.strategy import first_option
from vaultgram.errors import VaultgramError
from vaultgram.geometry.text import plan_frame
from vaultgram.limits import MAX_FACES, SPACING_RANGE
from vaultgram.meshing.densities import CHORD_TOLERANCE, TARGET_FRACTION, DensitySpec, group_counts
from vaultgram.meshing.fans import FAN_FLOOR, even_fans, held_vertices, point_loads, poles_to_retry, poles_to_widen
from vaultgram.meshing.fidelity import SAME_POINT, hold_boundary, on_points, place_on_points
from vaultgram.meshing.layout import Layout, edge_groups, kept_points
from vaultgram.meshing.optimise import maximise_min_quality
from vaultgram.meshing.orthogonalise import orthogonalise
from vaultgram.meshing.polish import POLISH_TARGET, polish_worst
from vaultgram.meshing.quadmesh import QuadMesh
from vaultgram.meshing.quality import check_not_folded, face_scaled_jacobians
from vaultgram.meshing.smoothing import DEFAULT_ITERATIONS, KINK_REACH, kink_offsets, laplacian_smooth
from vaultgram.meshing.splits import boundary_pole_splits, split_patterns, thinnest_fan
from vaultgram.meshing.untangle import improve_shapes, untangle
from vaultgram.meshing.weld import weld
from vaultgram.topology.decomposition import Decomposition, block_decomposition
from vaultgram.topology.discretise import discretise
from vaultgram.topology.recovery import triangulate_recovering
from vaultgram.topology.rulebook import load_vault_rulebook
from vaultgram.topology.skeleton import Skeleton, skeleton

__all__ = ["decompose", "plan_skeleton", "mesh_decomposition", "mesh_or_advise", "mesh_domain", "domain_frame"]

#: Smoothing passes with more refused poles evened (:func:`_fans_evened_and_smoothed`), each while the
#: worst face moved to another one's fan.
MAX_RETRIES = 3
#: A patch corner wider than this many degrees turns past straight: a quad mesh of the patch folds there
#: at any density (:func:`vaultgram.meshing.quality.check_not_folded` names it), so chamfers whose
#: smoothing makes a layout with a corner that wide stay corners (:func:`_settled_skeleton`). A degree
#: above 180: a corner on a straight stretch, 180 degrees up to the sampling (180.1 where a cut
#: rectangle's chord meets its side), meshes well.
LAYOUT_TURN_LIMIT = 181.0
#: Chamfers stay corners where their layout's thinnest fan is below the floor and below this fraction
#: of the corner layout's (:func:`_settled_skeleton`): 5 percent spares near ties (draws 216 and 217 of
#: 700 random plans, fans of 0.079 against 0.082: min scaled Jacobian 0.090 -> 0.082, 2 boundary
#: singularities fewer).
FAN_MARGIN = 0.95
#: A run of 135 to 150 degree corners stays corners where smoothing it leaves a patch side whose net
#: turning between its corners exceeds this many degrees and the widest of the layout before it
#: (:func:`_soft_runs_settled`): the side bulges or curls, and the patch's Coons map skews its quads
#: (the Armadillo's rounded foot: one patch with a side turning by 101 degrees where the corners made
#: five, min scaled Jacobian 0.589 -> 0.508; multiple_lobes: a side round two lobes turning by 259,
#: 0.395 -> 0.010). A quarter disc's arc turns by 90 and meshes well.
SIDE_TURN_LIMIT = 90.0
#: Rounds of untangling, shape improvement and the max-min optimisation again, each from the last one's
#: optimised mesh, while it keeps inverted faces and the round raised its worst face
#: (:func:`_untangled_again`), where a mesh folds with and without the three-quad splits.
UNTANGLE_ROUNDS = 4
#: The rounds' mesh is taken only where its worst face reaches this; below it the fold stands, with its
#: advice (:func:`mesh_or_advise`): tests/folding.py's crescent fans untangle to 0.0008 and 0.014, a layout
#: that has no usable mesh at that spacing, while hiroshi_senju_museum at 16,000 faces with its hole side
#: sampled by arc length reaches 0.093. It was untangling's own aim
#: (:data:`~vaultgram.meshing.untangle.UNTANGLE_TARGET`, 0.1) while hiroshi reached 0.114, with sides collapsed
#: beside the fold (3e-7 and 0.0005 of the median edge) that the max-min optimisation no longer makes
#: (:data:`~vaultgram.meshing.optimise.SIDE_SHARE`). Since that side is sampled by its offset length
#: (:data:`~vaultgram.meshing.weld.WRAP_FLOOR`) hiroshi does not fold at all (0.50 from 4x to 82,000 faces).
UNTANGLED_FLOOR = 0.08


# --------------------------------------------------------------------------------------------
# Topology (§3.1, §4)
# --------------------------------------------------------------------------------------------


def decompose(domain: Domain, spacing: float = 0.02, rules_dir: str | Path | None = None, smooth: bool = False,
              timings: dict | None = None, check_invariants: bool = False, trace: bool = False,
              chooser=None) -> Decomposition:
    """Topology finding (§3.1, §4): discretise, triangulate, skeletonise, rewrite with the rules, patch.

    ``rules_dir`` holds the rulebook (default: the one shipped with vaultgram); ``smooth`` smooths the
    skeleton branches with splines; ``check_invariants`` checks the rulebook's invariants while its
    strategies run (as ``vaultgram rules test`` does); ``trace`` keeps the graph the rules start from
    for a replay (``Decomposition.start_graph``); ``chooser`` resolves the rulebook's ``choose`` steps
    (default: the first option; exploration replays a variant's choices). The plan's chamfers are
    smooth boundary points unless their layout would turn past straight at a patch corner or keep a
    thinner fan, and so are its other 135 to 150 degree corners, run by run, where their layout is no
    worse either and bends no patch side further (:func:`_settled_skeleton`).
    """
    with domain_frame(domain):
        check_feature_layout(domain)
        rulebook = load_vault_rulebook(rules_dir)

        def rewrite(sk: Skeleton, how) -> Decomposition:
            with progress.timed(timings, "rules"):
                return block_decomposition(sk, rulebook, check_invariants, trace, how)

        sk, default = _settled_skeleton(domain, spacing, smooth, timings, rewrite)
        return default if chooser is None and default is not None else rewrite(sk, chooser or first_option)


def plan_skeleton(domain: Domain, spacing: float = 0.02, rules_dir: str | Path | None = None) -> Skeleton:
    """The skeleton :func:`decompose` rewrites (chamfers smoothed or kept, :func:`_settled_skeleton`), for
    a search of the rules' choices (the exploration) that :func:`decompose` then replays."""
    with domain_frame(domain):
        rulebook = load_vault_rulebook(rules_dir)
        return _settled_skeleton(domain, spacing, False, None,
                                 lambda sk, how: block_decomposition(sk, rulebook, chooser=how))[0]


def _settled_skeleton(domain: Domain, spacing: float, smooth: bool, timings: dict | None, rewrite
                      ) -> tuple[Skeleton, Decomposition | None]:
    """The skeleton of the plan with its chamfers as smooth points (issue 12,
    :func:`vaultgram.topology.discretise.discretise`) and the rules' default layout of it (``rewrite``
    with the first option of every choice; None for a plan without chamfers or other 135 to 150
    degree corners: nothing to decide).

    The skeleton and layout with the chamfers as corners instead where the smoothed layout is worse
    than theirs in either of two ways, both read off the layouts (no mesh is made):

    * a patch corner wider than :data:`LAYOUT_TURN_LIMIT` degrees, and wider than any of theirs: the
      smoothed corners changed the skeleton, and with it the patching elsewhere (at a hole's or a
      curve's corner, mostly), leaving a patch that turns past 180 degrees at a corner, where its
      quads fold (1924157 on 700 random plans: 11 folds);
    * a fan below :data:`~vaultgram.meshing.fans.FAN_FLOOR` thinner than :data:`FAN_MARGIN` times
      their thinnest (:func:`_thinnest_fan`), which the mesh keeps: e.g. a triangle patch whose pole,
      a point feature on the boundary, now faces a long side (draw 33 of the 700: min scaled
      Jacobian 0.40 with corners, 0.034 smoothed; on the 700, 55 plans so kept corners, 44 of which
      were worse by more than 0.01 smoothed, benchmarks/README.md).

    Then the other runs of 135 to 150 degree corners, one by one (:func:`_soft_runs_settled`).

    The decision takes the default choices, so that an exploration's variants (:func:`plan_skeleton`)
    and their replays see one skeleton."""
    sk = _skeleton(domain, spacing, smooth, timings, chamfers=True)
    settled = None
    if len(sk.triangulation.disc.smoothed):
        settled = _measured(rewrite(sk, first_option))
        if _worse(settled, None):
            plain = _skeleton(domain, spacing, smooth, timings, chamfers=False)
            plain_default = _measured(rewrite(plain, first_option))
            if _worse(settled, plain_default):
                sk, settled = plain, plain_default
    chamfers = sk.triangulation.disc.chamfers
    sk, settled = _soft_runs_settled(sk, settled, rewrite,
                                     lambda at: _skeleton(domain, spacing, smooth, timings, chamfers, at))
    return sk, settled and settled.dec


class _Measured(NamedTuple):
    """A layout with its widest patch corner and thinnest fan (:func:`_worse` compares them)."""

    dec: Decomposition
    wide: float
    thin: float
    bent: float


def _measured(dec: Decomposition) -> _Measured:
    """``dec`` with its widest patch corner, thinnest fan and most bent patch side."""
    return _Measured(dec, widest_corner(dec), _thinnest_fan(dec), _bent(dec))


def _bent(dec: Decomposition) -> float:
    """The largest net turning (degrees, either way) of a patch side of ``dec`` between its corners."""
    return max(float(np.abs(patch.side_turnings()).max()) for patch in dec.patches)


def _worse(layout: _Measured, than: _Measured | None) -> bool:
    """Whether ``layout`` has a patch corner wider than :data:`LAYOUT_TURN_LIMIT` and than
    ``than``'s widest, or a fan below the floor thinner than :data:`FAN_MARGIN` times ``than``'s
    thinnest (with ``than`` None: outside the limits alone)."""
    wide, thin = (LAYOUT_TURN_LIMIT, FAN_FLOOR) if than is None else (than.wide, FAN_MARGIN * than.thin)
    return layout.wide > max(LAYOUT_TURN_LIMIT, wide) or layout.thin < min(FAN_FLOOR, thin)


def _soft_runs_settled(sk: Skeleton, settled: _Measured | None, rewrite, skeleton_at
                       ) -> tuple[Skeleton, _Measured | None]:
    """The skeleton and default layout with the plan's other runs of 135 to 150 degree corners
    (:attr:`~vaultgram.topology.discretise.Discretisation.soft_runs` not smoothed yet: runs between
    softer bends, reflex corners or alike corners, and chamfers kept as corners) smooth points too
    where each, tried one by one in ring order, gives a layout no worse (:func:`_worse`) than the one
    before it (issue 12: 1 + max(1, round(theta / 90)) faces at a corner of theta degrees, two at 135
    to 150), and no patch side turns by more than :data:`SIDE_TURN_LIMIT` degrees unless one of the
    layout before did as much; a run refused as a whole is tried corner by corner. ``skeleton_at(points)``
    is the plan's skeleton with the soft corners at ``points`` smooth. A run whose trial the rules or the
    triangulation refuse stays corners."""
    disc = sk.triangulation.disc
    done = set(disc.smoothed.tolist())
    runs = [run for run in disc.soft_runs if not done.issuperset(run.tolist())]
    if not runs:
        return sk, settled
    settled = settled or _measured(rewrite(sk, first_option))
    for run in runs:  # a run as a whole, and where that is refused its corners one by one
        for part in [run] + ([run[k:k + 1] for k in range(len(run))] if len(run) > 1 else []):
            sk, settled, taken = _tried(sk, settled, disc.points[part], rewrite, skeleton_at)
            if taken and part is run:
                break
    return sk, settled


def _tried(sk: Skeleton, settled: _Measured, points: np.ndarray, rewrite, skeleton_at
           ) -> tuple[Skeleton, _Measured, bool]:
    """The skeleton and layout with the soft corners at ``points`` smooth too and True, if that layout
    is no worse than ``settled`` (:func:`_worse`, :data:`SIDE_TURN_LIMIT`); else ``sk``, ``settled``
    and False (also where the rules or the triangulation refuse it)."""
    try:
        trial_sk = skeleton_at(np.concatenate([sk.triangulation.disc.smooth_at, points]))
        trial = _measured(rewrite(trial_sk, first_option))
    except VaultgramError:
        return sk, settled, False
    if _worse(trial, settled) or trial.bent > max(SIDE_TURN_LIMIT, settled.bent):
        return sk, settled, False
    return trial_sk, trial, True


def _thinnest_fan(dec: Decomposition) -> float:
    """:func:`~vaultgram.meshing.splits.thinnest_fan` of ``dec`` at the default counts (a mesh asked at
    other densities may differ); 0 for a layout the mesher refuses (its patches overlap)."""
    try:
        layout = edge_groups(dec)
        return thinnest_fan(layout, group_counts(layout))
    except VaultgramError:
        return 0.0


def widest_corner(dec: Decomposition) -> float:
    """The widest interior angle (degrees) at a corner of any patch of ``dec``."""
    return max(float(patch.corner_angles().max()) for patch in dec.patches)


def _skeleton(domain: Domain, spacing: float, smooth: bool, timings: dict | None, chamfers: bool,
              smooth_at=()) -> Skeleton:
    """Discretise, triangulate and skeletonise the plan (§3.1), chamfers smooth or not, and the 135 to
    150 degree corners at ``smooth_at`` smooth."""
    with progress.timed(timings, "discretise"):
        disc = discretise(domain, spacing, chamfers=chamfers, smooth_at=smooth_at)
    with progress.timed(timings, "triangulate"):
        tri = triangulate_recovering(disc)
    with progress.timed(timings, "skeleton"):
        return skeleton(tri, smooth=smooth)


def domain_frame(domain: Domain):
    """Messages of the stages name places in the plan's coordinates, also for a plan worked on in its
    local frame (:mod:`vaultgram.geometry.frames`)."""
    return plan_frame(domain.origin, domain.diagonal)


# --------------------------------------------------------------------------------------------
# Geometry (§3.2)
# --------------------------------------------------------------------------------------------


def mesh_decomposition(dec: Decomposition, target_length: float | None = None, smooth: int = DEFAULT_ITERATIONS,
                       densities: DensitySpec | None = None, allow_folds: bool = False,
                       timings: dict | None = None, max_faces: int = MAX_FACES) -> QuadMesh:
    """Geometry of §3.2 for a decomposition: edge groups, densities, Coons patches, welding, smoothing
    (and, on a mesh below issue 12's mean scaled Jacobian, :func:`~vaultgram.meshing.orthogonalise.orthogonalise`).

    A smoothed mesh with inverted faces raises :class:`~vaultgram.errors.MeshFoldError` unless
    ``allow_folds``; the raw Coons patches (``smooth=0``) are returned as they are. Densities that ask
    for more than ``max_faces`` faces are refused before any is made (:mod:`vaultgram.meshing.guards`).
    """
    if smooth < 0:
        raise VaultgramError(f"smoothing iterations must be >= 0, got {smooth}")
    with domain_frame(dec.disc.domain):
        return _meshed(dec, target_length, smooth, densities, allow_folds, timings, max_faces)


def _point_loads(mesh: QuadMesh) -> np.ndarray:
    """The point features whose rings :func:`~vaultgram.meshing.polish.polish_worst` holds still: the inner
    ones (§4.1: a point load or a column, whose fans' spokes carry its radial force flow), not those on the
    boundary. Round a boundary point feature (§4.1: the concentrated thrust at a corner of the shell) the
    fans come out of Coons interpolation with unequal apex angles, and held still they were the worst face
    of 63 of the 90 saved random plans under the floor (session 30). Freed in the polish (which runs only on
    meshes under the floor): 90 -> 64 plans under 0.3 and 7 -> 0 under 0.1; the voussoir joints' median
    angle to the force flow is unchanged on average over 7 such plans (8.1 -> 8.0 degrees), up on 2 and down
    on 1 (benchmarks/README.md, session 30)."""
    return np.asarray(mesh.feature, dtype=bool) & ~np.asarray(mesh.boundary, dtype=bool)


def _meshed(dec: Decomposition, target_length, smooth: int, densities, allow_folds: bool, timings,
            max_faces: int) -> QuadMesh:
    """The stages of :func:`mesh_decomposition`; the mesh in the decomposition's frame."""
    with progress.timed(timings, "groups"):
        layout = edge_groups(dec)
        counts = group_counts(layout, densities, target_length, max_faces)
    mesh, x = _welded_and_smoothed(layout, counts, smooth, timings)
    quality = face_scaled_jacobians(x, mesh.faces) if smooth > 0 else None
    split = True
    if quality is not None and quality.min() <= 0:
        # issue 12: where the three-quad splits of thin fans (or the counts they need) fold, Figure 3's fans
        plain = group_counts(layout, densities, target_length, max_faces, split=False)
        if split_patterns(layout, counts) or not np.array_equal(plain, counts):
            counts = plain
            mesh, x, split = _fans_back(layout, counts, smooth, timings)
            quality = face_scaled_jacobians(x, mesh.faces)
    if quality is not None and quality.min() <= 0:  # issue 12 What 4: untangling on until it reaches
        again, y = _welded_and_smoothed(layout, counts, smooth, timings, split=split, rounds=True)
        if face_scaled_jacobians(y, again.faces).min() >= UNTANGLED_FLOOR:
            mesh, x = again, y
            quality = face_scaled_jacobians(x, mesh.faces)
    if quality is not None and quality.min() > 0:  # issue 12: the mean scaled Jacobian, the worst face kept
        with progress.timed(timings, "orthogonalise"):
            if quality.min() < POLISH_TARGET:  # issue 12 What 4: the worst corners raised together
                x = polish_worst(x, mesh.faces, mesh.fixed, mesh.constraints, still=_point_loads(mesh))
            x = orthogonalise(x, mesh.faces, mesh.fixed, mesh.constraints, still=mesh.feature)
    mesh = dataclasses.replace(mesh, vertices=x, info=_mesh_info(dec, layout, smooth), origin=dec.origin)
    if quality is not None and not allow_folds:
        check_not_folded(mesh, dec, quality)
    return mesh


def _fans_back(layout: Layout, counts, smooth: int, timings: dict | None
               ) -> tuple[QuadMesh, np.ndarray, bool | frozenset]:
    """The mesh at ``counts`` (Figure 3's, no split raised them) where the three-quad splits folded:
    the fans back, but for the splits at poles a rule marked on the boundary
    (:func:`~vaultgram.meshing.splits.boundary_pole_splits`), as a fan a boundary singularity whatever
    its shape; every split dropped where those fold too (or there are none). Also the splits kept
    (``_welded_and_smoothed``'s ``split``). Saved random plan 511 of the 700: a boundary point
    feature's 6 by 1 split folded, and with it dropped the 136 degree corner that
    ``move_rebranch_to_lone_corner`` made the pole of a triangle got nine faces, not two."""
    kept = boundary_pole_splits(layout, counts)
    if kept:
        mesh, x = _welded_and_smoothed(layout, counts, smooth, timings, split=kept)
        if face_scaled_jacobians(x, mesh.faces).min() > 0:
            return mesh, x, kept
    mesh, x = _welded_and_smoothed(layout, counts, smooth, timings, split=False)
    return mesh, x, False


def _welded_and_smoothed(layout: Layout, counts, smooth: int, timings: dict | None,
                         split: bool | frozenset = True, rounds: bool = False) -> tuple[QuadMesh, np.ndarray]:
    """The welded mesh (with or without the three-quad splits of :mod:`vaultgram.meshing.splits`) and
    its vertices after smoothing, untangling (with ``rounds``, again while faces stay inverted:
    :func:`_untangled_again`), the max-min optimisation and the boundary's bends put back (§3.2)."""
    with progress.timed(timings, "weld"):
        welded = weld(layout, counts, split)
    mesh, x = _fans_evened_and_smoothed(welded, layout, smooth, timings, rounds=rounds)
    if smooth > 0 and poles_to_widen(x, mesh.faces, welded.pole):  # a fan hemmed in by quads bounds it
        mesh, x = _better(mesh, x, *_fans_evened_and_smoothed(welded, layout, smooth, timings, wide=True,
                                                              rounds=rounds))
    return mesh, x


def _fans_evened_and_smoothed(welded: QuadMesh, layout: Layout, smooth: int, timings: dict | None,
                              wide: bool = False, rounds: bool = False) -> tuple[QuadMesh, np.ndarray]:
    """The ``welded`` mesh smoothed (:func:`_smoothed`), and smoothed again with the poles whose
    evening was refused (or left under the floor) evened regardless where one of them holds the worst
    face (:func:`~vaultgram.meshing.fans.poles_to_retry`), the better of the two; again while the
    better one's worst face moved to another such pole, with it evened too, at most
    :data:`MAX_RETRIES` times. (Saved random plan 290 of 700: one boundary point feature's fan evened,
    the worst face moves to the other's; that evened too, 0.275 -> 0.321. Evening every refused pole
    with a face under the floor at once instead, plan 355 got 0.148 instead of 0.230.)"""
    mesh, x, refused = _smoothed(welded, layout, smooth, timings, wide=wide, rounds=rounds)
    tried: frozenset = frozenset()
    for _ in range(MAX_RETRIES if smooth > 0 else 0):
        retry = tried | poles_to_retry(x, mesh.faces, mesh.face_patch, refused)
        if retry == tried:  # no refused pole holds the worst face, or it was retried already
            break
        tried = retry  # a pole whose evening was refused bounds the mesh: smoothed again with it evened
        mesh, x = _better(mesh, x, *_smoothed(welded, layout, smooth, timings, retry, wide, rounds)[:2])
    return mesh, x


def _better(mesh: QuadMesh, x: np.ndarray, other: QuadMesh, y: np.ndarray) -> tuple[QuadMesh, np.ndarray]:
    """The mesh of the two (same faces, vertices ``x`` and ``y``) whose worst face is better; the
    first where they tie."""
    if face_scaled_jacobians(y, mesh.faces).min() > face_scaled_jacobians(x, mesh.faces).min():
        return other, y
    return mesh, x


def _smoothed(mesh: QuadMesh, layout: Layout, smooth: int, timings: dict | None, regardless=frozenset(),
              wide: bool = False, rounds: bool = False) -> tuple[QuadMesh, np.ndarray, tuple]:
    """The welded ``mesh`` smoothed (§3.2): its fans evened (those round the poles in ``regardless``
    without the check, :func:`~vaultgram.meshing.fans.even_fans`, and again after smoothing,
    :func:`_evened_again`; where ``wide``, with the corners of the quads round each pole in the share),
    Laplacian smoothing, untangling, the
    max-min optimisation (with ``rounds``, untangling and the optimisation again while faces stay
    inverted: :func:`_untangled_again`) and the boundary's bends put back; the mesh with its labels, its
    vertices and the poles whose evening was refused."""
    with progress.timed(timings, "smooth"):
        x, rays, refused = mesh.vertices, (), ()
        if smooth > 0:  # the fans round poles evened, their spokes sliding on rays (§3.2, issue 12)
            held = held_vertices(mesh.fixed, mesh.boundary, mesh.constraints)
            x, rays, refused = even_fans(x, mesh.faces, mesh.face_patch, mesh.pole, held, regardless, wide,
                                         radial=point_loads(mesh.feature, mesh.boundary, mesh.curve_labels()[1]))
        reach = KINK_REACH * TARGET_FRACTION * layout.decomposition.disc.domain.diagonal
        offsets = kink_offsets(x, mesh.faces, mesh.boundary, reach, mesh.fixed | mesh.pole) if smooth > 0 else None
        x = laplacian_smooth(x, mesh.faces, smooth, mesh.fixed, mesh.constraints + rays, offsets=offsets)
        if smooth > 0 and regardless:
            x, rays = _evened_again(x, mesh, held, rays, regardless, wide)
        slides = mesh.constraints + rays
    with progress.timed(timings, "untangle"):
        if smooth > 0:
            x = untangle(x, mesh.faces, mesh.fixed, slides)
            x = improve_shapes(x, mesh.faces, mesh.fixed, slides)
            x = maximise_min_quality(x, mesh.faces, mesh.fixed, slides, still=mesh.feature)
            x = _untangled_again(x, mesh, slides) if rounds else x
            x, mesh = _held_to_the_plan(x, mesh, layout.decomposition.disc)
    return mesh, x, refused


def _untangled_again(x: np.ndarray, mesh: QuadMesh, slides: tuple) -> np.ndarray:
    """Untangling, shape improvement and the max-min optimisation again from the optimised ``x`` while
    it has inverted faces, at most :data:`UNTANGLE_ROUNDS` times and while each round raises the worst
    face (issue 12 What 4: a fold only where no valid mesh exists). Untangling's gradient steps stall
    where inverted faces lie beside faces of almost no area (any step inverts one of those), which the
    optimiser's one-vertex moves open up; from its result untangling goes on. hiroshi_senju_museum at
    16,000 faces asked, its hole side sampled by arc length (as before session 26): 4 inverted faces in
    a sheared quad patch wrapping a hole's 199 degree corner, none after one more round (worst face
    0.093); at 82,000: 9 inverted, none after three rounds but a worst face of 0.0065 (under
    :data:`UNTANGLED_FLOOR`: the fold stands). Run only where the mesh
    folds with and without the splits (:func:`_meshed`): a split that folds falls back to the fans
    first, as before."""
    worst = face_scaled_jacobians(x, mesh.faces).min()
    for _ in range(UNTANGLE_ROUNDS):
        if worst > 0:
            break
        y = untangle(x, mesh.faces, mesh.fixed, slides)
        y = improve_shapes(y, mesh.faces, mesh.fixed, slides)
        y = maximise_min_quality(y, mesh.faces, mesh.fixed, slides, still=mesh.feature)
        now = face_scaled_jacobians(y, mesh.faces).min()
        if now <= worst:
            break
        x, worst = y, now
    return x


def _evened_again(x: np.ndarray, mesh: QuadMesh, held: np.ndarray, rays: tuple, poles, wide: bool = False
                  ) -> tuple[np.ndarray, tuple]:
    """The fans round ``poles`` evened once more after smoothing, and the rays with their spokes' new
    ones: smoothing moves the spokes that stay (a quad's side, a patch's side sliding on the boundary),
    so a run evened between them before smoothing is uneven after it (fig7's curve end (1, 1): 10
    triangles in 165 degrees, the eight between two held spokes at 14.7 degrees, the two at the ends at
    22 and 26; evened again 16.5 each, the mesh's worst face 0.293 -> 0.314, its mean unchanged)."""
    only = np.zeros(len(x), dtype=bool)
    only[list(poles)] = True
    x, again, _ = even_fans(x, mesh.faces, mesh.face_patch, only, held, frozenset(poles), wide,
                            point_loads(mesh.feature, mesh.boundary, mesh.curve_labels()[1]))
    turned = {int(r.vertices[0]) for r in again}
    return x, tuple(r for r in rays if int(r.vertices[0]) not in turned) + again


def _held_to_the_plan(x: np.ndarray, mesh: QuadMesh, disc) -> tuple[np.ndarray, QuadMesh]:
    """The smoothed boundary put back on the plan (§3.2, issue 12 What 5; :mod:`vaultgram.meshing.fidelity`):
    a vertex on each sharp ring vertex the sliding left bare (:func:`_on_sharp_points`; where each
    vertex that could go there folds a face, one goes anyway when the optimisation after it unfolds
    the faces), and the bends that chords cut off put back; the mesh with its labels of the ring points
    following the vertices (``fixed`` the vertices on sharp ring vertices too, ``turning`` the turning
    of the ring point a boundary vertex sits on).

    The second try: multiple_lobes' outline vertex 22 (21.24, 18.62), a 202.5 degree bend that a sliding
    vertex left, has two candidates 0.23 m off, each folding a face there (-0.13, -0.04); placed, the
    optimisation unfolds it (worst face 0.407). Main placed one only because the max-min optimisation
    had collapsed the four strips' ends beside it into one point (the sides under 0.001 of the median
    edge that :data:`vaultgram.meshing.optimise.SIDE_SHARE` now keeps)."""
    tol, eps = CHORD_TOLERANCE * disc.domain.diagonal, SAME_POINT * disc.domain.diagonal
    sharp = disc.points[kept_points(disc) & (disc.ring >= 0)]
    placed, on_sharp = _on_sharp_points(x, mesh, sharp, eps, tol)
    if on_sharp.sum() < len(sharp):
        again, on_again = _on_sharp_points(x, mesh, sharp, eps, tol, folding=True)
        if on_again.sum() > on_sharp.sum() and face_scaled_jacobians(again, mesh.faces).min() > 0:
            placed, on_sharp = again, on_again
    placed = hold_boundary(placed, mesh.faces, mesh.constraints, tol)
    on_ring = disc.ring >= 0
    turning = mesh.turning.copy()
    turning[mesh.boundary] = on_points(placed[mesh.boundary], disc.points[on_ring], disc.turning[on_ring], eps)
    return placed, dataclasses.replace(mesh, fixed=mesh.fixed | on_sharp, turning=turning)


def _on_sharp_points(x: np.ndarray, mesh: QuadMesh, sharp: np.ndarray, eps: float, tol: float,
                     folding: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """A vertex on each of the ``sharp`` ring vertices the sliding left bare (:func:`place_on_points`,
    with ``folding`` even where it folds a face), and where one was placed the boundary held and the
    faces optimised again with those fixed; the vertices, and which of them sit on sharp points."""
    placed, on_sharp = place_on_points(x, mesh.faces, mesh.constraints, sharp, eps, folding)
    if not np.array_equal(placed, x):
        placed = hold_boundary(placed, mesh.faces, mesh.constraints, tol)
        placed = maximise_min_quality(placed, mesh.faces, mesh.fixed | on_sharp, mesh.constraints,
                                      still=mesh.feature, moved=np.flatnonzero(np.any(placed != x, axis=1)))
    return placed, on_sharp


def _mesh_info(dec: Decomposition, layout: Layout, smooth: int) -> dict:
    """What ``mesh.json`` records of how the mesh was made."""
    domain = dec.disc.domain
    return {
        "domain": domain.name,
        "spacing": dec.disc.spacing,
        "diagonal": domain.diagonal,
        "patches": len(layout.patterns),
        "triangle_patches": sum(p.pole is not None for p in layout.patterns),
        "edge_groups": layout.n_groups,
        "smooth": smooth,
    }


def mesh_domain(domain: Domain, spacing: float = 0.02, target_length: float | None = None,
                smooth: int = DEFAULT_ITERATIONS, densities: DensitySpec | None = None, rules_dir=None,
                allow_folds: bool = False, timings: dict | None = None, max_faces: int = MAX_FACES) -> QuadMesh:
    """Topology and geometry of §3: a smooth quad mesh of ``domain``.

    Parameters
    ----------
    domain : Domain
    spacing : float
        Relative discretisation spacing of the decomposition (§3.1).
    target_length : float, optional
        Global target edge length in the domain's units; default a fraction
        (:data:`vaultgram.meshing.densities.TARGET_FRACTION`) of the bounding-box diagonal. Overrides the
        density file's.
    smooth : int
        Laplacian smoothing iterations.
    densities : DensitySpec, optional
        Local density control (:func:`vaultgram.meshing.densities.load_densities`).
    allow_folds : bool
        Return a mesh that still has inverted faces after smoothing instead of raising.
    max_faces : int
        Refuse densities that ask for more faces (:mod:`vaultgram.meshing.guards`).

    Raises
    ------
    VaultgramError
        From any stage (invalid domain, a patch that is not 3- or 4-sided, bad densities, too many faces);
        :class:`~vaultgram.errors.MeshFoldError` when the smoothed mesh has inverted faces (unless
        ``allow_folds``).
    """
    with domain_frame(domain):
        check_feature_spacing(domain, spacing)
    dec = decompose(domain, spacing, rules_dir, timings=timings)
    return mesh_or_advise(dec, rules_dir, target_length, smooth, densities, allow_folds, timings, max_faces)


def mesh_or_advise(dec: Decomposition, rules_dir=None, target_length: float | None = None,
                   smooth: int = DEFAULT_ITERATIONS, densities: DensitySpec | None = None, allow_folds: bool = False,
                   timings: dict | None = None, max_faces: int = MAX_FACES) -> QuadMesh:
    """:func:`mesh_decomposition`, whose fold error, where the fold is not the layout's, says which
    finer mesh unfolds it (issue 12's Acceptance: a clear error naming the narrow place and the
    spacing it needs): half the target length, else half the spacing (the paper's 1% at least), each
    tried only then (:func:`_finer_mesh`)."""
    mesh = mesh_decomposition(dec, target_length, smooth, densities, True, timings, max_faces)
    if not allow_folds and smooth > 0:
        with domain_frame(dec.disc.domain):
            check_not_folded(mesh, dec, remedy=partial(_finer_mesh, dec, rules_dir, target_length, smooth, densities,
                                                       max_faces))
    return mesh


def _finer_mesh(dec: Decomposition, rules_dir, target_length: float | None, smooth: int, densities,
                max_faces: int) -> str:
    """Which of half the target length or half the spacing (not below :data:`SPACING_RANGE`'s least)
    meshes the decomposition's plan without a fold, as advice: on saved random plan 646 (points
    0.03 apart at spacing 0.05) half the spacing does; on plan 78 (a boundary point feature beside a
    curve) neither, and the advice is to move the features."""
    domain, spacing = dec.disc.domain, dec.disc.spacing
    target = target_length or (densities.target_length if densities else None) or TARGET_FRACTION * domain.diagonal
    finer = max(spacing / 2, SPACING_RANGE[0])
    if _unfolded(lambda: mesh_decomposition(dec, target / 2, smooth, densities, True, None, max_faces)):
        return f"mesh with --target-length {target / 2:.3g} or less"
    if finer < spacing and _unfolded(lambda: mesh_decomposition(decompose(domain, finer, rules_dir), target_length,
                                                                smooth, densities, True, None, max_faces)):
        return f"mesh with --spacing {finer:g} or less"
    return (f"neither --target-length {target / 2:.3g} nor --spacing {finer:g} unfolds it: move the features or "
            "curves there apart, or away from the boundary")


def _unfolded(make) -> bool:
    """Whether ``make()`` gives a mesh without an inverted face (False where it fails)."""
    try:
        mesh = make()
    except VaultgramError:
        return False
    return bool(face_scaled_jacobians(mesh.vertices, mesh.faces).min() > 0)
