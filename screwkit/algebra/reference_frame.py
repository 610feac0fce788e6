"""The reference frame of a set of screws: a point and a length that move with the mechanism.

Rank decisions and closeness measures are made about the mechanism's own reference point, with
moments divided by its characteristic length (*scaled coordinates*): both follow any rigid motion
of the mechanism and any change of unit, so the answers do not depend on where the user put the
origin or which unit they used. :func:`mechanism_frame` derives the point and the length from the
screws (the point nearest, in least squares, to the finite axes; the root-mean-square distance of
the axes from it), :func:`unit_scaled` expresses screws about them with unit rows, and
:func:`scaled_frame` does both in one pass. Each has a numpy path over the batch and a compiled
per-pose loop (:mod:`screwkit.algebra._reference_frame_numba`) doing the same operations in the
same order, so the two agree bit for bit (:mod:`screwkit.algebra.compiled`).

Examples
--------
>>> rows = np.array([[0, 0, 1, 0, -100.0, 0], [0, 1, 0, 0, 0, 0]])  # z through (100, 0, 0); y through 0
>>> point, length = mechanism_frame(rows)
>>> point.round(6) + 0.0, float(length)
(array([50.,  0.,  0.]), 50.0)
"""

from __future__ import annotations

import math

import numpy as np

from .compiled import compiled_kernels, sum_in_order

__all__ = ["UNDETERMINED_RTOL", "mechanism_frame", "scaled_frame", "unit_scaled"]

Array = np.ndarray

#: The compiled twin of this module's kernels.
KERNELS = "screwkit.algebra._reference_frame_numba"


def mechanism_frame(screws: Array, anchor: Array | None = None) -> tuple[Array, Array]:
    """The reference point and the characteristic length of screws ``(..., n, 6)``, batched
    (the kernel of :func:`screwkit.graphs.twistgraph.graph_frame`).

    The point is the least-squares point nearest to the finite axes (screws of infinite pitch are
    ignored). Directions along which the axes do not fix it (all axes parallel: a planar
    mechanism; eigenvalues of the normal matrix below :data:`UNDETERMINED_RTOL` of the largest)
    take the ``anchor`` ``(..., 3)``'s coordinate when one is given (a point that moves with the
    mechanism), else the solution nearest the origin. The length is the root-mean-square distance
    of the axes from the point; when every axis passes through it (a spherical mechanism) that is
    round-off, and below ``1e-12`` of the coordinates' own size it is replaced by that size (the
    farthest foot of an axis from the origin, or 1 when it is 0), a length that still follows the
    unit; moments about the common point are then zero whatever the length. With no finite axis,
    the point is the origin and the length 1.

    Parameters
    ----------
    screws : numpy.ndarray, shape (..., n, 6)
        The joint screws of each pose (floats).
    anchor : numpy.ndarray, shape (..., 3), optional
        A point that moves with the mechanism, for the directions the axes do not fix.

    Returns
    -------
    point : numpy.ndarray, shape (..., 3)
        The reference point of each pose.
    length : numpy.ndarray, shape (...)
        The characteristic length of each pose.

    Examples
    --------
    >>> rows = np.array([[0, 0, 1, 0, -100.0, 0], [0, 1, 0, 0, 0, 0]])
    >>> point, length = mechanism_frame(np.stack([rows, rows]))
    >>> point.round(6) + 0.0, length
    (array([[50.,  0.,  0.],
           [50.,  0.,  0.]]), array([50., 50.]))
    >>> planar = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, 1, 0, 0.0]])
    >>> mechanism_frame(planar, np.array([0, 0, 5.0]))[0].round(6) + 0.0
    array([0. , 0.5, 5. ])
    """
    point, length, _ = scaled_frame(screws, anchor, scale=False)
    return point, length


