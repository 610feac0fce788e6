"""Ranks and null spaces of screws: the one rank rule with its length scale.

A screw ``(s; s0)`` mixes a dimensionless direction and a moment with the unit of length. Before any
rank decision the moment half is divided by a characteristic length ``length_scale`` and every row is
normalised to unit length (row scaling does not change a rank). The rank is then the number of
singular values above ``rtol`` times the largest one. With ``length_scale`` given in the same unit as
the coordinates, the answer is the same in millimetres and in metres. When ``length_scale`` is None
it is taken from the data: the largest ``|s0| / |s|`` over rows whose direction is not round-off
(``|s| > 1e-9 |s0|``; a length in the data's own unit, kept within [1e-100, 1e100] like a given
one), or 1 if every row is a couple, leaving out the rows whose ratio is more than ``1 / rtol``
above the next smaller one (their direction is round-off at ``rtol``: ``(1e-8, 0, 0; 0, 0, 1)``
is a translation at ``rtol = 1e-6``, not a rotation about an axis 1e8 away). When the next
smaller ratio is 0 (an axis through the origin, which carries no length) the comparison is with
the data's unit 1: at a loose ``rtol`` give ``length_scale`` (the mechanism's size) when axes lie
far from the origin. Rows are scaled by powers of two before any square
(:func:`unit_rows`), so a decision is the same for screws of any finite magnitude, 1e-300 or
1e300. Symbolic rows have their generic rank and null spaces (:mod:`screwkit.algebra.symbolic`). Part of the
numeric/symbolic backend (:mod:`screwkit.algebra.backend`).

Examples
--------
>>> screw_rank(np.array([[0, 0, 1, 0, 0, 0], [0, 0, 2, 0, 0, 0]]))
1
>>> screw_nullspace(np.array([[0, 0, 1, 0, 0, 0]])).shape   # the wrenches reciprocal to a line
(5, 6)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exceptions import DegenerateGeometryError
from .backend import DEFAULT_RTOL, is_symbolic, sympy_module
from .branch_values import zeros
from .checks import MIN_LENGTH_SCALE, checked_length_scale, checked_rtol
from .zero_tests import _binary_exponents, _norms, zero_vectors

__all__ = [
    "characteristic_length",
    "direction_scaled",
    "matrix_nullspace",
    "scale_moments",
    "screw_image_of_nullspace",
    "screw_nullspace",
    "screw_rank",
    "screw_singular_values",
    "unit_rows",
    "unit_screws",
]

Array = np.ndarray


def direction_scaled(s: Array, s0: Array) -> tuple[Array, Array]:
    """Numeric ``(s, s0)`` times a power of two (exact) per screw so that ``|s|`` lies in [0.5, 2):
    ``s·s`` then neither underflows (a 1e-170 axis) nor overflows. Symbolic values are returned as
    they are (exact arithmetic has no range). Quotients homogeneous in ``(s, s0)`` (pitch, axis
    point) are unchanged.

    Parameters
    ----------
    s, s0 : numpy.ndarray, shape (..., 3)
        The direction and moment halves.

    Returns
    -------
    s, s0 : numpy.ndarray, shape (..., 3)
        Both halves times the same power of two per screw.

    Examples
    --------
    >>> direction_scaled(np.array([0.0, 0, 8.0]), np.array([1.0, 0, 0]))
    (array([0. , 0. , 0.5]), array([0.0625, 0.    , 0.    ]))
    """
    if is_symbolic(s, s0):
        return s, s0
    shift = _binary_exponents(s)
    return np.ldexp(s, -shift), np.ldexp(s0, -shift)


def unit_screws(screws: Array, length_scale: float) -> Array:
    """Numeric screws ``(..., 6)`` with the moment divided by ``length_scale`` and scaled to unit
    length, for tolerance decisions; symbolic screws unchanged (their decisions are exact).

    Parameters
    ----------
    screws : numpy.ndarray, shape (..., 6)
        Numeric screws.
    length_scale : float
        The characteristic length.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Raises
    ------
    DegenerateGeometryError
        For a zero screw (numeric, or identically zero).
    ScrewkitValueError
        For a length scale that is not a positive finite number (in either branch).

    Examples
    --------
    >>> unit_screws(np.array([0.0, 0, 2, 0, 0, 4]), 2.0)
    array([0.        , 0.        , 0.70710678, 0.        , 0.        , 0.70710678])
    """
    checked_length_scale(length_scale)
    if is_symbolic(screws):
        if np.any(zero_vectors(screws)):
            raise DegenerateGeometryError("Expected non-zero screws, got the zero screw.")
        return screws
    screws = np.asarray(screws, dtype=float)
    if np.any(zero_vectors(screws)):
        raise DegenerateGeometryError("Expected non-zero screws, got the zero screw.")
    return unit_rows(screws, length_scale)


def unit_rows(rows: Array, length_scale: float | Array) -> Array:
    """Numeric screws ``(..., 6)`` with the moment half divided by ``length_scale``, each scaled to
    unit length (zero rows stay zero): the rows every numeric rank decision reads.

    Each row is first multiplied by a power of two (exact) that brings its largest coordinate into
    [0.5, 1), before and after the division, so no square overflows or underflows: the result is
    the same for a screw and for that screw times any factor in the float range (1e-300 or 1e300).

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6)
        Numeric screws, any finite magnitude.
    length_scale : float or numpy.ndarray
        The characteristic length, in [1e-100, 1e100] (:func:`characteristic_length`); an array
        (one length per system, shape ``(..., 1, 1)`` for rows ``(..., k, 6)``) broadcasts.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Examples
    --------
    >>> unit_rows(np.array([[0.0, 0, 3e200, 0, 0, 4e200], [0.0] * 6]), 1.0)
    array([[0. , 0. , 0.6, 0. , 0. , 0.8],
           [0. , 0. , 0. , 0. , 0. , 0. ]])
    """
    scaled = np.ldexp(rows, -_binary_exponents(rows))
    scaled[..., 3:] /= length_scale
    scaled = np.ldexp(scaled, -_binary_exponents(scaled))
    lengths = np.linalg.norm(scaled, axis=-1, keepdims=True)
    return scaled / np.where(lengths > 0, lengths, 1.0)


def _derived_length(rows: Array, rtol: float = DEFAULT_RTOL) -> float:
    """The characteristic length of numeric rows (module docstring): the largest ``|s0| / |s|``
    below the first gap of ``1 / rtol`` in the sorted ratios, within [MIN_LENGTH_SCALE,
    1 / MIN_LENGTH_SCALE]; 1 without such a row.

    A row whose ratio exceeds the next smaller one (or the data's unit 1, when that one is 0: an
    axis through the origin gives no length) by more than ``1 / rtol`` has a direction that is
    round-off at ``rtol`` relative to the other rows: a translation ``(1e-8, 0, 0; 0, 0, 1)`` is a
    couple at ``rtol = 1e-6``, not a rotation 1e8 away, and must not set the length (a single
    such row does: there is nothing to compare it with)."""
    directions, moments = _norms(rows[..., :3]), _norms(rows[..., 3:])  # no square overflows
    has_direction = directions > DEFAULT_RTOL * moments  # a couple's round-off direction is not one
    ratios = np.sort(moments[has_direction] / directions[has_direction], axis=None)
    if not (ratios.size and ratios[-1] > 0):
        return 1.0
    references = np.where(ratios[:-1] > 0, ratios[:-1], 1.0)
    gaps = np.flatnonzero(ratios[1:] * rtol > references)
    length = ratios[gaps[0]] if gaps.size else ratios[-1]
    if length == 0:
        return 1.0
    return float(np.clip(length, MIN_LENGTH_SCALE, 1 / MIN_LENGTH_SCALE))


def scale_moments(
    rows: Array, length_scale: float | None, rtol: float = DEFAULT_RTOL
) -> tuple[Array, float]:
    """Divide the moment half of screws ``(..., 6)`` by a characteristic length.

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6)
    length_scale : float or None
        The characteristic length; None derives it from the data (see the module docstring).
    rtol : float, default 1e-9
        The tolerance of the decisions the length serves (a derived length ignores directions
        that are round-off at it).

    Returns
    -------
    scaled : numpy.ndarray, shape (..., 6)
    length_scale : float
        The length actually used.

    Examples
    --------
    >>> scale_moments(np.array([[1.0, 0, 0, 0, 0, 500.0]]), None)[1]
    500.0
    """
    if length_scale is None:
        length = _derived_length(np.asarray(rows, dtype=float), checked_rtol(rtol))
    else:
        checked = checked_length_scale(length_scale, allow_none=True)  # its message mentions None
        assert checked is not None  # None took the branch above
        length = checked
    scaled = np.array(rows, dtype=float)
    scaled[..., 3:] /= length
    return scaled, length


def characteristic_length(
    rows: Array, length_scale: float | None, rtol: float = DEFAULT_RTOL
) -> float | None:
    """The length a numeric rank decision on ``rows`` uses (:func:`scale_moments`); symbolic rows
    keep ``length_scale`` as given (their decisions are exact and need none).

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., k, 6)
        The screws.
    length_scale : float or None
        The caller's length (None: derived from the rows).
    rtol : float, default 1e-9
        The tolerance of the decisions the length serves: a derived length ignores a row whose
        direction is round-off at it relative to the other rows (module docstring).

    Returns
    -------
    float or None
        The length; None for symbolic rows.

    Examples
    --------
    >>> import sympy
    >>> characteristic_length(np.array([[1.0, 0, 0, 0, 0, 500.0]]), None)
    500.0
    >>> characteristic_length(np.array([[sympy.Symbol("a"), 0, 0, 0, 0, 1]], dtype=object), None) is None
    True
    """
    if is_symbolic(rows):
        return length_scale
    return _numeric_length(rows, length_scale, checked_rtol(rtol))


def _numeric_length(rows: Array, length_scale: float | None, rtol: float = DEFAULT_RTOL) -> float:
    """:func:`characteristic_length` of numeric rows."""
    if length_scale is None:
        return _derived_length(np.asarray(rows, dtype=float), rtol)
    return checked_length_scale(length_scale)


def _independent_rows(rows: Array, rtol: float, length_scale: float | None) -> Array:
    """The rows that raise the rank, in order (a basis made of the given generators)."""
    chosen: list[Array] = []
    rank = 0
    total = screw_rank(rows, rtol=rtol, length_scale=length_scale) if rows.shape[0] else 0
    if total == rows.shape[0]:
        return rows.copy()
    for row in rows:
        trial = np.array([*chosen, row], dtype=rows.dtype)
        new_rank = screw_rank(trial, rtol=rtol, length_scale=length_scale)
        if new_rank > rank:
            chosen.append(row)
            rank = new_rank
            if rank == total:
                break
    return np.array(chosen, dtype=rows.dtype).reshape(len(chosen), 6)


def screw_singular_values(rows: Array, *, length_scale: float | None = None) -> Array:
    """Singular values of screws ``(..., k, 6)`` after moment scaling and row normalisation.

    The largest is between 1 and sqrt(k); their ratios are frame-sensitive but unit-invariant.
    Zero rows are kept as zero rows. Batched over leading axes.

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., k, 6)
        Numeric screws.
    length_scale : float, optional
        The characteristic length (default: derived from the rows).

    Returns
    -------
    numpy.ndarray, shape (..., min(k, 6))

    Examples
    --------
    >>> screw_singular_values(np.array([[1.0, 0, 0, 0, 0, 0], [0, 1.0, 0, 0, 0, 0]]))
    array([1., 1.])
    """
    rows = np.asarray(rows, dtype=float)
    return np.linalg.svd(unit_rows(rows, _numeric_length(rows, length_scale)), compute_uv=False)


def screw_rank(rows: Array, *, rtol: float = DEFAULT_RTOL, length_scale: float | None = None) -> Any:
    """Rank of a set of screws ``(..., k, 6)``: numeric at a pose, generic when symbolic.

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., k, 6)
    rtol : float, default 1e-9
        Singular values at most ``rtol`` times the largest count as zero.
    length_scale : float or None
        See the module docstring.

    Returns
    -------
    int or numpy.ndarray of int
        Batched over leading axes when numeric. The symbolic rank is the *generic* rank, decided
        exactly at a random rational point (Schwartz–Zippel, :mod:`screwkit.algebra.symbolic`): it says
        nothing about special values of the symbols.

    Examples
    --------
    >>> screw_rank(np.zeros((0, 6)))
    0
    """
    checked_rtol(rtol)
    if rows.dtype == object:
        from . import symbolic_bases

        return symbolic_bases.generic_rank(rows.reshape(-1, rows.shape[-1])) if rows.size else 0
    if rows.shape[-2] == 0:
        return 0 if rows.ndim == 2 else np.zeros(rows.shape[:-2], dtype=int)
    values = screw_singular_values(rows, length_scale=_numeric_length(rows, length_scale, rtol))
    largest = values[..., :1]
    counted = (values > rtol * largest) & (largest > 0)
    result = counted.sum(axis=-1)
    return int(result) if np.ndim(result) == 0 else result


#: ``a ∘ b = a · (SWAP b)``: the reciprocal product as a Euclidean one (read-only).
SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])
SWAP.flags.writeable = False


def screw_nullspace(
    rows: Array,
    *,
    rtol: float = DEFAULT_RTOL,
    length_scale: float | None = None,
) -> Array:
    """Basis of the screws reciprocal to every row of ``rows`` (shape ``(k, 6)``).

    Parameters
    ----------
    rows : numpy.ndarray, shape (k, 6)
    rtol, length_scale
        As in :func:`screw_rank`.

    Returns
    -------
    numpy.ndarray, shape (6 - rank, 6)
        Numeric rows are an orthonormal basis in scaled coordinates, mapped back to the caller's
        unit; symbolic rows the generic null space (:func:`matrix_nullspace`).

    Examples
    --------
    >>> screw_nullspace(np.array([[0.0, 0, 0, 0, 0, 1]])).shape
    (5, 6)
    """
    checked_rtol(rtol)
    if rows.dtype == object:
        if rows.shape[0] == 0:
            return np.array(sympy_module().eye(6).tolist(), dtype=object)
        return matrix_nullspace(rows @ SWAP.astype(int), rtol=rtol)
    if rows.shape[0] == 0:
        return np.eye(6)
    length = _numeric_length(rows, length_scale, rtol)
    basis = matrix_nullspace(unit_rows(rows, length) @ SWAP, rtol=rtol)
    # In scaled coordinates x' = (x_s; x_m / L); reciprocity a∘x = L (a'∘x') is preserved.
    basis[:, 3:] *= length
    return basis


def screw_image_of_nullspace(
    mapping: Array, constraints: Array, *, rtol: float, length_scale: float
) -> Array:
    """The screws ``mapping @ x`` for ``x`` in the null space of ``constraints``: e.g. the platform
    twists a loop-closure matrix allows, with ``mapping`` the joint screws along a path to it.

    Parameters
    ----------
    mapping : numpy.ndarray, shape (6, n)
        Screw columns.
    constraints : numpy.ndarray, shape (6 m, n)
        Stacked screw rows (m blocks of 6; m may be 0).
    rtol : float
    length_scale : float
        Moments are divided by it before any numeric decision (module docstring).

    Returns
    -------
    numpy.ndarray, shape (k, 6)
        Numeric: an orthogonal basis of the image in scaled coordinates, moments scaled back. Columns
        are scaled to unit size first, and the image's rank is decided relative to the size of the
        mapping's columns, not to the image itself: internal motions (a rod spinning between two S
        joints) map to round-off, not to a screw. Symbolic: the images of an exact (generic) null
        space basis, not reduced to a basis.

    Examples
    --------
    >>> spin = np.array([[0.0], [0], [1], [0], [0], [0]])  # a free rotation about z, no loop
    >>> screw_image_of_nullspace(spin, np.zeros((0, 1)), rtol=1e-9, length_scale=1.0)
    array([[0., 0., 1., 0., 0., 0.]])
    """
    checked_rtol(rtol)
    n = mapping.shape[1]
    if mapping.dtype == object or constraints.dtype == object:
        rates = (
            matrix_nullspace(constraints, rtol=rtol)
            if constraints.shape[0]
            else np.eye(n, dtype=int) + zeros((n, n), symbolic=True)
        )
        return (mapping @ rates.T).T
    scaled = constraints.copy()
    scaled.reshape(-1, 6, n)[:, 3:, :] /= length_scale
    scaled_mapping = mapping.copy()
    scaled_mapping[3:] /= length_scale
    column_norm = np.linalg.norm(np.vstack([scaled, scaled_mapping]), axis=0)
    scaled = scaled.reshape(-1, n) if scaled.size else np.zeros((0, n))
    column_norm[column_norm == 0] = 1.0
    scaled_mapping = scaled_mapping / column_norm
    rates = matrix_nullspace(scaled / column_norm, rtol=rtol)  # orthonormal, in scaled coordinates
    u, values, _ = np.linalg.svd(scaled_mapping @ rates.T, full_matrices=False)
    keep = values > rtol * np.linalg.norm(scaled_mapping, 2)
    image = (u[:, keep] * values[keep]).T
    image[:, 3:] *= length_scale
    return image


def matrix_nullspace(matrix: Array, *, rtol: float = DEFAULT_RTOL) -> Array:
    """Basis of ``{x : matrix @ x = 0}`` as rows, for any ``(m, n)`` matrix.

    Numeric: the right singular vectors whose singular values are at most ``rtol`` times the
    largest (an orthonormal basis). Symbolic: the generic null space by Cramer's rule on a pivot
    block chosen at an exact random point (:mod:`screwkit.algebra.symbolic`), each vector primitive. The
    caller
    scales rows beforehand if they carry different units (row scaling keeps the null space).

    Parameters
    ----------
    matrix : array_like, shape (m, n)
        Float or sympy entries.
    rtol : float, default 1e-9
        Singular values below ``rtol`` times the largest count as zero (numeric).

    Returns
    -------
    numpy.ndarray, shape (n - rank, n)

    Examples
    --------
    >>> matrix_nullspace(np.array([[1.0, 1.0]]))
    array([[-0.70710678,  0.70710678]])
    """
    checked_rtol(rtol)
    if matrix.dtype == object:
        from . import symbolic_bases

        return symbolic_bases.nullspace(matrix)
    if matrix.shape[0] == 0:
        return np.eye(matrix.shape[1])
    _, values, vt = np.linalg.svd(matrix)
    rank = int(((values > rtol * values[:1]) & (values[:1] > 0)).sum())
    return vt[rank:].copy()
