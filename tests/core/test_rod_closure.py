"""The loop closure with rods replaced by their distance equations (screwkit.core._rod_closure) gives the
configurations of the loop closure over every loop's six equations, its Jacobian is the derivative of its
equations, and its compiled and numpy correctors agree."""

import networkx as nx
import numpy as np
import pytest
from hypothesis import given, settings

import screwkit as sk
from screwkit.core import _rod_closure
from screwkit.core._rod_closure import _RodLoops, rods_of
from screwkit.core.loop_closure import LAST_TOLERANCES, _system, close_loops
from screwkit.graphs.joints import spherical
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.graph_kinematics import graph_kinematics, kinematics_of
from tests.mechanisms import gough_stewart, gough_stewart_points, moved
from tests.strategies import rigid_motions, unit_factors

ROD_ROBOTS = ["h4", "quattro", "ragnar", "veloce", "delta", "v4"]


def _pinned(kinematics):
    return kinematics.model.pinned_model(kinematics.task.coordinates.link)


@pytest.mark.parametrize(("name", "count"), [("h4", 8), ("delta", 6), ("ragnar", 8), ("quattro", 8)])
def test_rods_are_the_links_between_two_balls(name, count):
    kinematics = kinematics_of(load_mechanism(name))
    rods = rods_of(_pinned(kinematics))
    assert rods is not None and len(rods.names) == count
    model = kinematics.model
    for pair, centres, length in zip(rods.joints, rods.centres, rods.lengths, strict=True):
        assert all(model.types[key] == "S" for key in pair)
        # each ball's centre lies on its three rotation axes: (c × s = s0) for every screw of the joint
        for key, centre in zip(pair, centres, strict=True):
            for column in model.joints[key][2]:
                row = model.columns[column].row
                np.testing.assert_allclose(np.cross(centre, row[:3]), row[3:], atol=1e-12)
        assert length == pytest.approx(np.linalg.norm(centres[1] - centres[0]))


def test_mechanisms_whose_loops_no_rod_closes_keep_every_equation():
    kinematics = kinematics_of(sk.mechanism(gough_stewart(*gough_stewart_points())))
    assert rods_of(_pinned(kinematics)) is None
    assert not isinstance(_system(kinematics.model, kinematics.task), _RodLoops)
    planar = kinematics_of(sk.mechanism("examples/planar_3rpr.toml"))
    assert not isinstance(_system(planar.model, planar.task), _RodLoops)


@pytest.mark.parametrize("name", ROD_ROBOTS)
def test_the_rods_equations_give_every_loops_configurations(name):
    robot = load_mechanism(name)
    kinematics = kinematics_of(robot)
    assert isinstance(_system(kinematics.model, kinematics.task), _RodLoops)
    poses = robot.random_poses(np.random.default_rng(21), 300)
    targets = kinematics._targets(poses)
    rods = close_loops(kinematics.model, kinematics.task, targets)
    every = close_loops(kinematics.model, kinematics.task, targets, rods=False)
    both = rods.reached & every.reached
    assert both.mean() > 0.97
    columns = [kinematics.model.joints[key][2][0] for key in kinematics.actuated]
    np.testing.assert_allclose(rods.theta[both][:, columns], every.theta[both][:, columns], rtol=0, atol=1e-9)
    # the whole model's loops close at the rods' configurations (the balls placed back)
    state = kinematics.model.state(rods.theta[both], {key: value[both] for key, value in rods.offsets.items()})
    assert np.abs(kinematics.model.loop_residual(state)).max() < 1e-9


def test_the_rods_jacobian_is_the_derivative_of_their_equations():
    robot = load_mechanism("h4")
    kinematics = kinematics_of(robot)
    system = _system(kinematics.model, kinematics.task)
    rng = np.random.default_rng(4)
    theta = np.zeros((5, kinematics.model.size))
    theta[:, system.remaining] = rng.uniform(-0.3, 0.3, (5, system.remaining.size))
    target = kinematics._targets(robot.random_poses(rng, 5))
    residual, blocks = system.equations(system.state(theta, {}, target), target)
    jacobian = system._jacobian(system.state(theta, {}, target))
    step = 1e-6
    for column, position in zip(system.remaining, range(system.remaining.size), strict=True):
        moved = [theta.copy(), theta.copy()]
        moved[0][:, column] += step
        moved[1][:, column] -= step
        ahead, behind = (system.equations(system.state(m, {}, target), target)[0] for m in moved)
        np.testing.assert_allclose(jacobian[:, :, position], (ahead - behind) / (2 * step), atol=1e-8)
    # two blocks: legs 1 and 4 on the platform's half turning about R_I, legs 2 and 3 on R_II's; 4 rods, 3
    # variables each (the two arms and the hinge)
    assert residual.shape == (5, 8) and [block.shape[1:] for block in blocks] == [(2, 4, 3)]


def test_compiled_and_numpy_correctors_agree(monkeypatch):
    pytest.importorskip("numba")
    robot = load_mechanism("ragnar")
    kinematics = kinematics_of(robot)
    system = _system(kinematics.model, kinematics.task)
    far = robot.random_poses(np.random.default_rng(8), 400)  # (>= the compiled paths' batch)
    poses = robot.default_pose + 0.05 * (far - robot.default_pose)  # Newton's basin from the reference
    target = kinematics._targets(poses)
    runs = []
    for compiled in (True, False):
        if not compiled:
            monkeypatch.setattr(_rod_closure, "compiled_kernels", lambda name, size: None)
        theta = np.zeros((len(poses), kinematics.model.size))
        offsets = np.tile(np.eye(4), (len(poses), len(system.spherical), 1, 1))
        tolerance = np.tile(LAST_TOLERANCES, (len(poses), 1))
        working = np.ones(len(poses), dtype=bool)
        sizes = system.newton(theta, offsets, target, tolerance, working)[0]
        runs.append((theta, offsets, sizes, system.last_blocks(np.arange(len(poses)))))
    (theta, offsets, sizes, blocks), (theta_np, offsets_np, sizes_np, blocks_np) = runs
    converged = (sizes < 1e-6) & (sizes_np < 1e-6)  # (the size before a last correction of at most 1e-7)
    assert converged.mean() > 0.9
    np.testing.assert_allclose(theta[converged], theta_np[converged], rtol=0, atol=1e-11)
    np.testing.assert_allclose(offsets[converged], offsets_np[converged], rtol=0, atol=1e-11)
    for block, twin in zip(blocks, blocks_np, strict=True):
        np.testing.assert_allclose(block[converged], twin[converged], rtol=0, atol=1e-10)


