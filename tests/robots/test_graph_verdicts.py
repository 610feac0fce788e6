"""The verdict path of a graph mechanism over poses (screwkit.robots.graph_kinematics): what it keeps
between the reach test and the analysis gives what solving again would."""

import pickle

import numpy as np

import screwkit as sk
from screwkit.robots import graph_kinematics as GK
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.graph_kinematics import kinematics_of

from ..mechanisms import gough_stewart, gough_stewart_points


def _gough_stewart_poses(count, seed):
    rng = np.random.default_rng(seed)
    return np.column_stack(
        [rng.uniform(-0.15, 0.15, (count, 2)), rng.uniform(0.9, 1.1, count), rng.uniform(-0.2, 0.2, (count, 3))]
    )


def test_solved_poses_are_read_back_as_solved(monkeypatch):
    graph = gough_stewart(*gough_stewart_points())
    poses = _gough_stewart_poses(30, 5)
    poses[7] = poses[2]  # a pose asked twice in one batch
    monkeypatch.setattr(GK, "MAX_CACHED_POSES", 16)  # the second batch overflows it: emptied, refilled
    kinematics = sk.mechanism(graph).parameters
    kinematics.solve(poses[:12])
    asked = np.concatenate([poses[::-1], poses[:5]])  # known, new, and known again within the batch
    again = kinematics.solve(asked)
    fresh = sk.mechanism(graph).parameters.solve(asked)  # nothing remembered
    assert again.reached.tolist() == fresh.reached.tolist()
    reached = fresh.reached
    np.testing.assert_array_equal(again.theta[reached], fresh.theta[reached])
    assert set(again.offsets) == set(fresh.offsets) == {f"S{i}" for i in range(1, 7)}
    for name, value in fresh.offsets.items():
        np.testing.assert_array_equal(again.offsets[name][reached], value[reached])
    third = kinematics.solve(asked)  # everything reached is now remembered
    np.testing.assert_array_equal(third.theta[reached], fresh.theta[reached])


def test_a_pose_out_of_reach_is_never_remembered():
    kinematics = kinematics_of(load_mechanism("h4"))
    poses = np.array([[0.0, 0.0, -3000.0, 0.0], [10.0, 0.0, -750.0, 0.1]])
    for _ in range(2):  # asked again: solved again, and out of reach again with its reason
        closed = kinematics.solve(poses)
        assert closed.reached.tolist() == [False, True]
        assert "do not close" in closed.reasons[0]


def test_forward_kinematics_remembers_its_poses():
    robot = sk.mechanism(gough_stewart(*gough_stewart_points()))
    kinematics = robot.parameters
    values = np.random.default_rng(3).uniform(-0.05, 0.05, (6, 6))
    poses, closed = kinematics.forward(values)
    assert closed.reached.all()
    remembered = kinematics.solve(poses)  # read back, not solved from the coordinates
    np.testing.assert_array_equal(remembered.theta, closed.theta)
    for name, value in closed.offsets.items():
        np.testing.assert_array_equal(remembered.offsets[name], value)


def _assert_same_state(state, expected):
    np.testing.assert_array_equal(state.theta, expected.theta)
    np.testing.assert_array_equal(state.current, expected.current)
    assert set(state.links) == set(expected.links)
    for link, value in expected.links.items():
        np.testing.assert_array_equal(state.links[link], value)


def test_the_continuations_state_is_the_models_at_the_solved_configurations():
    robot = sk.mechanism(gough_stewart(*gough_stewart_points()))
    kinematics, model = robot.parameters, robot.parameters.model
    poses = _gough_stewart_poses(40, 9)
    fresh = kinematics.solve(poses)  # all solved now: the continuation's state, row for row
    assert fresh.state is not None
    _assert_same_state(fresh.state, model.state(fresh.theta, fresh.offsets))
    again = kinematics.solve(poses[::3])  # remembered: the same rows of that state
    _assert_same_state(again.state, model.state(again.theta, again.offsets))
    assert kinematics.solve(poses).state is fresh.state  # the whole batch again: the state itself
    kinematics.remember(poses, fresh)  # another solution may now stand for a pose: none kept
    assert kinematics.solve(poses[5:7]).state is None
    closed = kinematics.solve(poses[5:7])
    expected = model.joint_table(model.state(closed.theta, closed.offsets), kinematics.reference)
    np.testing.assert_array_equal(robot.at(poses[5:7]).joints.screws, expected.screws)  # evaluated again


def test_a_pickled_graph_mechanism_keeps_its_poses_not_its_model_state():
    robot = sk.mechanism(gough_stewart(*gough_stewart_points()))
    kinematics = robot.parameters
    values = np.random.default_rng(4).uniform(-0.05, 0.05, (20, 6))
    poses, closed = kinematics.forward(values)  # remembered: the forward kinematics' configurations
    kinematics.solve(_gough_stewart_poses(20, 4))  # and the continuation's state of these
    copy = pickle.loads(pickle.dumps(robot))  # as a Dask client sends it to a worker
    assert copy.parameters._cache.recent is None and kinematics._cache.recent is not None
    assert len(pickle.dumps(robot)) < 200_000  # (the state of 20 poses alone: about 150 kB)
    there = copy.parameters.solve(poses)  # read back there, not solved again
    np.testing.assert_array_equal(there.theta, closed.theta)
