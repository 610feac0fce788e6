"""The worked example of CONTRIBUTING.md ("Adding a robot"), run in CI and checked by hand.

A newcomer ships a family by adding one module to ``screwkit/robots/families/`` (and a catalog file).
These tests do exactly that and nothing else: CONTRIBUTING's module, a planar 3-RPR written as the four
functions of the family protocol, is written to a temporary folder put on the families package's
search path (``screwkit.robots.families.__path__``, the package's own list of folders), and a catalog
mapping names it. The family must then be listed, load, and analyse.

The base pivots lie on the unit circle, the platform pivots on a circle of radius 0.3 at the same
angles. Hand derivation: at ``φ = 0`` the platform is a scaled copy of the base, ``B_k = C + r u_k``
and ``A_k = R u_k``, so every leg line ``A_k B_k`` passes through the centre of similarity
``D = R C / (R - r)``: the legs are concurrent and the platform can turn about ``D`` with the
actuators locked (an actuation singularity) at every position. The test measures concurrency
independently, by the determinant of the three leg lines ``l_k = (A_k, 1) × (B_k, 1)`` in homogeneous
planar coordinates.
"""

import copy
import dataclasses
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import screwkit.robots.families as families_package
from screwkit import Family, analyze, register
from screwkit.algebra import screw as S
from screwkit.exceptions import CatalogError, ScrewkitTypeError, ScrewkitValueError
from screwkit.robots.catalog import mechanism_from_mapping
from screwkit.robots.families import families

NAME = "planar_3rpr"
MODULE = f"screwkit.robots.families.{NAME}"
CORNERS = [[np.cos(t), np.sin(t)] for t in np.radians([90, 210, 330])]
MAPPING = {
    "mechanism": {"kind": "family", "name": "3-RPR", "family": NAME, "length_unit": "m"},
    "parameters": {
        "base": {"value": CORNERS, "unit": "m", "source": "our choice: unit circle"},
        "platform": {"value": (0.3 * np.array(CORNERS)).tolist(), "unit": "m", "source": "our choice"},
    },
    "pose": {"x": 0.0, "y": 0.0, "phi_deg": 20.0},
    "workspace": {"x": [-0.2, 0.2], "y": [-0.2, 0.2], "phi_deg": [-60.0, 60.0]},
}


def contributing_code():
    """The two Python blocks of CONTRIBUTING's "Adding a robot": the module, then its use."""
    text = (Path(__file__).resolve().parents[2] / "CONTRIBUTING.md").read_text(encoding="utf-8")
    section = text[text.index("## Adding a robot") :]
    module, use = re.findall(r"```python\n(.*?)```", section, re.S)[:2]
    return module, use


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """A folder holding CONTRIBUTING's module, put on the families package's search path."""
    where = tmp_path_factory.mktemp("families")
    (where / f"{NAME}.py").write_text(contributing_code()[0], encoding="utf-8")
    families_package.__path__.append(str(where))
    yield where
    families_package.__path__.remove(str(where))
    families().pop(NAME, None)
    sys.modules.pop(MODULE, None)


@pytest.fixture(scope="module")
def mechanism(folder):
    return mechanism_from_mapping(MAPPING)


def test_the_new_module_is_listed(folder):
    shipped = sorted(p.stem for p in Path(families_package.__file__).parent.iterdir()
                     if not p.name.startswith("_") and (p.suffix == ".py" or (p / "__init__.py").exists()))
    # the package's modules, then the folder's (families registered at run time come after them)
    assert list(families())[: len(shipped) + 1] == [*shipped, NAME]
    assert NAME in families() and "five_bar" not in families()


def test_listing_reads_the_declaration_without_importing(folder):
    # a fresh interpreter: the command line's options read every family's pose coordinates, and
    # must not import the family's module to do so
    code = (
        "import sys\nimport screwkit.robots.families as f\n"
        f"f.__path__.append({str(folder)!r})\n"
        "print(f.families().pose_names(), NAME in list(f.families()), MODULE in sys.modules)"
    ).replace("NAME", repr(NAME)).replace("MODULE", repr(MODULE))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.split("] ")[1].split() == ["True", "False"]


