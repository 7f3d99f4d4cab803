"""The geometric helper functions the tessellation registers for its rules (``rules/tessellation.vgr``).

The engine knows nothing about vaults: a rule may call these by name. They are pure and local (they
read only their arguments), so rules using them re-match incrementally.
"""

from __future__ import annotations

import math

from vaultgram.engine.expressions import Functions

__all__ = ["tessellation_functions", "lerp", "fan"]


def lerp(p, q, t) -> tuple[float, ...]:
    """The point at ``t`` of the way from ``p`` to ``q`` (in space).

    >>> lerp((0.0, 0.0, 0.0), (2.0, 4.0, 6.0), 0.25)
    (0.5, 1.0, 1.5)
    """
    return tuple(a + (b - a) * t for a, b in zip(p, q))


def fan(graph, v: int) -> bool:
    """Whether every face around node ``v`` is a triangle: each two neighbours next to each other in
    the rotation around ``v`` are joined (a pole's fan of triangles, §4.1)."""
    around = [graph.other(e, v) for e in graph.rotation(v)]
    return len(around) >= 3 and all(
        any(graph.other(e, a) == b for e in graph.rotation(a)) for a, b in zip(around, around[1:] + around[:1]))


def tessellation_functions() -> Functions:
    """The function table of the tessellation rulebook."""
    f = Functions()
    f.register("lerp", lerp, ("vec3", "vec3", "number"), "vec3")
    f.register("distance", math.dist, ("vec", "vec"), "float")
    f.register("fan", fan, ("node",), "bool", uses_graph=True, local=False)
    return f