def scaled_frame(
    screws: Array, anchor: Array | None = None, *, scale: bool = True
) -> tuple[Array, Array, Array | None]:
    """:func:`mechanism_frame` and the screws in its scaled coordinates, unit rows
    (:func:`unit_scaled`; None unless ``scale``): ``(point, length, scaled)``. On the numba path
    one compiled pass (:func:`screwkit.algebra._reference_frame_numba.mechanism_frame`) where the
    normal matrix is solved directly, the numpy path's operations in its order (the same bits);
    the other poses as the numpy path.

    Parameters
    ----------
    screws : numpy.ndarray, shape (..., n, 6)
        The joint screws of each pose (floats).
    anchor : numpy.ndarray, shape (..., 3), optional
        A point that moves with the mechanism (:func:`mechanism_frame`).
    scale : bool, default True
        Whether to return the scaled screws too.

    Returns
    -------
    point : numpy.ndarray, shape (..., 3)
        The reference point of each pose.
    length : numpy.ndarray, shape (...)
        The characteristic length of each pose.
    scaled : numpy.ndarray, shape (..., n, 6), or None
        The screws about ``point`` with moments over ``length``, unit rows (None unless ``scale``).

    Examples
    --------
    >>> rows = np.array([[0, 0, 1, 0, -100.0, 0], [0, 1, 0, 0, 0, 0]])
    >>> point, length, scaled = scaled_frame(rows)                    # about (50, 0, 0), per 50
    >>> point.round(6) + 0.0, float(length), scaled.round(6) + 0.0
    (array([50.,  0.,  0.]), 50.0, array([[ 0.      ,  0.      ,  0.707107,  0.      , -0.707107,  0.      ],
           [ 0.      ,  0.707107,  0.      ,  0.      ,  0.      , -0.707107]]))
    """
    batch = screws.shape[:-2]
    flat = np.ascontiguousarray(np.reshape(screws, (-1, *screws.shape[-2:])), dtype=float)
    anchors = None
    if anchor is not None:
        anchors = np.broadcast_to(np.asarray(anchor, dtype=float), (*batch, 3)).reshape(-1, 3)
    kernels = compiled_kernels(KERNELS, len(flat))  # the same sums, in the same order
    if kernels is None:
        point, length = _frame_numpy(flat, anchors)
        scaled = unit_scaled(flat, point, length) if scale else None
    else:
        point, length, direct, scaled = kernels.mechanism_frame(flat, scale)
        rest = ~direct
        if rest.any():  # the eigendecomposition's poses
            point[rest], length[rest] = _frame_numpy(flat[rest], None if anchors is None else anchors[rest])
            if scale:
                scaled[rest] = kernels.unit_scaled(flat[rest], point[rest], length[rest])
        scaled = scaled if scale else None
    return (
        point.reshape(*batch, 3),
        length.reshape(batch),
        None if scaled is None else scaled.reshape(screws.shape),
    )


def _frame_numpy(flat: Array, anchor: Array | None) -> tuple[Array, Array]:
    """:func:`mechanism_frame` of screws ``(n, k, 6)`` with numpy (the compiled pass's twin)."""
    count, normal, rhs, farthest = _frame_sums_numpy(flat)
    point = _least_squares_point(normal, rhs, anchor)
    length = np.sqrt(_frame_spread_numpy(flat, point) / np.maximum(count, 1))
    reach = np.sqrt(point[:, 0] * point[:, 0] + point[:, 1] * point[:, 1] + point[:, 2] * point[:, 2])
    size = np.maximum(farthest, reach)
    round_off = length <= 1e-12 * size
    fallback = np.where(size > 0, size, 1.0)
    length = np.where(round_off | (length == 0), fallback, length)
    return point, length


