"""The typed host graph that rules rewrite.

A :class:`HostGraph` stores its nodes and edges, with their attributes, in plain dictionaries by id
(:meth:`HostGraph.to_networkx` gives a networkx ``MultiDiGraph`` copy for any networkx algorithm);
for elements added in bulk (:meth:`HostGraph.add_nodes`, :meth:`HostGraph.add_edges`) their entries
are made from the arrays they came in when first used, as a rewrite of a large graph touches few.
It keeps, current on every change:

* a **type index** (type name -> element ids) so that a search can start from the rarest type;
* **typed adjacency** (node -> edge type -> incident edge ids) so that a search extends along
  exactly the edges a pattern asks for;
* a **rotation system**: the cyclic order of the edges around each node, as in networkx's
  ``PlanarEmbedding``. With an ``angle`` function (given by the host application, e.g. the direction
  of an edge's polyline as it leaves a node) edges are kept sorted counter-clockwise by that angle;
  without one, by edge id (creation order). Faces of a planar graph are walked with it
  (:mod:`vaultgram.engine.embedding`), and ``foreach`` visits neighbours in this order;
* the same typed structure for search loops, read-only: :attr:`HostGraph.incidence` (live
  mappings) and :meth:`HostGraph.arrays` (flat numpy arrays indexed by id, with ``type_code``);
* an **undo log** (journal): every primitive change records its inverse, so an application either
  completes or is rolled back exactly (:meth:`transaction`), and exploration can step back
  (:meth:`mark` / :meth:`rollback`) without copying the graph.

Node and edge ids are integers. Ids are chosen by the caller or allocated from counters that undo
also restores, so replaying the same applications gives the same ids. Every ordering the engine
exposes is by id, never by hash or insertion order.
"""

from __future__ import annotations

import bisect
import functools
import gc
import itertools
import weakref
from contextlib import contextmanager
from dataclasses import dataclass
from typing import TYPE_CHECKING, AbstractSet, Callable, Iterable, Iterator, Mapping, NamedTuple, Sequence

import numpy as np

from .errors import SchemaError
from .schema import TypeSchema

if TYPE_CHECKING:
    import networkx as nx

AngleFunction = Callable[["HostGraph", int, int], float]


def _collector_paused(method):
    """``method`` with Python's cyclic garbage collector paused: a bulk addition made millions of
    small objects (attribute dicts, end pairs), none of them in a cycle, and without the pause the
    collector re-scanned the whole graph over and over (two-thirds of building a 10^6-node graph,
    issue 18; they are made on first use now, but edges added in bulk at nodes already in use
    still make their tables at once). The collector is restored as it was, also on an error."""
    @functools.wraps(method)
    def paused(*args, **kwargs):
        enabled = gc.isenabled()
        gc.disable()
        try:
            return method(*args, **kwargs)
        finally:
            if enabled:
                gc.enable()
    return paused


@dataclass(frozen=True)
class ChangeSet:
    """What a slice of the journal touched: node ids (endpoints of changed edges included) and types."""

    nodes: frozenset[int]
    types: frozenset[str]


class Incidence(NamedTuple):
    """The typed structure of a host graph, for search loops: the graph's own tables, seen read-only.

    They stay current as the graph changes; never change them (only :class:`HostGraph` methods do).
    ``node_type``: node id -> type name; ``edge_type``: edge id -> type name; ``ends``: edge id ->
    (source, target); ``typed``: node id -> edge type name -> ids of the node's edges of that type.
    The entries for elements added in bulk are made when first looked up: look them up by id
    (``ends[e]``), never iterate them or test ``in`` (ask :meth:`HostGraph.has_node` and the like).
    """

    node_type: Mapping[int, str]
    edge_type: Mapping[int, str]
    ends: Mapping[int, tuple[int, int]]
    typed: Mapping[int, Mapping[str, AbstractSet[int]]]


class TypeArrays(NamedTuple):
    """The typed structure as flat arrays indexed by id (-1 where an id is not in use)."""

    node_code: np.ndarray  # node id -> type code
    edge_code: np.ndarray  # edge id -> type code
    edge_ends: np.ndarray  # edge id -> (source, target)


# ----------------------------------------------------------------------------------------------
# The journal: one record per primitive change, which knows how to undo it and what it touched
# ----------------------------------------------------------------------------------------------


def _touch_node(g: "HostGraph", n: int, nodes: set, types: set) -> None:
    nodes.add(n)
    types.add(g._node_type[n] if g.has_node(n) else "")


def _touch_edge(g: "HostGraph", e: int, nodes: set, types: set) -> None:
    if e in g._edge_type or _in_use(g._edge_codes, e):  # has_edge, without a call: one per journal record
        nodes.update(g._ends[e])
        types.add(g._edge_type[e])


def face_changes(g: "HostGraph", record, edge_types: AbstractSet[str]) -> tuple[set, set, set]:
    """What a journal record changed of the planar map of ``edge_types`` (for
    :class:`~.embedding.FaceIndex`): the half-edges (edge, end) of the edges of those types added or
    removed, the nodes where the rotation of those edges may have changed, and the nodes added,
    removed, whose attributes or type changed or that end an edge of those types whose attributes
    changed. Ends
    are read from the graph (or from the record of a removal): an edge the journal removes later is
    counted by that removal."""
    half_edges: set = set()
    rotated: set = set()
    attributed: set = set()
    if isinstance(record, (_AddEdge, _RemoveEdge, _AddMany)) and getattr(record, "kind", "edge") == "edge":
        ids = record.ids if isinstance(record, _AddMany) else (record.e,)
        for e in ids:
            if isinstance(record, _RemoveEdge):
                kind, ends = record.type_name, (record.u, record.v)
            else:
                kind, ends = (g._edge_type[e], g._ends[e]) if g.has_edge(e) else (None, None)
            if ends is not None and kind in edge_types:
                half_edges.update((e, u) for u in ends)
                rotated.update(ends)
    elif isinstance(record, _Rotation):
        rotated.add(record.n)
    elif isinstance(record, _SetAttr) and record.kind == "edge":
        if g.has_edge(record.i) and g._edge_type[record.i] in edge_types:
            attributed.update(g._ends[record.i])
    elif isinstance(record, _SetAttr):
        attributed.add(record.i)
    elif isinstance(record, (_Retype, _AddNode, _RemoveNode)):
        attributed.add(record.n)
    elif isinstance(record, _AddMany):
        attributed.update(record.ids)
    return half_edges, rotated, attributed


