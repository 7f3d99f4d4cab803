"""Match tables kept across rollbacks: a search that comes back to a graph state reuses its matches.

Exploration (issue 13) steps through states with the undo journal: it rolls the graph back to a
choice point and runs the same strategy step again with another option, and a completion starts
with the step at which the run stopped, at the very state where that step's options were found.
Each such step begins with a whole-graph search of its rules (with host functions in their
conditions, the costliest part of a run). A :class:`TableMemo` given to a
:class:`~.strategy.Runner` keeps the match table of each search, keyed by the rule, its parameter
values and :meth:`HostGraph.state_id` (the same again after a rollback to that state, different for
every other state), so that the second search at a state is a look-up. Results of a search depend
only on the graph, the rule and its parameters, so a hit is exactly what a new search would find.

Tables are kept up to a budget of rows, the least recently used dropped first.
"""

from __future__ import annotations

from typing import Hashable

from .columnar import Table

#: Rows of match tables a memo keeps by default (a few MB of ids).
DEFAULT_ROWS = 1 << 18


class TableMemo:
    """Match tables by (rule key, graph state), least recently used dropped beyond ``max_rows``
    (each table counts one row more than it has, so that empty ones count too).

    >>> import numpy as np
    >>> memo = TableMemo(max_rows=5)
    >>> two = Table({"a": np.arange(2)}, {}, np.arange(2))
    >>> memo.put(("r", 1), two); memo.put(("r", 2), two)  # 2 + 1 and 2 + 1: over the budget
    >>> memo.get(("r", 1)), memo.get(("r", 2)) is two, memo.hits, memo.misses
    (None, True, 1, 1)
    """

    def __init__(self, max_rows: int = DEFAULT_ROWS):
        self.max_rows = max_rows
        self._tables: dict[Hashable, Table] = {}
        self._rows = 0
        self.hits = 0
        self.misses = 0

    def get(self, key: Hashable) -> Table | None:
        """The table stored under ``key`` (now the most recently used), or None."""
        table = self._tables.pop(key, None)
        if table is None:
            self.misses += 1
            return None
        self._tables[key] = table
        self.hits += 1
        return table

    def put(self, key: Hashable, table: Table) -> None:
        """Keep ``table`` under ``key``, dropping the least recently used beyond the budget (a table
        larger than the whole budget is not kept)."""
        if table.rows + 1 > self.max_rows:
            return
        old = self._tables.pop(key, None)
        self._rows += table.rows + 1 - (old.rows + 1 if old is not None else 0)
        self._tables[key] = table
        while self._rows > self.max_rows:
            oldest = next(iter(self._tables))
            self._rows -= self._tables.pop(oldest).rows + 1

    def __len__(self) -> int:
        return len(self._tables)
