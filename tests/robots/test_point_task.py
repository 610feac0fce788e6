"""Point tasks (screwkit.robots.point_task): the planar five-bar whose end point is the task, against the
classic hand derivation of its Jacobians (Gosselin & Angeles 1990; Liu, Wang & Pritschow 2006):
``A ẋ = B θ̇`` with row i of A the unit direction u_i of distal link i (elbow B_i to end point C) and
B_ii = ((B_i − A_i) × u_i)·z; serial where A_i, B_i, C are in line, actuation where u_1 ∥ u_2."""

import numpy as np
import pytest
from hypothesis import given, settings

import screwkit as sk
from screwkit.core.singularity import label_table
from screwkit.graphs.joints import revolute
from screwkit.graphs.jointtable import JointTable
from screwkit.graphs.twistgraph import twist_graph
from screwkit.robots.point_task import TASK_JOINT, with_task_point
from tests.mechanisms import planar_3rpr, tsai_3upu
from tests.strategies import rigid_motions, unit_factors

A1, A2 = np.zeros(3), np.array([1.0, 0.0, 0.0])
PROXIMAL, DISTAL = 1.0, 1.2


def elbow(a, c, sign):
    d = c - a
    length = np.linalg.norm(d)
    along = (PROXIMAL**2 - DISTAL**2 + length**2) / (2 * length)
    height = np.sqrt(max(PROXIMAL**2 - along**2, 0.0))
    return a + along * d / length + sign * height * np.array([-d[1], d[0], 0.0]) / length


def five_bar(b1, b2, c):
    z = [0, 0, 1]
    return twist_graph("ground", "distal1", [
        ("ground", "proximal1", revolute("A1", z, A1, actuated=True)),
        ("proximal1", "distal1", revolute("B1", z, b1)),
        ("ground", "proximal2", revolute("A2", z, A2, actuated=True)),
        ("proximal2", "distal2", revolute("B2", z, b2)),
        ("distal2", "distal1", revolute("C", z, c)),
    ])


def point_verdict(b1, b2, c):
    """The verdict of the five-bar at one configuration with its end point as the task."""
    table = with_task_point(JointTable.from_graph(five_bar(b1, b2, c)), "distal1", c, 2)
    return label_table(table[None])[0]


def hand_jacobians(b1, b2, c):
    u = np.array([(c - b1) / np.linalg.norm(c - b1), (c - b2) / np.linalg.norm(c - b2)])
    b = np.array([np.cross(b1 - A1, u[0])[2], np.cross(b2 - A2, u[1])[2]])
    return u[:, :2], np.diag(b)


def test_either_leg_stretched_is_the_same_serial_singularity():
    # leg 1 stretched: C at PROXIMAL + DISTAL from A1; leg 2 likewise from A2 (mirror images)
    for stretched, other, sign in ((A1, A2, -1), (A2, A1, 1)):
        direction = np.array([0.5 - stretched[0], 1.6, 0.0])
        c = stretched + (PROXIMAL + DISTAL) * direction / np.linalg.norm(direction)
        b_stretched = stretched + PROXIMAL * direction / np.linalg.norm(direction)
        b_other = elbow(other, c, sign)
        b1, b2 = (b_stretched, b_other) if stretched is A1 else (b_other, b_stretched)
        _, hand_b = hand_jacobians(b1, b2, c)
        assert abs(hand_b[0 if stretched is A1 else 1, 0 if stretched is A1 else 1]) < 1e-12
        report = point_verdict(b1, b2, c)
        assert report.labels == ("serial",)
        assert [s.actuated_joint for s in report.serial] == (["A1"] if stretched is A1 else ["A2"])


def test_the_distal_links_in_line_are_an_actuation_singularity():
    b1 = np.array([np.cos(2.0), np.sin(2.0), 0.0])
    t2 = next(t for t in np.linspace(0.0, 1.6, 160001)
              if np.linalg.norm(A2 + np.array([np.cos(t), np.sin(t), 0.0]) - b1) < 2 * DISTAL)
    b2 = A2 + np.array([np.cos(t2), np.sin(t2), 0.0])
    c = (b1 + b2) / 2
    hand_a, _ = hand_jacobians(b1, b2, c)
    assert abs(np.linalg.det(hand_a)) < 1e-4
    report = point_verdict(b1, b2, c)
    assert report.labels == ("actuation",) and report.closeness["actuation"] < 1e-4


