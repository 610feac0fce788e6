"""Redundant actuation (screwkit.core.redundancy): verdicts and the degree of redundancy against rank
computations made here by hand from the geometry (the actuation wrenches of UPS legs are forces along
the legs; a planar five-bar locked at its actuators moves iff its loop equations allow it)."""

import numpy as np
import pytest
from hypothesis import given, settings

import screwkit as sk
from screwkit.core.singularity import classify
from screwkit.exceptions import TwistGraphError
from screwkit.graphs.joints import prismatic, revolute, spherical, universal
from screwkit.graphs.twistgraph import twist_graph
from tests.strategies import rigid_motions, unit_factors


def ups_legs(bases, tops):
    """A platform on UPS legs (actuated prismatic joints) between base points and platform points."""
    joints = []
    for i, (a, b) in enumerate(zip(bases, tops, strict=True)):
        d = (b - a) / np.linalg.norm(b - a)
        first = np.cross(d, [0.3, 0.5, 0.8])
        joints += [
            ("base", f"u{i}", universal(f"U{i}", first, np.cross(d, first), a)),
            (f"u{i}", f"s{i}", prismatic(f"P{i}", d, actuated=True)),
            (f"s{i}", "platform", spherical(f"S{i}", b)),
        ]
    return twist_graph("base", "platform", joints)


def leg_lines(bases, tops):
    """The legs' Plücker lines (s; a × s): the actuation wrenches of UPS legs, by hand."""
    s = tops - bases
    s = s / np.linalg.norm(s, axis=1, keepdims=True)
    return np.concatenate([s, np.cross(bases, s)], axis=1)


def circle(radius, angles, height):
    return np.stack([radius * np.cos(angles), radius * np.sin(angles), np.full(len(angles), height)], axis=1)


@pytest.fixture
def rng():
    return np.random.default_rng(7)


def test_seven_ups_at_a_generic_pose_is_regular_with_one_degree_of_redundancy(rng):
    bases = circle(1.0, np.sort(rng.uniform(0, 2 * np.pi, 7)), 0.0)
    tops = circle(0.6, np.sort(rng.uniform(0, 2 * np.pi, 7)), 1.0) + rng.normal(0, 0.05, (7, 3))
    report = classify(ups_legs(bases, tops))
    assert np.linalg.matrix_rank(leg_lines(bases, tops)) == 6  # the hand computation
    assert report.labels == () and report.dof == 6 and report.redundancy == 1
    assert "redundantly actuated: 7 actuated joints for 6 freedom(s); degree of redundancy 1" in str(report)


def test_six_legs_on_a_singular_complex_are_held_by_the_seventh_and_seven_are_not(rng):
    # legs in planes through the z axis meet it: their lines lie in a special linear complex (rank 5);
    # irregular radii and angles (base and platform points on circles at equal angles would make the
    # design architecturally singular, refused below)
    angles = np.sort(rng.uniform(0, 2 * np.pi, 7))
    radii = rng.uniform(0.8, 1.2, (2, 7))
    bases = radii[0, :, None] * circle(1.0, angles, 0.0)
    tops = radii[1, :, None] * circle(0.5, angles, 1.0)
    singular = classify(ups_legs(bases, tops))
    assert np.linalg.matrix_rank(leg_lines(bases, tops)) == 5
    assert singular.labels == ("actuation",) and singular.redundancy == 2  # 7 legs drive 5 freedoms
    # the seventh leg moved off the complex: the six others alone would be singular, all seven are not
    tops[6] = tops[6] + 0.3 * np.array([-np.sin(angles[6]), np.cos(angles[6]), 0.0])
    held = classify(ups_legs(bases, tops))
    lines = leg_lines(bases, tops)
    assert np.linalg.matrix_rank(lines[:6]) == 5 and np.linalg.matrix_rank(lines) == 6
    assert held.labels == () and held.redundancy == 1
    six = classify(ups_legs(bases[:6], tops[:6]))  # the non-redundant 6-UPS of the same six legs
    assert six.labels == ("actuation",) and six.redundancy == 1