class _AddNode(NamedTuple):
    n: int
    next_id: int  # the node counter before the addition

    def undo(self, g: "HostGraph") -> None:
        g._delete_node(self.n)
        g._next_node = self.next_id

    def touched(self, g: "HostGraph", nodes: set, types: set) -> None:
        _touch_node(g, self.n, nodes, types)


class _AddEdge(NamedTuple):
    e: int
    next_id: int  # the edge counter before the addition

    def undo(self, g: "HostGraph") -> None:
        g._delete_edge(self.e)
        g._next_edge = self.next_id

    def touched(self, g: "HostGraph", nodes: set, types: set) -> None:
        _touch_edge(g, self.e, nodes, types)


class _RemoveNode(NamedTuple):
    n: int
    type_name: str
    attrs: dict

    def undo(self, g: "HostGraph") -> None:
        g._insert_node(self.n, self.type_name, self.attrs)

    def touched(self, g: "HostGraph", nodes: set, types: set) -> None:
        nodes.add(self.n)
        types.add(self.type_name)


class _RemoveEdge(NamedTuple):
    e: int
    type_name: str
    u: int
    v: int
    attrs: dict
    positions: tuple[int, int]  # where the edge stood in the rotations of u and v

    def undo(self, g: "HostGraph") -> None:
        g._insert_edge(self.e, self.type_name, self.u, self.v, self.attrs, self.positions)

    def touched(self, g: "HostGraph", nodes: set, types: set) -> None:
        nodes.update((self.u, self.v))
        types.add(self.type_name)


class _SetAttr(NamedTuple):
    kind: str  # "node" or "edge"
    i: int
    name: str
    old: object

    def undo(self, g: "HostGraph") -> None:
        data = g._node_data[self.i] if self.kind == "node" else g._edge_data[self.i]
        data[self.name] = self.old

    def touched(self, g: "HostGraph", nodes: set, types: set) -> None:
        (_touch_node if self.kind == "node" else _touch_edge)(g, self.i, nodes, types)


class _Retype(NamedTuple):
    n: int
    old_type: str
    old_attrs: dict

    def undo(self, g: "HostGraph") -> None:
        g._set_node_type(self.n, self.old_type, g._node_type[self.n])
        g._replace_attrs(self.n, self.old_attrs)

    def touched(self, g: "HostGraph", nodes: set, types: set) -> None:
        types.add(self.old_type)
        _touch_node(g, self.n, nodes, types)


class _AddMany(NamedTuple):
    """Nodes or edges added at once (:meth:`HostGraph.add_nodes`, :meth:`HostGraph.add_edges`)."""

    kind: str  # "node" or "edge"
    ids: Sequence[int]  # a tuple, or for edges (numbered in a row) a range
    next_id: int

    def undo(self, g: "HostGraph") -> None:
        for i in reversed(self.ids):
            (g._delete_node if self.kind == "node" else g._delete_edge)(i)
        if self.kind == "node":
            g._next_node = self.next_id
        else:
            g._next_edge = self.next_id

    def touched(self, g: "HostGraph", nodes: set, types: set) -> None:
        for i in self.ids:
            (_touch_node if self.kind == "node" else _touch_edge)(g, i, nodes, types)


class _Lazy(dict):
    """A dictionary whose missing entries are made on first use by ``make(graph, key)``: the
    per-node tables of nodes and edges added in bulk are built only for the nodes a search or a
    rewrite reaches (``make`` raises KeyError for an unknown key). It holds its graph weakly, so that
    a graph is freed as soon as it is dropped, without waiting for the cyclic garbage collector."""

    def __init__(self, graph: "HostGraph", make: Callable[["HostGraph", int], object]):
        super().__init__()
        self.graph = weakref.ref(graph)
        self.make = make

    def __missing__(self, key):
        value = self[key] = self.make(self.graph(), key)
        return value


def _cell(column: np.ndarray | list, row: int) -> object:
    """The plain value in ``row`` of a bulk column (as ``tolist`` makes it; a vector as a tuple)."""
    if isinstance(column, list):
        return column[row]
    return tuple(column[row].tolist()) if column.ndim == 2 else column.item(row)


def _cells(column: np.ndarray | list, rows: np.ndarray) -> list:
    """The plain values in ``rows`` of a bulk column, as :func:`_cell` makes each."""
    if isinstance(column, list):
        return [column[r] for r in rows.tolist()]
    return list(zip(*column[rows].T.tolist())) if column.ndim == 2 else column[rows].tolist()


class _Bulk:
    """The attributes of the nodes (or the edges) added in bulk that have not been used one at a time
    yet, kept in the columns they were given in (numpy arrays of numbers, lists of other values):
    element ``i`` is row ``row[i]`` of block ``block[i]`` (-1: not here: its attributes are in the
    graph's dictionary, or it has none). Its dictionary is made when it is first used (:meth:`pop`):
    the rewrites of a large graph touch few of its elements, and making a dictionary for each was a
    third of building the tessellation's host graph at 10^6 vertices (issue 18)."""

    def __init__(self):
        self.blocks: list[dict[str, np.ndarray | list]] = []
        self.block = np.full(64, -1, dtype=np.int64)
        self.row = np.full(64, -1, dtype=np.int64)

    def add(self, ids: np.ndarray, columns: dict[str, np.ndarray | list]) -> None:
        """Hold the attribute ``columns`` of the new elements ``ids`` (row k for ``ids[k]``; nothing to
        hold for elements of a type without attributes)."""
        if not columns:
            return
        last = int(ids.max(initial=0))
        self.block, self.row = _fit(self.block, last), _fit(self.row, last)
        self.block[ids] = len(self.blocks)
        self.row[ids] = np.arange(len(ids))
        self.blocks.append(columns)

    def pop(self, i: int) -> dict:
        """The attributes of element ``i`` (in use, added in bulk, its dictionary not made yet) as a new
        dictionary, no longer held here: empty if none are held (its type has no attributes)."""
        b = int(self.block[i]) if i < len(self.block) else -1
        if b < 0:
            return {}
        self.block[i] = -1
        row = int(self.row[i])
        return {name: _cell(column, row) for name, column in self.blocks[b].items()}

    def drop(self, i: int) -> None:
        """Forget element ``i`` (it was removed)."""
        if i < len(self.block):
            self.block[i] = -1

    def parts(self, ids: np.ndarray, name: str) -> Iterator[tuple[np.ndarray, np.ndarray | list, np.ndarray]]:
        """For each block holding some of ``ids`` with attribute ``name``: the positions in ``ids`` of
        the elements it holds, and their rows of its column ``name``."""
        inside = (ids >= 0) & (ids < len(self.block))
        block = np.full(len(ids), -1, dtype=np.int64)
        block[inside] = self.block[ids[inside]]
        for b in np.flatnonzero(np.bincount(block[block >= 0], minlength=len(self.blocks))).tolist():
            column = self.blocks[b].get(name)
            if column is not None:
                at = np.flatnonzero(block == b)
                yield at, column, self.row[ids[at]]


