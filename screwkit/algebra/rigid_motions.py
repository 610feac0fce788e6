"""Rotations and rigid displacements over a batch: cross-product matrices, Rodrigues' formula and
its inverse, the exponential of a screw and the adjoint map (Murray, Li & Sastry, *A Mathematical
Introduction to Robotic Manipulation*, 1994, ch. 2).

Examples
--------
>>> bool(np.allclose(rotation_log(rotation_matrix(np.array([1.0, 0, 0]), np.array(0.5))), [0.5, 0, 0]))
True
"""

from __future__ import annotations

import numpy as np

__all__ = ["adjoint", "exp_screw", "hat", "rotation_log", "rotation_matrix"]

Array = np.ndarray


def hat(w: Array) -> Array:
    """Cross-product matrices of ``(..., 3)`` vectors.

    Parameters
    ----------
    w : numpy.ndarray, shape (..., 3)

    Returns
    -------
    numpy.ndarray, shape (..., 3, 3)
        ``[w]×`` with ``[w]× v = w × v``.

    Examples
    --------
    >>> hat(np.array([0.0, 0.0, 1.0])) @ np.array([1.0, 0.0, 0.0])
    array([0., 1., 0.])
    """
    zero = np.zeros(w.shape[:-1])
    return np.stack(
        [
            np.stack([zero, -w[..., 2], w[..., 1]], -1),
            np.stack([w[..., 2], zero, -w[..., 0]], -1),
            np.stack([-w[..., 1], w[..., 0], zero], -1),
        ],
        -2,
    )


def rotation_matrix(axis: Array, angle: Array) -> Array:
    """Rodrigues' formula (Murray, Li & Sastry 1994, Eq. 2.14) for unit axes and angles.

    Parameters
    ----------
    axis : numpy.ndarray, shape (..., 3)
        Unit axes (broadcast against ``angle``).
    angle : numpy.ndarray, shape (...)
        Angles in radians.

    Returns
    -------
    numpy.ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> rotation_matrix(np.array([0.0, 0.0, 1.0]), np.array(np.pi / 2)).round(12) @ [1, 0, 0]
    array([0., 1., 0.])
    """
    k = hat(np.asarray(axis, dtype=float))
    angle = np.asarray(angle, dtype=float)[..., None, None]
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * (k @ k)


def rotation_log(rotation: Array) -> Array:
    """The rotation vectors ``φ`` with ``exp([φ]×) = R`` (angles in ``[0, π]``), batched.

    The inverse of Rodrigues' formula (Murray, Li & Sastry 1994, Eqs. 2.17-2.18), with the series
    near 0 and the symmetric part near π, so it is accurate over every rotation.

    Parameters
    ----------
    rotation : numpy.ndarray, shape (..., 3, 3)

    Returns
    -------
    numpy.ndarray, shape (..., 3)

    Examples
    --------
    >>> rotation_log(rotation_matrix(np.array([0.0, 0.0, 1.0]), np.array(0.3))).round(12) + 0.0
    array([0. , 0. , 0.3])
    """
    r = np.asarray(rotation, dtype=float)
    skew = 0.5 * np.stack(
        [r[..., 2, 1] - r[..., 1, 2], r[..., 0, 2] - r[..., 2, 0], r[..., 1, 0] - r[..., 0, 1]], -1
    )
    cosine = np.clip(0.5 * (np.trace(r, axis1=-2, axis2=-1) - 1), -1.0, 1.0)
    sine = np.linalg.norm(skew, axis=-1)
    angle = np.arctan2(sine, cosine)
    with np.errstate(divide="ignore", invalid="ignore"):
        factor = np.where(sine > 1e-8, angle / np.where(sine > 0, sine, 1.0), 1.0 + angle**2 / 6)
    out = skew * factor[..., None]
    near_pi = cosine < -0.99  # sin θ small, the skew part loses the axis: read it from R + I
    if np.any(near_pi):
        sym = (r[near_pi] + np.eye(3)) / 2  # = a aᵀ (1 − cos θ)/2 + cos θ ... → a aᵀ at θ = π
        column = np.argmax(np.diagonal(sym, axis1=-2, axis2=-1), axis=-1)
        axis = np.take_along_axis(sym, column[:, None, None], axis=-1)[..., 0]
        axis /= np.linalg.norm(axis, axis=-1, keepdims=True)
        sign = np.where(np.einsum("bi,bi->b", axis, skew[near_pi]) < 0, -1.0, 1.0)
        out[near_pi] = axis * (sign * angle[near_pi])[:, None]
    return out