def test_an_architecturally_singular_design_is_refused():
    angles = np.linspace(0, 2 * np.pi, 7, endpoint=False)  # points on two circles at equal angles
    with pytest.raises(TwistGraphError, match=r"got 7 actuated joint\(s\): P0, .*, P6 driving 5 .*design"):
        classify(ups_legs(circle(1.0, angles, 0.0), circle(0.5, angles, 1.0)))


def elbow(a, c, sign, proximal=1.0, distal=1.2):
    """The elbow of an RR leg from base point ``a`` to ``c`` (planar, z = 0)."""
    d = c - a
    length = np.linalg.norm(d)
    along = (proximal**2 - distal**2 + length**2) / (2 * length)
    return a + along * d / length + sign * np.sqrt(proximal**2 - along**2) * np.array([-d[1], d[0], 0]) / length


def five_bar(c, legs, actuated=(True, True, True)):
    """Planar RRR legs ``(a, b)`` (base point, elbow) meeting at ``c``; the platform is leg 1's distal link."""
    joints, z = [], [0, 0, 1]
    for i, (a, b) in enumerate(legs, start=1):
        joints += [("ground", f"p{i}", revolute(f"A{i}", z, a, actuated=actuated[i - 1])),
                   (f"p{i}", f"d{i}", revolute(f"B{i}", z, b))]
        if i > 1:
            joints.append((f"d{i}", "d1", revolute(f"C{i}", z, c)))
    return twist_graph("ground", "d1", joints)


def locked_platform_freedoms(legs, c):
    """By hand: the freedoms of distal link 1 with the actuators locked, from the legs' planar loop
    equations (leg 1 turns about B1; leg i about B_i then c), twists (ω, v_x, v_y) of revolutes."""
    def twist(p):
        return np.array([1.0, p[1], -p[0]])

    blocks = []
    for i in range(1, len(legs)):
        row = np.zeros((3, 2 * len(legs) - 1))
        row[:, 0] = twist(legs[0][1])
        row[:, 2 * i - 1], row[:, 2 * i] = -twist(legs[i][1]), -twist(c)
        blocks.append(row)
    _, sigma, vt = np.linalg.svd(np.concatenate(blocks))
    null = vt[int(np.sum(sigma > 1e-9 * sigma[0])):]
    return int(np.any(np.abs(null[:, 0]) > 1e-9))  # the platform's rate b1 in the locked motions


def test_a_five_bar_with_a_third_actuated_leg_is_regular_where_its_five_bar_is_not():
    # the five-bar's actuation singularity for the platform distal 1: B1, B2 and c aligned (the distal
    # links stretched in line, c their midpoint at |B1 B2| = 2.4); a third leg from (0.5, -0.5) holds it
    a1, a2, a3 = np.zeros(3), np.array([1.0, 0, 0]), np.array([0.5, -0.5, 0])
    b1 = np.array([np.cos(2.0), np.sin(2.0), 0.0])
    t2 = next(t for t in np.linspace(0.0, 1.6, 160001) if np.linalg.norm(a2 + np.array([np.cos(t), np.sin(t), 0]) - b1) < 2.4)
    b2 = a2 + np.array([np.cos(t2), np.sin(t2), 0.0])
    c = (b1 + b2) / 2
    legs = [(a1, b1), (a2, b2)]
    three = [*legs, (a3, elbow(a3, c, 1))]
    assert locked_platform_freedoms(legs, c) == 1 and locked_platform_freedoms(three, c) == 0
    non_redundant = classify(five_bar(c, legs))
    assert non_redundant.labels == ("actuation",) and non_redundant.redundancy == 1
    redundant = classify(five_bar(c, three))
    assert redundant.labels == () and redundant.dof == 2 and redundant.redundancy == 1
    passive = classify(five_bar(c, three, actuated=(True, True, False)))  # the third leg passive
    assert passive.labels == ("actuation",) and passive.redundancy == 1


