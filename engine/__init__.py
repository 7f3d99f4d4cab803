"""A general typed graph-rewriting engine (it knows nothing about vaults).

A rulebook (:mod:`.rulebook`) is checked once from rule files (:mod:`vaultgram.grammar`); a
:class:`~.graph.HostGraph` of its schema is rewritten by a :class:`~.strategy.Runner`, which records
every application in a trace (:mod:`.trace`). Errors caused by input are in :mod:`.errors`.

>>> from vaultgram.engine.graph import HostGraph
>>> from vaultgram.engine.rulebook import rulebook_from_text
>>> from vaultgram.engine.strategy import Runner
>>> book = rulebook_from_text('''
... schema s { node A { w: int = 0 } }
... rule bump { match { a: A { w < 2 } } set a.w = a.w + 1 }
... strategy grow { bump fixpoint }
... ''')
>>> g = HostGraph(book.schema)
>>> n = g.add_node("A")
>>> [report.applications for report in Runner(book, g).run("grow")], g.get(n, "w")
([2], 2)
"""
