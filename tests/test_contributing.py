"""The worked example of CONTRIBUTING.md ("Adding a robot"), run in CI and checked by hand.

A planar 3-RPR written as the four functions of the family protocol, registered, named by a catalog
mapping and analysed with ``Mechanism.at(poses)``. The base pivots lie on the unit circle, the
platform pivots on a circle of radius 0.3 at the same angles. Hand derivation: at ``φ = 0`` the
platform is a scaled copy of the base, ``B_k = C + r u_k`` and ``A_k = R u_k``, so every leg line
``A_k B_k`` passes through the centre of similarity ``D = R C / (R - r)``: the legs are concurrent
and the platform can turn about ``D`` with the actuators locked (an actuation singularity) at every
position. The test measures concurrency independently, by the determinant of the three leg lines
``l_k = (A_k, 1) × (B_k, 1)`` in homogeneous planar coordinates.
"""

import copy
import dataclasses
import inspect
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from screwkit import Family, JointTable, analyze, register
from screwkit.algebra import screw as S
from screwkit.exceptions import CatalogError, ScrewkitTypeError, ScrewkitValueError
from screwkit.robots.catalog import mechanism_from_mapping
from screwkit.robots.families import families

# ---- the example of CONTRIBUTING.md, as written there (registration in the fixture below) ----------
Z = np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True)
class RPRParameters:
    base: np.ndarray  # (3, 2): the fixed pivots A_k
    platform: np.ndarray  # (3, 2): the moving pivots B_k in the platform frame


@dataclass(frozen=True)
class RPRConfiguration:
    pose: np.ndarray  # (..., 3): x, y, phi
    base: np.ndarray  # (..., 3, 3): A_k in space (plane z = 0)
    platform: np.ndarray  # (..., 3, 3): B_k in space


def parameters(mapping, *, source="<mapping>"):
    return RPRParameters(np.array(mapping["base"], float), np.array(mapping["platform"], float))


def inverse_kinematics(params, poses):  # closed form: the leg lengths are |B_k - A_k|
    poses = np.asarray(poses, float)
    x, y, phi = (poses[..., i, None] for i in range(3))
    bx, by = params.platform.T
    moving = np.stack([x + np.cos(phi) * bx - np.sin(phi) * by,
                       y + np.sin(phi) * bx + np.cos(phi) * by, 0 * x + 0 * bx], axis=-1)
    fixed = np.broadcast_to(np.pad(params.base, ((0, 0), (0, 1))), moving.shape)
    return RPRConfiguration(poses, fixed, moving)


def joints(config):  # per leg: R at A_k, actuated P along the leg, R at B_k; screws (..., 1, 6)
    legs = config.platform - config.base
    rows = []
    for k in range(3):
        low, high, a, b = f"leg{k + 1}_low", f"leg{k + 1}_high", config.base[..., k, :], config.platform[..., k, :]
        rows += [("base", low, f"R{k + 1}", "R", S.revolute_twist(Z, a)[..., None, :], False),
                 (low, high, f"P{k + 1}", "P", S.prismatic_twist(legs[..., k, :])[..., None, :], True),
                 (high, "platform", f"Q{k + 1}", "R", S.revolute_twist(Z, b)[..., None, :], False)]
    anchor = np.concatenate([config.base, config.platform], axis=-2).mean(axis=-2)  # a point of the plane
    return JointTable.from_rows("base", "platform", rows, dof=3, anchor=anchor)


def twist_basis(config):  # unit rates of x, y and phi (a rotation about z through (x, y))
    centre = np.pad(config.pose[..., :2], [(0, 0)] * (config.pose.ndim - 1) + [(0, 1)])
    along = np.broadcast_to(np.eye(6)[3:5], (*centre.shape[:-1], 2, 6))
    return np.concatenate([along, S.revolute_twist(Z, centre)[..., None, :]], axis=-2)


FAMILY = Family("planar_3rpr", parameters, inverse_kinematics, joints, twist_basis,
                pose_names=("x", "y", "phi"), angle_names=("phi",))
CORNERS = [[np.cos(t), np.sin(t)] for t in np.radians([90, 210, 330])]
MAPPING = {
    "mechanism": {"kind": "family", "name": "3-RPR", "family": "planar_3rpr", "length_unit": "m"},
    "parameters": {
        "base": {"value": CORNERS, "unit": "m", "source": "our choice: unit circle"},
        "platform": {"value": (0.3 * np.array(CORNERS)).tolist(), "unit": "m", "source": "our choice"},
    },
    "pose": {"x": 0.0, "y": 0.0, "phi_deg": 20.0},
    "workspace": {"x": [-0.2, 0.2], "y": [-0.2, 0.2], "phi_deg": [-60.0, 60.0]},
}
# ----------------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def mechanism():
    register(FAMILY)
    yield mechanism_from_mapping(MAPPING)
    families().pop(FAMILY.name)  # leave the registry as the other tests expect it


def leg_lines_determinant(mechanism, poses):
    """det[l_1; l_2; l_3] with l_k = (A_k, 1) × (B_k, 1), from the parameters (not the family)."""
    poses = np.asarray(poses, float)
    base = np.asarray(MAPPING["parameters"]["base"]["value"])
    platform = np.asarray(MAPPING["parameters"]["platform"]["value"])
    cos, sin = np.cos(poses[..., 2, None]), np.sin(poses[..., 2, None])
    px, py = platform.T
    moving = np.stack([poses[..., 0, None] + cos * px - sin * py, poses[..., 1, None] + sin * px + cos * py], -1)
    ones = np.ones((*moving.shape[:-1], 1))
    fixed = np.broadcast_to(base, moving.shape)
    lines = np.cross(np.concatenate([fixed, ones], -1), np.concatenate([moving, ones], -1))
    return np.linalg.det(lines)


