"""A kinematic model's joint screws as a joint table writes them: the scaled frame's screws back in
the graph's frame and unit, and each spherical joint's three screws along orthonormal directions.

The model (:mod:`screwkit.core.kinematic_model`) carries its screws in a scaled frame: a screw with
moment ``m`` about the graph's origin has moment ``s0 = (m − p × s) / L`` about the reference point
``p``, in characteristic lengths ``L``; back in the graph's frame, ``m = s0 L + p × s`` (the adjoint
map of the translation by ``p``, Murray, Li & Sastry, *A Mathematical Introduction to Robotic
Manipulation*, 1994, Eq. 2.58), a couple's moment being free of the point. A ball carries its axes
as a rotation offset times three axes, which drift from orthogonal; the table writes them as a
catalog does, along orthonormal directions through the same centre (:func:`orthonormal_axes`).

:func:`joint_rows` does both in one pass: a compiled per-pose loop
(:mod:`screwkit.core._joint_rows_numba`) when numba runs, else the numpy twin, component by component
in the same order, so the two agree bit for bit (:mod:`screwkit.algebra.compiled`).

Examples
--------
>>> current = np.array([[[0.0, 0, 1, 0.5, 0, 0]]])  # a hinge along z, scaled frame
>>> joint_rows(current, 2.0, np.array([1.0, 0, 0]), np.zeros((0, 3), dtype=np.int64)) + 0.0
array([[[ 0.,  0.,  1.,  1., -1.,  0.]]])
"""

from __future__ import annotations

import numpy as np

from ..algebra.compiled import compiled_kernels

__all__ = ["KERNELS", "joint_rows", "orthonormal_axes", "unscaled_screws"]

Array = np.ndarray

#: The compiled twin of :func:`joint_rows`.
KERNELS = "screwkit.core._joint_rows_numba"

#: A row whose direction's squared norm is at most this is a couple (its moment kept as it is).
COUPLE_SQUARED_NORM = 1e-24


def unscaled_screws(rows: Array, length: float, point: Array) -> Array:
    """Screws ``(..., 6)`` of a scaled frame (reference point ``point``, characteristic length
    ``length``) back in the original frame and unit: ``(s; s0 L + p × s)``, a couple (``|s|² ≤``
    :data:`COUPLE_SQUARED_NORM`) as it is; component by component, as the compiled loop.

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6)
    length : float
    point : numpy.ndarray, shape (3,)

    Returns
    -------
    numpy.ndarray, shape (..., 6)
        A new array.

    Examples
    --------
    >>> unscaled_screws(np.array([0.0, 0, 1, 0.5, 0, 0]), 2.0, np.array([1.0, 0, 0])) + 0.0
    array([ 0.,  0.,  1.,  1., -1.,  0.])
    """
    rows = np.asarray(rows, dtype=float)
    s0, s1, s2 = rows[..., 0], rows[..., 1], rows[..., 2]
    p0, p1, p2 = (float(value) for value in point)
    finite = (s0 * s0 + s1 * s1 + s2 * s2) > COUPLE_SQUARED_NORM
    out = np.empty(rows.shape)
    out[..., :3] = rows[..., :3]
    out[..., 3] = np.where(finite, rows[..., 3] * length + (p1 * s2 - p2 * s1), rows[..., 3])
    out[..., 4] = np.where(finite, rows[..., 4] * length + (p2 * s0 - p0 * s2), rows[..., 4])
    out[..., 5] = np.where(finite, rows[..., 5] * length + (p0 * s1 - p1 * s0), rows[..., 5])
    return out


