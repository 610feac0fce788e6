"""numba kernels of :mod:`screwkit.core._frames` (private; imported on the first large kernel call).

Each kernel loops over a flat batch ``(n, ...)`` and does, pose by pose, what the numpy path of
:mod:`screwkit.core._frames` does over the whole batch: the same rule (pivot choice, threshold, CGS2
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

from ._frames import CLOSED_FORM_MARGIN, COUPLE_RTOL

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


#: Operation codes of a frame program (:func:`run_program`; built by :mod:`screwkit.core.wrenches`).
SPAN, RECIPROCAL, ROD, EXTEND, CONTRACT, PARALLELOGRAM, COMPANION = 0, 1, 2, 3, 4, 5, 6
#: Source kinds of a span: joint screw rows ``(start, count)`` or a slot's rows ``(slot, bound)``.
JOINT_ROWS, SLOT_ROWS = 0, 1


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
    exceeds the margin (:data:`screwkit.core._frames.CLOSED_FORM_MARGIN`); the frame itself where the
    residual is
    negligible. Into ``out (6, 6)``; returns the order, or −1 where the generic rule must decide
    (``v``, ``coefficients (6,)`` are scratch). Paper 002 Eq. 1 (a serial chain's twist system is
    the sum of its members')."""
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


@njit(cache=True)
def run_program(
    scaled: Array, rtol: float, ops: Array, sources: Array, n_slots: int, outputs: Array
) -> tuple[Array, Array]:  # pragma: no cover - compiled
    """A frame program, pose by pose: ``scaled (n, rows, 6)`` joint screws; ``ops (m, 4)`` rows
    ``(code, slot, first, count)``: :data:`SPAN` of ``sources[first : first + count]`` (rows
    ``(kind, a, b)``), :data:`RECIPROCAL` of slot ``first``, :data:`ROD`, the reciprocal of the
    span of two spherical joints' rows (:func:`rod_into`, else span and reciprocal),
    :data:`EXTEND`, the span of one joint screw and a twist frame (:func:`extend_into`, else the
    span), :data:`CONTRACT`, the reciprocal of the span of one joint screw and the twists of a
    wrench frame (:func:`contract_into`, else the span of the screw and those twists, and its
    reciprocal), or :data:`PARALLELOGRAM`, two rods' wrenches and twists
    (:func:`parallelogram_into`, else the span of the rods' frames and its reciprocal) into
    ``slot`` and ``slot + 1`` (whose op is a :data:`COMPANION`, doing nothing); each other op into
    ``slot``. The first two sources of :data:`EXTEND` and :data:`CONTRACT` are a joint's one screw
    and a slot's frame, in the chain's order; a third source of :data:`CONTRACT` is the slot of the
    twist frame that its fallback spans (the same rows as an :data:`EXTEND` of the same chain, so
    the two decide alike), else those twists are the wrench frame's reciprocal. Returns the rows
    ``(n, len(outputs), 6, 6)`` and orders of the ``outputs`` slots. A
    span or reciprocal is exactly what the batched kernel :func:`span` or :func:`complement`
    (``swap``) computes on that pose, so running a program equals running its ops one by one (the
    numpy path's way, :func:`screwkit.core.wrenches._run`) up to the two paths' round-off."""
    n = scaled.shape[0]
    slots = np.zeros((n_slots, 6, 6))
    orders = np.zeros(n_slots, dtype=np.int64)
    out_rows = np.zeros((n, outputs.shape[0], 6, 6))
    out_orders = np.zeros((n, outputs.shape[0]), dtype=np.int64)
    most = 6
    for i in range(sources.shape[0]):
        most = max(most, sources[i, 2])
    work = np.empty((most * sources.shape[0] + 6, 6))
    norms = np.empty(work.shape[0])
    pivot = np.empty(6)
    coefficients = np.empty(6)
    a = np.empty((6, 6))
    v = np.zeros((6, 6))
    tau = np.zeros(6)
    y = np.empty(6)
    twists = np.empty((6, 6))
    for p in range(n):
        for op in range(ops.shape[0]):
            code, slot, first, count = ops[op, 0], ops[op, 1], ops[op, 2], ops[op, 3]
            if code == RECIPROCAL:
                complement_into(slots[first], orders[first], True, slots[slot], a, v, tau, y)
                orders[slot] = 6 - orders[first]
                continue
            if code == COMPANION:  # written by the op before it
                continue
            if code == PARALLELOGRAM:
                x, z = sources[first, 1], sources[first + 1, 1]
                rod_a, rod_b, into_w, into_t = slots[x], slots[z], slots[slot], slots[slot + 1]
                if parallelogram_into(rod_a, orders[x], rod_b, orders[z], rtol, into_w, into_t):
                    orders[slot], orders[slot + 1] = 2, 4
                    continue
            if code == EXTEND or code == CONTRACT:  # one joint screw and one frame, in closed form
                joint = first if sources[first, 0] == JOINT_ROWS else first + 1
                x = sources[2 * first + 1 - joint, 1]
                t = scaled[p, sources[joint, 1]]
                if code == EXTEND:
                    order = extend_into(slots[x], orders[x], t, rtol, slots[slot], pivot, coefficients)
                else:
                    order = contract_into(slots[x], orders[x], t, rtol, slots[slot], pivot, coefficients)
                if order >= 0:
                    orders[slot] = order
                    continue
            k = 0
            for q in range(first, first + (2 if code == CONTRACT else count)):
                kind, x, size = sources[q, 0], sources[q, 1], sources[q, 2]
                if code == CONTRACT and kind == SLOT_ROWS and count == 3:  # the node's twist frame
                    kind, x, size = sources[first + 2, 0], sources[first + 2, 1], sources[first + 2, 2]
                if kind == JOINT_ROWS:
                    for i in range(size):
                        for s in range(6):
                            work[k, s] = scaled[p, x + i, s]
                        k += 1
                elif code == CONTRACT and count == 2:  # the twists of the wrench frame in slot x
                    complement_into(slots[x], orders[x], True, twists, a, v, tau, y)
                    for i in range(6 - orders[x]):
                        for s in range(6):
                            work[k, s] = twists[i, s]
                        k += 1
                else:  # a slot's rows up to its bound; those beyond its order are zero, left out
                    for i in range(min(size, orders[x])):
                        for s in range(6):
                            work[k, s] = slots[x, i, s]
                        k += 1
            if code == ROD or code == CONTRACT:
                if code == ROD and rod_into(work, rtol, slots[slot]):
                    orders[slot] = 1
                    continue
                order = span_into(work, k, rtol, a, norms, pivot, coefficients)  # the rule, spelt out
                complement_into(a.copy(), order, True, slots[slot], a, v, tau, y)
                orders[slot] = 6 - order
                continue
            orders[slot] = span_into(work, k, rtol, slots[slot], norms, pivot, coefficients)
            if code == PARALLELOGRAM:  # the twists, as a reciprocal op would
                complement_into(slots[slot], orders[slot], True, slots[slot + 1], a, v, tau, y)
                orders[slot + 1] = 6 - orders[slot]
        for i in range(outputs.shape[0]):
            out_rows[p, i] = slots[outputs[i]]
            out_orders[p, i] = orders[outputs[i]]
    return out_rows, out_orders


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
    """The analysis core's last per-pose steps in one pass (:func:`screwkit.core._frames.closing`, whose
    numpy path does these operations in this order): the global frame, :func:`span` of the
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
    """:func:`screwkit.core._frames.limb_systems` pose by pose and limb by limb: ``locked``, ``passive``
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
    """:func:`screwkit.core._frames.scaled_magnitudes` of one row ``(6,)``."""
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
    """:func:`screwkit.core._frames.transmissions` pose by pose: ``raw``, ``twists`` ``(n, l, 6)``."""
    n, limbs = raw.shape[0], raw.shape[1]
    wrench = np.empty((n, limbs, 6))
    out = np.empty((n, limbs))
    for p in range(n):
        for k in range(limbs):
            _transmission_into(raw, twists, rtol, p, k, wrench, out)
    return wrench, out


@njit(cache=True, inline="always")
def _not_line(row: Array, line_rtol: float) -> bool:  # pragma: no cover - compiled
    """:func:`screwkit.core._frames.not_lines` of one row ``(6,)``."""
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
    """:func:`screwkit.core._frames.limb_wrenches` in one pass: per pose, the limb systems
    (:func:`limb_systems`), whether each actuation direction is a line (:func:`_not_line`), the
    unit wrenches along the directions with their transmissions (:func:`transmissions`) and the
    coupled limbs' wrenches less their part in their leg's frame (:func:`residual`)."""
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
