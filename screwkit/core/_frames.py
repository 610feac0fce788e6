"""Batched orthonormal frames of screw systems: the arithmetic under every pose (private).

Every rank decision of the analysis core is made here, over a leading batch axis, on screws
expressed about the mechanism's own reference point with moments divided by its characteristic
length (*scaled coordinates*, :func:`to_scaled`). In those coordinates a rigid motion about the
reference point acts as ``diag(R, R)``, an orthogonal map, and a change of unit does nothing,
so Euclidean norms, orthogonality and every decision below follow the mechanism, not the user's
frame.

A **frame** is a pair ``(rows, order)``: ``rows`` of shape ``(..., 6, 6)`` whose first ``order``
rows are an orthonormal basis of the system and whose other rows are zero.

**The rank rule** (one rule for the whole analysis): a system is spanned by generators with
Gram–Schmidt and column pivoting (QR with column pivoting, Golub & Van Loan, *Matrix
Computations*, 4th ed., §5.4.2), each pivot re-orthogonalised once (CGS2, Giraud et al., *Numer.
Math.* 101, 2005); the pivot joins the basis while its distance from the span of those already
chosen exceeds ``rtol`` times the largest generator's norm. Pivoting makes the result independent
of the generators' order up to ties.

Reciprocity in scaled coordinates is the Euclidean product with the halves swapped
(``a ∘ b = a · (SWAP b)``, ``SWAP`` orthogonal and symmetric), so the system reciprocal to a frame
is ``SWAP`` applied to its orthogonal complement: no rank decision is needed for it.

**Closed forms.** Where a system is known in closed form the core uses it instead of a span and a
complement: two spherical joints in series transmit the force along the line through their
centres (:func:`rod`; paper 002 §4.1 models each H4 rod so); two such rods in parallel along
parallel, distinct lines (a 4S parallelogram) have the wrench and twist systems of paper 002 §4.1
(:func:`parallelogram`); a 1-dof joint in series with a node adds one CGS2 step to the node's
twists (:func:`extend`) and takes one Householder reflector off its wrenches (:func:`contract`).
Each is checked where it is used and falls back on the rule where its preconditions fail or its
rank decision lies within a factor :data:`CLOSED_FORM_MARGIN` of the rule's threshold, so the
orders are the rule's.

**Two implementations, one rule.** :func:`span`, :func:`complement`, :func:`reciprocal`,
:func:`residual`, :func:`rod` and the closed forms have a numpy path (vectorized over the
batch) and, when numba is installed (the ``fast`` extra), compiled per-pose loops
(:mod:`screwkit.core._frames_numba`). The numpy path does the compiled loops' floating-point operations
in their order (sums left to right, no BLAS call, no library QR), so the two agree bit for bit,
and a pose's answer never depends on the batch it is in: single-pose and batched answers are
bit-identical whichever path runs. The analysis core strings spans, reciprocals and rods into one
flat *program* per mechanism (:func:`screwkit.core.wrenches._program`): on the numba path one compiled
call runs it pose by pose (:func:`screwkit.core._frames_numba.run_program`, the same per-pose loops),
on the numpy path its ops run one by one over the batch. numba is imported on
the first call over :data:`~screwkit.algebra.compiled.COMPILED_MIN_BATCH` frames or more
(:func:`screwkit.algebra.compiled.compiled_kernels`, which also reads ``SCREWKIT_NUMBA``), so a
single-pose analysis never pays for its import; its compiled code is cached on disk.

Examples
--------
>>> import numpy as np
>>> rows, order = span(np.array([[[1.0, 0, 0, 0, 0, 0], [2.0, 0, 0, 0, 0, 0]]]), 1e-9)
>>> order
array([1])
>>> reciprocal(rows, order)[1]
array([5])
"""

from __future__ import annotations

import math
from types import ModuleType

import numpy as np

from ..algebra import backend as B
from ..algebra.compiled import COMPILED_MIN_BATCH, compiled_kernels, sum_in_order

__all__ = [
    "SWAP",
    "actuation_directions",
    "backend",
    "closing",
    "complement",
    "contract",
    "empty",
    "extend",
    "from_scaled",
    "limb_systems",
    "limb_wrenches",
    "not_lines",
    "packed",
    "parallelogram",
    "reciprocal",
    "residual",
    "residuals_against",
    "rod",
    "scaled_magnitudes",
    "singular_ratio",
    "span",
    "swapped",
    "to_scaled",
    "transmission_index",
    "transmissions",
    "transmissions_numpy",
    "triangular",
    "unit_rows",
    "unit_size",
    "unpacked",
]

Array = np.ndarray

#: ``a ∘ b = a · (SWAP b)``: the reciprocal product as a Euclidean one.
SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])
SWAP.flags.writeable = False

def _numba_kernels(size: int) -> ModuleType | None:
    """The rank kernels (:mod:`screwkit.core._frames_numba`) for ``size`` frames, or None for numpy."""
    return compiled_kernels("screwkit.core._frames_numba", size)


def _import_kernels() -> ModuleType:
    """The numba kernels, whatever this process's choice (the numba path; tests call it directly)."""
    from . import _frames_numba as _frames_numba

    return _frames_numba


def _size(shape: tuple[int, ...]) -> int:
    """The number of frames in a batch shape."""
    return math.prod(shape)


