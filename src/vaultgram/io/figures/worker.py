"""Figures off the critical path: one background process draws each stage's figures while the later
stages run (issue 15: the figures of a small design cost more than the design).

:class:`FigureWorker` is the pipeline's ``on_stage`` callback (:func:`vaultgram.pipeline.design`).
When the decomposition is done it forks one process (the decomposition's graph cannot be pickled, a
forked child has it already); each later stage (the mesh, its supports, the thrust network, the
tessellation) reaches the process pickled through a pipe (pickle's protocol 5, which takes numpy
arrays whole: a 10^6-face thrust network in a third of the time of the pipe's default protocol 4),
and the process draws every figure whose stages have all arrived
(:attr:`vaultgram.io.figures.FigureSpec.final`), in the catalogue's order within each step.
:meth:`FigureWorker.finish` waits for the last figure: the wait is all the figures cost the run.
The process writes into the run's staging folder (:func:`vaultgram.io.files.output_folder`), so the
output folder stays complete or untouched; on a failure or interrupt :meth:`FigureWorker.close` ends
the process before the staging folder is removed. The figures are the same bytes as
:func:`vaultgram.io.figures.write_figures` writes in one process.

Given the run's data ``formats``, the process also writes the mesh's files (and works out its quality
for ``summary.json``) when the supports arrive, and the thrust network's when it arrives, if the mesh
has at least :data:`BACKGROUND_FACES` faces (:func:`writes_files`): at 10^5 faces they took about 2 s
of the run's writing, and the process has time to spare while form finding and the tessellation run
(its figures took 12 s of a 38 s design). On a smaller mesh the figures take longer than the later
stages, so the process is the one the run waits for, and the files are written after the design
(:func:`vaultgram.io.outputs.write_design` writes what the process did not).

Example
-------
>>> import tempfile
>>> from vaultgram.domain import load_domain
>>> from vaultgram.pipeline import design
>>> out = Path(tempfile.mkdtemp())
>>> with FigureWorker(out) as worker:
...     result = design(load_domain("examples/l_shape.json"), spacing=0.05, tessellation=None,
...                     on_stage=worker)
...     names = worker.finish()
>>> names[:2], (out / "figures" / "panel.png").is_file()
(['delaunay', 'skeleton'], True)
"""

from __future__ import annotations

import pickle
import queue
import signal
import threading
import time
import traceback
from dataclasses import replace
from pathlib import Path

#: The stages the pipeline reports after the decomposition, in its order (:class:`vaultgram.io.figures.Stages` fields).
LATER = ("mesh", "supports", "network", "tessellation")
#: The stages whose data files the process writes, from this many mesh faces on.
BACKGROUND = ("mesh", "network")
BACKGROUND_FACES = 20_000


def writes_files(formats, mesh, from_faces: int = BACKGROUND_FACES) -> bool:
    """Whether the figure process writes the data files of :data:`BACKGROUND` for a run with these
    ``formats`` (None: figures only) and this mesh: if it has ``from_faces`` faces or more."""
    return formats is not None and len(mesh.faces) >= from_faces


class FigureWorker:
    """The background figure process of one run, writing into ``out`` (a staging folder)."""

    def __init__(self, out: Path, formats=None, from_faces: int = BACKGROUND_FACES):
        self.out = Path(out)
        self.formats = formats  # the data files' formats, or None: figures only
        self.from_faces = from_faces
        self.process = None
        self.conn = None
        self.sender = None  # the thread that writes the pickled stages into the pipe (_send_all)
        self.outbox: queue.Queue = queue.Queue()
        self.seconds = 0.0  # the figures' own time, in the background process
        self.handover = 0.0  # the run's time handing the stages to the process (pickling them)
        self.domain = None
        self.files: tuple = ()  # the stages whose data files the process writes (BACKGROUND or none)
        self.mesh_quality = None  # the mesh's quality (vaultgram.io.outputs.mesh_quality), if it wrote them

    def __enter__(self) -> FigureWorker:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __call__(self, stage: str, value) -> None:
        """The pipeline reports that ``stage`` is done with this ``value``."""
        if stage == "domain":
            self.domain = value
        elif stage == "decomposition":
            self._start(value)
        elif stage in LATER and self.conn is not None:
            if stage == "mesh":
                self.files = BACKGROUND if writes_files(self.formats, value, self.from_faces) else ()
            start = time.perf_counter()
            self.outbox.put(pickle.dumps((stage, _drawn(stage, value)), protocol=pickle.HIGHEST_PROTOCOL))
            self.handover += time.perf_counter() - start

    def _start(self, decomposition) -> None:
        """Fork the figure process with the domain and the decomposition it inherits."""
        import multiprocessing  # here: the command line starts without it

        from vaultgram.io.figures import Stages

        self.close()
        context = multiprocessing.get_context("fork")
        mine, theirs = context.Pipe()
        data = Stages(self.domain, decomposition)
        self.process = context.Process(target=_serve, args=(data, self.out, theirs, (self.formats, self.from_faces)),
                                       daemon=True)
        self.process.start()
        theirs.close()
        self.conn = mine
        self.outbox = queue.Queue()
        self.sender = threading.Thread(target=_send_all, args=(mine, self.outbox), daemon=True)
        self.sender.start()

    def finish(self) -> list[str]:
        """Wait for every figure of the stages sent; the names of the figures written, in order."""
        if self.conn is None:
            return []
        self.outbox.put(None)
        self.sender.join()
        try:
            status, payload, seconds, self.mesh_quality = self.conn.recv()
        except EOFError:
            status, payload, seconds = "error", "the figure process ended without a word", 0.0
        self.seconds = seconds
        self.close()
        if status == "oserror":
            raise OSError(*payload)
        if status != "ok":
            raise RuntimeError(f"figures: {payload}")
        return payload

    def close(self) -> None:
        """End the process (if still running) and wait for it: nothing writes into ``out`` after this.
        The sender stops when the process has gone (its pipe is broken), before the pipe is closed."""
        if self.process is not None:
            if self.process.is_alive():
                self.process.terminate()
            self.process.join()
            self.process = None
        if self.sender is not None:
            self.outbox.put(None)
            self.sender.join()
            self.sender = None
        if self.conn is not None:
            self.conn.close()
            self.conn = None


