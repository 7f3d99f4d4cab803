"""vaultgram: structural patterns for masonry vaults and funicular shells.

The package has three layers:

* :mod:`vaultgram.grammar` -- the rule language (a lark grammar and its AST);
* :mod:`vaultgram.engine` -- a general typed graph-rewriting engine that knows nothing about vaults;
* the vault pipeline (the other modules of this package), which registers its node and edge types and
  geometric helper functions with the engine and runs the rulebook in :mod:`vaultgram.rules`.
"""

__version__ = "0.1.0"
