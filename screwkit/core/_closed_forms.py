"""Closed forms of the rank rule's systems: a rod, a 4S parallelogram, one joint screw more or less (private).

Where a system is known in closed form the analysis core uses it instead of a span and a
complement (:mod:`screwkit.core.frames`): two spherical joints in series transmit the force along
the line through their centres (:func:`rod`; paper 002 §4.1 models each H4 rod so); two such rods
in parallel along parallel, distinct lines (a 4S parallelogram) have the wrench and twist systems
of paper 002 §4.1 (:func:`parallelogram`); a 1-dof joint in series with a node adds one CGS2 step
to the node's twists (:func:`extend`) and takes one Householder reflector off its wrenches
(:func:`contract`). Each is checked where it is used and falls back on the rule where its
preconditions fail or its rank decision lies within a factor
:data:`~screwkit.core._kernel_constants.CLOSED_FORM_MARGIN` of the rule's threshold, so the orders
are the rule's. The numpy paths of :mod:`screwkit.core._closed_forms_numba`, operation for
operation (the two agree bit for bit).

Examples
--------
>>> sphere = lambda c: [[*e, *np.cross(c, e)] for e in np.eye(3)]
>>> rows, order = rod(np.array(sphere([0, 0, 0.0]) + sphere([0, 0, 2.0])), 1e-9)
>>> int(order), rows[0] + 0.0
(1, array([0., 0., 1., 0., 0., 0.]))
"""

from __future__ import annotations

import math

import numpy as np

from ._kernel_constants import CLOSED_FORM_MARGIN
from .frames import _dot_in_order, empty, reciprocal, span, sum_in_order, swapped

__all__ = [
    "contract",
    "extend",
    "parallelogram",
    "rod",
]

Array = np.ndarray


def _centres(rows: Array) -> tuple[Array, Array, Array, Array]:
    """:func:`screwkit.core._closed_forms_numba._centre` over a batch of three axes ``rows (n, 3, 6)``, in its
    operation order: ``(det, x, y, z)``, ``det ≤ 0`` where there is no point."""
    zero = np.zeros(rows.shape[0])
    n00, n01, n02, n11, n12, n22 = (zero.copy() for _ in range(6))
    b0, b1, b2 = zero.copy(), zero.copy(), zero.copy()
    good = np.ones(rows.shape[0], dtype=bool)
    for r in range(3):
        u0, u1, u2, m0, m1, m2 = (rows[:, r, s] for s in range(6))
        squared = u0 * u0 + u1 * u1 + u2 * u2
        good &= squared > 0
        inverse = 1.0 / np.where(squared > 0, squared, 1.0)
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
    det = np.where(good & (det > 0), det, 0.0)
    inverse = 1.0 / np.where(det > 0, det, 1.0)
    return (
        det,
        (a00 * b0 + a01 * b1 + a02 * b2) * inverse,
        (a01 * b0 + a11 * b1 + a12 * b2) * inverse,
        (a02 * b0 + a12 * b1 + a22 * b2) * inverse,
    )


