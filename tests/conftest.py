"""Shared fixtures: paths to the examples and to the shared architecture data (never copied here)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import settings

from paths import ARCHITECTURE, EXAMPLES

# In CI (CI=true) property tests draw the same examples every run: a landing never depends on luck.
# Locally they explore new examples each run.
settings.register_profile("ci", derandomize=True, database=None, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")


@pytest.fixture(scope="session")
def examples_dir() -> Path:
    return EXAMPLES


@pytest.fixture(scope="session")
def architecture_dir() -> Path:
    if not ARCHITECTURE.is_dir():
        pytest.skip(f"shared architecture data not found at {ARCHITECTURE}")
    return ARCHITECTURE

