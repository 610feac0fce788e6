"""The equations a loop-closure continuation corrects, and their Newton corrector (private;
:mod:`screwkit.core.loop_closure`, whose module docstring describes the method).

:class:`_LoopsAndTask` holds the loops and the task over the whole model (numpy over the batch);
:class:`_PinnedLoops` the loops of a model whose platform the task places, block by block, with the
compiled corrector (:mod:`screwkit.core._newton_numba`) when numba is installed;
:class:`screwkit.core._rod_closure._RodLoops` the same with its binary links between two balls (rods)
replaced by their distance equations.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from ..algebra.compiled import compiled_kernels
from ..algebra.rigid_motions import rotation_matrix
from ._batched_poe import KERNELS
from ._closure_parts import kernel_blocks, pose_residual, pose_residual_inverse, rows_replaced
from .kinematic_model import KinematicModel, KinematicState

Array = np.ndarray

#: Newton iterations allowed per step.
NEWTON_ITERATIONS = 10
#: The largest Newton correction taken at once (radians, characteristic lengths).
MAX_CORRECTION = 0.5
#: A spherical joint's angles are folded into its offset once one exceeds this (radians), far from
#: the gimbal lock of its three exponentials at π/2.
RECENTRE_ANGLE = 0.3


def _solve_step(jacobian: Array, residual: Array) -> Array:
    """The minimum-norm Gauss–Newton correction ``−Jᵀ (J Jᵀ + λ I)⁻¹ F`` per pose (module docstring)."""
    gram = jacobian @ np.swapaxes(jacobian, -1, -2)
    damping = 1e-13 * (np.trace(gram, axis1=-2, axis2=-1)[:, None, None] + 1.0)
    multipliers = np.linalg.solve(gram + damping * np.eye(gram.shape[-1]), residual[..., None])[..., 0]
    return -np.einsum("bji,bj->bi", jacobian, multipliers)


def _residual(model: KinematicModel, task: Any, state: KinematicState, target: Array) -> Array:
    return np.concatenate([model.loop_residual(state), task.difference(task.values(state), target)], axis=1)


class _LoopsAndTask:
    """The equations Newton's method solves: the loops' and the task's, over the whole model."""

    def __init__(self, model: KinematicModel, task: Any):
        self.model, self.task = model, task

    def state(self, theta: Array, offsets: dict[str, Array], target: Array) -> KinematicState:
        return self.model.state(theta, offsets)

    def equations(self, state: KinematicState, target: Array) -> tuple[Array, Array]:
        jacobian = np.concatenate([self.model.loop_jacobian(state), self.task.jacobian(state)], axis=1)
        return _residual(self.model, self.task, state, target), jacobian

    def correction(self, jacobian: Any, residual: Array, need: Array) -> Array:
        """The correction of the rows ``need`` of the equations' residual and Jacobian."""
        return _solve_step(jacobian[need], residual[need])

    def with_rows(self, jacobian: Any, rows: Array, other: Any, index: Array) -> Any:
        """``jacobian`` (as :meth:`equations` gives it) with its poses ``rows`` (bool) taken from
        ``other``'s poses ``index``."""
        return rows_replaced(jacobian, rows, other, index)

    def tangent(self, start: Array, target: Array) -> Array | None:
        """The tangent (Euler) predictor of a first step from the reference configuration to
        ``target`` (None: the first step has none, Newton's first correction is its tangent step)."""
        return None

    def newton(
        self, theta: Array, offsets: Array, target: Array, tolerance: Array, working: Array
    ) -> tuple[Array, Array, Array, Array]:
        """The corrector of one continuation step: Newton iterations on the poses ``working`` until
        their largest residual is within ``tolerance[:, 0]``, their last correction within
        ``tolerance[:, 1]`` or the error the contraction estimates within ``tolerance[:, 2]`` (at most
        :data:`NEWTON_ITERATIONS`, each correction scaled down to :data:`MAX_CORRECTION`, the last
        factorisation used again after a correction within ``tolerance[:, 3]``: module docstring),
        then the spherical joints' angles of a pose folded into their
        ``offsets (B, K, 4, 4)`` (:attr:`spherical` order) once one exceeds :data:`RECENTRE_ANGLE`.
        Updates ``theta`` and ``offsets`` in place; returns, for the poses ``working``, the last
        residual size, the sum of the corrections after the first (the predictor's own correction),
        the first correction, and the joint values before the fold."""
        rows = np.flatnonzero(working)
        sizes, corrected, first = np.zeros(rows.size), np.zeros(rows.size), np.ones(rows.size, dtype=bool)
        leading, before = np.zeros(rows.size), np.full(rows.size, np.inf)
        place = np.arange(rows.size)  # the working poses still iterating, as positions in ``rows``
        frozen = None  # each pose's Jacobian where its last correction was factorised
        for _ in range(NEWTON_ITERATIONS):  # only the poses not yet within the tolerance
            if place.size == 0:
                break
            at = rows[place]
            state = self.state(theta[at], self.offsets_of(offsets[at]), target[at])
            residual, jacobian = self.equations(state, target[at])
            if frozen is None:
                frozen = jacobian
            else:  # a simplified Newton step after a correction within tolerance[:, 3]: the last factors
                simplified = ~(before[place] > tolerance[at, 3])
                fresh = np.zeros(rows.size, dtype=bool)
                fresh[place[~simplified]] = True
                frozen = self.with_rows(frozen, fresh, jacobian, np.flatnonzero(~simplified))
                jacobian = self.with_rows(jacobian, simplified, frozen, place[simplified])
            size = np.max(np.abs(residual), axis=1, initial=0.0)
            sizes[place] = size
            need = size > tolerance[at, 0]
            place = place[need]
            if place.size == 0:
                break
            correction = self.correction(jacobian, residual, need)
            length = np.max(np.abs(correction), axis=1, initial=0.0)
            correction *= np.minimum(1.0, MAX_CORRECTION / np.maximum(length, 1e-300))[:, None]
            theta[rows[place]] += correction
            clipped = np.minimum(length, MAX_CORRECTION)
            leading[place] = np.where(first[place], clipped, leading[place])
            corrected[place] += np.where(first[place], 0.0, clipped)
            going = length > tolerance[rows[place], 1]  # a correction this small: converged
            contraction = length / before[place]  # the error left is about Θ/(1 − Θ) |Δθ| (module docstring)
            settled = going & ~first[place] & (contraction < 0.5)
            error = np.divide(contraction, 1.0 - contraction, out=np.full_like(length, np.inf), where=settled)
            settled &= error * length <= tolerance[rows[place], 2]
            sizes[place[settled]] *= contraction[settled]
            before[place], first[place] = length, False
            place = place[going & ~settled]
        spherical, unfolded = self.spherical_columns, theta[rows]
        if spherical.size:  # fold the spherical joints' angles into their offsets before they grow
            turned = rows[np.max(np.abs(unfolded[:, spherical]), axis=1) > RECENTRE_ANGLE]
            if turned.size:
                new_theta, new_offsets = self.model.recentred(theta[turned], self.offsets_of(offsets[turned]))
                theta[turned] = new_theta
                offsets[turned] = np.stack([new_offsets[key] for key in self.spherical], axis=1)
        return sizes, corrected, leading, unfolded

    @functools.cached_property
    def spherical(self) -> list[str]:
        """The spherical joints, in the order of the offsets' second axis."""
        return [key for key, kind in self.model.types.items() if kind == "S"]

    @functools.cached_property
    def spherical_columns(self) -> Array:
        """Their columns."""
        return np.array([i for key in self.spherical for i in self.model.joints[key][2]], dtype=int)

    def offsets_of(self, stacked: Array) -> dict[str, Array]:
        """The offsets ``(B, K, 4, 4)`` as the model's dict (views)."""
        return {key: stacked[:, k] for k, key in enumerate(self.spherical)}


