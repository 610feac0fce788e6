"""A condition within the report's vanishing tolerance at a pose the verdict reads regular says so, rather
than "vanishes at this pose" beside a regular verdict (a new user's finding: a path crossing printed to six
digits and fed back)."""

import numpy as np

import screwkit as sk
from tests.mechanisms import planar_3rpr

BASE = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 1.0, 0.0]])
PLATFORM = np.array([[0.4, 0.3, 0.0], [0.7, 0.35, 0.0], [0.55, 0.55, 0.0]])


def leg_lines_determinant(pose):
    """det[(u_i; (a_i × u_i)_z)] of the three leg lines, by hand: the platform's points turned by phi about
    their centroid (the reference pose's platform point) and carried to (x, y); zero iff the lines meet
    at one point (or are parallel)."""
    x, y, phi = pose
    turn = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])
    centroid = PLATFORM[:, :2].mean(axis=0)
    rows = []
    for a, c in zip(BASE[:, :2], PLATFORM[:, :2], strict=True):
        u = (np.array([x, y]) + turn @ (c - centroid)) - a
        u /= np.linalg.norm(u)
        rows.append([u[0], u[1], a[0] * u[1] - a[1] * u[0]])
    return np.linalg.det(np.array(rows))


def test_a_condition_near_zero_at_a_regular_pose_is_not_said_to_vanish_there():
    rpr = sk.mechanism(planar_3rpr(BASE, PLATFORM))
    near = [0.55, 0.4, -0.0976843]  # the crossing of phi in [-0.5, 0.5] at x = 0.55, y = 0.4, to 6 digits
    assert 0 < abs(leg_lines_determinant(near)) < 1e-7  # near the legs' concurrency, not at it
    report = sk.analyze(rpr, near)
    assert report.verdict.verdict == "regular"
    line = next(line for line in str(report).splitlines() if "actuation singularity when" in line)
    assert "near zero here" in line and "vanishes at this pose" not in line
    regular = sk.analyze(rpr, [0.55, 0.4, 0.3])
    assert not any("near zero" in line or "vanishes" in line for line in str(regular).splitlines()
                   if "singularity when" in line)