def _axes_numpy(screws: Array) -> tuple[Array, list[Array], list[Array]]:
    """Of screws ``(n, k, 6)``: which axes are finite ``(n, k)``, their unit directions (zero for
    infinite pitch) and their feet ``d × m / |d|²`` (each axis's point nearest the origin), component
    by component (``(n, k)`` arrays: no ``(n, k, 3, 3)`` temporaries)."""
    d = [screws[..., i] for i in range(3)]
    m = [screws[..., 3 + i] for i in range(3)]
    sizes = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
    finite = sizes > 0
    inverse = 1.0 / np.where(finite, sizes, 1.0)
    scale = np.sqrt(inverse) * finite
    units = [x * scale for x in d]
    feet = [(d[1] * m[2] - d[2] * m[1]) * inverse, (d[2] * m[0] - d[0] * m[2]) * inverse,
            (d[0] * m[1] - d[1] * m[0]) * inverse]
    return finite, units, feet


def _frame_sums_numpy(screws: Array) -> tuple[Array, Array, Array, Array]:
    """The sums of :func:`screwkit.algebra._reference_frame_numba.mechanism_frame` with numpy, operation for
    operation: the projectors ``P_k = I − u_k u_kᵀ`` of the finite axes never formed, their sum and
    ``Σ P_k f_k`` summed over the axes left to right (:func:`screwkit.algebra.compiled.sum_in_order`)."""
    finite, units, feet = _axes_numpy(screws)
    along = units[0] * feet[0] + units[1] * feet[1] + units[2] * feet[2]
    pairs = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
    terms = [units[i] * units[j] for i, j in pairs]
    totals = sum_in_order(np.stack(terms + [(feet[i] - units[i] * along) * finite for i in range(3)]))
    count = finite.sum(axis=-1)
    normal = np.empty((len(screws), 3, 3))
    for (i, j), total in zip(pairs, totals, strict=False):
        normal[:, i, j] = normal[:, j, i] = (count if i == j else 0.0) - total
    farthest = np.sqrt(feet[0] * feet[0] + feet[1] * feet[1] + feet[2] * feet[2]).max(axis=-1, initial=0.0)
    return count, normal, np.stack(list(totals[6:]), axis=-1), farthest


def _frame_spread_numpy(screws: Array, point: Array) -> Array:
    """The spread of :func:`screwkit.algebra._reference_frame_numba.mechanism_frame` with numpy, operation for
    operation."""
    finite, units, feet = _axes_numpy(screws)
    away = [point[:, None, i] - feet[i] for i in range(3)]
    along = units[0] * away[0] + units[1] * away[1] + units[2] * away[2]
    away = [(away[i] - units[i] * along) * finite for i in range(3)]
    return sum_in_order(away[0] * away[0] + away[1] * away[1] + away[2] * away[2])


def _least_squares_point(normal: Array, rhs: Array, anchor: Array | None) -> Array:
    """``N⁻¹ rhs`` for the symmetric positive semi-definite ``normal (..., 3, 3)``, with the
    directions of its eigenvalues below :data:`UNDETERMINED_RTOL` of the largest taken from
    ``anchor`` (or 0). Where ``4 det N / (tr N)³ > 1e-6`` every eigenvalue is above ``1e-6`` of
    the largest (``λ_min ≥ 4 det / tr²`` as the other two multiply to at most ``(tr/2)²``, and
    ``λ_max ≤ tr``), so the adjugate solves it directly; the other poses go through the
    eigendecomposition. A pose's answer depends on its own data only."""
    batch = normal.shape[:-2]
    flat, b = normal.reshape(-1, 3, 3), rhs.reshape(-1, 3)
    n00, n01, n02 = flat[:, 0, 0], flat[:, 0, 1], flat[:, 0, 2]
    n11, n12, n22 = flat[:, 1, 1], flat[:, 1, 2], flat[:, 2, 2]
    a00, a01, a02 = n11 * n22 - n12 * n12, n02 * n12 - n01 * n22, n01 * n12 - n02 * n11
    a11, a12, a22 = n00 * n22 - n02 * n02, n01 * n02 - n00 * n12, n00 * n11 - n01 * n01
    det = n00 * a00 + n01 * a01 + n02 * a02
    trace = n00 + n11 + n22
    direct = (trace > 0) & (4.0 * det > 1e-6 * (trace * trace * trace))
    safe = np.where(direct, det, 1.0)
    point = np.stack(
        [
            (a00 * b[:, 0] + a01 * b[:, 1] + a02 * b[:, 2]) / safe,
            (a01 * b[:, 0] + a11 * b[:, 1] + a12 * b[:, 2]) / safe,
            (a02 * b[:, 0] + a12 * b[:, 1] + a22 * b[:, 2]) / safe,
        ],
        axis=-1,
    )
    rest = ~direct
    if rest.any():
        values, vectors = np.linalg.eigh(flat[rest])
        determined = values > UNDETERMINED_RTOL * values[..., -1:]
        inverse = np.where(determined, 1.0 / np.where(determined, values, 1.0), 0.0)
        coordinates = np.einsum("...ji,...j->...i", vectors, b[rest]) * inverse  # in the eigenbasis
        if anchor is not None:
            anchors = np.broadcast_to(np.asarray(anchor, dtype=float), (*batch, 3)).reshape(-1, 3)[rest]
            coordinates = np.where(determined, coordinates, np.einsum("...ji,...j->...i", vectors, anchors))
        point[rest] = np.einsum("...ij,...j->...i", vectors, coordinates)
    return point.reshape(*batch, 3)


