"""Random typed host graphs of the test schema (:mod:`strategies.rules`).

``typed_graphs()`` draws a *description* of a random host graph (node types and edge endpoints, with
ids given explicitly) that :func:`build_graph` turns into a :class:`HostGraph`, so the same graph can
be rebuilt in another insertion order.
"""

from __future__ import annotations

from dataclasses import dataclass

from hypothesis import strategies as st

from vaultgram.engine.graph import HostGraph


@dataclass(frozen=True)
class GraphSpec:
    """Nodes as (id, type, w) and edges as (id, type, u, v, m), ids explicit."""

    nodes: tuple
    edges: tuple


@st.composite
def typed_graphs(draw, max_nodes: int = 30, max_edges: int = 45, min_nodes: int = 0):
    n = draw(st.integers(min_nodes, max_nodes))
    types = draw(st.lists(st.sampled_from(["A", "B", "C"]), min_size=n, max_size=n))
    ws = draw(st.lists(st.integers(0, 3), min_size=n, max_size=n))
    nodes = tuple((i, types[i], ws[i]) for i in range(n))
    a_nodes = [i for i in range(n) if types[i] in ("A", "B")]
    c_nodes = [i for i in range(n) if types[i] == "C"]
    edges = []
    m = draw(st.integers(0, max_edges))
    for k in range(m):
        kinds = []
        if len(a_nodes) >= 2:
            kinds.append("E")
        if a_nodes and c_nodes:
            kinds.append("D")
        if not kinds:
            break
        kind = draw(st.sampled_from(kinds))
        if kind == "E":
            u = draw(st.sampled_from(a_nodes))
            v = draw(st.sampled_from([x for x in a_nodes if x != u]))
        else:
            u = draw(st.sampled_from(a_nodes))
            v = draw(st.sampled_from(c_nodes))
        edges.append((k, kind, u, v, draw(st.integers(0, 2))))
    return GraphSpec(nodes, tuple(edges))


def build_graph(schema, spec: GraphSpec, node_order=None, edge_order=None) -> HostGraph:
    """Build the graph of ``spec`` (explicit ids), inserting nodes/edges in the given index orders."""
    g = HostGraph(schema)
    nodes = spec.nodes if node_order is None else [spec.nodes[i] for i in node_order]
    edges = spec.edges if edge_order is None else [spec.edges[i] for i in edge_order]
    for i, t, w in nodes:
        g.add_node(t, {"w": w}, id=i)
    for k, t, u, v, m in edges:
        g.add_edge(t, u, v, {"m": m}, id=k)
    return g


def permutations(n: int):
    return st.permutations(list(range(n)))



def build_graph_in_bulk(schema, spec: GraphSpec) -> HostGraph:
    """The graph of ``spec`` built with :meth:`HostGraph.add_nodes` (one call per node type) and
    :meth:`HostGraph.add_edges` (one call per run of consecutive edges of one type, so that the edge
    counter gives them the ids of ``spec``): the same graph as :func:`build_graph` makes."""
    g = HostGraph(schema)
    for t in sorted({t for _, t, _ in spec.nodes}):
        mine = [(i, w) for i, kind, w in spec.nodes if kind == t]
        g.add_nodes(t, [i for i, _ in mine], {"w": [w for _, w in mine]})
    start = 0
    for k in range(1, len(spec.edges) + 1):
        if k == len(spec.edges) or spec.edges[k][1] != spec.edges[start][1]:
            run = spec.edges[start:k]
            g.add_edges(run[0][1], [(u, v) for _, _, u, v, _ in run], {"m": [m for *_, m in run]})
            start = k
    return g
