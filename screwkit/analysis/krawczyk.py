"""The Krawczyk operator: a proof that a square system ``F(θ, u) = 0`` has exactly one solution
``θ`` in a box ``X`` for every parameter ``u`` in a box ``U``, batched over boxes.

For a point ``y`` of ``X``, a real matrix ``C`` and an interval matrix ``J`` holding every Jacobian
``∂F/∂θ`` over ``X × U``,

``K(X) = y - C F(y, U) + (I - C J)(X - y)``

holds every solution in ``X`` of ``F(·, u) = 0`` for each ``u ∈ U``, and ``K(X) ⊂ int X`` proves
that each ``F(·, u)`` has exactly one zero in ``X`` and that every matrix of ``J`` (hence the
Jacobian at that zero) is regular (Krawczyk 1969; Moore, Kearfott and Cloud, *Introduction to
Interval Analysis*, SIAM 2009, §8.2; Neumaier, *Interval Methods for Systems of Equations*, 1990,
§5.1). ``C`` is the inverse of ``J``'s midpoint, so ``I - C J`` is small where ``X`` is.

Rounding: real matrices times interval vectors and matrices are computed in midpoint-radius form
``C m ± |C| r`` with the error of the floating-point products bounded by
``γ_n |C| (|m| + r)``, ``γ_n = n u / (1 - n u)`` (Higham, *Accuracy and Stability of Numerical
Algorithms*, 2nd ed., 2002, §3.1, Eq. 3.5), every bound then moved outward by one double.

Examples
--------
>>> # F(θ, u) = θ² - u over X = [1, 2], U = [2, 2.1]: one square root in X
>>> y = np.array([[1.45]])
>>> f_y = (np.array([[1.45**2 - 2.1]]), np.array([[1.45**2 - 2.0]]))
>>> jac = (np.array([[[2.0]]]), np.array([[[4.0]]]))
>>> lo, hi, _ = krawczyk(f_y, jac, y, (np.array([[1.3]]), np.array([[1.6]])))
>>> bool(1.3 < lo[0, 0] and hi[0, 0] < 1.6)
True
"""

from __future__ import annotations

import numpy as np

__all__ = ["implicit_rates", "interval_matrix_vector", "krawczyk", "matrix_times_interval"]

Array = np.ndarray

_UNIT = 2.0**-53


def _down(x: Array) -> Array:
    return np.nextafter(x, -np.inf)


def _up(x: Array) -> Array:
    return np.nextafter(x, np.inf)


def _gamma(n: int) -> float:
    return n * _UNIT / (1.0 - n * _UNIT)


def matrix_times_interval(matrix: Array, lo: Array, hi: Array) -> tuple[Array, Array]:
    """Enclose ``C [lo, hi]`` for real matrices ``C (B, n, m)`` and interval matrices
    ``[lo, hi] (B, m, p)`` (module docstring).

    Parameters
    ----------
    matrix : numpy.ndarray, shape (B, n, m)
    lo, hi : numpy.ndarray, shape (B, m, p)

    Returns
    -------
    tuple of numpy.ndarray, shape (B, n, p)

    Examples
    --------
    >>> c = np.array([[[1.0, -1.0]]])
    >>> lo, hi = matrix_times_interval(c, np.array([[[0.0], [1.0]]]), np.array([[[1.0], [2.0]]]))
    >>> bool(lo[0, 0, 0] <= -2.0 and hi[0, 0, 0] >= 0.0)
    True
    """
    with np.errstate(invalid="ignore", over="ignore"):
        middle = 0.5 * (lo + hi)
        radius = _up(np.maximum(_up(hi - middle), _up(middle - lo)))
        size = np.abs(matrix)
        centre = matrix @ middle
        gamma = _gamma(matrix.shape[-1] + 2)
        spread = size @ _up(radius + gamma * (np.abs(middle) + radius))
        spread = _up(spread * (1.0 + 2.0 * gamma) + matrix.shape[-1] * np.finfo(float).tiny)
        out_lo, out_hi = _down(centre - spread), _up(centre + spread)
    bad = ~np.isfinite(out_lo) | ~np.isfinite(out_hi)
    return np.where(bad, -np.inf, out_lo), np.where(bad, np.inf, out_hi)


