"""Any twist graph over its motion (screwkit.mechanism, screwkit.robots.graph_kinematics): the
loop-closure inverse kinematics equals every catalog family's closed form, the Jacobians equal finite
differences of it, forward kinematics returns to the pose, and every bad input is named."""

import numpy as np
import pytest

import screwkit as sk
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError
from screwkit.graphs.joints import revolute
from screwkit.graphs.jointtable import JointTable
from screwkit.robots.catalog import list_mechanisms, load_mechanism
from screwkit.robots.graph_kinematics import kinematics_of

from ..mechanisms import gough_stewart, gough_stewart_points

POSES_PER_ROBOT = 2000


def _relative_gap(reference, ours):
    """The largest difference of two screw arrays ``(..., k, 6)`` of one joint, per pose, relative to the
    reference's size, up to the sign (a screw and its opposite are the same axis)."""
    scale = 1.0 + np.abs(reference).max(axis=(-1, -2))
    same = np.abs(reference - ours).max(axis=(-1, -2))
    opposite = np.abs(reference + ours).max(axis=(-1, -2))
    return np.minimum(same, opposite) / scale


def _spherical_centres(rows):
    """The centres ``(m, 3)`` of spherical joints from their screws ``(m, 3, 6)``: ``s0 = c × s``, i.e.
    ``−[s]× c = s0`` for each of the three rotations (least squares, batched)."""
    s, s0 = rows[..., :3], rows[..., 3:]
    hats = np.zeros((*s.shape, 3))
    hats[..., 0, 1], hats[..., 0, 2], hats[..., 1, 2] = -s[..., 2], s[..., 1], -s[..., 0]
    hats[..., 1, 0], hats[..., 2, 0], hats[..., 2, 1] = s[..., 2], -s[..., 1], s[..., 0]
    matrix = -hats.reshape(*rows.shape[:-2], 9, 3)
    moment = s0.reshape(*rows.shape[:-2], 9)
    normal = np.swapaxes(matrix, -1, -2)
    return np.linalg.solve(normal @ matrix, (normal @ moment[..., None]))[..., 0]


@pytest.mark.parametrize("name", list_mechanisms())
def test_loop_closure_equals_each_familys_closed_form(name):
    robot = load_mechanism(name)
    poses = robot.random_poses(np.random.default_rng(11), POSES_PER_ROBOT)
    kinematics = kinematics_of(robot)
    closed = kinematics.solve(poses)
    # a pose the continuation does not reach lies beyond the reach of the straight way to it from the
    # default pose (the closed form refuses a pose on that way), never inside it
    for pose in poses[~closed.reached]:
        way = robot.default_pose + np.linspace(0, 1, 400)[:, None] * (pose - robot.default_pose)
        assert not robot.reachable(way).all()
    assert closed.reached.mean() > 0.98
    poses = poses[closed.reached]
    closed = kinematics.solve(poses)
    ours = kinematics.model.joint_table(
        kinematics.model.state(closed.theta, closed.offsets), kinematics.reference
    )
    reference = robot.joints(poses)
    for spec in reference.specs:
        a, b = reference.joint_screws(spec.name), ours.joint_screws(spec.name)
        if spec.type == "S":  # any three rotations about the centre: compare the centres
            gap = np.abs(_spherical_centres(a) - _spherical_centres(b)).max() / (
                1 + np.abs(_spherical_centres(a)).max()
            )
        else:
            a = a / np.linalg.norm(
                np.where(np.linalg.norm(a[..., :3], axis=-1, keepdims=True) > 0, a[..., :3], a[..., 3:]),
                axis=-1,
                keepdims=True,
            )
            gap = _relative_gap(a, b).max()
        assert gap < 1e-9, (spec.name, gap)
    # and the platform's nominal twists: the family's and the loop closure's
    basis = kinematics.twist_basis(kinematics.model.state(closed.theta, closed.offsets))
    family_basis = robot.at(poses).twist_basis
    assert np.abs(basis - family_basis).max() < 1e-9 * (1 + np.abs(family_basis).max())


def _actuated_values(kinematics, poses):
    closed = kinematics.solve(poses)
    columns = [kinematics.model.joints[name][2][0] for name in kinematics.actuated]
    values = closed.theta[:, columns]
    sliding = np.array([np.linalg.norm(kinematics.model.columns[c].row[:3]) < 1e-12 for c in columns])
    return np.where(sliding, values * kinematics.model.length, values)


