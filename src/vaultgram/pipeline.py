"""The vault pipeline: the one place that chains the stages of the paper, in order.

Each stage is a function from one plain value to the next::

    Domain -> Discretisation -> Triangulation -> Skeleton -> Decomposition      (topology, §3.1, §4)
           -> Layout -> QuadMesh                                               (geometry, §3.2)
           -> FormDiagram -> ForceDiagram -> ThrustNetwork                     (form finding, §5)

:func:`decompose`, :func:`mesh_decomposition` and :func:`form_find` run one part each; :func:`design`
runs them all. The first two, and :func:`mesh_domain`, are :mod:`vaultgram.meshpipeline`'s, which what
needs only a mesh imports alone (not form finding, not tessellation). Stage values carry no timings:
pass a dict as ``timings`` and every function adds the seconds each stage took (the command line
prints them; they are never written to files).

Example
-------
>>> from vaultgram.domain import load_domain
>>> result = design(load_domain("examples/quad_with_hole.json"), zmax=3.0)
>>> len(result.decomposition.patches), result.network.summary["zmax"]
(12, 3.0)
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from vaultgram import progress
from vaultgram.domain import Domain, check_feature_spacing
from vaultgram.errors import (
    ConvergenceError,
    FormFindingError,
    HorizontalEquilibriumError,
    TessellationError,
    VaultgramError,
    VerticalEquilibriumError,
)
from vaultgram.formfinding.forcediagram import force_diagram
from vaultgram.formfinding.formdiagram import form_diagram
from vaultgram.formfinding.horizontal import horizontal
from vaultgram.formfinding.loads import mesh_point_loads
from vaultgram.formfinding.relaxation import relax
from vaultgram.formfinding.supports import support_vertices
from vaultgram.formfinding.thrust import ThrustNetwork, thrust_network
from vaultgram.formfinding.vertical import vertical
from vaultgram.geometry.arrays import distinct, steady
from vaultgram.geometry.halfedges import mesh_edges
from vaultgram.geometry.polygons import signed_area
from vaultgram.geometry.surfaces import area_vectors, vertex_normals
from vaultgram.io.files import collector_paused, freed_memory_kept
from vaultgram.limits import MAX_FACES
from vaultgram.meshing.densities import DensitySpec
from vaultgram.meshing.quadmesh import QuadMesh
from vaultgram.meshing.smoothing import DEFAULT_ITERATIONS
from vaultgram.meshpipeline import decompose, domain_frame, mesh_decomposition, mesh_domain, mesh_or_advise
from vaultgram.tessellation.courses import support_zones, voussoir_courses, voussoir_names
from vaultgram.tessellation.keystones import CutMesh, cut_keystones, load_tessellation_rulebook, pinwheel
from vaultgram.tessellation.mending import join_small_pairs, mend_meeting_points
from vaultgram.tessellation.metrics import summarise
from vaultgram.tessellation.model import Tessellation, voussoir_layout
from vaultgram.tessellation.refine import refine_large_faces
from vaultgram.tessellation.sizes import split_large_quads, unmerge_large
from vaultgram.tessellation.smoothing import smooth_on_surface
from vaultgram.tessellation.solids import solid_volumes, voussoir_solids
from vaultgram.tessellation.stagger import staggered_bond
from vaultgram.tessellation.strips import quad_strips
from vaultgram.tessellation.surface import ThrustSurface, surface_from_network
from vaultgram.tessellation.voussoirs import MAX_CONCAVITY, face_groups, without_concavities
from vaultgram.topology.decomposition import Decomposition

__all__ = ["decompose", "mesh_decomposition", "mesh_domain", "form_find", "thrust_of_mesh", "tessellate", "design",
           "Design", "TessellationOptions", "default_rise"]


# --------------------------------------------------------------------------------------------
# Form finding (§5)
# --------------------------------------------------------------------------------------------


def form_find(mesh_vertices, faces, supports=None, *, zmax: float | None = None, scale: float = 1.0,
              thickness=1.0, density: float = 1.0, point_loads=None, tol_deg: float = 0.5,
              alpha: float = 100.0, relax: bool = True, sag: float = 0.1, relax_mode: str = "auto",
              update_boundaries: bool = True, kmax_horizontal: int = 1000, kmax_vertical: int = 500,
              vertical_tol: float = 1e-12, timings: dict | None = None) -> ThrustNetwork:
    """Form-find a funicular vault over a planar mesh by Thrust Network Analysis (§5).

    Parameters
    ----------
    mesh_vertices : array (n, 2) or (n, 3)
    faces : sequence of counter-clockwise vertex-index sequences
    supports : vertex indices or boolean mask; default every boundary vertex
    zmax : float, optional
        Height of the highest vertex; the thrust scale is solved for. Without it ``scale`` is used.
    scale : float
        Thrust scale when ``zmax`` is None (force densities = scale x force/form length ratios).
    thickness, density : self-weight = 3D tributary area x thickness x density
    point_loads : dict {mesh vertex: load} or array (n_mesh,), positive downwards
    tol_deg : float
        Horizontal-equilibrium tolerance on the max angle between form and force edges (degrees).
    alpha : float
        Form weight (percent) in horizontal equilibrium; 100 keeps the form diagram.
    relax, sag, relax_mode
        Relax open edges (:func:`vaultgram.formfinding.relaxation.relax_openings`) before horizontal
        equilibrium: only the unsupported boundary (``"boundary"``), every free vertex (``"all"``),
        or the boundary first and every free vertex if that admits no compression-only equilibrium
        (``"auto"``, the default). The summary's ``relax_mode`` says which was used, and
        ``relax_fallback`` why the first failed.
    update_boundaries : bool
        See :func:`vaultgram.formfinding.formdiagram.form_diagram`.

    Raises
    ------
    FormFindingError, HorizontalEquilibriumError, ConvergenceError
        bad input (named), no compression-only solution (edges and angles named), non-convergence.

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> v, f = grid_mesh(6)
    >>> tn = form_find(v, f, zmax=2.0)
    >>> round(float(tn.vertices[:, 2].max()), 9), tn.summary["max_angle_deg"] < 0.5
    (2.0, True)
    """
    if relax_mode not in RELAX_MODES:
        raise FormFindingError(f"unknown relax mode {relax_mode!r}; use one of {', '.join(RELAX_MODES)}")
    with progress.timed(timings, "form"):
        form = form_diagram(mesh_vertices, faces, supports, update_boundaries=update_boundaries)
    n_open = int((~form.loaded).sum())
    modes = _relax_modes(relax, relax_mode, n_open)
    loads = dict(scale=scale, zmax=zmax, thickness=thickness, density=density, kmax=kmax_vertical, tol=vertical_tol,
                 point_loads=mesh_point_loads(point_loads, len(mesh_vertices)))
    first: Exception | None = None
    for mode in modes:
        try:
            network = _equilibrium(form, n_open, mode, sag, alpha, kmax_horizontal, tol_deg, timings, loads)
            break
        except (FormFindingError, ConvergenceError) as exc:
            if mode is None and isinstance(exc, VerticalEquilibriumError):
                raise  # the pattern as meshed balances but has no vertical equilibrium at this rise
            if mode == modes[-1]:
                if first is not None and modes[0] is None and not isinstance(exc, VerticalEquilibriumError):
                    raise first from None  # relaxing did not help: the pattern's own failure says more
                raise
            first = exc
    fallback = str(first) if first is not None else None
    summary = {**network.summary, "relax_mode": mode or "none", "relax_fallback": fallback}
    return dataclasses.replace(network, summary=summary)


#: How ``form_find`` relaxes the openings (see its ``relax_mode``).
RELAX_MODES = ("auto", "boundary", "all")


def _relax_modes(relax: bool, relax_mode: str, n_open: int) -> tuple:
    """The relaxations ``form_find`` tries in turn (None: the form diagram as meshed). Without openings,
    ``"auto"`` relaxes every free vertex (unit force densities: an isotropic stress state, so the heights
    of one plan meshed at 10^4 and 10^5 faces agree to 0.4% of zmax) only when the pattern as meshed
    has no compression-only equilibrium (common on fine meshes, whose fixed pattern leaves few force
    densities free)."""
    if not relax:
        return (None,)
    if relax_mode == "auto":
        return ("boundary", "all") if n_open else (None, "all")
    return (relax_mode,) if n_open or relax_mode == "all" else (None,)


def _equilibrium(form, n_open: int, mode: str | None, sag: float, alpha: float, kmax: int, tol_deg: float,
                 timings: dict | None, vertical_options: dict) -> ThrustNetwork:
    """Relaxation of the openings (``mode``, None for none), force diagram, horizontal and vertical
    equilibrium of a form diagram."""
    with progress.timed(timings, "relax"):
        relaxed = relax(form, sag, mode=mode) if mode is not None else None
    with progress.timed(timings, "force"):
        form = relaxed.form if relaxed is not None else form
        force = force_diagram(form, relaxed.q if mode == "all" else None)
    with progress.timed(timings, "horizontal"):
        h = horizontal(form, force, alpha=alpha, kmax=kmax, tol_deg=tol_deg)
    with progress.timed(timings, "vertical"):
        v = vertical(h.form, h.q, **vertical_options)
    return thrust_network(h, v, n_open)


def thrust_of_mesh(mesh: QuadMesh, supports=None, domain: Domain | None = None, point_load: float = 0.0,
                   timings: dict | None = None, zmax: float | None = None, **options) -> ThrustNetwork:
    """Form finding of a quad mesh with a support specification (:mod:`vaultgram.formfinding.supports`),
    ``point_load`` at each of its point features; ``options`` are those of :func:`form_find`.

    Without ``zmax`` the vault gets the rises of :data:`RISES` in turn, the first whose vertical
    equilibrium converges (a steep vault on a narrow plan may not); the summary's ``zmax`` says which.
    Where the openings admit no compression-only vault, the error says which holes to support as well
    (:func:`_support_hint`).
    """
    if isinstance(supports, list):
        supports = {"vertices": supports}
    try:
        return _thrust(mesh, supports, domain, point_load, timings, zmax, options)
    except HorizontalEquilibriumError as exc:
        hint = _support_hint(mesh, supports, domain, point_load, zmax, options)
        raise HorizontalEquilibriumError(f"{exc}{hint}", exc.edges, exc.angles, exc.result, exc.places) from None
    except FormFindingError as exc:
        raise FormFindingError(f"{exc}{_support_hint(mesh, supports, domain, point_load, zmax, options)}",
                               exc.places) from None


def _thrust(mesh: QuadMesh, supports, domain: Domain | None, point_load: float, timings: dict | None,
            zmax: float | None, options: dict) -> ThrustNetwork:
    """:func:`thrust_of_mesh` without the hint: form finding at ``zmax`` or at each of :data:`RISES`."""
    anchors = support_vertices(mesh.vertices, mesh.faces, supports, domain, mesh.origin)
    loads = {int(v): point_load for v in np.flatnonzero(mesh.feature)} if point_load else None
    heights = [zmax] if zmax is not None else [default_rise(mesh.vertices, rise) for rise in RISES]
    for k, height in enumerate(heights):
        try:
            network = form_find(mesh.vertices, mesh.faces, anchors, point_loads=loads, timings=timings, zmax=height,
                                **options)
            return dataclasses.replace(network, origin=mesh.origin)
        except VerticalEquilibriumError:
            if k == len(heights) - 1:
                raise


def _support_hint(mesh: QuadMesh, supports, domain: Domain | None, point_load: float, zmax: float | None,
                  options: dict) -> str:
    """Which holes to support as well when the openings admit no compression-only vault, as a
    ``--supports`` file's content: the largest holes the specification leaves open, 3 of them, then
    twice as many until every hole is held, tried in turn; the first set with which form finding
    succeeds is named (at most four more form findings, only on a run that failed). Where none does,
    the three largest, to try with other options. Empty where the supports are not given by rings.

    A plan whose holes are columns (mexico_airport's 21) needs them all: the designer is told so at
    once rather than three holes at a time.
    """
    if domain is None or not domain.holes or (supports is not None and "rings" not in supports):
        return ""
    held = sorted(supports["rings"] if supports is not None else ["outer"], key=str)
    open_holes = sorted((k for k in range(len(domain.holes)) if k not in held),
                        key=lambda k: -abs(signed_area(domain.holes[k])))
    if not open_holes:
        return ""
    head = f"; {len(open_holes)} of the {len(domain.holes)} holes are open"
    count = 3
    while True:
        trial = {"rings": held + open_holes[:count]}
        try:
            _thrust(mesh, trial, domain, point_load, None, zmax, options)
            what = "all of them" if count >= len(open_holes) else f"the {count} largest"
            return f"{head}: it form-finds with {what} supported, --supports with {json.dumps(trial)}"
        except VaultgramError:
            if count >= len(open_holes):
                break
            count *= 2
    rings = json.dumps({"rings": held + open_holes[:3]})
    return (f"{head}, and supporting them all does not help: try other options, or supporting the largest, "
            f"--supports with {rings}")


# --------------------------------------------------------------------------------------------
# Tessellation (§5)
# --------------------------------------------------------------------------------------------


def _check_tessellation_options(rhythm: int, thickness: float, max_concavity: float, surface_smooth: int) -> None:
    if rhythm not in (2, 4):
        raise TessellationError(f"rhythm must be 2 or 4 (keep every second or every fourth edge), got {rhythm}")
    if not (thickness > 0 and np.isfinite(thickness)):
        raise TessellationError(f"thickness must be a positive number, got {thickness}")
    if not 180.0 <= max_concavity < 360.0:
        raise TessellationError(f"max concavity must lie in [180, 360) degrees, got {max_concavity}")
    if surface_smooth < 0:
        raise TessellationError(f"surface smoothing iterations must be >= 0, got {surface_smooth}")


def tessellate(surface: ThrustSurface, rhythm: int = 2, thickness: float = 1.0,
               max_concavity: float = MAX_CONCAVITY, flat_extrados: bool = False, surface_smooth: int = 0,
               rules_dir: str | Path | None = None, timings: dict | None = None) -> Tessellation:
    """Voussoirs from a thrust surface (§5, Figures 11-13): keystones by the rulebook, a staggered
    bond of ``rhythm`` faces per voussoir without strong concavities, solids ``thickness`` thick,
    courses from the supports.

    Example
    -------
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.tessellation.surface import surface_from_network
    >>> v, f = grid_mesh(8)
    >>> t = tessellate(surface_from_network(form_find(v, f, zmax=2.0)), thickness=0.2)
    >>> t.summary["voussoirs"], t.summary["meeting_points"]
    (28, {'3': 34})
    """
    _check_tessellation_options(rhythm, thickness, max_concavity, surface_smooth)
    rulebook = load_tessellation_rulebook(rules_dir)
    with collector_paused(), freed_memory_kept():
        with progress.timed(timings, "refine"):
            x, faces, supported, refined = _refine(surface)
        with progress.timed(timings, "keystones"):
            cut = cut_keystones(x, faces, mesh_edges(faces, len(x)), rulebook)
            supported = np.where(cut.source >= 0, supported[np.maximum(cut.source, 0)], False)
            me = mesh_edges(cut.faces, len(cut.vertices))
        with progress.timed(timings, "stagger"):
            removed, bond, kept = _bond(cut, me, supported, rhythm, max_concavity)
        with progress.timed(timings, "sizes"):
            cut, me, group, kept["cut"] = _cut_large(cut, face_groups(me, removed), bond.target)
            layout = voussoir_layout(cut, me, group)
            supported = np.concatenate([supported, np.zeros(len(cut.vertices) - len(supported), dtype=bool)])
        with progress.timed(timings, "surface_smooth"):
            fixed = supported.copy()
            fixed[me.edges[me.boundary].ravel()] = True
            x = smooth_on_surface(cut.vertices, cut.faces, layout.loops, fixed, surface.vertices, surface.faces,
                                  surface_smooth, max_concavity)
        with progress.timed(timings, "solids"):
            normals = vertex_normals(x, cut.faces)
            solids = voussoir_solids(x, normals, layout.loops, thickness, flat_extrados)
        with progress.timed(timings, "courses"):
            courses, zones = _courses(layout, supported, me)
        with progress.timed(timings, "metrics"):
            summary = summarise(x, normals, layout, max_concavity, {**kept, "refined_strips": refined},
                                surface.holes, solid_volumes(solids, layout.n_voussoirs))
    return Tessellation(layout, x, normals, solids, courses, zones, tuple(voussoir_names(courses, zones)),
                        {**summary, "rhythm": rhythm, "thickness": thickness}, surface.origin)


def _bond(cut: CutMesh, me, supported: np.ndarray, rhythm: int, max_concavity: float):
    """The staggered bond (:mod:`vaultgram.tessellation.stagger`) with the pinwheels round the keystones,
    without strong concavities (:mod:`vaultgram.tessellation.voussoirs`), the largest voussoirs given
    back an edge (:mod:`vaultgram.tessellation.sizes`), the points of four voussoirs mended and small
    neighbours joined in pairs (:mod:`vaultgram.tessellation.mending`): the removed edges, the bond,
    and the counts of what was kept or changed, by reason."""
    x, faces = cut.vertices, cut.faces
    area_vec = area_vectors(x, faces)
    areas = steady(np.linalg.norm(area_vec, axis=1))  # equal for mirror faces, sums exact (geometry.arrays)
    rings = distinct(np.concatenate([me.face_edges(k) for k in cut.keystones])) if len(cut.keystones) else ()
    normals = area_vec / np.maximum(areas, 1e-300)[:, None]
    bond = staggered_bond(x, me, quad_strips(me, faces), supported, areas, rhythm, pinwheel(cut, me), rings, normals)
    removed, restored = without_concavities(x, me, bond.removed, max_concavity)
    inner = np.ones(len(x), dtype=bool)
    inner[me.edges[me.boundary].ravel()] = False
    whole = removed
    removed, unmerged = unmerge_large(me, removed, inner, areas, bond.target, len(x))
    if unmerged:  # a piece's best-fit plane is not its voussoir's: its corners are measured again
        removed, again = without_concavities(x, me, removed, max_concavity, me.faces_of[whole & ~removed].ravel())
        restored += again
    keystone = np.zeros(len(faces), dtype=bool)
    keystone[cut.keystones] = True
    removed, moved = mend_meeting_points(x, me, removed, inner, areas, bond.target, max_concavity, keystone)
    removed, joined = join_small_pairs(x, me, removed, areas, bond.target, max_concavity, keystone)
    kept = {"concavity": restored, "taken": bond.kept_taken, "aligned": bond.aligned, "unmerged": unmerged,
            "moved": moved, "joined": joined, "courses": bond.courses}
    return removed, bond, kept


def _refine(surface: ThrustSurface) -> tuple[np.ndarray, tuple, np.ndarray, int]:
    """The surface's vertices, faces and supports with the strips of its large faces refined
    (:mod:`vaultgram.tessellation.refine`)."""
    x, faces, parents, _, refined = refine_large_faces(surface.vertices, surface.faces)
    supported = list(surface.supported.tolist())
    for p in parents:  # a point added between supported points is supported (parents come first)
        supported.append(all(supported[v] for v in p))
    return x, faces, np.array(supported, dtype=bool), refined


def _cut_large(cut: CutMesh, group: np.ndarray, target: float):
    """The cut mesh with its too large single quads cut in two (:mod:`vaultgram.tessellation.sizes`)."""
    x, faces, group, _, cuts = split_large_quads(cut.vertices, cut.faces, group, target)
    if cuts:
        source = np.concatenate([cut.source, np.full(len(x) - len(cut.vertices), -1)])
        cut = CutMesh(x, faces, cut.keystones, source, cut.steps)
    return cut, mesh_edges(cut.faces, len(cut.vertices)), group, cuts


def _courses(layout, supported: np.ndarray, me) -> tuple[np.ndarray, np.ndarray]:
    """Construction course and support zone of every voussoir (:mod:`vaultgram.tessellation.courses`)."""
    zone_of_vertex = support_zones(me.edges, supported)
    owner = np.repeat(np.arange(layout.n_voussoirs), [len(loop) for loop in layout.loops])
    z = zone_of_vertex[np.concatenate(layout.loops)]
    zone = np.full(layout.n_voussoirs, np.iinfo(np.int64).max, dtype=np.int64)
    np.minimum.at(zone, owner[z >= 0], z[z >= 0])  # the smallest zone a voussoir rests on
    resting = np.flatnonzero(zone < np.iinfo(np.int64).max)
    return voussoir_courses(layout.joint_voussoirs(), layout.n_voussoirs, resting, zone[resting])


# --------------------------------------------------------------------------------------------
# Everything
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class TessellationOptions:
    """The tessellation's options (:func:`tessellate`; the thickness is the form finding's)."""

    rhythm: int = 2
    max_concavity: float = MAX_CONCAVITY
    flat_extrados: bool = False
    surface_smooth: int = 0


@dataclass(frozen=True, eq=False)
class Design:
    """Every stage's value for one domain, and the seconds each stage took."""

    domain: Domain
    decomposition: Decomposition
    mesh: QuadMesh
    supports: np.ndarray
    network: ThrustNetwork
    tessellation: Tessellation | None
    timings: dict = field(default_factory=dict)

    def summary(self) -> dict:
        """What ``summary.json`` holds for a whole design: the mesh, the thrust network, the voussoirs."""
        return {"mesh": self.mesh.info, "thrust": self.network.summary,
                "tessellation": self.tessellation.summary if self.tessellation is not None else None}