def test_redundancy_over_poses_of_a_graph_mechanism_is_batched():
    c = np.array([0.5, 1.5, 0.0])
    a1, a2, a3 = np.zeros(3), np.array([1.0, 0, 0]), np.array([0.5, -0.5, 0])
    graph = five_bar(c, [(a1, elbow(a1, c, 1)), (a2, elbow(a2, c, -1)), (a3, elbow(a3, c, 1))])
    m = sk.mechanism(graph)
    posed = m.at(m.reference_pose + np.array([[0.0, 0.0], [0.02, -0.05], [-0.03, 0.04]]))
    assert posed.redundancy.tolist() == [1, 1, 1] and posed[1].redundancy == 1
    assert posed.verdicts.tolist() == ["regular"] * 3
    jacobians = posed.jacobians
    assert jacobians.A.shape == (3, 3, 2) and jacobians.B.shape == (3, 3, 3)
    # the direct closeness of a non-square A: its smallest (dof-th) singular value over the largest
    values = np.linalg.svd(jacobians.A[0] / np.linalg.norm(jacobians.A[0], axis=1, keepdims=True), compute_uv=False)
    assert jacobians.closeness["direct"][0] > 0 and values[-1] > 0


def test_actuator_flags_that_leave_the_platform_uncontrolled_are_refused():
    z = [0, 0, 1]
    coaxial = twist_graph("B", "E", [("B", "L", revolute("A1", z, [0, 0, 0], actuated=True)),
                                     ("L", "E", revolute("A2", z, [0, 0, 0], actuated=True))])
    with pytest.raises(TwistGraphError, match=r"^Expected the `actuated` joints to drive the mechanism's 1 "
                       r"freedom\(s\) at generic configurations, got 2 actuated joint\(s\): A1, A2 driving 0"):
        classify(coaxial)
    # an under-actuated mechanism keeps working: uncontrolled everywhere, an actuation singularity
    under = twist_graph("B", "E", [("B", "L", revolute("A1", z, [0, 0, 0], actuated=True)),
                                   ("L", "E", revolute("R", z, [1, 0, 0]))])
    report = classify(under)
    assert report.dof == 2 and report.labels == ("actuation",) and report.redundancy == 0


def test_the_direct_closeness_of_a_non_square_A_is_zero_only_where_all_actuators_fail():
    # at the five-bar's actuation singularity (distal links in line) its 2x2 A is singular; the 3x2 A of
    # the robot with the third leg is not: its smallest singular value, normalised, stays away from 0
    a1, a2, a3 = np.zeros(3), np.array([1.0, 0, 0]), np.array([0.5, -0.5, 0])
    b1 = np.array([np.cos(2.0), np.sin(2.0), 0.0])
    t2 = next(t for t in np.linspace(0.0, 1.6, 160001)
              if np.linalg.norm(a2 + np.array([np.cos(t), np.sin(t), 0]) - b1) < 2.4)
    b2 = a2 + np.array([np.cos(t2), np.sin(t2), 0.0])
    c = (b1 + b2) / 2
    two = sk.mechanism(five_bar(c, [(a1, b1), (a2, b2)])).at()[0].jacobians
    three = sk.mechanism(five_bar(c, [(a1, b1), (a2, b2), (a3, elbow(a3, c, 1))])).at()[0]
    assert two.type == "direct" and two.closeness["direct"] < 1e-6
    assert three.jacobians.type == "regular" and three.jacobians.closeness["direct"] > 0.05
    hat = three.jacobians.A  # rows: unit forces; independent check of the rank of the 3x2 matrix
    assert np.linalg.matrix_rank(hat, tol=1e-9 * np.abs(hat).max()) == 2
    with pytest.raises(sk.ScrewkitValueError, match=r"redundantly actuated: no platform twist comes from one"):
        _ = three.wrench_transmission
    with pytest.raises(sk.ScrewkitValueError, match=r"3 actuated joints, 2 twists in the basis; redundantly"):
        three.jacobians.kinematic_jacobian()