@pytest.mark.parametrize(
    "build",
    [
        lambda: sk.mechanism(load_mechanism("h4").twist_graph(), platform_point=[0, 0, -750]),
        lambda: sk.mechanism(gough_stewart(*gough_stewart_points())),
    ],
    ids=["h4 graph", "6-UPS graph"],
)
def test_jacobians_equal_finite_differences_of_the_loop_closure(build):
    robot = build()
    kinematics = robot.parameters
    pose = robot.reference_pose + 0.05 * np.where(
        np.array([k == "translation" for k in kinematics.coordinates.kinds]), kinematics.model.length, 1.0
    ) * np.linspace(-1, 1, len(robot.coordinates))
    jacobians = robot.at(pose[None]).jacobians
    assert tuple(jacobians.actuated_joints) == robot.actuated
    rates = np.linalg.solve(jacobians.B[0], jacobians.A[0])  # θ̇ = B⁻¹ A χ̇
    numeric = np.empty_like(rates)
    for k in range(len(pose)):
        step = 1e-6 * (kinematics.model.length if kinematics.coordinates.kinds[k] == "translation" else 1.0)
        plus, minus = pose.copy(), pose.copy()
        plus[k] += step
        minus[k] -= step
        numeric[:, k] = (
            _actuated_values(kinematics, plus[None]) - _actuated_values(kinematics, minus[None])
        )[0] / (2 * step)
    assert np.abs(rates - numeric).max() < 1e-6 * (1 + np.abs(rates).max())


def test_forward_kinematics_returns_to_the_pose():
    robot = sk.mechanism(load_mechanism("h4").twist_graph(), platform_point=[0, 0, -750])
    poses = np.array([[0.0, 0.0, -750.0, 0.0], [40.0, -30.0, -800.0, 0.3], [-60.0, 20.0, -700.0, -0.2]])
    values = _actuated_values(robot.parameters, poses)
    posed = robot.forward(values)
    assert posed.reachable.all() and posed.failures == {}
    assert np.abs(posed.poses - poses).max() < 1e-9 * 800
    assert posed.verdicts.tolist() == load_mechanism("h4").at(poses).verdicts.tolist()


def test_forward_out_of_reach_is_flagged_not_returned():
    posed = load_mechanism("h4").forward(np.array([[0.1, 0, 0, 0], [3.0, -3.0, 0.0, 0.0]]))
    assert posed.reachable.tolist() == [True, False]
    assert np.isnan(posed.poses[1]).all() and "do not close" in posed.failures[(1,)]
    assert posed.verdicts.tolist() == ["regular", "unreachable"] and posed.codes.tolist() == [0, -1]
    with pytest.raises(UnreachablePoseError, match=r"Pose \(1,\) is out of reach: the loops"):
        _ = posed.singularities


def test_catalog_forward_matches_its_inverse_kinematics():
    h4 = load_mechanism("h4")
    poses = h4.random_poses(np.random.default_rng(2), 20)
    posed = h4.forward(_actuated_values(kinematics_of(h4), poses))
    assert np.abs(posed.poses - poses).max() < 1e-9 * 1000


def test_a_graph_mechanism_has_reference_coordinates_and_a_workspace():
    graph = gough_stewart(*gough_stewart_points())
    robot = sk.mechanism(graph)
    assert robot.coordinates == ("x", "y", "z", "rx", "ry", "rz")
    assert np.allclose(robot.reference_pose, [0, 0, 1, 0, 0, 0])
    assert robot.actuated == tuple(f"P{i}" for i in range(1, 7))
    assert robot.family == "loop_closure" and robot.parameters.complete
    poses = robot.random_poses(np.random.default_rng(0), 50)
    assert robot.at(poses).verdicts.tolist() == sk.classify_table(robot.joints(poses)).verdict.tolist()


def test_rigid_displacements_are_poses_too():
    robot = sk.mechanism(gough_stewart(*gough_stewart_points()))
    turn = np.eye(4)
    turn[:3, :3] = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1.0]]) @ np.eye(3)
    turn[:3, :3] = np.array([[np.cos(0.1), -np.sin(0.1), 0], [np.sin(0.1), np.cos(0.1), 0], [0, 0, 1]])
    turn[:3, 3] = [0.01, 0.02, 0.03]
    posed = robot.at(turn[None])
    assert np.allclose(posed.poses, [[0.01, 0.02, 1.03, 0, 0, 0.1]])
    with pytest.raises(ScrewkitValueError, match="rigid motions"):
        robot.at(2 * turn[None])
    h4 = sk.mechanism(load_mechanism("h4").twist_graph(), platform_point=[0, 0, -750])
    tilt = np.eye(4)
    tilt[:3, :3] = [[1, 0, 0], [0, np.cos(0.1), -np.sin(0.1)], [0, np.sin(0.1), np.cos(0.1)]]
    with pytest.raises(ScrewkitValueError, match="direction the motion does not have"):
        h4.at(tilt[None])


