"""The figure of a failure: where in the plan a stage failed on a geometric problem (the inverted
faces of a mesh that folds, a patch with more than four sides, boundary segments the triangulation
misses, form-diagram edges that flip or collapse in form finding), over the domain's boundaries.

``vaultgram design`` runs inside :func:`error_figure`: when a stage raises a
:class:`~vaultgram.errors.DomainError` or :class:`~vaultgram.errors.FormFindingError` that knows
its ``places``, the figure is written and the
error's one line says where it is; nothing else is written. Where it goes keeps the output folder
complete or untouched (issue 17):

* ``DIR/error.png`` when ``DIR`` does not exist, or holds nothing but an earlier ``error.png``: the
  folder then holds the figure alone (written through :func:`vaultgram.io.files.output_folder`);
* ``DIR.error.png`` beside it when ``DIR`` holds a result: that result stays as it was.

A run that succeeds removes both error figures of earlier runs (:func:`clear_error_figures`): they
no longer describe the folder.

Example
-------
>>> import tempfile
>>> from vaultgram.domain import load_domain
>>> from vaultgram.errors import DomainError
>>> out = Path(tempfile.mkdtemp()) / "out"
>>> try:
...     with error_figure(out, load_domain("examples/l_shape.json")):
...         raise DomainError("a fold near (1, 1)", places=[[(1, 1), (1.2, 1), (1.2, 1.2)]])
... except DomainError as exc:
...     print(str(exc).endswith(f"(drawn in {out / 'error.png'})"), sorted(p.name for p in out.iterdir()))
True ['error.png']
"""

from __future__ import annotations

import textwrap
from contextlib import contextmanager
from pathlib import Path
from typing import Iterator

import numpy as np

from vaultgram.errors import DomainError, FormFindingError
from vaultgram.io.figures import style

NAME = "error.png"


def error_figure_path(out: Path) -> Path:
    """Where the error figure of a run into ``out`` goes (see the module's docstring)."""
    out = Path(out)
    held = [p.name for p in out.iterdir()] if out.is_dir() else []
    return out / NAME if set(held) <= {NAME} else out.with_name(f"{out.name}.{NAME}")


def clear_error_figures(out: Path) -> None:
    """Remove the error figures earlier failed runs left in and beside ``out``."""
    out = Path(out)
    for path in (out / NAME, out.with_name(f"{out.name}.{NAME}")):
        path.unlink(missing_ok=True)


@contextmanager
def error_figure(out: Path, domain) -> Iterator[None]:
    """Run the block; a :class:`DomainError` or :class:`FormFindingError` with ``places`` leaves its
    figure (:func:`error_figure_path`) and says so at the end of its message, then goes on up. A block
    that succeeds clears the error figures of earlier runs."""
    try:
        yield
    except (DomainError, FormFindingError) as exc:
        if not exc.places:
            raise
        path = error_figure_path(out)
        write_error_figure(path, domain, exc)
        exc.args = (f"{exc} (drawn in {path})", *exc.args[1:])
        raise
    clear_error_figures(out)


def _zoom(ax, domain, places: list) -> None:
    """An inset in the upper right corner: the places and the boundaries near them, enlarged (a folded
    face is a speck in the whole plan)."""
    from vaultgram.io.figures.topology import rings

    allxy = np.vstack(places)
    lo, hi = allxy.min(axis=0), allxy.max(axis=0)
    pad = max(float((hi - lo).max()), 1e-9) * 0.6
    inset = ax.inset_axes([0.64, 0.64, 0.35, 0.35])
    style.lines(inset, style.polyline_segments([*rings(domain), *domain.curves]), "zoom-boundaries", "0.3", 1.0)
    style.polygons(inset, places, "zoom-places", "tab:red", edgecolor="black", width=0.5)
    inset.set_xlim(lo[0] - pad, hi[0] + pad)
    inset.set_ylim(lo[1] - pad, hi[1] + pad)
    inset.set_aspect("equal")
    inset.set_xticks([])
    inset.set_yticks([])
    inset.set_title("enlarged", fontsize=7)


def write_error_figure(path: Path, domain, exc: DomainError) -> None:
    """The domain's boundaries and features, the places of ``exc`` filled red (each also marked, so a
    face too small to see at this scale still shows), the message as the title; PNG, atomically
    (``DIR/error.png`` through a staging folder: the folder holds it alone)."""
    from vaultgram.io.figures.topology import draw_boundaries
    from vaultgram.io.files import output_folder

    fig, ax = style.new_figure()
    draw_boundaries(ax, domain, np.zeros((0, 2, 2)))
    places = [np.asarray(p, dtype=float).reshape(-1, 2) for p in exc.places]
    style.polygons(ax, places, "places", "tab:red", edgecolor="tab:red", width=1.0, zorder=5)
    marks = np.array([p.mean(axis=0) for p in places])
    ax.scatter(marks[:, 0], marks[:, 1], s=150, facecolors="none", edgecolors="tab:red", linewidths=1.5, zorder=6,
               gid="place-marks")
    style.plan(ax)
    ax.set_title("")  # not the boundaries': the message
    ax.set_title("\n".join(textwrap.wrap(str(exc), 110)[:6]), fontsize=7, loc="left")
    fig.subplots_adjust(top=0.88)
    _zoom(ax, domain, places)
    if path.name == NAME:
        with output_folder(path.parent) as stage:
            style.save(fig, stage / NAME)
    else:
        style.save(fig, path)