#: Directions in which the joint axes fix the reference point too weakly to be used (eigenvalues of
#: the least-squares normal matrix below this fraction of the largest: axes within about 1e-5 rad
#: of all parallel) take the anchor's coordinate (:func:`mechanism_frame`).
UNDETERMINED_RTOL = 1e-10


def unit_scaled(screws: Array, centre: Array, length: Array) -> Array:
    """Screws about ``centre`` with moments over ``length``, ``(s; (s0 − c × s) / L)``, every row
    divided by its norm (zero rows stay zero): the generators of the analysis core, component by
    component in the compiled loop's order
    (:func:`screwkit.algebra._reference_frame_numba.unit_scaled`), so the two paths agree bit for bit.

    Parameters
    ----------
    screws : array_like, shape (..., k, 6)
        The screws (floats).
    centre : array_like, shape (..., 3)
        The reference point of each pose.
    length : array_like, shape (...)
        The characteristic length of each pose (positive).

    Returns
    -------
    numpy.ndarray, shape (..., k, 6)
        The unit scaled rows.

    Examples
    --------
    >>> unit_scaled(np.array([[0, 0, 2.0, 0, 0, 0]]), np.zeros(3), np.array(1.0))
    array([[0., 0., 1., 0., 0., 0.]])
    """
    screws = np.asarray(screws, dtype=float)
    batch = screws.shape[:-2]
    centres = np.broadcast_to(np.asarray(centre, dtype=float), (*batch, 3))
    lengths = np.broadcast_to(np.asarray(length, dtype=float), batch)
    kernels = compiled_kernels(KERNELS, math.prod(batch))
    if kernels is not None and 0 not in batch and screws.shape[-2]:
        out = kernels.unit_scaled(
            np.ascontiguousarray(screws.reshape(-1, *screws.shape[-2:])),
            np.ascontiguousarray(centres.reshape(-1, 3)),
            np.ascontiguousarray(lengths.reshape(-1)),
        )
        return out.reshape(screws.shape)
    d0, d1, d2 = screws[..., 0], screws[..., 1], screws[..., 2]
    c0, c1, c2 = (centres[..., None, i] for i in range(3))
    inverse_length = 1.0 / lengths[..., None]
    m0 = (screws[..., 3] - (c1 * d2 - c2 * d1)) * inverse_length
    m1 = (screws[..., 4] - (c2 * d0 - c0 * d2)) * inverse_length
    m2 = (screws[..., 5] - (c0 * d1 - c1 * d0)) * inverse_length
    size = np.sqrt(d0 * d0 + d1 * d1 + d2 * d2 + m0 * m0 + m1 * m1 + m2 * m2)
    inverse = 1.0 / np.where(size == 0.0, 1.0, size)
    return np.stack([x * inverse for x in (d0, d1, d2, m0, m1, m2)], axis=-1)

