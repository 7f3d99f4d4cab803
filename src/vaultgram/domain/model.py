"""The domain of a vault: outer boundary, holes, point and curve features (paper §3.1 and §4).

A :class:`Domain` is the plain, immutable input of the pipeline
``Domain -> Discretisation -> Triangulation -> Skeleton -> ...``. It is read from

* vaultgram JSON (``{"name", "outer", "holes", "points", "curves", "supports"}``, see
  ``domain.schema.json`` next to this module; only ``outer`` is required, extra keys such as
  ``source`` are allowed and ignored),
* GeoJSON (a ``FeatureCollection`` or a single ``Feature``: one ``Polygon`` gives the outer ring and
  the holes, ``Point``/``MultiPoint`` give point features, ``LineString``/``MultiLineString`` give
  curve features),
* DXF (via ezdxf: the closed polyline enclosing all others is the outer ring, the other closed
  polylines are holes, ``POINT`` entities are point features and open polylines / lines are curve
  features).

Every loader normalises the rings (closing vertex dropped, outer ring counter-clockwise, holes
clockwise, so that the domain always lies to the *left* of every ring) and runs
:func:`~vaultgram.domain.validation.validate_domain` before returning, so a ``Domain`` that exists is
valid. Problems raise :class:`vaultgram.errors.DomainError` with a message that names the ring or
feature and the vertex index, e.g. ``outer ring: vertices 3 and 4 coincide at (10, 0)``. Vertex
indices are those of the normalised ring: the file's order, reversed when the orientation had to be
fixed (vertex 0 stays vertex 0); messages also give the coordinates.

Tolerance: two vertices closer than ``1e-9`` times the diagonal of the outer ring's bounding box are
"the same point" (:attr:`Domain.tolerance`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import shapely

from vaultgram.geometry.frames import NO_ORIGIN
from vaultgram.geometry.polygons import bbox_diagonal, signed_area

__all__ = ["Domain", "ring_name", "REL_TOL"]

#: Relative tolerance: vertices closer than ``REL_TOL * bbox diagonal`` coincide.
REL_TOL = 1e-9


@dataclass(frozen=True, eq=False)
class Domain:
    """A planar vault domain (paper §3.1 input, with the §4 point and curve features).

    Build one with a reader (:mod:`vaultgram.domain.readers`), which normalises and validates it;
    constructed directly, it is used as given.

    Attributes
    ----------
    name : str
        A label (file stem when the file gives none).
    outer : ndarray (n, 2) float64
        Outer boundary, counter-clockwise, without closing vertex.
    holes : tuple of ndarray (m_i, 2)
        Inner boundaries (openings), each clockwise, without closing vertex.
    points : ndarray (k, 2)
        Point features (§4.1): inside the domain or on its boundary. A point given just outside the
        boundary (closer than ``POINT_SNAP`` times the diagonal) is projected onto it.
    curves : tuple of ndarray (c_i, 2)
        Curve features (§4.2): open polylines inside the domain; only their end points may lie on
        the boundary.
    supports : object or None
        The raw ``supports`` value (validated for shape only): ``None`` means the whole outer
        boundary is supported and holes are open; ``{"rings": ["outer", 0, ...]}`` selects whole
        rings; ``{"polylines": [[[x, y], ...], ...]}`` supports the boundary parts lying on them.
    units : str or None
        The length unit of a CAD drawing (``"m"``, ``"mm"``, ...) as its file declares it; None when
        the file says nothing (vaultgram JSON and GeoJSON). Written back to CAD outputs.
    origin : tuple of float
        Where the domain's frame starts in the plan's own coordinates: (0, 0) for a plan near the
        origin; for a far one (site coordinates) the readers move the rings and features by it, so
        that the stages keep their digits, and the writers add it back
        (:mod:`vaultgram.geometry.frames`). The supports and density regions stay in the plan's
        coordinates.

    Example
    -------
    >>> d = Domain("square", np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]]))
    >>> d.area, d.diagonal, len(d.rings)
    (12.0, 5.0, 1)
    """

    name: str
    outer: np.ndarray
    holes: tuple = ()
    points: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    curves: tuple = ()
    supports: object | None = None
    units: str | None = None
    origin: tuple = NO_ORIGIN

    @property
    def diagonal(self) -> float:
        """Length of the diagonal of the outer ring's bounding box (the unit of all spacings)."""
        return bbox_diagonal(self.outer)

    @property
    def tolerance(self) -> float:
        """Absolute coincidence tolerance, ``REL_TOL * diagonal``."""
        return REL_TOL * self.diagonal

    @property
    def rings(self) -> tuple:
        """All rings in the standard order: outer ring first, then the holes."""
        return (self.outer, *self.holes)

    def polygon(self) -> shapely.Polygon:
        """The domain as a shapely polygon (outer shell with holes)."""
        return shapely.Polygon(self.outer, [h for h in self.holes])

    @property
    def area(self) -> float:
        """Area of the domain (outer area minus hole areas)."""
        return float(signed_area(self.outer) + sum(signed_area(h) for h in self.holes))

    def __repr__(self) -> str:  # arrays make the default repr unreadable
        return (
            f"Domain(name={self.name!r}, outer={len(self.outer)} vertices, holes={len(self.holes)}, "
            f"points={len(self.points)}, curves={len(self.curves)})"
        )


def ring_name(ring: int) -> str:
    """Human name of ring ``ring`` in the standard order (0 = outer, 1.. = hole ring-1), for messages.

    >>> ring_name(0), ring_name(2)
    ('outer ring', 'hole 1')
    """
    return "outer ring" if ring == 0 else f"hole {ring - 1}"