class _GroupedBlocks(_LoopsAndTask):
    """Equations whose Jacobian comes as groups of independent blocks of one shape, ``(B, k, rows,
    columns)`` per group, with ``groups`` of ``(equation rows (k, r), columns (k, c), ...)``: the
    minimum-norm correction solved block by block (blocks of one shape in one batched call)."""

    groups: list[tuple[Array, ...]]

    def with_rows(self, jacobian: Any, rows: Array, other: Any, index: Array) -> Any:
        pairs = zip(jacobian, other, strict=True)
        return [rows_replaced(mine, rows, theirs, index) for mine, theirs in pairs]

    def correction(self, jacobian: Any, residual: Array, need: Array) -> Array:
        count = int(need.sum())
        out = np.zeros((count, self.model.size))
        for (rows, columns, *_), blocks in zip(self.groups, jacobian, strict=True):
            flat = residual[need][:, rows].reshape(-1, rows.shape[1])
            step = _solve_step(blocks[need].reshape(-1, *blocks.shape[2:]), flat)
            out[:, columns.ravel()] = step.reshape(count, -1)
        return out


class _PinnedLoops(_GroupedBlocks):
    """The same configurations when the task fixes its link's whole pose: that link placed where the
    target says (:meth:`~screwkit.core.kinematic_tasks.PoseTask.displacement`), the loops of the
    model pinned there (:meth:`~screwkit.core.kinematic_model.KinematicModel.pinned_model`) close
    each part between the base and the link on its own, so the correction is solved block by block
    (blocks of one shape in one batched call): the same minimum-norm step per block, as each
    block's equations hold only its own joint variables."""

    def __init__(self, model: KinematicModel, task: Any):
        super().__init__(model, task)
        self.pinned = model.pinned_model(task.coordinates.link)
        shapes: dict[tuple[int, int], list[tuple[Array, Array]]] = {}
        for rows, columns in self.pinned.blocks:
            shapes.setdefault((rows.size, columns.size), []).append((rows, columns))
        self.groups = []  # (equation rows (k, 6 l), columns (k, c), the loops' signs (k, l, c))
        for blocks in shapes.values():
            rows, columns = np.array([r for r, _ in blocks]), np.array([c for _, c in blocks])
            loops = self.pinned.incidence[rows[:, ::6] // 6]  # (k, l, n)
            signs = np.take_along_axis(loops, columns[:, None, :], axis=2)
            self.groups.append((rows, columns, signs))
        product = self.pinned._product
        self.kernel_blocks = kernel_blocks(self.pinned)
        self.kernel_model = product.kernel_arrays(self.spherical)

    def state(self, theta: Array, offsets: dict[str, Array], target: Array) -> KinematicState:
        return self.pinned.state(theta, offsets, self.task.displacement(target))

    def equations(self, state: KinematicState, target: Array) -> tuple[Array, Any]:
        """The loops' residual and, per group of blocks, their Jacobians ``(B, k, 6 l, c)`` (the
        blocks of :meth:`~screwkit.core.kinematic_model.KinematicModel.loop_jacobian`)."""
        blocks = []
        for _, columns, signs in self.groups:
            screws = np.swapaxes(state.current[:, columns], -1, -2)  # (B, k, 6, c)
            jacobian = signs[None, :, :, None, :] * screws[:, :, None]  # (B, k, l, 6, c)
            blocks.append(jacobian.reshape(*jacobian.shape[:2], -1, jacobian.shape[-1]))
        return self.pinned.loop_residual(state), blocks

    def tangent(self, start: Array, target: Array) -> Array | None:
        """The tangent (Euler) predictor ``−J⁺ F`` of a first step from the reference configuration
        to ``target``: ``F``, the pinned loops' residual at the reference joint values with the link
        moved by ``D = displacement(target)``, is that of ``D``, of ``D⁻¹`` or zero per loop (the
        links on the pinned link's side of the tree all move by ``D`` there,
        :attr:`_reference_tangent`), and ``J⁺`` the minimum-norm solve at the reference configuration,
        the same for every pose. One matrix product per pose instead of an evaluation of the model:
        Newton's method then starts at an ``O(h²)`` error (Allgower & Georg 2003, §2.2)."""
        if self._reference_tangent is None or np.any(start != self._reference_tangent[2]):
            return None
        kinds, solve, _ = self._reference_tangent
        moved = self.task.displacement(target)
        forward = pose_residual(moved)
        residual = np.zeros((len(target), kinds.size, 6))
        residual[:, kinds > 0] = forward[:, None]
        residual[:, kinds < 0] = -pose_residual_inverse(moved, forward)[:, None]
        return residual.reshape(len(target), -1) @ solve

    @functools.cached_property
    def _reference_tangent(self) -> tuple[Array, Array, Array] | None:
        """Per pinned loop whether its residual at the reference joint values is that of the link's
        displacement ``D`` (1), of ``D⁻¹`` (−1) or zero (0), read off one generic ``D``; the
        minimum-norm solve ``−J⁺`` there as a ``(6 L, n)`` matrix (the correction is linear in the
        residual); the task's reference values. None if a loop's residual is none of these (then no
        tangent predictor)."""
        model, spherical = self.model, len(self.spherical)
        theta = np.zeros((1, model.size))
        offsets = np.tile(np.eye(4), (1, spherical, 1, 1))
        values = self.task.values(model.state(theta))
        if not np.allclose(self.task.displacement(values), np.eye(4), rtol=0.0, atol=1e-12):
            return None
        probe = np.eye(4)[None].copy()  # a generic displacement: no loop's residual is D's by chance
        probe[0, :3, :3] = rotation_matrix(np.array([0.48, -0.6, 0.64]), np.array(0.37))
        probe[0, :3, 3] = [0.3, -0.2, 0.5]
        loops = self.pinned.loop_residual(self.pinned.state(theta, self.offsets_of(offsets), probe))
        loops = loops.reshape(-1, 6)
        forward = pose_residual(probe)[0]
        backward = -pose_residual_inverse(probe, pose_residual(probe))[0]
        kinds = np.zeros(len(loops), dtype=int)
        for kind, expected in ((1, forward), (-1, backward)):
            kinds[np.all(np.abs(loops - expected) < 1e-12, axis=1)] = kind
        if np.any((kinds == 0) & np.any(np.abs(loops) > 1e-12, axis=1)):
            return None
        _, blocks = self.equations(self.state(theta, self.offsets_of(offsets), values), values)
        size = 6 * len(loops)
        tiled = [np.repeat(block, size, axis=0) for block in blocks]
        solve = self.correction(tiled, np.eye(size), np.ones(size, dtype=bool))
        return kinds, solve, values[0]

    def newton(
        self, theta: Array, offsets: Array, target: Array, tolerance: Array, working: Array
    ) -> tuple[Array, Array, Array, Array]:
        kernels = compiled_kernels(KERNELS, int(working.sum()))
        if kernels is None:
            return super().newton(theta, offsets, target, tolerance, working)
        solved, turned = np.ascontiguousarray(theta), np.ascontiguousarray(offsets)
        unfolded = np.empty_like(solved)
        placed = np.empty((len(target), 4, 4))  # (read for the poses ``working`` only)
        placed[working] = self.task.displacement(target[working])
        sizes, corrected, leading, _ = kernels.pinned_newton(
            solved, turned, placed, tolerance, working, NEWTON_ITERATIONS, MAX_CORRECTION, RECENTRE_ANGLE,
            self.kernel_model, self.pinned._loops, self.kernel_blocks, unfolded,
        )
        if solved is not theta or turned is not offsets:  # (copies of non-contiguous arrays)
            theta[:], offsets[:] = solved, turned
        return sizes[working], corrected[working], leading[working], unfolded[working]
