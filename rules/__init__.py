"""The vault rulebook: rule files (``*.vgr``) shipped as package data, not Python code."""
