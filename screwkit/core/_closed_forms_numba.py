"""numba kernels of :mod:`screwkit.core._closed_forms`: rods, parallelograms, one joint more (private).

Per-pose loops that :func:`screwkit.core._program_numba.run_program` inlines.
Each loop does, pose by pose, the floating-point operations of its numpy twin in the same order
(no ``fastmath``), so the two paths agree bit for bit (:mod:`screwkit.core.frames`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._frames_numba import _residual_into
from ._kernel_constants import CLOSED_FORM_MARGIN

__all__ = [
    "contract_into",
    "extend_into",
    "parallelogram_into",
    "rod_into",
]

Array = np.ndarray


@njit(cache=True, inline="always")
def _centre(rows: Array) -> tuple[float, float, float, float]:  # pragma: no cover - compiled
    """The least-squares point ``(x, y, z)`` of the three axes ``rows (3, 6)`` and the determinant
    of its normal matrix ``N = Σ (I − û ûᵀ)`` (≤ 0: no point): ``N⁻¹ Σ f`` with ``f = u × m / |u|²``
    each axis's foot (``(I − û ûᵀ) f = f``), by the adjugate (the inverses of ``|u|²`` and of the
    determinant multiplied in)."""
    n00 = n01 = n02 = n11 = n12 = n22 = 0.0
    b0 = b1 = b2 = 0.0
    for r in range(3):
        u0, u1, u2 = rows[r, 0], rows[r, 1], rows[r, 2]
        m0, m1, m2 = rows[r, 3], rows[r, 4], rows[r, 5]
        squared = u0 * u0 + u1 * u1 + u2 * u2
        if not squared > 0:
            return 0.0, 0.0, 0.0, 0.0
        inverse = 1.0 / squared
        b0 += (u1 * m2 - u2 * m1) * inverse
        b1 += (u2 * m0 - u0 * m2) * inverse
        b2 += (u0 * m1 - u1 * m0) * inverse
        n00 += 1.0 - u0 * u0 * inverse
        n11 += 1.0 - u1 * u1 * inverse
        n22 += 1.0 - u2 * u2 * inverse
        n01 -= u0 * u1 * inverse
        n02 -= u0 * u2 * inverse
        n12 -= u1 * u2 * inverse
    a00, a01, a02 = n11 * n22 - n12 * n12, n02 * n12 - n01 * n22, n01 * n12 - n02 * n11
    a11, a12, a22 = n00 * n22 - n02 * n02, n01 * n02 - n00 * n12, n00 * n11 - n01 * n01
    det = n00 * a00 + n01 * a01 + n02 * a02
    if not det > 0:
        return 0.0, 0.0, 0.0, 0.0
    inverse = 1.0 / det
    return (
        det,
        (a00 * b0 + a01 * b1 + a02 * b2) * inverse,
        (a01 * b0 + a11 * b1 + a12 * b2) * inverse,
        (a02 * b0 + a12 * b1 + a22 * b2) * inverse,
    )


@njit(cache=True)
def rod_into(rows: Array, rtol: float, out: Array) -> bool:  # pragma: no cover - compiled
    """The constraint wrench of two spherical joints in series, ``rows (6, 6)`` (three concurrent
    unit axes each, scaled): the unit line through their centres into ``out[0]`` (the rest of
    ``out`` zero). False where the closed form does not apply (the caller then spans and takes the
    reciprocal): a joint's axes without a common point, centres not more than ``√rtol`` apart, or
    the line not reciprocal to every axis within ``rtol``."""
    det1, x1, y1, z1 = _centre(rows[0:3])
    det2, x2, y2, z2 = _centre(rows[3:6])
    if not (det1 > 0 and det2 > 0):
        return False
    d0, d1, d2 = x2 - x1, y2 - y1, z2 - z1
    if not math.sqrt(d0 * d0 + d1 * d1 + d2 * d2) > math.sqrt(rtol):
        return False
    m0, m1, m2 = y1 * d2 - z1 * d1, z1 * d0 - x1 * d2, x1 * d1 - y1 * d0  # c1 × d
    inverse = 1.0 / math.sqrt(d0 * d0 + d1 * d1 + d2 * d2 + m0 * m0 + m1 * m1 + m2 * m2)
    d0, d1, d2 = d0 * inverse, d1 * inverse, d2 * inverse
    m0, m1, m2 = m0 * inverse, m1 * inverse, m2 * inverse
    for r in range(6):
        product = d0 * rows[r, 3] + d1 * rows[r, 4] + d2 * rows[r, 5]
        product += m0 * rows[r, 0] + m1 * rows[r, 1] + m2 * rows[r, 2]
        if not abs(product) <= rtol:
            return False
    for i in range(6):
        for s in range(6):
            out[i, s] = 0.0
    out[0, 0], out[0, 1], out[0, 2], out[0, 3], out[0, 4], out[0, 5] = d0, d1, d2, m0, m1, m2
    return True


@njit(cache=True, inline="always")
def _top(t: Array, order: int) -> float:  # pragma: no cover - compiled
    """The span rule's ``top`` (largest generator norm) for one joint screw ``t (6,)`` and a frame
    of ``order`` orthonormal rows (norm 1): ``|t|``, at least 1 if the frame has rows (NaN stays)."""
    total = 0.0
    for s in range(6):
        total += t[s] * t[s]
    size = math.sqrt(total)
    return size if (order == 0 or not size < 1.0) else 1.0


@njit(cache=True, inline="always")
def _unchanged(  # pragma: no cover - compiled
    rows: Array, order: int, size: float, top: float, rtol: float, out: Array
) -> int:
    """The frame ``rows`` itself into ``out`` where a screw's measure ``size`` (its distance from
    the twist system) is clearly below the rank threshold, returning its order; else −1 (the
    generic rule decides)."""
    if size < rtol * top / CLOSED_FORM_MARGIN:
        for i in range(6):
            for s in range(6):
                out[i, s] = rows[i, s]
        return order
    return -1


@njit(cache=True, inline="always")
def extend_into(  # pragma: no cover - compiled
    rows: Array, order: int, t: Array, rtol: float, out: Array, v: Array, coefficients: Array
) -> int:
    """The span of a frame ``rows (6, 6)`` of ``order`` and one joint screw ``t (6,)``, in closed
    form: the frame's rows kept, ``t``'s residual against them (CGS2) appended, normalised, where it
    exceeds the margin (:data:`screwkit.core._kernel_constants.CLOSED_FORM_MARGIN`); the frame
    itself where the residual is negligible. Into ``out (6, 6)``; returns the order, or −1 where the
    generic rule must decide (``v``, ``coefficients (6,)`` are scratch). Paper 002 Eq. 1 (a serial
    chain's twist system is the sum of its members')."""
    _residual_into(t, rows[:order], v, coefficients)  # CGS2 against the frame's rows
    total = 0.0
    for s in range(6):
        total += v[s] * v[s]
    size = math.sqrt(total)
    top = _top(t, order)
    if size > CLOSED_FORM_MARGIN * rtol * top and order < 6:
        for i in range(6):
            for s in range(6):
                out[i, s] = rows[i, s] if i < order else 0.0
        for s in range(6):
            out[order, s] = v[s] / size
        return order + 1
    return _unchanged(rows, order, size, top, rtol, out)


@njit(cache=True, inline="always")
def contract_into(  # pragma: no cover - compiled
    rows: Array, order: int, t: Array, rtol: float, out: Array, c: Array, u: Array
) -> int:
    """The wrenches of a frame's wrench system ``rows (6, 6)`` of ``order`` that are also reciprocal
    to one joint screw ``t (6,)`` (the reciprocal of the twist system widened by ``t``), in closed
    form: with ``c_i = rows_i ∘ t`` (``a ∘ b = a · SWAP b``), the Householder reflector ``H`` taking
    ``c`` to ``∓|c| e_0`` applied to the rows, ``(H rows)_1 … (H rows)_{order−1}`` (orthonormal, and
    ``(H rows)_j ∘ t = (H c)_j = 0``); the rows themselves where ``|c|`` is negligible (``t``
    already in the twist system). ``|c|`` is ``t``'s distance from the twist system, the measure of
    :func:`extend_into`, held to the same margin. Into ``out (6, 6)``; returns the order, or −1
    where the generic rule must decide (``c``, ``u (6,)`` are scratch). Paper 002 Eq. 1 with
    Eq. 3 (``W = T^⊥``): the wrenches reciprocal to a chain are those reciprocal to every member."""
    for i in range(order):
        total = 0.0
        for s in range(6):
            total += rows[i, s] * t[(s + 3) % 6]
        c[i] = total
    total = 0.0
    for i in range(order):
        total += c[i] * c[i]
    size = math.sqrt(total)
    top = _top(t, 6 - order)
    if size > CLOSED_FORM_MARGIN * rtol * top and order > 0:
        c[0] -= -math.copysign(size, c[0])  # v = c − β e_0, β = −sign(c_0) |c|
        total = 0.0
        for i in range(order):
            total += c[i] * c[i]
        scale = 2.0 / total
        for s in range(6):
            total = 0.0
            for i in range(order):
                total += c[i] * rows[i, s]
            u[s] = total  # vᵀ rows
        for i in range(6):
            for s in range(6):
                out[i, s] = rows[i + 1, s] - c[i + 1] * scale * u[s] if i + 1 < order else 0.0
        return order - 1
    return _unchanged(rows, order, size, top, rtol, out)


@njit(cache=True, inline="always")
def _line(rows: Array, order: int) -> tuple[float, ...]:  # pragma: no cover - compiled
    """Of a frame's first row, a line ``(d; μ)`` scaled to a unit direction: ``(ok, d, μ)`` with
    ``ok`` False unless the frame has order 1 and a nonzero direction."""
    d0, d1, d2 = rows[0, 0], rows[0, 1], rows[0, 2]
    size = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
    ok = order == 1 and size > 0
    size = size if ok else 1.0
    return ok, d0 / size, d1 / size, d2 / size, rows[0, 3] / size, rows[0, 4] / size, rows[0, 5] / size


@njit(cache=True, inline="always")
def parallelogram_into(  # pragma: no cover - compiled
    first: Array,
    first_order: int,
    second: Array,
    second_order: int,
    rtol: float,
    wrenches: Array,
    twists: Array,
) -> bool:
    """The wrench and twist systems of two rods in parallel whose lines are parallel and distinct
    (a 4S parallelogram, paper 002 §4.1), in closed form, from the rods' wrench frames ``first``,
    ``second (6, 6)`` (order 1 each, :func:`rod_into`): with ``d`` the lines' unit direction, ``μ``
    the first line's moment per unit direction, ``Δ`` the second's less the first's (``Δ = e × d``,
    ``e`` from a point of the first line to one of the second), ``a = d × Δ / |d × Δ|`` (in the
    plane of the lines, across them), ``b = d × a`` (normal to that plane) and ``h = a · μ``:
    wrenches ``(d; h a)/√(1 + h²)`` and the couple ``(0; b)`` (the paper's ``τ̂01`` and ``τ̂∞1``,
    orthonormalised), twists ``(0; a)``, ``(0; b)`` (the paper's ``ε̂∞1``, ``ε̂∞2``), ``(d; 0)`` and
    ``(a; −h d)/√(1 + h²)`` (rotations about ``d`` and about ``a``: the paper's ``ε̂01``, ``ε̂02``
    less their translations), every pair orthonormal and each wrench reciprocal to each twist.
    Into ``wrenches`` (order 2) and ``twists`` (order 4). False where it does not apply (the caller
    then spans and takes the reciprocal): a rod not of order 1, the lines' distance not clearly
    above the rank threshold (the second line's residual against the first at most
    ``rtol · CLOSED_FORM_MARGIN``), or a rod's line not within ``rtol / CLOSED_FORM_MARGIN`` of the
    closed-form wrench system (lines not parallel: not a parallelogram)."""
    ok1, d0, d1, d2, u0, u1, u2 = _line(first, first_order)
    ok2, g0, g1, g2, v0, v1, v2 = _line(second, second_order)
    if not (ok1 and ok2):
        return False
    total = 0.0  # the second line's residual against the first (both unit rows): the rule's measure
    for s in range(6):
        total += first[0, s] * second[0, s]
    apart = 0.0
    for s in range(6):
        gap = second[0, s] - total * first[0, s]
        apart += gap * gap
    if not math.sqrt(apart) > CLOSED_FORM_MARGIN * rtol:
        return False
    sign = 1.0 if d0 * g0 + d1 * g1 + d2 * g2 >= 0 else -1.0
    e0, e1, e2 = sign * v0 - u0, sign * v1 - u1, sign * v2 - u2  # Δ
    a0, a1, a2 = d1 * e2 - d2 * e1, d2 * e0 - d0 * e2, d0 * e1 - d1 * e0  # d × Δ
    size = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
    if not size > 0:
        return False
    a0, a1, a2 = a0 / size, a1 / size, a2 / size
    b0, b1, b2 = d1 * a2 - d2 * a1, d2 * a0 - d0 * a2, d0 * a1 - d1 * a0  # d × a
    h = a0 * u0 + a1 * u1 + a2 * u2
    root = math.sqrt(1.0 + h * h)
    for i in range(6):
        for s in range(6):
            wrenches[i, s] = 0.0
            twists[i, s] = 0.0
    wrenches[0, 0], wrenches[0, 1], wrenches[0, 2] = d0 / root, d1 / root, d2 / root
    wrenches[0, 3], wrenches[0, 4], wrenches[0, 5] = h * a0 / root, h * a1 / root, h * a2 / root
    wrenches[1, 3], wrenches[1, 4], wrenches[1, 5] = b0, b1, b2
    twists[0, 3], twists[0, 4], twists[0, 5] = a0, a1, a2
    twists[1, 3], twists[1, 4], twists[1, 5] = b0, b1, b2
    twists[2, 0], twists[2, 1], twists[2, 2] = d0, d1, d2
    twists[3, 0], twists[3, 1], twists[3, 2] = a0 / root, a1 / root, a2 / root
    twists[3, 3], twists[3, 4], twists[3, 5] = -h * d0 / root, -h * d1 / root, -h * d2 / root
    for line in (first, second):  # each rod's line in the closed-form wrench system (CGS, once)
        p0 = 0.0
        p1 = 0.0
        for s in range(6):
            p0 += line[0, s] * wrenches[0, s]
            p1 += line[0, s] * wrenches[1, s]
        apart = 0.0
        for s in range(6):
            gap = line[0, s] - p0 * wrenches[0, s] - p1 * wrenches[1, s]
            apart += gap * gap
        if not math.sqrt(apart) <= rtol / CLOSED_FORM_MARGIN:
            return False
    return True
