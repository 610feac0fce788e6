"""Batched orthonormal frames of screw systems: the arithmetic under every pose (private).

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

**Closed forms.** Where a system is known in closed form the core uses it instead of a span and a
complement: two spherical joints in series transmit the force along the line through their
centres (:func:`rod`; paper 002 §4.1 models each H4 rod so), with the rule as the fallback where
that line is not clearly defined.

**Two implementations, one rule.** :func:`span`, :func:`complement`, :func:`reciprocal`,
:func:`residual`, :func:`rod`, :func:`unit_scaled` and :func:`singular_ratio` have a numpy path
(vectorized over the batch) and, when numba is installed (the ``fast`` extra), compiled per-pose
loops (:mod:`screwkit._frames_numba`) that follow the same rule and agree with the numpy path up
to round-off. The analysis core strings spans, reciprocals and rods into one flat *program* per
mechanism (:func:`screwkit.wrenches._program`): on the numba path one compiled call runs it pose
by pose (:func:`screwkit._frames_numba.run_program`, the same per-pose loops), on the numpy path
its ops run one by one over the batch. The choice is made once per process and never
depends on the batch size, so single-pose and batched answers stay bit-identical. numba is
imported on the first kernel call, not with :mod:`screwkit`; its compiled code is cached on disk.
The environment variable ``SCREWKIT_NUMBA``, read once when this module is imported, forces the
choice: ``0`` (or ``false``, ``no``, ``off``) the numpy path, anything else the default (numba if
it imports).

Examples
--------
>>> import numpy as np
>>> rows, order = span(np.array([[[1.0, 0, 0, 0, 0, 0], [2.0, 0, 0, 0, 0, 0]]]), 1e-9)
>>> order
array([1])
>>> reciprocal(rows, order)[1]
array([5])
"""

from __future__ import annotations

import importlib.util
import os
from types import ModuleType

import numpy as np

__all__ = [
    "SWAP",
    "complement",
    "empty",
    "from_scaled",
    "reciprocal",
    "residual",
    "rod",
    "singular_ratio",
    "span",
    "swapped",
    "to_scaled",
    "unit_scaled",
]

Array = np.ndarray

#: ``a ∘ b = a · (SWAP b)``: the reciprocal product as a Euclidean one.
SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])
SWAP.flags.writeable = False

#: ``SCREWKIT_NUMBA=0`` forces the numpy path (read once, here).
_NUMBA_WANTED = os.environ.get("SCREWKIT_NUMBA", "1").strip().lower() not in {"0", "false", "no", "off"}
_compiled: dict[str, ModuleType | None] = {}


def compiled_kernels(name: str) -> ModuleType | None:
    """The numba kernel module ``screwkit.<name>``, imported on first use; None for the numpy path.

    One rule for every compiled path, decided once per process and module: numba if it is installed
    and ``SCREWKIT_NUMBA`` is not ``0`` (a broken numba install falls back to numpy for good).
    """
    if name not in _compiled:
        module = None
        if _NUMBA_WANTED and importlib.util.find_spec("numba") is not None:
            try:
                module = importlib.import_module(f"{__package__}.{name}")
            except ImportError:  # a broken numba install: the numpy path, for the whole process
                module = None
        _compiled[name] = module
    return _compiled[name]


def _numba_kernels() -> ModuleType | None:
    """The rank kernels (:mod:`screwkit._frames_numba`) or None for the numpy path."""
    return compiled_kernels("_frames_numba")


def _import_kernels() -> ModuleType:
    """The numba kernels, whatever this process's choice (the numba path; tests call it directly)."""
    from . import _frames_numba

    return _frames_numba


def backend() -> str:
    """``"numba"`` or ``"numpy"``: the implementation the kernels use in this process.

    Examples
    --------
    >>> backend() in {"numba", "numpy"}
    True
    """
    return "numpy" if _numba_kernels() is None else "numba"


def to_scaled(screws: Array, centre: Array, length: Array) -> Array:
    """Screws ``(..., k, 6)`` about ``centre`` ``(..., 3)`` with moments over ``length`` ``(...)``.

    Examples
    --------
    >>> to_scaled(np.array([[0, 0, 1.0, 2.0, 0, 0]]), np.array([0, 2.0, 0]), np.array(2.0))
    array([[0., 0., 1., 0., 0., 0.]])
    """
    directions = screws[..., :3]
    moments = screws[..., 3:] - np.cross(centre[..., None, :], directions)
    return np.concatenate([directions, moments / length[..., None, None]], axis=-1)


