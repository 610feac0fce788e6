"""Gosselin–Angeles types in the report and the CLI, over the families' nominal twist bases.

Known values: each family's basis written out by hand (three translations and the rotation about the
end effector's own axis through its point; the planar translations and rotation about z), and
``A = B ∂θ/∂χ`` against central differences of the closed-form inverse kinematics (so the columns
are the rates of the pose coordinates, in order, and the rows the actuators' rates). Labels: the
report's type against :func:`screwkit.core.singularity.classify`'s labels at every catalog entry's
default pose, and at a serial (reach boundary, ``h_i = 0``) and a parallel (paper 002 Eq. 7) pose of
the H4. CLI JSON equals the library's report. One test per error message.
"""

from __future__ import annotations

import contextlib
import io
import json

import numpy as np
import pytest

from screwkit.exceptions import UnreachablePoseError
from screwkit.interface.cli import main
from screwkit.interface.report import analyze
from screwkit.robots.catalog import list_mechanisms, load_mechanism
from screwkit.robots.families.four_limb.kinematics import inverse_kinematics, reachable
from screwkit.robots.mechanism import Mechanism
from screwkit.robots.posed import PosedMechanism

from ..robots.test_h4 import singular_pose

K = np.array([0.0, 0.0, 1.0])
#: Where each family keeps its actuated joint values, in the row order of A (the sorted joint names).
ACTUATED = {
    "four_limb": lambda config: config.theta,
    "mcgill_smg": lambda config: config.actuated,  # (θ_I1, θ_I2, θ_II1, θ_II2): I.pan, I.proximal.a, ...
    "peppermill": lambda config: config.actuated[..., [0, 2, 1, 3]],  # (d1, θ1, d2, θ2): 1.slide, 1.turn, ...
    "planar_3rrp": lambda config: config.joint_angles,
}


@pytest.fixture(scope="module")
def reports():
    """The report of every catalog entry at its default pose (no superbracket: not needed here)."""
    return {name: analyze(name, superbracket=False) for name in list_mechanisms()}


def json_of(argv):
    output = io.StringIO()
    with contextlib.redirect_stdout(output):
        status = main(argv)
    return status, json.loads(output.getvalue())


def hand_basis(mechanism: Mechanism, config) -> np.ndarray:
    """The nominal twists written out: translations, then (a; p × a) about the end effector's axis."""
    if mechanism.family == "planar_3rrp":
        point, axis = np.append(config.platform_point, 0.0), K
        translations = np.eye(6)[3:5]
    else:
        point = config.pose[:3]
        axis = config.platform_joint_axis if mechanism.family == "four_limb" else K
        translations = np.eye(6)[3:]
    return np.vstack([translations, np.concatenate([axis, np.cross(point, axis)])])


def dtheta_dchi(mechanism: Mechanism, pose: np.ndarray, length: float) -> np.ndarray:
    """Central differences of the inverse kinematics: (actuators in A's row order, pose coordinates)."""
    columns = []
    for k, name in enumerate(mechanism.pose_names):
        step = np.zeros(len(pose))
        step[k] = 1e-6 if name == "phi" else 1e-6 * length
        plus, minus = (ACTUATED[mechanism.family](mechanism.configuration(pose + s)) for s in (step, -step))
        columns.append(((plus - minus + np.pi) % (2 * np.pi) - np.pi) / (2 * step[k]))
    return np.stack(columns, axis=-1)


# --------------------------------------------------------------------------------------------------
# The families' twist bases
# --------------------------------------------------------------------------------------------------


def first_reachable(mechanism, poses):
    """The first of ``poses`` the mechanism reaches (a workspace box can hold unreachable poses: the
    Ragnar's box of Eq. 19), and its configuration."""
    for pose in poses:
        try:
            return pose, mechanism.configuration(pose)
        except UnreachablePoseError:
            continue
    raise AssertionError(f"none of {len(poses)} poses is reachable by {mechanism.name}")


#: Catalog entries whose family's basis and actuated joints are written out by hand above (a family
#: added later is checked by its own tests, not by this table).
HAND_DERIVED = [name for name in list_mechanisms() if load_mechanism(name).family in ACTUATED]


@pytest.mark.parametrize("name", HAND_DERIVED)
def test_twist_basis_is_the_nominal_motion_of_the_pose_coordinates(name, reports):
    mechanism = load_mechanism(name)
    pose, config = first_reachable(mechanism, mechanism.random_poses(np.random.default_rng(11), 20))
    np.testing.assert_allclose(mechanism.twist_basis(pose), hand_basis(mechanism, config), atol=1e-12)
    # A χ̇ = B θ̇ for every motion, i.e. A = B ∂θ/∂χ: the columns are the pose rates in order and the
    # rows the actuators' rates (for the V4 this needs the rotation about j, not k)
    jac = mechanism.jacobians(pose)
    length = jac.analysis.length_scale
    expected = jac.B @ dtheta_dchi(mechanism, pose, length)
    np.testing.assert_allclose(jac.A, expected, rtol=0, atol=1e-6 * np.abs(jac.A).max())
    # the report at the default pose holds the same Jacobians as the mechanism's own
    report, own = reports[name], mechanism.jacobians()
    np.testing.assert_array_equal(report.jacobians.A, own.A)
    np.testing.assert_array_equal(report.jacobians.B, own.B)
    assert report.jacobians.actuated_joints == own.actuated_joints