def rod(rows: Array, rtol: float) -> tuple[Array, Array]:
    """The reciprocal of the span of two spherical joints in series, rows ``(..., 6, 6)`` (three
    concurrent axes each, scaled): in closed form, the unit line through the two centres
    (order 1), where it applies; elsewhere (a joint's axes without a common point, centres not
    more than ``√rtol`` apart, or the line not reciprocal to every axis within ``rtol``)
    :func:`reciprocal` of :func:`span`. The numpy path of
    :func:`screwkit.core._closed_forms_numba.rod_into` (which the compiled programs run), operation for
    operation, so the two agree bit for bit.

    Each centre is the least-squares point of its axes, ``N⁻¹ Σ f`` with ``N = Σ (I − û ûᵀ)`` and
    ``f = u × m / |u|²`` the feet (by the adjugate of ``N``).

    Parameters
    ----------
    rows : array_like, shape (..., 6, 6)
        Three unit axes of each spherical joint, scaled.
    rtol : float
        The rule's relative threshold.

    Returns
    -------
    rows : numpy.ndarray, shape (..., 6, 6)
        The wrench frame's rows.
    order : numpy.ndarray of int, shape (...)
        1 where the closed form applies.

    Examples
    --------
    >>> sphere = lambda c: [[*e, *np.cross(c, e)] for e in np.eye(3)]
    >>> rows, order = rod(np.array(sphere([0, 0, 0.0]) + sphere([0, 0, 1.0])), 1e-9)
    >>> int(order), rows[0] + 0.0
    (1, array([0., 0., 1., 0., 0., 0.]))
    """
    rows = np.asarray(rows, dtype=float)
    batch = rows.shape[:-2]
    flat = rows.reshape(-1, 6, 6)
    with np.errstate(all="ignore"):  # poses where the closed form fails compute values not kept
        det1, x1, y1, z1 = _centres(flat[:, 0:3])
        det2, x2, y2, z2 = _centres(flat[:, 3:6])
        good = (det1 > 0) & (det2 > 0)
        d0, d1, d2 = x2 - x1, y2 - y1, z2 - z1
        good &= np.sqrt(d0 * d0 + d1 * d1 + d2 * d2) > math.sqrt(rtol)
        m0, m1, m2 = y1 * d2 - z1 * d1, z1 * d0 - x1 * d2, x1 * d1 - y1 * d0  # c1 × d
        size = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2 + m0 * m0 + m1 * m1 + m2 * m2)
        inverse = 1.0 / np.where(good, size, 1.0)
        line = [d0 * inverse, d1 * inverse, d2 * inverse, m0 * inverse, m1 * inverse, m2 * inverse]
        for r in range(6):
            product = line[0] * flat[:, r, 3] + line[1] * flat[:, r, 4] + line[2] * flat[:, r, 5]
            product += line[3] * flat[:, r, 0] + line[4] * flat[:, r, 1] + line[5] * flat[:, r, 2]
            good &= np.abs(product) <= rtol
    out, order = empty((flat.shape[0],))
    out[:, 0] = np.where(good[:, None], np.stack(line, axis=-1), 0.0)
    order[good] = 1
    if not good.all():
        bad = ~good
        out[bad], order[bad] = reciprocal(*span(flat[bad], rtol))
    return out.reshape(*batch, 6, 6), order.reshape(batch)


def _top(t: Array, order: Array) -> Array:
    """The span rule's ``top`` for joint screws ``t (n, 6)`` and frames of ``order`` orthonormal rows
    (norm 1): ``|t|``, at least 1 where the frame has rows (NaN stays)."""
    size = np.sqrt(_dot_in_order(t, t))
    return np.where((order == 0) | ~(size < 1.0), size, 1.0)


