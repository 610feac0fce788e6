"""numba kernels of :mod:`screwkit.core.frames`: the rank rule (private; imported on a first large call).

Each kernel loops over a flat batch ``(n, ...)`` and does, pose by pose, what the numpy path of
:mod:`screwkit.core.frames` does over the whole batch: the same rule (pivot choice, threshold, CGS2
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
    "residual",
    "span",
    "span_into",
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
