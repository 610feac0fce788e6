"""Analyses over many poses, all through the posed mechanism: transmission indices, workspace maps,
singularity loci and trajectory checks.

Layer 6 of the data flow (docs/architecture.md): built on :mod:`screwkit.robots`.
"""

__all__: list[str] = []
