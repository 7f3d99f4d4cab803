"""Exploring topology variants (the paper's conclusion): a bounded search over the rulebook's choice points.

The rulebook's ``choose`` steps are choice points (docs/exploration.md lists them). :mod:`.program`
runs the decomposition between choice points, :mod:`.search` walks the states they open breadth-first
with the graph's undo journal, :mod:`.layout` tells variants apart (hash, exact check),
:mod:`.evaluate` rebuilds, meshes and measures each variant, :mod:`.ranking` scores them and marks the
Pareto front, :mod:`.parallel` spreads the evaluation over processes or a Dask cluster,
:mod:`.gallery` draws them, and :mod:`.explore` ties it together for ``vaultgram explore`` and
``vaultgram replay``.
"""
