"""The Delta robot (screwkit.robots.families.delta, mechanisms/delta.toml), checked against
computations written here from the geometry of Clavel's patent (US 4,976,582) and Williams' kinematics
notes (2015), not from the family's code.

* Each leg: the actuated revolute joint at ``A_i = R r_i`` turns the arm of length ``b`` about the
  horizontal axis ``u_i`` tangent to the base circle; the rods of length ``l`` join the elbow ``B_i`` to
  ``C_i = p + r r_i`` (``r_i`` the leg's radial direction, ``γ_i = 0°, 120°, 240°``).
* Forward kinematics (Williams, "forward position kinematics"): ``p`` is where the three spheres of
  radius ``l`` about ``B_i - r r_i`` meet; solved here by subtracting the sphere equations (two linear
  equations, a line) and one quadratic along the line, the root below the elbows.
* Singularities (Williams, velocity kinematics ``A ṗ = B θ̇`` with rows ``w_i`` of ``A``): direct (an
  actuation singularity of the twist graph) where the rod directions ``w_i`` are linearly dependent,
  i.e. the three parallelograms' rods are parallel to one plane.
"""

import ast
import re
from pathlib import Path

import numpy as np

from screwkit.robots.catalog import load_mechanism

DELTA = load_mechanism(Path(__file__).resolve().parents[2] / "mechanisms" / "delta.toml")
R, r, b, ROD = (DELTA.parameters.base_radius, DELTA.parameters.platform_radius, DELTA.parameters.arm_length,
              DELTA.parameters.rod_length)
GAMMA = np.radians([0.0, 120.0, 240.0])
RADIAL = np.stack([np.cos(GAMMA), np.sin(GAMMA), np.zeros(3)], -1)


def rotate(vector, axis, angle):
    """Rodrigues' rotation of ``vector`` about the unit ``axis`` by ``angle`` (batched)."""
    cos, sin = np.cos(angle)[..., None], np.sin(angle)[..., None]
    return vector * cos + np.cross(axis, vector) * sin + axis * np.sum(axis * vector, -1)[..., None] * (1 - cos)


def elbows(theta):
    """B_i from the arm angles: r_i turned by θ_i about u_i = k × r_i (θ > 0 lowers the arm)."""
    axes = np.cross([0.0, 0.0, 1.0], RADIAL)
    return R * RADIAL + b * rotate(np.broadcast_to(RADIAL, (*theta.shape[:-1], 3, 3)), axes, theta)


def forward(theta):
    """The platform point from the arm angles: three spheres' intersection, the lower root."""
    centres = elbows(theta) - r * RADIAL
    # |p - c_i|² = l²: subtracting sphere 1 gives 2 (c_i - c_1)·p = |c_i|² - |c_1|² (i = 2, 3)
    rows = 2 * (centres[..., 1:, :] - centres[..., :1, :])
    rhs = np.sum(centres[..., 1:, :] ** 2, -1) - np.sum(centres[..., :1, :] ** 2, -1)
    point = np.linalg.lstsq(rows, rhs, rcond=None)[0]  # one point of the line
    direction = np.cross(rows[0], rows[1])
    direction /= np.linalg.norm(direction)
    offset = point - centres[0]
    # |offset + t d|² = l²
    half_b = offset @ direction
    t = -half_b + np.array([-1.0, 1.0]) * np.sqrt(half_b**2 - (offset @ offset - ROD**2))
    candidates = point + t[:, None] * direction
    return candidates[np.argmin(candidates[:, 2])]


def test_inverse_kinematics_closes_every_leg(rng):
    poses = DELTA.random_poses(rng, 200)
    theta = DELTA.configuration(poses).theta
    gap = np.linalg.norm(poses[:, None, :] + r * RADIAL - elbows(theta), axis=-1) - ROD
    assert np.max(np.abs(gap)) < 1e-9 * ROD


def test_forward_kinematics_of_the_ik_returns_the_pose(rng):
    poses = DELTA.random_poses(rng, 50)
    theta = DELTA.configuration(poses).theta
    for pose, angles in zip(poses, theta, strict=True):
        np.testing.assert_allclose(forward(angles), pose, atol=1e-8 * ROD)


def test_the_default_pose_by_hand():
    # on the axis every leg is the same planar problem: d = (r - R, 0, z) in the leg's plane,
    # |d - b (cos θ, -sin θ)| = l; elbows out: the root with the arm pointing away from the axis
    z = DELTA.default_pose[2]
    d = np.array([r - R, z])
    angles = np.linspace(-np.pi / 2, np.pi / 2, 200_001)
    gap = np.abs(np.hypot(d[0] - b * np.cos(angles), d[1] + b * np.sin(angles)) - ROD)
    expected = angles[np.argmin(gap)]
    np.testing.assert_allclose(DELTA.configuration().theta, expected, atol=2e-5)


def rod_determinant(poses):
    """det[w_1; w_2; w_3], the rod directions from the test's own geometry."""
    theta = DELTA.configuration(poses).theta
    rods = poses[..., None, :] + r * RADIAL - elbows(theta)
    return np.linalg.det(rods / ROD)


def test_actuation_singular_exactly_where_the_rods_are_coplanar():
    # along the x axis at the height of the default pose the rod directions become dependent where
    # the platform is far out (rods 2, 3 and 1 parallel to one plane); find that root by bisection
    z = DELTA.default_pose[2]
    line = np.stack([np.linspace(0.0, 1200.0, 241), np.zeros(241), np.full(241, z)], -1)
    line = line[DELTA.reachable(line)]
    signs = np.sign(rod_determinant(line))
    crossing = np.flatnonzero(np.diff(signs))
    assert len(crossing), "the rods become coplanar on this line within reach"
    low, high = line[crossing[0]], line[crossing[0] + 1]
    for _ in range(60):
        middle = (low + high) / 2
        same = np.sign(rod_determinant(middle[None]))[0] == signs[crossing[0]]
        low, high = (middle, high) if same else (low, middle)
    root = (low + high) / 2
    assert 300.0 < root[0] < 1200.0  # outside the workspace box (|x| <= 300), inside the reach
    near = root + np.array([[0.0, 0.0, 0.0], [-5.0, 0.0, 0.0], [5.0, 0.0, 0.0]])
    verdicts = DELTA.at(near, rtol=1e-6).verdicts.tolist()
    assert verdicts[0] == "actuation singularity" and verdicts[1:] == ["regular", "regular"]


def test_regular_over_the_workspace(rng):
    poses = DELTA.random_poses(rng, 500)
    assert abs(rod_determinant(poses)).min() > 0.05  # the rods stay far from coplanar in the box
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
    repo = Path(__file__).resolve().parents[2]
    text = (repo / "CONTRIBUTING.md").read_text(encoding="utf-8")
    stated = re.search(r"families/delta\.py` \((\d+) lines, (\d+) of them code.*?delta\.toml` \((\d+) lines", text, re.S)
    assert stated, "CONTRIBUTING's worked example states the Delta's sizes"
    module = _counts(repo / "screwkit" / "robots" / "families" / "delta.py")
    toml_lines = len((repo / "mechanisms" / "delta.toml").read_text(encoding="utf-8").splitlines())
    assert tuple(map(int, stated.groups())) == (*module, toml_lines)
