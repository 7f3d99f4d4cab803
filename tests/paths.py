"""Where the tests find their inputs: the bundled examples and the shared data beside the checkout."""

from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "examples"
# beside the checkout; from a worktree one level deeper (/work/wt/NAME), the one beside its parent
SHARED = next((d / "shared" for d in (REPO.parent, REPO.parent.parent) if (d / "shared").is_dir()),
              REPO.parent / "shared")
ARCHITECTURE = SHARED / "data" / "architecture"
REFERENCE = SHARED / "reference"
ARCHITECTURE_PLANS = sorted(ARCHITECTURE.glob("*.json")) if ARCHITECTURE.is_dir() else []
