"""What belongs to one source paper, built on the public stages: paper 004's transmission indices of
the four-limb robots (pressure angles, LTI, Table 4).

Layer 7 of the data flow (docs/architecture.md).
"""

__all__: list[str] = []
