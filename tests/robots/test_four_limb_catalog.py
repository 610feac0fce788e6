"""The four-limb catalog entries of paper 004 (Quattro, V4, Veloce, Ragnar) against the paper.

Known values are the paper's (Tables 1, 3, 4, Sec. 5); the singularity types of Sec. 4.2 (type 1:
``|B| = 0``, type 2: ``|A| = 0``) are compared with the labels of the twist graph
(:func:`screwkit.core.singularity.classify`, one pose; :func:`screwkit.core.singularity.classify_table`, many) at poses
found by root search. An independent numpy computation of the platform's twist system (intersections
and sums of joint-screw spans, no screwkit screw systems) confirms the constraint singularities the
entries document (Quattro: a surface through the workspace centre; the Ragnar read with horizontal
actuated axes: every pose).
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from screwkit.core.singularity import classify, classify_table
from screwkit.core.wrenches import wrench_analysis
from screwkit.gca.diagram_points import diagram_points
from screwkit.interface.cli import main
from screwkit.interface.report import analyze
from screwkit.papers.paper_004 import (
    four_limb_jacobians,
    transmission_indices,
)
from screwkit.robots.catalog import list_mechanisms, load_mechanism
from screwkit.robots.families.four_limb.kinematics import reachable

from ..paper_004 import spiral_trajectory

PI = math.pi
NAMES = ["quattro", "v4", "veloce", "ragnar"]
SCHOENFLIES = ["quattro", "v4", "veloce"]


@pytest.fixture(scope="module")
def entries():
    return {name: load_mechanism(name) for name in NAMES}


@pytest.fixture(scope="module")
def horizontal_ragnar(entries):
    """The Ragnar read with horizontal actuated axes (u_i = +-i, ragnar.toml's header): 5 DOF."""
    ragnar = entries["ragnar"]
    return dataclasses.replace(ragnar, parameters=dataclasses.replace(ragnar.parameters, axis_inclination=0.0))


def bisect(function, lo, hi, iterations=100):
    """Scalar bisection on a sign change of ``function`` in [lo, hi] (the root to machine precision)."""
    f_lo = function(lo)
    assert np.sign(f_lo) != np.sign(function(hi)), "no sign change in the bracket"
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        f_mid = function(mid)
        if np.sign(f_mid) == np.sign(f_lo):
            lo, f_lo = mid, f_mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def det_a(mechanism, pose):
    return float(np.linalg.det(four_limb_jacobians(mechanism.configuration(pose)).A))


def batch_report(mechanism, poses, **options):
    return classify_table(mechanism.joints(poses), **options)


# -------------------------------------------------------------------------------------------------
# The entries hold the paper's numbers
# -------------------------------------------------------------------------------------------------

PAPER = {  # Table 3 and Sec. 5 (R = 275, b = 375, l = 800 mm); Ragnar: text after Table 4
    "quattro": {"alpha": -PI / 4, "beta": 3 * PI / 4, "platform_radius": 80.0, "platform_offset": 70.0},
    "v4": {"alpha": 0.0, "beta": PI / 2, "platform_radius": 80.0, "platform_offset": 70.0},
    "veloce": {"alpha": -PI / 4, "beta": 3 * PI / 4, "platform_radius": 100.0, "lead": 20.0},
    "ragnar": {"alpha": 0.0, "beta": PI, "platform_radius": 100.0, "lead": 20.0,
               "axis_inclination": PI / 4},  # inferred from Table 4, not printed (ragnar.toml)
}


@pytest.mark.parametrize("name", NAMES)
def test_parameters_are_the_papers(entries, name):
    params = entries[name].parameters
    assert (params.arm_length, params.rod_length) == (375.0, 800.0)
    for key, value in PAPER[name].items():
        assert getattr(params, key) == pytest.approx(value, abs=1e-15), key
    if name == "ragnar":
        assert params.base_radius is None
        assert params.base_points == ((350, 100, 0), (-350, 100, 0), (-350, -100, 0), (350, -100, 0))
    else:
        assert params.base_radius == 275.0 and params.base_points is None
    assert entries[name].length_unit == "mm"
    for key, documented in entries[name].parameter_sources.items():
        assert "paper 004" in documented["source"] or documented["source"].startswith("our choice"), key


@pytest.mark.parametrize("name", NAMES)
def test_table_1_platform_points(entries, name):
    # c_i of Table 1 written out by hand at phi = 0.3 (V4 row corrected, see v4.toml)
    pose = np.array([30.0, -20.0, -700.0, 0.3])
    config = entries[name].configuration(pose)
    c, s = math.cos(0.3), math.sin(0.3)
    eta = [(2 * i - 1) * PI / 4 for i in range(1, 5)]
    for i in range(4):
        sc, ss = np.sign(math.cos(eta[i])), np.sign(math.sin(eta[i]))
        if name == "quattro":
            expected = sc * 80 * np.array([c, s, 0]) + ss * 70 * np.array([0, 1, 0])
        elif name == "v4":
            expected = sc * 80 * np.array([c, 0, -s]) + ss * 70 * np.array([0, 1, 0])
        else:
            expected = 100 * np.array([math.cos(eta[i]), math.sin(eta[i]), 0]) + (i % 2 == 0) * 20 * 0.3 / (
                2 * PI
            ) * np.array([0, 0, 1])
        np.testing.assert_allclose(config.c[i], expected + pose[:3], atol=1e-12)


@pytest.mark.parametrize(("name", "width"), [("quattro", 20.0), ("v4", 400.0), ("veloce", 20.0)])
def test_labels_do_not_depend_on_the_chosen_parallelogram_width(entries, name, width):
    # the rod spacing d is our choice (paper 004 does not give it): orders and labels must not move
    mechanism = entries[name]
    changed = dataclasses.replace(
        mechanism, parameters=dataclasses.replace(mechanism.parameters, parallelogram_width=width)
    )
    for pose in (mechanism.default_pose, [120.0, -80.0, -700.0, 0.6]):
        reference, report = classify(mechanism.twist_graph(pose)), classify(changed.twist_graph(pose))
        assert report.labels == reference.labels
        assert report.global_order == reference.global_order
        # each actuation wrench is the same modulo its limb's constraint couple (which shifts the force
        # line within the parallelogram plane, where the choice may differ)
        for changed_limb, limb in zip(report.analysis.limbs, reference.analysis.limbs, strict=True):
            couples = limb.constraint_wrenches.basis
            both = np.vstack([changed_limb.actuation_wrench, limb.actuation_wrench, couples]) / [
                1,
                1,
                1,
                1e3,
                1e3,
                1e3,
            ]
            assert np.linalg.matrix_rank(both, tol=1e-9 * np.abs(both).max()) == 1 + len(couples)


# -------------------------------------------------------------------------------------------------
# Paper 004's singularity types <-> twist-graph labels
# -------------------------------------------------------------------------------------------------

TYPE_2_BRACKETS = {  # segments of reachable poses on which det A changes sign (found by a grid scan)
    "v4": ([400.0, 150.0, -750.0, PI / 4], [500.0, 150.0, -750.0, PI / 4]),  # inside the workspace
    "veloce": ([-870.0, -90.0, -325.0, 0.0], [-840.0, -90.0, -325.0, 0.0]),  # near the reach limit
}


def spiral_pose(vartheta):
    """Eqs. (17)-(18) at one value of the path parameter."""
    rho = vartheta / (4 * PI)
    return np.array(
        [650 * rho * math.cos(vartheta), 650 * rho * math.sin(vartheta), -975 + 500 * rho, PI * rho - PI / 2]
    )


@pytest.fixture(scope="module")
def type_2_poses(entries):
    """|A| = 0 by bisection: the Quattro on the spiral near phi = -90 deg (Sec. 5.1), V4, Veloce."""
    quattro = entries["quattro"]
    poses = {"quattro": spiral_pose(bisect(lambda v: det_a(quattro, spiral_pose(v)), 0.05, 0.15))}
    for name, (start, end) in TYPE_2_BRACKETS.items():
        a, b = np.array(start), np.array(end)
        poses[name] = a + bisect(lambda t, m=entries[name], a=a, b=b: det_a(m, a + t * (b - a)), 0.0, 1.0) * (
            b - a
        )
    return poses


@pytest.mark.parametrize("name", SCHOENFLIES)
def test_type_2_is_an_actuation_singularity(entries, type_2_poses, name):
    mechanism, pose = entries[name], type_2_poses[name]
    config = mechanism.configuration(pose)
    assert abs(np.linalg.det(four_limb_jacobians(config).A)) < 1e-12 * mechanism.parameters.rod_length
    assert transmission_indices(config).zeta < 1e-12  # sigma = 90 deg (Sec. 4.2)
    report = classify(mechanism.twist_graph(pose))
    assert report.labels == ("actuation",)
    assert (report.constraint_order, report.global_order, report.uncontrolled_dof) == (2, 5, 1)
    assert report.closeness["actuation"] < 1e-12 < 1e-4 < report.closeness["constraint"]
    # the uncontrolled twist is the null vector of A: A (v_p, phi_dot) = 0 with v_p the velocity of p
    twist = report.uncontrolled_twists[0]
    p = config.pose[:3]
    velocity = twist[3:] + np.cross(twist[:3], p)  # of the end-effector point at p
    rate_vector = np.concatenate([velocity, [twist[:3] @ config.platform_joint_axis]])
    null = np.linalg.svd(four_limb_jacobians(config).A)[2][-1]
    assert abs(abs(rate_vector @ null) / np.linalg.norm(rate_vector) - 1.0) < 1e-6
    if name == "quattro":  # Sec. 5.1: "Type-2 singularity when |phi| = pi/2": here -88.3 deg
        assert math.degrees(pose[3]) == pytest.approx(-88.27, abs=0.01)


@pytest.mark.parametrize("name", SCHOENFLIES)
def test_type_1_is_a_serial_singularity(entries, name):
    # |B| = 0: limb 2 fully stretched, at the reach limit along a ray (bisection on Eq. 3 having a
    # root). The IK's arccos turns the 1e-16 left by bisection into h_2 / b ~ 3e-8, so the label is
    # checked at rtol = 1e-6; 1 mm inside it is gone.
    mechanism = entries[name]
    start, ray = np.array([100.0, 100.0, -750.0, 0.3]), np.array([1.0, 0.3, 0.0, 0.0])
    inside, outside = 0.0, 2000.0  # bisection keeping `inside` reachable
    assert reachable(mechanism.parameters, start) and not reachable(
        mechanism.parameters, start + outside * ray
    )
    for _ in range(100):
        middle = 0.5 * (inside + outside)
        inside, outside = (
            (middle, outside) if reachable(mechanism.parameters, start + middle * ray) else (inside, middle)
        )
    pose = start + inside * ray
    config = mechanism.configuration(pose)
    assert np.argmin(np.abs(config.h)) == 1 and abs(config.h[1]) < 1e-6 * 375
    report = classify(mechanism.twist_graph(pose), rtol=1e-6)
    assert report.labels == ("serial",)
    assert [s.actuated_joint for s in report.serial] == ["A2"]
    assert report.lost_dof == 1 and report.global_order == 6  # the limb locks, nothing is uncontrolled
    assert report.closeness["serial"] == pytest.approx(transmission_indices(config).kappa, rel=0.2)
    assert classify(mechanism.twist_graph(start + (inside - 1.0) * ray), rtol=1e-6).labels == ()


@pytest.mark.parametrize("name", SCHOENFLIES)
def test_random_workspace_poses_are_regular_batch_and_single(entries, name, rng):
    mechanism = entries[name]
    poses = mechanism.random_poses(rng, 150)
    poses = poses[reachable(mechanism.parameters, poses)]
    indices = transmission_indices(mechanism.configuration(poses))
    report = batch_report(mechanism, poses)
    labels = report.labels.ravel().tolist()
    # regular where paper 004's index says so (eta > 0.005: far from both types)
    assert all(label == () for label, eta in zip(labels, indices.eta, strict=True) if eta > 0.005)
    assert sum(eta > 0.005 for eta in indices.eta) >= 100
    for k in range(0, len(poses), 37):  # the vectorized labels are the single-pose ones
        assert classify(mechanism.twist_graph(poses[k])).labels == labels[k]


def test_quattro_spiral_trajectory_labels(entries):
    # Sec. 5.1 along Eqs. (17)-(18), vectorized: regular except where the screw theory finds more.
    quattro = entries["quattro"]
    poses = spiral_trajectory(401)
    config = quattro.configuration(poses)
    labels = batch_report(quattro, poses).labels.ravel().tolist()
    det = np.linalg.det(four_limb_jacobians(config).A)
    crossing = int(np.flatnonzero(np.sign(det[:-1]) != np.sign(det[1:]))[0])
    assert crossing == 3  # between phi = -88.65 and -88.2 deg: the type-2 root of the fixture
    assert labels[0] == ("constraint",)  # the start (0, 0, -975, -90 deg) is on the z axis
    assert labels[200] == ("constraint",)  # (325, 0, -725, 0): on the plane y = 0 at phi = 0, where
    # Sec. 5.1 finds sigma = 0 (the best force transmission)
    assert all(label == () for k, label in enumerate(labels) if k not in (0, 200))
    assert transmission_indices(config).zeta[200] == pytest.approx(1.0, abs=1e-12)


# -------------------------------------------------------------------------------------------------
# Constraint singularities, confirmed by an independent computation
# -------------------------------------------------------------------------------------------------


def _row_space(rows, rtol=1e-9):
    _, values, vt = np.linalg.svd(np.atleast_2d(rows))
    return vt[: int((values > rtol * values[0]).sum())]


def _intersection(a, b, rtol=1e-9):
    stacked = np.vstack([a, -b]).T  # a^T x = b^T y
    _, values, vt = np.linalg.svd(stacked)
    rank = int((values > rtol * values[0]).sum())
    null = vt[rank:, : len(a)]
    return _row_space(null @ a, rtol) if len(null) else np.zeros((0, 6))


def independent_platform_order(config, length=1000.0):
    """Order of the end effector's twist system from the joints' geometry with numpy alone:
    per limb R(u_i at A_i) + (rod a: S(m) + S(p)) ∩ (rod b: S(n) + S(q)); per sub-platform the
    intersection of its two limbs; plus the joint R_I or H_I; the two legs intersected."""

    def rotations(point):  # three zero-pitch screws through a point, moments over `length`
        return np.hstack([np.eye(3), np.cross(point, np.eye(3)) / length])

    def screw(axis, point, pitch=0.0):
        return np.concatenate([axis, (np.cross(point, axis) + pitch * axis) / length])

    limbs = []
    for i in range(4):
        (m, n), (p, q) = config.elbow_corners[i], config.platform_corners[i]
        parallelogram = _intersection(
            _row_space(np.vstack([rotations(m), rotations(p)])),
            _row_space(np.vstack([rotations(n), rotations(q)])),
        )
        limbs.append(_row_space(np.vstack([screw(config.u[i], config.a[i]), parallelogram])))
    legs = []
    for k, (i, j) in enumerate(config.subplatform_limbs):
        joint = screw(
            config.platform_joint_axis, config.platform_joint_points[k], config.platform_joint_pitches[k]
        )
        legs.append(_row_space(np.vstack([_intersection(limbs[i], limbs[j]), joint])))
    return len(_intersection(*legs))


@pytest.mark.parametrize(
    ("name", "pose", "order"),
    [
        ("quattro", [100.0, 100.0, -750.0, 0.0], 4),
        ("quattro", [0.0, 0.0, -750.0, 0.4], 5),  # the z axis
        ("quattro", [-250.0, 0.0, -650.0, 0.0], 5),  # the plane y = 0 at phi = 0
        ("quattro", [-250.0, 0.0, -650.0, 0.2], 4),  # ... only at phi = 0
        ("v4", [0.0, 0.0, -750.0, 0.0], 4),
        ("veloce", [0.0, 0.0, -750.0, 0.0], 4),
        ("ragnar", [0.0, 0.0, -575.0, 0.0], 4),  # inclined axes
        ("ragnar", [150.0, -300.0, -700.0, 2.0], 4),
        ("horizontal_ragnar", [0.0, 0.0, -575.0, 0.0], 5),  # every pose
        ("horizontal_ragnar", [150.0, -300.0, -700.0, 2.0], 5),
    ],
)
def test_platform_twist_order_independent(entries, horizontal_ragnar, name, pose, order):
    mechanism = horizontal_ragnar if name == "horizontal_ragnar" else entries[name]
    assert independent_platform_order(mechanism.configuration(pose)) == order
    assert classify(mechanism.twist_graph(pose)).analysis.platform_twists.order == order


def test_quattro_constraint_singularity_is_paper_002_condition(entries):
    # paper 002's constraint condition [gikj] = 0: z, n_1 x n_4, n_2 x n_3 coplanar (n_i = u_i x w_i,
    # the normal of limb i's constraint couple). By the half-turn symmetry R_z(pi) (limbs 1<->3, 2<->4)
    # n_2 x n_3 = -R_z(pi)(n_1 x n_4) on the z axis, so both have the same horizontal part; at phi = 0 the
    # mirror y -> -y (limbs 1<->4, 2<->3) makes the configuration symmetric on the plane y = 0, where the
    # three are again coplanar (checked here). A line across y = 0 at phi = 0:
    quattro = entries["quattro"]
    poses = np.column_stack([np.full(9, 200.0), np.linspace(-40.0, 40.0, 9), np.full(9, -700.0), np.zeros(9)])
    config = quattro.configuration(poses)
    n = np.cross(config.u, config.w)
    normals = np.cross(np.cross(n[:, 0], n[:, 3]), np.cross(n[:, 1], n[:, 2]))
    coplanarity = normals[:, 2] / np.linalg.norm(normals, axis=-1)
    assert abs(coplanarity[4]) < 1e-12 and np.all(np.abs(np.delete(coplanarity, 4)) > 1e-4)
    assert np.all(np.sign(coplanarity[:4]) == -np.sign(coplanarity[5:]))  # it changes sign: a surface
    labels = batch_report(quattro, poses).labels.ravel().tolist()
    assert labels == [()] * 4 + [("constraint",)] + [()] * 4
    # the gained freedom: the end effector's rotations span two directions (z and a horizontal one)
    for pose, rotations in ((poses[4], 2), (poses[3], 1)):
        twists = classify(quattro.twist_graph(pose)).analysis.platform_twists.basis
        omega = np.linalg.svd(twists[:, :3], compute_uv=False)
        assert int((omega > 1e-9 * omega[0]).sum()) == rotations


def test_horizontal_ragnar_turns_freely_about_x(horizontal_ragnar, rng):
    # all actuated axes along +-x (the horizontal reading of "parallel to the x-z plane", ragnar.toml):
    # every limb's constraint couple is normal to x, so the rotation about x is never constrained
    ragnar = horizontal_ragnar
    poses = ragnar.random_poses(rng, 60)
    poses = poses[reachable(ragnar.parameters, poses)]
    config = ragnar.configuration(poses)
    np.testing.assert_allclose(np.abs(config.u[..., 0]), 1.0)
    n = np.cross(config.u, config.w)
    assert np.abs(n[..., 0]).max() < 1e-12
    report = batch_report(ragnar, poses)
    assert np.all(report.constraint_order == 1) and np.all(report.global_order == 5)
    for pose in poses[:3]:  # the one constraint couple is normal to x: the rotation about x is free
        analysis = classify(ragnar.twist_graph(pose)).analysis
        couple = analysis.constraint_wrenches.basis[0]
        assert np.linalg.norm(couple[:3]) < 1e-12 and abs(couple[3]) < 1e-12 * np.linalg.norm(couple)
        rotation = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
        stacked = np.vstack([analysis.platform_twists.basis / [1, 1, 1, 1e3, 1e3, 1e3], rotation])
        assert np.linalg.matrix_rank(stacked, tol=1e-9) == 5


def test_paper_lti_cannot_see_constraint_singularities(entries, horizontal_ragnar):
    # Eqs. (15)-(16) use the 4x4 Jacobians only: at the Quattro's constraint-singular centre pose the
    # LTI is high, and the horizontal Ragnar's permanent one leaves A regular
    for mechanism, pose in ((entries["quattro"], [0.0, 0.0, -750.0, 0.0]),
                            (horizontal_ragnar, [0.0, 0.0, -575.0, 0.0])):
        config = mechanism.configuration(pose)
        assert transmission_indices(config).eta > 0.6
        assert "constraint" in classify(mechanism.twist_graph(pose)).labels


# -------------------------------------------------------------------------------------------------
# Wrench diagram, superbracket and the command line
# -------------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def quattro_report():
    return analyze("quattro")


def test_quattro_superbracket_constraint_factor_vanishes_on_the_surface(entries, quattro_report):
    # the factored superbracket's constraint factor (paper 002's [gikj]) is zero on y = 0 at phi = 0
    result = quattro_report.superbracket
    assert result.labels == ("constraint", "actuation")
    constraint = result.conditions[0]
    quattro = entries["quattro"]
    values = []
    for y in (-30.0, 0.0, 30.0):
        pose = [200.0, y, -700.0, 0.0]
        points = diagram_points(quattro_report.diagram.points, wrench_analysis(quattro.twist_graph(pose)))
        values.append(float(constraint.evaluate(points)))
    assert abs(values[1]) < 1e-12 < min(abs(values[0]), abs(values[2]))


def test_cli_list_shows_the_new_entries(capsys):
    assert main(["list", "--json"]) == 0
    listed = {entry["name"]: entry for entry in json.loads(capsys.readouterr().out)}
    for name in NAMES:
        mechanism = load_mechanism(name)
        assert name in list_mechanisms()
        assert listed[name]["title"] == mechanism.name and listed[name]["family"] == "four_limb"
        assert listed[name]["sources"] == list(mechanism.sources)
    assert main(["list"]) == 0
    text = capsys.readouterr().out
    assert all(line.split()[0] in listed for line in text.strip().splitlines())


def test_cli_analyze_quattro_matches_the_library(capsys):
    # (the full superbracket through the CLI is exercised for the planar entry; here the rest)
    assert main(["analyze", "quattro", "--json", "--no-superbracket"]) == 0
    printed = json.loads(capsys.readouterr().out)
    expected = json.loads(json.dumps(analyze("quattro", superbracket=False).to_dict()))
    assert printed["verdict"] == expected["verdict"] and printed["wrenches"] == expected["wrenches"]
    assert printed["mechanism"]["name"] == "Quattro" and printed["pose"]["x"] == 100.0
    assert main(["analyze", "quattro", "--no-superbracket"]) == 0
    assert "regular (dof 4)" in capsys.readouterr().out


@pytest.mark.parametrize("name", ["v4", "veloce", "ragnar"])
def test_cli_analyze_other_entries(capsys, entries, name):
    pose = [str(v) for v in (0.0, 0.0, -750.0 if name != "ragnar" else -575.0, 10.0)]
    assert main(["analyze", name, "--no-superbracket", "--json", "--pose", *pose]) == 0
    printed = json.loads(capsys.readouterr().out)
    report = classify(
        entries[name].twist_graph(np.array([float(pose[0]), 0.0, float(pose[2]), math.radians(10.0)]))
    )
    assert printed["verdict"]["labels"] == list(report.labels)
    assert printed["verdict"]["global_order"] == report.global_order
    if name == "ragnar":  # inclined axes: 4 DOF, six wrench lines, a diagram with nothing degenerate
        assert printed["wrenches"]["platform_twist_order"] == 4 and not printed["diagram"]["degenerate"]


def test_cli_analyze_unreachable_pose_is_an_analysis_error(capsys):
    assert main(["analyze", "veloce", "--pose", "0", "0", "-3000", "0"]) == 1
    assert "out of reach of Veloce" in capsys.readouterr().err
