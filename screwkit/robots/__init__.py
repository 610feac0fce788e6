"""Robots: the family protocol and the families (closed-form kinematics), the catalog and snapshot
files, and the posed mechanism, the one composer of every quantity over a batch of poses.

Layer 5 of the data flow (docs/architecture.md): built on :mod:`screwkit.core` and :mod:`screwkit.gca`.
"""

__all__: list[str] = []
