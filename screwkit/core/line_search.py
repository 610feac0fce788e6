"""Actuation wrenches drawn as lines: the constraint wrench to add that makes a screw a line.

An actuation wrench is defined up to its limb's constraint wrenches (paper 002 §4.3); the one drawn
in diagrams and reported is a line where adding a constraint wrench can make it one: the
smallest such addition found along a few directions (:func:`nearest_lines`, :func:`line_search`).
:data:`LINE_RTOL` decides that a screw is already a line.

Examples
--------
>>> couple = np.zeros((1, 1, 6)); couple[0, 0, 5] = 1.0                   # the couple about z
>>> line_search(np.array([[0, 0, 1.0, 0, 0, 2.0]]), couple, np.array([1])) # pitch 2 along z: a line
array([[0., 0., 1., 0., 0., 0.]])
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from . import _limbs as LK

__all__ = ["LINE_RTOL", "line_search", "nearest_lines"]

Array = np.ndarray

#: Relative tolerance deciding that a chosen actuation wrench is a line (zero pitch).
LINE_RTOL = 1e-6


def nearest_lines(wrench: Array, constraints_at: Callable[[Array], Array], order: Array) -> Array:
    """``wrench + c`` of zero pitch with ``c`` the smallest constraint wrench found that makes it a
    line, where the wrench is not already one (batched; rows orthonormal, scaled).

    The pitch numerator of ``w + C α`` is the quadratic ``αᵀQα + bᵀα + p0`` (``Q`` the symmetric
    part of ``C_s C_mᵀ``). Along a direction ``u`` it is a quadratic in one variable; the
    directions tried are the frame's rows, the gradient ``b`` (steepest descent) and the
    eigenvectors of ``Q``, and the root of smallest ``|α|`` wins. Only the wrenches that are not
    lines (:data:`LINE_RTOL`) and have constraint wrenches to add are searched (each on its own: a
    pose's answer does not depend on the others).

    Parameters
    ----------
    wrench : numpy.ndarray, shape (..., 6)
        Unit wrenches in scaled coordinates (:mod:`screwkit.core.frames`).
    constraints_at : callable
        ``constraints_at(where)`` gives the constraint system's rows ``(m, 6, 6)`` (orthonormal,
        zero beyond the order) at a boolean mask of the batch; asked only where a wrench is searched.
    order : numpy.ndarray of int, shape (...)
        The constraint system's order.

    Returns
    -------
    numpy.ndarray, shape (..., 6)
        The wrenches, made lines where a root was found (:func:`line_search`), else as given.

    Examples
    --------
    >>> couple = np.zeros((6, 6)); couple[0, 5] = 1.0                      # the couple about z
    >>> screw = np.array([0, 0, 1.0, 0, 0, 1.0]) / np.sqrt(2)              # pitch 1 along z
    >>> nearest_lines(screw[None], lambda where: couple[None][where], np.array([1]))[0] * np.sqrt(2)
    array([0., 0., 1., 0., 0., 0.])
    """
    searched = LK.not_lines(wrench, LINE_RTOL) & (np.asarray(order) > 0)
    best = wrench.copy()
    if searched.any():
        best[searched] = line_search(wrench[searched], constraints_at(searched), np.asarray(order)[searched])
    return best


def line_search(wrench: Array, constraints: Array, order: Array) -> Array:
    """:func:`nearest_lines` over wrenches that are not lines: the search itself.

    Parameters
    ----------
    wrench : numpy.ndarray, shape (n, 6)
        Unit scaled wrenches, none a line.
    constraints : numpy.ndarray, shape (n, k, 6)
        Each wrench's constraint rows (orthonormal, zero beyond ``order``).
    order : numpy.ndarray of int, shape (n,)
        The number of constraint rows of each.

    Returns
    -------
    numpy.ndarray, shape (n, 6)
        ``wrench + α c`` of zero pitch with the smallest ``|α|`` over the directions tried, or the
        wrench itself where no real root exists.

    Examples
    --------
    >>> couple = np.zeros((1, 1, 6)); couple[0, 0, 5] = 1.0
    >>> line_search(np.array([[0, 0, 1.0, 0, 0, 1.0]]), couple, np.array([1]))
    array([[0., 0., 1., 0., 0., 0.]])
    """
    s, m = wrench[..., :3], wrench[..., 3:]
    pitch = np.einsum("...i,...i->...", s, m)
    mask = np.arange(constraints.shape[-2]) < order[..., None]
    rows = constraints * mask[..., None]
    gradient = np.einsum("...i,...ki->...k", s, rows[..., 3:]) + np.einsum(
        "...ki,...i->...k", rows[..., :3], m
    )
    q = np.einsum("...ki,...li->...kl", rows[..., :3], rows[..., 3:])
    _, vectors = np.linalg.eigh((q + np.swapaxes(q, -1, -2)) / 2)
    directions = np.concatenate(
        [
            np.broadcast_to(np.eye(rows.shape[-2]), vectors.shape),
            gradient[..., None, :],
            np.swapaxes(vectors, -1, -2),
        ],
        axis=-2,
    )  # (..., d, k): every direction tried, on an axis of their own
    u = directions * mask[..., None, :]
    norm_u = np.linalg.norm(u, axis=-1)
    c = np.einsum("...dk,...ki->...di", u / np.where(norm_u > 0, norm_u, 1.0)[..., None], rows)
    usable = norm_u > 0
    a = np.einsum("...i,...i->...", c[..., :3], c[..., 3:])
    b = np.einsum("...i,...di->...d", s, c[..., 3:]) + np.einsum("...di,...i->...d", c[..., :3], m)
    p0 = pitch[..., None]
    disc = b * b - 4 * a * p0
    # the stable pair of roots (Numerical Recipes §5.6): q = -(b + sgn(b) √disc) / 2, α = q/a, p/q
    q = -(b + np.where(b < 0, -1.0, 1.0) * np.sqrt(np.where(disc >= 0, disc, 0.0))) / 2
    real = usable & (disc >= 0)
    with np.errstate(over="ignore"):  # a root past the float range is no candidate (inf)
        roots = np.stack(
            [
                np.where(np.abs(a) > 0, q / np.where(np.abs(a) > 0, a, 1.0), np.inf),
                np.where(np.abs(q) > 0, p0 / np.where(np.abs(q) > 0, q, 1.0), np.inf),
            ],
            axis=-1,
        ).reshape(*q.shape[:-1], -1)  # (..., 2d): direction by direction, both roots of each
    sizes = np.where(np.repeat(real, 2, axis=-1) & np.isfinite(roots), np.abs(roots), np.inf)
    pick = np.argmin(sizes, axis=-1)[..., None]  # the smallest |α|, the first of equals
    alpha = np.take_along_axis(roots, pick, -1)[..., 0]
    found = np.isfinite(np.take_along_axis(sizes, pick, -1)[..., 0])
    chosen = np.take_along_axis(c, (pick // 2)[..., None], -2)[..., 0, :]
    return np.where(
        found[..., None], wrench + np.where(found, alpha, 0.0)[..., None] * chosen, wrench
    )
