"""Where the benchmarks find their inputs: the bundled examples, and the shared plans in ``shared``
beside the checkout (from a worktree one level deeper, ``/work/wt/NAME``, the one beside its
parent), as the tests do (``tests/paths.py``). The scripts skip the shared plans when they are absent."""

from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "examples"
SHARED = next((d / "shared" for d in (REPO.parent, REPO.parent.parent) if (d / "shared").is_dir()),
              REPO.parent / "shared")
ARCHITECTURE = SHARED / "data" / "architecture"
