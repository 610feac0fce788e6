"""numba kernel of :func:`screwkit.core._joint_rows.joint_rows` (private; imported on the first large call).

The kernel loops over the batch and does, pose by pose, what the numpy path of
:mod:`screwkit.core._joint_rows` does over the whole batch: the same floating-point operations in the
same order (no ``fastmath``: nothing is reordered or fused), so the two paths agree bit for bit
(:mod:`screwkit.algebra.compiled`). ``cache=True`` stores the compiled code beside this file (or in
``NUMBA_CACHE_DIR``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["joint_rows"]

Array = np.ndarray


@njit(cache=True, error_model="numpy", inline="always")
def _ball(out: Array, p: int, i: int, j: int, k: int) -> None:  # pragma: no cover - compiled
    """:func:`screwkit.core._joint_rows.orthonormal_axes` on rows ``i, j, k`` of pose ``p``, in place."""
    a0, a1, a2 = out[p, i, 0], out[p, i, 1], out[p, i, 2]
    b0, b1, b2 = out[p, j, 0], out[p, j, 1], out[p, j, 2]
    c0, c1, c2 = out[p, k, 0], out[p, k, 1], out[p, k, 2]
    first_alone = a1 == 0.0 and a2 == 0.0
    r00 = a0 if first_alone else -math.copysign(math.sqrt(a0 * a0 + a1 * a1 + a2 * a2), a0)
    q00, q01, q02 = a0 / r00, a1 / r00, a2 / r00
    r01 = q00 * b0 + q01 * b1 + q02 * b2
    r02 = q00 * c0 + q01 * c1 + q02 * c2
    e0, e1, e2 = b0 - r01 * q00, b1 - r01 * q01, b2 - r01 * q02
    u0 = a0 - r00
    factor = 0.0 if first_alone else 2.0 * (u0 * b0 + a1 * b1 + a2 * b2) / (u0 * u0 + a1 * a1 + a2 * a2)
    below1, below2 = b1 - factor * a1, b2 - factor * a2
    second_alone = below2 == 0.0
    r11 = below1 if second_alone else -math.copysign(math.sqrt(e0 * e0 + e1 * e1 + e2 * e2), below1)
    q10, q11, q12 = e0 / r11, e1 / r11, e2 / r11
    r12 = q10 * c0 + q11 * c1 + q12 * c2
    sign = 1.0 if first_alone == second_alone else -1.0
    q20 = sign * (q01 * q12 - q02 * q11)
    q21 = sign * (q02 * q10 - q00 * q12)
    q22 = sign * (q00 * q11 - q01 * q10)
    r22 = q20 * c0 + q21 * c1 + q22 * c2
    for m in range(6):
        first = out[p, i, m] / r00
        second = (out[p, j, m] - r01 * first) / r11
        out[p, k, m] = (out[p, k, m] - r02 * first - r12 * second) / r22
        out[p, i, m], out[p, j, m] = first, second


@njit(cache=True, error_model="numpy")
def joint_rows(  # pragma: no cover - compiled
    current: Array, length: float, point: Array, balls: Array, couple: float, out: Array
) -> None:
    """:func:`screwkit.core._joint_rows.joint_rows` pose by pose, ``current (B, n, 6)`` into ``out``
    (``couple``: :data:`screwkit.core._joint_rows.COUPLE_SQUARED_NORM`)."""
    count, size = current.shape[0], current.shape[1]
    p0, p1, p2 = point[0], point[1], point[2]
    for p in range(count):
        for r in range(size):
            s0, s1, s2 = current[p, r, 0], current[p, r, 1], current[p, r, 2]
            out[p, r, 0], out[p, r, 1], out[p, r, 2] = s0, s1, s2
            if s0 * s0 + s1 * s1 + s2 * s2 > couple:
                out[p, r, 3] = current[p, r, 3] * length + (p1 * s2 - p2 * s1)
                out[p, r, 4] = current[p, r, 4] * length + (p2 * s0 - p0 * s2)
                out[p, r, 5] = current[p, r, 5] * length + (p0 * s1 - p1 * s0)
            else:
                for m in range(3, 6):
                    out[p, r, m] = current[p, r, m]
        for b in range(balls.shape[0]):
            _ball(out, p, balls[b, 0], balls[b, 1], balls[b, 2])