def test_jacobians_over_poses_are_the_hand_derived_ones():
    c0 = np.array([0.5, 1.6, 0.0])
    b1, b2 = elbow(A1, c0, 1), elbow(A2, c0, -1)
    m = sk.mechanism(five_bar(b1, b2, c0), task=("distal1", c0))
    assert m.coordinates == ("x", "y")
    rng = np.random.default_rng(3)
    poses = c0[:2] + rng.uniform(-0.15, 0.15, (40, 2))
    posed = m.at(poses)
    assert posed.verdicts.tolist() == ["regular"] * 40
    jac = posed.jacobians
    for k, (x, y) in enumerate(poses):
        c = np.array([x, y, 0.0])
        hand_a, hand_b = hand_jacobians(elbow(A1, c, 1), elbow(A2, c, -1), c)
        # A⁻¹B does not depend on the rows' scaling: the point's velocity per actuator rate
        np.testing.assert_allclose(jac.kinematic_jacobian()[k], np.linalg.solve(hand_a, hand_b), atol=1e-9)
    # symmetric: the mirror pose about x = 0.5 gives the mirrored serial closeness
    mirrored = m.at([[0.4, 1.7], [0.6, 1.7]]).closeness["serial"]
    assert mirrored[0] == pytest.approx(mirrored[1], rel=1e-9)


def test_approaching_either_stretched_leg_the_serial_closeness_goes_to_zero_alike():
    c0 = np.array([0.5, 1.6, 0.0])
    m = sk.mechanism(five_bar(elbow(A1, c0, 1), elbow(A2, c0, -1), c0), task=("distal1", c0))
    for base in (A1, A2):
        direction = (c0 - base) / np.linalg.norm(c0 - base)
        reach = base + (PROXIMAL + DISTAL) * direction
        poses = [c0 + t * (reach - c0) for t in (0.5, 0.9, 0.99)]
        serial = m.at(np.array(poses)[:, :2]).closeness["serial"]
        assert serial[0] > serial[1] > serial[2] and serial[2] < 0.2


def test_the_task_link_name_must_be_free():
    table = JointTable.from_rows("B", "task point", [("B", "task point", "R", "R", [[[0, 0, 1.0, 0, 0, 0]]], True)])
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected no link 'task point' nor joint 'task point S'"):
        with_task_point(table, "task point", np.zeros(3), 1)
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected the task's link to be a link of the mechanism, got 'L'"):
        with_task_point(table, "L", np.zeros(3), 1)
    assert TASK_JOINT == "task point S"


def test_the_report_of_a_point_task_measures_the_point():
    c0 = np.array([0.5, 1.6, 0.0])
    m = sk.mechanism(five_bar(elbow(A1, c0, 1), elbow(A2, c0, -1), c0), task=("distal1", c0))
    one = m.at([[0.55, 1.65]])[0]
    assert JointTable.from_graph(one.graph).free == 3  # the task's free rotations survive the graph
    report = sk.analyze(one, superbracket=False)
    assert report.verdict.labels == () and report.verdict.nominal_global_order == 3
    assert "global order 3/3" in str(report.verdict) and "2 and 3 free rotations" in str(report.verdict)
    c = np.array([0.55, 1.65, 0.0])
    hand_a, hand_b = hand_jacobians(elbow(A1, c, 1), elbow(A2, c, -1), c)
    np.testing.assert_allclose(report.jacobians.kinematic_jacobian(), np.linalg.solve(hand_a, hand_b), atol=1e-9)


@settings(max_examples=6, deadline=None)
@given(motion=rigid_motions(), unit=unit_factors)
def test_point_task_verdicts_follow_rigid_motions_and_units(motion, unit):
    rotation, translation = motion

    def moved(p):
        return unit * (rotation @ p + translation)

    def verdict(b1, b2, c):
        axis = rotation @ np.array([0.0, 0.0, 1.0])
        graph = twist_graph("ground", "distal1", [
            ("ground", "proximal1", revolute("A1", axis, moved(A1), actuated=True)),
            ("proximal1", "distal1", revolute("B1", axis, moved(b1))),
            ("ground", "proximal2", revolute("A2", axis, moved(A2), actuated=True)),
            ("proximal2", "distal2", revolute("B2", axis, moved(b2))),
            ("distal2", "distal1", revolute("C", axis, moved(c))),
        ])
        table = with_task_point(JointTable.from_graph(graph), "distal1", moved(c), 2)
        return label_table(table[None])[0].labels

    direction = np.array([0.5, 1.6, 0.0]) / np.linalg.norm([0.5, 1.6, 0.0])
    c = (PROXIMAL + DISTAL) * direction  # leg 1 stretched
    assert verdict(PROXIMAL * direction, elbow(A2, c, -1), c) == ("serial",)
    c = np.array([0.5, 1.6, 0.0])
    assert verdict(elbow(A1, c, 1), elbow(A2, c, -1), c) == ()


def five_bar_with_tool(actuated):
    """The five-bar with a tool link hinged to distal link 1 about z through the end point C: turning
    the tool moves no point of the task (C), so an actuator there drives none of its two freedoms."""
    z, c = [0, 0, 1], [0.5, 1.8, 0.0]
    return twist_graph("ground", "tool", [
        ("ground", "proximal1", revolute("A1", z, A1, actuated="A1" in actuated)),
        ("proximal1", "distal1", revolute("B1", z, [0.0, 1.0, 0.0])),
        ("ground", "proximal2", revolute("A2", z, A2, actuated="A2" in actuated)),
        ("proximal2", "distal2", revolute("B2", z, [1.0, 1.0, 0.0])),
        ("distal2", "distal1", revolute("C", z, c, actuated="C" in actuated)),
        ("distal1", "tool", revolute("T", z, c, actuated="T" in actuated)),
    ])


