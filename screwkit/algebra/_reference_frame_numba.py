"""numba kernels of :mod:`screwkit.algebra.reference_frame` (private; imported on the first large call).

Each kernel loops over a flat batch ``(n, ...)`` and does, pose by pose, what the numpy path of
:mod:`screwkit.algebra.reference_frame` does over the whole batch: the same floating-point
operations in the same order (no ``fastmath``: nothing is reordered or fused), so the two paths
agree bit for bit (:mod:`screwkit.algebra.compiled`). ``cache=True`` stores the compiled code
beside this file (or in ``NUMBA_CACHE_DIR``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

Array = np.ndarray


@njit(cache=True, inline="always")
def _scaled_rows(  # pragma: no cover - compiled
    screws: Array, p: int, c0: float, c1: float, c2: float, length: float, out: Array
) -> None:
    """Pose ``p`` of :func:`unit_scaled` about the centre ``(c0, c1, c2)``, into ``out[p]`` (the
    inverses of the length and of each row's norm multiplied in)."""
    inverse_length = 1.0 / length
    for r in range(screws.shape[1]):
        d0, d1, d2 = screws[p, r, 0], screws[p, r, 1], screws[p, r, 2]
        m0 = (screws[p, r, 3] - (c1 * d2 - c2 * d1)) * inverse_length
        m1 = (screws[p, r, 4] - (c2 * d0 - c0 * d2)) * inverse_length
        m2 = (screws[p, r, 5] - (c0 * d1 - c1 * d0)) * inverse_length
        size = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2 + m0 * m0 + m1 * m1 + m2 * m2)
        inverse = 1.0 / (1.0 if size == 0.0 else size)
        out[p, r, 0], out[p, r, 1], out[p, r, 2] = d0 * inverse, d1 * inverse, d2 * inverse
        out[p, r, 3], out[p, r, 4], out[p, r, 5] = m0 * inverse, m1 * inverse, m2 * inverse


@njit(cache=True)
def unit_scaled(screws: Array, centres: Array, lengths: Array) -> Array:  # pragma: no cover - compiled
    """:func:`screwkit.algebra.reference_frame.unit_scaled` pose by pose: ``(s; (s0 − c × s) / L)``
    over its norm."""
    out = np.empty((screws.shape[0], screws.shape[1], 6))
    for p in range(screws.shape[0]):
        _scaled_rows(screws, p, centres[p, 0], centres[p, 1], centres[p, 2], lengths[p], out)
    return out


@njit(cache=True, inline="always")
def _unit_axis(screws: Array, p: int, j: int) -> tuple[float, ...]:  # pragma: no cover - compiled
    """Of screw ``screws[p, j]``: ``(f, u, foot)`` with ``f`` 1.0 for a finite axis (0.0 for a couple),
    ``u`` its unit direction (zero for a couple) and ``foot = d × m / |d|²`` the foot of the axis
    from the origin, the operations of the numpy path (:func:`screwkit.algebra.reference_frame._axes_numpy`):
    one division, ``1 / |d|²``, multiplied in."""
    d0, d1, d2 = screws[p, j, 0], screws[p, j, 1], screws[p, j, 2]
    m0, m1, m2 = screws[p, j, 3], screws[p, j, 4], screws[p, j, 5]
    size = d0 * d0 + d1 * d1 + d2 * d2
    finite = size > 0
    inverse = 1.0 / (size if finite else 1.0)
    f = 1.0 if finite else 0.0
    scale = math.sqrt(inverse) * f
    foot0 = (d1 * m2 - d2 * m1) * inverse
    foot1 = (d2 * m0 - d0 * m2) * inverse
    foot2 = (d0 * m1 - d1 * m0) * inverse
    return f, d0 * scale, d1 * scale, d2 * scale, foot0, foot1, foot2