def unit_scaled(screws: Array, centre: Array, length: Array) -> Array:
    """:func:`to_scaled` with every row divided by its norm (zero rows stay zero): the generators
    of the analysis core. One compiled loop on the numba path.

    Examples
    --------
    >>> unit_scaled(np.array([[0, 0, 2.0, 0, 0, 0]]), np.zeros(3), np.array(1.0))
    array([[0., 0., 1., 0., 0., 0.]])
    """
    kernels = _numba_kernels()
    batch = screws.shape[:-2]
    if kernels is None or 0 in batch or screws.shape[-2] == 0:
        rows = to_scaled(screws, centre, length)
        size = np.linalg.norm(rows, axis=-1, keepdims=True)
        return rows / np.where(size > 0, size, 1.0)
    flat = np.ascontiguousarray(screws.reshape(-1, *screws.shape[-2:]), dtype=float)
    centres = np.ascontiguousarray(np.broadcast_to(centre, (*batch, 3)).reshape(-1, 3), dtype=float)
    lengths = np.ascontiguousarray(np.broadcast_to(length, batch).reshape(-1), dtype=float)
    return kernels.unit_scaled(flat, centres, lengths).reshape(screws.shape)


def from_scaled(rows: Array, centre: Array, length: Array) -> Array:
    """The inverse of :func:`to_scaled`: rows ``(..., k, 6)`` back to the user's frame and unit.

    Examples
    --------
    >>> from_scaled(np.array([[0, 0, 1.0, 0, 0, 0]]), np.array([0, 2.0, 0]), np.array(2.0))
    array([[0., 0., 1., 2., 0., 0.]])
    """
    directions = rows[..., :3]
    moments = rows[..., 3:] * length[..., None, None] + np.cross(centre[..., None, :], directions)
    return np.concatenate([directions, moments], axis=-1)


def swapped(rows: Array) -> Array:
    """``rows (..., 6)`` with their halves exchanged: ``SWAP`` applied exactly (no BLAS call, whose
    kernels, and so whose last bits, depend on the batch size).

    Examples
    --------
    >>> swapped(np.arange(6.0))
    array([3., 4., 5., 0., 1., 2.])
    """
    return np.concatenate([rows[..., 3:], rows[..., :3]], axis=-1)


def empty(batch: tuple[int, ...]) -> tuple[Array, Array]:
    """The frame of the 0-system over a batch.

    Examples
    --------
    >>> empty((2,))[1]
    array([0, 0])
    """
    return np.zeros((*batch, 6, 6)), np.zeros(batch, dtype=int)


def _project_out(vectors: Array, rows: Array) -> Array:
    """``vectors (..., k, 6)`` minus their projections on the orthonormal (or zero) ``rows``."""
    coefficients = np.einsum("...ks,...rs->...kr", vectors, rows)
    return vectors - np.einsum("...kr,...rs->...ks", coefficients, rows)


def span(generators: Array, rtol: float) -> tuple[Array, Array]:
    """The frame of the system spanned by ``generators`` ``(..., k, 6)`` (the module's rank rule).

    Examples
    --------
    >>> rows, order = span(np.array([[1.0, 0, 0, 0, 0, 0], [1.0, 1e-12, 0, 0, 0, 0]]), 1e-9)
    >>> int(order), rows[0]
    (1, array([1., 0., 0., 0., 0., 0.]))
    """
    return (_span_numpy if _numba_kernels() is None else _span_numba)(generators, rtol)


def _span_numba(generators: Array, rtol: float) -> tuple[Array, Array]:
    """:func:`span` by the compiled per-pose loop."""
    work = np.array(generators, dtype=float)
    batch, k = work.shape[:-2], work.shape[-2]
    if k == 0 or 0 in batch:
        return empty(batch)
    kernels = _numba_kernels() or _import_kernels()
    rows, order = kernels.span(np.ascontiguousarray(work.reshape(-1, k, 6)), float(rtol))
    return rows.reshape(*batch, 6, 6), order.reshape(batch)


