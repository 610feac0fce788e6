"""Readable bases of many numeric screw systems at once, over a leading axis.

:meth:`screwkit.algebra.screwsystem.ScrewSystem.readable_basis` takes about a millisecond a system; a
condition map reads the constraint couples of a Delta's or a 3-UPU's legs at thousands of poses.
:func:`readable_bases` gives each system of a batch the basis ``readable_basis`` gives it: the same
rank decisions, the same rows to round-off (``~1e-16``). Systems of couples (directions that are
round-off: the structure of their readable basis is known) go through the method's own steps on
arrays over the batch; every other system, and every system where a decision taken over the
batch could come out the other way near its threshold, goes through ``readable_basis`` itself.

For a system of couples ``readable_basis`` takes (its docstring's steps 1 and 4): the couple
subsystem as the reciprocal of the reciprocal (two null spaces of unit rows), its moments
orthonormalised by an SVD, the frame's axes in their span first (Gram–Schmidt after them), each
row a unit couple. The batch takes those steps on the same arrays in the same order, with numpy's
batched linear algebra (the same LAPACK calls matrix by matrix: the same bits, tested). For one
couple (a Delta's or a 3-UPU's leg) the reciprocal of the reciprocal is the couple itself up to
sign and round-off, and the SVD of a ``1 × 3`` row ``a`` reduces it by one Householder reflector,
whose first row is ``a / β`` with ``β = −sign(a₁) |a|`` (Golub and Van Loan, *Matrix
Computations*, 4th ed., 2013, §5.1.2; LAPACK's ``dlarfg``), the ``1 × 1`` singular value's sign
going to ``u``: ``vt = −sign(a₁) a / |a|``, the same for ``a`` and ``−a``. The batch takes that
closed form (checked once against numpy's SVD) where the first coordinate is clearly non-zero;
where round-off decides its sign, the null spaces are taken.

Examples
--------
>>> couples = np.array([[[0.0, 0, 0, 0, 0, 2.0]], [[0.0, 0, 0, 3.0, -4.0, 0]]])
>>> readable_bases(couples, [1, 1], rtol=1e-9, length_scale=[1.0, 1.0]) + 0.0
array([[[ 0. ,  0. ,  0. ,  0. ,  0. ,  1. ]],
<BLANKLINE>
       [[ 0. ,  0. ,  0. , -0.6,  0.8,  0. ]]])
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from .checks import checked_rtol
from .ranks import SWAP, unit_rows
from .screwsystem import ScrewSystem
from .zero_tests import _binary_exponents

__all__ = ["readable_bases"]

Array = np.ndarray
#: The tolerances the batch decides at; outside, every system goes through ``readable_basis`` (the
#: margins below assume that ``rtol`` is far above round-off and far below 1).
RTOL_RANGE = (1e-12, 1e-6)
#: A decision is taken over the batch only where its value is this factor away from its threshold.
MARGIN = 4.0
#: A bound on the round-off of the reciprocal rows (two SVDs of unit rows, ``~1e-15``).
ROUND_OFF = 1e-13
#: The least first coordinate of a single couple's unit moment whose sign the null spaces keep.
CLEAR = 1e-6
#: ``|e − v (v·e)|² = Σ_{j ≠ i} v_j²`` for the frame's axes ``e_i`` and a unit ``v``: the squares' sums.
_OTHER_AXES = 1.0 - np.eye(3)


def readable_bases(rows: Any, orders: Any, *, rtol: float, length_scale: Any) -> Array:
    """The readable basis of each of ``n`` numeric screw systems, as ``readable_basis`` gives it.

    Parameters
    ----------
    rows : array_like, shape (n, m, 6)
        Each system's independent basis in its first ``orders[i]`` rows (the rest is not read).
    orders : array_like of int, shape (n,)
        Each system's order, at most ``m``.
    rtol : float
        The systems' relative tolerance.
    length_scale : array_like, shape (n,)
        Each system's characteristic length.

    Returns
    -------
    numpy.ndarray, shape (n, m, 6)
        Row ``i`` holds ``ScrewSystem.from_independent(rows[i, :orders[i]], rtol=rtol,
        length_scale=length_scale[i]).readable_basis()`` in its first ``orders[i]`` rows, NaN after.

    Raises
    ------
    ScrewkitValueError
        For arrays of other shapes, orders outside ``[0, m]``, rows that are not finite, a length
        scale that is not positive and finite, or an ``rtol`` out of range.

    Examples
    --------
    >>> two = np.array([[[0.0, 0, 0, 1.0, 1.0, 0], [0.0, 0, 0, 1.0, -1.0, 0]]])
    >>> readable_bases(two, [2], rtol=1e-9, length_scale=[1.0]) + 0.0
    array([[[0., 0., 0., 1., 0., 0.],
            [0., 0., 0., 0., 1., 0.]]])
    """
    checked_rtol(rtol)
    rows = np.asarray(rows, dtype=float)
    orders = np.asarray(orders)
    length = np.asarray(length_scale, dtype=float)
    if rows.ndim != 3 or rows.shape[2] != 6 or orders.shape != rows.shape[:1] or length.shape != orders.shape:
        raise ScrewkitValueError(
            "Expected `rows` of shape (n, m, 6) with `orders` and `length_scale` of shape (n,), got "
            f"{rows.shape}, {orders.shape} and {length.shape}."
        )
    if not (np.issubdtype(orders.dtype, np.integer) and np.all((orders >= 0) & (orders <= rows.shape[1]))):
        raise ScrewkitValueError(f"Expected `orders` to be integers in [0, {rows.shape[1]}], got {orders}.")
    if not np.isfinite(rows).all():
        raise ScrewkitValueError("Expected finite `rows`, got NaN or infinite entries.")
    if not (np.isfinite(length).all() and np.all(length > 0)):
        raise ScrewkitValueError(f"Expected `length_scale` to be positive and finite, got {length}.")
    found = np.full(rows.shape, np.nan)
    done = orders == 0
    if RTOL_RANGE[0] <= rtol <= RTOL_RANGE[1]:
        for order in (1, 2, 3):  # a system of couples has at most three
            index = np.flatnonzero(orders == order)
            if order == 1 and index.size:  # one couple: in closed form where its first coordinate is clear
                basis, taken = _one_couple(rows[index, 0], rtol, length[index])
                found[index[taken], 0] = basis[taken]
                done[index[taken]] = True
                index = index[~taken]
            if index.size:
                basis, taken = _couples(rows[index, :order], rtol, length[index])
                found[index[taken], :order] = basis[taken]
                done[index[taken]] = True
    for i in np.flatnonzero(~done):
        system = ScrewSystem.from_independent(rows[i, : orders[i]], rtol=rtol, length_scale=float(length[i]))
        found[i, : orders[i]] = system.readable_basis()
    return found


def _one_couple(rows: Array, rtol: float, length: Array) -> tuple[Array, Array]:
    """The readable bases ``(p, 6)`` of systems of one couple ``(p, 6)``, and where they are those
    of ``readable_basis``: the SVD's unit moment ``−sign(m₁) m / |m|`` (module docstring) where
    its first coordinate is clear, the frame's axis it lies along within ``1e3 rtol``, else that."""
    directions, moments = rows[:, :3], rows[:, 3:]
    size = np.hypot(np.hypot(moments[:, 0], moments[:, 1]), moments[:, 2])  # no square overflows
    direction = np.hypot(np.hypot(directions[:, 0], directions[:, 1]), directions[:, 2])
    # the unit row's direction (its size bounds every rank decision the directions enter)
    whole = np.hypot(size / length, direction)
    spread = direction / np.where(whole > 0, whole, 1.0)
    clear = (size > 0) & (np.abs(moments[:, 0]) >= CLEAR * size) & _svd_of_a_row_is_householder()
    vector = moments * (-np.sign(moments[:, :1]) / np.where(size > 0, size, 1.0)[:, None])
    gaps = np.sqrt((vector * vector) @ _OTHER_AXES)  # |e − v (v·e)| for the frame's axes e
    threshold = 1e3 * rtol
    inside = gaps <= threshold
    along = inside.any(axis=-1)
    couple = np.where(along[:, None], inside, vector)  # the axis itself (at most one within 1e3 rtol)
    taken = clear & np.all((gaps * MARGIN <= threshold) | (gaps > MARGIN * threshold), axis=-1)
    taken &= spread + ROUND_OFF <= rtol / MARGIN
    taken &= spread + np.where(along, gaps.min(axis=-1), 0.0) + ROUND_OFF <= min(threshold, 1e-3) / MARGIN
    couple = couple / np.linalg.norm(couple, axis=-1)[:, None]
    return np.concatenate([np.zeros_like(couple), couple], axis=-1), taken


