"""Seeded starts of the loop-closure continuation (private; :mod:`screwkit.core.loop_closure`): a large
batch continues most of its poses from an already solved pose of the same batch nearby, not from the
reference configuration.

A batch's poses are far from the reference configuration (an H4 pose takes 2.5 continuation steps from
it) but near each other. :func:`close_seeded` solves a few *seed* poses spread over the batch's poses
farther than one step from the reference, from the reference (farthest-point sampling in the
continuation's own step measure, the largest scaled task coordinate difference: Gonzalez, *Theoretical
Computer Science* 38, 1985, whose greedy choice covers them within twice the best radius), then every
other far pose from its nearest solved seed: the seed's closed configuration and its task values are the
start of that pose's straight way, the orientation of the seed's equations
(:meth:`~screwkit.core._working_modes.Orientations.taken`) the one each step must keep. A pose reached
along reference → seed → pose is in the working and assembly mode connected to the reference along that
path (every step of both ways kept its orientation). A pose whose way from its seed fails is taken again
from the reference (and its retries), so every pose reached from the reference alone is still reached.

Determinism: the seeds are a function of the batch (the sampling starts at its first far pose, ties go to
the first), so one batch gives one result; the same pose in another batch (or another chunk of
:data:`~screwkit.core.loop_closure.CHUNK` poses) comes from another seed, to the same configuration
within the closure's tolerance (the configurations agree to round-off, ~1e-11, not bit for bit).
Batches with fewer than :data:`MIN_BATCH` poses farther than one step from the reference are solved
from it alone (a map near the reference configuration: a step per pose either way).

Examples
--------
>>> import numpy as np
>>> from screwkit.robots.catalog import load_mechanism
>>> from screwkit.robots.graph_kinematics import kinematics_of
>>> h4 = load_mechanism("h4")
>>> kinematics = kinematics_of(h4)
>>> poses = h4.random_poses(np.random.default_rng(1), 2 * MIN_BATCH)
>>> closed = kinematics.solve(poses)  # seeded: most poses are several steps from the reference
>>> alone = kinematics.solve(poses[:5])  # from the reference alone
>>> columns = [kinematics.model.joints[name][2][0] for name in kinematics.actuated]
>>> bool(np.allclose(closed.theta[:5, columns], alone.theta[:, columns], rtol=0.0, atol=1e-9))
True
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, cast

import numpy as np

from ._closure_parts import assembled, replace_rows
from ._working_modes import Orientations
from .kinematic_model import KinematicState

__all__ = ["MIN_BATCH", "POSES_PER_SEED", "close_seeded", "seed_rows"]

Array = np.ndarray

#: Batches with fewer poses are solved from the reference configuration alone.
MIN_BATCH = 256
#: Poses per seed (the closure's time per H4 pose, CPU, with the working-mode check of every step, load < 1).
#: 2,000 poses in one batch: 96 seeds 140-143 µs, 128 seeds 146-148, 256 seeds 179-181 (a seed costs a
#: pose's way from the reference), against 201-213 from the reference alone; 32 seeds, 200 more poses from
#: them, then the rest from all, 160-166. Batches of 512 (as the verdicts take them): 16 per seed 173-203,
#: 8 per seed 174-204, 4 per seed 209-242, against 208-276 from the reference alone.
POSES_PER_SEED = 16


def seed_rows(targets: Array, count: int) -> Array:
    """``count`` rows of ``targets`` spread over them: farthest-point sampling from the first row, each
    next the farthest from those chosen in the largest coordinate difference (module docstring).

    Parameters
    ----------
    targets : numpy.ndarray, shape (B, k)
        The task's scaled values.
    count : int
        How many rows (at most ``B``).

    Returns
    -------
    numpy.ndarray of int, shape (c,)
        Distinct rows, ``c = count`` unless fewer distinct values are there.

    Examples
    --------
    >>> seed_rows(np.array([[0.0], [0.1], [1.0], [0.5]]), 3).tolist()
    [0, 2, 3]
    >>> seed_rows(np.array([[0.0], [1.0], [0.0], [1.0]]), 3).tolist()
    [0, 1]
    """
    chosen = np.zeros(count, dtype=int)
    distance = np.max(np.abs(targets - targets[0]), axis=1)
    for slot in range(1, count):
        chosen[slot] = int(np.argmax(distance))
        if distance[chosen[slot]] == 0.0:  # every row is one already chosen
            return chosen[:slot]
        distance = np.minimum(distance, np.max(np.abs(targets - targets[chosen[slot]]), axis=1))
    return chosen


def _stacked(system: Any, offsets: dict[str, Array], count: int) -> Array:
    """The spherical joints' offsets as the continuation stacks them ``(count, K, 4, 4)``."""
    if not system.spherical:
        return np.zeros((count, 0, 4, 4))
    return np.stack([offsets[key] for key in system.spherical], axis=1)


