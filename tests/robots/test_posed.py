"""One class for a batch of poses and for one pose: ``posed[i]`` is a :class:`PosedMechanism` of
shape ``()`` reading its batch's joint table; the per-pose views need one pose."""

import numpy as np
import pytest

import screwkit as sk
from screwkit.exceptions import ScrewkitIndexError, ScrewkitValueError
from screwkit.robots.posed import PosedMechanism

POSES = [[0.0, 0.0, -750.0, 0.0], [30.0, -20.0, -750.0, 0.3]]


def test_indexing_gives_a_posed_mechanism_of_one_pose():
    posed = sk.load_mechanism("h4").at(POSES)
    one = posed[1]
    assert isinstance(one, PosedMechanism)
    assert one.shape == () and one.poses.shape == (4,)
    assert one.poses.tolist() == POSES[1]
    assert not one.poses.flags.writeable
    assert (one.rtol, one.length_scale) == (posed.rtol, posed.length_scale)
    assert not hasattr(sk, "Pose")


@pytest.mark.parametrize("view, call", [
    ("graph", lambda p: p.graph),
    ("analysis", lambda p: p.analysis),
    ("singularity", lambda p: p.singularity),
    (r"diagram_and_sampler\(\)", lambda p: p.diagram_and_sampler()),
    ("diagram", lambda p: p.diagram),
    ("superbracket", lambda p: p.superbracket),
])
def test_error_a_per_pose_view_of_a_batch_says_to_index_it(view, call):
    posed = sk.load_mechanism("h4").at(POSES)
    with pytest.raises(ScrewkitValueError, match=rf"^PosedMechanism\.{view} needs one pose: index the batch "
                       r"\(posed\[i\]\) first, got shape \(2,\)\.$"):
        call(posed)


def test_error_one_pose_has_no_length_no_iteration_no_index():
    one = sk.load_mechanism("h4").at(POSES)[0]
    with pytest.raises(TypeError, match="a posed mechanism of one pose has no length"):
        len(one)
    with pytest.raises(TypeError, match="a posed mechanism of one pose is not iterable"):
        iter(one)
    with pytest.raises(ScrewkitIndexError, match=r"Expected a batch to index, got one pose \(shape \(\)\)"):
        one[0]


class CountingFamily:
    """Wraps a family protocol, counting its joint tables (one per inverse kinematics)."""

    def __init__(self, protocol):
        self.protocol, self.calls = protocol, 0

    def joint_table(self, configuration):
        self.calls += 1
        return self.protocol.joint_table(configuration)

    def __getattr__(self, name):
        return getattr(self.protocol, name)


def test_indexing_a_batch_reuses_its_joint_table(monkeypatch):
    h4 = sk.load_mechanism("h4")
    counting = CountingFamily(h4.family_protocol)
    monkeypatch.setattr(type(h4), "family_protocol", property(lambda self: counting))
    configurations = []
    original = type(h4).configuration
    monkeypatch.setattr(type(h4), "configuration",
                        lambda self, *args, **kw: configurations.append(1) or original(self, *args, **kw))
    posed = h4.at(POSES)
    _ = posed.joints
    assert (counting.calls, len(configurations)) == (1, 1)
    one = posed[1]
    assert one.__dict__["joints"].batch_shape == ()
    _ = one.singularity, one.jacobians, one.graph
    assert (counting.calls, len(configurations)) == (1, 1)  # no new inverse kinematics, no new table
    np.testing.assert_array_equal(one.twist_basis, posed.twist_basis[1])


def test_one_pose_answers_as_the_batch_and_as_a_pose_alone():
    h4 = sk.load_mechanism("h4")
    posed = h4.at(POSES)
    alone = h4.at([POSES[1]])[0]
    one = posed[1]
    for p in (one, alone):
        assert p.verdicts.tolist() == posed.verdicts[1]
        assert p.codes.tolist() == posed.codes[1]
        for key, values in posed.closeness.items():
            assert float(p.closeness[key]) == values[1], key
        assert str(p.singularities) == str(posed.singularities[1]) == str(p.singularity)
        np.testing.assert_array_equal(p.jacobians.A, posed.jacobians.A[1])
        np.testing.assert_array_equal(p.jacobians.B, posed.jacobians.B[1])
        assert p.jacobians.shape == ()
        np.testing.assert_array_equal(p.wrench_transmission.lti, posed.wrench_transmission.lti[1])
        np.testing.assert_array_equal(p.wrench_transmission.input, posed.wrench_transmission.input[1])
    points = one.diagram.points
    values, exists = posed.diagram_points(points)
    one_values, one_exists = one.diagram_points(points)
    assert one_exists.shape == () and bool(one_exists) == exists[1]
    for label, value in values.items():
        np.testing.assert_array_equal(one_values[label], value[1], err_msg=label)


