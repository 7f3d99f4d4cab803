"""``python -m vaultgram`` runs the command-line interface."""

from vaultgram.cli import main

main()
