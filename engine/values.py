"""The value types of attributes and rule parameters: one table, and every check made against it.

The rule language declares attributes and parameters with one of the types of :data:`VALUE_TYPES`.
Everything the engine asks about such a type is answered here and nowhere else:

* which names are value types (:func:`check_type_name`, used when a schema is built);
* whether a run-time value fits one (:func:`value_conforms`; ``int`` fits ``float``), after numpy
  values have been made plain (:func:`normalise_value`);
* which static expression types may be stored in an attribute of that type (:func:`storable`; a
  ``list`` expression may go into a ``vec2`` attribute, its length is checked at run time);
* which static types a host function's parameter of that kind takes (:func:`passable`, with the
  extra kinds ``number`` and ``vec`` of function signatures).

>>> value_conforms((1.0, 2), "vec2"), value_conforms(True, "int"), value_conforms(3, "float")
(True, False, True)
>>> storable("list", "vec2"), passable("number", "int"), passable("list", "vec2")
(True, True, False)
"""

from __future__ import annotations

import math
from typing import Callable, NamedTuple

import numpy as np

from .errors import RuleTypeError

NUMERIC = ("int", "float")
VECTORS = ("vec2", "vec3")


def _number(value: object) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _vector(n: int) -> Callable[[object], bool]:
    def conforms(value: object) -> bool:
        return (
            isinstance(value, tuple) and len(value) == n and all(_number(c) and math.isfinite(c) for c in value)
        )

    return conforms


class ValueType(NamedTuple):
    """A value type: how a run-time value is recognised, and which static types it takes.

    ``stores``: the static types of expressions that an attribute of this type can be given;
    ``takes``: the static types that a function parameter of this type accepts.
    """

    name: str
    conforms: Callable[[object], bool]
    stores: frozenset[str]
    takes: frozenset[str]


def _type(name: str, conforms, stores=(), takes=()) -> ValueType:
    return ValueType(name, conforms, frozenset((name, *stores)), frozenset((name, *takes)))


#: The value types, in the order they are listed to users.
VALUE_TYPES: dict[str, ValueType] = {
    t.name: t
    for t in (
        _type("int", lambda v: isinstance(v, int) and not isinstance(v, bool)),
        _type("float", _number, stores=("int",), takes=("int",)),
        _type("bool", lambda v: isinstance(v, bool)),
        _type("str", lambda v: isinstance(v, str)),
        _type("vec2", _vector(2), stores=("list",)),
        _type("vec3", _vector(3), stores=("list",)),
        _type("list", lambda v: isinstance(v, (list, tuple)), stores=VECTORS),
        _type("any", lambda v: True),
    )
}

#: Parameter kinds of host-function signatures that are not value types.
_ARGUMENT_KINDS = {"number": frozenset(NUMERIC), "vec": frozenset(VECTORS)}


def check_type_name(name: str, pos) -> None:
    """Raise a RuleTypeError at ``pos`` unless ``name`` is a value type."""
    if name not in VALUE_TYPES:
        raise RuleTypeError(
            f"unknown attribute type {name!r}", pos, "attribute types are: " + " ".join(VALUE_TYPES)
        )


def value_conforms(value: object, type_name: str) -> bool:
    """Whether a run-time value fits a declared value type (``int`` fits ``float``)."""
    spec = VALUE_TYPES.get(type_name)
    return spec is not None and spec.conforms(value)


def normalise_value(value: object) -> object:
    """Turn numpy scalars and arrays into plain Python values (vectors and lists become tuples)."""
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return tuple(normalise_value(v) for v in value)
    return value


def normalise_column(values, type_name: str) -> np.ndarray | list | None:
    """Many values of one declared type at once, made plain as :func:`normalise_value` makes each: a
    numpy array of the type's shape is checked as a whole (finite numbers of the right kind and
    count) and kept as a new numpy array (bool, int64, float64; vectors as rows of float64) whose
    elements ``tolist`` makes the plain values; other values become a list of plain values. None
    when ``values`` does not fit (the caller then names the first bad value)."""
    array = np.asarray(values)
    kind = array.dtype.kind
    if type_name in VECTORS:
        size = int(type_name[-1])
        if array.ndim != 2 or array.shape[1] != size or kind not in "iuf" or not np.isfinite(array).all():
            return None
        return array.astype(float)
    if array.ndim != 1:
        return None
    if type_name == "bool":
        return array.astype(bool) if kind == "b" else None
    if type_name == "int":
        return array.astype(int) if kind in "iu" else None
    if type_name == "float":
        return array.astype(float) if kind in "iuf" and np.isfinite(array).all() else None
    return [normalise_value(v) for v in values] if all(value_conforms(normalise_value(v), type_name)
                                                       for v in values) else None


def storable(static: str, declared: str) -> bool:
    """Whether an expression of static value type ``static`` may be stored in a ``declared`` attribute."""
    return declared == "any" or static == "any" or static in VALUE_TYPES[declared].stores


def passable(kind: str, static: str) -> bool:
    """Whether a value of static type ``static`` may be passed to a function parameter of ``kind``
    (a value type, ``number`` or ``vec``; an unknown kind takes only itself)."""
    if kind == "any" or static == "any":
        return True
    if kind in VALUE_TYPES:
        return static in VALUE_TYPES[kind].takes
    return static in _ARGUMENT_KINDS.get(kind, (kind,))
