"""Progress of a run on stderr: each stage of the pipeline as it starts and ends, and a progress bar
(tqdm) for the long loops (smoothing iterations, horizontal-equilibrium iterations).

Nothing is reported unless a command turns it on (:func:`reporting`), and then only to a terminal:
a run whose stderr is a file or a pipe, or with ``--quiet``, stays silent. The stages call
:func:`started` and :func:`ended` (the pipeline's timer does), a loop makes a :func:`ticker` and
calls it once per iteration; both cost one context-variable lookup when nothing is reported, and
tqdm is imported only when a bar is drawn.

Example
-------
>>> import io
>>> out = io.StringIO()
>>> with reporting(True, out, force=True):
...     started("smooth")
...     tick = ticker("smooth", 3)
...     for _ in range(3):
...         tick()
...     ended("smooth", 0.25)
>>> [line for line in out.getvalue().splitlines() if line.startswith("vaultgram")]
['vaultgram: smooth ...', 'vaultgram: smooth done in 0.250 s']
"""

from __future__ import annotations

import sys
import time
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field

__all__ = ["reporting", "started", "ended", "timed", "ticker", "note"]


@dataclass
class _Reporter:
    """Where the lines go, and the bar of the loop running now (one at a time)."""

    stream: object
    bars: dict = field(default_factory=dict)

    def line(self, text: str) -> None:
        self.close_bars()
        print(f"vaultgram: {text}", file=self.stream, flush=True)

    def bar(self, stage: str, total: int):
        from tqdm import tqdm

        self.close_bars()
        self.bars[stage] = tqdm(total=total, desc=f"vaultgram: {stage}", file=self.stream, leave=False,
                                mininterval=0.2, unit="it", dynamic_ncols=True)
        return self.bars[stage]

    def close_bars(self) -> None:
        for bar in self.bars.values():
            bar.close()
        self.bars.clear()


_REPORTER: ContextVar[_Reporter | None] = ContextVar("vaultgram_progress", default=None)


@contextmanager
def reporting(enabled: bool = True, stream=None, force: bool = False):
    """Report progress to ``stream`` (default stderr) inside the block, if ``enabled`` and the stream is
    a terminal (or ``force``)."""
    stream = sys.stderr if stream is None else stream
    on = enabled and (force or bool(getattr(stream, "isatty", lambda: False)()))
    token = _REPORTER.set(_Reporter(stream) if on else None)
    try:
        yield
    finally:
        reporter = _REPORTER.get()
        if reporter is not None:
            reporter.close_bars()
        _REPORTER.reset(token)


def note(text: str) -> None:
    """A line of progress (a command's own steps: reading the input, writing the outputs)."""
    reporter = _REPORTER.get()
    if reporter is not None:
        reporter.line(text)


def started(stage: str) -> None:
    """A stage starts."""
    note(f"{stage} ...")


def ended(stage: str, seconds: float) -> None:
    """A stage ended after ``seconds`` (its loop's bar, if any, is closed)."""
    note(f"{stage} done in {seconds:.3f} s")


@contextmanager
def timed(timings: dict | None, stage: str):
    """Add the seconds the ``with`` block takes to ``timings[stage]`` (nothing if ``timings`` is None),
    and report the stage's start and end."""
    start = time.perf_counter()
    started(stage)
    yield
    seconds = time.perf_counter() - start
    ended(stage, seconds)
    if timings is not None:
        timings[stage] = timings.get(stage, 0.0) + seconds


def ticker(stage: str, total: int):
    """A function to call once per iteration of a loop of at most ``total`` iterations: it advances
    the stage's progress bar (a no-op when nothing is reported). The bar closes when the stage ends."""
    reporter = _REPORTER.get()
    if reporter is None or total <= 1:
        return _nothing
    bar = reporter.bar(stage, total)
    return lambda: bar.update(1)


def _nothing() -> None:
    return None
