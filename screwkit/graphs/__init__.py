"""Twist graphs: joints (edges carrying screws), the graphs themselves (schema, loops, equivalent
graph) and their topology (limbs, legs, one series-parallel tree).

Layer 2 of the data flow (docs/architecture.md): built on :mod:`screwkit.algebra`.
"""

__all__: list[str] = []
