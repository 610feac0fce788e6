"""Loop-closure kinematics of any twist graph: the joint values at given platform poses (inverse
kinematics) or given actuated-joint values (forward kinematics), by continuation from the graph's
reference configuration.

The mechanism's model is :class:`~screwkit.core.kinematic_model.KinematicModel` (product of exponentials
over a spanning tree, one loop-closure equation per joint off it). A *task* adds the equations that
say where the mechanism should be:

* :class:`~screwkit.core.kinematic_tasks.PoseTask`: the coordinates of a link (the platform by
  default): the position of a point of it along the translation directions of its motion, and its
  rotation vector along the rotation directions
  (:func:`~screwkit.core.task_coordinates.task_coordinates`: both read off the link's twist system
  at the reference configuration, so a Schoenflies motion gets ``x, y, z, phi``, a planar one ``x, y, phi``, a
  spherical one ``rx, ry, rz``); with ``rotations=False`` only a point of the link (the five-bar's end
  point), whose orientation then stays free;
* :class:`~screwkit.core.kinematic_tasks.JointTask`: the actuated joints' values (radians, lengths).

:func:`close_loops` then follows the straight path from the start's task values to each target in
steps no longer than :data:`MAX_STEP` (characteristic lengths or radians), closing the loops and the
task at every step by Gauss–Newton iterations with the minimum-norm correction (the Moore–Penrose
step ``Δθ = −Jᵀ (J Jᵀ + λ I)⁻¹ F``, Levenberg's tiny ``λ`` so that the dependent equations of an
overconstrained loop leave it solvable; Nocedal & Wright, *Numerical Optimization*, 2nd ed., 2006,
§10.3), so that each pose stays in the working and assembly mode connected to the start. A pose
whose path leaves the mechanism's reach, runs into a singularity where Newton's method stops
converging, or gives non-finite values is flagged with the reason and the residual — never returned
as a configuration. All poses of a batch move together (arrays with a leading batch axis); a large
batch continues most of its poses from its own poses solved nearby (:mod:`screwkit.core._seeded_starts`).

The predictor-corrector follows Allgower & Georg, *Introduction to Numerical Continuation Methods*,
2003, Chs. 2-3 (the Moore-Penrose Newton corrector): the secant of the last two steps predicts each
step (every joint variable, a spherical joint's angles taken before they fold into its offset), the
tangent at the reference configuration the first step when the task fixes its link's pose (else the
first step starts at the reference configuration, and its first correction is the tangent step),
Newton's method corrects it, and a step is trusted when its corrections stay small: the whole way
the corrector goes from the predicted values (from the previous configuration on a first step
without predictor) is at most :data:`JUMP_LIMIT`, else the pose is taken again in shorter steps
from its last trusted step. The
minimum-norm correction lies in the row space of the equations' Jacobian, the orthogonal
complement of its null space, so an internal motion (a rod's spin about its own axis) never enters
the measure at first order. A step's iterations stop once the residual is within its tolerance or
the last correction is small enough that Newton's quadratic convergence leaves a residual of its
square (the last step's is then checked on the whole model); a step on the way also stops once the
error that the corrector's contraction ``Θ = |Δθₖ| / |Δθₖ₋₁|`` leaves, ``Θ / (1 − Θ) |Δθₖ|``, is
within :data:`STEP_ERROR` (the a-posteriori bound of a contraction; Deuflhard, *Newton Methods for
Nonlinear Problems*, 2004, Ch. 2). After a correction within :data:`REUSE_CORRECTION` (on a step on
the way: after the first) an iteration solves with the last factorisation (simplified Newton, ibid.).

When the task fixes its link's whole pose, a step's Newton iterations run in a compiled kernel when
numba is installed (:mod:`screwkit.core._newton_numba`: the model, the loops' residual and the
block-by-block correction, pose by pose), else in numpy over the batch (``_PinnedLoops``); the
two agree to round-off (:func:`screwkit.algebra.compiled.compiled_kernels` chooses). When, moreover,
every loop is closed by a *rod* (a binary link between two spherical joints: the distal links of a
Delta, an H4, a Ragnar), each rod's six loop equations and its balls' six angles give way to one
equation, the distance between its balls' centres (Merlet, *Parallel Robots*, 2nd ed., 2006, §3.1),
on the other joints (an H4 leg group: 4 equations in 3 variables instead of 24 in 27); the rods are
placed back after every step and the whole model's loops checked as for any mechanism
(:mod:`screwkit.core._rod_closure`; ``close_loops(..., rods=False)`` solves every loop's equations).

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> from screwkit.core.kinematic_tasks import PoseTask
>>> from screwkit.core.task_coordinates import task_coordinates
>>> arm = twist_graph("B", "E", [
...     ("B", "L", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("L", "E", revolute("R2", [0, 0, 1], [1, 0, 0], actuated=True))], dof=2)
>>> model = KinematicModel(arm)
>>> coordinates = task_coordinates(model, point=[1, 1, 0], rotations=False)
>>> coordinates.names
('x', 'y')
>>> task = PoseTask(model, coordinates)
>>> closed = close_loops(model, task, task.scaled_targets(np.array([[-1.0, 1.0]])))
>>> bool(closed.reached[0]), np.degrees(closed.theta[0]).round(6).tolist()  # the elbow as at the start
(True, [90.0, 0.0])
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from ._closure_parts import assembled, replace_rows
from ._closure_systems import (
    _LoopsAndTask,
    _PinnedLoops,
    _residual,
)
from ._rod_closure import _RodLoops, rods_of
from ._seeded_starts import close_seeded
from ._working_modes import Orientations, unreached_reasons
from .kinematic_model import KinematicModel, KinematicState
from .kinematic_tasks import PoseTask

__all__ = ["FINAL_TOLERANCE", "MAX_STEP", "ClosedConfigurations", "close_loops"]

Array = np.ndarray

#: The longest step of the continuation (characteristic lengths, or radians).
#: Measured on 2,000 H4 poses with the first step's tangent predictor: model evaluations per pose
#: 10.1 at 0.25, 8.6 at 0.35, 8.9 at 0.4 (2 % of the poses taken again at 0.25, 5 % at 0.35, 20 % at 0.5).
MAX_STEP = 0.35
#: The residual (characteristic lengths, radians) at which the Newton iterations of a step on the
#: way stop, and of the last step.
STEP_TOLERANCE = 1e-6
LAST_STEP_TOLERANCE = 1e-12
#: The Newton correction (radians, characteristic lengths) below which the iterations of a step on
#: the way, and of the last step, stop without evaluating the model again: Newton's method converges
#: quadratically, so the residual left is of the order of the correction's square (the last step's
#: is then checked, :data:`FINAL_TOLERANCE`). Such a step reports the residual before its last
#: correction, which :data:`LOST_TOLERANCE` judges: the corrections stay well below it (measured:
#: 1e-3 on the way left 24 of 2,000 H4 poses flagged as lost, 1e-2 over half).
STEP_CORRECTION = 1e-4
LAST_STEP_CORRECTION = 1e-7
#: The error left in the joint values (radians, characteristic lengths) at which the iterations of a
#: step on the way also stop, ``Θ / (1 − Θ) |Δθₖ|`` for a contraction ``Θ = |Δθₖ| / |Δθₖ₋₁| < 1/2``
#: (module docstring; the step then reports its residual before the last correction times ``Θ``): the
#: next step's predictor errs by far more (~1e-2). Measured on 2,000 H4 poses: 8.6 -> 7.3 model
#: evaluations per pose, the same poses reached. Not on the last step, nor on a retry (whose short
#: steps near a singularity converge slowly: the estimate there once lost a V4 pose).
STEP_ERROR = 1e-3
#: The Newton correction (radians, characteristic lengths) after which the next iteration solves with
#: the last factorisation (simplified Newton: its steps contract at a rate of the order of the distance
#: from the factorised point); on a step on the way, always after the first. Measured on 2,000 H4
#: poses: 8.7 -> 7.8 us per model evaluation, the same evaluations per pose.
REUSE_CORRECTION = 1e-4
#: (residual, correction, error, reuse) of a step on the way, of a retry's, of a last step.
STEP_TOLERANCES = np.array([STEP_TOLERANCE, STEP_CORRECTION, STEP_ERROR, math.inf])
RETRY_TOLERANCES = np.array([STEP_TOLERANCE, STEP_CORRECTION, 0.0, REUSE_CORRECTION])
LAST_TOLERANCES = np.array([LAST_STEP_TOLERANCE, LAST_STEP_CORRECTION, 0.0, REUSE_CORRECTION])
#: The residual below which a configuration is accepted (characteristic lengths, radians).
FINAL_TOLERANCE = 1e-9
#: A step whose Newton iterations end above this residual has lost the mechanism.
LOST_TOLERANCE = 1e-3
#: The largest correction Newton's method may make from a step's predicted values (after a first
#: step's first, tangent, iteration when it has no predictor), in radians or characteristic lengths:
#: beyond it the step may have jumped to another branch of the loop equations (another assembly or
#: working mode), and the rest of the pose's way is taken again from its last trusted step in steps
#: :data:`RETRY_REFINEMENT` times shorter, without the spherical
#: joints' secant (whose overshoot near a leg's serial singularity once took Ragnar poses to the
#: other elbow branch when the retry accepted any correction) and without the measure.
JUMP_LIMIT = 0.2
#: Poses solved together (bounds the memory of the batched Jacobians).
CHUNK = 1024
#: Refinements of the step tried for the poses the first continuation could not reach.
RETRY_REFINEMENT = 4
#: The most continuation steps taken for one pose.
MAX_STEPS = 2000


@dataclass(frozen=True)
class ClosedConfigurations:
    """The continuation's result over a batch.

    Attributes
    ----------
    theta : numpy.ndarray, shape (B, n)
        Joint values (spherical joints' in ``offsets``).
    offsets : dict
        Spherical joint name → rotation offsets ``(B, 4, 4)``.
    reached : numpy.ndarray of bool, shape (B,)
        True where the loops and the task closed to :data:`FINAL_TOLERANCE`.
    residual : numpy.ndarray, shape (B,)
        The largest loop or task residual (characteristic lengths, radians).
    reasons : numpy.ndarray of str, shape (B,)
        Why a pose was not reached (empty where it was).
    state : KinematicState or None
        The whole model at ``theta`` and ``offsets`` (where the loops and the task were checked), when
        :func:`close_loops` made it.
    """

    theta: Array
    offsets: dict[str, Array]
    reached: Array
    residual: Array
    reasons: Array
    state: KinematicState | None = None


def _continue(
    system: _LoopsAndTask,
    targets: Array,
    theta: Array,
    offsets: Array,
    start: Array,
    step_length: float,
    jump_limit: float,
    spherical_secant: bool,
    step_tolerances: Array,
    modes: Orientations,
) -> tuple[Array, Array, Array, Array, KinematicState, tuple[Array, Array, Array]]:
    """One continuation of a chunk, each pose in equal steps of at most ``step_length`` (a pose whose
    way is done rests; a step trusted only where it kept the orientations ``modes``); returns theta,
    offsets, the residual at the targets (inf where non-finite), the fraction of the way where each
    pose was lost (NaN if not), the whole model's state there,
    and each pose's last accepted step: its theta, offsets and fraction of the way."""
    model, task = system.model, system.task
    count = targets.shape[0]
    lost_at = np.full(count, np.nan)
    kept = (theta.copy(), offsets.copy(), np.zeros(count))  # the last step each pose was trusted at
    active = np.ones(count, dtype=bool)
    residual_size = np.zeros(count)
    way = np.max(np.abs(targets - start), axis=1, initial=0.0)
    own = np.clip(np.ceil(way / step_length), 1, MAX_STEPS)
    steps = int(np.max(own, initial=1))
    previous = theta.copy()  # each pose's joint values one step back, and the secant from them
    secant = np.zeros_like(theta)  # (a spherical joint's taken before its angles fold into its offset)
    extrapolated = np.ones(model.size, dtype=bool)
    extrapolated[system.spherical_columns] = spherical_secant
    for step in range(1, steps + 1):
        moving = step <= own
        target = start + (targets - start) * np.minimum(1.0, step / own)[:, None]
        ahead = active & moving & (step > 1)
        theta[ahead] += np.where(extrapolated, secant[ahead], 0.0)
        tangent = system.tangent(start, target) if step == 1 and spherical_secant else None
        if tangent is not None:  # the first step's predictor: the tangent at the reference configuration
            theta += tangent
            ahead = active & moving
        last = (step >= own)[:, None]  # (residual, correction) tolerances
        tolerance = np.where(last, LAST_TOLERANCES, step_tolerances)
        working = active & moving
        corrected = np.zeros(count)  # the corrections the predictor left, the measure of a jump
        residual_size[working], corrected[working], leading, unfolded = system.newton(
            theta, offsets, target, tolerance, working
        )
        if spherical_secant:  # the whole way from the predicted values counts
            corrected[working] += np.where(ahead[working], leading, 0.0)
        secant[working] = unfolded - previous[working]
        previous[working] = theta[working]
        bad = ~np.isfinite(residual_size) | ~np.all(np.isfinite(theta), axis=1)
        newly = active & moving & (bad | (residual_size > LOST_TOLERANCE) | (corrected > jump_limit))
        checked = active & moving & ~newly  # (the rods' corrector hands its own final Jacobian)
        newly |= ~modes.kept(system, theta, offsets, target, checked, getattr(system, "last_blocks", None))
        lost_at[newly] = np.minimum(1.0, step / own[newly])
        active &= ~newly
        trusted = active & moving
        kept[0][trusted], kept[1][trusted] = theta[trusted], offsets[trusted]
        kept[2][trusted] = np.minimum(1.0, step / own[trusted])
        theta[~np.all(np.isfinite(theta), axis=1)] = 0.0  # frozen and flagged, never propagated
    state = model.state(theta, system.offsets_of(offsets))  # the whole model's loops and task, as checked
    residual = _residual(model, task, state, targets)
    size = np.max(np.abs(residual), axis=1, initial=0.0)
    size[~active] = np.maximum(size[~active], LOST_TOLERANCE)  # a lost pose is never accepted
    return theta, offsets, np.where(np.isfinite(size), size, np.inf), lost_at, state, kept


def close_loops(
    model: KinematicModel,
    task: Any,
    targets: Array,
    *,
    rods: bool = True,
) -> ClosedConfigurations:
    """Joint values closing the loops and the task at each target, by continuation (module docstring).

    Parameters
    ----------
    model : KinematicModel
    task : PoseTask or JointTask
    targets : numpy.ndarray, shape (B, k)
        The task's scaled values (``task.scaled_targets``), reached from the reference configuration.
    rods : bool, default True
        When the task places the platform and rods (binary links between two balls) close every loop,
        solve the rods' distance equations on the other joints and place the rods after
        (:mod:`screwkit.core._rod_closure`); False solves every loop's six equations.

    Returns
    -------
    ClosedConfigurations

    Raises
    ------
    ScrewkitValueError
        If ``targets`` is not finite or has the wrong shape.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.core.kinematic_tasks import PoseTask
    >>> from screwkit.core.task_coordinates import task_coordinates
    >>> arm = twist_graph("B", "E", [
    ...     ("B", "L", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("L", "E", revolute("R2", [0, 0, 1], [1, 0, 0], actuated=True))], dof=2)
    >>> model = KinematicModel(arm)
    >>> task = PoseTask(model, task_coordinates(model, point=[1, 1, 0], rotations=False))
    >>> closed = close_loops(model, task, task.scaled_targets(np.array([[3.0, 0.0]])))  # beyond reach
    >>> bool(closed.reached[0]), closed.reasons[0][:38]
    (False, 'the loops and the task do not close at')
    """
    targets = np.asarray(targets, dtype=float)
    if targets.ndim != 2 or not np.all(np.isfinite(targets)):
        raise ScrewkitValueError(f"Expected finite targets of shape (B, k), got shape {targets.shape}.")
    out_theta = np.zeros((len(targets), model.size))
    out_offsets: dict[str, list[Array]] = {}
    residual = np.zeros(len(targets))
    reasons = np.full(len(targets), "", dtype=object)
    states, system = [], _system(model, task, rods)  # a large chunk's poses mostly from solved ones nearby
    steps = functools.partial(_continue, system, step_length=MAX_STEP, jump_limit=JUMP_LIMIT,
                              spherical_secant=True, step_tolerances=STEP_TOLERANCES)
    reference = functools.partial(_close_chunk, model, task, rods=rods)
    for begin in range(0, len(targets), CHUNK):
        chunk = slice(begin, begin + CHUNK)
        result = close_seeded(system, targets[chunk], reference, steps, FINAL_TOLERANCE, MAX_STEP)
        out_theta[chunk], residual[chunk], reasons[chunk] = result[0], result[2], result[3]
        states.append((chunk, result[4]))
        for key, value in result[1].items():
            out_offsets.setdefault(key, []).append(value)
    reached = residual < FINAL_TOLERANCE
    offsets = {key: np.concatenate(parts) for key, parts in out_offsets.items()}
    state = assembled(len(targets), states)
    return ClosedConfigurations(out_theta, offsets, reached, residual, reasons, state)


def _system(model: KinematicModel, task: Any, rods: bool = True) -> _LoopsAndTask:
    """The equations of ``task`` on ``model``, built once per task (kept in ``task.prepared``): with
    ``rods``, a pinned model's rods replaced by their distance equations when they close all its loops
    (:mod:`screwkit.core._rod_closure`)."""
    prepared = getattr(task, "prepared", {})
    name = "loop_closure" if rods else "loop_closure_every_loop"
    system = prepared.get(name)
    if system is None or system.model is not model:
        fixes_pose = isinstance(task, PoseTask) and task.fixes_pose and task.coordinates.link != model.base
        found = rods_of(model.pinned_model(task.coordinates.link)) if fixes_pose and rods else None
        if found is not None:
            system = _RodLoops(model, task, found)
        else:
            system = (_PinnedLoops if fixes_pose else _LoopsAndTask)(model, task)
        prepared[name] = system
    return system


def _close_chunk(
    model: KinematicModel, task: Any, targets: Array, *, rods: bool = True
) -> tuple[Array, dict[str, Array], Array, Array, KinematicState]:
    count = len(targets)
    system = _system(model, task, rods)

    def begin(rows: Array) -> tuple[Array, Array, Array]:
        """The reference configuration for ``rows`` poses, and the task's values there."""
        theta = np.zeros((int(rows.sum()), model.size))
        values = task.values(model.state(theta[:1]))
        offsets = np.tile(np.eye(4), (len(theta), len(system.spherical), 1, 1))
        return theta, offsets, np.repeat(values, len(theta), axis=0)

    everything = np.ones(count, dtype=bool)
    theta, offsets, start = begin(everything)
    modes = Orientations(system, theta, offsets, start)
    theta, offsets, residual, lost_at, state, kept = _continue(
        system, targets, theta, offsets, start, MAX_STEP, JUMP_LIMIT, True, STEP_TOLERANCES, modes
    )
    missed, changed = ~(residual < FINAL_TOLERANCE), np.full(count, "", dtype=object)
    for refinement in (RETRY_REFINEMENT, RETRY_REFINEMENT**2):  # again, in shorter steps, from the
        if not np.any(missed):  # last step each pose was trusted at; the second time only the poses
            break  # whose orientation a step would have changed (a leg grazing its singularity)
        fraction = kept[2][missed]
        retry_start = start[missed] + (targets[missed] - start[missed]) * fraction[:, None]
        modes = Orientations(system, kept[0][missed], kept[1][missed], retry_start)
        again = _continue(  # the steps are short: the corrections may be what they need
            system, targets[missed], kept[0][missed], kept[1][missed], retry_start, MAX_STEP / refinement,
            math.inf, False, RETRY_TOLERANCES, modes,
        )
        theta[missed], offsets[missed], changed[missed] = again[0], again[1], modes.changed
        residual[missed], lost_at[missed] = again[2], fraction + (1.0 - fraction) * again[3]
        replace_rows(state, missed, again[4])
        kept[0][missed], kept[1][missed] = again[5][:2]
        kept[2][missed] = fraction + (1.0 - fraction) * again[5][2]
        missed = ~(residual < FINAL_TOLERANCE) & (changed != "")
    reasons = unreached_reasons(residual, ~(residual < FINAL_TOLERANCE), lost_at, changed)
    return theta, system.offsets_of(offsets), residual, reasons, state