class _Block(NamedTuple):
    """Edges added in bulk, as half-edges sorted by node (then edge id): for a node ``n`` its
    half-edges are ``[ptr[n], ptr[n + 1])`` (a CSR pointer over node ids, so that indexing a node on
    first use is two lookups, not two binary searches: issue 18's ``all``). Their rotation keys are
    sorted when the node's rotation is first used (sorting every half-edge by node and key at once
    was half of building the tessellation's host graph at 10^6 vertices)."""

    type_name: str
    node: np.ndarray
    edge: np.ndarray
    key: np.ndarray
    ptr: np.ndarray

    @classmethod
    def of(cls, type_name: str, node: np.ndarray, edge: np.ndarray, key: np.ndarray) -> "_Block":
        """The block of half-edges already sorted by node, with its pointer."""
        ptr = np.zeros(int(node.max(initial=-1)) + 2, dtype=np.int64)
        np.cumsum(np.bincount(node, minlength=len(ptr) - 1), out=ptr[1:])
        return cls(type_name, node, edge, key, ptr)

    def span(self, n: int) -> tuple[int, int]:
        return tuple(self.ptr[n:n + 2].tolist()) if n + 1 < len(self.ptr) else (0, 0)


class _Rotation(NamedTuple):
    n: int
    order: list[int]
    keys: list[tuple[float, int]]

    def undo(self, g: "HostGraph") -> None:
        g._rot[self.n] = self.order
        g._rot_keys[self.n] = self.keys

    def touched(self, g: "HostGraph", nodes: set, types: set) -> None:
        nodes.add(self.n)


