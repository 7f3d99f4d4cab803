"""Array helpers (vaultgram.geometry.arrays): the components of linked elements."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from vaultgram.geometry.arrays import link_components


def _scipy_roots(n: int, a, b) -> np.ndarray:
    """The smallest element of each element's component, by scipy's ``connected_components``."""
    graph = coo_matrix((np.ones(len(a)), (a, b)), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    first = np.full(labels.max() + 1 if n else 0, n)
    np.minimum.at(first, labels, np.arange(n))
    return first[labels]


@st.composite
def linked(draw):
    """A number of elements and links between them (self-links and repeated links too)."""
    n = draw(st.integers(0, 60))
    if n == 0:
        return 0, [], []
    pairs = draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=90))
    return n, [p for p, _ in pairs], [q for _, q in pairs]


@given(linked())
@settings(max_examples=200, deadline=None)
def test_link_components_are_scipys_connected_components(case):
    n, a, b = case
    assert link_components(n, a, b).tolist() == _scipy_roots(n, np.array(a, dtype=int), np.array(b, dtype=int)).tolist()


def test_a_long_chain_in_random_order_is_one_component():
    """5000 elements chained in a random order: one component, rooted at the smallest element."""
    n = 5000
    order = np.random.default_rng(1).permutation(n)
    roots = link_components(n, order[:-1], order[1:])
    assert (roots == 0).all()
