"""Strict reading of JSON values: the checks every reader shares (meshes, supports, densities).

JSON has no integers apart from numbers, and Python's ``int()`` and ``np.asarray`` turn 1.5, ``"1"``
and ``true`` into 1 and a string ``"0123"`` into four indices without a word. These helpers accept
exactly what a file format says, and name the element and its index in the one-line error:
an index is an integer (not a bool, not a float, not a string), a coordinate a finite number, a list
a JSON array (``{}`` is not an empty list).

>>> indices([0, 2], 3, "faces[0]").tolist()
[0, 2]
>>> indices([0, 1.5], 3, "faces[0]")
Traceback (most recent call last):
...
vaultgram.grammar.errors.InputError: faces[0][1]: expected a vertex index (an integer), got 1.5
"""

from __future__ import annotations

import math

import numpy as np

from vaultgram.errors import VaultgramError

__all__ = ["json_list", "json_object", "is_integer", "is_number", "indices", "points", "finite_number",
           "graph_document"]


def _kind(value) -> str:
    return {dict: "an object", list: "a list", str: "a string", bool: "a bool", type(None): "null"}.get(
        type(value), type(value).__name__)


def json_list(value, what: str) -> list:
    """``value`` if it is a JSON array (or, from Python, a tuple), else an error naming ``what``."""
    if not isinstance(value, (list, tuple)):
        raise VaultgramError(f"{what}: expected a list, got {_kind(value)}")
    return value


def json_object(value, what: str) -> dict:
    """``value`` if it is a JSON object, else an error naming ``what``."""
    if not isinstance(value, dict):
        raise VaultgramError(f"{what}: expected an object, got {_kind(value)}")
    return value


def is_integer(value) -> bool:
    """A JSON integer (a bool is not one)."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def is_number(value) -> bool:
    """A finite JSON number (a bool is not one)."""
    return (isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))
            and math.isfinite(float(value)))


def finite_number(value, what: str) -> float:
    """``value`` as a float if it is a finite number, else an error naming ``what``."""
    if not is_number(value):
        raise VaultgramError(f"{what}: expected a finite number, got {value!r}")
    return float(value)


def indices(value, n: int, what: str, item: str = "vertex index") -> np.ndarray:
    """A list of integers in ``[0, n)`` as an int64 array; an error names the first bad one."""
    for k, i in enumerate(json_list(value, what)):
        if not is_integer(i):
            raise VaultgramError(f"{what}[{k}]: expected a {item} (an integer), got {i!r}")
        if not 0 <= i < n:
            raise VaultgramError(f"{what}[{k}]: {item} {i} is out of range (0 to {n - 1})")
    return np.asarray(value, dtype=np.int64).reshape(-1)


def points(value, what: str, dims: tuple = (2, 3)) -> np.ndarray:
    """A list of points, each a list of ``dims`` finite numbers, as an (n, d) float array (d the
    largest length given, shorter points padded with zeros); an error names the first bad one."""
    rows = json_list(value, what)
    for k, p in enumerate(rows):
        if not isinstance(p, (list, tuple)) or len(p) not in dims:
            raise VaultgramError(f"{what}[{k}]: expected a point of {' or '.join(map(str, dims))} numbers, got {p!r}")
        for c in p:
            if not is_number(c):
                raise VaultgramError(f"{what}[{k}]: expected finite numbers, got {c!r}")
    width = max((len(p) for p in rows), default=min(dims))
    out = np.zeros((len(rows), width))
    for k, p in enumerate(rows):
        out[k, :len(p)] = p
    return out


def graph_document(value, what: str = "graph") -> dict:
    """A host graph's JSON (``rules run --graph`` and the other rules commands): an object with a
    list ``nodes`` and, unless the graph has none, a list ``edges``, each a list of objects. ``{}``
    given for either list, or as the whole file (which holds no graph: no ``nodes``), is refused,
    as is a file that is no object. The engine's ``HostGraph.from_json`` checks types, ids and
    attributes after this.

    >>> graph_document({"nodes": [{"id": 0, "type": "Corner"}]})["nodes"][0]["type"]
    'Corner'
    >>> graph_document({"nodes": [], "edges": {}})
    Traceback (most recent call last):
    ...
    vaultgram.grammar.errors.InputError: graph.edges: expected a list, got an object
    >>> graph_document({})
    Traceback (most recent call last):
    ...
    vaultgram.grammar.errors.InputError: graph: expected an object with a list 'nodes' (and 'edges'), got no 'nodes'
    """
    if "nodes" not in json_object(value, what):
        raise VaultgramError(f"{what}: expected an object with a list 'nodes' (and 'edges'), got no 'nodes'")
    for key in ("nodes", "edges"):
        for k, item in enumerate(json_list(value.get(key, []), f"{what}.{key}")):
            json_object(item, f"{what}.{key}[{k}]")
    return value
