"""numba kernel of the rods' Newton corrector (:mod:`screwkit.core._rod_closure`; private).

Pose by pose, what ``_RodLoops.newton`` does over the batch in numpy: the remaining links' product of
exponentials (:func:`screwkit.core._newton_numba._evaluate_pose`), one distance equation per rod and its
Jacobian (the formulas of :mod:`screwkit.core._rod_closure`), and the minimum-norm Gauss–Newton
correction, here in its column form ``−(JᵀJ + λ I)⁻¹ Jᵀ g`` (equal to ``−Jᵀ (J Jᵀ + λ I)⁻¹ g``, the
push-through identity; the matrix is the joint variables' size, a few per leg) by a Cholesky
factorisation (Golub & Van Loan, *Matrix Computations*, 4th ed., 2013, Alg. 4.2.1). The numpy twin
solves block by block, each with Levenberg's ``λ`` from its own block's trace where this takes it from
the whole ``JᵀJ`` (``λ ≈ 1e-13`` times the trace: the corrections differ at that level), so the two
agree to round-off, not bit for bit (``tests/core/test_rod_closure.py``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._newton_numba import _evaluate_pose
from ._newton_steps_numba import cholesky_solve, damped_cholesky, took_correction

__all__ = ["rod_newton"]

Array = np.ndarray


@njit(cache=True, inline="always")
def _rods_residual(  # pragma: no cover - compiled
    links: Array, ends: Array, centres: Array, lengths: Array, points: Array, residual: Array
) -> float:
    """The rods' residual into ``residual (R)`` and their ends' centres into ``points (R, 2, 3)``;
    returns the largest magnitude (NaN stays)."""
    size = 0.0
    for r in range(lengths.shape[0]):
        for side in range(2):
            g = links[ends[r, side]]
            c = centres[r, side]
            for i in range(3):
                points[r, side, i] = g[i, 0] * c[0] + g[i, 1] * c[1] + g[i, 2] * c[2] + g[i, 3]
        total = 0.0
        for i in range(3):
            gap = points[r, 1, i] - points[r, 0, i]
            total += gap * gap
        value = (total - lengths[r] * lengths[r]) / (2.0 * lengths[r])
        residual[r] = value
        if not abs(value) <= size:
            size = abs(value)
    return size


@njit(cache=True, inline="always")
def _rods_jacobian(  # pragma: no cover - compiled
    current: Array, points: Array, lengths: Array, signs: Array, jacobian: Array
) -> None:
    """The rods' Jacobian ``(R, m)``: ``(q_b − q_a)ᵀ (σ_b (v + ω × q_b) − σ_a (v + ω × q_a)) / ℓ``."""
    for r in range(lengths.shape[0]):
        for c in range(current.shape[0]):
            total = 0.0
            for side in range(2):
                sign = signs[r, side, c] if side == 1 else -signs[r, side, c]
                if sign == 0.0:
                    continue
                q = points[r, side]
                w0, w1, w2 = current[c, 0], current[c, 1], current[c, 2]
                velocity0 = current[c, 3] + (w1 * q[2] - w2 * q[1])
                velocity1 = current[c, 4] + (w2 * q[0] - w0 * q[2])
                velocity2 = current[c, 5] + (w0 * q[1] - w1 * q[0])
                total += sign * (
                    (points[r, 1, 0] - points[r, 0, 0]) * velocity0
                    + (points[r, 1, 1] - points[r, 0, 1]) * velocity1
                    + (points[r, 1, 2] - points[r, 0, 2]) * velocity2
                )
            jacobian[r, c] = total / lengths[r]