def backend() -> str:
    """``"numba"`` or ``"numpy"``: the implementation of batches of :data:`COMPILED_MIN_BATCH`
    frames or more in this process (smaller ones run numpy until numba is loaded).

    Examples
    --------
    >>> backend() in {"numba", "numpy"}
    True
    """
    return "numpy" if _numba_kernels(COMPILED_MIN_BATCH) is None else "numba"


def to_scaled(screws: Array, centre: Array, length: Array) -> Array:
    """Screws ``(..., k, 6)`` about ``centre`` ``(..., 3)`` with moments over ``length`` ``(...)``.

    Examples
    --------
    >>> to_scaled(np.array([[0, 0, 1.0, 2.0, 0, 0]]), np.array([0, 2.0, 0]), np.array(2.0))
    array([[0., 0., 1., 0., 0., 0.]])
    """
    directions = screws[..., :3]
    moments = screws[..., 3:] - B.cross(centre[..., None, :], directions)
    return np.concatenate([directions, moments / length[..., None, None]], axis=-1)


def from_scaled(rows: Array, centre: Array, length: Array) -> Array:
    """The inverse of :func:`to_scaled`: rows ``(..., k, 6)`` back to the user's frame and unit.

    Examples
    --------
    >>> from_scaled(np.array([[0, 0, 1.0, 0, 0, 0]]), np.array([0, 2.0, 0]), np.array(2.0))
    array([[0., 0., 1., 2., 0., 0.]])
    """
    directions = rows[..., :3]
    moments = rows[..., 3:] * length[..., None, None] + B.cross(centre[..., None, :], directions)
    return np.concatenate([directions, moments], axis=-1)


def swapped(rows: Array) -> Array:
    """``rows (..., 6)`` with their halves exchanged: ``SWAP`` applied exactly (no BLAS call, whose
    kernels, and so whose last bits, depend on the batch size).

    Examples
    --------
    >>> swapped(np.arange(6.0))
    array([3., 4., 5., 0., 1., 2.])
    """
    return np.concatenate([rows[..., 3:], rows[..., :3]], axis=-1)


def empty(batch: tuple[int, ...]) -> tuple[Array, Array]:
    """The frame of the 0-system over a batch.

    Examples
    --------
    >>> empty((2,))[1]
    array([0, 0])
    """
    return np.zeros((*batch, 6, 6)), np.zeros(batch, dtype=int)


def span(generators: Array, rtol: float) -> tuple[Array, Array]:
    """The frame of the system spanned by ``generators`` ``(..., k, 6)`` (the module's rank rule).

    Examples
    --------
    >>> rows, order = span(np.array([[1.0, 0, 0, 0, 0, 0], [1.0, 1e-12, 0, 0, 0, 0]]), 1e-9)
    >>> int(order), rows[0]
    (1, array([1., 0., 0., 0., 0., 0.]))
    """
    kernels = _numba_kernels(_size(np.shape(generators)[:-2]))
    return (_span_numpy if kernels is None else _span_numba)(generators, rtol)


def _span_numba(generators: Array, rtol: float) -> tuple[Array, Array]:
    """:func:`span` by the compiled per-pose loop."""
    work = np.array(generators, dtype=float)
    batch, k = work.shape[:-2], work.shape[-2]
    if k == 0 or 0 in batch:
        return empty(batch)
    kernels = _import_kernels()
    rows, order = kernels.span(np.ascontiguousarray(work.reshape(-1, k, 6)), float(rtol))
    return rows.reshape(*batch, 6, 6), order.reshape(batch)


def _dot_in_order(a: Array, b: Array) -> Array:
    """``Σ_s a[..., s] b[..., s]`` over the last axis, summed left to right from ``0.0``
    (:func:`sum_in_order`)."""
    return sum_in_order(a * b)


def _span_numpy(generators: Array, rtol: float) -> tuple[Array, Array]:
    """:func:`span` vectorized over the batch with numpy: :func:`screwkit.core._frames_numba.span`'s
    operations in its order, so the two paths agree bit for bit."""
    work = np.array(generators, dtype=float)
    batch, k = work.shape[:-2], work.shape[-2]
    if k == 0 or 0 in batch:
        return empty(batch)
    w = work.reshape(-1, k, 6)
    n = w.shape[0]
    rows, order = np.zeros((n, 6, 6)), np.zeros(n, dtype=int)
    norms = np.sqrt(_dot_in_order(w, w))
    threshold = rtol * norms.max(axis=-1)  # NaN if a norm is NaN, as the kernel's loop
    active = np.ones(n, dtype=bool)
    poses = np.arange(n)
    with np.errstate(all="ignore"):  # poses already stopped compute values that are not kept
        for step in range(min(k, 6)):
            pivot = w[poses, np.argmax(norms, axis=-1)]  # the first largest, or the first NaN
            coefficients = _dot_in_order(rows[:, :step], pivot[:, None, :])  # CGS2, from the pivot as drawn
            for i in range(step):
                pivot = pivot - coefficients[:, i, None] * rows[:, i]
            size = np.sqrt(_dot_in_order(pivot, pivot))
            active &= (size > threshold) & (size > 0)
            if not active.any():
                break
            unit = np.where(active[:, None], pivot / size[:, None], 0.0)
            rows[:, step] = unit
            order += active
            moved = w - _dot_in_order(w, unit[:, None, :])[..., None] * unit[:, None, :]
            w = np.where(active[:, None, None], moved, w)
            norms = np.where(active[:, None], np.sqrt(_dot_in_order(w, w)), norms)
    return rows.reshape(*batch, 6, 6), order.reshape(batch)


