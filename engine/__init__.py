"""A general typed graph-rewriting engine (it knows nothing about vaults)."""
