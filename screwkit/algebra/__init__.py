"""The algebra under everything: screws and screw systems, projective points, lines and planes,
and the numeric/symbolic backend (the only place where float and sympy code differ).

Screws: :mod:`~screwkit.algebra.screw` (the conventions and kernels), :mod:`~screwkit.algebra.screwvalue`
(the value class), :mod:`~screwkit.algebra.screwsystem`, :mod:`~screwkit.algebra.readable`,
:mod:`~screwkit.algebra.motion_type`. Projective geometry: :mod:`~screwkit.algebra.projective`,
:mod:`~screwkit.algebra.incidence`. The backend: :mod:`~screwkit.algebra.backend`,
:mod:`~screwkit.algebra.branch_values`, :mod:`~screwkit.algebra.zero_tests`,
:mod:`~screwkit.algebra.ranks`, :mod:`~screwkit.algebra.checks`, with the generic (symbolic) kernels
:mod:`~screwkit.algebra.symbolic`, :mod:`~screwkit.algebra.symbolic_bases`,
:mod:`~screwkit.algebra.cramer`. Frames and compiled twins: :mod:`~screwkit.algebra.reference_frame`,
:mod:`~screwkit.algebra.compiled`.

Layer 1 of the data flow (docs/architecture.md): it imports nothing of screwkit but the exceptions.
"""

__all__: list[str] = []
