"""The type names the vault pipeline puts in its graphs, in one place.

The node and edge types themselves (their parents and attributes) are declared by the rulebook, in
``rules/schema.vgr``; the pipeline builds its graph with the names below, and
:func:`vaultgram.topology.rulebook.load_vault_rulebook` checks that a rulebook declares every one.
"""

from __future__ import annotations

__all__ = ["PLAN_EDGES", "SKELETON_NODES", "PIPELINE_TYPES", "PATCH_STRATEGIES", "TOPOLOGY_STRATEGY",
           "SINGULARITY", "LOOP_VERTEX", "BOUNDARY_VERTEX", "CORNER", "FEATURE_POINT", "CURVE_POINT",
           "CURVE_EXTREMITY", "PATCH", "BRANCH", "BOUNDARY", "CURVE", "DUAL", "REBRANCH", "DIAGONAL",
           "PATCH_CORNER", "SKELETON_VERTEX"]

# Nodes (§3.1, §4): skeleton vertices, boundary points, feature and curve points, and patches.
SINGULARITY = "Singularity"  # the centre of a singular face of the Delaunay mesh
LOOP_VERTEX = "LoopVertex"  # a cut of a skeleton loop without singularity
BOUNDARY_VERTEX = "BoundaryVertex"  # a point of a ring
CORNER = "Corner"  # a ring point at a polygon corner, or where a curve meets the ring
FEATURE_POINT = "FeaturePoint"  # an inner point feature (§4.1)
CURVE_POINT = "CurvePoint"  # a point of a curve feature (§4.2)
CURVE_EXTREMITY = "CurveExtremity"  # an end of a curve feature off the boundary (§4.2)
PATCH = "Patch"  # a face of the plan, for the patching rules

# Edges.
BRANCH = "Branch"  # a skeleton branch, with its polyline
BOUNDARY = "Boundary"  # a segment between consecutive ring points
CURVE = "Curve"  # a curve-feature segment, from the curve's first point towards its last
DUAL = "Dual"  # a skeleton vertex -> a vertex of its dual face
REBRANCH = "Rebranch"  # drawn by the rebranching rule (Figure 2e)
DIAGONAL = "Diagonal"  # drawn by a patching rule (Figures 4 and 8)
PATCH_CORNER = "PatchCorner"  # a Patch -> one of its corners

#: The schema's parent type of the skeleton vertices (Singularity, LoopVertex); the pipeline makes none.
SKELETON_VERTEX = "SkeletonVertex"

#: The edges that draw the patch layout in the plan (§3.1, Figure 2f): patch sides are made of them.
PLAN_EDGES = (BRANCH, REBRANCH, BOUNDARY, CURVE, DIAGONAL)

#: Nodes standing for skeleton nodes: singularities and the cuts of skeleton loops.
SKELETON_NODES = (SINGULARITY, LOOP_VERTEX)

#: Every node and edge type the pipeline creates; a rulebook's schema must declare them all.
PIPELINE_TYPES = (SINGULARITY, LOOP_VERTEX, BOUNDARY_VERTEX, CORNER, FEATURE_POINT, CURVE_POINT, CURVE_EXTREMITY,
                  BRANCH, BOUNDARY, CURVE, DUAL, REBRANCH, DIAGONAL, PATCH, PATCH_CORNER)

#: The strategy that rewrites the skeleton graph into the block decomposition (pruning, rebranching).
TOPOLOGY_STRATEGY = "topology"

#: Strategies run on the Patch nodes, in this order: repair curve T-junctions, then split at features.
PATCH_STRATEGIES = ("curve_patching", "patching")