def test_point_task_refuses_an_actuator_that_drives_none_of_its_freedoms():
    point = ("tool", [0.5, 1.8, 0.0])
    assert sk.mechanism(five_bar_with_tool({"A1", "A2"}), task=point).actuated == ("A1", "A2")
    for actuated in ({"A1", "A2", "T"}, {"A1", "T"}):
        with pytest.raises(sk.TwistGraphError) as error:
            sk.mechanism(five_bar_with_tool(actuated), task=point)
        message = str(error.value)
        assert "\n" not in message and "`actuated`" in message
        assert message.startswith("Expected every `actuated` joint to drive the task point, got T driving none "
                                  "of its 2 freedom(s)")


def test_point_task_refuses_actuators_that_leave_the_point_uncontrolled():
    # a copy of leg 1 (A1', B1' where A1, B1 are) actuated with A1: each alone holds B1 (one freedom of
    # the point), both together still one, so the point keeps a freedom with them held
    z, c = [0, 0, 1], [0.5, 1.8, 0.0]
    graph = twist_graph("ground", "distal1", [
        ("ground", "proximal1", revolute("A1", z, A1, actuated=True)),
        ("proximal1", "distal1", revolute("B1", z, [0.0, 1.0, 0.0])),
        ("ground", "copy1", revolute("A1'", z, A1, actuated=True)),
        ("copy1", "distal1", revolute("B1'", z, [0.0, 1.0, 0.0])),
        ("ground", "proximal2", revolute("A2", z, A2)),
        ("proximal2", "distal2", revolute("B2", z, [1.0, 1.0, 0.0])),
        ("distal2", "distal1", revolute("C", z, c)),
    ])
    with pytest.raises(sk.TwistGraphError, match=r"`actuated` joints to drive the mechanism's 2 freedom\(s\)"):
        sk.mechanism(graph, task=("distal1", c))


def test_a_point_task_of_a_platform_with_more_freedoms_keeps_every_actuator():
    # a 3-RPR's platform point has 2 of the platform's 3 freedoms: any one leg held leaves it moving
    # in the plane, yet each leg drives it (the other two held, the point moves with that leg alone),
    # so the three legs are a redundant actuation of the point, not an idle one
    base = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.8, 0.0]])
    platform = np.array([[0.4, 0.3, 0.0], [0.6, 0.3, 0.0], [0.5, 0.5, 0.0]])
    robot = sk.mechanism(planar_3rpr(base, platform), task=("platform", [0.5, 0.4, 0.0]))
    assert robot.actuated == ("P1", "P2", "P3") and robot.coordinates == ("x", "y")


def test_a_point_task_s_operation_mode_is_the_point_s_translations():
    # the five-bar's end point C moves with velocity A⁻¹B θ̇ (the hand Jacobians): both invertible at
    # this pose, so the point has the two translations of its plane and nothing else (a point has no
    # rotation); the task link's 2T3R (the point's two translations and the three free rotations
    # about it) is no motion type of the point
    c0 = np.array([0.5, 1.6, 0.0])
    hand_a, hand_b = hand_jacobians(elbow(A1, c0, 1), elbow(A2, c0, -1), c0)
    assert np.linalg.matrix_rank(np.linalg.solve(hand_a, hand_b)) == 2
    m = sk.mechanism(five_bar(elbow(A1, c0, 1), elbow(A2, c0, -1), c0), task=("distal1", c0))
    assert m.operation_modes.names() == ["2T (this one)"]
    assert sk.modes_at(m.twist_graph()).describe() == "one operation mode through this pose: 2T"
    # a 3-RPR's platform point: the platform's three planar freedoms move the point in its plane
    base = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.8, 0.0]])
    platform = np.array([[0.4, 0.3, 0.0], [0.6, 0.3, 0.0], [0.5, 0.5, 0.0]])
    robot = sk.mechanism(planar_3rpr(base, platform), task=("platform", [0.5, 0.4, 0.0]))
    assert robot.operation_modes.names() == ["2T (this one)"]
    # Tsai's 3-UPU (three kinds of mode, tests/core/test_mode_search.py) with its platform's centre as
    # the task: the point translates freely in the 3T mode, follows the free orientation with three
    # velocities in the 3R mode (p a function of R), and stays in the base plane in the planar mode
    upu = sk.mechanism(tsai_3upu([0.1, 0.05, 0.8]), task=("platform", [0.1, 0.05, 0.8]))
    assert upu.operation_modes.names() == ["3T (this one)", "2T"]
