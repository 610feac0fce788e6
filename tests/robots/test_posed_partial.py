"""The whole-batch views of a posed batch some of whose poses are out of reach answer per pose: each
reached pose exactly what a batch of the reached poses alone gives, NaN and the marker "unreachable" at
the others (the Jacobians, the wrench-based transmission, what the maps read of them)."""

import numpy as np
import pytest

import screwkit as sk
from screwkit.analysis import quantities as Q
from screwkit.exceptions import UnreachablePoseError

# poses (x, y, z, phi) of the H4 and V4 (mm, rad): the second and fourth out of reach (z far below the
# arms' reach: paper 004's Eq. 3 has no real root there)
FOUR_LIMB_POSES = [[0, 0, -750, 0], [0, 0, -3000, 0], [30, -20, -750, 0.3], [0, 0, -4000, 0.1], [0, 40, -800, 0]]
REACHED = [0, 2, 4]


def _h4_graph():
    """The H4 as a twist graph at its default pose: loop-closure kinematics (screwkit.mechanism)."""
    return sk.mechanism(sk.load_mechanism("h4").twist_graph(), platform_point=[0, 0, -750])


def _robots():
    return {"h4": lambda: sk.load_mechanism("h4"), "v4": lambda: sk.load_mechanism("v4"), "h4 graph": _h4_graph}


@pytest.mark.parametrize("name", ["h4", "v4", "h4 graph"])
def test_the_jacobians_of_a_partial_batch_are_those_of_its_reached_poses_and_nan(name):
    make = _robots()[name]
    posed = make().at(FOUR_LIMB_POSES)
    assert posed.reachable.tolist() == [True, False, True, False, True]
    alone = make().at([FOUR_LIMB_POSES[i] for i in REACHED]).jacobians  # a fresh mechanism: solved anew
    jac = posed.jacobians
    assert jac.shape == (5,) and jac.types.tolist() == [
        alone.types[0], "unreachable", alone.types[1], "unreachable", alone.types[2]
    ]
    assert jac.reached.tolist() == posed.reachable.tolist()
    for field in ("A", "B", "wrenches", "twist_basis"):
        mine, theirs = getattr(jac, field), getattr(alone, field)
        np.testing.assert_allclose(mine[REACHED], theirs, rtol=1e-12, atol=1e-12 * np.abs(theirs).max())
        assert np.isnan(mine[[1, 3]]).all()
    for kind in ("direct", "inverse"):
        np.testing.assert_allclose(jac.closeness[kind][REACHED], alone.closeness[kind], rtol=1e-12)
        assert np.isnan(jac.closeness[kind][[1, 3]]).all()
    np.testing.assert_allclose(jac.det_A[REACHED], alone.det_A, rtol=1e-12)
    np.testing.assert_allclose(jac.det_B[REACHED], alone.det_B, rtol=1e-12)
    assert np.isnan(jac.det_A[[1, 3]]).all() and np.isnan(jac.det_B[[1, 3]]).all()
    assert jac.serial[REACHED].tolist() == alone.serial.tolist() and not jac.serial[[1, 3]].any()
    assert not jac.direct[[1, 3]].any() and not jac.inverse[[1, 3]].any()  # no singularity claimed there
    rates = jac.kinematic_jacobian()
    np.testing.assert_allclose(rates[REACHED], alone.kinematic_jacobian(), rtol=1e-10, atol=1e-12)
    assert np.isnan(rates[[1, 3]]).all()
    # one pose out of reach, read from the batch's Jacobians: says so, in words and in JSON
    out = jac[1]
    assert out.type == "unreachable" and "out of reach" in str(out) and "unreachable" in repr(out)
    data = out.to_dict()
    assert data["type"] == "unreachable" and data["A"][0][0] is None and data["closeness"]["direct"] is None
    assert "2 unreachable" in repr(jac)
    # the core's report over the whole batch (wrench systems) needs every pose, and says where to look
    with pytest.raises(UnreachablePoseError, match=r"\(1,\).*the per-pose views mark it: posed.verdicts"):
        _ = posed.singularities


@pytest.mark.parametrize("name", ["h4", "h4 graph"])
def test_the_wrench_transmission_of_a_partial_batch_is_nan_out_of_reach(name):
    make = _robots()[name]
    posed = make().at(FOUR_LIMB_POSES)
    alone = make().at([FOUR_LIMB_POSES[i] for i in REACHED]).wrench_transmission
    result = posed.wrench_transmission
    assert result.reachable.tolist() == posed.reachable.tolist()
    assert result.actuated_joints == alone.actuated_joints
    for field in ("input", "output", "lti"):
        mine = np.asarray(getattr(result, field))
        np.testing.assert_allclose(mine[REACHED], getattr(alone, field), rtol=1e-12)
        assert np.isnan(mine[[1, 3]]).all()
    # what the maps read of it: NaN where the verdict code is -1, never a number there
    for quantity in ("det_A", "det_B", "wrench_lti"):
        values = Q.values(posed, quantity)
        assert np.array_equal(np.isnan(values), Q.values(posed, "verdict") == -1), quantity


def test_a_batch_with_no_pose_in_reach_has_no_jacobians_and_says_why():
    posed = sk.load_mechanism("v4").at([[0, 0, -3000, 0], [0, 0, -4000, 0]])
    with pytest.raises(UnreachablePoseError, match=r"^Expected some pose of the batch in reach for `jacobians`"):
        _ = posed.jacobians
    with pytest.raises(UnreachablePoseError, match="wrench_transmission"):
        _ = posed.wrench_transmission


def test_a_map_of_a_graph_mechanism_over_its_reach_marks_the_poses_out_of_reach():
    # the H4 graph's x-z slice runs out of the arms' reach at low z: NaN exactly where not reachable
    result = sk.grid_map(_h4_graph(), "det_A", x=("x", -200, 200, 5), y=("z", -1400, -700, 5),
                         fixed={"y": 0, "phi": 0})
    assert 0 < result.reachable.sum() < result.reachable.size
    assert np.array_equal(np.isnan(result.values), ~result.reachable)
