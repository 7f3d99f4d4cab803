"""vaultgram for COMPAS, compas_tna and RhinoVAULT users (optional extra ``vaultgram[compas]``).

The functions live in :mod:`vaultgram.io.compasfiles`; this module is their public name::

    from vaultgram.compas import to_compas_mesh, to_formdiagram, from_compas_mesh
"""

from vaultgram.io.compasfiles import from_compas_mesh, to_compas_mesh, to_formdiagram

__all__ = ["to_compas_mesh", "to_formdiagram", "from_compas_mesh"]
