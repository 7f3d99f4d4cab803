"""Interrupts that end a run where they land, also inside an import.

Python raises a signal's exception (``KeyboardInterrupt`` for SIGINT; the output folder's
``SystemExit(143)`` for SIGTERM) in whatever bytecode runs when the handler is called. Inside the
import system's own code that may be a weak-reference callback of a module lock, whose exceptions
Python prints as ``Exception ignored in ...`` with a traceback and then drops: the run goes on as if
no one had asked it to stop (seen once in 80 interrupts sent 0.06-0.6 s into ``vaultgram design``,
while it imports). The handlers here put such a signal off until the run is back in its own code: the
signal is sent again after :data:`RETRY` seconds (by SIGALRM), to whichever handler is set by then.
"""

from __future__ import annotations

import os
import signal

#: Seconds after which a signal that landed inside the import system is sent again.
RETRY = 0.01
_PENDING: list[int] = []


def in_import_system(frame) -> bool:
    """Whether ``frame`` (the one a signal handler interrupted) is the import system's own code, where
    an exception may land in a callback that drops it.

    >>> import sys
    >>> in_import_system(sys._getframe()), in_import_system(None)
    (False, False)
    """
    return frame is not None and frame.f_code.co_filename.startswith("<frozen importlib")


def deferred(raise_for):
    """A signal handler that calls ``raise_for(signum)`` (which raises the signal's exception), unless
    the signal landed inside the import system: then it is sent again shortly (:func:`_send_again`)."""

    def handler(signum, frame):
        if in_import_system(frame):
            _PENDING.append(signum)
            signal.signal(signal.SIGALRM, _send_again)
            signal.setitimer(signal.ITIMER_REAL, RETRY)
            return
        raise_for(signum)

    return handler


def _send_again(_signum, _frame) -> None:
    """SIGALRM: the signals put off, sent to this process again, in the order they came."""
    while _PENDING:
        os.kill(os.getpid(), _PENDING.pop(0))


def _interrupt(_signum) -> None:
    raise KeyboardInterrupt


def handle_interrupts() -> None:
    """SIGINT raises ``KeyboardInterrupt`` as Python's own handler does, but never inside the import
    system (:func:`deferred`). For the program's own process: its first step."""
    signal.signal(signal.SIGINT, deferred(_interrupt))
