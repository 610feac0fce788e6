"""The core's closing steps over a batch: global frame, closeness factors, actuation rows (private).

The global wrench system (paper 002 Eq. 4) is the span of the constraint system and the limbs'
actuation wrenches; the closeness measures are singular-value ratios of the legs' constraint
wrenches stacked (with the actuation wrenches), kept as packed triangular factors
(:func:`triangular`, :func:`packed`: six rows with the same singular values); the actuation
wrenches go back to the user's frame as unit forces or couples (:func:`unit_size`). Each numpy
path does the operations of its compiled twin (:mod:`screwkit.core._closing_numba`) in their
order: the two agree bit for bit.

Examples
--------
>>> float(singular_ratio(np.array([[2.0, 0, 0, 0, 0, 0], [0, 1.0, 0, 0, 0, 0]]), 2))
0.5
"""

from __future__ import annotations

import numpy as np

from ._kernel_constants import COUPLE_RTOL
from .frames import _dot_in_order, _size, compiled_twin, from_scaled, span

__all__ = [
    "UPPER",
    "closing",
    "packed",
    "singular_ratio",
    "triangular",
    "unit_size",
    "unpacked",
]

Array = np.ndarray


def triangular(rows: Array) -> Array:
    """Rows ``(..., k, 6)`` → the upper triangular factor ``R (..., 6, 6)`` of their Householder QR
    from the left (``rows = Q R``, Golub & Van Loan §5.2.1; fewer than six rows padded with zero
    rows first): six rows with the same singular values, a cheaper input for
    :func:`singular_ratio`, stored in :func:`packed` form. The numpy path does
    :func:`screwkit.core._closing_numba.triangular`'s operations in its order (bit for bit).

    Parameters
    ----------
    rows : array_like, shape (..., k, 6)

    Returns
    -------
    numpy.ndarray, shape (..., 6, 6)
        Upper triangular.

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
    kernels = compiled_twin("_closing_numba", _size(batch))
    if kernels is not None:
        flat = np.ascontiguousarray(rows.reshape(-1, k, 6))
        return kernels.triangular(flat).reshape(*batch, 6, 6)
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



def unit_size(rows: Array, length: Array) -> Array:
    """``(..., k, 1)``: what divides user-frame wrench rows ``(..., k, 6)`` into a unit force (or a
    unit couple where the force is negligible,
    :data:`~screwkit.core._kernel_constants.COUPLE_RTOL`); norms summed left to right.

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., k, 6)
        User-frame wrench rows.
    length : numpy.ndarray, shape (...)
        The characteristic length.

    Returns
    -------
    numpy.ndarray, shape (..., k, 1)
        The force's norm, the moment's for a couple; 1 for a zero row.

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
    """The analysis core's last per-pose steps (:func:`screwkit.core.wrench_systems.analyze_table`):

    * the global frame, :func:`span` of the ``constraint (..., 6, 6)`` rows and the limbs' scaled
      wrench rows ``wrenches (..., l, 6)`` (paper 002 Eq. 4);
    * the closeness factors, :func:`packed` :func:`triangular` of the legs' wrench frames
      ``legs (..., L, 6, 6)`` stacked, and of that triangle with the ``apart (..., l, 6)`` rows;
    * the actuation rows: the wrench rows in the user's frame (:func:`from_scaled` about
      ``centre (..., 3)`` and ``length (...)``) over :func:`unit_size`, zero where ``serial``.

    Returns ``(global rows, global order, constraint factor, actuation factor, actuation rows)``.
    On the numba path one compiled pass (:func:`screwkit.core._closing_numba.closing`), these
    operations in this order (bit for bit).

    Parameters
    ----------
    constraint : numpy.ndarray, shape (..., 6, 6)
        The constraint frame's rows (scaled).
    wrenches : numpy.ndarray, shape (..., l, 6)
        The limbs' scaled wrench rows (zero where serial).
    legs : numpy.ndarray, shape (..., L, 6, 6)
        The compound legs' wrench frames.
    apart : numpy.ndarray, shape (..., l, 6)
        The wrench rows apart from their legs (the actuation closeness's rows).
    serial : numpy.ndarray of bool, shape (..., l)
    centre : numpy.ndarray, shape (..., 3)
    length : numpy.ndarray, shape (...)
    rtol : float
        The rule's relative threshold.

    Returns
    -------
    global_rows : numpy.ndarray, shape (..., 6, 6)
    global_order : numpy.ndarray of int, shape (...)
    constraint_factor, actuation_factor : numpy.ndarray, shape (..., 21)
        Packed triangles.
    actuation : numpy.ndarray, shape (..., l, 6)
        The actuation rows, user frame.

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
    kernels = compiled_twin("_closing_numba", _size(batch))
    if kernels is not None and 0 not in batch:
        arrays = (constraint, wrenches, legs, apart, serial)
        flat = [np.reshape(np.asarray(a), (_size(batch), *np.shape(a)[len(batch) :])) for a in arrays]
        centres = np.ascontiguousarray(np.broadcast_to(centre, (*batch, 3)).reshape(-1, 3), dtype=float)
        lengths = np.ascontiguousarray(np.broadcast_to(length, batch).reshape(-1), dtype=float)
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

    Parameters
    ----------
    triangle : numpy.ndarray, shape (..., 6, 6)

    Returns
    -------
    numpy.ndarray, shape (..., 21)

    Examples
    --------
    >>> triangle = np.triu(np.arange(36.0).reshape(6, 6))
    >>> packed(triangle).shape, bool((unpacked(packed(triangle)) == triangle).all())
    ((21,), True)
    """
    return triangle[..., UPPER[0], UPPER[1]]


def unpacked(values: Array) -> Array:
    """:func:`packed`'s inverse: ``(..., 21)`` → the upper triangular ``(..., 6, 6)`` (exact zeros
    below the diagonal).

    Parameters
    ----------
    values : numpy.ndarray, shape (..., 21)

    Returns
    -------
    numpy.ndarray, shape (..., 6, 6)
    """
    out = np.zeros((*values.shape[:-1], 6, 6))
    out[..., UPPER[0], UPPER[1]] = values
    return out


def singular_ratio(rows: Array, index: int) -> Array:
    """``σ_index / σ_1`` of rows ``(..., k, 6)`` (1 for ``index ≤ 0``, 0 when ``k < index``).

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., k, 6)
    index : int
        Which singular value over the largest (1-based).

    Returns
    -------
    numpy.ndarray, shape (...)

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