@functools.lru_cache(maxsize=1)
def _svd_of_a_row_is_householder() -> bool:
    """Whether numpy's SVD of a row ``a`` ``(1 × 3)`` gives ``vt = −sign(a₁) a / |a|`` (LAPACK's
    Householder reflector ``a / β`` with ``β = −sign(a₁) |a|``; the ``1 × 1`` singular value's sign
    goes to ``u``), checked once on rows of every sign pattern; else one couple takes the steps."""
    rows = np.random.default_rng(0).normal(size=(64, 1, 3))
    expected = -np.sign(rows[:, :, :1]) * rows / np.linalg.norm(rows, axis=-1, keepdims=True)
    return bool(np.allclose(np.linalg.svd(rows)[2][:, :1], expected, rtol=0.0, atol=1e-12))


def _couples(rows: Array, rtol: float, length: Array) -> tuple[Array, Array]:
    """The readable bases ``(p, k, 6)`` of systems of ``k`` couples, and where the batch's
    decisions are those of ``readable_basis`` (False: a direction that is not round-off, or a
    decision near its threshold): the method's steps, on the same arrays in the same order."""
    order = rows.shape[1]
    lengths = length[:, None, None]
    scaled = np.ldexp(rows, -_binary_exponents(rows))  # as readable_basis: each row times a power of 2
    sizes = np.linalg.norm(np.concatenate([scaled[..., :3], scaled[..., 3:] / lengths], axis=-1), axis=-1)
    # the directions of the unit rows: their Frobenius norm bounds the singular values (no finite
    # candidate, no axes centre: the eigenvalues of Σ(|s|² I − s sᵀ) are at most its square)
    spread = np.linalg.norm(scaled[..., :3] / np.where(sizes > 0, sizes, 1.0)[..., None], axis=(-2, -1))
    # the couple subsystem (self.reciprocal() + couples).reciprocal(), as readable_basis takes it
    reciprocal, values, decided = _null_space(scaled, order, rtol, length)
    couples, _, decided_again = _null_space(reciprocal, 6 - order, rtol, length)
    orthonormal = np.linalg.svd(couples[..., 3:])[2][:, :order]
    # the couples lie in the reciprocal rows' span within the rows' directions (and round-off)
    # over their conditioning: the sum with the couples adds no dimension to the reciprocal
    conditioning = values[:, 0] / values[:, -1]
    taken = (sizes > 0).all(axis=-1) & decided & decided_again
    taken &= (spread + ROUND_OFF) * conditioning <= rtol / MARGIN
    axes, placed = _axis_first(orthonormal, rtol)
    taken &= placed
    # _pick: the couples are the first independent candidates when the rows lie in their span
    unit = unit_rows(scaled, lengths)
    along = np.einsum("pjc,pic->pji", unit[..., 3:], axes)
    outside = np.concatenate([unit[..., :3], unit[..., 3:] - along @ axes], axis=-1)
    residual = np.linalg.norm(outside, axis=(-2, -1))  # bounds the (k+1)-th singular value
    taken &= residual <= min(1e3 * rtol, 1e-3) / MARGIN
    picked = np.concatenate([np.zeros_like(axes), axes], axis=-1)
    return picked / np.linalg.norm(picked[..., 3:], axis=-1)[..., None], taken


