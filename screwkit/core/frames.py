"""Batched orthonormal frames of screw systems: the one rank rule under every pose, in scaled coordinates.

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

**Closed forms** of some systems (a rod, a 4S parallelogram, one joint screw more or less) replace a
span and a complement where they apply (:mod:`screwkit.core._closed_forms`); residuals against a
frame are :mod:`screwkit.core._residuals`; the limbs' own systems
and actuation wrenches (:mod:`screwkit.core._limbs`) and the core's closing steps
(:mod:`screwkit.core._closing`) build on the rule.

**Two implementations, one rule.** :func:`span`, :func:`complement`, :func:`reciprocal`,
:func:`~screwkit.algebra.reference_frame.unit_scaled` and the kernels of those modules (and
:mod:`screwkit.core._residuals`) have a
numpy path (vectorized over the batch) and, when numba is installed (the ``fast`` extra), compiled per-pose
loops (:mod:`screwkit.core._frames_numba` and its siblings ``_closed_forms_numba``,
``_limbs_numba``, ``_closing_numba``, ``_program_numba``). The numpy path does the compiled loops'
floating-point operations in their order (sums left to right, no BLAS call, no library QR), so the
two agree bit for bit, and a pose's answer never depends on the batch it is in: single-pose and
batched answers are bit-identical whichever path runs. The analysis core strings spans, reciprocals
and rods into one flat *program* per mechanism (:mod:`screwkit.core._program`): on the numba path
one compiled call runs it pose by pose (:func:`screwkit.core._program_numba.run_program`, the same
per-pose loops), on the numpy path its ops run one by one over the batch. numba is imported on
the first call over :data:`COMPILED_MIN_BATCH` frames or more (:func:`compiled_kernels`), so a
single-pose analysis never pays for its import; its compiled code is cached on disk. One decision
serves every compiled module of the core (:func:`compiled_twin`). The environment variable
``SCREWKIT_NUMBA``, read once when this module is imported, forces the choice: ``0`` (or ``false``,
``no``, ``off``) the numpy path, anything else the default (numba if it imports).

Examples
--------
>>> rows, order = span(np.array([[[1.0, 0, 0, 0, 0, 0], [2.0, 0, 0, 0, 0, 0]]]), 1e-9)
>>> order
array([1])
>>> reciprocal(rows, order)[1]
array([5])
"""

from __future__ import annotations

import importlib
import math
from types import ModuleType

import numpy as np

from ..algebra import backend as B
from ..algebra.compiled import COMPILED_MIN_BATCH, compiled_kernels, sum_in_order
from ..algebra.ranks import SWAP

__all__ = [
    "SWAP",
    "backend",
    "compiled_twin",
    "complement",
    "empty",
    "from_scaled",
    "reciprocal",
    "span",
    "swapped",
    "to_scaled",
]

Array = np.ndarray


def _numba_kernels(size: int) -> ModuleType | None:
    """The rank kernels (:mod:`screwkit.core._frames_numba`) for ``size`` frames, or None for numpy."""
    return compiled_kernels("screwkit.core._frames_numba", size)


def _import_kernels() -> ModuleType:
    """The numba kernels, whatever this process's choice (the numba path; tests call it directly)."""
    from . import _frames_numba as _frames_numba

    return _frames_numba


def compiled_twin(module: str, size: int) -> ModuleType | None:
    """The numba twin of one of the core's kernel modules for a call over ``size`` batch elements.

    One decision for every compiled module of the core: that of the rank kernels
    (:mod:`screwkit.core._frames_numba`, :func:`compiled_kernels`), so a process runs them all
    compiled or all with numpy.

    Parameters
    ----------
    module : str
        The twin's name in :mod:`screwkit.core` (``"_limbs_numba"``, ``"_closing_numba"``,
        ``"_program_numba"``).
    size : int
        The number of batch elements of the call.

    Returns
    -------
    module or None
        The compiled module, None for the numpy path.

    Examples
    --------
    >>> compiled_twin("_limbs_numba", 1) is None or backend() == "numba"
    True
    """
    if _numba_kernels(size) is None:
        return None
    return importlib.import_module(f"screwkit.core.{module}")


