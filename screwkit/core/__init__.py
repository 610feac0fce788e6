"""The analysis core: constraint, actuation and global wrench systems over a batch of poses, the
verdicts and closeness measures, the Jacobians, the generic (symbolic) analysis and the motion of
a graph along its own twists.

Layer 3 of the data flow (docs/architecture.md): built on :mod:`screwkit.graphs`.
"""

__all__: list[str] = []
