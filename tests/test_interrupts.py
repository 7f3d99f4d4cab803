"""Interrupts put off while they land inside the import system (:mod:`vaultgram.interrupts`)."""

import signal
import sys
import time

import pytest

from vaultgram.interrupts import deferred, in_import_system


def _frame_in(filename: str):
    """A frame of code compiled as if it were the file ``filename``."""
    space = {}
    exec(compile("import sys\nframe = sys._getframe()", filename, "exec"), space)
    return space["frame"]


def _interrupt(_signum):
    raise KeyboardInterrupt


@pytest.fixture
def handlers():
    """SIGINT's and SIGALRM's handlers restored after the test."""
    saved = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGALRM)}
    yield
    signal.setitimer(signal.ITIMER_REAL, 0)
    for s, h in saved.items():
        signal.signal(s, h)


def test_the_import_systems_frames_are_told_from_the_programs():
    assert in_import_system(_frame_in("<frozen importlib._bootstrap>"))
    assert not in_import_system(_frame_in("<frozen runpy>"))
    assert not in_import_system(sys._getframe())


def test_a_signal_in_the_programs_code_raises_at_once(handlers):
    with pytest.raises(KeyboardInterrupt):
        deferred(_interrupt)(signal.SIGINT, sys._getframe())


def test_a_signal_inside_the_import_system_is_raised_again_once_out_of_it(handlers):
    """The handler returns (the import system's callback would have dropped the exception) and the
    signal comes again within a few hundredths of a second, to the handler then set, which raises it
    in the program's code."""
    handler = deferred(_interrupt)
    signal.signal(signal.SIGINT, handler)
    handler(signal.SIGINT, _frame_in("<frozen importlib._bootstrap>"))
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        time.sleep(2)
    assert time.monotonic() - start < 1.5