def _span_numpy(generators: Array, rtol: float) -> tuple[Array, Array]:
    """:func:`span` vectorized over the batch with numpy."""
    work = np.array(generators, dtype=float)
    batch = work.shape[:-2]
    rows, order = empty(batch)
    if work.shape[-2] == 0:
        return rows, order
    norms = np.sqrt(np.einsum("...ks,...ks->...k", work, work))
    threshold = rtol * norms.max(axis=-1)
    active = np.ones(batch, dtype=bool)
    for step in range(min(work.shape[-2], 6)):
        pick = np.argmax(norms, axis=-1)
        pivot = np.take_along_axis(work, pick[..., None, None], axis=-2)[..., 0, :]
        pivot = pivot - np.einsum(
            "...r,...rs->...s", np.einsum("...rs,...s->...r", rows, pivot), rows
        )  # CGS2
        size = np.sqrt(np.einsum("...s,...s->...", pivot, pivot))
        active &= (size > threshold) & (size > 0)
        unit = np.where(active[..., None], pivot / np.where(size > 0, size, 1.0)[..., None], 0.0)
        rows[..., step, :] = unit
        order += active
        work = work - np.einsum("...ks,...s->...k", work, unit)[..., None] * unit[..., None, :]
        norms = np.sqrt(np.einsum("...ks,...ks->...k", work, work))
    return rows, order


def complement(rows: Array, order: Array) -> tuple[Array, Array]:
    """An orthonormal frame of the orthogonal complement of a frame (order ``6 − order``).

    The complete Householder QR of the frame's rows as columns: its first ``order`` columns span
    the frame, the others its complement (no rank decision is made).

    Examples
    --------
    >>> rows, order = complement(np.diag([1.0, 0, 0, 0, 0, 0]), np.array(1))
    >>> int(order), float(np.abs(rows[:5, 0]).max()), float(np.abs(rows[5]).max())
    (5, 0.0, 0.0)
    """
    return (_complement_numpy if _numba_kernels() is None else _complement_numba)(rows, order)


def _complement_numba(rows: Array, order: Array, *, swap: bool = False) -> tuple[Array, Array]:
    """:func:`complement` (or, with ``swap``, :func:`reciprocal`) by the compiled per-pose loop."""
    rows = np.asarray(rows, dtype=float)
    order = np.asarray(order)
    batch = rows.shape[:-2]
    if 0 in batch:
        return np.zeros((*batch, 6, 6)), 6 - order
    flat_order = np.ascontiguousarray(np.broadcast_to(order, batch).reshape(-1), dtype=np.int64)
    kernels = _numba_kernels() or _import_kernels()
    out = kernels.complement(np.ascontiguousarray(rows.reshape(-1, 6, 6)), flat_order, swap)
    return out.reshape(*batch, 6, 6), 6 - order


def _complement_numpy(rows: Array, order: Array) -> tuple[Array, Array]:
    """:func:`complement` by numpy's batched complete QR."""
    q = np.linalg.qr(np.swapaxes(rows, -1, -2), mode="complete")[0]  # (..., 6, 6), columns
    wanted = 6 - order
    index = order[..., None] + np.arange(6)  # row k of the complement is column order + k of q
    picked = np.take_along_axis(np.swapaxes(q, -1, -2), np.minimum(index, 5)[..., None], axis=-2)
    return np.where((index < 6)[..., None], picked, 0.0), wanted


def reciprocal(rows: Array, order: Array) -> tuple[Array, Array]:
    """The frame of the reciprocal system: ``SWAP`` applied to the complement.

    Examples
    --------
    >>> line = np.zeros((6, 6)); line[0, 2] = 1.0           # the z axis through the reference point
    >>> rows, order = reciprocal(line, np.array(1))
    >>> int(order), bool(np.abs(rows[:5] @ SWAP @ line[0]).max() < 1e-15)
    (5, True)
    """
    if _numba_kernels() is None:
        out, wanted = _complement_numpy(rows, order)
        return swapped(out), wanted
    return _complement_numba(rows, order, swap=True)


