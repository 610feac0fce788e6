"""numba kernels of :mod:`screwkit.core._limbs`: limbs' systems, actuation wrenches, transmissions (private).

Each loop does, pose by pose, the floating-point operations of its numpy twin in the same order
(no ``fastmath``), so the two paths agree bit for bit (:mod:`screwkit.core.frames`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._frames_numba import _residual_into

__all__ = [
    "limb_systems",
    "limb_wrenches",
    "transmissions",
]

Array = np.ndarray


@njit(cache=True, inline="always")
def _limb_into(  # pragma: no cover - compiled
    locked: Array,
    locked_order: Array,
    passive: Array,
    actuated: Array,
    rtol: float,
    p: int,
    k: int,
    out: tuple,
    t: Array,
    coefficients: Array,
) -> None:
    """Pose ``p``, limb ``k`` of :func:`limb_systems` into ``out = (perpendicular, serial, free,
    free_order, direction)`` (``free`` of length 0: not written)."""
    perpendicular, serial, free, free_order, direction = out
    for s in range(6):
        t[s] = actuated[p, k, s]
    for _ in range(2):  # the residual against the locked rows, re-orthogonalised once
        for i in range(6):
            total = 0.0
            for s in range(6):
                total += t[s] * locked[p, k, i, s]
            coefficients[i] = total
        for i in range(6):
            for s in range(6):
                t[s] -= coefficients[i] * locked[p, k, i, s]
    total = 0.0
    for s in range(6):
        total += t[s] * t[s]
    size = math.sqrt(total)
    is_serial = size <= rtol
    serial[p, k] = is_serial
    order = locked_order[p, k]
    free_order[p, k] = order + (0 if is_serial else 1)
    slot = min(order, 5)
    divisor = size if size > 0 else 1.0
    for s in range(6):
        perpendicular[p, k, s] = t[s]
        if free.shape[0] and not is_serial:
            free[p, k, slot, s] = t[s] / divisor
    for i in range(6):  # SWAP t⊥ projected on the passive rows
        total = 0.0
        for s in range(6):
            total += passive[p, k, i, s] * t[(s + 3) % 6]
        coefficients[i] = total
    squares = 0.0
    for s in range(6):
        total = 0.0
        for i in range(6):
            total += coefficients[i] * passive[p, k, i, s]
        direction[p, k, s] = total
        squares += total * total
    size = math.sqrt(squares)
    divisor = size if size > 0 else 1.0
    for s in range(6):
        direction[p, k, s] /= divisor


@njit(cache=True, inline="always")
def _limb_outputs(locked: Array, free_rows: bool) -> tuple:  # pragma: no cover - compiled
    """The arrays :func:`_limb_into` writes, for ``locked (n, l, 6, 6)``."""
    n, limbs = locked.shape[0], locked.shape[1]
    free = locked.copy() if free_rows else np.zeros((0, limbs, 6, 6))
    return (
        np.empty((n, limbs, 6)),
        np.empty((n, limbs), dtype=np.bool_),
        free,
        np.empty((n, limbs), dtype=np.int64),
        np.empty((n, limbs, 6)),
    )


@njit(cache=True)
def limb_systems(
    locked: Array, locked_order: Array, passive: Array, actuated: Array, rtol: float, free_rows: bool
) -> tuple[Array, Array, Array, Array, Array]:  # pragma: no cover - compiled
    """:func:`screwkit.core._limbs.limb_systems` pose by pose and limb by limb: ``locked``, ``passive``
    ``(n, l, 6, 6)``, ``locked_order (n, l)``, ``actuated (n, l, 6)``; the free rows ``(0, l, 6, 6)``
    unless ``free_rows``."""
    out = _limb_outputs(locked, free_rows)
    t, coefficients = np.empty(6), np.empty(6)
    for p in range(actuated.shape[0]):
        for k in range(actuated.shape[1]):
            _limb_into(locked, locked_order, passive, actuated, rtol, p, k, out, t, coefficients)
    return out


@njit(cache=True)
def _scaled_magnitude(row: Array, rtol: float) -> float:  # pragma: no cover - compiled
    """:func:`screwkit.core._limbs.scaled_magnitudes` of one row ``(6,)``."""
    directions = 0.0
    moments = 0.0
    for s in range(3):
        directions += row[s] * row[s]
    for s in range(3, 6):
        moments += row[s] * row[s]
    directions, moments = math.sqrt(directions), math.sqrt(moments)
    return directions if directions > rtol * moments else moments


@njit(cache=True, inline="always")
def _transmission_into(  # pragma: no cover - compiled
    raw: Array, twists: Array, rtol: float, p: int, k: int, wrench: Array, out: Array
) -> None:
    """Pose ``p``, limb ``k`` of :func:`transmissions` into ``wrench``, ``out``."""
    total = 0.0
    for s in range(6):
        total += raw[p, k, s] * raw[p, k, s]
    size = math.sqrt(total)
    divisor = size if size > 0 else 1.0
    for s in range(6):
        wrench[p, k, s] = raw[p, k, s] / divisor
    product = 0.0
    for s in range(6):
        product += wrench[p, k, s] * twists[p, k, (s + 3) % 6]
    product = abs(product)
    denominator = _scaled_magnitude(wrench[p, k], rtol) * _scaled_magnitude(twists[p, k], rtol)
    out[p, k] = product / denominator if denominator > 0 else 0.0


@njit(cache=True)
def transmissions(  # pragma: no cover - compiled
    raw: Array, twists: Array, rtol: float
) -> tuple[Array, Array]:
    """:func:`screwkit.core._limbs.transmissions` pose by pose: ``raw``, ``twists`` ``(n, l, 6)``."""
    n, limbs = raw.shape[0], raw.shape[1]
    wrench = np.empty((n, limbs, 6))
    out = np.empty((n, limbs))
    for p in range(n):
        for k in range(limbs):
            _transmission_into(raw, twists, rtol, p, k, wrench, out)
    return wrench, out


@njit(cache=True, inline="always")
def _not_line(row: Array, line_rtol: float) -> bool:  # pragma: no cover - compiled
    """:func:`screwkit.core._limbs.not_lines` of one row ``(6,)``."""
    forces = row[0] * row[0] + row[1] * row[1] + row[2] * row[2]
    pitch = row[0] * row[3] + row[1] * row[4] + row[2] * row[5]
    norm = math.sqrt(forces + (row[3] * row[3] + row[4] * row[4] + row[5] * row[5]))
    size = math.sqrt(forces)
    size = size if (size >= 1e-300 or math.isnan(size)) else 1e-300  # np.maximum: NaN propagates
    return abs(pitch) > line_rtol * size * norm


@njit(cache=True)
def limb_wrenches(  # pragma: no cover - compiled
    locked: Array,
    locked_order: Array,
    passive: Array,
    actuated: Array,
    legs: Array,
    coupled: Array,
    leg_of: Array,
    rtol: float,
    line_rtol: float,
) -> tuple[Array, Array, Array, Array, Array, Array, Array]:
    """:func:`screwkit.core._limbs.limb_wrenches` in one pass: per pose, the limb systems
    (:func:`limb_systems`), whether each actuation direction is a line (:func:`_not_line`), the
    unit wrenches along the directions with their transmissions (:func:`transmissions`) and the
    coupled limbs' wrenches less their part in their leg's frame
    (:func:`~screwkit.core._frames_numba.residual`)."""
    n, limbs, m = actuated.shape[0], actuated.shape[1], coupled.shape[0]
    out = _limb_outputs(locked, False)
    wrench, index = np.empty((n, limbs, 6)), np.empty((n, limbs))
    not_line = np.empty((n, limbs), dtype=np.bool_)
    residuals = np.empty((n, m, 6))
    t, coefficients = np.empty(6), np.empty(6)
    for p in range(n):
        for k in range(limbs):
            _limb_into(locked, locked_order, passive, actuated, rtol, p, k, out, t, coefficients)
            not_line[p, k] = _not_line(out[4][p, k], line_rtol)
            _transmission_into(out[4], actuated, rtol, p, k, wrench, index)
        for j in range(m):
            _residual_into(wrench[p, coupled[j]], legs[p, leg_of[j]], residuals[p, j], coefficients)
    return out[1], out[3], out[4], wrench, index, residuals, not_line
