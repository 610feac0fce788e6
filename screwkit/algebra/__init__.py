"""The algebra under everything: screws and screw systems, projective points, lines and planes,
and the numeric/symbolic backend (the one module where float and sympy code differ).

Layer 1 of the data flow (docs/architecture.md): it imports nothing of screwkit but the exceptions.
"""

__all__: list[str] = []