def rod(rows: Array, rtol: float) -> tuple[Array, Array]:
    """The reciprocal of the span of two spherical joints in series, rows ``(..., 6, 6)`` (three
    concurrent axes each, scaled): in closed form, the unit line through the two centres
    (order 1), where it applies; elsewhere (a joint's axes without a common point, centres not
    more than ``√rtol`` apart, or the line not reciprocal to every axis within ``rtol``)
    :func:`reciprocal` of :func:`span`. The numpy path of
    :func:`screwkit._frames_numba.rod_into` (which the compiled programs run).

    Each centre is the least-squares point of its axes, ``N⁻¹ Σ f`` with ``N = Σ (I − û ûᵀ)`` and
    ``f = u × m / |u|²`` the feet (by the adjugate of ``N``).

    Examples
    --------
    >>> sphere = lambda c: [[*e, *np.cross(c, e)] for e in np.eye(3)]
    >>> rows, order = rod(np.array(sphere([0, 0, 0.0]) + sphere([0, 0, 1.0])), 1e-9)
    >>> int(order), rows[0] + 0.0
    (1, array([0., 0., 1., 0., 0., 0.]))
    """
    rows = np.asarray(rows, dtype=float)
    u, m = rows[..., :3], rows[..., 3:]
    squared = np.einsum("...i,...i->...", u, u)
    good = np.all(squared > 0, axis=-1)
    squared = np.where(squared > 0, squared, 1.0)
    feet = np.cross(u, m) / squared[..., None]
    eye = np.eye(3)
    projectors = eye - u[..., :, None] * u[..., None, :] / squared[..., None, None]
    centres = []
    for joint in (slice(0, 3), slice(3, 6)):
        normal = projectors[..., joint, :, :].sum(axis=-3)
        b = feet[..., joint, :].sum(axis=-2)
        n0, n1, n2 = normal[..., 0, :], normal[..., 1, :], normal[..., 2, :]
        adjugate = np.stack([np.cross(n1, n2), np.cross(n2, n0), np.cross(n0, n1)], axis=-1)
        det = np.einsum("...i,...i->...", n0, adjugate[..., :, 0])
        good &= det > 0
        centres.append(np.einsum("...ij,...j->...i", adjugate, b) / np.where(det > 0, det, 1.0)[..., None])
    d = centres[1] - centres[0]
    good &= np.linalg.norm(d, axis=-1) > np.sqrt(rtol)
    line = np.concatenate([d, np.cross(centres[0], d)], axis=-1)
    size = np.linalg.norm(line, axis=-1, keepdims=True)
    line = line / np.where(size > 0, size, 1.0)
    products = np.einsum("...s,...ks->...k", line, swapped(rows))
    good &= np.all(np.abs(products) <= rtol, axis=-1)
    out, order = empty(rows.shape[:-2])
    out[..., 0, :] = np.where(good[..., None], line, 0.0)
    order = np.where(good, 1, order)
    bad = ~good
    if bad.any():
        frame = reciprocal(*span(rows[bad], rtol))
        out[bad], order[bad] = frame
    return out, order


def residual(vectors: Array, rows: Array) -> Array:
    """``vectors (..., k, 6)`` minus their projections on a frame's rows (re-orthogonalised once).

    Examples
    --------
    >>> residual(np.array([[1.0, 1.0, 0, 0, 0, 0]]), np.eye(6)[:1])
    array([[0., 1., 0., 0., 0., 0.]])
    """
    return (_residual_numpy if _numba_kernels() is None else _residual_numba)(vectors, rows)


def _residual_numba(vectors: Array, rows: Array) -> Array:
    """:func:`residual` by the compiled per-pose loop."""
    vectors, rows = np.asarray(vectors, dtype=float), np.asarray(rows, dtype=float)
    batch = np.broadcast_shapes(vectors.shape[:-2], rows.shape[:-2])
    k, m = vectors.shape[-2], rows.shape[-2]
    if 0 in batch or k == 0:
        return np.zeros((*batch, k, 6))
    flat_vectors = np.ascontiguousarray(np.broadcast_to(vectors, (*batch, k, 6)).reshape(-1, k, 6))
    flat_rows = np.ascontiguousarray(np.broadcast_to(rows, (*batch, m, 6)).reshape(-1, m, 6))
    return (_numba_kernels() or _import_kernels()).residual(flat_vectors, flat_rows).reshape(*batch, k, 6)


def _residual_numpy(vectors: Array, rows: Array) -> Array:
    """:func:`residual` vectorized over the batch with numpy."""
    return _project_out(_project_out(vectors, rows), rows)


def singular_ratio(rows: Array, index: int) -> Array:
    """``σ_index / σ_1`` of rows ``(..., k, 6)`` (1 for ``index ≤ 0``, 0 when ``k < index``).

    numpy's SVD, or on the numba path one-sided Jacobi rotations of the non-zero rows
    (:func:`screwkit._frames_numba.singular_ratio`); the two agree up to round-off.

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
    kernels = _numba_kernels()
    if kernels is not None and 0 not in batch:
        flat = np.ascontiguousarray(rows.reshape(-1, *rows.shape[-2:]), dtype=float)
        return kernels.singular_ratio(flat, int(index)).reshape(batch)
    values = np.linalg.svd(rows, compute_uv=False)
    top = values[..., 0]
    return np.where(top > 0, values[..., index - 1] / np.where(top > 0, top, 1.0), 0.0)
