"""Loop-closure kinematics (screwkit.core.loop_closure, screwkit.core.kinematic_model): hand-derived
inverse and forward kinematics of a planar 2R arm, a four-bar and a 6-UPS Gough-Stewart platform,
coordinates named from the motion, Jacobians against finite differences, unreachable poses flagged,
and invariance under a change of frame and of length unit."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.algebra.rigid_motions import exp_screw, rotation_log, rotation_matrix
from screwkit.core import loop_closure
from screwkit.core._joint_rows import orthonormal_axes
from screwkit.core.kinematic_model import KinematicModel
from screwkit.core.kinematic_tasks import JointTask, PoseTask
from screwkit.core.loop_closure import close_loops
from screwkit.core.motion import moved_configurations, newton_closure
from screwkit.core.task_coordinates import task_coordinates
from screwkit.exceptions import ScrewkitValueError
from screwkit.graphs.joints import helical, parallelogram, prismatic, revolute, spherical
from screwkit.graphs.twistgraph import twist_graph

from ..mechanisms import gough_stewart, gough_stewart_points, moved, planar_3rpr
from ..strategies import rigid_motions, rotations, unit_factors


def arm_2r():
    """A planar 2R arm: R1 at the origin, R2 at (1, 0, 0), its end point at (1, 1, 0) (elbow at +90°)."""
    return twist_graph(
        "B",
        "E",
        [
            ("B", "L", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
            ("L", "E", revolute("R2", [0, 0, 1], [1, 0, 0], actuated=True)),
        ],
        dof=2,
    )


def arm_2r_inverse(x, y):
    """The hand-derived inverse kinematics of arm_2r (both links of length 1), the elbow branch of the
    reference (relative elbow angle in (0, π)); returned as displacements from the reference (0, π/2)."""
    c2 = (x * x + y * y - 2.0) / 2.0
    elbow = np.arccos(c2)
    shoulder = np.arctan2(y, x) - np.arctan2(np.sin(elbow), 1 + np.cos(elbow))
    return np.stack([shoulder, elbow - np.pi / 2], axis=-1)


def test_arm_2r_inverse_kinematics_matches_the_hand_derivation():
    rng = np.random.default_rng(3)
    targets = rng.uniform(-1.9, 1.9, size=(3000, 2))
    radius = np.hypot(*targets.T)
    # the straight way from (1, 1) must stay in the annulus 0.3 < r < 1.95 (no serial singularity on it)
    t = np.linspace(0, 1, 50)[:, None, None]
    way = np.array([1.0, 1.0]) + t * (targets - [1.0, 1.0])
    inside = (np.hypot(way[..., 0], way[..., 1]).min(axis=0) > 0.3) & (radius < 1.95)
    targets = targets[inside]
    model = KinematicModel(arm_2r())
    task = PoseTask(model, task_coordinates(model, point=[1, 1, 0], rotations=False))
    closed = close_loops(model, task, task.scaled_targets(targets))
    assert closed.reached.all()
    expected = arm_2r_inverse(*targets.T)
    difference = (closed.theta - expected + np.pi) % (2 * np.pi) - np.pi
    assert len(targets) > 1500 and np.abs(difference).max() < 1e-9


def test_out_of_reach_is_flagged_with_a_reason_never_returned():
    model = KinematicModel(arm_2r())
    task = PoseTask(model, task_coordinates(model, point=[1, 1, 0], rotations=False))
    closed = close_loops(model, task, task.scaled_targets(np.array([[1.0, 1.0], [2.5, 0.0], [0.5, 1.2]])))
    assert closed.reached.tolist() == [True, False, True]
    assert closed.reasons[0] == closed.reasons[2] == ""
    assert "do not close" in closed.reasons[1] and "residual" in closed.reasons[1]
    assert closed.residual[1] > 1e-3


def test_non_finite_targets_are_refused():
    model = KinematicModel(arm_2r())
    task = PoseTask(model, task_coordinates(model, point=[1, 1, 0], rotations=False))
    with pytest.raises(ScrewkitValueError, match="finite targets"):
        close_loops(model, task, np.array([[np.nan, 0.0]]))


def four_bar():
    """Crank A (0, 0) - B (1, 0), coupler B - C (3, 2), rocker C - D (3, 0)."""
    return twist_graph(
        "ground",
        "coupler",
        [
            ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
            ("crank", "coupler", revolute("B", [0, 0, 1], [1, 0, 0])),
            ("ground", "rocker", revolute("D", [0, 0, 1], [3, 0, 0])),
            ("rocker", "coupler", revolute("C", [0, 0, 1], [3, 2, 0])),
        ],
        dof=1,
    )


def test_four_bar_forward_kinematics_matches_the_circle_intersection():
    model = KinematicModel(four_bar())
    task = JointTask(model, ["A"])
    angles = np.linspace(-0.6, 0.6, 61)
    closed = close_loops(model, task, task.scaled_targets(angles[:, None]))
    assert closed.reached.all()
    state = model.state(closed.theta, closed.offsets)
    c = np.einsum("bij,j->bi", model.displacement(state, "coupler"), [3.0, 2.0, 0.0, 1.0])[:, :2]
    # hand derivation: B' = (cos a, sin a); C' on |C' - D| = 2 and |C' - B'| = sqrt(8), the upper branch
    b = np.stack([np.cos(angles), np.sin(angles)], axis=1)
    d = np.array([3.0, 0.0])
    gap = np.linalg.norm(d - b, axis=1)
    along = (8.0 - 4.0 + gap**2) / (2 * gap)  # distance from B' to the chord's foot
    height = np.sqrt(8.0 - along**2)
    unit = (d - b) / gap[:, None]
    normal = np.stack([-unit[:, 1], unit[:, 0]], axis=1)
    expected = b + along[:, None] * unit + height[:, None] * normal
    assert np.abs(c - expected).max() < 1e-9


def gs_model():
    return KinematicModel(gough_stewart(*gough_stewart_points()))


def gs_leg_lengths(poses):
    """Hand derivation: leg i runs from a_i to p + R(r) (c_i - c0), r the rotation vector (Rodrigues)."""
    base, platform = gough_stewart_points()
    centre = platform.mean(axis=0)
    rotation = rotation_matrix(
        poses[:, 3:] / np.maximum(np.linalg.norm(poses[:, 3:], axis=1, keepdims=True), 1e-300),
        np.linalg.norm(poses[:, 3:], axis=1),
    )
    ends = poses[:, None, :3] + np.einsum("bij,kj->bki", rotation, platform - centre)
    return np.linalg.norm(ends - base, axis=-1)


def test_gough_stewart_inverse_kinematics_matches_the_leg_lengths():
    model = gs_model()
    coordinates = task_coordinates(model)
    assert coordinates.names == ("x", "y", "z", "rx", "ry", "rz")
    assert np.allclose(coordinates.point, [0.0, 0.0, 1.0])  # the centroid of the spherical joints
    rng = np.random.default_rng(5)
    poses = np.concatenate(
        [rng.uniform(-0.1, 0.1, (2000, 3)) + np.array([0, 0, 1]), rng.uniform(-0.2, 0.2, (2000, 3))], axis=1
    )
    task = PoseTask(model, coordinates)
    closed = close_loops(model, task, task.scaled_targets(poses))
    assert closed.reached.all()
    sliders = [model.joints[f"P{i}"][2][0] for i in range(1, 7)]
    lengths = closed.theta[:, sliders] * model.length + gs_leg_lengths(
        np.array([[0.0, 0.0, 1.0, 0.0, 0.0, 0.0]])
    )
    assert np.abs(lengths - gs_leg_lengths(poses)).max() < 1e-9


def test_gough_stewart_forward_kinematics_returns_to_the_pose():
    model = gs_model()
    pose_task = PoseTask(model, task_coordinates(model))
    pose = np.array([[0.05, -0.03, 1.04, 0.1, -0.05, 0.15]])
    legs = gs_leg_lengths(pose) - gs_leg_lengths(np.array([[0.0, 0.0, 1.0, 0.0, 0.0, 0.0]]))
    joint_task = JointTask(model, [f"P{i}" for i in range(1, 7)])
    closed = close_loops(model, joint_task, joint_task.scaled_targets(legs))
    assert closed.reached.all()
    reached = pose_task.unscaled(pose_task.values(model.state(closed.theta, closed.offsets)))
    assert np.abs(reached - pose).max() < 1e-9


@pytest.mark.parametrize(
    ("joints", "names", "directions"),
    [
        (
            [
                ("B", "L1", revolute("R1", [0, 0, 1], [0, 0, 0])),
                ("L1", "L2", revolute("R2", [0, 0, 1], [1, 0, 0])),
                ("L2", "L3", prismatic("P", [0, 0, 1])),
                ("L3", "E", revolute("R3", [0, 0, 1], [1, 1, 0])),
            ],
            ("x", "y", "z", "phi"),
            [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, 1]],
        ),
        (
            [
                ("B", "L1", revolute("R1", [1, 0, 0], [0, 0, 0])),
                ("L1", "L2", revolute("R2", [0, 1, 0], [0, 0, 0])),
                ("L2", "E", revolute("R3", [0, 0, 1], [0, 0, 0])),
            ],
            ("rx", "ry", "rz"),
            [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
        ),
        ([("B", "E", prismatic("P", [1, 1, 0]))], ("t1",), [[2**-0.5, 2**-0.5, 0]]),
        ([("B", "E", helical("H", [0, 0, 1], [0, 0, 0], 0.1))], ("phi",), [[0, 0, 1]]),
    ],
    ids=["scara", "wrist", "oblique slider", "screw"],
)
def test_coordinates_are_named_from_the_motion(joints, names, directions):
    coordinates = task_coordinates(KinematicModel(twist_graph("B", "E", joints)))
    assert coordinates.names == names
    assert np.allclose(coordinates.directions, directions)


def test_planar_coordinates_and_the_joint_centroid():
    graph = planar_3rpr(
        np.array([[0, 0, 0], [1, 0, 0], [0.5, 0.8, 0.0]]),
        np.array([[0.4, 0.3, 0], [0.6, 0.3, 0], [0.5, 0.5, 0.0]]),
    )
    coordinates = task_coordinates(KinematicModel(graph))
    assert coordinates.names == ("x", "y", "phi")
    assert np.allclose(coordinates.point, [0.5, 1.1 / 3, 0.0])  # the mean of the platform's R points


def test_a_link_that_cannot_move_and_an_unknown_link_are_refused():
    rigid = twist_graph(
        "B",
        "E",
        [("B", "E", revolute("R1", [0, 0, 1], [0, 0, 0])), ("B", "E", revolute("R2", [0, 0, 1], [1, 0, 0]))],
    )
    with pytest.raises(ScrewkitValueError, match="loops hold fixed"):
        task_coordinates(KinematicModel(rigid))
    with pytest.raises(ScrewkitValueError, match="`link` to name a link"):
        task_coordinates(KinematicModel(arm_2r()), link="nowhere")


def _central_differences(function, theta, step=1e-6):
    """``d function / d theta`` of one configuration ``theta (1, n)`` by central differences."""
    columns = []
    for column in range(theta.shape[1]):
        plus, minus = theta.copy(), theta.copy()
        plus[0, column] += step
        minus[0, column] -= step
        columns.append((function(plus) - function(minus))[0] / (2 * step))
    return np.stack(columns, axis=-1)


def test_pose_task_jacobian_is_the_derivative_of_its_values():
    model = gs_model()
    task = PoseTask(model, task_coordinates(model), complete=True)
    theta = np.random.default_rng(2).uniform(-0.3, 0.3, (1, model.size))
    numeric = _central_differences(lambda t: task.values(model.state(t)), theta)
    assert np.abs(task.jacobian(model.state(theta))[0] - numeric).max() < 1e-7


def test_loop_jacobian_is_the_derivative_of_the_loop_residual():
    model = gs_model()
    # at a closed configuration (the residual's derivative is made of the current screws there)
    task = PoseTask(model, task_coordinates(model))
    closed = close_loops(model, task, task.values(model.state(np.zeros((1, model.size)))) + 0.05)
    numeric = _central_differences(lambda t: model.loop_residual(model.state(t, closed.offsets)), closed.theta)
    analytic = model.loop_jacobian(model.state(closed.theta, closed.offsets))[0]
    assert np.abs(analytic - numeric).max() < 1e-7


@settings(max_examples=40, deadline=None)
@given(rotations(), st.floats(0.0, np.pi))
def test_rotation_log_inverts_rodrigues_everywhere(rotation, angle):
    axis = rotation[:, 0]
    vector = rotation_log(rotation_matrix(axis, np.array(angle)))
    if angle < np.pi - 1e-6:
        assert np.allclose(vector, axis * angle, atol=1e-9)
    else:  # at π the axis's sign is free
        assert np.allclose(np.abs(vector), np.abs(axis * angle), atol=1e-6)
    assert np.allclose(
        rotation_matrix(vector / max(np.linalg.norm(vector), 1e-300), np.linalg.norm(vector)),
        rotation_matrix(axis, np.array(angle)),
        atol=1e-9,
    )


@settings(max_examples=15, deadline=None)
@given(rigid_motions(), unit_factors)
def test_forward_kinematics_is_invariant_under_frame_and_unit(motion, factor):
    rotation, translation = motion
    graph = gough_stewart(*gough_stewart_points())
    other = moved(graph, rotation, translation, factor)
    legs = np.array([[0.02, -0.01, 0.03, 0.0, 0.015, -0.02]])
    platforms = []
    for g, scale in ((graph, 1.0), (other, factor)):
        model = KinematicModel(g)
        task = JointTask(model, [f"P{i}" for i in range(1, 7)])
        closed = close_loops(model, task, task.scaled_targets(legs * scale))
        assert closed.reached.all()
        platforms.append(model.displacement(model.state(closed.theta, closed.offsets), "platform")[0])
    # the same motion seen in the other frame and unit: T g T⁻¹ with lengths times the factor
    frame = np.eye(4)
    frame[:3, :3], frame[:3, 3] = rotation, translation
    expected = frame @ platforms[0] @ np.linalg.inv(frame)
    expected[:3, 3] *= factor
    assert np.allclose(platforms[1][:3, :3], expected[:3, :3], atol=1e-9)
    assert np.allclose(
        platforms[1][:3, 3], expected[:3, 3], atol=1e-9 * factor * (1 + np.abs(translation).max())
    )


def test_spherical_joints_turn_past_the_gimbal_lock_of_their_angles():
    # one S joint driven 150° about its second axis: the offset carries the turn
    graph = twist_graph("B", "E", [("B", "E", spherical("S", [0, 0, 0]))], dof=3)
    model = KinematicModel(graph)
    task = PoseTask(model, task_coordinates(model))
    target = np.array([[0.0, np.radians(150), 0.0]])
    closed = close_loops(model, task, target)
    assert closed.reached.all()
    rotation = model.displacement(model.state(closed.theta, closed.offsets), "E")[0, :3, :3]
    assert np.allclose(rotation, rotation_matrix(np.array([0.0, 1.0, 0.0]), np.radians(150)), atol=1e-9)


def test_pinning_the_platform_closes_each_leg_on_its_own():
    # a 6-UPS with its platform placed from outside: six loops base-leg-platform, each of one leg's
    # six variables (U 2, P 1, S 3), closing at the configuration the whole model reaches
    model = gs_model()
    pinned = model.pinned_model("platform")
    assert sorted((rows.size, columns.size) for rows, columns in pinned.blocks) == [(6, 6)] * 6
    for _, columns in pinned.blocks:
        legs = {model.columns[c].joint[1:] for c in columns}
        assert len(legs) == 1 and {model.columns[c].joint[0] for c in columns} == {"U", "P", "S"}
    for wrong in ("base", "nowhere"):
        with pytest.raises(ScrewkitValueError, match="other than the base for link"):
            model.pinned_model(wrong)
    task = PoseTask(model, task_coordinates(model))
    pose = np.array([[0.04, -0.02, 1.05, 0.1, -0.1, 0.2]])
    closed = close_loops(model, task, task.scaled_targets(pose))
    state = model.state(closed.theta, closed.offsets)
    platform = state.links["platform"]
    assert np.allclose(task.displacement(task.values(state)), platform, atol=1e-12)
    assert np.abs(pinned.loop_residual(pinned.state(closed.theta, closed.offsets, platform))).max() < 1e-12


def test_the_first_steps_predictor_is_the_tangent_of_the_path():
    # a 6-UPS moved along a straight line of its task space: the predictor from the reference
    # configuration is the Euler step of the solution path, its error against the configurations the
    # corrector closes to 1e-12 falls as the step's square (ratio 4 for half the step), where a wrong
    # residual or sign would leave an error of the step's own order (ratio 2)
    model = gs_model()
    task = PoseTask(model, task_coordinates(model))
    system = loop_closure._PinnedLoops(model, task)
    start = task.values(model.state(np.zeros((1, model.size))))  # the reference's scaled values
    direction = np.array([[0.5, -0.3, 0.4, 0.6, -0.5, 0.7]])
    errors = []
    for length in (0.04, 0.02, 0.01):
        targets = start + length * direction
        closed = close_loops(model, task, targets)
        assert closed.reached.all()
        predicted = system.tangent(start, targets)
        errors.append(np.abs(predicted - closed.theta).max())
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all((ratios > 3.5) & (ratios < 4.5)), ratios
    assert errors[-1] < 1e-3


def test_the_joint_motions_are_the_product_of_their_screws_exponentials():
    # a chain R - Π - P - S with a spherical offset: each link's displacement by hand, from
    # exp_screw and Rodrigues' formula one joint at a time (the model evaluates all joints at once)
    chain = twist_graph("B", "E", [
        ("B", "L1", revolute("R", [0, 0, 1], [0.5, 0, 0])),
        ("L1", "L2", parallelogram("Pa", [1, 0, 0], [0, 0, -1])),
        ("L2", "L3", prismatic("P", [0, 1, 0])),
        ("L3", "E", spherical("S", [0.2, 0.1, -0.3])),
    ], dof=6)
    model = KinematicModel(chain)
    theta = np.random.default_rng(4).uniform(-1, 1, (3, model.size))
    offset = np.tile(np.eye(4), (3, 1, 1))
    offset[:, :3, :3] = rotation_matrix(np.array([0.6, 0.0, 0.8]), np.array([0.3, -0.7, 1.1]))
    offset[:, :3, 3] = [0.1, -0.2, 0.05]
    state = model.state(theta, {"S": offset})
    expected = np.tile(np.eye(4), (3, 1, 1))
    for key, link in [("R", "L1"), ("Pa", "L2"), ("P", "L3"), ("S", "E")]:
        motion = offset.copy() if key == "S" else np.tile(np.eye(4), (3, 1, 1))
        for index in model.joints[key][2]:
            column = model.columns[index]
            if column.hinge is None:
                step = exp_screw(column.row, theta[:, index])
            else:  # the coupler's circular translation
                step = np.tile(np.eye(4), (3, 1, 1))
                step[:, :3, 3] = rotation_matrix(column.hinge, theta[:, index]) @ column.rod - column.rod
            motion = motion @ step
        expected = expected @ motion
        assert np.abs(state.links[link] - expected).max() < 1e-12


def test_the_twist_basis_of_a_pose_fixing_task_is_the_loops_minimum_norm_solution():
    from screwkit.robots.graph_kinematics import graph_kinematics

    kinematics = graph_kinematics(gough_stewart(*gough_stewart_points()))
    assert kinematics.task.fixes_pose
    closed = kinematics.solve(np.array([[0.03, -0.05, 1.02, 0.1, 0.05, -0.1]]))
    model, task = kinematics.model, kinematics.task
    state = model.state(closed.theta, closed.offsets)
    # independently: joint rates closing the loops with unit coordinate rates, by least squares
    jacobian = np.concatenate([model.loop_jacobian(state), task.jacobian(state)], axis=1)[0]
    loops = model.loop_jacobian(state).shape[1]
    rates = np.zeros((jacobian.shape[0], 6))
    rates[loops + np.arange(6), np.arange(6)] = np.where(task.translation, 1.0 / model.length, 1.0)
    joint_rates = np.linalg.lstsq(jacobian, rates, rcond=None)[0]
    twists = (model.link_jacobian(state, "platform")[0] @ joint_rates).T
    twists = np.concatenate(
        [twists[:, :3], twists[:, 3:] * model.length + np.cross(model.point, twists[:, :3])], axis=1
    )
    assert np.abs(kinematics.twist_basis(state)[0] - twists).max() < 1e-9


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_a_balls_axes_come_out_orthonormal_through_its_centre_spanning_the_same_system(seed):
    rng = np.random.default_rng(seed)
    centre = rng.normal(size=3) * 10
    directions = rng.normal(size=(3, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    rows = np.hstack([directions, np.cross(centre, directions)])  # lines through the centre
    out = orthonormal_axes(rows)
    np.testing.assert_allclose(out[:, :3] @ out[:, :3].T, np.eye(3), atol=1e-9)
    np.testing.assert_allclose(out[:, 3:], np.cross(centre, out[:, :3]), atol=1e-9 * 10)
    assert np.linalg.matrix_rank(np.vstack([rows, out]), tol=1e-8) == 3


def test_newton_closure_and_moved_configurations_on_edge_sizes():
    model = KinematicModel(planar_3rpr(
        np.array([[0, 0, 0], [1, 0, 0], [0.5, 0.8, 0.0]]), np.array([[0.4, 0.3, 0], [0.6, 0.3, 0], [0.5, 0.5, 0.0]])
    ))
    theta, residual = newton_closure(model, np.zeros((0, model.size)))
    assert theta.shape == (0, model.size) and residual.shape == (0,)
    with pytest.raises(ScrewkitValueError, match=r"`theta` of shape \(B, 9\)"):
        newton_closure(model, np.zeros(model.size))
    assert moved_configurations(model, np.random.default_rng(0), 0).shape == (0, model.size)
    with pytest.raises(ScrewkitValueError, match="`count` to be a non-negative integer, got -1"):
        moved_configurations(model, np.random.default_rng(0), -1)
