"""Ranking variants: a documented score, and the Pareto front over two metrics.

**Score** (higher is better): mesh quality first, then fewer irregularities,

``score = min_scaled_jacobian + mean_scaled_jacobian - 0.5 * boundary_singularities
- 0.05 * singularities - 0.01 * edge_groups - inverted_faces``

A boundary singularity is what the paper's §3.1 sets out to avoid, so it weighs ten times a layout
singularity; edge groups are degrees of freedom of the density (§3.2), a mild cost in design effort;
a folded face disqualifies. Ties are broken by the variant id (the order the search found them).

**Pareto front**: over two metrics named by the caller, each with its sense (:data:`SENSE`: quality
up, counts down); a variant is on the front when no other is at least as good in both and better in
one.
"""

from __future__ import annotations

from vaultgram.errors import VaultgramError

#: +1: larger is better, -1: smaller is better.
SENSE = {
    "min_scaled_jacobian": 1, "mean_scaled_jacobian": 1, "score": 1, "patches": -1, "singularities": -1,
    "poles": -1, "edge_groups": -1, "boundary_singularities": -1, "interior_singular_vertices": -1,
    "inverted_faces": -1, "faces": -1, "angle_deviation_deg": -1, "max_thrust": -1, "zmax": 1,
}
DEFAULT_PARETO = ("min_scaled_jacobian", "edge_groups")


def score(metrics: dict) -> float | None:
    """The score of a variant's metrics (module docstring); None for a variant without a mesh.

    >>> score({"min_scaled_jacobian": 0.5, "mean_scaled_jacobian": 0.9, "boundary_singularities": 0,
    ...        "singularities": 4, "edge_groups": 10, "inverted_faces": 0})
    1.1
    """
    if "error" in metrics:
        return None
    value = (metrics["min_scaled_jacobian"] + metrics["mean_scaled_jacobian"] - 0.5 * metrics["boundary_singularities"]
             - 0.05 * metrics["singularities"] - 0.01 * metrics["edge_groups"] - metrics["inverted_faces"])
    return round(value, 6)


def parse_pareto(text: str) -> tuple[str, str]:
    """Two metric names, ``a,b``, each one of :data:`SENSE`."""
    names = tuple(n.strip() for n in text.split(","))
    unknown = [n for n in names if n not in SENSE]
    if len(names) != 2 or unknown:
        raise VaultgramError(f"--pareto takes two metrics a,b among {', '.join(sorted(SENSE))}; got {text!r}")
    return names


def pareto_front(rows: list[dict], metrics: tuple[str, str]) -> set[int]:
    """The ids of the rows (``{"id", "metrics"}``) on the Pareto front over two metrics.

    >>> rows = [{"id": i, "metrics": {"min_scaled_jacobian": q, "edge_groups": g}}
    ...         for i, (q, g) in enumerate([(0.5, 10), (0.6, 12), (0.4, 11)])]
    >>> sorted(pareto_front(rows, ("min_scaled_jacobian", "edge_groups")))  # 2 is worse than 0 in both
    [0, 1]
    """
    def key(row):
        return tuple(SENSE.get(m, 1) * row["metrics"][m] for m in metrics)

    scored = [(key(r), r["id"]) for r in rows if all(m in r["metrics"] for m in metrics)]
    return {i for k, i in scored
            if not any(all(o >= s for o, s in zip(other, k)) and other != k for other, _ in scored)}
