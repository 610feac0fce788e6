"""numba kernels of :mod:`screwkit._frames` (private; imported on the first large kernel call).

Each kernel loops over a flat batch ``(n, ...)`` and does, pose by pose, what the numpy path of
:mod:`screwkit._frames` does over the whole batch: the same rule (pivot choice, threshold, CGS2
re-orthogonalisation, complete Householder QR) and the same floating-point operations in the same
order (no ``fastmath``: nothing is reordered or fused), so the two paths agree bit for bit. A pose's
answer depends only on that pose's input (no reduction across the batch, no BLAS call), so single
and batched answers are bit-identical. ``cache=True`` stores the compiled code beside this file
(or in ``NUMBA_CACHE_DIR``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

Array = np.ndarray


@njit(cache=True)
def span(work: Array, rtol: float) -> tuple[Array, Array]:  # pragma: no cover - compiled
    """``work (n, k, 6)`` (overwritten) → rows ``(n, 6, 6)``, order ``(n,)``; ``k ≥ 1``."""
    n, k = work.shape[0], work.shape[1]
    rows = np.zeros((n, 6, 6))
    order = np.zeros(n, dtype=np.int64)
    norms = np.empty(k)
    pivot = np.empty(6)
    coefficients = np.empty(6)
    steps = min(k, 6)
    for p in range(n):
        w = work[p]
        r = rows[p]
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
        for step in range(steps):
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
                total = 0.0
                for s in range(6):
                    total += w[j, s] * r[step, s]
                for s in range(6):
                    w[j, s] -= total * r[step, s]
                total = 0.0
                for s in range(6):
                    total += w[j, s] * w[j, s]
                norms[j] = math.sqrt(total)
        order[p] = count
    return rows, order


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
        for i in range(6):
            for j in range(6):
                a[i, j] = rows[p, j, i]  # a's columns are the frame's rows
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
            for c in range(j + 1, 6):
                dot = 0.0
                for i in range(j, 6):
                    dot += v[j, i] * a[i, c]
                dot *= tau[j]
                for i in range(j, 6):
                    a[i, c] -= dot * v[j, i]
        o = order[p]
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
                    out[p, c - o, (i + 3) % 6] = y[i]
                else:
                    out[p, c - o, i] = y[i]
    return out


@njit(cache=True)
def residual(vectors: Array, rows: Array) -> Array:  # pragma: no cover - compiled
    """``vectors (n, k, 6)`` minus their projections on ``rows (n, r, 6)``, twice."""
    n, k, m = vectors.shape[0], vectors.shape[1], rows.shape[1]
    out = vectors.copy()
    coefficients = np.empty(m)
    for p in range(n):
        for j in range(k):
            for _ in range(2):
                for i in range(m):
                    total = 0.0
                    for s in range(6):
                        total += out[p, j, s] * rows[p, i, s]
                    coefficients[i] = total
                for i in range(m):
                    for s in range(6):
                        out[p, j, s] -= coefficients[i] * rows[p, i, s]
    return out
