"""Hypothesis strategies and helpers shared by the test suites (importable as ``strategies``, since
``tests`` is on the path).

* :mod:`strategies.rules` -- the small test schema (types A, B, C and edges E, D) and ``book()``, a
  rulebook of that schema plus some rules;
* :mod:`strategies.graphs` -- random typed host graphs of that schema (``typed_graphs()``), built by
  ``build_graph()`` in any insertion order.
"""
