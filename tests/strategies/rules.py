"""The schema of the engine tests, and rulebooks of it.

    node A { w: int = 0 }     node B : A     node C { w: int = 0 }
    edge E (A -- A) { m: int = 0 }           edge D (A -> C) { m: int = 0 }
"""

from __future__ import annotations

from vaultgram.engine.rulebook import rulebook_from_text

SCHEMA = """
schema t {
  node A { w: int = 0 }
  node B : A
  node C { w: int = 0 }
  edge E (A -- A) { m: int = 0 }
  edge D (A -> C) { m: int = 0 }
}
"""


def book(rules: str = "", functions=None):
    """A rulebook of the test schema plus ``rules``."""
    return rulebook_from_text(SCHEMA + rules, functions)
