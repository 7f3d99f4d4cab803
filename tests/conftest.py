"""Shared fixtures: paths to the examples and to the shared architecture data (never copied here)."""

from __future__ import annotations

from pathlib import Path

import pytest
from paths import ARCHITECTURE, EXAMPLES


@pytest.fixture(scope="session")
def examples_dir() -> Path:
    return EXAMPLES


@pytest.fixture(scope="session")
def architecture_dir() -> Path:
    if not ARCHITECTURE.is_dir():
        pytest.skip(f"shared architecture data not found at {ARCHITECTURE}")
    return ARCHITECTURE