def _serve(data, out: Path, conn, files=(None, BACKGROUND_FACES)) -> None:
    """The figure process: draw what is ready, then after each stage received its data files if due
    (``files``: the formats and the mesh size of :func:`writes_files`) and the figures that became
    ready. A thread takes the stages off the pipe as they come, so the pipeline never waits for a
    drawing."""
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # the parent's handler unwinds the parent's stack
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # an interrupt is the parent's to handle: it ends this process
    start = time.process_time()
    inbox: queue.Queue = queue.Queue()
    threading.Thread(target=_receive, args=(conn, inbox), daemon=True).start()
    written: list[str] = []
    quality = None
    try:
        written += _draw_ready(data, out, written)
        for stage, value in iter(inbox.get, ("done", None)):
            data = _with(data, stage, value)
            quality = _write_files(data, stage, out, *files) or quality
            written += _draw_ready(data, out, written)
        reply = ("ok", written, time.process_time() - start, quality)
    except OSError as exc:  # a data file or figure that cannot be written: the parent names it in one line
        reply = ("oserror", (exc.errno, exc.strerror, exc.filename), time.process_time() - start, None)
    except Exception:  # noqa: BLE001 -- reported to the parent, which raises
        reply = ("error", traceback.format_exc(limit=3), time.process_time() - start, None)
    try:
        conn.send(reply)
    except OSError:  # the parent has gone (it failed or was interrupted)
        pass
    conn.close()


def _drawn(stage: str, value):
    """What the process reads of a stage: the tessellation without its solids and without the cut mesh
    and edge tables of its layout, which neither its figures nor its files need (at 10^6 faces they
    were 0.9 of its 1 GB pickle, 0.7 s of the run's time handing it over)."""
    if stage != "tessellation" or value is None:
        return value
    return replace(value, solids=None, layout=replace(value.layout, mesh=None, edges=None))


def _send_all(conn, outbox: queue.Queue) -> None:
    """Write the pickled stages of ``outbox`` into the pipe until None, then ``done``: the pipeline goes
    on while a stage is written (at 10^6 faces the writes took 3.9 s of the run, the figure process
    reading them between its drawings). Stops if the process has gone (the pipe is broken): the
    run learns it from :meth:`FigureWorker.finish`."""
    try:
        for payload in iter(outbox.get, None):
            conn.send_bytes(payload)
        conn.send(("done", None))
    except OSError:
        pass


def _receive(conn, inbox: queue.Queue) -> None:
    """Move the messages of ``conn`` to ``inbox`` until ``done`` (or the parent is gone)."""
    while True:
        try:
            message = conn.recv()
        except (EOFError, OSError):
            message = ("done", None)
        inbox.put(message)
        if message[0] == "done":
            return


def _write_files(data, stage: str, out: Path, formats, from_faces: int) -> dict | None:
    """The data files of the stage just received, if the process writes them (:func:`writes_files`):
    the mesh's once its supports are known (then its quality, returned), the thrust network's."""
    from vaultgram.io.files import collector_paused
    from vaultgram.io.outputs import mesh_quality, write_mesh_files, write_thrust

    if data.mesh is None or not writes_files(formats, data.mesh, from_faces):
        return None
    with collector_paused():  # as write_design writes them
        if stage == "supports":
            write_mesh_files(data.mesh, out, data.supports, plot=False, formats=formats)
            return mesh_quality(data.mesh, data.domain)
        if stage == "network":
            write_thrust(data.network, out, plot=False, formats=formats)
    return None


def _with(data, stage: str, value):
    """``data`` with one more stage; the patch layout (of the decomposition alone) is not made again."""
    new = replace(data, **{stage: value})
    if "layout" in data.__dict__:
        new.__dict__["layout"] = data.layout
    return new


def _draw_ready(data, out: Path, done: list[str]) -> list[str]:
    """Write the figures whose stages are all there and that are not written yet."""
    from vaultgram.io.figures import CATALOGUE, write_figures

    ready = [spec for spec in CATALOGUE if spec.name not in done and spec.ready(data)]
    return [spec.name for spec in write_figures(data, out, ready)]
