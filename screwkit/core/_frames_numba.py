"""numba kernels of :mod:`screwkit.core._frames`: the rank rule (private; imported on a first large call).

Each kernel loops over a flat batch ``(n, ...)`` and does, pose by pose, what the numpy path of
:mod:`screwkit.core._frames` does over the whole batch: the same rule (pivot choice, threshold, CGS2
re-orthogonalisation, complete Householder QR) and the same floating-point operations in the same
order (no ``fastmath``: nothing is reordered or fused), so the two paths agree bit for bit. A pose's
answer depends only on that pose's input (no reduction across the batch, no BLAS call), so single
and batched answers are bit-identical. ``cache=True`` stores the compiled code beside this file
(or in ``NUMBA_CACHE_DIR``).

The other compiled twins build on these loops: the closed forms
(:mod:`screwkit.core._closed_forms_numba`), the frame-program interpreter
(:mod:`screwkit.core._program_numba`), the limbs' systems (:mod:`screwkit.core._limbs_numba`) and the
closing steps (:mod:`screwkit.core._closing_numba`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = [
    "complement",
    "complement_into",
    "mechanism_frame",
    "residual",
    "span",
    "span_into",
    "unit_scaled",
]

Array = np.ndarray


@njit(cache=True)
def span_into(  # pragma: no cover - compiled
    w: Array, k: int, rtol: float, r: Array, norms: Array, pivot: Array, coefficients: Array
) -> int:
    """One pose of :func:`span`: the first ``k`` rows of ``w`` (overwritten) → the frame's rows in
    ``r (6, 6)`` (zero beyond the order, which is returned); ``norms (≥ k,)``, ``pivot (6,)`` and
    ``coefficients (6,)`` are scratch. Rows of ``w`` that are exactly zero stay zero and are never
    picked, so they are skipped (as if absent: the first largest pivot is the same)."""
    for i in range(6):
        for s in range(6):
            r[i, s] = 0.0
    if k == 0:
        return 0
    for j in range(k):
        total = 0.0
        for s in range(6):
            total += w[j, s] * w[j, s]
        norms[j] = math.sqrt(total)
    top = norms[0]
    for j in range(1, k):
        if math.isnan(top):
            break
        if math.isnan(norms[j]) or norms[j] > top:
            top = norms[j]
    threshold = rtol * top
    count = 0
    for step in range(min(k, 6)):
        pick = 0  # np.argmax: the first largest, or the first NaN
        for j in range(k):
            if math.isnan(norms[j]):
                pick = j
                break
            if norms[j] > norms[pick]:
                pick = j
        for s in range(6):
            pivot[s] = w[pick, s]
        for i in range(count):  # CGS2: the pivot re-orthogonalised once against the rows
            total = 0.0
            for s in range(6):
                total += r[i, s] * pivot[s]
            coefficients[i] = total
        for i in range(count):
            for s in range(6):
                pivot[s] -= coefficients[i] * r[i, s]
        total = 0.0
        for s in range(6):
            total += pivot[s] * pivot[s]
        size = math.sqrt(total)
        if not (size > threshold and size > 0):
            break  # the numpy path then adds zero rows only
        for s in range(6):
            r[step, s] = pivot[s] / size
        count += 1
        for j in range(k):
            if norms[j] == 0.0:
                continue  # a zero row stays zero
            total = 0.0
            for s in range(6):
                total += w[j, s] * r[step, s]
            for s in range(6):
                w[j, s] -= total * r[step, s]
            total = 0.0
            for s in range(6):
                total += w[j, s] * w[j, s]
            norms[j] = math.sqrt(total)
    return count


@njit(cache=True)
def span(work: Array, rtol: float) -> tuple[Array, Array]:  # pragma: no cover - compiled
    """``work (n, k, 6)`` (overwritten) → rows ``(n, 6, 6)``, order ``(n,)``; ``k ≥ 1``."""
    n, k = work.shape[0], work.shape[1]
    rows = np.zeros((n, 6, 6))
    order = np.zeros(n, dtype=np.int64)
    norms = np.empty(k)
    pivot = np.empty(6)
    coefficients = np.empty(6)
    for p in range(n):
        order[p] = span_into(work[p], k, rtol, rows[p], norms, pivot, coefficients)
    return rows, order


@njit(cache=True)
def complement_into(  # pragma: no cover - compiled
    rows: Array, o: int, swap: bool, out: Array, a: Array, v: Array, tau: Array, y: Array
) -> None:
    """One pose of :func:`complement`: the frame ``rows (6, 6)`` of order ``o`` → the complement's
    rows in ``out (6, 6)`` (zero beyond ``6 − o``); ``a``, ``v (6, 6)``, ``tau``, ``y (6,)`` are
    scratch. Columns of ``a`` beyond ``o`` are zero (the frame's zero rows) and no reflector
    changes them, so the reflections skip them."""
    for i in range(6):
        for j in range(6):
            a[i, j] = rows[j, i]  # a's columns are the frame's rows
            out[i, j] = 0.0
    for j in range(6):
        alpha = a[j, j]
        total = 0.0
        for i in range(j + 1, 6):
            total += a[i, j] * a[i, j]
        tau[j] = 0.0
        v[j, j] = 1.0
        for i in range(j + 1, 6):
            v[j, i] = 0.0
        if total == 0.0:
            continue
        beta = -math.copysign(math.sqrt(alpha * alpha + total), alpha)
        tau[j] = (beta - alpha) / beta
        scale = 1.0 / (alpha - beta)
        for i in range(j + 1, 6):
            v[j, i] = a[i, j] * scale
        a[j, j] = beta
        for i in range(j + 1, 6):
            a[i, j] = 0.0
        for c in range(j + 1, o):
            dot = 0.0
            for i in range(j, 6):
                dot += v[j, i] * a[i, c]
            dot *= tau[j]
            for i in range(j, 6):
                a[i, c] -= dot * v[j, i]
    for c in range(o, 6):  # column c of Q = H_0 H_1 … H_5 e_c
        for i in range(6):
            y[i] = 0.0
        y[c] = 1.0
        for j in range(5, -1, -1):
            if tau[j] == 0.0:
                continue
            dot = 0.0
            for i in range(j, 6):
                dot += v[j, i] * y[i]
            dot *= tau[j]
            for i in range(j, 6):
                y[i] -= dot * v[j, i]
        for i in range(6):
            if swap:
                out[c - o, (i + 3) % 6] = y[i]
            else:
                out[c - o, i] = y[i]


@njit(cache=True)
def complement(rows: Array, order: Array, swap: bool) -> Array:  # pragma: no cover - compiled
    """Rows ``(n, 6, 6)``, order ``(n,)`` → the complement's rows ``(n, 6, 6)`` (halves exchanged
    when ``swap``): columns ``order..5`` of the complete Householder QR of the rows as columns
    (LAPACK ``dgeqrf``/``dorgqr``'s reflectors, Golub & Van Loan §5.2)."""
    n = rows.shape[0]
    out = np.zeros((n, 6, 6))
    a = np.empty((6, 6))
    v = np.zeros((6, 6))  # v[j, j:] the j-th reflector (v[j, j] = 1)
    tau = np.zeros(6)
    y = np.empty(6)
    for p in range(n):
        complement_into(rows[p], order[p], swap, out[p], a, v, tau, y)
    return out


@njit(cache=True)
def residual(vectors: Array, frames: Array, which: Array) -> Array:  # pragma: no cover - compiled
    """``vectors (n, k, 6)`` minus their projections on the rows of ``frames (n, f, r, 6)``,
    twice: vector ``j`` on frame ``which[j]``."""
    n, k = vectors.shape[0], vectors.shape[1]
    out = np.empty((n, k, 6))
    coefficients = np.empty(frames.shape[2])
    for p in range(n):
        for j in range(k):
            _residual_into(vectors[p, j], frames[p, which[j]], out[p, j], coefficients)
    return out


@njit(cache=True, inline="always")
def _residual_into(vector: Array, rows: Array, out: Array, coefficients: Array) -> None:  # pragma: no cover
    """One vector ``(6,)`` of :func:`residual` against ``rows (m, 6)``, into ``out (6,)``."""
    m = rows.shape[0]
    for s in range(6):
        out[s] = vector[s]
    for _ in range(2):
        for i in range(m):
            total = 0.0
            for s in range(6):
                total += out[s] * rows[i, s]
            coefficients[i] = total
        for i in range(m):
            for s in range(6):
                out[s] -= coefficients[i] * rows[i, s]


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
    """:func:`screwkit.core._frames.unit_scaled` pose by pose: ``(s; (s0 − c × s) / L)`` over its norm."""
    out = np.empty((screws.shape[0], screws.shape[1], 6))
    for p in range(screws.shape[0]):
        _scaled_rows(screws, p, centres[p, 0], centres[p, 1], centres[p, 2], lengths[p], out)
    return out



@njit(cache=True, inline="always")
def _unit_axis(screws: Array, p: int, j: int) -> tuple[float, ...]:  # pragma: no cover - compiled
    """Of screw ``screws[p, j]``: ``(f, u, foot)`` with ``f`` 1.0 for a finite axis (0.0 for a couple),
    ``u`` its unit direction (zero for a couple) and ``foot = d × m / |d|²`` the foot of the axis
    from the origin, the operations of the numpy path (:func:`screwkit.graphs.twistgraph._axes_numpy`):
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
    """:func:`screwkit.graphs.twistgraph.mechanism_frame` in one pass where the normal matrix is solved
    directly (its adjugate, :func:`screwkit.graphs.twistgraph._least_squares_point`'s test), with the unit
    scaled screws (:func:`unit_scaled`) if ``scale``: ``point (n, 3)``, ``length (n,)``,
    ``direct (n,)`` (False: the pose's point, length and scaled screws are left to the caller,
    whose eigendecomposition decides) and ``scaled (n, k, 6)`` (``(0, k, 6)`` unless ``scale``).

    The numpy path's operations in its order (:func:`screwkit.graphs.twistgraph._frame_numpy`, bit for
    bit): over the finite axes, in order from ``0.0``, the count, ``Σ u uᵀ`` and ``Σ (I − u uᵀ) f``
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
