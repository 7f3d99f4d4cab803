"""``python -m vaultgram`` runs the command-line interface.

An interrupt (Ctrl-C) that lands while the interface is still being imported, or after the command
has finished, ends the run with the shell's code for it (130) and no traceback; one that lands
during a command is handled by the command (its output folder stays complete or untouched).
"""

import sys

try:
    from vaultgram.cli import main

    main()
except KeyboardInterrupt:
    sys.exit(130)
