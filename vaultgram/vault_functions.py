"""The geometric helper functions the vault pipeline registers for its rules.

The engine knows nothing about geometry; rules in ``rules/`` may call these by name. Each is pure
and local (it reads only its arguments), so rules using them re-match incrementally.
"""

from __future__ import annotations

import math

from vaultgram.engine.expressions import Functions


def distance(p, q) -> float:
    return math.dist(p, q)


def midpoint(p, q) -> tuple[float, ...]:
    return tuple((a + b) / 2 for a, b in zip(p, q))


def lerp(p, q, t) -> tuple[float, ...]:
    return tuple(a + (b - a) * t for a, b in zip(p, q))


def angle_between(p, centre, q) -> float:
    """The angle p-centre-q in degrees, in [0, 180]."""
    a = math.atan2(p[1] - centre[1], p[0] - centre[0])
    b = math.atan2(q[1] - centre[1], q[0] - centre[0])
    d = abs(a - b) % (2 * math.pi)
    return math.degrees(min(d, 2 * math.pi - d))


def vault_functions() -> Functions:
    """A registry with the engine's builtins plus the vault pipeline's geometry."""
    f = Functions()
    f.register("distance", distance, ("vec", "vec"), "float")
    f.register("midpoint", midpoint, ("vec2", "vec2"), "vec2")
    f.register("lerp", lerp, ("vec2", "vec2", "number"), "vec2")
    f.register("angle_between", angle_between, ("vec2", "vec2", "vec2"), "float")
    return f