def _null_space(rows: Array, rank: int, rtol: float, length: Array) -> tuple[Array, Array, Array]:
    """:func:`screwkit.algebra.ranks.screw_nullspace` of each system ``(p, r, 6)`` of rank ``rank``:
    the reciprocal rows ``(p, 6 - rank, 6)``, the singular values of the unit rows and whether
    the rank is clear of the threshold ``rtol``."""
    matrix = np.matmul(unit_rows(rows, length[:, None, None]), SWAP)
    _, values, vt = np.linalg.svd(matrix)
    decided = values[:, rank - 1] > MARGIN * rtol * values[:, 0]
    if rank < values.shape[1]:
        decided &= values[:, rank] * MARGIN < rtol * values[:, 0]
    basis = vt[:, rank:].copy()
    basis[..., 3:] *= length[:, None, None]
    return basis, values, decided


def _dot(a: Array, b: Array) -> Array:
    """Row-wise ``a @ b`` of ``(p, 3)`` rows, as one pose's ``a @ b`` takes it."""
    return np.matmul(a[:, None, :], b[:, :, None])[:, 0, 0]


def _axis_first(moments: Array, rtol: float) -> tuple[Array, Array]:
    """``readable._axis_first`` of orthonormal moments ``(p, k, 3)``: the frame's axes in their span
    first, then Gram–Schmidt; and where no decision lies within :data:`MARGIN` of ``1e3 rtol``."""
    count, order = len(moments), moments.shape[1]
    threshold = 1e3 * rtol
    projector = np.matmul(np.swapaxes(moments, -1, -2), moments)
    chosen = np.zeros((count, 3 + order, 3))  # unused slots stay 0: subtracting them changes nothing
    filled = np.zeros(count, dtype=int)
    clear = np.ones(count, dtype=bool)
    for axis in np.eye(3):
        gap = axis - np.matmul(projector, axis)
        gap = np.sqrt(_dot(gap, gap))
        clear &= (gap * MARGIN <= threshold) | (gap > MARGIN * threshold)
        inside = gap <= threshold
        chosen[inside, filled[inside]] = axis
        filled += inside
    for k in range(order):
        row = moments[:, k]
        for slot in range(3 + k):
            picked = chosen[:, slot]
            row = row - _dot(row, picked)[:, None] * picked
        size = np.sqrt(_dot(row, row))
        room = filled < order
        clear &= ~room | (size * MARGIN <= threshold) | (size > MARGIN * threshold)
        new = room & (size > threshold)
        chosen[new, filled[new]] = row[new] / size[new, None]
        filled += new
    return chosen[:, :order], clear & (filled >= order)
