"""numba interpreter of a frame program (:mod:`screwkit.core._program`; private).

The compiled loop that runs a mechanism's whole program pose by pose, op by op, with
the rank rule's and the closed forms' per-pose loops.
Each loop does, pose by pose, the floating-point operations of its numpy twin in the same order
(no ``fastmath``), so the two paths agree bit for bit (:mod:`screwkit.core.frames`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._closed_forms_numba import contract_into, extend_into, parallelogram_into, rod_into
from ._frames_numba import complement_into, span_into
from ._kernel_constants import (
    COMPANION,
    CONTRACT,
    EXTEND,
    JOINT_ROWS,
    PARALLELOGRAM,
    RECIPROCAL,
    ROD,
    SLOT_ROWS,
)

__all__ = [
    "run_program",
]

Array = np.ndarray


@njit(cache=True)
def run_program(
    scaled: Array, rtol: float, ops: Array, sources: Array, n_slots: int, outputs: Array
) -> tuple[Array, Array]:  # pragma: no cover - compiled
    """A frame program, pose by pose: ``scaled (n, rows, 6)`` joint screws; ``ops (m, 4)`` rows
    ``(code, slot, first, count)``: :data:`~screwkit.core._kernel_constants.SPAN` of ``sources[first : first
    + count]`` (rows
    ``(kind, a, b)``), :data:`RECIPROCAL` of slot ``first``, :data:`ROD`, the reciprocal of the
    span of two spherical joints' rows (:func:`rod_into`, else span and reciprocal),
    :data:`EXTEND`, the span of one joint screw and a twist frame (:func:`extend_into`, else the
    span), :data:`CONTRACT`, the reciprocal of the span of one joint screw and the twists of a
    wrench frame (:func:`contract_into`, else the span of the screw and those twists, and its
    reciprocal), or :data:`PARALLELOGRAM`, two rods' wrenches and twists
    (:func:`parallelogram_into`, else the span of the rods' frames and its reciprocal) into
    ``slot`` and ``slot + 1`` (whose op is a :data:`COMPANION`, doing nothing); each other op into
    ``slot``. The first two sources of :data:`EXTEND` and :data:`CONTRACT` are a joint's one screw
    and a slot's frame, in the chain's order; a third source of :data:`CONTRACT` is the slot of the
    twist frame that its fallback spans (the same rows as an :data:`EXTEND` of the same chain, so
    the two decide alike), else those twists are the wrench frame's reciprocal. Returns the rows
    ``(n, len(outputs), 6, 6)`` and orders of the ``outputs`` slots. A
    span or reciprocal is exactly what the batched kernel :func:`~screwkit.core._frames_numba.span` or
    :func:`~screwkit.core._frames_numba.complement`
    (``swap``) computes on that pose, so running a program equals running its ops one by one (the
    numpy path's way, :func:`screwkit.core._program.run_program`) up to the two paths' round-off."""
    n = scaled.shape[0]
    slots = np.zeros((n_slots, 6, 6))
    orders = np.zeros(n_slots, dtype=np.int64)
    out_rows = np.zeros((n, outputs.shape[0], 6, 6))
    out_orders = np.zeros((n, outputs.shape[0]), dtype=np.int64)
    most = 6
    for i in range(sources.shape[0]):
        most = max(most, sources[i, 2])
    work = np.empty((most * sources.shape[0] + 6, 6))
    norms = np.empty(work.shape[0])
    pivot = np.empty(6)
    coefficients = np.empty(6)
    a = np.empty((6, 6))
    v = np.zeros((6, 6))
    tau = np.zeros(6)
    y = np.empty(6)
    twists = np.empty((6, 6))
    for p in range(n):
        for op in range(ops.shape[0]):
            code, slot, first, count = ops[op, 0], ops[op, 1], ops[op, 2], ops[op, 3]
            if code == RECIPROCAL:
                complement_into(slots[first], orders[first], True, slots[slot], a, v, tau, y)
                orders[slot] = 6 - orders[first]
                continue
            if code == COMPANION:  # written by the op before it
                continue
            if code == PARALLELOGRAM:
                x, z = sources[first, 1], sources[first + 1, 1]
                rod_a, rod_b, into_w, into_t = slots[x], slots[z], slots[slot], slots[slot + 1]
                if parallelogram_into(rod_a, orders[x], rod_b, orders[z], rtol, into_w, into_t):
                    orders[slot], orders[slot + 1] = 2, 4
                    continue
            if code == EXTEND or code == CONTRACT:  # one joint screw and one frame, in closed form
                joint = first if sources[first, 0] == JOINT_ROWS else first + 1
                x = sources[2 * first + 1 - joint, 1]
                t = scaled[p, sources[joint, 1]]
                if code == EXTEND:
                    order = extend_into(slots[x], orders[x], t, rtol, slots[slot], pivot, coefficients)
                else:
                    order = contract_into(slots[x], orders[x], t, rtol, slots[slot], pivot, coefficients)
                if order >= 0:
                    orders[slot] = order
                    continue
            k = 0
            for q in range(first, first + (2 if code == CONTRACT else count)):
                kind, x, size = sources[q, 0], sources[q, 1], sources[q, 2]
                if code == CONTRACT and kind == SLOT_ROWS and count == 3:  # the node's twist frame
                    kind, x, size = sources[first + 2, 0], sources[first + 2, 1], sources[first + 2, 2]
                if kind == JOINT_ROWS:
                    for i in range(size):
                        for s in range(6):
                            work[k, s] = scaled[p, x + i, s]
                        k += 1
                elif code == CONTRACT and count == 2:  # the twists of the wrench frame in slot x
                    complement_into(slots[x], orders[x], True, twists, a, v, tau, y)
                    for i in range(6 - orders[x]):
                        for s in range(6):
                            work[k, s] = twists[i, s]
                        k += 1
                else:  # a slot's rows up to its bound; those beyond its order are zero, left out
                    for i in range(min(size, orders[x])):
                        for s in range(6):
                            work[k, s] = slots[x, i, s]
                        k += 1
            if code == ROD or code == CONTRACT:
                if code == ROD and rod_into(work, rtol, slots[slot]):
                    orders[slot] = 1
                    continue
                order = span_into(work, k, rtol, a, norms, pivot, coefficients)  # the rule, spelt out
                complement_into(a.copy(), order, True, slots[slot], a, v, tau, y)
                orders[slot] = 6 - order
                continue
            orders[slot] = span_into(work, k, rtol, slots[slot], norms, pivot, coefficients)
            if code == PARALLELOGRAM:  # the twists, as a reciprocal op would
                complement_into(slots[slot], orders[slot], True, slots[slot + 1], a, v, tau, y)
                orders[slot + 1] = 6 - orders[slot]
        for i in range(outputs.shape[0]):
            out_rows[p, i] = slots[outputs[i]]
            out_orders[p, i] = orders[outputs[i]]
    return out_rows, out_orders
