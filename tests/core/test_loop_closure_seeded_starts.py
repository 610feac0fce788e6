"""A large batch continued from its own solved poses (screwkit.core._seeded_starts) closes every pose to
the configuration that the continuation from the reference configuration alone gives, and a pose whose
way from its seed fails is taken again from the reference."""

import functools

import numpy as np
import pytest

import screwkit as sk
from screwkit.core import _seeded_starts
from screwkit.core.loop_closure import (
    FINAL_TOLERANCE,
    MAX_STEP,
    STEP_TOLERANCES,
    _close_chunk,
    _continue,
    _system,
    close_loops,
)
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.graph_kinematics import kinematics_of
from tests.mechanisms import gough_stewart, gough_stewart_points

POSES = 2 * _seeded_starts.MIN_BATCH  # (a batch that is seeded)


def _single_joints(kinematics):
    """The columns of the joints of one variable (a spherical joint's angles fold into its offset)."""
    model = kinematics.model
    return np.concatenate([columns for _, _, columns in model.joints.values() if len(columns) == 1])


def _gough_stewart_poses(rng):
    mechanism = sk.mechanism(gough_stewart(*gough_stewart_points()))
    reference = np.asarray(mechanism.reference_pose, dtype=float)
    spread = np.array([0.5, 0.5, 0.3, 0.5, 0.5, 0.8])  # characteristic lengths (the unit) and radians
    return mechanism, reference + rng.uniform(-spread, spread, (POSES, 6))


def _from_reference_alone(kinematics, targets):
    """Each pose solved in a batch too small to be seeded."""
    size = _seeded_starts.MIN_BATCH - 1
    parts = [close_loops(kinematics.model, kinematics.task, targets[k : k + size]) for k in range(0, len(targets), size)]
    return np.concatenate([p.theta for p in parts]), np.concatenate([p.reached for p in parts])


@pytest.mark.parametrize("name", ["h4", "ragnar", "delta", "6-UPS"])
def test_seeded_configurations_are_those_from_the_reference(name):
    rng = np.random.default_rng(21)
    if name == "6-UPS":
        mechanism, poses = _gough_stewart_poses(rng)
    else:
        mechanism = load_mechanism(name)
        poses = mechanism.random_poses(rng, POSES)
    kinematics = kinematics_of(mechanism)
    targets = kinematics._targets(poses)
    model = kinematics.model
    reference = kinematics.task.values(model.state(np.zeros((1, model.size))))
    assert np.sum(np.max(np.abs(targets - reference), axis=1) > MAX_STEP) >= _seeded_starts.MIN_BATCH  # seeded
    seeded = close_loops(kinematics.model, kinematics.task, targets)
    theta, reached = _from_reference_alone(kinematics, targets)
    assert reached.sum() > 0.9 * POSES
    assert np.all(seeded.reached[reached])  # nothing reached from the reference is lost
    both = seeded.reached & reached
    columns = _single_joints(kinematics)
    scale = np.maximum(1.0, np.abs(theta[both][:, columns]))
    assert np.max(np.abs(seeded.theta[both][:, columns] - theta[both][:, columns]) / scale) < 1e-9
    # the state returned is the model at the returned joint values, pose by pose
    assert np.array_equal(seeded.state.theta, seeded.theta)


def test_poses_whose_way_from_their_seed_fails_are_taken_from_the_reference():
    h4 = load_mechanism("h4")
    kinematics = kinematics_of(h4)
    model, task = kinematics.model, kinematics.task
    targets = kinematics._targets(h4.random_poses(np.random.default_rng(22), POSES))
    system = _system(model, task)
    failed = []

    def from_starts(*args, **kwargs):  # every step refused: no correction is within a zero jump limit
        out = _continue(system, *args, step_length=MAX_STEP, jump_limit=0.0, spherical_secant=True,
                        step_tolerances=STEP_TOLERANCES, **kwargs)
        failed.append(int(np.sum(~(out[2] < FINAL_TOLERANCE))))
        return out

    reference = functools.partial(_close_chunk, model, task)
    theta, offsets, residual, reasons, state = _seeded_starts.close_seeded(
        system, targets, reference, from_starts, FINAL_TOLERANCE, MAX_STEP
    )
    reference_values = task.values(model.state(np.zeros((1, model.size))))
    far = int(np.sum(np.max(np.abs(targets - reference_values), axis=1) > MAX_STEP))
    assert failed == [far - far // _seeded_starts.POSES_PER_SEED] and far >= _seeded_starts.MIN_BATCH
    alone, reached = _from_reference_alone(kinematics, targets)
    assert np.array_equal(residual < FINAL_TOLERANCE, reached) and reached.all()
    columns = _single_joints(kinematics)
    assert np.max(np.abs(theta[:, columns] - alone[:, columns])) < 1e-9
    assert np.array_equal(state.theta, theta) and set(reasons) == {""}
    for key, value in offsets.items():  # the state is the model at the returned configuration
        assert np.array_equal(state.offsets[key], value)


def test_a_batch_of_repeated_poses_is_seeded_by_its_distinct_ones():
    h4 = load_mechanism("h4")
    kinematics = kinematics_of(h4)
    three = kinematics._targets(h4.random_poses(np.random.default_rng(23), 3))
    repeated = np.tile(three, (POSES // 3 + 1, 1))
    assert _seeded_starts.seed_rows(repeated, 50).tolist() in ([0, 1, 2], [0, 2, 1])
    closed = close_loops(kinematics.model, kinematics.task, repeated)
    alone, reached = _from_reference_alone(kinematics, three)
    columns = _single_joints(kinematics)
    assert closed.reached.all() and reached.all()
    assert np.max(np.abs(closed.theta[:, columns] - np.tile(alone, (POSES // 3 + 1, 1))[:, columns])) < 1e-9