#: The default heights of a vault, tried in turn: these fractions of the shorter side of its plan's
#: bounding box (a quarter of the span is a usual rise for a masonry vault).
RISES = (0.25, 0.15, 0.1)


def default_rise(vertices: np.ndarray, rise: float = RISES[0]) -> float:
    """A height for a vault over ``vertices``: ``rise`` times the shorter side of the plan's
    bounding box.

    >>> default_rise(np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 6.0]]))
    1.5
    """
    extent = np.ptp(np.asarray(vertices, dtype=float)[:, :2], axis=0)
    return float(rise * extent.min())


def design(domain: Domain, spacing: float = 0.02, rules_dir: str | Path | None = None,
           target_length: float | None = None, smooth: int = DEFAULT_ITERATIONS,
           densities: DensitySpec | None = None, allow_folds: bool = False, supports=None,
           point_load: float = 0.0, zmax: float | None = None, thickness: float = 1.0,
           tessellation: TessellationOptions | None = TessellationOptions(), trace: bool = False,
           max_faces: int = MAX_FACES, on_stage=None, **options) -> Design:
    """The whole pipeline on a domain: decomposition (§3.1, §4), mesh (§3.2), thrust network (§5) and
    tessellation (§5).

    ``supports`` overrides the domain's own; ``zmax`` defaults to a rise (:func:`thrust_of_mesh`); ``thickness``
    is the shell's, for its self-weight and its voussoirs; ``tessellation`` None stops at the thrust
    network; ``trace`` keeps the decomposition's starting graph for a replay; ``max_faces`` limits the
    mesh (:mod:`vaultgram.meshing.guards`); ``on_stage(name, value)``, if given, is told of each stage
    as it is done (``domain``, ``decomposition``, ``mesh``, ``supports``, ``network``, ``tessellation``:
    :class:`vaultgram.io.figures.worker.FigureWorker` draws their figures meanwhile); ``options`` are
    those of :func:`form_find`.
    """
    timings: dict = {}
    done = on_stage if on_stage is not None else (lambda name, value: None)
    with domain_frame(domain):
        check_feature_spacing(domain, spacing)
    done("domain", domain)
    dec = decompose(domain, spacing, rules_dir, timings=timings, trace=trace)
    done("decomposition", dec)
    mesh = mesh_or_advise(dec, rules_dir, target_length, smooth, densities, allow_folds, timings, max_faces)
    done("mesh", mesh)
    spec = domain.supports if supports is None else supports
    spec = {"vertices": spec} if isinstance(spec, list) else spec
    with progress.timed(timings, "supports"):
        anchors = support_vertices(mesh.vertices, mesh.faces, spec, domain, mesh.origin)
    done("supports", anchors)
    # the specification itself, not its vertices: a failure's hint names the holes it leaves open
    network = thrust_of_mesh(mesh, spec, domain, point_load, timings, zmax=zmax, thickness=thickness, **options)
    done("network", network)
    voussoirs = None
    if tessellation is not None:
        t = tessellation
        with progress.timed(timings, "surface"):
            surface = surface_from_network(network)
        voussoirs = tessellate(surface, t.rhythm, thickness, t.max_concavity, t.flat_extrados, t.surface_smooth,
                               rules_dir, timings)
        done("tessellation", voussoirs)
    return Design(domain, dec, mesh, anchors, network, voussoirs, timings)
