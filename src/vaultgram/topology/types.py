"""The type names the vault pipeline puts in its graphs, in one place.

The node and edge types themselves (their parents and attributes) are declared by the rulebook, in
``rules/schema.vgr``; the pipeline builds its graph with the names below, and
:func:`vaultgram.topology.rulebook.load_vault_rulebook` checks that a rulebook declares every one.
"""

from __future__ import annotations

__all__ = ["PLAN_EDGES", "SKELETON_NODES", "PIPELINE_TYPES", "PATCH_STRATEGIES", "TOPOLOGY_STRATEGY"]

#: The edges that draw the patch layout in the plan (§3.1, Figure 2f): patch sides are made of them.
PLAN_EDGES = ("Branch", "Rebranch", "Boundary", "Curve", "Diagonal")

#: Nodes standing for skeleton nodes: singularities and the cuts of skeleton loops.
SKELETON_NODES = ("Singularity", "LoopVertex")

#: Every node and edge type the pipeline creates; a rulebook's schema must declare them all.
PIPELINE_TYPES = ("Singularity", "LoopVertex", "BoundaryVertex", "Corner", "FeaturePoint", "CurvePoint",
                  "CurveExtremity", "Branch", "Boundary", "Curve", "Dual", "Rebranch", "Diagonal", "Patch",
                  "PatchCorner")

#: The strategy that rewrites the skeleton graph into the block decomposition (pruning, rebranching).
TOPOLOGY_STRATEGY = "topology"

#: Strategies run on the Patch nodes, in this order: repair curve T-junctions, then split at features.
PATCH_STRATEGIES = ("curve_patching", "patching")
