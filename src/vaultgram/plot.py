"""Quick figures of the pipeline's stages (matplotlib, no screen needed)."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from vaultgram.patches import half_edge_polyline  # noqa: E402

EDGE_STYLE = {
    "Boundary": dict(color="black", lw=1.2),
    "Branch": dict(color="tab:blue", lw=1.0),
    "Rebranch": dict(color="tab:orange", lw=1.0),
    "Diagonal": dict(color="tab:green", lw=1.0),
    "Curve": dict(color="tab:purple", lw=2.0),
}


def plot_decomposition(decomposition, path: str | Path) -> None:
    """Boundaries, branches, rebranches, singularities and patch numbers; written atomically as PNG."""
    g = decomposition.graph
    fig, ax = plt.subplots(figsize=(7, 7))
    for e in g.edges():
        style = EDGE_STYLE.get(g.edge_type(e))
        if style:
            xy = half_edge_polyline(g, e, g.ends(e)[0])
            ax.plot(xy[:, 0], xy[:, 1], **style)
    for n in decomposition.singularities():
        x, y = g.get(n, "pos")
        ax.plot(x, y, "o", color="tab:red", ms=5)
    for patch in decomposition.patches:
        cx, cy = patch.polygon().mean(axis=0)
        ax.text(cx, cy, str(patch.id), ha="center", va="center", fontsize=7, color="gray")
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(f"{len(decomposition.patches)} patches, {len(decomposition.singularities())} singularities")
    save_figure(fig, Path(path))


def save_figure(fig, path: Path) -> None:
    """Save without timestamps or version metadata (byte-identical reruns), via a temporary file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    fig.savefig(tmp, dpi=120, metadata={"Software": None})
    plt.close(fig)
    tmp.replace(path)