@njit(cache=True, inline="always")
def _ball_motions_into(  # pragma: no cover - compiled
    links: Array, points: Array, centres: Array, lengths: Array, joint_rods: Array, from_rod: Array,
    joint_links: Array, rods: Array, out: Array
) -> None:
    """The balls' motions ``(2R, 4, 4)`` of ``_RodLoops._ball_motions``, each rod's displacement into
    ``rods (R, 4, 4)``."""
    for r in range(lengths.shape[0]):
        gap = np.empty(3)
        reference = np.empty(3)
        size = 0.0
        for i in range(3):
            gap[i] = points[r, 1, i] - points[r, 0, i]
            reference[i] = (centres[r, 1, i] - centres[r, 0, i]) / lengths[r]
            size += gap[i] * gap[i]
        size = math.sqrt(size)
        for i in range(3):
            gap[i] /= size
        k0 = reference[1] * gap[2] - reference[2] * gap[1]
        k1 = reference[2] * gap[0] - reference[0] * gap[2]
        k2 = reference[0] * gap[1] - reference[1] * gap[0]
        cosine = reference[0] * gap[0] + reference[1] * gap[1] + reference[2] * gap[2]
        skew = np.array([[0.0, -k2, k1], [k2, 0.0, -k0], [-k1, k0, 0.0]])
        g = rods[r]
        for i in range(3):
            for j in range(3):
                square = skew[i, 0] * skew[0, j] + skew[i, 1] * skew[1, j] + skew[i, 2] * skew[2, j]
                g[i, j] = (1.0 if i == j else 0.0) + skew[i, j] + square / (1.0 + cosine)
        for i in range(3):
            g[i, 3] = points[r, 0, i] - (g[i, 0] * centres[r, 0, 0] + g[i, 1] * centres[r, 0, 1]
                                         + g[i, 2] * centres[r, 0, 2])
            g[3, i] = 0.0
        g[3, 3] = 1.0
    for j in range(joint_rods.shape[0]):
        start = rods[joint_rods[j]] if from_rod[j, 0] else links[joint_links[j, 0]]
        end = rods[joint_rods[j]] if from_rod[j, 1] else links[joint_links[j, 1]]
        motion = out[j]
        for i in range(3):  # the rotation of start⁻¹ end, Rₛᵀ Rₑ
            for k in range(3):
                motion[i, k] = start[0, i] * end[0, k] + start[1, i] * end[1, k] + start[2, i] * end[2, k]
            motion[3, i] = 0.0
        centre = centres[j // 2, j % 2]  # a ball turns about its centre: (R, c − R c)
        for i in range(3):
            turned = motion[i, 0] * centre[0] + motion[i, 1] * centre[1] + motion[i, 2] * centre[2]
            motion[i, 3] = centre[i] - turned
        motion[3, 3] = 1.0


@njit(cache=True)
def rod_newton(  # pragma: no cover - compiled
    theta: Array,
    placed: Array,
    tolerance: Array,
    iterations: int,
    max_correction: float,
    model: tuple,
    ends: Array,
    centres: Array,
    lengths: Array,
    signs: Array,
    joint_rods: Array,
    from_rod: Array,
    joint_links: Array,
) -> tuple[Array, Array, Array, Array, Array]:
    """Newton's corrector on the rods' equations, pose by pose: at most ``iterations`` corrections,
    each scaled down to ``max_correction`` at most, until the largest residual is within
    ``tolerance[p, 0]``, the last correction within ``tolerance[p, 1]`` or, the corrections
    contracting at ``Θ < 1/2``, the error estimate ``Θ / (1 − Θ) |Δθₖ|`` within ``tolerance[p, 2]``
    (the stopping rules of :func:`screwkit.core._newton_numba.pinned_newton`).

    Updates the remaining joint variables ``theta (P, m)`` in place, the platform placed at ``placed
    (P, 4, 4)``; returns the last residual size (P,), the sum of the corrections after the first (P,),
    the first (P,), and at the final values the balls' motions ``(P, 2R, 4, 4)`` (``joint_rods (2R)``
    the rod of each, ``from_rod (2R, 2)`` whether its links ``u``, ``v`` are the rod, else
    ``joint_links (2R, 2)``) and the rods' Jacobian ``(P, R, m)``.
    ``model`` holds the remaining links' :func:`screwkit.core._newton_numba.evaluate` arrays; ``ends
    (R, 2)`` the links at each rod's ends, ``centres (R, 2, 3)`` its balls' centres at the reference,
    ``lengths (R)``, ``signs (R, 2, m)`` each end link's tree path over the variables."""
    joint_ptr, n_links = model[5], model[11]
    count, m = theta.shape
    rods = lengths.shape[0]
    sizes = np.zeros(count)
    corrected = np.zeros(count)
    leading = np.zeros(count)
    links = np.empty((n_links, 4, 4))
    motions_out = np.empty((count, joint_rods.shape[0], 4, 4))
    jacobians = np.empty((count, rods, m))
    placed_rods = np.empty((rods, 4, 4))
    steps = np.empty((m, 4, 4))
    rows = np.empty((m, 6))
    work = np.empty((3, 4, 4))
    motions = np.empty((joint_ptr.shape[0] - 1, 4, 4))
    current = np.empty((m, 6))
    offsets = np.empty((0, 4, 4))
    points = np.empty((rods, 2, 3))
    residual = np.empty(rods)
    jacobian = np.empty((rods, m))
    normal = np.empty((m, m))
    solution = np.empty(m)
    for p in range(count):
        first = True
        stale = True  # the values moved since the links were evaluated
        before = math.inf
        for _ in range(iterations):
            _evaluate_pose(theta[p], offsets, placed[p], model, steps, rows, work, links, motions, current)
            stale = False
            size = _rods_residual(links, ends, centres, lengths, points, residual)
            sizes[p] = size
            if not size > tolerance[p, 0]:
                break
            _rods_jacobian(current, points, lengths, signs, jacobian)
            for i in range(m):
                value = 0.0
                for r in range(rods):
                    value += jacobian[r, i] * residual[r]
                solution[i] = value
                for j in range(i + 1):
                    total = 0.0
                    for r in range(rods):
                        total += jacobian[r, i] * jacobian[r, j]
                    normal[i, j] = total
            damped_cholesky(normal, m)
            cholesky_solve(normal, m, solution)
            stale = True
            stop, before = took_correction(
                theta[p], solution, -1.0, max_correction, tolerance[p], first, before, size, p, sizes,
                leading, corrected,
            )
            if stop:
                break
            first = False
        if stale:
            _evaluate_pose(theta[p], offsets, placed[p], model, steps, rows, work, links, motions, current)
            _rods_residual(links, ends, centres, lengths, points, residual)
        _rods_jacobian(current, points, lengths, signs, jacobians[p])
        _ball_motions_into(
            links, points, centres, lengths, joint_rods, from_rod, joint_links, placed_rods, motions_out[p]
        )
    return sizes, corrected, leading, motions_out, jacobians