def five_bar():
    return sk.twist_graph(
        "ground",
        "distal1",
        [
            ("ground", "proximal1", revolute("A1", [0, 0, 1], [0, 0, 0], actuated=True)),
            ("proximal1", "distal1", revolute("B1", [0, 0, 1], [0, 1, 0])),
            ("ground", "proximal2", revolute("A2", [0, 0, 1], [1, 0, 0], actuated=True)),
            ("proximal2", "distal2", revolute("B2", [0, 0, 1], [1, 1, 0])),
            ("distal2", "distal1", revolute("C", [0, 0, 1], [0.5, 1.8, 0])),
        ],
        dof=2,
    )


def test_a_point_task_takes_the_points_coordinates():
    robot = sk.mechanism(five_bar(), task=("distal1", [0.5, 1.8, 0]))
    assert robot.coordinates == ("x", "y") and np.allclose(robot.reference_pose, [0.5, 1.8])
    # hand derivation: the end point at (0.5, 1.7) is 1 from B1 and from B2, whose shoulders turn about A1, A2
    posed = robot.at([[0.5, 1.7]])
    basis = posed.twist_basis[0]
    assert basis.shape == (2, 6)
    values = _actuated_values(robot.parameters, np.array([[0.5, 1.7]]))[0]
    elbow = np.array([np.cos(np.pi / 2 + values[0]), np.sin(np.pi / 2 + values[0])])
    assert np.isclose(np.linalg.norm(np.array([0.5, 1.7]) - elbow), np.hypot(0.5, 0.8))


@pytest.mark.parametrize(
    ("arguments", "error", "message"),
    [
        ({"task": "distal1"}, ScrewkitValueError, r"`task` to be \(link, point\)"),
        ({"task": ("nowhere", [0, 0, 0])}, ScrewkitValueError, "`task` to name a link"),
        ({"task": ("distal1", [0, 0])}, ScrewkitValueError, "task point"),
        ({"task": ("distal1", [0, np.nan, 0])}, ScrewkitValueError, "task point"),
        ({"platform_point": "top"}, ScrewkitTypeError, "platform_point"),
        ({"platform_point": [0, 0]}, ScrewkitValueError, "platform_point"),
        ({"workspace": {"x": (0, 1)}}, ScrewkitValueError, "`workspace` to map each coordinate"),
    ],
)
def test_bad_arguments_are_named(arguments, error, message):
    graph = five_bar() if "task" in arguments else gough_stewart(*gough_stewart_points())
    with pytest.raises(error, match=message):
        sk.mechanism(graph, **arguments)


