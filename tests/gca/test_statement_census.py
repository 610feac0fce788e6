"""Every factor of every mechanism we build cheaply has a statement (issue 21, "more statements"):
the catalog, the twist graphs of the tests and docs, and a spherical 3-RRR, a 3-UPS wrist on a
central spherical joint and a 3-RPS built here. No condition may read only "the bracket expression …
vanishes"; the general 6-6 Gough–Stewart factor, which has no simpler statement, says why (the six
lines in one linear complex, the factor proved irreducible)."""

import numpy as np
import pytest

import screwkit as sk
from tests import mechanisms as M
from tests import mechanisms_extra as X

Z = np.array([0.0, 0.0, 1.0])


def three_rps(height=1.0):
    """A 3-RPS: R about the base circle's tangent at a_i, actuated P, S at c_i in the vertical plane
    through a_i and the centre (the platform level, centred, at ``height``)."""
    joints = []
    for i, angle in enumerate(np.deg2rad([90.0, 210.0, 330.0]), start=1):
        radial = np.array([np.cos(angle), np.sin(angle), 0.0])
        a, c = radial, 0.5 * radial + height * Z
        joints += [("base", f"leg{i}", sk.revolute(f"R{i}", np.cross(Z, radial), a)),
                   (f"leg{i}", f"rod{i}", sk.prismatic(f"P{i}", c - a, actuated=True)),
                   (f"rod{i}", "platform", sk.spherical(f"S{i}", c))]
    return sk.twist_graph("base", "platform", joints, dof=3)


def spherical_3rrr():
    """A spherical 3-RRR: every joint axis through the origin, the first of each leg actuated."""
    joints = []
    for i in range(3):
        angle = 2 * np.pi * i / 3
        axes = [[np.cos(angle + turn), np.sin(angle + turn), z] for turn, z in ((0.0, -0.6), (0.9, 0.2), (0.3, 0.9))]
        joints += [("base", f"proximal{i}", sk.revolute(f"A{i}", axes[0], [0, 0, 0], actuated=True)),
                   (f"proximal{i}", f"distal{i}", sk.revolute(f"B{i}", axes[1], [0, 0, 0])),
                   (f"distal{i}", "platform", sk.revolute(f"C{i}", axes[2], [0, 0, 0]))]
    return sk.twist_graph("base", "platform", joints, dof=3)


def ups_wrist():
    """A wrist: the platform on a central spherical joint, turned by three actuated UPS legs."""
    centre = np.array([0.0, 0.0, 1.0])
    joints = [("base", "platform", sk.spherical("centre", centre))]
    for i in range(3):
        angle = 2 * np.pi * i / 3
        a = np.array([np.cos(angle), np.sin(angle), 0.0])
        c = centre + np.array([0.4 * np.cos(angle + 0.5), 0.4 * np.sin(angle + 0.5), 0.2])
        first = np.cross(c - a, Z)
        joints += [("base", f"cylinder{i}", sk.universal(f"U{i}", first, np.cross(c - a, first), a)),
                   (f"cylinder{i}", f"piston{i}", sk.prismatic(f"P{i}", c - a, actuated=True)),
                   (f"piston{i}", "platform", sk.spherical(f"S{i}", c))]
    return sk.twist_graph("base", "platform", joints, dof=3)


def planar_4rpr():
    """docs/redundancy.md's 4-RPR: four actuated legs for three freedoms."""
    base = [[0, 0, 0], [1, 0, 0], [0.5, 1, 0], [1, 1, 0]]
    platform = [[0.4, 0.3, 0], [0.7, 0.35, 0], [0.55, 0.55, 0], [0.65, 0.5, 0]]
    joints = []
    for i, (a, c) in enumerate(zip(base, platform, strict=True), start=1):
        joints += [("base", f"cylinder{i}", sk.revolute(f"A{i}", [0, 0, 1], a)),
                   (f"cylinder{i}", f"piston{i}", sk.prismatic(f"P{i}", np.subtract(c, a), actuated=True)),
                   (f"piston{i}", "platform", sk.revolute(f"C{i}", [0, 0, 1], c))]
    return sk.twist_graph("base", "platform", joints)


def five_bar():
    """docs/mechanisms.md's five-bar."""
    return sk.twist_graph("ground", "distal1", [
        ("ground", "proximal1", sk.revolute("A1", [0, 0, 1], [0, 0, 0], actuated=True)),
        ("proximal1", "distal1", sk.revolute("B1", [0, 0, 1], [0, 1, 0])),
        ("ground", "proximal2", sk.revolute("A2", [0, 0, 1], [1, 0, 0], actuated=True)),
        ("proximal2", "distal2", sk.revolute("B2", [0, 0, 1], [1, 1, 0])),
        ("distal2", "distal1", sk.revolute("C", [0, 0, 1], [0.5, 1.8, 0]))], dof=2)


TILT = M.rotation_about([0.2, 1.0, 0.1], 0.1)
GRAPHS = {
    "Tsai's 3-UPU": lambda: M.tsai_3upu([0.05, 0.1, 1.0]),
    "general 6-6 Gough-Stewart": lambda: M.gough_stewart(*M.gough_stewart_points(TILT, [0.05, 0.02, 1.0])),
    "octahedral 3-3": lambda: M.gough_stewart(*X.octahedral_points(TILT, [0.05, 0.02, 1.0])),
    "3-PRS": lambda: X.three_prs(M.rotation_about([1, 0.3, 0], 0.2), [0.02, 0.03, 1.0])[0],
    "3-RPS": three_rps,
    "Delta": lambda: X.delta([0.1, 0.05, -2.0]),
    "planar 3-RPR": lambda: M.planar_3rpr(M.PLANAR_BASE, M.PLANAR_PLATFORM),
    "five-bar": five_bar,
    "redundant 4-RPR": planar_4rpr,
    "spherical 3-RRR": spherical_3rrr,
    "3-UPS wrist": ups_wrist,
}


@pytest.mark.parametrize("target", sk.list_mechanisms() + list(GRAPHS))
def test_every_factor_has_a_statement(target):
    report = sk.analyze(GRAPHS[target]() if target in GRAPHS else target)
    found = report.superbracket.conditions
    assert found
    for c in found:
        assert not c.statement.startswith("the bracket expression"), (target, str(c.factor), c.statement)
    if target == "general 6-6 Gough-Stewart":
        (c,) = found
        assert "belong to one linear line complex" in c.statement
        assert "irreducible in the coordinates of its 12 points taken free, proved exactly" in c.statement