def complement(rows: Array, order: Array) -> tuple[Array, Array]:
    """An orthonormal frame of the orthogonal complement of a frame (order ``6 − order``).

    The complete Householder QR of the frame's rows as columns: its first ``order`` columns span
    the frame, the others its complement (no rank decision is made).

    Examples
    --------
    >>> rows, order = complement(np.diag([1.0, 0, 0, 0, 0, 0]), np.array(1))
    >>> int(order), float(np.abs(rows[:5, 0]).max()), float(np.abs(rows[5]).max())
    (5, 0.0, 0.0)
    """
    kernels = _numba_kernels(_size(np.shape(rows)[:-2]))
    return (_complement_numpy if kernels is None else _complement_numba)(rows, order)


def _complement_numba(rows: Array, order: Array, *, swap: bool = False) -> tuple[Array, Array]:
    """:func:`complement` (or, with ``swap``, :func:`reciprocal`) by the compiled per-pose loop."""
    rows = np.asarray(rows, dtype=float)
    order = np.asarray(order)
    batch = rows.shape[:-2]
    if 0 in batch:
        return np.zeros((*batch, 6, 6)), 6 - order
    flat_order = np.ascontiguousarray(np.broadcast_to(order, batch).reshape(-1), dtype=np.int64)
    kernels = _import_kernels()
    out = kernels.complement(np.ascontiguousarray(rows.reshape(-1, 6, 6)), flat_order, swap)
    return out.reshape(*batch, 6, 6), 6 - order


def _complement_numpy(rows: Array, order: Array, *, swap: bool = False) -> tuple[Array, Array]:
    """:func:`complement` (or, with ``swap``, :func:`reciprocal`) vectorized over the batch:
    :func:`screwkit.core._frames_numba.complement`'s Householder QR operation for operation, so the two
    paths agree bit for bit."""
    rows = np.asarray(rows, dtype=float)
    order = np.asarray(order)
    batch = rows.shape[:-2]
    if 0 in batch:
        return np.zeros((*batch, 6, 6)), 6 - order
    a = np.swapaxes(rows.reshape(-1, 6, 6), -1, -2).copy()  # a's columns are the frame's rows
    n = a.shape[0]
    v = np.zeros((n, 6, 6))  # v[:, j, j:] the j-th reflector (v[:, j, j] = 1)
    v[:, np.arange(6), np.arange(6)] = 1.0
    tau = np.zeros((n, 6))
    with np.errstate(all="ignore"):  # poses whose column is already reduced are not updated
        for j in range(6):
            alpha = a[:, j, j]
            below = a[:, j + 1 :, j]
            total = _dot_in_order(below, below) if j < 5 else np.zeros(n)
            reflect = total != 0.0
            every = bool(reflect.all())  # the usual case: no pose to leave as it is
            beta = -np.copysign(np.sqrt(alpha * alpha + total), alpha)
            tau[:, j] = (beta - alpha) / beta if every else np.where(reflect, (beta - alpha) / beta, 0.0)
            reflector = below * (1.0 / (alpha - beta))[:, None]
            v[:, j, j + 1 :] = reflector if every else np.where(reflect[:, None], reflector, 0.0)
            if j == 5 or not reflect.any():
                continue
            block = a[:, j:, j + 1 :]
            dot = _dot_in_order(np.swapaxes(block, -1, -2), v[:, j, None, j:]) * tau[:, j, None]
            moved = block - dot[:, None, :] * v[:, j, j:, None]
            a[:, j:, j + 1 :] = moved if every else np.where(reflect[:, None, None], moved, block)
        y = np.broadcast_to(np.eye(6), (n, 6, 6)).copy()  # y[:, c] becomes column c of H_0 H_1 … H_5
        for j in range(5, -1, -1):
            reflect = tau[:, j] != 0.0
            if not reflect.any():
                continue
            dot = _dot_in_order(y[:, :, j:], v[:, j, None, j:]) * tau[:, j, None]
            moved = y[:, :, j:] - dot[:, :, None] * v[:, j, None, j:]
            y[:, :, j:] = moved if reflect.all() else np.where(reflect[:, None, None], moved, y[:, :, j:])
    flat_order = np.broadcast_to(order, batch).reshape(-1)
    index = flat_order[:, None] + np.arange(6)  # row k of the complement is column order + k
    out = np.where((index < 6)[..., None], y[np.arange(n)[:, None], np.minimum(index, 5)], 0.0)
    return (swapped(out) if swap else out).reshape(*batch, 6, 6), 6 - order


def reciprocal(rows: Array, order: Array) -> tuple[Array, Array]:
    """The frame of the reciprocal system: ``SWAP`` applied to the complement.

    Examples
    --------
    >>> line = np.zeros((6, 6)); line[0, 2] = 1.0           # the z axis through the reference point
    >>> rows, order = reciprocal(line, np.array(1))
    >>> int(order), bool(np.abs(rows[:5] @ SWAP @ line[0]).max() < 1e-15)
    (5, True)
    """
    kernels = _numba_kernels(_size(np.shape(rows)[:-2]))
    return (_complement_numpy if kernels is None else _complement_numba)(rows, order, swap=True)