def test_twist_basis_picks_one_pose_of_a_batch():
    for name in ("h4", "mcgill_smg", "peppermill", "planar_3rrp"):
        mechanism = load_mechanism(name)
        poses = mechanism.random_poses(np.random.default_rng(5), 2)
        family = mechanism.family_protocol
        np.testing.assert_allclose(family.twist_basis(mechanism.configuration(poses))[1],
                                   mechanism.twist_basis(poses[1]), atol=1e-12)


# --------------------------------------------------------------------------------------------------
# Types in the report
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", list_mechanisms())
def test_report_type_at_the_default_pose_goes_with_the_labels(name, reports):
    report = reports[name]
    labels, jac = report.verdict.labels, report.jacobians
    if labels == ():
        assert jac.type == "regular"
    # serial <-> inverse, actuation <-> direct; a constraint singularity alone leaves A regular (the
    # platform gains a twist outside the Schoenflies basis; tests/robots/test_four_limb_catalog.py, the
    # Ragnar read with horizontal axes)
    assert ("serial" in labels) == (jac.type in ("inverse", "combined"))
    assert ("actuation" in labels) == (jac.type in ("direct", "combined"))
    summary = report.to_dict()["jacobians"]
    assert summary["type"] == jac.type and summary["closeness"] == jac.closeness
    assert summary["det_A"] == pytest.approx(np.linalg.det(jac.A), rel=1e-12)
    assert summary["det_B"] == pytest.approx(np.prod(np.diag(jac.B)), rel=1e-12)
    assert summary["actuated_joints"] == report.graph_summary()["actuated"]
    text = str(report)
    assert "\njacobians (Gosselin-Angeles)" in text and f"type: {jac.type}" in text
    if "constraint" in labels and jac.type == "regular":
        assert "the constraint singularity (a gained twist outside them) leaves it regular" in text


H4 = load_mechanism("h4")
#: Rays from the default pose (φ = 0, so a CLI round trip in degrees is exact) to the reach boundary.
RAYS = [(1.0, 0.3, 0.2, 0.0), (-1.0, 0.4, 0.3, 0.0), (0.5, -1.0, -0.3, 0.0), (0.3, 1.0, 0.4, 0.0),
        (-0.6, -1.0, 0.1, 0.0), (1.0, -0.2, 0.5, 0.0), (-1.0, -0.3, -0.2, 0.0), (0.2, 0.9, -0.1, 0.0)]


def h4_serial_pose() -> np.ndarray:
    """A pose of the H4 where one limb has h_i = 0 to rounding (a type-1 singularity, paper 004 Fig. 4).

    As tests/core/test_jacobians.py's ``quattro_serial_pose``: bisection on reachability along a ray finds
    the edge of the workspace, where a limb is stretched (h_i = 0). There h_i vanishes like the square
    root of the distance to the edge, so a bisected pose only gives |h_i|/b ~ 1e-8; among the last
    reachable floats of a few rays, take one where Eq. (3)'s double root is exact (|h_i|/b < 1e-13).
    """
    params = H4.parameters
    for ray in RAYS:
        direction = np.array(ray)
        low, high = 0.0, 2000.0
        for _ in range(100):
            middle = (low + high) / 2
            low, high = (middle, high) if reachable(params, H4.default_pose + middle * direction) else (low, middle)
        steps = low - np.arange(256) * np.spacing(low)
        poses = H4.default_pose + steps[:, None] * direction
        poses = poses[reachable(params, poses)]
        smallest = np.abs(inverse_kinematics(params, poses).h).min(axis=-1) / params.arm_length
        if smallest.min() < 1e-13:
            return poses[int(np.argmin(smallest))]
    raise AssertionError("no ray gave an exact double root")


@pytest.fixture(scope="module")
def serial_pose():
    pose = h4_serial_pose()
    h = np.abs(inverse_kinematics(H4.parameters, pose).h) / H4.parameters.arm_length
    assert np.sort(h)[1] > 0.1  # one limb only
    return pose, f"A{int(np.argmin(h)) + 1}"


