"""Meshes drawn as before session 24's point-load caps, for the tests of mechanisms those plans
showed then.

Since session 24 a point load's fans get at most the triangles that reach the quality floor
(:func:`vaultgram.meshing.densities.point_load_caps`). That changes the counts of every plan with an
inner point feature, and with them the random plans some tests draw for another mechanism (a curve
end's fan under the floor, a split that folds). Those tests draw them with the caps off.
"""

from __future__ import annotations

import numpy as np

from vaultgram.meshing import densities


def without_point_load_caps(monkeypatch) -> None:
    """Turn the point-load caps off for the rest of the test (every group at the ceiling)."""
    monkeypatch.setattr(densities, "point_load_caps",
                        lambda layout: np.full(layout.n_groups, densities.COUNT_CEILING, dtype=np.int64))
