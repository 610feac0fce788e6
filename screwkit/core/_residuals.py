"""Residuals of vectors against frames: each vector less its projections on a frame's rows (private).

Classical Gram–Schmidt applied twice (CGS2, Giraud et al., *Numer. Math.* 101, 2005) against the
orthonormal rows of a frame (:mod:`screwkit.core.frames`): the part of a twist outside a twist
system (a limb's ``t⊥``), of a wrench outside a leg's constraint system. The numpy path does the
compiled loop's operations in its order (:func:`screwkit.core._frames_numba.residual`): the two
agree bit for bit.

Examples
--------
>>> residual(np.array([[1.0, 1.0, 0, 0, 0, 0]]), np.eye(6)[:1])
array([[0., 1., 0., 0., 0., 0.]])
"""

from __future__ import annotations

import numpy as np

from .frames import _dot_in_order, _import_kernels, _numba_kernels, _size

__all__ = ["residual", "residuals_against"]

Array = np.ndarray


def residual(vectors: Array, rows: Array) -> Array:
    """``vectors (..., k, 6)`` minus their projections on a frame's rows (re-orthogonalised once).

    Parameters
    ----------
    vectors : numpy.ndarray, shape (..., k, 6)
    rows : numpy.ndarray, shape (..., m, 6)
        Orthonormal rows (zero rows allowed), broadcast against ``vectors``' batch.

    Returns
    -------
    numpy.ndarray, shape (..., k, 6)

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

    Parameters
    ----------
    vectors : numpy.ndarray, shape (..., k, 6)
    frames : numpy.ndarray, shape (..., f, 6, 6)
        Orthonormal rows, zero beyond each frame's order.
    which : array_like of int, shape (k,)
        The frame of each vector.

    Returns
    -------
    numpy.ndarray, shape (..., k, 6)

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