def _dot(a: list[Array], b: list[Array]) -> Array:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def orthonormal_axes(rows: Array) -> Array:
    """A spherical joint's three screws ``(..., 3, 6)`` (lines through its centre) recombined into
    lines along orthonormal directions through that centre: the same 3-system, written as a catalog
    writes a ball.

    The scaled frame's length (the axes' root-mean-square distance from the reference point) reads
    the basis: ``Σ |(c − p) × s_i|²`` is ``2 |c − p|²`` only over orthonormal ``s_i``. The rows are
    ``R⁻ᵀ`` times the given ones, ``R`` the triangle of the directions' QR factorization
    ``[d₀ d₁ d₂] = Q R`` (a linear combination of lines through ``c`` is a line through ``c``; the
    new directions are the columns of ``Q``): Gram–Schmidt's ``r_ij = q_i · d_j`` with the signs of
    Householder's factorization as LAPACK computes it (``numpy.linalg.qr``): ``r_kk = −sign(a_kk) |a|``
    of the column ``a`` left below the diagonal, ``r_kk = a_kk`` where that column has nothing below
    it (Golub & Van Loan, *Matrix Computations*, 4th ed., 2013, §5.1.2 and §5.2.2), and
    ``q₂ = det(Q) q₀ × q₁``.

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 3, 6)

    Returns
    -------
    numpy.ndarray, shape (..., 3, 6)

    Examples
    --------
    >>> centre, axes = np.array([0.0, 0, 2]), np.array([[1.0, 0, 0], [0.6, 0.8, 0], [0, 0, 1]])
    >>> out = orthonormal_axes(np.hstack([axes, np.cross(centre, axes)]))
    >>> bool(np.allclose(out[:, :3] @ out[:, :3].T, np.eye(3)))       # orthonormal directions
    True
    >>> bool(np.allclose(out[:, 3:], np.cross(centre, out[:, :3])))  # through the same centre
    True
    """
    rows = np.asarray(rows, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):  # (dependent axes: NaN rows, as compiled)
        d = [[rows[..., i, j] for j in range(3)] for i in range(3)]  # d[i][j]: axis i, component j
        first_alone = (d[0][1] == 0.0) & (d[0][2] == 0.0)  # no first reflection (LAPACK's tau = 0)
        r00 = np.where(first_alone, d[0][0], -np.copysign(np.sqrt(_dot(d[0], d[0])), d[0][0]))
        q0 = [x / r00 for x in d[0]]
        r01, r02 = _dot(q0, d[1]), _dot(q0, d[2])
        e1 = [d[1][j] - r01 * q0[j] for j in range(3)]
        # the second axis after the first reflection I − 2 u uᵀ / uᵀu, u = d₀ − r₀₀ e₀: its components 1, 2
        u = [d[0][0] - r00, d[0][1], d[0][2]]
        uu = _dot(u, u)
        factor = np.where(first_alone, 0.0, 2.0 * _dot(u, d[1]) / np.where(first_alone, 1.0, uu))
        below1, below2 = d[1][1] - factor * u[1], d[1][2] - factor * u[2]
        second_alone = below2 == 0.0
        r11 = np.where(second_alone, below1, -np.copysign(np.sqrt(_dot(e1, e1)), below1))
        q1 = [x / r11 for x in e1]
        r12 = _dot(q1, d[2])
        sign = np.where(first_alone == second_alone, 1.0, -1.0)  # det Q: −1 per reflection
        q2 = [sign * (q0[1] * q1[2] - q0[2] * q1[1]), sign * (q0[2] * q1[0] - q0[0] * q1[2]),
              sign * (q0[0] * q1[1] - q0[1] * q1[0])]
        r22 = _dot(q2, d[2])
        out = np.empty(rows.shape)
        out[..., 0, :] = rows[..., 0, :] / r00[..., None]
        out[..., 1, :] = (rows[..., 1, :] - r01[..., None] * out[..., 0, :]) / r11[..., None]
        third = rows[..., 2, :] - r02[..., None] * out[..., 0, :] - r12[..., None] * out[..., 1, :]
        out[..., 2, :] = third / r22[..., None]
    return out


def joint_rows(current: Array, length: float, point: Array, balls: Array) -> Array:
    """A joint table's rows from a model's current screws: :func:`unscaled_screws`, then
    :func:`orthonormal_axes` on each ball's three columns; compiled over large batches.

    Parameters
    ----------
    current : numpy.ndarray, shape (..., n, 6)
        The screws in the scaled frame.
    length : float
        The characteristic length.
    point : numpy.ndarray, shape (3,)
        The reference point.
    balls : numpy.ndarray of int, shape (k, 3)
        Each spherical joint's three columns.

    Returns
    -------
    numpy.ndarray, shape (..., n, 6)
        A new C-ordered array (owning its data).

    Examples
    --------
    >>> hinges = np.concatenate([np.eye(3), np.zeros((3, 3))], axis=-1)[None]  # a ball at the origin
    >>> rows = joint_rows(hinges, 1.0, np.zeros(3), np.array([[0, 1, 2]]))
    >>> rows[0, :, :3] + 0.0  # already orthonormal: the same axes
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    flat = current.reshape(-1, *current.shape[-2:])
    kernels = compiled_kernels(KERNELS, len(flat))
    if kernels is not None and current.size:
        out = np.empty(current.shape)
        kernels.joint_rows(
            np.ascontiguousarray(flat, dtype=float),
            float(length),
            np.ascontiguousarray(point, dtype=float),
            np.ascontiguousarray(balls, dtype=np.int64),
            COUPLE_SQUARED_NORM,
            out.reshape(flat.shape),
        )
        return out
    rows = unscaled_screws(current, length, point)
    if len(balls):
        rows[..., balls, :] = orthonormal_axes(rows[..., balls, :])
    return rows