@njit(cache=True)
def mechanism_frame(screws: Array, scale: bool) -> tuple[Array, Array, Array, Array]:  # pragma: no cover
    """:func:`screwkit.algebra.reference_frame.mechanism_frame` in one pass where the normal matrix is
    solved directly (its adjugate, :func:`screwkit.algebra.reference_frame._least_squares_point`'s
    test), with the unit scaled screws (:func:`unit_scaled`) if ``scale``: ``point (n, 3)``, ``length (n,)``,
    ``direct (n,)`` (False: the pose's point, length and scaled screws are left to the caller,
    whose eigendecomposition decides) and ``scaled (n, k, 6)`` (``(0, k, 6)`` unless ``scale``).

    The numpy path's operations in its order (:func:`screwkit.algebra.reference_frame._frame_numpy`,
    bit for bit): over the finite axes, in order from ``0.0``, the count, ``Σ u uᵀ`` and ``Σ (I − u uᵀ) f``
    (``f = d × m / |d|²`` each axis's foot, ``u`` its unit direction), the farthest foot; the
    normal matrix ``N = Σ (I − u uᵀ)``; ``N⁻¹ Σ (I − u uᵀ) f`` by the adjugate; the axes' squared
    distances from that point ``Σ |(I − u uᵀ)(c − f)|²`` (each axis's ``u``, ``f`` kept from the
    first pass); the length rule."""
    n, k = screws.shape[0], screws.shape[1]
    point = np.empty((n, 3))
    length = np.empty(n)
    direct = np.empty(n, dtype=np.bool_)
    scaled = np.empty((n if scale else 0, k, 6))
    axes = np.empty((k, 7))
    for p in range(n):
        count = 0
        t00 = t01 = t02 = t11 = t12 = t22 = 0.0
        r0 = r1 = r2 = 0.0
        far = 0.0
        for j in range(k):
            f, u0, u1, u2, f0, f1, f2 = _unit_axis(screws, p, j)
            axes[j, 0], axes[j, 1], axes[j, 2], axes[j, 3] = f, u0, u1, u2
            axes[j, 4], axes[j, 5], axes[j, 6] = f0, f1, f2
            count += f > 0
            t00 += u0 * u0
            t01 += u0 * u1
            t02 += u0 * u2
            t11 += u1 * u1
            t12 += u1 * u2
            t22 += u2 * u2
            along = u0 * f0 + u1 * f1 + u2 * f2
            r0 += (f0 - u0 * along) * f
            r1 += (f1 - u1 * along) * f
            r2 += (f2 - u2 * along) * f
            foot = math.sqrt(f0 * f0 + f1 * f1 + f2 * f2)
            if not math.isnan(far) and (math.isnan(foot) or foot > far):
                far = foot  # np.max: NaN propagates
        n00, n11, n22 = count - t00, count - t11, count - t22
        n01, n02, n12 = 0.0 - t01, 0.0 - t02, 0.0 - t12
        a00, a01, a02 = n11 * n22 - n12 * n12, n02 * n12 - n01 * n22, n01 * n12 - n02 * n11
        a11, a12, a22 = n00 * n22 - n02 * n02, n01 * n02 - n00 * n12, n00 * n11 - n01 * n01
        det = n00 * a00 + n01 * a01 + n02 * a02
        trace = n00 + n11 + n22
        direct[p] = trace > 0 and 4.0 * det > 1e-6 * (trace * trace * trace)
        if not direct[p]:
            continue
        c0 = (a00 * r0 + a01 * r1 + a02 * r2) / det
        c1 = (a01 * r0 + a11 * r1 + a12 * r2) / det
        c2 = (a02 * r0 + a12 * r1 + a22 * r2) / det
        total = 0.0
        for j in range(k):
            f, u0, u1, u2 = axes[j, 0], axes[j, 1], axes[j, 2], axes[j, 3]
            f0, f1, f2 = axes[j, 4], axes[j, 5], axes[j, 6]
            a0, a1, a2 = c0 - f0, c1 - f1, c2 - f2
            along = u0 * a0 + u1 * a1 + u2 * a2
            a0, a1, a2 = (a0 - u0 * along) * f, (a1 - u1 * along) * f, (a2 - u2 * along) * f
            total += a0 * a0 + a1 * a1 + a2 * a2
        size = math.sqrt(total / max(count, 1))
        reach = math.sqrt(c0 * c0 + c1 * c1 + c2 * c2)
        reach = far if (far >= reach or math.isnan(far)) else reach  # np.maximum: NaN propagates
        if size <= 1e-12 * reach or size == 0:
            size = reach if reach > 0 else 1.0
        point[p, 0], point[p, 1], point[p, 2], length[p] = c0, c1, c2, size
        if scale:
            _scaled_rows(screws, p, c0, c1, c2, size, scaled)
    return point, length, direct, scaled