# a pose out of reach in a batch: the reached poses get their verdicts, it gets the marker ------------
def _five_bar_point_task():
    from .test_graph_mechanism import five_bar

    return sk.mechanism(five_bar(), task=("distal1", [0.5, 1.8, 0]))


# the V4 (catalog, closed-form IK) and a five-bar's end point (a graph, loop closure), each with one pose
# beyond reach: z = -3000 mm is farther than the V4's arms and rods reach (paper 004's Eq. 3 has no
# real root); (5, 5) is 5.6 from the five-bar's base joints, whose two links reach 1 + 1.8 at most
MIXED = [
    ("v4", [[0.0, 0.0, -750.0, 0.0], [0.0, 0.0, -3000.0, 0.0], [0.0, 0.0, -800.0, 0.2]]),
    ("five_bar", [[0.5, 1.8], [5.0, 5.0], [0.55, 1.75]]),
]


@pytest.mark.parametrize(("name", "poses"), MIXED, ids=[name for name, _ in MIXED])
def test_a_batch_with_a_pose_out_of_reach_marks_it_and_answers_for_the_others(name, poses):
    robot = _five_bar_point_task() if name == "five_bar" else sk.load_mechanism(name)
    posed = robot.at(poses)
    assert posed.reachable.tolist() == [True, False, True] and list(posed.failures) == [(1,)]
    # each reached pose answers as it does alone (an independent batch of the reached poses)
    alone = robot.at([poses[0], poses[2]])
    assert posed.verdicts.tolist() == [alone.verdicts[0], "unreachable", alone.verdicts[1]]
    assert posed.codes.tolist() == [alone.codes[0], -1, alone.codes[1]]
    assert posed.redundancy.tolist() == [0, -1, 0]
    for kind, values in posed.closeness.items():
        assert np.isnan(values[1])
        np.testing.assert_array_equal(values[[0, 2]], alone.closeness[kind])
    # indexing: a reached pose is analysed, the one out of reach says why when asked
    assert posed[2].singularity.verdict == alone[1].singularity.verdict
    np.testing.assert_array_equal(posed[2].jacobians.A, alone[1].jacobians.A)
    assert posed[1].verdicts.tolist() == "unreachable" and not posed[1].reachable
    with pytest.raises(sk.UnreachablePoseError, match=r"^Pose .* is out of reach.*[^.]\.$"):
        _ = posed[1].singularity
    # the whole batch's Jacobians answer per pose (tests/robots/test_posed_partial.py); the core's
    # report of the whole batch needs every pose: refused naming the pose
    assert posed.jacobians.types.tolist() == [alone.jacobians.types[0], "unreachable", alone.jacobians.types[1]]
    with pytest.raises(sk.UnreachablePoseError, match=r"\(1,\)"):
        _ = posed.singularities


def test_a_batch_out_of_reach_everywhere_is_all_markers():
    posed = sk.load_mechanism("v4").at([[0.0, 0.0, -3000.0, 0.0], [0.0, 0.0, -4000.0, 0.0]])
    assert posed.verdicts.tolist() == ["unreachable", "unreachable"] and posed.codes.tolist() == [-1, -1]
    assert all(np.isnan(values).all() for values in posed.closeness.values())


def test_a_fresh_graph_mechanism_whose_first_batch_reaches_nothing_answers_with_markers():
    # (a reviewer's finding: the remembered-poses cache, still empty, was sized from the batch's
    # solutions and raised numpy's broadcast error when there were none)
    h4 = sk.load_mechanism("h4")
    graph = sk.mechanism(h4.twist_graph([0.0, 0.0, -750.0, 0.0]))
    assert graph.reachable([[0.0, 0.0, 0.0, 0.0]]).tolist() == [False]
    posed = sk.mechanism(h4.twist_graph([0.0, 0.0, -750.0, 0.0])).at([[0.0, 0.0, 1e9, 0.0], [0.0, 0.0, 0.0, 0.0]])
    assert posed.verdicts.tolist() == ["unreachable", "unreachable"] and posed.codes.tolist() == [-1, -1]
    assert not posed.reachable.any() and len(posed.failures) == 2