@settings(max_examples=8, deadline=None)
@given(motion=rigid_motions(), unit=unit_factors)
def test_verdicts_and_redundancy_follow_rigid_motions_and_units(motion, unit):
    rotation, translation = motion
    rng = np.random.default_rng(11)
    angles = np.sort(rng.uniform(0, 2 * np.pi, 7))
    radii = rng.uniform(0.8, 1.2, (2, 7))
    bases = radii[0, :, None] * circle(1.0, angles, 0.0)
    tops = radii[1, :, None] * circle(0.5, angles, 1.0)  # six legs meet the z axis: singular ...
    moved = tops.copy()
    moved[6] = moved[6] + 0.3 * np.array([-np.sin(angles[6]), np.cos(angles[6]), 0.0])  # ... held by one
    for top, labels, redundancy in ((tops, ("actuation",), 2), (moved, (), 1)):
        report = classify(ups_legs(unit * (bases @ rotation.T + translation), unit * (top @ rotation.T + translation)))
        assert report.labels == labels and report.redundancy == redundancy


def test_a_graph_mechanism_with_actuators_that_drive_nothing_is_refused():
    z = [0, 0, 1]
    coaxial = twist_graph("B", "E", [("B", "L", revolute("A1", z, [0, 0, 0], actuated=True)),
                                     ("L", "E", revolute("A2", z, [0, 0, 0], actuated=True))])
    with pytest.raises(TwistGraphError, match=r"^Expected the `actuated` joints to drive the mechanism's 1 "):
        sk.mechanism(coaxial)


def planar_rpr(platform_points, base_points):
    """A planar n-RPR (docs/redundancy.md): R at the base point, actuated P, R at the platform point."""
    joints = []
    for i, (a, c) in enumerate(zip(base_points, platform_points, strict=True), start=1):
        joints += [("base", f"cylinder{i}", revolute(f"A{i}", [0, 0, 1], a)),
                   (f"cylinder{i}", f"piston{i}", prismatic(f"P{i}", np.subtract(c, a), actuated=True)),
                   (f"piston{i}", "platform", revolute(f"C{i}", [0, 0, 1], c))]
    return twist_graph("base", "platform", joints)


@pytest.mark.parametrize("point", [(0.575, 0.425, 0.0), (0.2, 0.9, 0.0)])
def test_the_direct_closeness_of_the_4rpr_equals_the_hand_computed_one(point):
    # by hand (screwkit.core.jacobians' Â, its normalisation written out): leg i's actuation wrench is
    # the unit force along it, u_i through A_i; the coordinates' twists are the translations along x
    # and y (Â entries: cosines u_i·x, u_i·y) and the rotation about z through the platform point P
    # (Â entry: the mutual moment over the characteristic length, z·((A_i − P) × u_i) / L)
    from screwkit.graphs.twistgraph import graph_frame

    base = np.array([[0, 0, 0], [1, 0, 0], [0.5, 1, 0], [1, 1, 0]], dtype=float)
    platform = np.array([[0.4, 0.3, 0], [0.7, 0.35, 0], [0.55, 0.55, 0], [0.65, 0.5, 0]])
    graph = planar_rpr(platform, base)
    jacobians = sk.mechanism(graph, platform_point=point).at()[0].jacobians
    _, length = graph_frame(graph)
    u = (platform - base) / np.linalg.norm(platform - base, axis=1, keepdims=True)
    moments = np.cross(base - np.asarray(point), u)[:, 2] / length
    hat = np.column_stack([u[:, 0], u[:, 1], moments])
    sigma = np.linalg.svd(hat, compute_uv=False)
    assert jacobians.closeness["direct"] == pytest.approx(sigma[-1] / sigma[0], rel=1e-9)
    assert 0.01 < sigma[-1] / sigma[0] < 1  # a value that says something: neither 0 nor 1
