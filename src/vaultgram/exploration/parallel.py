"""Evaluating variants in parallel: in this process, in a process pool, or on a Dask cluster.

Every backend maps :func:`~.evaluate.evaluate_or_error` over the jobs and returns the evaluations in
the order of the jobs, so the files written do not depend on the backend or the number of workers.
Dask (``--scheduler ADDRESS``, the optional extra ``vaultgram[dask]``) is for users who outgrow one
machine: its workers need vaultgram and, for a ``--rules`` folder, the same path.
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
from typing import Sequence

from vaultgram.errors import VaultgramError
from vaultgram.exploration.evaluate import Evaluation, Job, evaluate_or_error

CONNECT_TIMEOUT = "5s"


def connect(address: str):
    """A Dask client of the scheduler at ``address``; one clear error when it cannot be reached."""
    try:
        from distributed import Client
    except ImportError:
        raise VaultgramError("--scheduler needs Dask: pip install 'vaultgram[dask]'") from None
    try:
        return Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as exc:
        raise VaultgramError(f"--scheduler {address}: cannot reach the Dask scheduler ({exc})") from None


def check_workers(workers: int) -> None:
    """``--workers`` is at least 1."""
    if workers < 1:
        raise VaultgramError(f"--workers must be at least 1, got {workers}")


def evaluate_all(jobs: Sequence[Job], workers: int = 1, client=None) -> list[Evaluation]:
    """The evaluations of ``jobs``, in order: on the Dask ``client`` if given, else with ``workers``
    processes (1: in this process)."""
    if client is not None:
        return client.gather(client.map(evaluate_or_error, list(jobs), pure=False))
    if workers == 1 or len(jobs) <= 1:
        return [evaluate_or_error(job) for job in jobs]
    with ProcessPoolExecutor(max_workers=workers) as pool:
        return list(pool.map(evaluate_or_error, jobs))