def close_seeded(
    system: Any,
    targets: Array,
    from_reference: Callable[[Array], tuple[Array, dict[str, Array], Array, Array, KinematicState]],
    from_starts: Callable[..., tuple[Any, ...]],
    tolerance: float,
    step_length: float,
) -> tuple[Array, dict[str, Array], Array, Array, KinematicState]:
    """A chunk's configurations, its far poses mostly continued from a solved seed nearby (module docstring).

    Parameters
    ----------
    system : object
        The continuation's equations (:mod:`screwkit.core.loop_closure`).
    targets : numpy.ndarray, shape (B, k)
        The task's scaled values.
    from_reference : callable
        Solves targets from the reference configuration (with its retries): theta, offsets, residual,
        reasons, state.
    from_starts : callable
        ``from_starts(targets, theta, offsets, start, modes=...)``: one continuation from given
        configurations, as the loop closure's; theta, offsets and the residual first, the state fifth.
    tolerance : float
        The residual below which a pose is reached.
    step_length : float
        The continuation's longest step: a pose within one step of the reference is solved from it.

    Returns
    -------
    tuple
        Theta ``(B, n)``, offsets (name → ``(B, 4, 4)``), residual ``(B,)``, reasons ``(B,)`` and the
        state, as ``from_reference``'s.

    Examples
    --------
    See the module docstring.
    """
    model, count = system.model, len(targets)
    reference = system.task.values(model.state(np.zeros((1, model.size))))
    far = np.flatnonzero(np.max(np.abs(targets - reference), axis=1) > step_length)
    if far.size < MIN_BATCH:  # (a map's poses near the reference: one step each anyway)
        return from_reference(targets)
    seeds = far[seed_rows(targets[far], far.size // POSES_PER_SEED)]
    rest = np.setdiff1d(far, seeds)
    first_rows = np.setdiff1d(np.arange(count), rest)  # the seeds and the poses near the reference
    first = from_reference(targets[first_rows])
    solved = np.flatnonzero((first[2] < tolerance) & np.isin(first_rows, seeds))
    if not solved.size:
        return from_reference(targets)
    distance = np.max(np.abs(targets[rest][:, None] - targets[first_rows[solved]][None]), axis=2)
    near = np.argmin(distance, axis=1)  # (ties: the first seed)
    seed_offsets = _stacked(system, first[1], len(first_rows))[solved]
    modes = Orientations(system, first[0][solved], seed_offsets, targets[first_rows[solved]]).taken(near)
    starts = targets[first_rows[solved]][near]
    theta, offsets, residual, _, state, _ = from_starts(
        targets[rest], first[0][solved][near], seed_offsets[near], starts, modes=modes
    )
    order = np.argsort(np.concatenate([first_rows, rest]))
    state = cast(KinematicState, assembled(count, [(first_rows, first[4]), (rest, state)]))
    theta = np.concatenate([first[0], theta])[order]
    residual = np.concatenate([first[2], residual])[order]
    reasons = np.concatenate([first[3], np.full(len(rest), "", dtype=object)])[order]
    rest_offsets = system.offsets_of(offsets)
    offsets_out = {key: np.concatenate([first[1][key], rest_offsets[key]])[order] for key in first[1]}
    failed = rest[~(residual[rest] < tolerance)]
    if failed.size:  # from the reference, as without seeds
        again = from_reference(targets[failed])
        theta[failed], residual[failed], reasons[failed] = again[0], again[2], again[3]
        for key, value in offsets_out.items():
            value[failed] = again[1][key]
        replace_rows(state, failed, again[4])
    return theta, offsets_out, residual, reasons, state
