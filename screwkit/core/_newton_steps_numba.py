"""numba pieces of the loop closure's Newton correctors (private; :mod:`screwkit.core._newton_numba`'s
pinned loops and :mod:`screwkit.core._rod_newton_numba`'s rods): a damped Cholesky factorisation, its
solve, and the step's stopping rules (the loop closure's, :mod:`screwkit.core.loop_closure`)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["cholesky_solve", "damped_cholesky", "took_correction"]

Array = np.ndarray


@njit(cache=True, inline="always")
def damped_cholesky(gram: Array, size: int) -> None:  # pragma: no cover - compiled
    """The Cholesky factor of ``gram[:size, :size] + λ I`` into its lower triangle (read from it), with
    Levenberg's ``λ = 1e-13 (trace + 1)`` that keeps dependent equations solvable (Golub & Van Loan,
    *Matrix Computations*, 4th ed., 2013, Alg. 4.2.1)."""
    trace = 0.0
    for i in range(size):
        trace += gram[i, i]
    damping = 1e-13 * (trace + 1.0)
    for j in range(size):
        total = gram[j, j] + damping
        for k in range(j):
            total -= gram[j, k] * gram[j, k]
        pivot = math.sqrt(total) if total > 0.0 else 1e-300
        gram[j, j] = pivot
        for i in range(j + 1, size):
            value = gram[i, j]
            for k in range(j):
                value -= gram[i, k] * gram[j, k]
            gram[i, j] = value / pivot


@njit(cache=True, inline="always")
def cholesky_solve(factor: Array, size: int, solution: Array) -> None:  # pragma: no cover - compiled
    """``solution[:size]`` replaced by ``(L Lᵀ)⁻¹ solution`` with the factor :func:`damped_cholesky` left."""
    for i in range(size):
        value = solution[i]
        for m in range(i):
            value -= factor[i, m] * solution[m]
        solution[i] = value / factor[i, i]
    for i in range(size - 1, -1, -1):
        value = solution[i]
        for m in range(i + 1, size):
            value -= factor[m, i] * solution[m]
        solution[i] = value / factor[i, i]


@njit(cache=True, inline="always")
def took_correction(  # pragma: no cover - compiled
    theta: Array,
    correction: Array,
    sign: float,
    max_correction: float,
    tolerance: Array,
    first: bool,
    before: float,
    size: float,
    p: int,
    sizes: Array,
    leading: Array,
    corrected: Array,
) -> tuple[bool, float]:
    """One Newton correction taken: ``theta += sign × correction``, scaled down to ``max_correction``
    at most, its length added to pose ``p``'s ``leading`` (the first) or ``corrected`` (the others);
    returns whether the iterations stop (the correction within ``tolerance[1]``, or contracting at
    ``Θ < 1/2`` with the error estimate ``Θ / (1 − Θ) |Δθ|`` within ``tolerance[2]``, the residual
    ``size`` before it times ``Θ`` then written into ``sizes[p]``) and its length."""
    length = 0.0
    for k in range(theta.shape[0]):
        value = abs(correction[k])
        if not value <= length:
            length = value
    scale = min(1.0, max_correction / max(length, 1e-300))
    for k in range(theta.shape[0]):
        theta[k] += sign * correction[k] * scale
    if first:
        leading[p] = min(length, max_correction)
    else:
        corrected[p] += min(length, max_correction)
    if not length > tolerance[1]:  # a correction this small: converged
        return True, length
    if not first and length < 0.5 * before:  # contracting: the error left is about Θ/(1 − Θ) |Δθ|
        contraction = length / before
        if contraction / (1.0 - contraction) * length <= tolerance[2]:
            sizes[p] = size * contraction
            return True, length
    return False, length