def interval_matrix_vector(alo: Array, ahi: Array, blo: Array, bhi: Array) -> tuple[Array, Array]:
    """``[A] [b]`` for interval matrices ``(B, n, m)`` and vectors ``(B, m)``: each product's bounds
    from its four corner products, the sums' rounding bounded by ``γ_m`` of their magnitudes.

    Parameters
    ----------
    alo, ahi : numpy.ndarray, shape (B, n, m)
    blo, bhi : numpy.ndarray, shape (B, m)

    Returns
    -------
    tuple of numpy.ndarray, shape (B, n)

    Examples
    --------
    >>> lo, hi = interval_matrix_vector(np.ones((1, 1, 2)), np.ones((1, 1, 2)), np.array([[-1.0, 2.0]]),
    ...                                 np.array([[1.0, 3.0]]))
    >>> bool(lo[0, 0] <= 1.0 and hi[0, 0] >= 4.0)
    True
    """
    with np.errstate(invalid="ignore", over="ignore"):
        corners = np.stack(
            [alo * blo[:, None, :], alo * bhi[:, None, :], ahi * blo[:, None, :], ahi * bhi[:, None, :]]
        )
        low, high = corners.min(axis=0), corners.max(axis=0)
        gamma = _gamma(alo.shape[-1] + 1)
        low_sum, high_sum = low.sum(axis=-1), high.sum(axis=-1)
        low_out = _down(low_sum - gamma * np.abs(low).sum(axis=-1))
        high_out = _up(high_sum + gamma * np.abs(high).sum(axis=-1))
    bad = ~np.isfinite(low_out) | ~np.isfinite(high_out)
    return np.where(bad, -np.inf, low_out), np.where(bad, np.inf, high_out)


def krawczyk(
    f_at_y: tuple[Array, Array], jacobian: tuple[Array, Array], y: Array, box: tuple[Array, Array]
) -> tuple[Array, Array, Array]:
    """The Krawczyk operator ``K(X)`` over a batch of boxes (module docstring).

    Parameters
    ----------
    f_at_y : tuple of numpy.ndarray, shape (B, n)
        An enclosure of ``F(y, U)``.
    jacobian : tuple of numpy.ndarray, shape (B, n, n)
        An enclosure of ``∂F/∂θ`` over ``X × U``.
    y : numpy.ndarray, shape (B, n)
        A point of each box ``X``.
    box : tuple of numpy.ndarray, shape (B, n)
        ``X``.

    Returns
    -------
    lo, hi : numpy.ndarray, shape (B, n)
        ``K(X)`` (the whole line where ``C`` cannot be formed).
    proved : numpy.ndarray of bool, shape (B,)
        ``K(X) ⊂ int X``: exactly one zero in ``X`` for every parameter.

    Examples
    --------
    >>> y = np.zeros((1, 2))
    >>> f_y = (np.full((1, 2), -1e-3), np.full((1, 2), 1e-3))     # |F(0, u)| <= 1e-3
    >>> eye = np.eye(2)[None]
    >>> _, _, proved = krawczyk(f_y, (eye * 0.9, eye * 1.1), y, (y - 0.01, y + 0.01))
    >>> proved.tolist()
    [True]
    """
    jlo, jhi = jacobian
    middle = 0.5 * (jlo + jhi)
    n = y.shape[1]
    finite = np.all(np.isfinite(middle), axis=(1, 2))
    middle = np.where(finite[:, None, None], middle, np.eye(n))
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        determinant = np.linalg.det(middle)
    regular = finite & np.isfinite(determinant) & (np.abs(determinant) > 1e-300)
    inverse = np.linalg.inv(np.where(regular[:, None, None], middle, np.eye(n)))
    cf_lo, cf_hi = matrix_times_interval(inverse, f_at_y[0][..., None], f_at_y[1][..., None])
    cj_lo, cj_hi = matrix_times_interval(inverse, jlo, jhi)
    eye = np.eye(n)
    m_lo, m_hi = _down(eye - cj_hi), _up(eye - cj_lo)
    d_lo, d_hi = _down(box[0] - y), _up(box[1] - y)
    p_lo, p_hi = interval_matrix_vector(m_lo, m_hi, d_lo, d_hi)
    lo = _down(_down(y - cf_hi[..., 0]) + p_lo)
    hi = _up(_up(y - cf_lo[..., 0]) + p_hi)
    lo = np.where(regular[:, None] & np.isfinite(lo), lo, -np.inf)
    hi = np.where(regular[:, None] & np.isfinite(hi), hi, np.inf)
    proved = regular & np.all((lo > box[0]) & (hi < box[1]), axis=1)
    return lo, hi, proved


