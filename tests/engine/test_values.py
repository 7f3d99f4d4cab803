"""The table of value types (engine/values.py): run-time conformance and the static rules."""

from __future__ import annotations

import numpy as np
import pytest

from vaultgram.engine.errors import RuleTypeError
from vaultgram.engine.values import (
    VALUE_TYPES,
    check_type_name,
    normalise_value,
    passable,
    storable,
    value_conforms,
)

FITS = {
    "int": [0, -3],
    "float": [0, 1.5, float("inf")],
    "bool": [True, False],
    "str": ["", "a"],
    "vec2": [(0, 1.5)],
    "vec3": [(0.0, 1.0, 2.0)],
    "list": [(), [1, "a"], (1.0, 2.0)],
    "any": [None, object(), True],
}
MISFITS = {
    "int": [True, 1.0, "1"],
    "float": [False, "1.0", None],
    "bool": [0, 1, "true"],
    "str": [1, None],
    "vec2": [(1.0,), (1.0, 2.0, 3.0), [1.0, 2.0], (1.0, float("nan")), (True, 1.0)],
    "vec3": [(1.0, 2.0), (1.0, 2.0, float("inf"))],
    "list": ["ab", None, {1: 2}],
    "any": [],
}


def test_the_table_lists_the_language_types_in_order():
    assert list(VALUE_TYPES) == ["int", "float", "bool", "str", "vec2", "vec3", "list", "any"]


@pytest.mark.parametrize("name", sorted(VALUE_TYPES))
def test_value_conforms(name):
    assert all(value_conforms(v, name) for v in FITS[name])
    assert not any(value_conforms(v, name) for v in MISFITS[name])


def test_unknown_types_fit_nothing_and_are_reported():
    assert not value_conforms(1, "vec4")
    with pytest.raises(RuleTypeError, match="unknown attribute type 'vec4'"):
        check_type_name("vec4", None)
    check_type_name("vec2", None)


def test_normalise_value_makes_numpy_plain():
    assert normalise_value(np.array([1.0, 2.0])) == (1.0, 2.0)
    assert normalise_value([np.int64(3), [1, 2]]) == (3, (1, 2))
    assert type(normalise_value(np.float64(2.5))) is float
    assert normalise_value("ab") == "ab"


def test_storable_and_passable():
    # an attribute takes ints for floats, lists for vectors (length checked at run time), vectors for lists
    stores = {(s, d) for s in VALUE_TYPES for d in VALUE_TYPES if storable(s, d)}
    assert stores == {(t, t) for t in VALUE_TYPES} | {(s, "any") for s in VALUE_TYPES} | {
        ("any", d) for d in VALUE_TYPES
    } | {("int", "float"), ("list", "vec2"), ("list", "vec3"), ("vec2", "list"), ("vec3", "list")}
    # a function parameter is stricter: only int widens (to float), plus the kinds number and vec
    assert passable("float", "int") and not passable("int", "float")
    assert not passable("vec2", "list") and not passable("list", "vec2")
    assert passable("number", "int") and passable("number", "float") and not passable("number", "bool")
    assert passable("vec", "vec3") and not passable("vec", "list")
    assert passable("none", "none") and not passable("int", "none")
    assert passable("any", "str") and passable("str", "any")
