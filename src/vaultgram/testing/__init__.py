"""Property-based testing of rulebooks (``vaultgram rules test``): random domains drawn with hypothesis
(:mod:`.domains`) run through the topology stage with the rulebook's invariants checked
(:mod:`.rulestest`). Needs hypothesis (the ``test`` or ``rulestest`` extra)."""