def test_report_at_a_serial_pose_of_the_h4_says_inverse(serial_pose):
    pose, limb = serial_pose
    report = analyze("h4", pose, superbracket=False)
    assert report.verdict.labels == ("serial",)
    assert [s.actuated_joint for s in report.verdict.serial] == [limb]
    jac = report.to_dict()["jacobians"]
    assert jac["type"] == "inverse" and jac["serial_limbs"] == [limb]
    assert jac["closeness"]["inverse"] <= 1e-9 < jac["closeness"]["direct"]
    row = jac["actuated_joints"].index(limb)
    assert abs(jac["B"][row][row]) <= 1e-9 * np.abs(jac["B"]).max() and abs(jac["det_A"]) > 0
    assert f"serial singularity of the limb of {limb!r} (B_jj = 0)" in str(report)


def test_report_at_a_parallel_pose_of_the_h4_says_direct():
    pose = singular_pose(1)  # a root of paper 002's Eq. (7): an actuation singularity
    report = analyze("h4", pose, superbracket=False)
    assert report.verdict.labels == ("actuation",)
    jac = report.to_dict()["jacobians"]
    assert jac["type"] == "direct" and jac["serial_limbs"] == []
    assert jac["closeness"]["direct"] <= 1e-9 < jac["closeness"]["inverse"]
    # det A vanishes relative to the product of the rows' sizes (unit forces; the φ column in mm)
    scale = np.prod(np.linalg.norm(jac["A"], axis=0))
    assert abs(jac["det_A"]) <= 1e-8 * scale


def test_snapshot_report_has_the_jacobians_of_its_configuration():
    report = analyze("examples/planar_3rpr.toml", superbracket=False)
    # hand derivation from the file: leg i runs from A_i (base) to C_i (platform); its actuation
    # wrench is the unit force along the leg through C_i (B_ii = 1 against the unit slider twist), and
    # A's row is that force on the twists x, y and phi about the centroid c of the C_i
    base = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]])
    ends = np.array([[0.4, 0.3], [0.7, 0.35], [0.55, 0.55]])
    legs = (ends - base) / np.linalg.norm(ends - base, axis=1, keepdims=True)
    centre = ends.mean(axis=0)
    arm = ends - centre
    expected = np.column_stack([legs, arm[:, 0] * legs[:, 1] - arm[:, 1] * legs[:, 0]])
    assert report.pose_names == ("x", "y", "phi")
    assert np.allclose(report.jacobians.A, expected, atol=1e-12)
    assert np.allclose(report.jacobians.B, np.eye(3), atol=1e-12)
    assert report.to_dict()["jacobians"]["type"] == "regular"
    assert "\njacobians" in str(report) and report.transmission["wrench"] is not None


def test_report_says_why_when_the_basis_is_refused(monkeypatch):
    # a basis outside the platform's twists (here: a rotation about x for the planar platform)
    # (the composer takes the basis from the posed mechanism: screwkit.robots.posed.PosedMechanism.twist_basis)
    monkeypatch.setattr(PosedMechanism, "twist_basis", property(lambda self: np.eye(6)[[0, 3, 4]]))
    report = analyze("planar_3rrp", superbracket=False)
    summary = report.to_dict()["jacobians"]
    assert report.jacobians is None and summary["type"] is None and summary["A"] is None
    assert summary["note"].startswith("not computed: Expected `twist_basis` to lie in the platform's twist system")
    assert "  not computed: Expected `twist_basis`" in str(report)


# --------------------------------------------------------------------------------------------------
# CLI
# --------------------------------------------------------------------------------------------------


def test_cli_json_at_the_serial_pose_is_the_library_report(serial_pose):
    pose, _ = serial_pose
    argv = [repr(float(v)) for v in pose[:3]] + ["0"]
    status, printed = json_of(["analyze", "h4", "--json", "--no-superbracket", "--pose", *argv])
    assert status == 0
    library = analyze("h4", pose, superbracket=False).to_dict()
    assert printed == json.loads(json.dumps(library, ensure_ascii=False))
    assert printed["jacobians"]["type"] == "inverse"


@pytest.mark.parametrize("name", ["mcgill_smg", "planar_3rrp"])
def test_cli_json_at_the_default_pose_is_the_library_report(name, reports):
    status, printed = json_of(["analyze", name, "--json", "--no-superbracket"])
    assert status == 0
    assert printed == json.loads(json.dumps(reports[name].to_dict(), ensure_ascii=False))
    assert printed["jacobians"]["type"] == "regular"


def test_cli_text_has_the_jacobians_section(capsys, reports):
    assert main(["analyze", "peppermill", "--no-superbracket"]) == 0
    text = capsys.readouterr().out
    assert text.rstrip("\n") == str(reports["peppermill"])
    assert "rows (actuated joints): 1.slide, 1.turn, 2.slide, 2.turn" in text


# --------------------------------------------------------------------------------------------------
# Errors
# --------------------------------------------------------------------------------------------------

