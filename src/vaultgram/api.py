"""vaultgram's Python API: one function per stage, and :func:`design` for all of them.

These are the functions ``import vaultgram`` gives (``vaultgram.design``, ``vaultgram.mesh``, ...): each
takes a plan or the previous stage's value, with the command line's options as keyword arguments, and
works the same in Rhino 8's CPython and Grasshopper's script components (Python 3.9). The stages
themselves are in :mod:`vaultgram.pipeline`; see ``docs/api.md``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Union

from vaultgram.domain import Domain, load_domain
from vaultgram.formfinding.thrust import ThrustNetwork
from vaultgram.meshing.quadmesh import QuadMesh
from vaultgram.pipeline import Design, thrust_of_mesh
from vaultgram.pipeline import decompose as _decompose
from vaultgram.pipeline import design as _design
from vaultgram.pipeline import mesh_domain as _mesh_domain
from vaultgram.pipeline import tessellate as _tessellate
from vaultgram.tessellation.model import Tessellation
from vaultgram.tessellation.surface import surface_from_network
from vaultgram.topology.decomposition import Decomposition

__all__ = ["load", "decompose", "mesh", "formfind", "tessellate", "design", "save", "Result"]

#: What :func:`design` returns: every stage's value (``domain``, ``decomposition``, ``mesh``,
#: ``supports``, ``network``, ``tessellation``) and the seconds each stage took (``timings``).
Result = Design

PlanLike = Union[Domain, str, Path]


def load(path: str | Path, **options) -> Domain:
    """Read a plan: vaultgram JSON, GeoJSON, DXF or Rhino .3dm.

    Parameters
    ----------
    path : str or Path
    **options
        ``input_format``, ``layers`` (role -> layer name for DXF and .3dm), ``spacing`` (.3dm curves
        are sampled at it): see :func:`vaultgram.domain.load_domain`.

    Returns
    -------
    Domain

    Raises
    ------
    DomainError
        The file is missing or malformed, or the plan is invalid (the message says where).

    Examples
    --------
    >>> import vaultgram
    >>> vaultgram.load("examples/quad_with_hole.json")
    Domain(name='quad_with_hole', outer=4 vertices, holes=1, points=0, curves=0)
    """
    return load_domain(path, **options)


def _domain(plan: PlanLike) -> Domain:
    return plan if isinstance(plan, Domain) else load_domain(plan)


def decompose(plan: PlanLike, spacing: float = 0.02, **options) -> Decomposition:
    """The block decomposition of a plan (§3.1, §4): its skeleton rewritten by the rulebook into 3- and
    4-sided patches.

    Parameters
    ----------
    plan : Domain, str or Path
        A plan, or a file to :func:`load`.
    spacing : float
        Boundary discretisation, a fraction of the bounding-box diagonal.
    **options
        ``rules_dir``, ``smooth`` (:func:`vaultgram.pipeline.decompose`).

    Returns
    -------
    Decomposition

    Raises
    ------
    VaultgramError
        A bad plan or rule file.

    Examples
    --------
    >>> import vaultgram
    >>> dec = vaultgram.decompose("examples/quad_with_hole.json")
    >>> len(dec.patches), dec.patches_json()["counts"]
    (12, {'3': 0, '4': 12})
    """
    return _decompose(_domain(plan), spacing, **options)


def mesh(plan: PlanLike, spacing: float = 0.02, **options) -> QuadMesh:
    """The smooth quad mesh of a plan (§3): decomposition, Coons patches, welding, smoothing.

    Parameters
    ----------
    plan : Domain, str or Path
    spacing : float
    **options
        ``target_length``, ``smooth``, ``densities``, ``rules_dir``, ``allow_folds``
        (:func:`vaultgram.pipeline.mesh_domain`).

    Returns
    -------
    QuadMesh

    Raises
    ------
    VaultgramError
        A bad plan; ``MeshFoldError`` when the smoothed mesh still folds.

    Examples
    --------
    >>> import vaultgram
    >>> m = vaultgram.mesh("examples/quad_with_hole.json", target_length=1.0)
    >>> len(m.faces), m.info["patches"]
    (128, 12)
    """
    return _mesh_domain(_domain(plan), spacing, **options)


def formfind(pattern: QuadMesh | PlanLike, supports=None, **options) -> ThrustNetwork:
    """The thrust network of a pattern by Thrust Network Analysis (§5).

    Parameters
    ----------
    pattern : QuadMesh, Domain, str or Path
        A mesh, or a plan (meshed first with :func:`mesh`'s defaults).
    supports : optional
        A support specification (``{"rings": [...]}``, ``{"polylines": [...]}``, ``{"vertices": [...]}``
        or a vertex list); default the plan's own, else the outer boundary.
    **options
        ``zmax``, ``thickness``, ``density``, ``point_load``, ``tol_deg``, ``sag``, ``relax_mode``, ...
        (:func:`vaultgram.pipeline.thrust_of_mesh` and :func:`vaultgram.pipeline.form_find`).

    Returns
    -------
    ThrustNetwork

    Raises
    ------
    FormFindingError
        No compression-only equilibrium (the edges are named), bad supports.

    Examples
    --------
    >>> import vaultgram
    >>> network = vaultgram.formfind("examples/quad_with_hole.json", zmax=3.0)
    >>> network.summary["zmax"], network.summary["max_angle_deg"] < 0.5
    (3.0, True)
    """
    domain = None
    if not isinstance(pattern, QuadMesh):
        domain = _domain(pattern)
        pattern = _mesh_domain(domain)
    spec = supports if supports is not None else (domain.supports if domain is not None else None)
    return thrust_of_mesh(pattern, spec, domain, **options)


def tessellate(network: ThrustNetwork, **options) -> Tessellation:
    """Voussoirs cut from a thrust network (§5): keystones, a staggered bond, solids, courses.

    Parameters
    ----------
    network : ThrustNetwork
    **options
        ``rhythm`` (2 or 4), ``thickness``, ``max_concavity``, ``flat_extrados``, ``surface_smooth``,
        ``rules_dir`` (:func:`vaultgram.pipeline.tessellate`).

    Returns
    -------
    Tessellation

    Raises
    ------
    TessellationError
        Bad options, or a network that cannot be tessellated.

    Examples
    --------
    >>> import vaultgram
    >>> from vaultgram.geometry.meshes import grid_mesh
    >>> from vaultgram.pipeline import form_find
    >>> t = vaultgram.tessellate(form_find(*grid_mesh(8), zmax=2.0), thickness=0.2)
    >>> t.summary["voussoirs"]
    28
    """
    return _tessellate(surface_from_network(network), **options)


def design(plan: PlanLike, **options) -> Result:
    """The whole pipeline on a plan: decomposition, mesh, thrust network and voussoirs.

    Parameters
    ----------
    plan : Domain, str or Path
    **options
        Those of every stage: ``spacing``, ``rules_dir``, ``target_length``, ``smooth``, ``densities``,
        ``allow_folds``, ``supports``, ``point_load``, ``zmax``, ``thickness``, ``tessellation``
        (:class:`vaultgram.pipeline.TessellationOptions`, or None to stop at the thrust network) and
        those of :func:`vaultgram.pipeline.form_find` (``density``, ``tol_deg``, ``sag``, ``relax_mode``...).

    Returns
    -------
    Result
        Every stage's value and the seconds each took.

    Raises
    ------
    VaultgramError
        From any stage, naming the problem and where.

    Examples
    --------
    >>> import vaultgram
    >>> result = vaultgram.design("examples/quad_with_hole.json", zmax=3.0, tessellation=None)
    >>> len(result.decomposition.patches), result.network.summary["zmax"], result.tessellation
    (12, 3.0, None)
    """
    return _design(_domain(plan), **options)


def save(result: Result, out: str | Path, formats=("json", "obj"), figures: bool = True) -> Path:
    """Write a design's files to a folder, as ``vaultgram design --format`` does: all of them or,
    if writing fails, none.

    Parameters
    ----------
    result : Result
    out : str or Path
    formats : sequence of str
        Of ``json``, ``obj``, ``compas``, ``3dm``, ``dxf`` (:mod:`vaultgram.io.outputs`).
    figures : bool
        Also the figures of every stage (``figures/``) and ``report.html``, as ``design`` writes them.

    Returns
    -------
    Path
        The folder.

    Raises
    ------
    VaultgramError
        An unknown format, or one whose optional package is missing.

    Examples
    --------
    >>> import tempfile, vaultgram
    >>> result = vaultgram.design("examples/quad_with_hole.json", zmax=3.0, tessellation=None)
    >>> folder = vaultgram.save(result, tempfile.mkdtemp(), formats=["json", "dxf"], figures=False)
    >>> names = {p.name for p in folder.iterdir()}
    >>> "thrust.json" in names, "result.dxf" in names, "thrust.obj" in names
    (True, True, False)
    """
    from vaultgram.io.files import output_folder
    from vaultgram.io.outputs import parse_formats, write_design

    out = Path(out)
    with output_folder(out) as stage:  # all the files, or none
        write_design(result, stage, parse_formats(",".join(formats)), plots=figures, report=figures)
    return out
