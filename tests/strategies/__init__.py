"""Hypothesis strategies and helpers shared by the test suites (importable as ``strategies``, since
``tests`` is on the path).

* :mod:`strategies.rules` -- the small test schema (types A, B, C and edges E, D) and ``book()``, a
  rulebook of that schema plus some rules;
* :mod:`strategies.graphs` -- random typed host graphs of that schema (``typed_graphs()``), built by
  ``build_graph()`` in any insertion order;
* :mod:`strategies.domains` -- random plans: star-shaped polygons, polygons with holes, convex domains
  with a hole, rectangles with point and curve features, squares with curves;
* :mod:`strategies.meshes` -- random planar meshes: perturbed grids.

A strategy that draws a domain or a mesh belongs here, so that every stage's tests can draw the same
inputs; a strategy that only one test's arguments need stays beside it.
"""