def implicit_rates(jacobian: tuple[Array, Array], parameters: tuple[Array, Array]) -> tuple[Array, Array]:
    """Enclose ``dθ/du = -J⁻¹ P`` for every ``J`` in ``jacobian`` and ``P`` in ``parameters`` (the
    implicit function theorem on ``F(θ, u) = 0``, ``J = ∂F/∂θ``, ``P = ∂F/∂u``).

    With ``C`` the inverse of ``J``'s midpoint, ``E = I - C J`` and ``ρ = ‖|E|‖_∞ < 1``,
    ``(C J)⁻¹ = I + Δ`` with ``‖Δ‖_∞ <= ρ / (1 - ρ)`` (the Neumann series; Neumaier 1990, §4.1), so
    ``dθ/du = -(I + Δ) G``, ``G = C P``, lies entrywise within ``ρ/(1 - ρ) max_j |G_jl|`` of ``-G``.

    Parameters
    ----------
    jacobian : tuple of numpy.ndarray, shape (B, n, n)
    parameters : tuple of numpy.ndarray, shape (B, n, k)

    Returns
    -------
    tuple of numpy.ndarray, shape (B, n, k)
        The whole line where ``ρ >= 1``.

    Examples
    --------
    >>> j = (np.array([[[1.9]]]), np.array([[[2.1]]]))
    >>> lo, hi = implicit_rates(j, (np.array([[[1.0]]]), np.array([[[1.0]]])))   # -1/2 ± 5 %
    >>> bool(lo[0, 0, 0] <= -1 / 1.9 and hi[0, 0, 0] >= -1 / 2.1)
    True
    """
    jlo, jhi = jacobian
    n = jlo.shape[1]
    middle = 0.5 * (jlo + jhi)
    finite = np.all(np.isfinite(middle), axis=(1, 2))
    middle = np.where(finite[:, None, None], middle, np.eye(n))
    with np.errstate(invalid="ignore", over="ignore"):
        regular = finite & (np.abs(np.linalg.det(middle)) > 1e-300)
    inverse = np.linalg.inv(np.where(regular[:, None, None], middle, np.eye(n)))
    m_lo, m_hi = matrix_times_interval(inverse, jlo, jhi)
    eye = np.eye(n)
    size = np.maximum(np.abs(_down(eye - m_hi)), np.abs(_up(eye - m_lo)))
    rho = _up(size.sum(axis=2).max(axis=1) * (1.0 + _gamma(n)))
    g_lo, g_hi = matrix_times_interval(inverse, *parameters)
    with np.errstate(divide="ignore", invalid="ignore"):
        delta = np.where(regular & (rho < 1.0), _up(rho / _down(1.0 - rho)), np.inf)
        reach = _up(delta[:, None, None] * np.maximum(np.abs(g_lo), np.abs(g_hi)).max(axis=1, keepdims=True))
    lo, hi = _down(-g_hi - reach), _up(-g_lo + reach)
    bad = ~np.isfinite(lo) | ~np.isfinite(hi)
    return np.where(bad, -np.inf, lo), np.where(bad, np.inf, hi)
