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
