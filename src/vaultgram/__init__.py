"""vaultgram: structural patterns for masonry vaults and funicular shells.

The package has three layers:

* :mod:`vaultgram.grammar` -- the rule language (a lark grammar and its AST);
* :mod:`vaultgram.engine` -- a general typed graph-rewriting engine that knows nothing about vaults;
* the vault pipeline (the other modules of this package), which registers its node and edge types and
  geometric helper functions with the engine and runs the rulebook in :mod:`vaultgram.rules`.

The Python API (:mod:`vaultgram.api`) is here by name, loaded on first use so that ``import vaultgram``
and the command line stay quick::

    import vaultgram
    result = vaultgram.design("plan.3dm", zmax=3.0)
"""

__version__ = "0.1.0"

__all__ = ["load", "decompose", "mesh", "formfind", "tessellate", "design", "save", "Result", "__version__"]


def __getattr__(name: str):
    """The API's functions (:mod:`vaultgram.api`), imported when first asked for."""
    if name in __all__ and name != "__version__":
        from vaultgram import api

        return getattr(api, name)
    raise AttributeError(f"module 'vaultgram' has no attribute {name!r}")
