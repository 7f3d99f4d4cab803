"""The domain strategies, shipped in the package (:mod:`vaultgram.testing.domains`, which
``vaultgram rules test`` draws from) and re-exported here for the test suites."""

from vaultgram.testing.domains import (  # noqa: F401
    SQUARE,
    convex_domains,
    feature_domains,
    polygons_with_holes,
    square_with,
    squares_with_curves,
    star_polygons,
    vault_domains,
)
from vaultgram.testing.orthogonal import RECTILINEAR_PLANS, orthogonal_domains  # noqa: F401, E402
