"""The Python API (vaultgram.api, by name on the package): every name resolves, every function is
documented with Parameters, Returns, Raises and Examples (the examples run in tests/test_doctests.py)."""

from __future__ import annotations

import inspect

import pytest

import vaultgram
from vaultgram import api

from paths import EXAMPLES

FUNCTIONS = [name for name in api.__all__ if inspect.isfunction(getattr(api, name))]


def test_the_package_gives_the_api_by_name():
    assert set(api.__all__) <= set(vaultgram.__all__)
    for name in api.__all__:
        assert getattr(vaultgram, name) is getattr(api, name)
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        vaultgram.nope  # noqa: B018


@pytest.mark.parametrize("name", FUNCTIONS)
def test_every_function_is_documented(name):
    doc = inspect.getdoc(getattr(api, name))
    for section in ("Parameters\n----------", "Returns\n-------", "Raises\n------", "Examples\n--------"):
        assert section in doc, f"{name}: no {section.splitlines()[0]}"


def test_stages_compose_as_design_does():
    """formfind(mesh(plan)) is design's network; tessellate needs only the network."""
    plan = vaultgram.load(EXAMPLES / "quad_with_hole.json")
    m = vaultgram.mesh(plan, target_length=1.0)
    network = vaultgram.formfind(m, zmax=3.0)
    result = vaultgram.design(plan, target_length=1.0, zmax=3.0, tessellation=None)
    assert (network.vertices == result.network.vertices).all() and (network.q == result.network.q).all()
    assert isinstance(result, vaultgram.Result)
