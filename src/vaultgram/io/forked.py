"""Independent writes at once, in forked processes: the files of a 10^5-face design are a few
seconds of formatting numbers (JSON, OBJ), one core's work per file, and the machine has more.

:func:`run_all` runs each job in a child forked from this process (it has the job's data already:
nothing is pickled on the way in) but the last, which runs here, then waits for all. An exception in
a child (a full disk, an interrupt) comes back pickled and is raised here, the first one in the order
of the jobs, so that a caller sees what it would have seen in one process. The children write into
the caller's staging folder (:func:`vaultgram.io.files.output_folder`), which moves nothing until
every one is done.

>>> import tempfile
>>> folder = Path(tempfile.mkdtemp())
>>> run_all([lambda: (folder / "a").write_text("a"), lambda: (folder / "b").write_text("b")])
>>> sorted(p.name for p in folder.iterdir())
['a', 'b']
>>> try:
...     run_all([lambda: 1 / 0, lambda: None])
... except ZeroDivisionError as exc:
...     print(exc)
division by zero
"""

from __future__ import annotations

import signal
from pathlib import Path  # noqa: F401 -- the doctest's
from typing import Callable, Sequence


def run_all(jobs: Sequence[Callable[[], object]]) -> None:
    """Run every job, all but the last in forked children; raise the first failure."""
    if not jobs:
        return
    import multiprocessing  # here: the command line starts without it

    context = multiprocessing.get_context("fork")
    started = []
    try:
        for job in jobs[:-1]:
            mine, theirs = context.Pipe(duplex=False)
            process = context.Process(target=_child, args=(job, theirs), daemon=True)
            process.start()
            theirs.close()
            started.append((process, mine))
        jobs[-1]()
        for process, conn in started:
            failure = _outcome(process, conn)
            if failure is not None:
                raise failure
    finally:
        for process, conn in started:
            if process.is_alive():
                process.terminate()
            process.join()
            conn.close()


def _outcome(process, conn) -> BaseException | None:
    """The exception the child sent, or None when it finished."""
    try:
        failure = conn.recv()
    except EOFError:
        failure = RuntimeError(f"a writing process ended without a word (exit code {process.exitcode})")
    process.join()
    return failure


def _child(job, conn) -> None:
    """Run ``job`` in the child and send back None or its exception."""
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # the parent's handler would unwind the parent's stack
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # an interrupt is the parent's: it ends the children
    try:
        job()
        outcome = None
    except BaseException as exc:  # noqa: BLE001 -- raised again in the parent
        outcome = exc
    try:
        conn.send(outcome)
    except Exception:  # noqa: BLE001 -- an exception that does not pickle: its text
        conn.send(RuntimeError(f"{type(outcome).__name__}: {outcome}"))
    conn.close()