def test_the_family_loads_from_its_module(mechanism):
    family = families()[NAME]
    assert isinstance(family, Family) and family.name == NAME
    assert sys.modules[MODULE].FAMILY is family
    assert mechanism.family_protocol is family
    assert mechanism.pose_names == ("x", "y", "phi") and mechanism.angle_names == ("phi",)
    assert mechanism.default_pose[2] == pytest.approx(np.radians(20.0))


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
     r"Expected a new family name, got 'four_limb', which is already registered \("),
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
    (Family("odd", *[print] * 4, ("x",), (), application_points=[0.0, 0.0, 0.0]), ScrewkitTypeError,
     r"Expected `family.application_points` to be callable or None, got list"),
]


@pytest.mark.parametrize(("family", "error", "match"), REGISTER_ERRORS)
def test_register_errors(family, error, match):
    with pytest.raises(error, match=match):
        register(family)
    assert "odd" not in families()


def test_contributing_code_runs_as_written(folder):
    # the second block, as a newcomer runs it once the module is in place
    code = f"import screwkit.robots.families as f\nf.__path__.append({str(folder)!r})\n" + contributing_code()[1]
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "verdict\n  actuation singularity (dof 3)" in done.stdout


def test_a_family_made_at_run_time_is_registered(mechanism):
    copied = dataclasses.replace(families()[NAME], name="planar_3rpr_copy")
    assert register(copied) is copied
    try:
        mapping = copy.deepcopy(MAPPING)
        mapping["mechanism"]["family"] = "planar_3rpr_copy"
        posed = mechanism_from_mapping(mapping).at([[0.05, 0.0, 0.0]])
        assert posed.verdicts.tolist() == ["actuation singularity"]
        assert list(families())[-1] == "planar_3rpr_copy"
    finally:
        families().pop("planar_3rpr_copy")


@pytest.mark.parametrize(
    ("text", "error", "match"),
    [
        ("X = 1\n", ScrewkitTypeError,
         r"Expected the module screwkit.robots.families.broken to declare its family as `FAMILY = Family\(...\)`, "
         r"got NoneType\."),
        ("from screwkit import Family\nFAMILY = Family('other', *[print] * 4, ('x',), ())\n", ScrewkitValueError,
         r"Expected the family of the module screwkit.robots.families.broken to be named 'broken', got 'other'\."),
    ],
)
def test_a_module_that_does_not_declare_its_family(tmp_path, monkeypatch, text, error, match):
    (tmp_path / "broken.py").write_text(text, encoding="utf-8")
    monkeypatch.setattr(families_package, "__path__", [*families_package.__path__, str(tmp_path)])
    monkeypatch.delitem(sys.modules, "screwkit.robots.families.broken", raising=False)
    assert "broken" in families()
    with pytest.raises(error, match=match):
        families()["broken"]
    sys.modules.pop("screwkit.robots.families.broken", None)


def test_error_a_field_the_family_reads_but_the_file_lacks(mechanism):
    # the example's parameters() reads mapping["platform"] without checking it: the catalog says which
    # field is missing instead of letting a KeyError through
    mapping = copy.deepcopy(MAPPING)
    del mapping["parameters"]["platform"]
    with pytest.raises(CatalogError, match=r"<mapping>: \[parameters\]: missing field `platform` "
                       r"\(read by the family 'planar_3rpr'\)\."):
        mechanism_from_mapping(mapping)


def test_error_a_family_whose_joints_are_not_a_joint_table(mechanism, monkeypatch):
    family = families()[NAME]
    monkeypatch.setitem(families(), NAME, dataclasses.replace(family, joints=lambda configuration: "rows"))
    with pytest.raises(ScrewkitTypeError, match=r"Expected the family 'planar_3rpr''s joints\(configuration\) "
                       r"to return a JointTable, got str\."):
        _ = mechanism.at().verdicts