def _size(shape: tuple[int, ...]) -> int:
    """The number of frames in a batch shape."""
    return math.prod(shape)


def backend() -> str:
    """``"numba"`` or ``"numpy"``: the implementation of batches of :data:`COMPILED_MIN_BATCH`
    frames or more in this process (smaller ones run numpy until numba is loaded).

    Returns
    -------
    str
        ``"numba"`` or ``"numpy"``.

    Examples
    --------
    >>> backend() in {"numba", "numpy"}
    True
    """
    return "numpy" if _numba_kernels(COMPILED_MIN_BATCH) is None else "numba"


def to_scaled(screws: Array, centre: Array, length: Array) -> Array:
    """Screws ``(..., k, 6)`` about ``centre`` ``(..., 3)`` with moments over ``length`` ``(...)``.

    Parameters
    ----------
    screws : numpy.ndarray, shape (..., k, 6)
        User-frame screws.
    centre : numpy.ndarray, shape (..., 3)
        The reference point.
    length : numpy.ndarray, shape (...)
        The characteristic length.

    Returns
    -------
    numpy.ndarray, shape (..., k, 6)
        The screws in scaled coordinates.

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

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., k, 6)
        Scaled rows.
    centre : numpy.ndarray, shape (..., 3)
        The reference point.
    length : numpy.ndarray, shape (...)
        The characteristic length.

    Returns
    -------
    numpy.ndarray, shape (..., k, 6)
        The rows in the user's frame and unit.

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

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6)

    Returns
    -------
    numpy.ndarray, shape (..., 6)
        ``(rows[..., 3:], rows[..., :3])``.

    Examples
    --------
    >>> swapped(np.arange(6.0))
    array([3., 4., 5., 0., 1., 2.])
    """
    return np.concatenate([rows[..., 3:], rows[..., :3]], axis=-1)


def empty(batch: tuple[int, ...]) -> tuple[Array, Array]:
    """The frame of the 0-system over a batch.

    Parameters
    ----------
    batch : tuple of int
        The batch shape.

    Returns
    -------
    rows : numpy.ndarray, shape ``batch + (6, 6)``
        Zeros.
    order : numpy.ndarray of int, shape ``batch``
        Zeros.

    Examples
    --------
    >>> empty((2,))[1]
    array([0, 0])
    """
    return np.zeros((*batch, 6, 6)), np.zeros(batch, dtype=int)


def span(generators: Array, rtol: float) -> tuple[Array, Array]:
    """The frame of the system spanned by ``generators`` ``(..., k, 6)`` (the module's rank rule).

    Parameters
    ----------
    generators : array_like, shape (..., k, 6)
        Scaled generators.
    rtol : float
        The rule's relative threshold.

    Returns
    -------
    rows : numpy.ndarray, shape (..., 6, 6)
        An orthonormal basis in the first ``order`` rows, zero rows after.
    order : numpy.ndarray of int, shape (...)

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

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6, 6)
        A frame's rows.
    order : numpy.ndarray of int, shape (...)
        Its order.

    Returns
    -------
    rows : numpy.ndarray, shape (..., 6, 6)
        The complement's frame rows.
    order : numpy.ndarray of int, shape (...)
        ``6 − order``.

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

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6, 6)
        A frame's rows (scaled).
    order : numpy.ndarray of int, shape (...)
        Its order.

    Returns
    -------
    rows : numpy.ndarray, shape (..., 6, 6)
        The reciprocal system's frame rows.
    order : numpy.ndarray of int, shape (...)
        ``6 − order``.

    Examples
    --------
    >>> line = np.zeros((6, 6)); line[0, 2] = 1.0           # the z axis through the reference point
    >>> rows, order = reciprocal(line, np.array(1))
    >>> int(order), bool(np.abs(rows[:5] @ SWAP @ line[0]).max() < 1e-15)
    (5, True)
    """
    kernels = _numba_kernels(_size(np.shape(rows)[:-2]))
    return (_complement_numpy if kernels is None else _complement_numba)(rows, order, swap=True)
