"""Whole-graph matching with numpy: the same search plans, executed a column at a time.

A full search (every match of a rule) runs the plan's steps over a *table* of partial matches, one
numpy column per bound variable, instead of one partial match at a time:

* ``Scan`` is a cross join with the nodes of the wanted types (from the type index);
* ``Extend`` gathers, for every row, the half-edges of its start node from a CSR incidence array,
  then keeps those of the right type, direction and end type that respect injectivity (or that
  close onto the already bound end);
* ``Check`` and inline constraints evaluate the compiled condition row by row (conditions are
  arbitrary expressions; they only run on the rows that survived the structural steps);
* NACs are an anti-join: the NAC's plan runs from the table and the rows it extends are dropped.

The incidence arrays are built from the host graph once per graph version (:func:`graph_arrays`).
Incremental re-matching near a change still uses the depth-first matcher, which is cheaper for one
anchor. Both are checked against each other and against networkx in the tests.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, field

import numpy as np

from .checker import Condition
from .graph import HostGraph
from .plan import Bound, Check, Extend, Scan, Step


@dataclass(frozen=True)
class GraphArrays:
    """Typed incidence of a host graph as flat arrays (half-edges sorted by node)."""

    version: int
    code: dict[str, int]  # type name -> small integer code
    node_code: np.ndarray  # node id -> type code (-1 for ids not in use)
    he_ptr: np.ndarray  # CSR pointer over node ids: half-edges of node n are he_ptr[n]:he_ptr[n+1]
    he_edge: np.ndarray  # edge id of each half-edge
    he_other: np.ndarray  # node at the other end
    he_code: np.ndarray  # edge type code
    he_source: np.ndarray  # True where the half-edge's node is the edge's source
    degrees: dict = field(default_factory=dict, compare=False)  # edge types -> degree per node (_degrees)


#: Attribute values compared as one numpy array (Python compares them the same way).
_NUMBERS = frozenset((bool, int, float))
_CACHE: "weakref.WeakKeyDictionary[HostGraph, GraphArrays]" = weakref.WeakKeyDictionary()


def forget_arrays(g: HostGraph) -> None:
    """Drop the cached arrays of ``g`` (benchmarks use it to time a search from scratch)."""
    _CACHE.pop(g, None)


def graph_arrays(g: HostGraph) -> GraphArrays:
    """The incidence arrays of ``g``, rebuilt only when its structure changed since the last call."""
    cached = _CACHE.get(g)
    if cached is not None and cached.version == g.version:
        return cached
    node_code, edge_code, edge_ends = g.arrays()
    n_ids = len(node_code)
    alive = np.flatnonzero(edge_code >= 0)
    m = len(alive)
    eids, ends, ecode = alive, edge_ends[alive], edge_code[alive]
    node = np.concatenate([ends[:, 0], ends[:, 1]])
    order = np.argsort(node, kind="stable")
    counts = np.bincount(node, minlength=n_ids)
    he_ptr = np.zeros(n_ids + 1, dtype=np.int64)
    np.cumsum(counts, out=he_ptr[1:])
    arrays = GraphArrays(
        version=g.version,
        code=g.type_code,
        node_code=node_code.copy(),
        he_ptr=he_ptr,
        he_edge=np.concatenate([eids, eids])[order],
        he_other=np.concatenate([ends[:, 1], ends[:, 0]])[order],
        he_code=np.concatenate([ecode, ecode])[order],
        he_source=np.concatenate([np.ones(m, bool), np.zeros(m, bool)])[order],
    )
    _CACHE[g] = arrays
    return arrays


class Table:
    """Partial matches as columns: node variables and edge variables, all of the same length.

    ``origin`` is, for each row, the index of the row of the starting table it grew from (NACs use
    it to know which matches they extend).
    """

    def __init__(self, nodes: dict[str, np.ndarray], edges: dict[str, np.ndarray], origin: np.ndarray):
        self.nodes = nodes
        self.edges = edges
        self.origin = origin
        self.rows = len(origin)

    @classmethod
    def start(cls, given: dict[str, int]) -> "Table":
        """One row binding the given node variables (none: the single empty partial match)."""
        return cls({k: np.array([v], dtype=np.int64) for k, v in given.items()}, {}, np.zeros(1, dtype=np.int64))

    @classmethod
    def concat(cls, parts: list["Table"]) -> "Table":
        """The rows of ``parts`` one after the other (the parts without rows may lack the columns of
        steps they never reached, and add nothing)."""
        full = [t for t in parts if t.rows]
        if len(full) <= 1:
            return full[0] if full else parts[0]
        # a column at a time, each part's column let go once joined: memory is the parts plus one column
        nodes = {k: np.concatenate([t.nodes.pop(k) for t in full]) for k in list(full[0].nodes)}
        edges = {k: np.concatenate([t.edges.pop(k) for t in full]) for k in list(full[0].edges)}
        return cls(nodes, edges, np.concatenate([t.origin for t in full]))

    def take(self, index: np.ndarray) -> "Table":
        return Table({k: v[index] for k, v in self.nodes.items()}, {k: v[index] for k, v in self.edges.items()},
                     self.origin[index])

    def reorder(self, index: np.ndarray) -> "Table":
        """The rows in the order ``index`` (a permutation), in place a column at a time (so that only
        one column is copied at once, not the whole table)."""
        for columns in (self.nodes, self.edges):
            for k in columns:
                columns[k] = columns[k][index]
        self.origin = self.origin[index]
        return self

    def filter(self, mask: np.ndarray) -> "Table":
        return self.take(np.flatnonzero(mask))

    def column(self, var: str) -> np.ndarray:
        return self.nodes[var] if var in self.nodes else self.edges[var]


def _type_mask(arrays: GraphArrays, types) -> np.ndarray:
    """A boolean lookup over type codes: True for the given type names."""
    mask = np.zeros(len(arrays.code) + 1, dtype=bool)
    mask[[arrays.code[t] for t in types]] = True
    return mask


#: The most partial matches a step takes at once. A larger table is cut into chunks of this many
#: rows, each run through the rest of the plan on its own, so that memory stays proportional to the
#: graph plus the matches found: a 4-cycle at 10^6 nodes would otherwise hold every open 3-path
#: (18 million rows) before closing them (issue 18).
CHUNK_ROWS = 1 << 17


def run_columnar(
    g: HostGraph, plan: list[Step], table: Table, values: dict, rule: str, chunk: int | None = None
) -> Table:
    """Execute a plan over a table of partial matches; return the table of complete ones, in the
    order a single pass would give (chunks are concatenated in order)."""
    return _run_from(g, graph_arrays(g), plan, 0, table, values, rule, chunk or CHUNK_ROWS)


def _run_from(g: HostGraph, arrays: GraphArrays, plan: list[Step], first: int, table: Table, values: dict,
              rule: str, chunk: int) -> Table:
    """Steps ``first:`` of the plan over ``table``, cutting a table of more than ``chunk`` rows into
    chunks that each run the remaining steps (depth first over chunks: at most one chunk per step
    is alive)."""
    for i in range(first, len(plan)):
        if table.rows == 0:
            return table
        if table.rows > chunk:
            return Table.concat([_run_from(g, arrays, plan, i, table.take(np.arange(lo, min(lo + chunk, table.rows))),
                                           values, rule, chunk) for lo in range(0, table.rows, chunk)])
        table, checks = _PHASES[type(plan[i])](g, arrays, plan[i], table)
        table = _check_rows(g, table, checks, values, rule)
    return table


def _scan_phase(g: HostGraph, arrays: GraphArrays, step: Scan, table: Table):
    return _scan(g, arrays, step, table), step.node.checks


def _extend_phase(g: HostGraph, arrays: GraphArrays, step: Extend, table: Table):
    checks = step.edge.checks + (step.end_node.checks if step.end_node is not None else ())
    return _extend(arrays, step, table), checks


def _check_phase(g: HostGraph, arrays: GraphArrays, step: Check, table: Table):
    return table, (step.condition,)


def _bound_phase(g: HostGraph, arrays: GraphArrays, step: Bound, table: Table):
    """Rows whose given node still exists with a fitting type."""
    col = table.nodes[step.node.var]
    ok = (col < len(arrays.node_code)) & (col >= 0)
    ok[ok] = _type_mask(arrays, step.node.types)[arrays.node_code[col[ok]]]
    return table.filter(ok), step.node.checks


#: For each kind of step: (graph, arrays, step, table) -> (the table after the step, the conditions
#: its new rows must then pass).
_PHASES = {Scan: _scan_phase, Extend: _extend_phase, Check: _check_phase, Bound: _bound_phase}


def _scan(g: HostGraph, arrays: GraphArrays, step: Scan, table: Table) -> Table:
    candidates = np.flatnonzero(_type_mask(arrays, step.node.types)[arrays.node_code])  # ids in order
    rows = np.repeat(np.arange(table.rows), len(candidates))
    new = np.tile(candidates, table.rows)
    ok = np.ones(len(new), dtype=bool)
    for col in table.nodes.values():
        ok &= col[rows] != new
    out = table.take(rows[ok])
    out.nodes[step.node.var] = new[ok]
    return out


def _extend(arrays: GraphArrays, step: Extend, table: Table) -> Table:
    pe = step.edge
    start = table.nodes[step.start]
    lo, hi = arrays.he_ptr[start], arrays.he_ptr[start + 1]
    counts = hi - lo
    rows = np.repeat(np.arange(table.rows), counts)
    offsets = np.arange(len(rows)) - np.repeat(np.cumsum(counts) - counts, counts)
    he = lo[rows] + offsets
    ok = _type_mask(arrays, pe.types)[arrays.he_code[he]]
    if pe.mode == "out":
        ok &= arrays.he_source[he] == step.forward
    edge = arrays.he_edge[he]
    other = arrays.he_other[he]
    for col in table.edges.values():
        ok &= col[rows] != edge
    if step.end_node is None:
        ok &= other == table.nodes[step.end][rows]
    else:
        ok &= _type_mask(arrays, step.end_node.types)[arrays.node_code[other]]
        for col in table.nodes.values():
            ok &= col[rows] != other
    keep = np.flatnonzero(ok)
    out = table.take(rows[keep])
    out.edges[pe.var] = edge[keep]
    if step.end_node is not None:
        out.nodes[step.end] = other[keep]
    return out


def _degrees(g: HostGraph, types: frozenset) -> np.ndarray:
    """Per node id, its number of edges of ``types``, from the incidence arrays; kept with them, for
    the chunks of one search and the searches until the graph changes (each chunk of a scan over
    10^6 nodes counted every half-edge again)."""
    arrays = graph_arrays(g)
    if types not in arrays.degrees:
        counts = np.diff(arrays.he_ptr)
        owner = np.repeat(np.arange(len(counts)), counts)
        degree = np.bincount(owner[_type_mask(arrays, types)[arrays.he_code]], minlength=len(counts))
        degree.flags.writeable = False  # shared by every search of this version
        arrays.degrees[types] = degree
    return arrays.degrees[types]


def _column_mask(g: HostGraph, test, ids: np.ndarray, rhs) -> np.ndarray:
    """Where a column test holds for the elements ``ids``: on their degrees (numpy), or on their
    attribute: compared against a number as one numpy array per bulk column the values are still in
    (:meth:`HostGraph.bulk_numbers`), the others read as plain values (:func:`_values_mask`)."""
    if test.types is not None:
        return np.asarray(test.op(_degrees(g, test.types)[ids], rhs), dtype=bool)
    mask = np.zeros(len(ids), dtype=bool)
    rest = np.ones(len(ids), dtype=bool)
    if type(rhs) in _NUMBERS:
        for at, numbers in g.bulk_numbers(test.kind, ids, test.attr):
            mask[at] = np.asarray(test.op(numbers, rhs), dtype=bool).reshape(len(at))
            rest[at] = False
    at = np.flatnonzero(rest)
    mask[at] = _values_mask(test.op, g.values(test.kind, ids[at].tolist(), test.attr), rhs)
    return mask


def _values_mask(op, values: list, rhs) -> np.ndarray:
    """Where ``op(value, rhs)`` holds: numbers compared as one numpy array (Python compares them the
    same way), other values one by one."""
    if type(rhs) in _NUMBERS and set(map(type, values)) <= _NUMBERS:
        return np.asarray(op(np.array(values), rhs), dtype=bool).reshape(len(values))
    return np.fromiter((bool(op(v, rhs)) for v in values), dtype=bool, count=len(values))


def _check_columns(g: HostGraph, table: Table, conditions: tuple[Condition, ...], values: dict, rule: str) -> Table:
    """Evaluate the conditions that have a vectorised form, for every row at once, in order."""
    for c in conditions:
        test = c.column
        try:
            keep = _column_mask(g, test, table.column(test.var), test.rhs(g, values))
        except Exception as exc:  # e.g. a comparison with a value of the wrong kind
            raise c.failure(rule, exc) from None
        table = table.filter(keep)
    return table


def _check_rows(g: HostGraph, table: Table, conditions: tuple[Condition, ...], values: dict, rule: str) -> Table:
    """Keep the rows where all conditions hold: first those with a vectorised form, on every row at
    once, then the others row by row (they are arbitrary expressions), in their written order."""
    lead = next((k for k, c in enumerate(conditions) if c.column is None), len(conditions))
    if lead and table.rows:
        table = _check_columns(g, table, conditions[:lead], values, rule)
        conditions = conditions[lead:]
    if not conditions or table.rows == 0:
        return table
    names = [*table.nodes, *table.edges]
    columns = [table.column(v).tolist() for v in names]
    keep = np.ones(table.rows, dtype=bool)
    binding = dict(values)
    for i in range(table.rows):
        for name, col in zip(names, columns):
            binding[name] = col[i]
        for c in conditions:
            try:
                if not c.fn(g, binding):
                    keep[i] = False
                    break
            except Exception as exc:  # a host function or arithmetic failing on this graph
                raise c.failure(rule, exc) from None
    return table.filter(keep)


def nac_rows(g: HostGraph, plan: list[Step], table: Table, values: dict, rule: str) -> np.ndarray:
    """Boolean mask of the rows of ``table`` around which a NAC (given by its plan) can be matched."""
    start = Table(table.nodes, table.edges, np.arange(table.rows))
    found = run_columnar(g, plan, start, values, rule)
    mask = np.zeros(table.rows, dtype=bool)
    mask[found.origin] = True
    return mask
