"""``python -m vaultgram`` and the ``vaultgram`` command run the command-line interface (:func:`run`).

An interrupt (Ctrl-C) that lands while the interface is still being imported, or after the command
has finished, ends the run with the shell's code for it (130) and no traceback; one that lands
during a command is handled by the command (its output folder stays complete or untouched).
"""

import sys


def run() -> None:
    """The program: interrupts handled first (:func:`vaultgram.interrupts.handle_interrupts`), then the
    interface imported and run."""
    try:
        from vaultgram.interrupts import handle_interrupts

        handle_interrupts()
        from vaultgram.cli import main

        main()
    except KeyboardInterrupt:
        sys.exit(130)


if __name__ == "__main__":
    run()
