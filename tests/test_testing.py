"""screwkit.testing.check_family: every shipped family passes; each check fails on a family broken
in the way it is meant to catch."""

from __future__ import annotations

import dataclasses
import functools
import pathlib

import numpy as np
import pytest

from screwkit.core.jacobians import schoenflies_basis
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families import families
from screwkit.testing import check_family

REPO = pathlib.Path(__file__).resolve().parents[1]
#: The catalog files of this checkout (an editable install may map the catalog elsewhere).
ROBOTS = {path.stem: load_mechanism(path) for path in sorted((REPO / "mechanisms").glob("*.toml"))}


@pytest.mark.parametrize("name", sorted(families()))
def test_every_shipped_family_passes(name):
    robots = [robot for robot in ROBOTS.values() if robot.family == name]
    assert robots, f"no catalog robot of the family {name}"
    for robot in robots:
        report = check_family(robot, samples=4)
        report.raise_if_failed()
        assert {c.name for c in report.checks} == {"closure", "jacobian", "rank", "reachability", "branch"}


def test_delta_elbows_out_is_the_documented_mode():
    """The Delta's documented mode puts each elbow B_i farther from the axis k than its joint A_i."""
    delta = ROBOTS["delta"]
    config = delta.configuration(delta.random_poses(np.random.default_rng(3), 50))
    assert np.all(np.linalg.norm(config.b[..., :2], axis=-1) > np.linalg.norm(config.a[..., :2], axis=-1))


@pytest.fixture
def broken(request):
    """Register a broken copy of a family under a new name; a robot of it; forget it afterwards."""
    made = []

    def make(robot, **changes):
        mechanism = load_mechanism(robot)
        family = dataclasses.replace(mechanism.family_protocol, name=f"broken_{len(made)}", **changes)
        families()[family.name] = family
        made.append(family.name)
        return dataclasses.replace(mechanism, family=family.name)

    yield make
    for name in made:
        del families()[name]


def _status(report):
    return {check.name: check.status for check in report.checks}


def test_elbows_in_fails_the_branch_check(broken):
    h4 = load_mechanism("h4")
    ik = functools.partial(h4.family_protocol.inverse_kinematics, working_mode=(1, 1, 1, 1))
    status = _status(check_family(broken("h4", inverse_kinematics=ik), samples=2))
    assert status["branch"] == "fail"
    assert status["closure"] == status["jacobian"] == "pass"  # elbows in is a valid branch otherwise


def test_elbows_out_is_the_documented_four_limb_mode():
    """The criterion behind the branch check for parallelogram legs, checked from the geometry:
    in the documented mode the elbows B_i are farther from the base's centre than the joints A_i."""
    for robot in ("h4", "quattro", "v4", "veloce", "ragnar"):
        config = load_mechanism(robot).configuration()
        radial = config.a[:, :2] / np.linalg.norm(config.a[:, :2], axis=-1, keepdims=True)
        assert np.all(np.sum((config.b - config.a)[:, :2] * radial, axis=-1) > 0), robot


def test_a_branch_jump_fails_the_branch_check(broken):
    """A 3-RRP inverse kinematics that switches limb 1's branch where x crosses 0."""
    planar = load_mechanism("planar_3rrp")
    solve = planar.family_protocol.inverse_kinematics

    def jumping(parameters, poses, working_mode=(1, 1, 1)):
        poses = np.asarray(poses, dtype=float)
        sign = np.where(poses[..., :1] > 0.01, -1, 1)
        return solve(parameters, poses, np.concatenate([sign, np.ones_like(sign), np.ones_like(sign)], -1))

    robot = broken("planar_3rrp", inverse_kinematics=jumping)
    start = robot.default_pose
    ends = start + np.array([[0.03, 0.0, 0.0], [-0.03, 0.0, 0.0]])  # one path crosses x = 0.01
    assert robot.reachable(ends).all()
    status = _status(check_family(robot, ends))
    assert status["branch"] == "fail"


def test_a_wrong_twist_row_fails_closure(broken):
    def rotated(config):  # the fourth row turns about x instead of the platform's own axis
        return schoenflies_basis(
            config.pose[..., :3], np.broadcast_to([1.0, 0.0, 0.0], config.pose[..., :3].shape)
        )

    status = _status(check_family(broken("h4", twist_basis=rotated), samples=2))
    assert status["closure"] == "fail"


def test_a_repeated_twist_row_fails_rank(broken):
    basis = load_mechanism("h4").family_protocol.twist_basis

    def repeated(config):
        rows = np.array(basis(config))
        rows[..., 3, :] = rows[..., 0, :]
        return rows

    report = check_family(broken("h4", twist_basis=repeated), samples=2)
    assert _status(report)["rank"] == "fail"
    with pytest.raises(ScrewkitValueError, match=r"fails .* checks?: .*rank: fail"):
        report.raise_if_failed()


def test_a_jacobian_sign_flip_fails_the_jacobian_check(broken):
    """Actuated joint A1's screw reversed: B⁻¹A's first row changes sign, the IK does not."""
    joints = load_mechanism("h4").family_protocol.joints

    def flipped(config):
        table = joints(config)
        screws = np.array(table.screws)
        screws[..., 0, :] *= -1
        return dataclasses.replace(table, screws=screws)

    status = _status(check_family(broken("h4", joints=flipped), samples=2))
    assert status["jacobian"] == "fail"
    assert status["rank"] == "pass"


def test_a_wrong_reach_test_fails_reachability(broken):
    status = _status(
        check_family(broken("h4", reachable=lambda p, poses: np.ones(len(poses), bool)), samples=2)
    )
    assert status["reachability"] == "fail"


def test_missing_hooks_are_skipped_not_passed(broken):
    report = check_family(broken("planar_3rrp", actuated_values=None, working_modes=None), samples=2)
    status = _status(report)
    assert status["jacobian"] == status["branch"] == "skip"
    assert report.passed


def test_bad_subjects():
    with pytest.raises(ScrewkitTypeError, match="Expected `subject`"):
        check_family(3.0)
    with pytest.raises(ScrewkitValueError, match="registered family"):
        check_family("five_bar")
    with pytest.raises(ScrewkitValueError, match="Expected `poses` only with a Mechanism"):
        check_family("four_limb", np.zeros((1, 4)))
    unregistered = dataclasses.replace(families()["four_limb"])
    with pytest.raises(ScrewkitValueError, match="registered family"):
        check_family(unregistered)