def extend(rows: Array, order: Array, t: Array, rtol: float) -> tuple[Array, Array, Array]:
    """The span of a twist frame ``(rows (..., 6, 6), order (...))`` and one joint screw
    ``t (..., 6)``, in closed form (paper 002 Eq. 1: a serial chain's twist system is the sum of its
    members'): the frame's rows kept and ``t``'s residual against them (CGS2: classical Gram–Schmidt
    applied twice, Giraud, Langou & Rozložník, Comput. Math. Appl. 50, 2005) appended, normalised,
    where it is clearly above the rank rule's threshold; the frame itself where it is clearly below
    (:data:`~screwkit.core._kernel_constants.CLOSED_FORM_MARGIN`). Returns ``(rows, order,
    decided)``; where ``decided`` is False the caller spans (the rule decides). The numpy path of
    :func:`screwkit.core._closed_forms_numba.extend_into`, operation for operation.

    Parameters
    ----------
    rows : array_like, shape (..., 6, 6)
        A twist frame's rows.
    order : array_like of int, shape (...)
        Its order.
    t : array_like, shape (..., 6)
        The joint's scaled screw.
    rtol : float
        The rule's relative threshold.

    Returns
    -------
    rows : numpy.ndarray, shape (..., 6, 6)
    order : numpy.ndarray of int, shape (...)
    decided : numpy.ndarray of bool, shape (...)
        False where the caller must span.

    Examples
    --------
    >>> frame = np.eye(6)[:2]; frame = np.concatenate([frame, np.zeros((4, 6))])
    >>> rows, order, decided = extend(frame, np.array(2), np.array([1.0, 0, 1, 0, 0, 0]), 1e-9)
    >>> int(order), bool(decided), rows[2]
    (3, True, array([0., 0., 1., 0., 0., 0.]))
    """
    rows, t = np.asarray(rows, dtype=float), np.asarray(t, dtype=float)
    batch = rows.shape[:-2]
    flat, order = rows.reshape(-1, 6, 6), np.broadcast_to(order, batch).reshape(-1)
    t = t.reshape(-1, 6)
    v = t.copy()
    with np.errstate(all="ignore"):  # undecided poses compute values that are not kept
        for _ in range(2):
            coefficients = [_dot_in_order(v, flat[:, i]) for i in range(6)]
            for i in range(6):
                v = np.where((i < order)[:, None], v - coefficients[i][:, None] * flat[:, i], v)
        size = np.sqrt(_dot_in_order(v, v))
        top = _top(t, order)
        independent = (size > CLOSED_FORM_MARGIN * rtol * top) & (order < 6)
        dependent = size < rtol * top / CLOSED_FORM_MARGIN
        kept = np.arange(6) < np.where(independent, order, 6)[:, None]
        out = np.where(kept[..., None], flat, 0.0)
        where = np.flatnonzero(independent)
        out[where, order[where]] = v[where] / size[where, None]
    new_order = np.where(independent, order + 1, order)
    return out.reshape(*batch, 6, 6), new_order.reshape(batch), (independent | dependent).reshape(batch)


def contract(rows: Array, order: Array, t: Array, rtol: float) -> tuple[Array, Array, Array]:
    """The wrenches of a wrench frame ``(rows (..., 6, 6), order (...))`` also reciprocal to one
    joint screw ``t (..., 6)`` (the reciprocal of the twist system widened by ``t``), in closed form
    (paper 002 Eq. 1 with Eq. 3, ``W = T^⊥``): with ``c_i = rows_i ∘ t``, the Householder reflector
    ``H`` taking ``c`` to ``∓|c| e_0`` (Golub & Van Loan, *Matrix Computations*, 4th ed., §5.1.2)
    applied to the rows, rows ``1 … order − 1`` of ``H rows``
    (orthonormal, each reciprocal to ``t``) where ``|c|`` (``t``'s distance from the twist system,
    :func:`extend`'s measure) is clearly above the rule's threshold; the frame itself where it is
    clearly below (:data:`~screwkit.core._kernel_constants.CLOSED_FORM_MARGIN`). Returns ``(rows,
    order, decided)``; where ``decided`` is False the caller takes the reciprocal, spans and takes
    the reciprocal again (the rule decides). The numpy path of
    :func:`screwkit.core._closed_forms_numba.contract_into`, operation for operation.

    Parameters
    ----------
    rows : array_like, shape (..., 6, 6)
        A wrench frame's rows.
    order : array_like of int, shape (...)
        Its order.
    t : array_like, shape (..., 6)
        The joint's scaled screw.
    rtol : float
        The rule's relative threshold.

    Returns
    -------
    rows : numpy.ndarray, shape (..., 6, 6)
    order : numpy.ndarray of int, shape (...)
    decided : numpy.ndarray of bool, shape (...)
        False where the caller must take the rule's way.

    Examples
    --------
    >>> couples = np.zeros((6, 6)); couples[0, 3] = couples[1, 4] = 1.0   # two couples, about x and y
    >>> rows, order, decided = contract(couples, np.array(2), np.array([1.0, 0, 0, 0, 0, 0]), 1e-9)
    >>> int(order), bool(decided), rows[0] + 0.0                           # a rotation about x: one left
    (1, True, array([0., 0., 0., 0., 1., 0.]))
    """
    rows, t = np.asarray(rows, dtype=float), np.asarray(t, dtype=float)
    batch = rows.shape[:-2]
    flat, order = rows.reshape(-1, 6, 6), np.broadcast_to(order, batch).reshape(-1)
    t = t.reshape(-1, 6)
    used = np.arange(6) < order[:, None]
    with np.errstate(all="ignore"):  # undecided poses compute values that are not kept
        c = np.where(used, _dot_in_order(flat, swapped(t)[:, None, :]), 0.0)
        size = np.sqrt(_dot_in_order(c, c))
        top = _top(t, 6 - order)
        independent = (size > CLOSED_FORM_MARGIN * rtol * top) & (order > 0)
        dependent = size < rtol * top / CLOSED_FORM_MARGIN
        c[:, 0] -= -np.copysign(size, c[:, 0])  # v = c − β e_0, β = −sign(c_0) |c|
        scale = 2.0 / _dot_in_order(c, c)
        u = sum_in_order(np.swapaxes(c[:, :, None] * flat, -1, -2))  # vᵀ rows, over the rows in order
        moved = flat[:, 1:] - (c[:, 1:] * scale[:, None])[..., None] * u[:, None, :]
        moved = np.where(used[:, 1:, None], moved, 0.0)
        moved = np.concatenate([moved, np.zeros_like(flat[:, :1])], 1)
        out = np.where(independent[:, None, None], moved, flat)
    new_order = np.where(independent, order - 1, order)
    return out.reshape(*batch, 6, 6), new_order.reshape(batch), (independent | dependent).reshape(batch)


