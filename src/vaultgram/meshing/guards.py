"""Resource guards: how big a mesh the densities ask for, known before any of it is made.

The counts of the edge groups (:func:`vaultgram.meshing.densities.group_counts`) fix the number of
faces of every patch: a quad patch is a ``c(bottom) x c(right)`` grid, a triangle patch (§3.2, Figure
3) the same grid with its left side collapsed to the pole. So the size of the mesh, and roughly the
memory the pipeline needs for it, are known from the counts alone, in microseconds: a request far
beyond what the machine can hold (``--target-length 1e-3`` on a 10 x 10 plan asks for about 10^8
faces) is refused with the estimate and the limit instead of swapping until the kernel kills it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from vaultgram.errors import VaultgramError
from vaultgram.limits import BYTES_PER_FACE, MAX_FACES
from vaultgram.meshing.splits import divided_patterns, division, split_patterns

__all__ = ["MAX_FACES", "BYTES_PER_FACE", "MeshEstimate", "estimate_mesh", "check_mesh_size"]



@dataclass(frozen=True)
class MeshEstimate:
    """The faces a layout's counts give, and the memory the pipeline needs for them (bytes)."""

    faces: int
    memory: int

    def text(self) -> str:
        """``about 1.0e+08 faces (about 800 GB of memory)``."""
        return f"about {self.faces:.3g} faces (about {_bytes_text(self.memory)} of memory)"


def estimate_mesh(layout, counts) -> MeshEstimate:
    """The number of faces the Coons grids of ``layout`` (:class:`vaultgram.meshing.layout.Layout`)
    have for ``counts`` (one per edge group), exact: per patch the product of the counts of its first
    two sides, a triangle's counted from its pole; and :data:`BYTES_PER_FACE` times that.

    >>> from vaultgram.domain import load_domain
    >>> from vaultgram.meshing.densities import group_counts
    >>> from vaultgram.meshing.layout import edge_groups
    >>> from vaultgram.meshing.weld import weld
    >>> from vaultgram.pipeline import decompose
    >>> layout = edge_groups(decompose(load_domain("examples/quad_with_hole.json")))
    >>> counts = group_counts(layout)
    >>> estimate_mesh(layout, counts).faces == len(weld(layout, counts).faces)
    True
    """
    c = np.asarray(counts, dtype=float)[layout.group_of]
    split, divided = split_patterns(layout, counts), divided_patterns(layout, counts)
    faces = 0.0
    for i, pat in enumerate(layout.patterns):
        k = pat.pole or 0
        m, n = c[pat.sides[k][0]], c[pat.sides[(k + 1) % len(pat.sides)][0]]
        if i in divided:  # parts of three quads each, their opposite sides cut at the spokes
            ends = (0, *division(int(m), int(n), divided[i]), int(n))
            faces += sum(_split_faces(m, hi - lo) for lo, hi in zip(ends[:-1], ends[1:]))
        else:
            faces += _split_faces(m, n) if i in split else m * n
    return MeshEstimate(int(min(faces, 2.0**62)), int(min(faces * BYTES_PER_FACE, 2.0**62)))


def _split_faces(m: float, n: float) -> float:
    """The faces of a triangle split into three quads: ``n/2 (n/2 + 2 (m - n/2))``.

    >>> _split_faces(7, 6)  # 3 x 3 at the pole, 3 x 4 at B and at C
    33
    """
    return n // 2 * (2 * m - n // 2)


def check_mesh_size(layout, counts, max_faces: int = MAX_FACES) -> MeshEstimate:
    """The estimate (:func:`estimate_mesh`), or a :class:`~vaultgram.errors.VaultgramError` naming it
    and the limit when it has more than ``max_faces`` faces."""
    estimate = estimate_mesh(layout, counts)
    if estimate.faces > max_faces:
        raise VaultgramError(
            f"the densities ask for {estimate.text()}, more than the limit of {max_faces} faces "
            "(--max-faces): use a larger --target-length or smaller counts, or raise --max-faces")
    return estimate


def _bytes_text(n: float) -> str:
    """Bytes as ``12 MB``, ``3.4 GB``, ``800 GB``, ``1.2e+03 TB``."""
    for unit, size in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{n / 1e3:.3g} kB"
