"""The limbs' systems, actuation wrenches and transmission indices over a batch (private).

After the frame program (:mod:`screwkit.core._program`) gives each limb's twists with its actuator
locked and its passive wrenches, these kernels find the limb's free twists, whether it is at a
serial singularity, the direction of its actuation wrench, whether that is a line, and its
transmission index (paper 002 §4.3, paper 004 §1), in scaled coordinates
(:mod:`screwkit.core.frames`). Each numpy path does the operations of its compiled twin
(:mod:`screwkit.core._limbs_numba`) in their order: the two agree bit for bit.

Examples
--------
>>> force, translation = np.array([[2.0, 0, 0, 0, 0, 0]]), np.array([[0, 0, 0, 1.0, 0, 0]])
>>> transmissions(force, translation, 1e-9)[1]
array([1.])
"""

from __future__ import annotations

import numpy as np

from ._residuals import _residual_numpy, residuals_against
from .frames import (
    _dot_in_order,
    _size,
    compiled_twin,
    sum_in_order,
    swapped,
)

__all__ = [
    "actuation_directions",
    "limb_systems",
    "limb_wrenches",
    "not_lines",
    "scaled_magnitudes",
    "transmission_index",
    "transmissions",
    "transmissions_numpy",
    "unit_rows",
]

Array = np.ndarray


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
      :func:`~screwkit.core._residuals.residual`);
    * serial: ``|t⊥| ≤ rtol`` (the actuated joint adds no freedom: a serial singularity);
    * the limb's free twists: the locked frame with ``t⊥ / |t⊥|`` as one more row (unchanged where
      serial);
    * the direction of the actuation wrench: ``SWAP t⊥`` projected on the ``passive`` rows
      ``(..., l, 6, 6)`` (orthonormal, zero beyond their order), unit (zero if the projection is):
      a wrench reciprocal to every passive joint and not to ``t`` (paper 002 §3 and §4.3: the
      limb's actuation wrench, the actuator locked), clean where ``t⊥`` is round-off.

    Sums run left to right from ``0.0`` (:func:`sum_in_order`), as the compiled kernel
    (:func:`screwkit.core._limbs_numba.limb_systems`): the two paths agree bit for bit.

    Parameters
    ----------
    locked : array_like, shape (..., l, 6, 6)
        Each limb's twists with its actuator locked (a frame).
    locked_order : array_like of int, shape (..., l)
    passive : array_like, shape (..., l, 6, 6)
        Each limb's passive wrenches (a frame).
    actuated : array_like, shape (..., l, 6)
        Each limb's actuated twist, scaled.
    rtol : float
        The rule's relative threshold.
    free_rows : bool, default True
        Whether to return the free twists' rows.

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
    kernels = compiled_twin("_limbs_numba", _size(batch[:-1]))
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

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6)
    line_rtol : float
        The relative pitch tolerance (:data:`screwkit.core.line_search.LINE_RTOL`).

    Returns
    -------
    numpy.ndarray of bool, shape (...)

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
    (:func:`screwkit.core._limbs_numba.limb_wrenches`): the same operations, bit for bit.

    Parameters
    ----------
    locked, locked_order, passive, actuated
        As in :func:`limb_systems`.
    legs : array_like, shape (..., L, 6, 6)
        The compound legs' wrench frames.
    coupled : array_like of int, shape (m,)
        The limbs with partners.
    leg_of : array_like of int, shape (m,)
        Each one's leg.
    rtol : float
        The rule's relative threshold.
    line_rtol : float
        As in :func:`not_lines`.

    Returns
    -------
    tuple of numpy.ndarray
        ``(serial (..., l), free order (..., l), direction (..., l, 6), wrench (..., l, 6),
        transmissions (..., l), residuals (..., m, 6), not_line (..., l))``.

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
    kernels = compiled_twin("_limbs_numba", _size(batch[:-1]))
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

    Parameters
    ----------
    passive : numpy.ndarray, shape (..., 6, 6)
    perpendicular : numpy.ndarray, shape (..., 6)
        ``t⊥``.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

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

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6)

    Returns
    -------
    numpy.ndarray, shape (..., 6)

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

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6)
    rtol : float

    Returns
    -------
    numpy.ndarray, shape (...)

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
    (:func:`screwkit.core._limbs_numba.transmissions`), the same operations in the same order.

    Parameters
    ----------
    raw : numpy.ndarray, shape (..., l, 6)
        Wrench rows, scaled.
    twists : numpy.ndarray, shape (..., l, 6)
        The actuated twists, scaled.
    rtol : float

    Returns
    -------
    wrench : numpy.ndarray, shape (..., l, 6)
        Unit rows.
    index : numpy.ndarray, shape (..., l)

    Examples
    --------
    >>> force, translation = np.array([[2.0, 0, 0, 0, 0, 0]]), np.array([[0, 0, 0, 1.0, 0, 0]])
    >>> wrench, index = transmissions(force, translation, 1e-9)
    >>> wrench[0, 0], index[0]
    (np.float64(1.0), np.float64(1.0))
    """
    batch = raw.shape[:-1]
    kernels = compiled_twin("_limbs_numba", _size(batch[:-1]))
    if kernels is not None and 0 not in batch:
        flat = [np.ascontiguousarray(np.reshape(a, (-1, batch[-1], 6)), dtype=float) for a in (raw, twists)]
        wrench, index = kernels.transmissions(flat[0], flat[1], float(rtol))
        return wrench.reshape(*batch, 6), index.reshape(batch)
    return transmissions_numpy(unit_rows(raw), twists, rtol)


def transmissions_numpy(wrench: Array, twists: Array, rtol: float) -> tuple[Array, Array]:
    """:func:`transmissions` of unit ``wrench`` rows with numpy (the kernel's operations).

    Parameters
    ----------
    wrench : numpy.ndarray, shape (..., l, 6)
        Unit wrench rows.
    twists : numpy.ndarray, shape (..., l, 6)
    rtol : float

    Returns
    -------
    wrench : numpy.ndarray, shape (..., l, 6)
        The given rows.
    index : numpy.ndarray, shape (..., l)
    """
    return wrench, transmission_index(wrench, twists, np.abs(_dot_in_order(wrench, swapped(twists))), rtol)


def transmission_index(wrench: Array, twists: Array, product: Array, rtol: float) -> Array:
    """``product / (N(w) N(t))`` (:func:`scaled_magnitudes`), zero where a magnitude is: the
    transmission index given the reciprocal product ``|w ∘ t|`` (or a load standing for it).

    Parameters
    ----------
    wrench, twists : numpy.ndarray, shape (..., 6)
    product : numpy.ndarray, shape (...)
    rtol : float

    Returns
    -------
    numpy.ndarray, shape (...)
    """
    denominator = scaled_magnitudes(wrench, rtol) * scaled_magnitudes(twists, rtol)
    return np.where(denominator > 0, product / np.where(denominator > 0, denominator, 1.0), 0.0)