class HostGraph:
    """A typed multigraph with directed and undirected edges, type indexes, rotations and undo."""

    def __init__(self, schema: TypeSchema, angle: AngleFunction | None = None):
        self.schema = schema
        self.angle = angle
        # attributes (id -> dict) and edge ends (id -> (source, target)); those of elements added in
        # bulk are made on first use, from the columns the _Bulk keep and from _edge_ends
        self._node_bulk, self._edge_bulk = _Bulk(), _Bulk()
        self._node_data: dict[int, dict] = _Lazy(self, lambda g, n: g._bulk_attrs(g._node_bulk, g._node_codes, n))
        self._edge_data: dict[int, dict] = _Lazy(self, lambda g, e: g._bulk_attrs(g._edge_bulk, g._edge_codes, e))
        self._ends: dict[int, tuple[int, int]] = _Lazy(self, HostGraph._bulk_ends)
        # types by id (made on first use from the type-code arrays for elements added in bulk), and
        # the type index: ids by type, those added in bulk put in when the type's set is next used
        self._node_type: dict[int, str] = _Lazy(self, lambda g, n: g._bulk_type(g._node_codes, n))
        self._edge_type: dict[int, str] = _Lazy(self, lambda g, e: g._bulk_type(g._edge_codes, e))
        self._by_type: dict[str, set[int]] = _Lazy(self, HostGraph._type_members)
        self._by_type.update((t, set()) for t in (*schema.node_types, *schema.edge_types))
        self._pending: dict[str, tuple[set[int], list[Sequence[int]]]] = {}  # type -> (its set, ids to put in)
        self._blocks: list[_Block] = []  # edges added in bulk, indexed per node on first use
        self._inc: dict[int, dict[str, set[int]]] = _Lazy(self, HostGraph._bulk_incidence)
        # a node's rotation and its keys are made together, from the bulk blocks, on first use
        self._rot_keys: dict[int, list[tuple[float, int]]] = _Lazy(self, lambda g, n: g._bulk_rotation(n)[0])
        self._rot: dict[int, list[int]] = _Lazy(self, lambda g, n: g._bulk_rotation(n)[1])
        self._next_node = 0
        self._next_edge = 0
        self._journal: list = []  # of the records above
        self._serials: list[int] = []  # per journal record: ``changes`` just after it (unique, see state_id)
        self._base_serial = 0  # the state id of the graph when its journal is empty
        self.changes = 0  # bumped by every change and every undo, never reset: a cache key for any state
        self.version = 0  # bumped by every change of structure or types (caches key on it)
        # the same typed structure as flat arrays indexed by id (-1: unused id), for whole-graph search
        self.type_code = {t: i for i, t in enumerate((*schema.node_types, *schema.edge_types))}
        self._type_names = list(self.type_code)  # type code -> type name
        self._node_codes = np.full(64, -1, dtype=np.int64)
        self._edge_codes = np.full(64, -1, dtype=np.int64)
        self._edge_ends = np.full((64, 2), -1, dtype=np.int64)
        self.incidence = Incidence(self._node_type, self._edge_type, self._ends, self._inc)
        self._fitting: set[tuple[str, str, str]] = set()  # (edge type, end types) checked to fit the schema
        self._watchers: list = []  # told of every record undone and of forget (watch)

    # ------------------------------------------------------------------------------------------
    # Queries
    # ------------------------------------------------------------------------------------------

    def __len__(self) -> int:
        return self.count(self.schema.node_types)  # the node types are few

    @property
    def num_edges(self) -> int:
        return self.count(self.schema.edge_types)

    def nodes(self) -> list[int]:
        """All node ids, sorted (every id in use is below the node counter)."""
        return np.flatnonzero(self._node_codes[: self._next_node] >= 0).tolist()

    def edges(self) -> list[int]:
        """All edge ids, sorted (every id in use is below the edge counter)."""
        return np.flatnonzero(self._edge_codes[: self._next_edge] >= 0).tolist()

    def has_node(self, n: int) -> bool:
        return n in self._node_type or _in_use(self._node_codes, n)  # the type table first: it is quicker

    def has_edge(self, e: int) -> bool:
        return e in self._edge_type or _in_use(self._edge_codes, e)

    def node_type(self, n: int) -> str:
        return self._node_type[n]

    def edge_type(self, e: int) -> str:
        return self._edge_type[e]

    def ends(self, e: int) -> tuple[int, int]:
        """(source, target) of an edge; for an undirected edge, the order it was created with."""
        return self._ends[e]

    def is_directed(self, e: int) -> bool:
        return self.schema.edge_types[self._edge_type[e]].directed

    def other(self, e: int, n: int) -> int:
        u, v = self._ends[e]
        return v if u == n else u

    def node_attrs(self, n: int) -> Mapping[str, object]:
        return self._node_data[n]

    def edge_attrs(self, e: int) -> Mapping[str, object]:
        return self._edge_data[e]

    def get(self, n: int, name: str) -> object:
        return self._node_data[n][name]

    def values(self, kind: str, ids: Iterable[int], name: str) -> list:
        """Attribute ``name`` of many nodes (``kind`` "node") or edges ("edge") at once (those still in
        the columns they were added with in bulk are read there, their dictionaries not made)."""
        data, bulk = (self._node_data, self._node_bulk) if kind == "node" else (self._edge_data, self._edge_bulk)
        ids = list(ids)
        if not bulk.blocks:
            return [data[i][name] for i in ids]
        out = np.empty(len(ids), dtype=object)
        held = np.zeros(len(ids), dtype=bool)
        for at, column, rows in bulk.parts(np.array(ids, dtype=np.int64), name):
            out[at] = np.fromiter(_cells(column, rows), dtype=object, count=len(at))
            held[at] = True
        loose = np.flatnonzero(~held).tolist()
        out[loose] = np.fromiter((data[ids[k]][name] for k in loose), dtype=object, count=len(loose))
        return out.tolist()

    def bulk_numbers(self, kind: str, ids: np.ndarray, name: str) -> Iterator[tuple[np.ndarray, np.ndarray]]:
        """For the whole-graph matcher: attribute ``name`` of those of the nodes (``kind`` "node") or
        edges ("edge") ``ids`` that are still in a column of numbers they were added with in bulk,
        as (their positions in ``ids``, their values) per column (one numpy array per column, read
        without making their dictionaries). The others' values are read with :meth:`values`."""
        bulk = self._node_bulk if kind == "node" else self._edge_bulk
        for at, column, rows in bulk.parts(ids, name):
            if isinstance(column, np.ndarray) and column.ndim == 1:
                yield at, column[rows]

    def get_edge(self, e: int, name: str) -> object:
        return self._edge_data[e][name]

    def count(self, types: Iterable[str]) -> int:
        """Number of elements whose type is one of ``types`` (pass a type's subtypes)."""
        return sum(len(self._by_type[t]) if t not in self._pending else
                   len(self._pending[t][0]) + sum(map(len, self._pending[t][1])) for t in types)

    def of_types(self, types: Iterable[str]) -> Iterator[int]:
        """Element ids of the given exact types (pass ``schema.subtypes(T)`` for T and its subtypes)."""
        return itertools.chain.from_iterable(self._by_type[t] for t in types)

    def incident(self, n: int, types: Iterable[str] | None = None) -> Iterator[int]:
        """Edge ids incident to ``n`` whose exact type is in ``types`` (all edges when None)."""
        inc = self._inc[n]
        if types is None:
            for edges in inc.values():
                yield from edges
            return
        for t in types:
            edges = inc.get(t)
            if edges:
                yield from edges

    def degree(self, n: int, types: Iterable[str] | None = None) -> int:
        inc = self._inc[n]
        if types is None:
            return sum(len(s) for s in inc.values())
        return sum(len(inc[t]) for t in types if t in inc)

    def arrays(self) -> TypeArrays:
        """Type code per node id, and per edge id its type code and (source, target); -1 where unused.

        The arrays are views of the graph's own: read them before the next change, never write them.
        """
        return TypeArrays(self._node_codes[: self._next_node], self._edge_codes[: self._next_edge],
                          self._edge_ends[: self._next_edge])

    def rotation(self, n: int) -> list[int]:
        """Incident edge ids in cyclic (counter-clockwise when the graph has an angle function) order."""
        return list(self._rot[n])

    def before_around(self, n: int, e: int, types: AbstractSet[str]) -> int:
        """The edge of ``types`` just before ``e`` (itself of ``types``) in the rotation around ``n``,
        cyclically (``e`` when it is the only one): a face walk's next step, without copying or
        filtering the whole rotation."""
        rot, edge_type = self._rot[n], self._edge_type
        if edge_type[e] not in types:
            raise ValueError(f"edge {e} is not of the types {sorted(types)}")
        i = rot.index(e)
        while True:
            i -= 1
            if edge_type[rot[i]] in types:  # i runs below zero: Python wraps round to the end
                return rot[i]

    def next_around(self, n: int, e: int, step: int = 1) -> int:
        """The edge ``step`` places after ``e`` in the rotation around ``n`` (negative: before)."""
        rot = self._rot[n]
        return rot[(rot.index(e) + step) % len(rot)]

    # ------------------------------------------------------------------------------------------
    # Changes (each one journaled)
    # ------------------------------------------------------------------------------------------

    def add_node(self, type_name: str, attrs: Mapping[str, object] | None = None, id: int | None = None) -> int:
        """Add a node of a concrete declared type; attributes are checked and defaults filled in."""
        info = self.schema.node_types.get(type_name)
        if info is None:
            raise SchemaError(f"unknown node type '{type_name}'")
        if info.abstract:
            raise SchemaError(f"node type '{type_name}' is abstract and cannot be instantiated")
        n = self._allocate(id, "node")
        values = self.schema.fill_attrs(type_name, attrs or {}, f"node {n}")
        self._record(_AddNode(n, self._next_node))
        self._next_node = max(self._next_node, n + 1)
        self._insert_node(n, type_name, values)
        return n

    def add_edge(
        self, type_name: str, u: int, v: int, attrs: Mapping[str, object] | None = None, id: int | None = None
    ) -> int:
        """Add an edge of a concrete declared type between existing nodes of allowed endpoint types."""
        info = self.schema.edge_types.get(type_name)
        if info is None:
            raise SchemaError(f"unknown edge type '{type_name}'")
        if info.abstract:
            raise SchemaError(f"edge type '{type_name}' is abstract and cannot be instantiated")
        try:
            fitting = (type_name, self._node_type[u], self._node_type[v])
        except KeyError:
            raise SchemaError(f"edge {type_name}: node {v if self.has_node(u) else u} does not exist") from None
        if u == v:
            raise SchemaError(f"edge {type_name}: a self-loop at node {u} is not allowed")
        if fitting not in self._fitting:
            self._check_endpoints(type_name, u, v)
            self._fitting.add(fitting)
        e = self._allocate(id, "edge")
        values = self.schema.fill_attrs(type_name, attrs or {}, f"edge {e}") if attrs or info.attrs else {}
        self._record(_AddEdge(e, self._next_edge))
        self._next_edge = max(self._next_edge, e + 1)
        self._insert_edge(e, type_name, u, v, values, None)
        return e

    @_collector_paused
    def add_nodes(self, type_name: str, ids, attrs: Mapping[str, object] | None = None) -> list[int]:
        """Add many nodes of one type at once: ``ids`` (new, distinct) and their attribute values by
        column (``{name: values}``, one value per node; numpy arrays are checked as a whole). The same
        as :meth:`add_node` for each, in one journal record, much faster for large graphs."""
        info = self.schema.node_types.get(type_name)
        if info is None or info.abstract:
            raise SchemaError(f"node type '{type_name}' is unknown or abstract and cannot be instantiated")
        array = self._new_node_ids(ids)
        columns = self.schema.filled_columns(type_name, attrs or {}, len(array), f"{type_name} nodes")
        ids = array.tolist()
        self._record(_AddMany("node", tuple(ids), self._next_node))
        self._next_node = max(self._next_node, int(array.max(initial=-1)) + 1)
        self._node_bulk.add(array, columns)
        self.version += 1
        self._index_bulk(type_name, ids)
        self._node_codes = _fit(self._node_codes, int(array.max(initial=0)))
        self._node_codes[array] = self.type_code[type_name]
        return ids  # their attributes, incidence and rotations are made on first use (_Lazy)

    def _new_node_ids(self, ids) -> np.ndarray:
        """``ids`` (any iterable of integers) as an array, checked to be new, distinct and non-negative."""
        if isinstance(ids, range):
            array = np.arange(ids.start, ids.stop, ids.step)
        else:
            array = np.asarray(ids if isinstance(ids, np.ndarray) else list(ids)).astype(np.int64).reshape(-1)
        known = array[array < len(self._node_codes)]
        distinct = (np.diff(array) > 0).all() or len(np.unique(array)) == len(array)  # increasing: no sort
        if (array < 0).any() or (self._node_codes[known] >= 0).any() or not distinct:
            raise SchemaError("add_nodes: node ids must be new, distinct and non-negative")
        return array

    @_collector_paused
    def add_edges(self, type_name: str, ends, attrs: Mapping[str, object] | None = None, angles=None) -> list[int]:
        """Add many edges of one type at once, between the node pairs ``ends`` ((k, 2)), with new ids
        from the edge counter and attribute values by column. ``angles`` ((k, 2), optional) are the
        rotation keys the angle function would give at the source and at the target (computed in
        bulk by the caller); without them the angle function is called. One journal record."""
        info = self.schema.edge_types.get(type_name)
        if info is None or info.abstract:
            raise SchemaError(f"edge type '{type_name}' is unknown or abstract and cannot be instantiated")
        ends = np.asarray(ends, dtype=np.int64).reshape(-1, 2)
        self._check_new_ends(type_name, ends)
        columns = self.schema.filled_columns(type_name, attrs or {}, len(ends), f"{type_name} edges")
        ids = range(self._next_edge, self._next_edge + len(ends))  # kept as a range: no 10^6 ints to hold
        self._record(_AddMany("edge", ids, self._next_edge))
        self._next_edge += len(ends)
        self._edge_bulk.add(np.arange(ids.start, ids.stop), columns)
        self._index_edges(type_name, ids, ends, angles)
        return list(ids)  # their attributes and ends are made on first use (_Lazy)

    def _check_new_ends(self, type_name: str, ends: np.ndarray) -> None:
        """Refuse (SchemaError) edges of ``type_name`` between the node pairs ``ends`` if a node does not
        exist, an edge is a loop or joins nodes of types it cannot: that is checked once per pair of
        end types, at the first edge with it, in the order of the pairs' type codes."""
        codes = np.where((ends >= 0) & (ends < len(self._node_codes)), self._node_codes[np.clip(ends, 0, len(
            self._node_codes) - 1)], -1) if len(ends) else ends
        if (codes < 0).any():
            raise SchemaError(f"edge {type_name}: node {int(ends[codes < 0].min())} does not exist")
        if (ends[:, 0] == ends[:, 1]).any():
            raise SchemaError(f"edge {type_name}: a self-loop at node {int(ends[ends[:, 0] == ends[:, 1]][0, 0])}")
        size = len(self.type_code)
        first = np.full(size * size, len(ends))
        np.minimum.at(first, codes[:, 0] * size + codes[:, 1], np.arange(len(ends)))
        for k in first[first < len(ends)].tolist():
            self._check_endpoints(type_name, int(ends[k, 0]), int(ends[k, 1]))

    def _index_edges(self, type_name: str, ids: range, ends: np.ndarray, angles) -> None:
        """Type index, arrays, incidence and rotations of edges just added in bulk."""
        self.version += 1
        self._index_bulk(type_name, ids)
        new = slice(ids.start, ids.stop)
        self._edge_codes, self._edge_ends = _fit(self._edge_codes, new.stop - 1), _fit(self._edge_ends, new.stop - 1)
        self._edge_codes[new] = self.type_code[type_name]
        self._edge_ends[new] = ends
        node = ends.ravel()  # the half-edges: each edge's source, then its target
        if angles is not None:
            key = np.asarray(angles, dtype=float).ravel()
        elif self.angle is None:
            key = np.zeros(len(node))  # as _rotation_key gives it
        else:
            key = np.array([self._rotation_key(ids[k // 2], n)[0] for k, n in enumerate(node.tolist())])
        order = np.argsort(node, kind="stable")  # by node, then by edge id
        block = _Block.of(type_name, node[order], ids.start + order // 2, key[order])
        # nodes whose tables exist already get the new edges now; the others when first used
        indexed = self._inc.keys() | self._rot_keys.keys()
        for n in (set(block.node.tolist()) & indexed) if indexed else ():
            self._merge_block(n, block)
        self._blocks.append(block)

    def _merge_block(self, n: int, block: "_Block") -> None:
        """Add a bulk block's half-edges at node ``n`` to its existing tables."""
        lo, hi = block.span(n)
        edges, keys = block.edge[lo:hi].tolist(), block.key[lo:hi].tolist()
        self._inc[n].setdefault(block.type_name, set()).update(edges)
        merged = sorted(self._rot_keys[n] + list(zip(keys, edges)))
        self._rot_keys[n] = merged
        self._rot[n] = [e for _, e in merged]

    def _bulk_incidence(self, n: int) -> dict[str, set[int]]:
        """The typed incidence of a node never indexed one edge at a time (from the bulk blocks)."""
        if not self.has_node(n):
            raise KeyError(n)
        out: dict[str, set[int]] = {}
        for block in self._blocks:
            lo, hi = block.span(n)
            if hi > lo:
                out.setdefault(block.type_name, set()).update(block.edge[lo:hi].tolist())
        return out

    def _bulk_rotation(self, n: int) -> tuple[list[tuple[float, int]], list[int]]:
        """The rotation keys and rotation of a node never indexed one edge at a time (from the bulk
        blocks), stored in both tables at once so that they never disagree."""
        if not self.has_node(n):
            raise KeyError(n)
        keys: list[tuple[float, int]] = []
        for block in self._blocks:
            lo, hi = block.span(n)
            keys += zip(block.key[lo:hi].tolist(), block.edge[lo:hi].tolist())
        keys.sort()
        dict.__setitem__(self._rot_keys, n, keys)
        dict.__setitem__(self._rot, n, [e for _, e in keys])
        return keys, self._rot[n]

    def _bulk_attrs(self, bulk: _Bulk, codes: np.ndarray, i: int) -> dict:
        """The attributes of a node or an edge added in bulk (``bulk`` and ``codes``: those of nodes or
        of edges), from the columns held, or of one without attributes (KeyError for an id not in use)."""
        if not _in_use(codes, i):
            raise KeyError(i)
        return bulk.pop(i)

    def _bulk_type(self, codes: np.ndarray, i: int) -> str:
        """The type of a node or an edge added in bulk, from its type-code array ``codes`` (KeyError
        for an id not in use)."""
        if not _in_use(codes, i):
            raise KeyError(i)
        return self._type_names[codes[i]]

    def _index_bulk(self, type_name: str, ids: Sequence[int]) -> None:
        """Put ids added in bulk in the type index: they wait, with the type's set taken out of it,
        until the set is next used (:meth:`_type_members`; a rewrite of a large graph may not use it,
        and putting in 10^6 ids costs 0.05 s)."""
        if type_name not in self._pending:
            self._pending[type_name] = (dict.pop(self._by_type, type_name), [])
        self._pending[type_name][1].append(ids)

    def _type_members(self, type_name: str) -> set[int]:
        """The set of a type in the type index, with the ids added in bulk that wait for it put in, in
        the order they were added: the set, hence its iteration order, is the one that putting
        them in at once would have made (KeyError for a type with nothing waiting: an unknown one)."""
        members, waiting = self._pending.pop(type_name)
        for ids in waiting:
            members.update(ids)
        return members

    def _bulk_ends(self, e: int) -> tuple[int, int]:
        """The ends of an edge added in bulk, from the ends array (KeyError for an edge not in use)."""
        if not _in_use(self._edge_codes, e):
            raise KeyError(e)
        u, v = self._edge_ends[e].tolist()
        return u, v

    def remove_edge(self, e: int) -> None:
        u, v = self._ends[e]
        positions = (self._rot[u].index(e), self._rot[v].index(e))
        attrs = dict(self._edge_data[e])
        self._record(_RemoveEdge(e, self._edge_type[e], u, v, attrs, positions))
        self._delete_edge(e)

    def remove_node(self, n: int) -> None:
        """Remove a node that has no edges left (the dangling condition of double-pushout rewriting)."""
        if self._rot[n]:
            raise SchemaError(f"node {n} still has {len(self._rot[n])} edge(s): {sorted(self._rot[n])}")
        self._record(_RemoveNode(n, self._node_type[n], dict(self._node_data[n])))
        self._delete_node(n)

    def set_node_attr(self, n: int, name: str, value: object) -> None:
        self._set_attr("node", n, self._node_type[n], self._node_data[n], name, value)
        self._refresh_rotations([n, *(self.other(e, n) for e in self._rot[n])])

    def set_edge_attr(self, e: int, name: str, value: object) -> None:
        u, v = self._ends[e]
        self._set_attr("edge", e, self._edge_type[e], self._edge_data[e], name, value)
        self._refresh_rotations([u, v])

    def retype(self, n: int, type_name: str) -> None:
        """Change a node's type; attributes the new type lacks are dropped, missing ones defaulted."""
        info = self.schema.node_types.get(type_name)
        if info is None or info.abstract:
            raise SchemaError(f"node {n}: cannot retype to '{type_name}' (unknown or abstract type)")
        old_type = self._node_type[n]
        old_attrs = dict(self._node_data[n])
        kept = {k: v for k, v in old_attrs.items() if k in info.attrs}
        values = self.schema.fill_attrs(type_name, kept, f"node {n}")
        self._set_node_type(n, type_name, old_type)
        for e in self._rot[n]:
            u, v = self._ends[e]
            try:
                self._check_endpoints(self._edge_type[e], u, v)
            except SchemaError:
                self._set_node_type(n, old_type, type_name)
                raise
        self._record(_Retype(n, old_type, old_attrs))
        self._replace_attrs(n, values)

    # ------------------------------------------------------------------------------------------
    # Transactions and undo
    # ------------------------------------------------------------------------------------------

    def _record(self, entry) -> None:
        """Journal a change (for undo) and count it."""
        self._journal.append(entry)
        self.changes += 1
        self._serials.append(self.changes)

    def mark(self) -> int:
        """A point in the journal to roll back to."""
        return len(self._journal)

    def rollback(self, mark: int) -> None:
        """Undo every change made since ``mark``, restoring the graph (ids, rotations, counters) exactly.
        Each watcher (:meth:`watch`) sees each record just before it is undone."""
        while len(self._journal) > mark:
            record = self._journal.pop()
            for watcher in self._watchers:
                watcher.undoing(self, record)
            record.undo(self)
            self._serials.pop()
            self.changes += 1

    def watch(self, watcher) -> None:
        """Keep ``watcher`` told of the changes that leave the journal, for an index of its own that it
        brings up to date with :meth:`journal_since`: ``watcher.undoing(graph, record)`` just before each
        record is undone (the graph is then as the record left it), ``watcher.forgetting(graph)`` just
        before :meth:`forget` drops the journal."""
        self._watchers.append(watcher)

    def journal_since(self, mark: int) -> list:
        """The journal records after ``mark``, oldest first (for :func:`face_changes`)."""
        return self._journal[mark:]

    def state_id(self) -> int:
        """An id of the graph's current state that is the same again after a rollback to it: the
        serial of the last journal record (``changes`` just after it was made; unique, as ``changes``
        never repeats). Records below the last one can only go after it, so the id stands for the
        whole journal, hence for the contents. A cache of results computed from the graph can key
        on it (:class:`~.memo.TableMemo`); ``changes`` cannot, as undo moves it on.

        >>> from vaultgram.engine.rulebook import rulebook_from_text
        >>> g = HostGraph(rulebook_from_text("schema s { node A }").schema)
        >>> before = g.state_id(); mark = g.mark(); n = g.add_node("A")
        >>> after = g.state_id(); g.rollback(mark)
        >>> g.state_id() == before != after
        True
        """
        return self._serials[-1] if self._serials else self._base_serial

    @contextmanager
    def transaction(self):
        """Changes inside the block all happen, or (on any exception) none of them do."""
        mark = self.mark()
        try:
            yield
        except BaseException:
            self.rollback(mark)
            raise

    def forget(self) -> None:
        """Drop the undo log (after a run whose changes will never be undone)."""
        for watcher in self._watchers:
            watcher.forgetting(self)
        self._base_serial = self.state_id()  # the same state: the same id
        self._journal.clear()
        self._serials.clear()

    def changes_since(self, mark: int) -> ChangeSet:
        """The nodes and types touched by the changes after ``mark``."""
        nodes: set[int] = set()
        types: set[str] = set()
        for record in self._journal[mark:]:
            record.touched(self, nodes, types)
        types.discard("")
        return ChangeSet(frozenset(nodes), frozenset(types))

    # ------------------------------------------------------------------------------------------
    # Export and comparison
    # ------------------------------------------------------------------------------------------

    def snapshot(self) -> dict:
        """A canonical plain description: two graphs are identical exactly when their snapshots are equal."""
        return {
            "nodes": {n: (self._node_type[n], sorted(self._node_data[n].items())) for n in self.nodes()},
            "edges": {
                e: (self._edge_type[e], self._ends[e], sorted(self.edge_attrs(e).items())) for e in self.edges()
            },
            "rotations": {n: list(self._rot[n]) for n in self.nodes()},
            "counters": (self._next_node, self._next_edge),
        }

    def to_networkx(self) -> nx.MultiDiGraph:
        """A copy as a networkx MultiDiGraph; the element type is stored in attribute ``type``. (networkx
        is imported here: the engine does not need it otherwise, and it costs 0.2 s at start-up.)"""
        import networkx as nx

        g = nx.MultiDiGraph()
        for n in self.nodes():
            g.add_node(n, type=self._node_type[n], **self._node_data[n])
        for e in self.edges():
            u, v = self._ends[e]
            g.add_edge(u, v, key=e, type=self._edge_type[e], directed=self.is_directed(e), **self.edge_attrs(e))
        return g

    def to_json(self) -> dict:
        """Nodes and edges with their types and attributes, in id order (JSON-serialisable)."""
        return {
            "nodes": [{"id": n, "type": self._node_type[n], **self._node_data[n]} for n in self.nodes()],
            "edges": [
                {"id": e, "type": self._edge_type[e], "source": self._ends[e][0], "target": self._ends[e][1],
                 **self.edge_attrs(e)}
                for e in self.edges()
            ],
        }

    @classmethod
    def from_json(cls, data: Mapping, schema: TypeSchema, angle: AngleFunction | None = None) -> "HostGraph":
        """The inverse of :meth:`to_json`; raises SchemaError naming the offending node or edge."""
        if not isinstance(data, Mapping) or not isinstance(data.get("nodes", []), list):
            raise SchemaError("a graph is an object with lists 'nodes' and 'edges'")
        g = cls(schema, angle)
        for k, item in enumerate(data.get("nodes", [])):
            attrs = {a: v for a, v in item.items() if a not in ("id", "type")}
            if "type" not in item:
                raise SchemaError(f"nodes[{k}] has no 'type'")
            g.add_node(item["type"], attrs, item.get("id"))
        for k, item in enumerate(data.get("edges", [])):
            attrs = {a: v for a, v in item.items() if a not in ("id", "type", "source", "target")}
            if not {"type", "source", "target"} <= set(item):
                raise SchemaError(f"edges[{k}] needs 'type', 'source' and 'target'")
            g.add_edge(item["type"], item["source"], item["target"], attrs, item.get("id"))
        g.forget()
        return g

    # ------------------------------------------------------------------------------------------
    # Internals
    # ------------------------------------------------------------------------------------------

    def _allocate(self, requested: int | None, kind: str) -> int:
        if requested is None:
            return self._next_node if kind == "node" else self._next_edge
        if not isinstance(requested, int) or isinstance(requested, bool) or requested < 0:
            raise SchemaError(f"{kind} id must be a non-negative integer, got {requested!r}")
        if _in_use(self._node_codes if kind == "node" else self._edge_codes, requested):
            raise SchemaError(f"{kind} id {requested} already exists")
        return requested

    def _check_endpoints(self, type_name: str, u: int, v: int) -> None:
        tu, tv = self._node_type[u], self._node_type[v]
        if not self.schema.endpoints_fit(type_name, tu, tv):
            info = self.schema.edge_types[type_name]
            arrow = "->" if info.directed else "--"
            raise SchemaError(
                f"edge {type_name} ({info.source} {arrow} {info.target}) "
                f"cannot join node {u} ({tu}) and node {v} ({tv})"
            )

    def _set_node_type(self, n: int, type_name: str, old: str | None) -> None:
        """Record a node's type in the type index and the type-code array (creation, retype, undo);
        ``old``: its type until now (None for a new node)."""
        self.version += 1
        if old is not None:
            self._by_type[old].discard(n)
        self._node_type[n] = type_name
        self._by_type[type_name].add(n)
        self._node_codes = _fit(self._node_codes, n)
        self._node_codes[n] = self.type_code[type_name]

    def _insert_node(self, n: int, type_name: str, attrs: dict) -> None:
        if attrs:  # no attributes: the empty dictionary is made when first read (_bulk_attrs)
            self._node_data[n] = dict(attrs)
        self._set_node_type(n, type_name, None)
        self._inc[n] = {}
        self._rot[n] = []
        self._rot_keys[n] = []

    def _delete_node(self, n: int) -> None:
        self.version += 1
        dict.pop(self._node_data, n, None)  # not there while it is still held in bulk
        self._node_bulk.drop(n)
        self._by_type[self._node_type[n]].discard(n)
        dict.pop(self._node_type, n)
        self._node_codes[n] = -1
        for table in (self._inc, self._rot, self._rot_keys):
            dict.pop(table, n, None)

    def _insert_edge(self, e: int, type_name: str, u: int, v: int, attrs: dict, positions) -> None:
        self.version += 1
        if attrs:  # no attributes: the empty dictionary is made when first read (_bulk_attrs)
            self._edge_data[e] = dict(attrs)
        self._edge_type[e] = type_name
        self._ends[e] = (u, v)
        self._by_type[type_name].add(e)
        if e >= len(self._edge_codes):
            self._edge_codes, self._edge_ends = _fit(self._edge_codes, e), _fit(self._edge_ends, e)
        self._edge_codes[e] = self.type_code[type_name]
        self._edge_ends[e, 0], self._edge_ends[e, 1] = u, v
        plain = (0.0, e) if self.angle is None else None  # both ends' rotation key: one tuple for the collector
        for k, n in enumerate((u, v)):
            inc = self._inc[n]
            bucket = inc.get(type_name)
            if bucket is None:
                inc[type_name] = {e}
            else:
                bucket.add(e)
            keys, key = self._rot_keys[n], plain or self._rotation_key(e, n)
            if positions is not None:
                i = positions[k]
            elif not keys or keys[-1] <= key:  # after every edge there (a new edge, without an angle)
                i = len(keys)
            else:
                i = bisect.bisect(keys, key)
            keys.insert(i, key)
            self._rot[n].insert(i, e)

    def _delete_edge(self, e: int) -> None:
        self.version += 1
        u, v = self._ends[e]
        dict.pop(self._ends, e)
        type_name = self._edge_type[e]
        dict.pop(self._edge_type, e)
        dict.pop(self._edge_data, e, None)  # not there while it is still held in bulk
        self._edge_bulk.drop(e)
        self._by_type[type_name].discard(e)
        self._edge_codes[e] = -1
        for n in (u, v):
            bucket = self._inc[n][type_name]
            bucket.discard(e)
            if not bucket:
                del self._inc[n][type_name]
            i = self._rot[n].index(e)
            del self._rot[n][i], self._rot_keys[n][i]

    def _rotation_key(self, e: int, n: int) -> tuple[float, int]:
        if self.angle is None:
            return (0.0, e)
        return (float(self.angle(self, e, n)), e)

    def _refresh_rotations(self, nodes: Iterable[int]) -> None:
        """Re-sort rotations after an attribute change (only when an angle function defines them)."""
        if self.angle is None:
            return
        for n in dict.fromkeys(nodes):
            keys = sorted(self._rotation_key(e, n) for e in self._rot[n])
            if keys != self._rot_keys[n]:  # new keys in the same order too: edges added later are placed by them
                self._record(_Rotation(n, self._rot[n], self._rot_keys[n]))
                self._rot[n] = [e for _, e in keys]
                self._rot_keys[n] = keys

    def _set_attr(self, kind: str, i: int, type_name: str, data: dict, name: str, value: object) -> None:
        value = self.schema.checked_value(type_name, name, value, f"{kind} {i}")
        self._record(_SetAttr(kind, i, name, data[name]))
        data[name] = value

    def _replace_attrs(self, n: int, values: Mapping[str, object]) -> None:
        data = self._node_data[n]
        data.clear()
        data.update(values)


def _in_use(codes: np.ndarray, i: int) -> bool:
    """Whether ``i`` is an id with a type in the type-code array ``codes`` (of the nodes or of the edges)."""
    try:
        return 0 <= i < len(codes) and codes.item(i) >= 0
    except TypeError:  # not an integer
        return False


def _fit(array: np.ndarray, i: int) -> np.ndarray:
    """``array`` grown (doubling, filled with -1) so that index ``i`` exists."""
    if i < len(array):
        return array
    grown = np.full((max(2 * len(array), i + 1), *array.shape[1:]), -1, dtype=array.dtype)
    grown[: len(array)] = array
    return grown
