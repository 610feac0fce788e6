"""Constants shared by the numpy kernels and their numba twins (private).

Both implementations of a kernel must read one value, so they live below both: the closed forms'
margin (:mod:`screwkit.core._closed_forms`), the couple tolerance of the actuation rows
(:mod:`screwkit.core._closing`) and the op codes of a frame program (:mod:`screwkit.core._program`,
run by :func:`screwkit.core._program_numba.run_program`).

Examples
--------
>>> CLOSED_FORM_MARGIN, SPAN, JOINT_ROWS
(100.0, 0, 0)
"""

from __future__ import annotations

from ..algebra import backend as B

__all__ = [
    "CLOSED_FORM_MARGIN",
    "COMPANION",
    "CONTRACT",
    "COUPLE_RTOL",
    "EXTEND",
    "JOINT_ROWS",
    "PARALLELOGRAM",
    "RECIPROCAL",
    "ROD",
    "SLOT_ROWS",
    "SPAN",
]

#: A closed-form rank decision (:func:`~screwkit.core._closed_forms.extend`,
#: :func:`~screwkit.core._closed_forms.contract`) is taken only where its measure lies outside
#: ``[rtol·top / CLOSED_FORM_MARGIN, rtol·top · CLOSED_FORM_MARGIN]`` (``top`` the span rule's
#: largest generator norm): there the rule cannot decide otherwise; within that band (and at a NaN)
#: the caller runs the generic span and complement.
CLOSED_FORM_MARGIN = 100.0

#: A user-frame wrench row is drawn as a unit couple where its force is at most this fraction of its
#: moment over the length (:func:`screwkit.core._closing.unit_size`).
COUPLE_RTOL = B.DEFAULT_RTOL

#: Operation codes of a frame program (:class:`screwkit.core._program.Program`).
SPAN, RECIPROCAL, ROD, EXTEND, CONTRACT, PARALLELOGRAM, COMPANION = 0, 1, 2, 3, 4, 5, 6
#: Source kinds of a span: joint screw rows ``(start, count)`` or a slot's rows ``(slot, bound)``.
JOINT_ROWS, SLOT_ROWS = 0, 1