def _centres(rows: Array) -> tuple[Array, Array, Array, Array]:
    """:func:`screwkit.core._frames_numba._centre` over a batch of three axes ``rows (n, 3, 6)``, in its
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
    :func:`screwkit.core._frames_numba.rod_into` (which the compiled programs run), operation for
    operation, so the two agree bit for bit.

    Each centre is the least-squares point of its axes, ``N⁻¹ Σ f`` with ``N = Σ (I − û ûᵀ)`` and
    ``f = u × m / |u|²`` the feet (by the adjugate of ``N``).

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


#: A closed-form rank decision (:func:`extend`, :func:`contract`) is taken only where its measure lies
#: outside ``[rtol·top / CLOSED_FORM_MARGIN, rtol·top · CLOSED_FORM_MARGIN]`` (``top`` the span
#: rule's largest generator norm): there the rule cannot decide otherwise; within that band (and at
#: a NaN) the caller runs the generic span and complement. (Also the compiled kernels' constant.)
CLOSED_FORM_MARGIN = 100.0


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
    (:data:`CLOSED_FORM_MARGIN`). Returns ``(rows, order, decided)``; where ``decided`` is False the
    caller spans (the rule decides). The numpy path of :func:`screwkit.core._frames_numba.extend_into`,
    operation for operation.

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
    clearly below (:data:`CLOSED_FORM_MARGIN`). Returns ``(rows, order, decided)``; where ``decided``
    is False the caller takes the reciprocal, spans and takes the reciprocal again (the rule
    decides). The numpy path of :func:`screwkit.core._frames_numba.contract_into`, operation for
    operation.

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
    formulas and when they apply: :func:`screwkit.core._frames_numba.parallelogram_into`, whose
    operations this numpy path does in its order (the two agree bit for bit).

    Paper 002 §4.1 spans the wrenches by ``τ̂01 = (s_mp; r_p × s_mp)`` and ``τ̂∞1 = (0; s_mp × s_mn)``
    and the twists by ``ε̂01 = (s_mp; r_p × s_mp)``, ``ε̂02 = (s_mn; r_n × s_mn)``, ``ε̂∞1 = (0; n)``,
    ``ε̂∞2 = (0; s_mp × n)``: the same two systems (``tests/test_frames.py`` checks them by rank).

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


def residual(vectors: Array, rows: Array) -> Array:
    """``vectors (..., k, 6)`` minus their projections on a frame's rows (re-orthogonalised once).

    Examples
    --------
    >>> residual(np.array([[1.0, 1.0, 0, 0, 0, 0]]), np.eye(6)[:1])
    array([[0., 1., 0., 0., 0., 0.]])
    """
    kernels = _numba_kernels(_size(np.broadcast_shapes(np.shape(vectors)[:-2], np.shape(rows)[:-2])))
    return (_residual_numpy if kernels is None else _residual_numba)(vectors, rows)


def _residual_numba(vectors: Array, rows: Array) -> Array:
    """:func:`residual` by the compiled per-pose loop."""
    vectors, rows = np.asarray(vectors, dtype=float), np.asarray(rows, dtype=float)
    batch = np.broadcast_shapes(vectors.shape[:-2], rows.shape[:-2])
    k, m = vectors.shape[-2], rows.shape[-2]
    if 0 in batch or k == 0:
        return np.zeros((*batch, k, 6))
    flat_vectors = np.ascontiguousarray(np.broadcast_to(vectors, (*batch, k, 6)).reshape(-1, k, 6))
    flat_rows = np.ascontiguousarray(np.broadcast_to(rows, (*batch, m, 6)).reshape(-1, 1, m, 6))
    out = _import_kernels().residual(flat_vectors, flat_rows, np.zeros(k, dtype=np.int64))
    return out.reshape(*batch, k, 6)


def residuals_against(vectors: Array, frames: Array, which: Array) -> Array:
    """``vectors (..., k, 6)`` each minus its projections on one of ``frames (..., f, 6, 6)``
    (vector ``j`` on frame ``which[j]``; rows orthonormal, zero beyond their order), twice: what
    :func:`residual` does vector by vector, in one call over strided frames (a program's block).

    Examples
    --------
    >>> frames = np.zeros((2, 6, 6)); frames[0, 0, 0] = frames[1, 0, 1] = 1.0   # e_1 and e_2, order 1
    >>> residuals_against(np.array([[1.0, 1, 0, 0, 0, 0]] * 2), frames, np.array([0, 1]))
    array([[0., 1., 0., 0., 0., 0.],
           [1., 0., 0., 0., 0., 0.]])
    """
    batch, which = vectors.shape[:-2], np.asarray(which, dtype=np.int64)
    if _numba_kernels(_size(batch)) is not None and 0 not in batch:
        flat = np.reshape(vectors, (-1, *vectors.shape[-2:]))
        out = _import_kernels().residual(flat, np.reshape(frames, (-1, *frames.shape[-3:])), which)
        return out.reshape(vectors.shape)
    out = np.empty(vectors.shape)
    for frame in dict.fromkeys(which.tolist()):
        chosen = np.flatnonzero(which == frame)
        out[..., chosen, :] = _residual_numpy(vectors[..., chosen, :], frames[..., frame, :, :])
    return out


def _residual_numpy(vectors: Array, rows: Array) -> Array:
    """:func:`residual` vectorized over the batch: :func:`screwkit.core._frames_numba.residual`'s
    operations in its order, so the two paths agree bit for bit."""
    vectors, rows = np.asarray(vectors, dtype=float), np.asarray(rows, dtype=float)
    batch = np.broadcast_shapes(vectors.shape[:-2], rows.shape[:-2])
    k, m = vectors.shape[-2], rows.shape[-2]
    out = np.array(np.broadcast_to(vectors, (*batch, k, 6)))
    rows = np.broadcast_to(rows, (*batch, m, 6))
    for _ in range(2):
        coefficients = _dot_in_order(out[..., :, None, :], rows[..., None, :, :])  # (..., k, m)
        for i in range(m):
            out = out - coefficients[..., i, None] * rows[..., None, i, :]
    return out


def limb_systems(
    locked: Array,
    locked_order: Array,
    passive: Array,
    actuated: Array,
    rtol: float,
    *,
    free_rows: bool = True,
) -> tuple[Array, Array, Array | None, Array, Array]:
    """The limbs' own systems from their locked ones (batched over ``(..., l)`` limbs): with ``t``
    a limb's actuated twist ``(..., l, 6)`` and ``locked`` ``(..., l, 6, 6)`` (order
    ``locked_order``) the twists of the limb with its actuator locked,

    * ``t⊥``, ``t`` less its projection on the locked rows (re-orthogonalised once, as
      :func:`residual`);
    * serial: ``|t⊥| ≤ rtol`` (the actuated joint adds no freedom: a serial singularity);
    * the limb's free twists: the locked frame with ``t⊥ / |t⊥|`` as one more row (unchanged where
      serial);
    * the direction of the actuation wrench: ``SWAP t⊥`` projected on the ``passive`` rows
      ``(..., l, 6, 6)`` (orthonormal, zero beyond their order), unit (zero if the projection is):
      a wrench reciprocal to every passive joint and not to ``t`` (paper 002 §3 and §4.3: the
      limb's actuation wrench, the actuator locked), clean where ``t⊥`` is round-off.

    Sums run left to right from ``0.0`` (:func:`sum_in_order`), as the compiled kernel
    (:func:`screwkit.core._frames_numba.limb_systems`): the two paths agree bit for bit.

    Returns
    -------
    perpendicular (..., l, 6), serial (..., l), free rows (..., l, 6, 6) (None unless
    ``free_rows``), free order (..., l), direction (..., l, 6)

    Examples
    --------
    >>> locked, passive = np.zeros((1, 6, 6)), np.eye(6)[None]
    >>> locked[0, 0, 0] = 1.0  # one locked row, e_1: a frame of order 1
    >>> out = limb_systems(locked, np.array([1]), passive, np.array([[1.0, 1, 0, 0, 0, 0]]), 1e-9)
    >>> out[0][0], bool(out[1][0]), out[2][0, 1], int(out[3][0])
    (array([0., 1., 0., 0., 0., 0.]), False, array([0., 1., 0., 0., 0., 0.]), 2)
    """
    batch = actuated.shape[:-1]
    kernels = _numba_kernels(_size(batch[:-1]))
    if kernels is not None and 0 not in batch:
        # strided views as they are (the program's block): no copies, the same arithmetic
        flat = [np.reshape(np.asarray(a, dtype=float), (-1, *a.shape[len(batch) - 1 :]))
                for a in (locked, passive, actuated)]
        order = np.ascontiguousarray(np.reshape(locked_order, (-1, batch[-1])), dtype=np.int64)
        out = kernels.limb_systems(flat[0], order, flat[1], flat[2], float(rtol), free_rows)
        perpendicular, serial, rows, free_order, direction = (
            a.reshape(*batch, *a.shape[2:]) if a.shape[0] else None for a in out
        )
        return perpendicular, serial, rows, free_order, direction  # type: ignore[return-value]
    out = _limb_systems_numpy(locked, locked_order, passive, actuated, rtol)
    return out if free_rows else (out[0], out[1], None, out[3], out[4])


def _limb_systems_numpy(
    locked: Array, locked_order: Array, passive: Array, actuated: Array, rtol: float
) -> tuple[Array, Array, Array, Array, Array]:
    """:func:`limb_systems` vectorized with numpy, the kernel's operations in its order."""
    perpendicular = _residual_numpy(actuated[..., None, :], locked)[..., 0, :]
    size = np.sqrt(_dot_in_order(perpendicular, perpendicular))
    serial = size <= rtol
    rows, order = np.array(locked, dtype=float), np.asarray(locked_order)
    unit = perpendicular / np.where(size > 0, size, 1.0)[..., None]
    slot = np.minimum(order, 5)[..., None, None]
    kept = np.take_along_axis(rows, slot, -2)
    np.put_along_axis(rows, slot, np.where(serial[..., None, None], kept, unit[..., None, :]), -2)
    return perpendicular, serial, rows, order + ~serial, actuation_directions(passive, perpendicular)


def not_lines(rows: Array, line_rtol: float) -> Array:
    """Which wrench rows ``(..., 6)`` are not lines: ``|s·m| > line_rtol · |s| · |w|``, i.e. the pitch
    ``h = s·m / s·s`` (the screw's pitch, module conventions; :func:`screwkit.algebra.screw.pitch`) has
    ``|h| |s| > line_rtol |w|``, component by component (the compiled kernels' operations).

    Examples
    --------
    >>> not_lines(np.array([[0, 0, 1.0, 1.0, 0, 0], [0, 0, 1.0, 0, 0, 1.0]]), 1e-6)
    array([False,  True])
    """
    w = [rows[..., s] for s in range(6)]
    forces = w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
    pitch = w[0] * w[3] + w[1] * w[4] + w[2] * w[5]
    norm = np.sqrt(forces + (w[3] * w[3] + w[4] * w[4] + w[5] * w[5]))
    return np.abs(pitch) > line_rtol * np.maximum(np.sqrt(forces), 1e-300) * norm


def limb_wrenches(
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
    """The limbs' actuation wrenches from their locked and passive frames (the analysis core's
    step after the program): :func:`limb_systems` (without the free rows), whether each actuation
    direction is a line (:func:`not_lines`), the unit wrenches along the directions with their
    transmission indices (:func:`transmissions`) and the ``coupled`` limbs' wrenches less their
    part in their leg's frame (``legs (..., L, 6, 6)``, limb ``coupled[j]`` in leg ``leg_of[j]``;
    :func:`residuals_against`). Returns ``(serial, free order, direction, wrench, transmissions,
    residuals, not_line)``. On the numba path one compiled pass
    (:func:`screwkit.core._frames_numba.limb_wrenches`): the same operations, bit for bit.

    Examples
    --------
    >>> locked, passive = np.zeros((1, 1, 6, 6)), np.zeros((1, 1, 6, 6))
    >>> locked[0, 0, 0, 1] = passive[0, 0, 0, 0] = 1.0  # locked: e_2; passive: the force along x
    >>> out = limb_wrenches(locked, np.array([[1]]), passive, np.array([[[0, 0, 0, 1.0, 0, 0]]]),
    ...                     np.zeros((1, 0, 6, 6)), np.array([], int), np.array([], int), 1e-9, 1e-6)
    >>> bool(out[0][0, 0]), out[3][0, 0], float(out[4][0, 0])  # not serial, a unit force along x
    (False, array([1., 0., 0., 0., 0., 0.]), 1.0)
    """
    batch = actuated.shape[:-1]
    coupled, leg_of = np.asarray(coupled, dtype=np.int64), np.asarray(leg_of, dtype=np.int64)
    kernels = _numba_kernels(_size(batch[:-1]))
    if kernels is not None and 0 not in batch:
        arrays, size = (locked, passive, actuated, legs), _size(batch[:-1])
        flat = [np.reshape(np.asarray(a, dtype=float), (size, *a.shape[len(batch) - 1 :])) for a in arrays]
        order = np.ascontiguousarray(np.reshape(locked_order, (-1, batch[-1])), dtype=np.int64)
        out = kernels.limb_wrenches(flat[0], order, flat[1], flat[2], flat[3], coupled, leg_of, float(rtol),
                                    float(line_rtol))
        return tuple(a.reshape((*batch[:-1], *a.shape[1:])) for a in out)
    systems = limb_systems(locked, locked_order, passive, actuated, rtol, free_rows=False)
    serial, free_order, direction = systems[1], systems[3], systems[4]
    wrench, index = transmissions(direction, actuated, rtol)
    residuals = residuals_against(wrench[..., coupled, :], legs, leg_of)
    return serial, free_order, direction, wrench, index, residuals, not_lines(direction, line_rtol)


def actuation_directions(passive: Array, perpendicular: Array) -> Array:
    """``SWAP t⊥`` projected on the ``passive`` rows ``(..., 6, 6)`` (orthonormal, zero beyond
    their order), unit (zero where the projection is): the direction of a limb's actuation wrench
    (:func:`limb_systems`; ``t⊥`` ``(..., 6)``). ``SWAP t⊥`` lies in the passive system; projecting
    it there keeps a clean passive wrench even when ``t⊥`` is round-off (a serial singularity), so
    ``w ∘ t`` is then round-off too. Sums left to right from ``0.0`` (the compiled kernel's order).

    Examples
    --------
    >>> actuation_directions(np.eye(6)[:1], np.array([0, 0, 0, 2.0, 0, 0]))
    array([1., 0., 0., 0., 0., 0.])
    """
    coefficients = _dot_in_order(passive, swapped(perpendicular)[..., None, :])  # (..., 6)
    direction = sum_in_order(np.swapaxes(coefficients[..., :, None] * passive, -1, -2))
    size = np.sqrt(_dot_in_order(direction, direction))
    return direction / np.where(size > 0, size, 1.0)[..., None]


def unit_rows(rows: Array) -> Array:
    """``rows (..., 6)`` over their norms (zero rows kept), the norm summed left to right from
    ``0.0`` (:func:`sum_in_order`; the compiled kernels' order).

    Examples
    --------
    >>> unit_rows(np.array([[3.0, 4, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0]]))[:, :2]
    array([[0.6, 0.8],
           [0. , 0. ]])
    """
    size = np.sqrt(_dot_in_order(rows, rows))
    return rows / np.where(size > 0, size, 1.0)[..., None]


def scaled_magnitudes(rows: Array, rtol: float) -> Array:
    """``N(s)`` of scaled rows ``(..., 6)`` (the length is then 1): ``|s|`` where the direction is
    more than ``rtol`` of the moment, else ``|s0|`` (a couple or translation); the norms summed in
    order (:func:`sum_in_order`). :func:`screwkit.core.wrenches.normalized_reciprocal_product`'s ``N``.

    Examples
    --------
    >>> scaled_magnitudes(np.array([[0, 0, 0, 3.0, 4, 0], [1.0, 0, 0, 5, 0, 0]]), 1e-9)
    array([5., 1.])
    """
    directions = np.sqrt(_dot_in_order(rows[..., :3], rows[..., :3]))
    moments = np.sqrt(_dot_in_order(rows[..., 3:], rows[..., 3:]))
    return np.where(directions > rtol * moments, directions, moments)


def transmissions(raw: Array, twists: Array, rtol: float) -> tuple[Array, Array]:
    """Unit wrenches and their transmission indices: ``raw (..., l, 6)`` wrench rows made unit
    (:func:`unit_rows`) and ``|w ∘ t| / (N(w) N(t))`` with the ``twists (..., l, 6)``
    (:func:`scaled_magnitudes`; zero where a magnitude is): the transmission index, paper 004 §1's
    virtual coefficient, in scaled coordinates (``L = 1`` in
    :func:`screwkit.core.wrenches.normalized_reciprocal_product`). Compiled per pose for large batches
    (:func:`screwkit.core._frames_numba.transmissions`), the same operations in the same order.

    Examples
    --------
    >>> force, translation = np.array([[2.0, 0, 0, 0, 0, 0]]), np.array([[0, 0, 0, 1.0, 0, 0]])
    >>> wrench, index = transmissions(force, translation, 1e-9)
    >>> wrench[0, 0], index[0]
    (np.float64(1.0), np.float64(1.0))
    """
    batch = raw.shape[:-1]
    kernels = _numba_kernels(_size(batch[:-1]))
    if kernels is not None and 0 not in batch:
        flat = [np.ascontiguousarray(np.reshape(a, (-1, batch[-1], 6)), dtype=float) for a in (raw, twists)]
        wrench, index = kernels.transmissions(flat[0], flat[1], float(rtol))
        return wrench.reshape(*batch, 6), index.reshape(batch)
    return transmissions_numpy(unit_rows(raw), twists, rtol)


def transmissions_numpy(wrench: Array, twists: Array, rtol: float) -> tuple[Array, Array]:
    """:func:`transmissions` of unit ``wrench`` rows with numpy (the kernel's operations)."""
    return wrench, transmission_index(wrench, twists, np.abs(_dot_in_order(wrench, swapped(twists))), rtol)


def transmission_index(wrench: Array, twists: Array, product: Array, rtol: float) -> Array:
    """``product / (N(w) N(t))`` (:func:`scaled_magnitudes`), zero where a magnitude is: the
    transmission index given the reciprocal product ``|w ∘ t|`` (or a load standing for it)."""
    denominator = scaled_magnitudes(wrench, rtol) * scaled_magnitudes(twists, rtol)
    return np.where(denominator > 0, product / np.where(denominator > 0, denominator, 1.0), 0.0)


def triangular(rows: Array) -> Array:
    """Rows ``(..., k, 6)`` → the upper triangular factor ``R (..., 6, 6)`` of their Householder QR
    from the left (``rows = Q R``, Golub & Van Loan §5.2.1; fewer than six rows padded with zero
    rows first): six rows with the same singular values, a cheaper input for
    :func:`singular_ratio`, stored in :func:`packed` form. The numpy path does
    :func:`screwkit.core._frames_numba.triangular`'s operations in its order (bit for bit).

    Examples
    --------
    >>> rows = np.vstack([np.eye(6), 3 * np.eye(6)[:1]])
    >>> values = [np.linalg.svd(r, compute_uv=False) for r in (triangular(rows), rows)]
    >>> triangular(rows).shape, bool(np.allclose(*values))
    ((6, 6), True)
    """
    rows = np.asarray(rows, dtype=float)
    batch, k = rows.shape[:-2], rows.shape[-2]
    if k < 6:
        rows, k = np.concatenate([rows, np.zeros((*batch, 6 - k, 6))], axis=-2), 6
    if 0 in batch:
        return np.zeros((*batch, 6, 6))
    if _numba_kernels(_size(batch)) is not None:
        flat = np.ascontiguousarray(rows.reshape(-1, k, 6))
        return _import_kernels().triangular(flat).reshape(*batch, 6, 6)
    a = rows.reshape(-1, k, 6).copy()
    with np.errstate(all="ignore"):  # poses whose column is already zero compute values not kept
        for j in range(6):
            total = _dot_in_order(a[:, j:, j], a[:, j:, j])
            act = total != 0.0
            alpha = -np.copysign(np.sqrt(total), a[:, j, j])
            a[:, j, j] = np.where(act, a[:, j, j] - alpha, a[:, j, j])
            v = a[:, j:, j]
            vv = np.where(act, _dot_in_order(v, v), 1.0)
            for c in range(j + 1, 6):
                dot = 2.0 * _dot_in_order(v, a[:, j:, c]) / vv
                a[:, j:, c] = np.where(act[:, None], a[:, j:, c] - dot[:, None] * v, a[:, j:, c])
            a[:, j, j] = np.where(act, alpha, a[:, j, j])
            a[:, j + 1 :, j] = np.where(act[:, None], 0.0, a[:, j + 1 :, j])
    return a[:, :6].reshape(*batch, 6, 6)


#: A user-frame wrench row is drawn as a unit couple where its force is at most this fraction of its
#: moment over the length (:func:`unit_size`).
COUPLE_RTOL = B.DEFAULT_RTOL


def unit_size(rows: Array, length: Array) -> Array:
    """``(..., k, 1)``: what divides user-frame wrench rows ``(..., k, 6)`` into a unit force (or a
    unit couple where the force is negligible, :data:`COUPLE_RTOL`); norms summed left to right.

    Examples
    --------
    >>> unit_size(np.array([[0, 0, 2.0, 1, 0, 0], [0, 0, 0, 0, 3.0, 0]]), np.array(1.0))[:, 0]
    array([2., 3.])
    """
    forces = np.sqrt(rows[..., 0] * rows[..., 0] + rows[..., 1] * rows[..., 1] + rows[..., 2] * rows[..., 2])
    moments = np.sqrt(rows[..., 3] * rows[..., 3] + rows[..., 4] * rows[..., 4] + rows[..., 5] * rows[..., 5])
    is_couple = forces <= COUPLE_RTOL * moments / length[..., None]
    size = np.where(is_couple, moments, forces)
    return np.where(size > 0, size, 1.0)[..., None]


def closing(
    constraint: Array,
    wrenches: Array,
    legs: Array,
    apart: Array,
    serial: Array,
    centre: Array,
    length: Array,
    rtol: float,
) -> tuple[Array, Array, Array, Array, Array]:
    """The analysis core's last per-pose steps (:func:`screwkit.core.wrenches.analyze_table`):

    * the global frame, :func:`span` of the ``constraint (..., 6, 6)`` rows and the limbs' scaled
      wrench rows ``wrenches (..., l, 6)`` (paper 002 Eq. 4);
    * the closeness factors, :func:`packed` :func:`triangular` of the legs' wrench frames
      ``legs (..., L, 6, 6)`` stacked, and of that triangle with the ``apart (..., l, 6)`` rows;
    * the actuation rows: the wrench rows in the user's frame (:func:`from_scaled` about
      ``centre (..., 3)`` and ``length (...)``) over :func:`unit_size`, zero where ``serial``.

    Returns ``(global rows, global order, constraint factor, actuation factor, actuation rows)``.
    On the numba path one compiled pass (:func:`screwkit.core._frames_numba.closing`), these
    operations in this order (bit for bit).

    Examples
    --------
    >>> constraint, legs = np.zeros((6, 6)), np.zeros((1, 6, 6))
    >>> constraint[0, 3] = legs[0, 0, 3] = 1.0                    # a couple about x
    >>> line = np.array([[0, 0, 1.0, 0, 0, 0]])                    # a force along z, through the centre
    >>> rows, order, _, _, actuation = closing(constraint, line, legs, line, np.array([False]),
    ...                                        np.array([0, 0, 1.0]), np.array(2.0), 1e-9)
    >>> int(order), actuation                                     # moved to the user's frame: z through it
    (2, array([[0., 0., 1., 0., 0., 0.]]))
    """
    batch = wrenches.shape[:-2]
    if _numba_kernels(_size(batch)) is not None and 0 not in batch:
        arrays = (constraint, wrenches, legs, apart, serial)
        flat = [np.reshape(np.asarray(a), (_size(batch), *np.shape(a)[len(batch) :])) for a in arrays]
        centres = np.ascontiguousarray(np.broadcast_to(centre, (*batch, 3)).reshape(-1, 3), dtype=float)
        lengths = np.ascontiguousarray(np.broadcast_to(length, batch).reshape(-1), dtype=float)
        kernels = _import_kernels()
        out = kernels.closing(*flat[:4], np.ascontiguousarray(flat[4]), centres, lengths, float(rtol))
        return tuple(a.reshape((*batch, *a.shape[1:])) for a in out)
    rows, order = span(np.concatenate([constraint, wrenches], axis=-2), rtol)
    triangle = triangular(np.reshape(legs, (*batch, -1, 6)))
    actuation_factor = packed(triangular(np.concatenate([triangle, apart], axis=-2)))
    user = from_scaled(wrenches, np.asarray(centre, dtype=float), np.asarray(length, dtype=float))
    actuation = np.where(serial[..., None], 0.0, user / unit_size(user, np.asarray(length, dtype=float)))
    return rows, order, packed(triangle), actuation_factor, actuation


#: The entries on and above the diagonal of a 6×6 matrix, row by row (:func:`packed`).
UPPER = np.triu_indices(6)


def packed(triangle: Array) -> Array:
    """An upper triangular ``(..., 6, 6)`` (:func:`triangular`) as its 21 entries ``(..., 21)`` on
    and above the diagonal (row by row): the closeness inputs a batch keeps in 168 bytes a pose.

    Examples
    --------
    >>> triangle = np.triu(np.arange(36.0).reshape(6, 6))
    >>> packed(triangle).shape, bool((unpacked(packed(triangle)) == triangle).all())
    ((21,), True)
    """
    return triangle[..., UPPER[0], UPPER[1]]


def unpacked(values: Array) -> Array:
    """:func:`packed`'s inverse: ``(..., 21)`` → the upper triangular ``(..., 6, 6)`` (exact zeros
    below the diagonal)."""
    out = np.zeros((*values.shape[:-1], 6, 6))
    out[..., UPPER[0], UPPER[1]] = values
    return out


def singular_ratio(rows: Array, index: int) -> Array:
    """``σ_index / σ_1`` of rows ``(..., k, 6)`` (1 for ``index ≤ 0``, 0 when ``k < index``).

    Examples
    --------
    >>> float(singular_ratio(np.array([[1.0, 0, 0, 0, 0, 0], [0, 0.5, 0, 0, 0, 0]]), 2))
    0.5
    """
    batch = rows.shape[:-2]
    if index <= 0:
        return np.ones(batch)
    if rows.shape[-2] < index:
        return np.zeros(batch)
    values = np.linalg.svd(rows, compute_uv=False)
    top = values[..., 0]
    return np.where(top > 0, values[..., index - 1] / np.where(top > 0, top, 1.0), 0.0)