def _unit_direction_line(rows: Array, order: Array) -> tuple[Array, list[Array]]:
    """Of frames' first rows ``(n, 6, 6)``: ``(ok, [d0, d1, d2, μ0, μ1, μ2])``, the line scaled to a
    unit direction, ``ok`` False unless the frame has order 1 and a nonzero direction."""
    d0, d1, d2 = rows[:, 0, 0], rows[:, 0, 1], rows[:, 0, 2]
    size = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
    ok = (order == 1) & (size > 0)
    size = np.where(ok, size, 1.0)
    return ok, [rows[:, 0, s] / size for s in range(6)]


def parallelogram(
    first: tuple[Array, Array], second: tuple[Array, Array], rtol: float
) -> tuple[Array, Array, Array, Array, Array]:
    """The wrench and twist systems of two rods in parallel whose lines are parallel and distinct (a
    4S parallelogram, paper 002 §4.1), in closed form from the rods' wrench frames (order 1 each,
    :func:`rod`): ``(wrench rows, wrench order, twist rows, twist order, decided)``; where
    ``decided`` is False the caller spans the two frames and takes the reciprocal (the rule). The
    formulas and when they apply: :func:`screwkit.core._closed_forms_numba.parallelogram_into`, whose
    operations this numpy path does in its order (the two agree bit for bit).

    Paper 002 §4.1 spans the wrenches by ``τ̂01 = (s_mp; r_p × s_mp)`` and ``τ̂∞1 = (0; s_mp × s_mn)``
    and the twists by ``ε̂01 = (s_mp; r_p × s_mp)``, ``ε̂02 = (s_mn; r_n × s_mn)``, ``ε̂∞1 = (0; n)``,
    ``ε̂∞2 = (0; s_mp × n)``: the same two systems (``tests/core/test_frames.py`` checks them by rank).

    Parameters
    ----------
    first, second : tuple of numpy.ndarray
        The two rods' wrench frames ``(rows (..., 6, 6), order (...))``.
    rtol : float
        The rule's relative threshold.

    Returns
    -------
    wrenches : numpy.ndarray, shape (..., 6, 6)
    wrench_order : numpy.ndarray of int, shape (...)
        2.
    twists : numpy.ndarray, shape (..., 6, 6)
    twist_order : numpy.ndarray of int, shape (...)
        4.
    decided : numpy.ndarray of bool, shape (...)
        False where the caller must span.

    Examples
    --------
    >>> rod = lambda p: np.array([[0, 0, 1.0, *np.cross(p, [0, 0, 1.0])]] + [[0.0] * 6] * 5)
    >>> w, w_order, t, t_order, decided = parallelogram((rod([0, 0, 0]), 1), (rod([1.0, 0, 0]), 1), 1e-9)
    >>> int(w_order), int(t_order), bool(decided), t[:, :3] @ [0, 0, 1.0] + 0.0  # one rotation about z
    (2, 4, True, array([0., 0., 1., 0., 0., 0.]))
    """
    rows1, order1 = np.asarray(first[0], dtype=float), np.asarray(first[1])
    batch = rows1.shape[:-2]
    rows1 = rows1.reshape(-1, 6, 6)
    rows2 = np.asarray(second[0], dtype=float).reshape(-1, 6, 6)
    order1, order2 = order1.reshape(-1), np.asarray(second[1]).reshape(-1)
    n = rows1.shape[0]
    wrenches, twists = np.zeros((n, 6, 6)), np.zeros((n, 6, 6))
    with np.errstate(all="ignore"):  # undecided poses compute values that are not kept
        ok1, (d0, d1, d2, u0, u1, u2) = _unit_direction_line(rows1, order1)
        ok2, (g0, g1, g2, v0, v1, v2) = _unit_direction_line(rows2, order2)
        total = _dot_in_order(rows1[:, 0], rows2[:, 0])
        gap = rows2[:, 0] - total[:, None] * rows1[:, 0]
        decided = ok1 & ok2 & (np.sqrt(_dot_in_order(gap, gap)) > CLOSED_FORM_MARGIN * rtol)
        sign = np.where(d0 * g0 + d1 * g1 + d2 * g2 >= 0, 1.0, -1.0)
        e0, e1, e2 = sign * v0 - u0, sign * v1 - u1, sign * v2 - u2
        a0, a1, a2 = d1 * e2 - d2 * e1, d2 * e0 - d0 * e2, d0 * e1 - d1 * e0
        size = np.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
        decided &= size > 0
        a0, a1, a2 = a0 / size, a1 / size, a2 / size
        b0, b1, b2 = d1 * a2 - d2 * a1, d2 * a0 - d0 * a2, d0 * a1 - d1 * a0
        h = a0 * u0 + a1 * u1 + a2 * u2
        root = np.sqrt(1.0 + h * h)
        force = [d0 / root, d1 / root, d2 / root, h * a0 / root, h * a1 / root, h * a2 / root]
        wrenches[:, 0] = np.stack(force, -1)
        wrenches[:, 1, 3:] = np.stack([b0, b1, b2], -1)
        twists[:, 0, 3:] = np.stack([a0, a1, a2], -1)
        twists[:, 1, 3:] = np.stack([b0, b1, b2], -1)
        twists[:, 2, :3] = np.stack([d0, d1, d2], -1)
        rotation = [a0 / root, a1 / root, a2 / root, -h * d0 / root, -h * d1 / root, -h * d2 / root]
        twists[:, 3] = np.stack(rotation, -1)
        for line in (rows1[:, 0], rows2[:, 0]):  # each rod's line in the closed-form wrench system
            p0, p1 = _dot_in_order(line, wrenches[:, 0]), _dot_in_order(line, wrenches[:, 1])
            gap = line - p0[:, None] * wrenches[:, 0] - p1[:, None] * wrenches[:, 1]
            decided &= np.sqrt(_dot_in_order(gap, gap)) <= rtol / CLOSED_FORM_MARGIN
    twos, fours = np.full(n, 2), np.full(n, 4)
    return (
        wrenches.reshape(*batch, 6, 6),
        twos.reshape(batch),
        twists.reshape(*batch, 6, 6),
        fours.reshape(batch),
        decided.reshape(batch),
    )
