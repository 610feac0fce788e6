"""Twist graphs: joints (edges carrying screws), the graphs themselves (schema, loops, equivalent
graph) and their topology (limbs, legs, one series-parallel tree).

:mod:`~screwkit.graphs.joints` (one joint) → :mod:`~screwkit.graphs.twistgraph` (schema, frame, data)
→ :mod:`~screwkit.graphs.jointtable` (the joints over a batch of poses), :mod:`~screwkit.graphs.loops`
(loops, loop closure), :mod:`~screwkit.graphs.reduction` (series-parallel reduction, equivalent
graph), :mod:`~screwkit.graphs.topology` (the structure, analysed once).

Layer 2 of the data flow (docs/architecture.md): built on :mod:`screwkit.algebra`.
"""

__all__: list[str] = []