def test_a_singular_reference_or_a_wrong_dof_is_refused():
    stretched = sk.twist_graph(
        "B",
        "E",
        [
            ("B", "L", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
            ("L", "E", revolute("R2", [0, 0, 1], [1, 0, 0], actuated=True)),
        ],
        dof=2,
    )
    with pytest.raises(ScrewkitValueError, match="dof = 2 freedoms at the reference configuration, got 1"):
        sk.mechanism(stretched, task=("E", [2, 0, 0]))


def test_other_targets():
    assert sk.mechanism("h4") is not None and sk.mechanism("h4").family == "four_limb"
    robot = load_mechanism("h4")
    assert sk.mechanism(robot) is robot
    assert sk.mechanism("examples/planar_3rpr.toml").coordinates == ("x", "y", "phi")
    with pytest.raises(ScrewkitTypeError, match="`graph_or_file` to be a twist graph"):
        sk.mechanism(42)
    with pytest.raises(ScrewkitValueError, match="virtual joint"):
        sk.mechanism(sk.equivalent_twist_graph(robot.twist_graph()))


def test_unreachable_poses_of_a_batch_are_flagged_with_their_reason():
    robot = sk.mechanism(five_bar(), task=("distal1", [0.5, 1.8, 0]))
    poses = np.array([[0.5, 1.8], [5.0, 5.0], [0.55, 1.75]])
    posed = robot.at(poses)
    assert posed.reachable.tolist() == [True, False, True]
    assert list(posed.failures) == [(1,)] and "do not close" in posed.failures[(1,)]
    # the reached poses get their verdicts, the one out of reach the marker (the core's report over the
    # whole batch still names it)
    assert posed.verdicts.tolist() == ["regular", "unreachable", "regular"]
    with pytest.raises(UnreachablePoseError, match=r"Pose \(1,\)"):
        _ = posed.singularities
    assert robot.at(poses[posed.reachable]).verdicts.tolist() == ["regular", "regular"]


def test_everything_over_poses_works_for_a_graph():
    robot = sk.mechanism("examples/planar_3rpr.toml")
    result = sk.grid_map(robot, "verdict", x=("x", 0.45, 0.65, 6), y=("y", 0.3, 0.5, 6), fixed={"phi": 0.0})
    assert result.values.shape == (6, 6) and result.reachable.all()
    closeness = sk.grid_map(
        robot, "closeness:actuation", x=("x", 0.45, 0.65, 5), y=("y", 0.3, 0.5, 5), fixed={"phi": 0.0}
    )
    assert np.all(closeness.values >= 0)
    path = sk.check_path(robot, [0.55, 0.4, 0.0], [0.6, 0.45, 0.2], samples=8)
    assert path.to_dict() is not None
    jac = robot.at([[0.55, 0.4, 0.0]]).jacobians
    assert jac.A.shape == (1, 3, 3)
    transmission = robot.at([[0.55, 0.4, 0.0]]).wrench_transmission
    assert 0 < float(np.min(transmission.lti)) <= 1


def test_joint_table_of_the_reference_is_the_graphs():
    graph = gough_stewart(*gough_stewart_points())
    robot = sk.mechanism(graph)
    table = robot.joints(robot.reference_pose)
    reference = JointTable.from_graph(graph)
    for spec in reference.specs:
        gap = np.abs(table.joint_screws(spec.name) - reference.joint_screws(spec.name)).max()
        assert gap < 1e-12


def test_the_report_of_a_graph_mechanisms_pose():
    robot = sk.mechanism("examples/planar_3rpr.toml")
    posed = robot.at([[0.6, 0.45, 0.1]])[0]
    report = sk.analyze(posed, superbracket=False)
    # the graph at that configuration, analysed by itself, gives the same verdict and orders
    alone = sk.classify(posed.graph)
    assert report.verdict.verdict == alone.verdict
    assert report.verdict.global_order == alone.global_order
    assert report.pose_names == ("x", "y", "phi") and report.jacobians.type == "regular"
    assert np.allclose(report.pose, [0.6, 0.45, 0.1])


def test_graph_mechanisms_pass_the_family_conformance_checks():
    from screwkit.testing import check_family

    for robot in (sk.mechanism(gough_stewart(*gough_stewart_points())), sk.mechanism("examples/planar_3rpr.toml")):
        report = check_family(robot)
        assert report.passed, [str(check) for check in report.failures]


def test_graph_closeness_equals_the_closed_forms_whatever_a_balls_axes():
    # the measures read the scaled frame's length (the axes' RMS distance from the reference point):
    # a ball carried as a rotation times three axes drifts from orthogonal axes, and once read 464 of
    # 1,000 H4 poses up to 1.5e-2 off the closed form's (whose balls have orthonormal axes)
    catalog = load_mechanism("h4")
    graph = sk.mechanism(catalog.twist_graph(), platform_point=[0, 0, -750])
    poses = np.asarray(catalog.random_poses(np.random.default_rng(3), 300))
    closed, looped = catalog.at(poses).singularities.closeness, graph.at(poses).singularities.closeness
    for kind in ("constraint", "actuation", "serial"):
        np.testing.assert_allclose(looped[kind], closed[kind], rtol=0, atol=1e-9)


@pytest.mark.parametrize("name", list_mechanisms())
def test_reachable_refuses_a_single_pose_not_in_a_batch(name):
    # one pose of shape (n,) was read as n poses of one coordinate (McGill SMG, Peppermill) or raised
    # a numpy reshape error (the others)
    robot = load_mechanism(name)
    pose = np.asarray(robot.reference_pose, dtype=float)
    with pytest.raises(ScrewkitValueError, match=r"`poses` of shape \(m, \d\)"):
        robot.reachable(pose)
    assert robot.reachable(pose[None]).tolist() == [True]