def _rebuilt(graph):
    out = nx.MultiDiGraph(**graph.graph)
    out.add_edges_from(graph.edges(keys=True, data=True))
    return out


def _delta_variant(change):
    """The Delta's twist graph changed by ``change(graph)``, as a graph mechanism at its default pose."""
    delta = load_mechanism("delta")
    graph = _rebuilt(delta.twist_graph())
    change(graph)
    return delta, graph_kinematics(graph, point=np.array(delta.default_pose))


def _ball_hinge(graph):
    # arm 1 hangs from a ball held by two stays (rods to the base): a ball that is no rod's
    graph.remove_edge("base", "arm1", "A1")
    hinge = np.array([163.68, 0.0, 0.0])
    graph.add_edge("base", "arm1", key="H1", joint=spherical("H1", hinge))
    for k, (on_base, on_arm) in enumerate([([0, 50, 100], [0, 50, 0]), ([100, -50, 0], [0, -50, 0])], start=1):
        graph.add_edge("base", f"stay{k}", key=f"B{k}", joint=spherical(f"B{k}", hinge + on_base))
        graph.add_edge(f"stay{k}", "arm1", key=f"C{k}", joint=spherical(f"C{k}", hinge + on_arm))


def _idle_rod_on_the_base(graph):
    graph.add_edge("base", "idle", key="Y1", joint=spherical("Y1", [30.0, 0.0, 0.0]))
    graph.add_edge("idle", "base", key="Y2", joint=spherical("Y2", [0.0, 40.0, 0.0]))


@pytest.mark.parametrize("change", [_ball_hinge, _idle_rod_on_the_base])
def test_graphs_the_rods_equations_do_not_carry_keep_every_loops_equations(change):
    # (a reviewer's graphs: a ball that is no rod's folded its angles into offsets the rods' equations
    # ignore, and 66 of 200 poses came back unreached; a rod between two placed links has no variable,
    # and the corrector raised numpy's reshape error)
    delta, kinematics = _delta_variant(change)
    assert rods_of(_pinned(kinematics)) is None
    assert not isinstance(_system(kinematics.model, kinematics.task), _RodLoops)
    closed = close_loops(kinematics.model, kinematics.task, kinematics._targets(
        delta.random_poses(np.random.default_rng(5), 60)))
    assert closed.reached.all()


def test_poses_just_out_of_reach_are_flagged_not_closed_by_a_stretched_ball():
    # (a new user's finding: just past a leg's reach the rods' Newton stops at the least-squares gap, and
    # a closing ball written as D_rod⁻¹ D_platform absorbed it as a translation, the whole model's loops
    # then "closed": on these rays 25 of 40 poses 1 µm to 0.2 mm out of reach were accepted; a ball turns
    # about its centre, so the gap stays in the loop residual)
    delta = load_mechanism("delta")
    kinematics = kinematics_of(delta)
    start = np.asarray(delta.default_pose, dtype=float)
    rng = np.random.default_rng(0)
    for _ in range(10):
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        inside, outside = 0.0, 3000.0  # mm along the ray: the closed form's reach edge, by bisection
        for _ in range(60):
            middle = (inside + outside) / 2
            reached = delta.reachable([start + middle * direction])[0]
            inside, outside = (middle, outside) if reached else (inside, middle)
        steps = inside + np.array([-0.01, 0.001, 0.01, 0.05, 0.2])
        targets = kinematics._targets(start + steps[:, None] * direction)
        closed = close_loops(kinematics.model, kinematics.task, targets)
        assert closed.reached.tolist() == [True, False, False, False, False], (direction, closed.residual)


@settings(max_examples=8, deadline=None)
@given(motion=rigid_motions(), factor=unit_factors)
def test_the_rods_closure_is_invariant_under_frame_and_unit(motion, factor):
    # the Delta moved rigidly and described in another unit: the same arm angles at the moved poses
    # (its coordinates then run along the moved frame's axes, from the moved platform point)
    rotation, translation = motion
    delta = load_mechanism("delta")
    graph = delta.twist_graph()
    point = np.asarray(delta.default_pose, dtype=float)
    poses = delta.random_poses(np.random.default_rng(2), 12)
    here = graph_kinematics(graph, point=point)
    there = graph_kinematics(moved(graph, rotation, translation, factor), point=(rotation @ point + translation) * factor)
    assert isinstance(_system(there.model, there.task), _RodLoops)
    closed = close_loops(here.model, here.task, here._targets(poses))
    moved_poses = (poses - point) @ rotation.T * factor + (rotation @ point + translation) * factor
    other = close_loops(there.model, there.task, there._targets(moved_poses))
    assert np.array_equal(closed.reached, other.reached) and closed.reached.sum() >= 10
    columns = [here.model.joints[key][2][0] for key in here.actuated]
    np.testing.assert_allclose(closed.theta[closed.reached][:, columns], other.theta[other.reached][:, columns],
                               rtol=0, atol=1e-9)
