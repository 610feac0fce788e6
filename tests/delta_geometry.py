"""The Delta robot's geometry written from Clavel's patent (US 4,976,582) and Williams' kinematics
notes (2015), independently of screwkit.robots.families.delta: used by tests/robots/test_delta.py
and tests/facts_delta.py.

* Leg ``i`` lies at ``γ_i = 0°, 120°, 240°`` about ``k`` (radial direction ``r_i``); its actuated
  revolute joint at ``A_i = R r_i`` turns the arm of length ``b`` about the horizontal axis
  ``u_i = k × r_i``; the rods of length ``l`` join the elbow ``B_i`` to ``C_i = p + r r_i``.
* Forward kinematics (Williams, "forward position kinematics"): ``p`` is where the three spheres of
  radius ``l`` about ``B_i - r r_i`` meet; solved by subtracting the sphere equations (two linear
  equations: a line) and one quadratic along the line, the root below the elbows.
* The direct singularity (Williams, velocity kinematics ``A ṗ = B θ̇``, the rows of ``A`` the rod
  directions ``w_i``): ``det[w_1; w_2; w_3] = 0``.
"""

import numpy as np

GAMMA = np.radians([0.0, 120.0, 240.0])
RADIAL = np.stack([np.cos(GAMMA), np.sin(GAMMA), np.zeros(3)], -1)


def dimensions(mechanism):
    """``(R, r, b, l)`` of a Delta catalog entry."""
    p = mechanism.parameters
    return p.base_radius, p.platform_radius, p.arm_length, p.rod_length


def rotate(vector, axis, angle):
    """Rodrigues' rotation of ``vector`` about the unit ``axis`` by ``angle`` (batched)."""
    cos, sin = np.cos(angle)[..., None], np.sin(angle)[..., None]
    return vector * cos + np.cross(axis, vector) * sin + axis * np.sum(axis * vector, -1)[..., None] * (1 - cos)


def elbows(mechanism, theta):
    """B_i from the arm angles: r_i turned by θ_i about u_i = k × r_i (θ > 0 lowers the arm)."""
    base, _, arm, _ = dimensions(mechanism)
    axes = np.cross([0.0, 0.0, 1.0], RADIAL)
    return base * RADIAL + arm * rotate(np.broadcast_to(RADIAL, (*theta.shape[:-1], 3, 3)), axes, theta)


def forward(mechanism, theta):
    """The platform point from the arm angles ``(3,)``: the three spheres' lower intersection."""
    _, platform, _, rod = dimensions(mechanism)
    centres = elbows(mechanism, theta) - platform * RADIAL
    rows = 2 * (centres[1:] - centres[:1])  # |p - c_i|² - |p - c_1|² = 0, i = 2, 3
    rhs = np.sum(centres[1:] ** 2, -1) - np.sum(centres[:1] ** 2, -1)
    point = np.linalg.lstsq(rows, rhs, rcond=None)[0]
    direction = np.cross(rows[0], rows[1])
    direction /= np.linalg.norm(direction)
    offset = point - centres[0]
    half = offset @ direction  # |offset + t d|² = l²
    t = -half + np.array([-1.0, 1.0]) * np.sqrt(half**2 - (offset @ offset - rod**2))
    candidates = point + t[:, None] * direction
    return candidates[np.argmin(candidates[:, 2])]


def rod_determinant(mechanism, poses):
    """det[w_1; w_2; w_3], the rod directions from the arm angles of the family's inverse kinematics."""
    _, platform, _, rod = dimensions(mechanism)
    theta = mechanism.configuration(poses).theta
    rods = poses[..., None, :] + platform * RADIAL - elbows(mechanism, theta)
    return np.linalg.det(rods / rod)


def coplanar_root_on_x(mechanism, z, high=1500.0):
    """The smallest ``x > 0`` on the line ``(x, 0, z)`` where the rods' directions are dependent
    (bisection of :func:`rod_determinant` between grid points of a sign change), or None."""
    line = np.stack([np.linspace(0.0, high, 301), np.zeros(301), np.full(301, z)], -1)
    line = line[mechanism.reachable(line)]
    signs = np.sign(rod_determinant(mechanism, line))
    crossing = np.flatnonzero(np.diff(signs))
    if not len(crossing):
        return None
    low, top = line[crossing[0]], line[crossing[0] + 1]
    for _ in range(60):
        middle = (low + top) / 2
        same = np.sign(rod_determinant(mechanism, middle[None]))[0] == signs[crossing[0]]
        low, top = (middle, top) if same else (low, middle)
    return (low + top) / 2