def exp_screw(row: Array, angle: Array) -> Array:
    """Displacements of a unit screw by angles: the exponential of a twist (Murray, Li & Sastry
    1994, Eq. 2.36: ``p = (I − R)(ω × v) + ω ωᵀ v θ``; ``(I, v θ)`` for ``ω = 0``).

    Parameters
    ----------
    row : numpy.ndarray, shape (6,)
        The screw ``(ω; v)`` (a rotation screw is normalised to a unit axis: ``angle`` in radians).
    angle : numpy.ndarray, shape (B,)

    Returns
    -------
    numpy.ndarray, shape (B, 4, 4)

    Examples
    --------
    >>> exp_screw(np.array([0, 0, 1.0, 0, -1.0, 0]), np.array([np.pi]))[0, :3, 3].round(12) + 0.0
    array([2., 0., 0.])
    """
    angle = np.asarray(angle, dtype=float)
    g = np.zeros((len(angle), 4, 4))
    g[:, 3, 3] = 1.0
    w, v = row[:3], row[3:]
    size = float(np.sqrt(w @ w))
    if size < 1e-12:
        g[:, 0, 0] = g[:, 1, 1] = g[:, 2, 2] = 1.0
        g[:, :3, 3] = angle[:, None] * v
        return g
    w, v = w / size, v / size  # a rotation screw: θ in radians about its unit axis
    k = hat(w)
    kk = k @ k
    sine, versine = np.sin(angle)[:, None, None], (1.0 - np.cos(angle))[:, None, None]
    rot = np.eye(3) + sine * k + versine * kk
    g[:, :3, :3] = rot
    # (I − R)(ω × v) = −(sin θ K + (1 − cos θ) K²)(ω × v), plus the pitch's ω ωᵀ v θ
    moment = np.array([w[1] * v[2] - w[2] * v[1], w[2] * v[0] - w[0] * v[2], w[0] * v[1] - w[1] * v[0]])
    turned = sine[:, :, 0] * (k @ moment) + versine[:, :, 0] * (kk @ moment)
    g[:, :3, 3] = np.outer(angle, w * (w @ v)) - turned
    return g


def adjoint(g: Array, rows: Array) -> Array:
    """The adjoint map of displacements applied to screws: ``(R s; R s0 + p × R s)`` (Murray, Li &
    Sastry 1994, Eq. 2.58).

    Parameters
    ----------
    g : numpy.ndarray, shape (B, 4, 4)
    rows : numpy.ndarray, shape (B, 6)

    Returns
    -------
    numpy.ndarray, shape (B, 6)

    Examples
    --------
    >>> shift = np.eye(4)[None].copy(); shift[0, 0, 3] = 1.0
    >>> adjoint(shift, np.array([[0, 0, 1.0, 0, 0, 0]]))  # the z axis moved to x = 1
    array([[ 0.,  0.,  1.,  0., -1.,  0.]])
    """
    rotation, p = g[:, :3, :3], g[:, :3, 3]
    s = np.einsum("bij,bj->bi", rotation, rows[:, :3])
    s0 = np.einsum("bij,bj->bi", rotation, rows[:, 3:])
    s0[:, 0] += p[:, 1] * s[:, 2] - p[:, 2] * s[:, 1]  # p × R s, written out (np.cross's overhead
    s0[:, 1] += p[:, 2] * s[:, 0] - p[:, 0] * s[:, 2]  # dominates the small batches of a
    s0[:, 2] += p[:, 0] * s[:, 1] - p[:, 1] * s[:, 0]  # continuation)
    return np.concatenate([s, s0], axis=-1)
