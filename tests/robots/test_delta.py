"""The Delta robot (screwkit.robots.families.delta, mechanisms/delta.toml), checked against the robot's
own geometry (tests/delta_geometry.py: Clavel's patent and Williams' kinematics notes, written
independently of the family's code), and CONTRIBUTING's statement of the worked example's sizes."""

import ast
import re
from pathlib import Path

import numpy as np

from screwkit.robots.catalog import load_mechanism

from ..delta_geometry import RADIAL, coplanar_root_on_x, dimensions, elbows, forward, rod_determinant

REPO = Path(__file__).resolve().parents[2]
DELTA = load_mechanism(REPO / "mechanisms" / "delta.toml")
R, r, b, ROD = dimensions(DELTA)


def test_inverse_kinematics_closes_every_leg(rng):
    poses = DELTA.random_poses(rng, 200)
    theta = DELTA.configuration(poses).theta
    gap = np.linalg.norm(poses[:, None, :] + r * RADIAL - elbows(DELTA, theta), axis=-1) - ROD
    assert np.max(np.abs(gap)) < 1e-9 * ROD


def test_forward_kinematics_of_the_ik_returns_the_pose(rng):
    poses = DELTA.random_poses(rng, 50)
    theta = DELTA.configuration(poses).theta
    for pose, angles in zip(poses, theta, strict=True):
        np.testing.assert_allclose(forward(DELTA, angles), pose, atol=1e-8 * ROD)


def test_the_default_pose_by_hand():
    # on the axis every leg is the same planar problem: d = (r - R, z) in the leg's plane,
    # |d - b (cos θ, -sin θ)| = l; elbows out: the root with the arm pointing away from the axis
    z = DELTA.default_pose[2]
    d = np.array([r - R, z])
    angles = np.linspace(-np.pi / 2, np.pi / 2, 200_001)
    gap = np.abs(np.hypot(d[0] - b * np.cos(angles), d[1] + b * np.sin(angles)) - ROD)
    np.testing.assert_allclose(DELTA.configuration().theta, angles[np.argmin(gap)], atol=2e-5)


def test_actuation_singular_exactly_where_the_rods_are_coplanar():
    root = coplanar_root_on_x(DELTA, DELTA.default_pose[2])
    assert root is not None and 300.0 < root[0] < 1200.0  # outside the box (|x| <= 300), within reach
    near = root + np.array([[0.0, 0.0, 0.0], [-5.0, 0.0, 0.0], [5.0, 0.0, 0.0]])
    verdicts = DELTA.at(near, rtol=1e-6).verdicts.tolist()
    assert verdicts == ["actuation singularity", "regular", "regular"]


def test_regular_over_the_workspace(rng):
    poses = DELTA.random_poses(rng, 500)
    assert abs(rod_determinant(DELTA, poses)).min() > 0.05  # the rods stay far from coplanar in the box
    assert set(DELTA.at(poses).verdicts.tolist()) == {"regular"}


def _counts(path):
    """(lines, code lines) of a module: code lines are neither blank, comments nor docstrings."""
    text = path.read_text(encoding="utf-8")
    docstrings = set()
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Module | ast.ClassDef | ast.FunctionDef) and ast.get_docstring(node) is not None:
            docstrings.update(range(node.body[0].lineno, node.body[0].end_lineno + 1))
    lines = text.splitlines()
    code = [n for n, line in enumerate(lines, 1) if line.strip() and not line.strip().startswith("#")
            and n not in docstrings]
    return len(lines), len(code)


def test_contributing_states_the_worked_examples_sizes():
    text = (REPO / "CONTRIBUTING.md").read_text(encoding="utf-8")
    stated = re.search(r"families/delta\.py` \((\d+) lines, (\d+) of them code.*?delta\.toml` \((\d+) lines", text, re.S)
    assert stated, "CONTRIBUTING's worked example states the Delta's sizes"
    module = _counts(REPO / "screwkit" / "robots" / "families" / "delta.py")
    toml_lines = len((REPO / "mechanisms" / "delta.toml").read_text(encoding="utf-8").splitlines())
    assert tuple(map(int, stated.groups())) == (*module, toml_lines)
