"""Examples per second of ``vaultgram rules test`` on the bundled rulebook (issue 14).

Run: ``python benchmarks/rules_test.py [--examples N] [--seed S]``. Runs the property test of
:func:`vaultgram.testing.rulestest.check_rulebook` (derandomised unless a seed is given) and prints the
examples, rule applications, invariant checks, seconds and examples per second. Floor: 500 examples in
under 5 minutes (1.7 examples/s) on the 2-core machine.
"""

from __future__ import annotations

import argparse

from vaultgram.testing.rulestest import check_rulebook
from vaultgram.topology.rulebook import default_rules_dir


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--examples", type=int, default=500)
    parser.add_argument("--seed", type=int, default=None)
    args = parser.parse_args()
    summary = check_rulebook(default_rules_dir(), args.examples, args.seed)
    if summary.failure is not None:
        raise SystemExit(f"FAILED: {summary.failure.message}")
    rate = summary.examples / summary.seconds
    print(f"{summary.text()}; {rate:.1f} examples/s (floor: 500 in 300 s, 1.7/s)")


if __name__ == "__main__":
    main()
