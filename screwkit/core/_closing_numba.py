"""numba kernels of :mod:`screwkit.core._closing`: global frame, closeness factors, actuation rows (private).

Each loop does, pose by pose, the floating-point operations of its numpy twin in the same order
(no ``fastmath``), so the two paths agree bit for bit (:mod:`screwkit.core.frames`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._frames_numba import span_into
from ._kernel_constants import COUPLE_RTOL

__all__ = [
    "closing",
    "triangular",
]

Array = np.ndarray


@njit(cache=True, inline="always")
def _triangle_into(a: Array, k: int) -> None:  # pragma: no cover - compiled
    """The Householder QR from the left of the first ``k ≥ 6`` rows of ``a (≥ k, 6)``, in place:
    ``R`` in ``a[:6]`` (zeros below its diagonal), the rest of those rows left as the reflections
    leave them (Golub & Van Loan §5.2.1)."""
    for j in range(6):
        total = 0.0
        for i in range(j, k):
            total += a[i, j] * a[i, j]
        if total == 0.0:
            continue
        alpha = -math.copysign(math.sqrt(total), a[j, j])
        a[j, j] -= alpha  # v = x − α e_j in place of x
        vv = 0.0
        for i in range(j, k):
            vv += a[i, j] * a[i, j]
        for c in range(j + 1, 6):
            dot = 0.0
            for i in range(j, k):
                dot += a[i, j] * a[i, c]
            dot = 2.0 * dot / vv
            for i in range(j, k):
                a[i, c] -= dot * a[i, j]
        a[j, j] = alpha
        for i in range(j + 1, k):
            a[i, j] = 0.0


@njit(cache=True)
def triangular(rows: Array) -> Array:  # pragma: no cover - compiled
    """``rows (n, k, 6)``, ``k ≥ 6`` → the triangular factor ``R (n, 6, 6)`` of each pose's
    Householder QR from the left (``rows = Q R``; Golub & Van Loan §5.2.1): the same singular
    values in six rows."""
    n, k = rows.shape[0], rows.shape[1]
    out = np.zeros((n, 6, 6))
    a = np.empty((k, 6))
    for p in range(n):
        for i in range(k):
            for s in range(6):
                a[i, s] = rows[p, i, s]
        _triangle_into(a, k)
        for i in range(6):
            for s in range(6):
                out[p, i, s] = a[i, s]
    return out


@njit(cache=True)
def closing(  # pragma: no cover - compiled
    constraint: Array,
    wrenches: Array,
    legs: Array,
    apart: Array,
    serial: Array,
    centre: Array,
    length: Array,
    rtol: float,
) -> tuple[Array, Array, Array, Array, Array]:
    """The analysis core's last per-pose steps in one pass (:func:`screwkit.core._closing.closing`, whose
    numpy path does these operations in this order): the global frame,
    :func:`~screwkit.core._frames_numba.span` of the
    ``constraint (n, 6, 6)`` rows and the limbs' scaled wrench ``rows (n, l, 6)``; the closeness
    factors, :func:`triangular` of the legs' wrench frames ``legs (n, L, 6, 6)`` stacked and of
    that triangle with the ``apart (n, l, 6)`` rows, packed (21 entries row by row); the
    actuation rows, the wrench rows in the user's frame (about ``centre (n, 3)``, moments times
    ``length (n,)``), each over its force's norm (its moment's for a couple), zero where
    ``serial (n, l)``."""
    n, limbs, legs_count = wrenches.shape[0], wrenches.shape[1], legs.shape[1]
    rows = np.zeros((n, 6, 6))
    order = np.zeros(n, dtype=np.int64)
    constraint_packed = np.empty((n, 21))
    actuation_packed = np.empty((n, 21))
    actuation = np.empty((n, limbs, 6))
    k = max(6 + limbs, 6 * legs_count)
    work = np.empty((k, 6))
    norms = np.empty(k)
    pivot = np.empty(6)
    coefficients = np.empty(6)
    for p in range(n):
        for i in range(6):
            for s in range(6):
                work[i, s] = constraint[p, i, s]
        for i in range(limbs):
            for s in range(6):
                work[6 + i, s] = wrenches[p, i, s]
        order[p] = span_into(work, 6 + limbs, rtol, rows[p], norms, pivot, coefficients)
        for leg in range(legs_count):
            for i in range(6):
                for s in range(6):
                    work[6 * leg + i, s] = legs[p, leg, i, s]
        if 6 * legs_count < 6:
            for i in range(6 * legs_count, 6):
                for s in range(6):
                    work[i, s] = 0.0
        _triangle_into(work, max(6 * legs_count, 6))
        _pack(work, constraint_packed[p])
        for i in range(limbs):
            for s in range(6):
                work[6 + i, s] = apart[p, i, s]
        _triangle_into(work, 6 + limbs)
        _pack(work, actuation_packed[p])
        c0, c1, c2, scale = centre[p, 0], centre[p, 1], centre[p, 2], length[p]
        for i in range(limbs):
            d0, d1, d2 = wrenches[p, i, 0], wrenches[p, i, 1], wrenches[p, i, 2]
            m0 = wrenches[p, i, 3] * scale + (c1 * d2 - c2 * d1)
            m1 = wrenches[p, i, 4] * scale + (c2 * d0 - c0 * d2)
            m2 = wrenches[p, i, 5] * scale + (c0 * d1 - c1 * d0)
            forces = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            moments = math.sqrt(m0 * m0 + m1 * m1 + m2 * m2)
            size = moments if forces <= COUPLE_RTOL * moments / scale else forces
            size = size if size > 0 else 1.0
            keep = 0.0 if serial[p, i] else 1.0
            actuation[p, i, 0], actuation[p, i, 1], actuation[p, i, 2] = d0 / size, d1 / size, d2 / size
            actuation[p, i, 3], actuation[p, i, 4], actuation[p, i, 5] = m0 / size, m1 / size, m2 / size
            if keep == 0.0:
                for s in range(6):
                    actuation[p, i, s] = 0.0
    return rows, order, constraint_packed, actuation_packed, actuation


@njit(cache=True, inline="always")
def _pack(a: Array, out: Array) -> None:  # pragma: no cover - compiled
    """The entries on and above the diagonal of ``a[:6]``, row by row, into ``out (21,)``."""
    q = 0
    for i in range(6):
        for s in range(i, 6):
            out[q] = a[i, s]
            q += 1