def test_the_example_as_written(mechanism):
    posed = mechanism.at([[0.0, 0.0, 0.35], [0.0, 0.0, 0.0]])  # at phi = 0 the legs meet at the origin
    assert posed.verdicts.tolist() == ["regular", "actuation singularity"]
    assert "actuation singularity" in str(analyze(posed[1]))
    hand = leg_lines_determinant(mechanism, posed.poses)
    assert abs(hand[0]) > 0.05 and abs(hand[1]) < 1e-12


def test_singular_exactly_where_the_legs_are_concurrent(mechanism, rng):
    poses = mechanism.random_poses(rng, 200)
    poses[::4, 2] = 0.0  # a quarter of them with the platform parallel to the base
    posed = mechanism.at(poses)
    hand = leg_lines_determinant(mechanism, poses)
    concurrent = np.abs(hand) < 1e-12
    assert concurrent.sum() == 50 and np.all(concurrent == (poses[:, 2] == 0.0))
    assert np.all(posed.verdicts[concurrent] == "actuation singularity")
    assert np.all(posed.verdicts[~concurrent] == "regular")


def test_locked_platform_turns_about_the_centre_of_similarity(mechanism):
    pose = np.array([0.12, -0.07, 0.0])
    twists = mechanism.at(pose[None])[0].singularity.uncontrolled_twists
    assert len(twists) == 1
    point, direction = S.axis(twists[0])
    centre = pose[:2] * 1.0 / (1.0 - 0.3)  # D = R C / (R - r), R = 1, r = 0.3
    np.testing.assert_allclose(np.abs(direction), [0.0, 0.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(point[:2], centre, atol=1e-9)


def test_jacobians_over_the_nominal_twists(mechanism):
    jac = mechanism.at([[0.05, 0.02, 0.3], [0.05, 0.02, 0.0]]).jacobians
    assert jac.type.tolist() == ["regular", "direct"]
    assert jac.actuated_joints == ("P1", "P2", "P3")


REGISTER_ERRORS = [
    ({"name": "x"}, ScrewkitTypeError, r"Expected `family` to be a screwkit.robots.families.Family, got dict"),
    (Family("four_limb", *[print] * 4, ("x",), ()), ScrewkitValueError,
     r"Expected a new family name, got 'four_limb', which is already registered \(four_limb, "),
    (Family("two words", *[print] * 4, ("x",), ()), ScrewkitTypeError,
     r"Expected `family.name` to be an identifier, got 'two words'"),
    (Family("odd", print, print, 3, print, ("x",), ()), ScrewkitTypeError,
     r"Expected `family.joints` to be callable, got int"),
    (Family("odd", *[print] * 4, ["x"], ()), ScrewkitTypeError,
     r"Expected `family.pose_names` to be a tuple of str, got \['x'\]"),
    (Family("odd", *[print] * 4, ("x",), ("phi",)), ScrewkitValueError,
     r"Expected `family.angle_names` to be some of the pose coordinates \('x',\), got \('phi',\)"),
    (Family("odd", *[print] * 4, ("x",), (), reachable=True), ScrewkitTypeError,
     r"Expected `family.reachable` to be callable or None, got bool"),
]


@pytest.mark.parametrize(("family", "error", "match"), REGISTER_ERRORS)
def test_register_errors(family, error, match):
    with pytest.raises(error, match=match):
        register(family)
    assert "odd" not in families()


def contributing_code():
    text = (Path(__file__).resolve().parents[1] / "CONTRIBUTING.md").read_text(encoding="utf-8")
    section = text[text.index("## Adding a robot") :]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_contributing_shows_this_code():
    code = contributing_code()
    for function in (parameters, inverse_kinematics, joints, twist_basis, RPRParameters, RPRConfiguration):
        assert inspect.getsource(function) in code, function.__name__


def test_contributing_code_runs_as_written():
    done = subprocess.run([sys.executable, "-c", contributing_code()], capture_output=True, text=True, check=True)
    assert "verdict\n  actuation singularity (dof 3)" in done.stdout


def test_error_a_field_the_family_reads_but_the_file_lacks(mechanism):
    # the example's parameters() reads mapping["platform"] without checking it: the catalog says which
    # field is missing instead of letting a KeyError through
    mapping = copy.deepcopy(MAPPING)
    del mapping["parameters"]["platform"]
    with pytest.raises(CatalogError, match=r"<mapping>: \[parameters\]: missing field `platform` "
                       r"\(read by the family 'planar_3rpr'\)\."):
        mechanism_from_mapping(mapping)


def test_error_a_family_whose_joints_are_not_a_joint_table(mechanism, monkeypatch):
    monkeypatch.setitem(families(), FAMILY.name, dataclasses.replace(FAMILY, joints=lambda configuration: "rows"))
    with pytest.raises(ScrewkitTypeError, match=r"Expected the family 'planar_3rpr''s joints\(configuration\) "
                       r"to return a JointTable, got str\."):
        _ = mechanism.at().verdicts
