"""Shared fixtures: paths to the examples and to the shared architecture data (never copied here)."""

from __future__ import annotations

import atexit
import os
import shutil
import tempfile
from pathlib import Path

import pytest
from hypothesis import settings

from paths import ARCHITECTURE, EXAMPLES

# The caches (parse, checked rule files, checked rulebooks: vaultgram.grammar.cache's folder) of a test
# session live in a folder of its own, removed at its end, unless VAULTGRAM_CACHE_DIR is set: the
# rulebook cache keys an entry by its files' paths, and tests' rule files are in temporary folders, so
# each run would leave some 10 MB of new entries in the user's cache. Set before xdist starts its
# workers, which share it.
if "VAULTGRAM_CACHE_DIR" not in os.environ:
    os.environ["VAULTGRAM_CACHE_DIR"] = tempfile.mkdtemp(prefix="vaultgram-tests-")
    atexit.register(shutil.rmtree, os.environ["VAULTGRAM_CACHE_DIR"], ignore_errors=True)

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

