"""numba kernels of the loop-closure continuation (:mod:`screwkit.core.loop_closure`; private).

Pose by pose, the work its numpy twins do over the batch: the product of exponentials of a
kinematic model (:meth:`screwkit.core._batched_poe.BatchedProduct.evaluate`), the loops' residual
(:meth:`screwkit.core.kinematic_model.KinematicModel.loop_residual`) and the Newton corrector of one
continuation step on the loops of a model pinned to its platform, block by block
(``screwkit.core.loop_closure._PinnedLoops``). The formulas are theirs (Murray, Li & Sastry, *A
Mathematical Introduction to Robotic Manipulation*, 1994, Eqs. 2.14, 2.36, 2.58; the inverse of
Rodrigues' formula, Eqs. 2.17-2.18; the minimum-norm Gauss-Newton correction ``−Jᵀ (J Jᵀ + λ I)⁻¹ F``,
Nocedal & Wright, *Numerical Optimization*, 2nd ed., 2006, §10.3). The order of the operations differs
(a Cholesky factorisation where numpy calls LAPACK's LU, the Gram matrix ``J Jᵀ`` summed column by
column from the screws' outer products, which skips the zeros of the loops' Jacobian), so the two
paths agree to round-off, not bit for bit (``tests/core/test_newton_kernels.py``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._newton_steps_numba import cholesky_solve, damped_cholesky, took_correction

__all__ = ["bordered_orientation", "evaluate", "loop_residual", "pinned_newton"]

Array = np.ndarray


@njit(cache=True, inline="always")
def _compose(a: Array, b: Array, out: Array) -> None:  # pragma: no cover - compiled
    """``out = a b`` of rigid displacements (4 × 4, last row ``0 0 0 1``)."""
    for i in range(3):
        for j in range(4):
            total = a[i, 0] * b[0, j] + a[i, 1] * b[1, j] + a[i, 2] * b[2, j]
            if j == 3:
                total += a[i, 3]
            out[i, j] = total
    out[3, 0] = 0.0
    out[3, 1] = 0.0
    out[3, 2] = 0.0
    out[3, 3] = 1.0


@njit(cache=True, inline="always")
def _invert(g: Array, out: Array) -> None:  # pragma: no cover - compiled
    """``out = g⁻¹ = (Rᵀ, −Rᵀ p)``."""
    for i in range(3):
        for j in range(3):
            out[i, j] = g[j, i]
        out[i, 3] = -(g[0, i] * g[0, 3] + g[1, i] * g[1, 3] + g[2, i] * g[2, 3])
    out[3, 0] = 0.0
    out[3, 1] = 0.0
    out[3, 2] = 0.0
    out[3, 3] = 1.0


@njit(cache=True, inline="always")
def _adjoint_into(g: Array, row: Array, out: Array) -> None:  # pragma: no cover - compiled
    """``out = (R s; R s0 + p × R s)`` (Murray, Li & Sastry 1994, Eq. 2.58)."""
    s0 = g[0, 0] * row[0] + g[0, 1] * row[1] + g[0, 2] * row[2]
    s1 = g[1, 0] * row[0] + g[1, 1] * row[1] + g[1, 2] * row[2]
    s2 = g[2, 0] * row[0] + g[2, 1] * row[1] + g[2, 2] * row[2]
    m0 = g[0, 0] * row[3] + g[0, 1] * row[4] + g[0, 2] * row[5]
    m1 = g[1, 0] * row[3] + g[1, 1] * row[4] + g[1, 2] * row[5]
    m2 = g[2, 0] * row[3] + g[2, 1] * row[4] + g[2, 2] * row[5]
    px, py, pz = g[0, 3], g[1, 3], g[2, 3]
    out[0], out[1], out[2] = s0, s1, s2
    out[3] = m0 + (py * s2 - pz * s1)
    out[4] = m1 + (pz * s0 - px * s2)
    out[5] = m2 + (px * s1 - py * s0)


@njit(cache=True, inline="always")
def _rotation_log_into(r: Array, out: Array) -> None:  # pragma: no cover - compiled
    """The rotation vector of ``r[:3, :3]`` (:func:`screwkit.algebra.rigid_motions.rotation_log`)."""
    k0 = 0.5 * (r[2, 1] - r[1, 2])
    k1 = 0.5 * (r[0, 2] - r[2, 0])
    k2 = 0.5 * (r[1, 0] - r[0, 1])
    cosine = min(1.0, max(-1.0, 0.5 * (r[0, 0] + r[1, 1] + r[2, 2] - 1.0)))
    sine = math.sqrt(k0 * k0 + k1 * k1 + k2 * k2)
    angle = math.atan2(sine, cosine)
    if cosine < -0.99:  # the axis from (R + I) / 2 = a aᵀ near θ = π
        column = 0
        for i in range(1, 3):
            if r[i, i] > r[column, column]:
                column = i
        a0 = 0.5 * (r[0, column] + (1.0 if column == 0 else 0.0))
        a1 = 0.5 * (r[1, column] + (1.0 if column == 1 else 0.0))
        a2 = 0.5 * (r[2, column] + (1.0 if column == 2 else 0.0))
        size = math.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
        sign = -1.0 if a0 * k0 + a1 * k1 + a2 * k2 < 0 else 1.0
        out[0], out[1], out[2] = a0 / size * sign * angle, a1 / size * sign * angle, a2 / size * sign * angle
        return
    factor = angle / sine if sine > 1e-8 else 1.0 + angle * angle / 6.0
    out[0], out[1], out[2] = k0 * factor, k1 * factor, k2 * factor


@njit(cache=True)
def _evaluate_pose(  # pragma: no cover - compiled
    theta: Array,
    offsets: Array,
    pinned: Array,
    model: tuple,
    steps: Array,
    rows: Array,
    work: Array,
    links: Array,
    motions: Array,
    current: Array,
) -> None:
    """One pose of :func:`evaluate` into ``links``, ``motions``, ``current`` (``steps``, ``rows``,
    ``work (3, 4, 4)``: scratch)."""
    (exponential, reference_rows, hinges, hinge_axes, hinge_rods, joint_ptr, joint_columns, offset_slot,
     tree, roots, column_parent, _) = model
    n = theta.shape[0]
    for i in range(n):
        _step_into(exponential, i, theta[i], steps[i])
        for k in range(6):
            rows[i, k] = reference_rows[i, k]
    for h in range(hinges.shape[0]):  # the Π's twist turns with its rods: (0; a × R(a, θ) w)
        i = hinges[h]
        w0 = hinge_rods[h, 0] + steps[i, 0, 3]
        w1 = hinge_rods[h, 1] + steps[i, 1, 3]
        w2 = hinge_rods[h, 2] + steps[i, 2, 3]
        a0, a1, a2 = hinge_axes[h, 0], hinge_axes[h, 1], hinge_axes[h, 2]
        rows[i, 3] = a1 * w2 - a2 * w1
        rows[i, 4] = a2 * w0 - a0 * w2
        rows[i, 5] = a0 * w1 - a1 * w0
    turned = np.empty(6)
    scratch = work[0]
    for j in range(joint_ptr.shape[0] - 1):
        first, last = joint_ptr[j], joint_ptr[j + 1]
        motion = motions[j]
        if first == last:
            motion[:, :] = 0.0
            for k in range(4):
                motion[k, k] = 1.0
            continue
        c = joint_columns[first]
        slot = offset_slot[j]
        if slot >= 0:
            _adjoint_into(offsets[slot], rows[c], turned)
            rows[c, :] = turned
            _compose(offsets[slot], steps[c], motion)
        else:
            motion[:, :] = steps[c]
        for q in range(first + 1, last):
            c = joint_columns[q]
            _adjoint_into(motion, rows[c], turned)
            rows[c, :] = turned
            _compose(motion, steps[c], scratch)
            motion[:, :] = scratch
    inverse = work[1]
    links[roots[0], :, :] = 0.0
    for k in range(4):
        links[roots[0], k, k] = 1.0
    if roots.shape[0] > 1:
        links[roots[1]] = pinned
    for e in range(tree.shape[0]):
        child, parent, joint, forward = tree[e, 0], tree[e, 1], tree[e, 2], tree[e, 3]
        if forward:
            _compose(links[parent], motions[joint], links[child])
        else:
            _invert(motions[joint], inverse)
            _compose(links[parent], inverse, links[child])
    for i in range(n):
        _adjoint_into(links[column_parent[i]], rows[i], current[i])


@njit(cache=True)
def evaluate(  # pragma: no cover - compiled
    theta: Array, offsets: Array, pinned: Array, model: tuple
) -> tuple[Array, Array, Array]:
    """Link displacements ``(B, links, 4, 4)``, joint displacements ``(B, joints, 4, 4)`` and current
    screws ``(B, n, 6)`` at ``theta (B, n)``, with the spherical joints' rotation ``offsets (B, K, 4,
    4)`` (joint ``j``'s in slot ``offset_slot[j]``, none where −1) and the pinned root's displacements
    ``pinned (B, 4, 4)`` (read when ``roots`` has two links). ``model`` holds
    :meth:`screwkit.core._batched_poe.BatchedProduct.kernel_arrays`: per column the coefficients of
    its exponential ``(n, 4, 12)`` and reference screw, the Π hinges, each joint's columns
    (``joint_columns[joint_ptr[j] : joint_ptr[j + 1]]``, in order), the spherical joints' offset slots,
    the tree's edges ``(child, parent, joint, forward)`` each after its parent's, the roots, each
    column's parent link and the number of links."""
    joint_ptr, n_links = model[5], model[11]
    count, n = theta.shape
    links = np.empty((count, n_links, 4, 4))
    motions = np.empty((count, joint_ptr.shape[0] - 1, 4, 4))
    current = np.empty((count, n, 6))
    steps = np.empty((n, 4, 4))
    rows = np.empty((n, 6))
    work = np.empty((3, 4, 4))
    for p in range(count):
        _evaluate_pose(
            theta[p], offsets[p], pinned[min(p, pinned.shape[0] - 1)], model, steps, rows, work, links[p],
            motions[p], current[p],
        )
    return links, motions, current


@njit(cache=True, inline="always")
def _loop_residual_into(  # pragma: no cover - compiled
    links: Array, motions: Array, loops: Array, work: Array, out: Array
) -> None:
    """Each loop ``(u, v, joint)``'s ``links[u] motions[joint] links[v]⁻¹`` as rotation vector and
    translation into ``out (6 L)`` (``work (3, 4, 4)``: scratch)."""
    step, inverse, closed = work[0], work[1], work[2]
    vector = np.empty(3)
    for loop in range(loops.shape[0]):
        _compose(links[loops[loop, 0]], motions[loops[loop, 2]], step)
        _invert(links[loops[loop, 1]], inverse)
        _compose(step, inverse, closed)
        _rotation_log_into(closed, vector)
        for k in range(3):
            out[6 * loop + k] = vector[k]
            out[6 * loop + 3 + k] = closed[k, 3]


@njit(cache=True)
def loop_residual(links: Array, motions: Array, loops: Array) -> Array:  # pragma: no cover - compiled
    """The loops' residual ``(B, 6 L)`` (:meth:`screwkit.core.kinematic_model.KinematicModel.loop_residual`)
    of links ``(B, links, 4, 4)`` and joint motions ``(B, joints, 4, 4)``; ``loops (L, 3)`` rows
    ``(u, v, joint)``: the closing joint and its links."""
    count = links.shape[0]
    out = np.zeros((count, 6 * loops.shape[0]))
    work = np.empty((3, 4, 4))
    for p in range(count):
        _loop_residual_into(links[p], motions[p], loops, work, out[p])
    return out


@njit(cache=True)
def _block_factor(  # pragma: no cover - compiled
    current: Array, block: int, blocks: tuple, gram: Array
) -> None:
    """The Cholesky factor of block ``block``'s ``J Jᵀ + λ I`` into ``gram``'s lower triangle
    (:func:`pinned_newton`'s ``blocks``). ``J Jᵀ`` is summed column by column: a column ``c`` held by
    loops ``i, j`` with signs ``σᵢ, σⱼ`` adds ``σᵢ σⱼ s_c s_cᵀ`` (its current screw's outer product) to
    the loops' 6 × 6 block; then ``J Jᵀ + λ I = L Lᵀ`` (Golub & Van Loan, *Matrix Computations*, 4th
    ed., 2013, Alg. 4.2.1)."""
    block_ptr, _, column_ptr, column_index, entry_ptr, entry_loop, entry_sign = blocks
    size = 6 * (block_ptr[block + 1] - block_ptr[block])
    for i in range(size):
        for j in range(i + 1):
            gram[i, j] = 0.0
    for q in range(column_ptr[block], column_ptr[block + 1]):
        screw = current[column_index[q]]
        for e in range(entry_ptr[q], entry_ptr[q + 1]):  # loops ascending: i ≤ j, the lower triangle
            i, si = entry_loop[e], entry_sign[e]
            for f in range(entry_ptr[q], e + 1):
                j, sign = entry_loop[f], si * entry_sign[f]
                for a in range(6):
                    scaled = sign * screw[a]
                    top = 6 if i != j else a + 1
                    for b in range(top):
                        gram[6 * i + a, 6 * j + b] += scaled * screw[b]
    damped_cholesky(gram, size)


@njit(cache=True)
def _block_solve(  # pragma: no cover - compiled
    current: Array, residual: Array, block: int, blocks: tuple, gram: Array, solution: Array, out: Array
) -> None:
    """The minimum-norm correction ``−Jᵀ (J Jᵀ + λ I)⁻¹ F`` of block ``block``'s columns into ``out``,
    from the factor :func:`_block_factor` left in ``gram`` (``solution``: scratch)."""
    block_ptr, block_loops, column_ptr, column_index, entry_ptr, entry_loop, entry_sign = blocks
    first_loop = block_ptr[block]
    size = 6 * (block_ptr[block + 1] - first_loop)
    for i in range(size):
        solution[i] = residual[6 * block_loops[first_loop + i // 6] + i % 6]
    cholesky_solve(gram, size, solution)
    for q in range(column_ptr[block], column_ptr[block + 1]):
        c = column_index[q]
        total = 0.0
        for e in range(entry_ptr[q], entry_ptr[q + 1]):
            i, sign = entry_loop[e], entry_sign[e]
            for a in range(6):
                total += sign * current[c, a] * solution[6 * i + a]
        out[c] = -total


@njit(cache=True)
def pinned_newton(  # pragma: no cover - compiled
    theta: Array,
    offsets: Array,
    pinned: Array,
    tolerance: Array,
    working: Array,
    iterations: int,
    max_correction: float,
    recentre_angle: float,
    model: tuple,
    loops: Array,
    blocks: tuple,
    unfolded: Array,
) -> tuple[Array, Array, Array, Array]:
    """The Newton corrector of one continuation step on the loops of a model pinned to its platform,
    pose by pose where ``working``: at most ``iterations`` corrections, each the blocks' minimum-norm
    correction scaled down to ``max_correction`` at most, until the largest residual is within
    ``tolerance[p, 0]``, the last correction within ``tolerance[p, 1]`` or, the corrections contracting
    at ``Θ = |Δθₖ| / |Δθₖ₋₁| < 1/2``, the error estimate ``Θ / (1 − Θ) |Δθₖ|`` within
    ``tolerance[p, 2]`` (the residual before the last correction times ``Θ`` then reported); after a
    correction within ``tolerance[p, 3]``, the next solves with the last Cholesky factors and the
    screws they were made at (simplified Newton); then, once a spherical
    joint's angle exceeds ``recentre_angle``, every spherical joint's angles folded into its offset
    (:meth:`screwkit.core.kinematic_model.KinematicModel.recentred`).

    Updates ``theta (B, n)`` and ``offsets (B, K, 4, 4)`` in place and writes the joint values before
    the fold into ``unfolded (B, n)``; returns the last residual size (B,), the sum of the
    corrections after each pose's first (B,), the first's (B,) and the evaluations of the model (B,).
    ``model`` holds :func:`evaluate`'s arrays; ``blocks`` is ``(block_ptr, block_loops, column_ptr,
    column_index, entry_ptr, entry_loop, entry_sign)``: block ``b``'s loops ``block_loops[block_ptr[b]
    : block_ptr[b + 1]]``, its columns ``column_index[column_ptr[b] : column_ptr[b + 1]]``, column
    ``q``'s loops (local to its block, ascending) and signs ``entry_*[entry_ptr[q] : entry_ptr[q +
    1]]``."""
    exponential, joint_ptr, joint_columns, offset_slot = model[0], model[5], model[6], model[7]
    n_links = model[11]
    block_ptr = blocks[0]
    count, n = theta.shape
    sizes = np.zeros(count)
    corrected = np.zeros(count)
    leading = np.zeros(count)
    evaluations = np.zeros(count, dtype=np.int64)
    steps = np.empty((n, 4, 4))
    rows = np.empty((n, 6))
    work = np.empty((3, 4, 4))
    links = np.empty((n_links, 4, 4))
    motions = np.empty((joint_ptr.shape[0] - 1, 4, 4))
    current = np.empty((n, 6))
    residual = np.empty(6 * loops.shape[0])
    largest = 6 * int(np.max(block_ptr[1:] - block_ptr[:-1]))
    grams = np.empty((block_ptr.shape[0] - 1, largest, largest))
    frozen = np.empty((n, 6))  # the screws the factors were made at
    solution = np.empty(largest)
    correction = np.empty(n)
    for p in range(count):
        if not working[p]:
            continue
        first = True
        before = math.inf
        for _ in range(iterations):
            _evaluate_pose(theta[p], offsets[p], pinned[p], model, steps, rows, work, links, motions, current)
            evaluations[p] += 1
            _loop_residual_into(links, motions, loops, work, residual)
            size = 0.0
            for k in range(residual.shape[0]):
                value = abs(residual[k])
                if not value <= size:  # (a NaN stays)
                    size = value
            sizes[p] = size
            if not size > tolerance[p, 0]:
                break
            correction[:] = 0.0
            if first or before > tolerance[p, 3]:  # else a simplified Newton step: the last factors again
                frozen[:, :] = current
                for b in range(block_ptr.shape[0] - 1):
                    _block_factor(frozen, b, blocks, grams[b])
            for b in range(block_ptr.shape[0] - 1):
                _block_solve(frozen, residual, b, blocks, grams[b], solution, correction)
            stop, before = took_correction(
                theta[p], correction, 1.0, max_correction, tolerance[p], first, before, size, p, sizes,
                leading, corrected,
            )
            if stop:
                break
            first = False
        unfolded[p] = theta[p]
        _recentre(
            theta[p], offsets[p], exponential, joint_ptr, joint_columns, offset_slot, recentre_angle, work
        )
    return sizes, corrected, leading, evaluations


@njit(cache=True, inline="always")
def _step_into(exponential: Array, i: int, t: float, out: Array) -> None:  # pragma: no cover - compiled
    """``exp(ŝᵢ t)`` of column ``i`` from its coefficients (:func:`evaluate`)."""
    b1, b2, b3 = t, math.sin(t), 1.0 - math.cos(t)
    for e in range(12):
        value = exponential[i, 0, e] + b1 * exponential[i, 1, e] + b2 * exponential[i, 2, e]
        out[e // 4, e % 4] = value + b3 * exponential[i, 3, e]
    out[3, 0] = 0.0
    out[3, 1] = 0.0
    out[3, 2] = 0.0
    out[3, 3] = 1.0


@njit(cache=True)
def _recentre(  # pragma: no cover - compiled
    theta: Array,
    offsets: Array,
    exponential: Array,
    joint_ptr: Array,
    joint_columns: Array,
    offset_slot: Array,
    recentre_angle: float,
    work: Array,
) -> None:
    """One pose's spherical joints' angles folded into their offsets (offset × the product of the
    joint's exponentials), when one of them exceeds ``recentre_angle``."""
    largest = 0.0
    for j in range(offset_slot.shape[0]):
        if offset_slot[j] >= 0:
            for q in range(joint_ptr[j], joint_ptr[j + 1]):
                largest = max(largest, abs(theta[joint_columns[q]]))
    if not largest > recentre_angle:
        return
    step, product = work[0], work[1]
    for j in range(offset_slot.shape[0]):
        slot = offset_slot[j]
        if slot < 0:
            continue
        for q in range(joint_ptr[j], joint_ptr[j + 1]):
            c = joint_columns[q]
            _step_into(exponential, c, theta[c], step)
            _compose(offsets[slot], step, product)
            offsets[slot, :, :] = product
            theta[c] = 0.0


@njit(cache=True)
def _oriented_columns(columns: Array) -> None:  # pragma: no cover - compiled
    """``columns (d, p)`` replaced in place by the orthonormal basis of their span that modified
    Gram-Schmidt gives: the ``Q`` of their QR factorisation with ``R``'s diagonal positive (Golub & Van
    Loan 2013, Alg. 5.2.6), the factor :func:`numpy.linalg.qr` gives once its signs are moved into ``Q``."""
    for j in range(columns.shape[1]):
        for i in range(j):
            dot = 0.0
            for k in range(columns.shape[0]):
                dot += columns[k, i] * columns[k, j]
            for k in range(columns.shape[0]):
                columns[k, j] -= dot * columns[k, i]
        size = 0.0
        for k in range(columns.shape[0]):
            size += columns[k, j] * columns[k, j]
        size = math.sqrt(size)
        for k in range(columns.shape[0]):
            columns[k, j] /= size


@njit(cache=True)
def bordered_orientation(  # pragma: no cover - compiled
    blocks: Array, left: Array, right: Array
) -> tuple[Array, Array, Array, Array]:
    """Per block ``J (P, m, n)`` with borders ``L (P, m, a)``, ``N (P, n, c)`` (``m + c = n + a``): the
    sign of ``det [[J, L], [Nᵀ, 0]]`` from its LU factorisation with partial pivoting (the pivots'
    signs times the permutation's parity; Golub & Van Loan 2013, Alg. 3.4.1), and from the same
    factors the left null space and null space the border carries to ``J``, the solutions ``X`` of
    ``J X + L Y = 0``, ``Nᵀ X = I`` and of their transposed twin, orthonormalised with their
    orientation (:func:`_oriented_columns`), and how far they turned from the border: the largest
    length of a column of ``X`` (at least 1). The numpy twin is
    ``screwkit.core._working_modes``' (``numpy.linalg.det``, ``solve``, ``qr``)."""
    count, m, n = blocks.shape
    a, c = left.shape[2], right.shape[2]
    size = m + c
    signs = np.zeros(count)
    new_left = np.empty((count, m, a))
    new_right = np.empty((count, n, c))
    turned = np.ones(count)
    factors = np.empty((size, size))
    order = np.empty(size, dtype=np.int64)
    vector = np.empty(size)
    for p in range(count):
        factors[:, :] = 0.0
        factors[:m, :n] = blocks[p]
        factors[:m, n:] = left[p]
        factors[m:, :n] = right[p].T
        sign = 1.0
        for i in range(size):
            order[i] = i
        for k in range(size):
            pivot = k
            for i in range(k + 1, size):
                if abs(factors[i, k]) > abs(factors[pivot, k]):
                    pivot = i
            if pivot != k:
                sign = -sign
                order[k], order[pivot] = order[pivot], order[k]
                for j in range(size):
                    factors[k, j], factors[pivot, j] = factors[pivot, j], factors[k, j]
            if factors[k, k] == 0.0:
                sign = 0.0
                continue
            if factors[k, k] < 0.0:
                sign = -sign
            for i in range(k + 1, size):
                multiplier = factors[i, k] / factors[k, k]
                factors[i, k] = multiplier
                if multiplier != 0.0:  # (the loops' Jacobian is sparse: a column is in one or two loops)
                    for j in range(k + 1, size):
                        factors[i, j] -= multiplier * factors[k, j]
        signs[p] = sign
        for column in range(c):  # (P B) x = P e: forward with L, back with U
            for i in range(size):
                value = 1.0 if order[i] == m + column else 0.0
                for k in range(i):
                    value -= factors[i, k] * vector[k]
                vector[i] = value
            for i in range(size - 1, -1, -1):
                value = vector[i]
                for k in range(i + 1, size):
                    value -= factors[i, k] * vector[k]
                vector[i] = value / factors[i, i]
            new_right[p, :, column] = vector[:n]
        for column in range(a):  # Bᵀ y = e, Bᵀ = Uᵀ Lᵀ P: forward with Uᵀ, back with Lᵀ (by the rows of U
            vector[:] = 0.0  # and L, Uᵀ's and Lᵀ's columns), then y = Pᵀ w
            vector[n + column] = 1.0
            for i in range(size):
                vector[i] /= factors[i, i]
                for k in range(i + 1, size):
                    vector[k] -= factors[i, k] * vector[i]
            for i in range(size - 1, 0, -1):
                for k in range(i):
                    vector[k] -= factors[i, k] * vector[i]
            for i in range(size):
                if order[i] < m:
                    new_left[p, order[i], column] = vector[i]
        for basis in (new_left[p], new_right[p]):
            for j in range(basis.shape[1]):
                length = 0.0
                for k in range(basis.shape[0]):
                    length += basis[k, j] * basis[k, j]
                length = math.sqrt(length)
                if not length <= turned[p]:  # (a NaN stays)
                    turned[p] = length
            _oriented_columns(basis)
    return signs, new_left, new_right, turned
