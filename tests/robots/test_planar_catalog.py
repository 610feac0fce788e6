"""The planar 3-RRP catalog entry (paper 003) and its physical twist graph.

The twist-graph labels (:func:`screwkit.core.singularity.classify` with ``dof = 3``; vectorized
:func:`screwkit.core.singularity.classify_table`) are compared with the family's instant-centre classification
(``tests/paper_003.classify``, paper 003 Sec. 4) at singular configurations found
by root search: inverse <-> serial, direct <-> actuation, combined <-> both; and the wrenches with
paper 003's geometry (the lines t_k through the elbows, the concurrency point D = C_18).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from screwkit.algebra import screw as S
from screwkit.core.singularity import classify as classify_graph
from screwkit.core.singularity import classify_table
from screwkit.exceptions import CatalogError, ScrewkitTypeError, ScrewkitValueError
from screwkit.graphs.loops import fundamental_loops
from screwkit.interface.cli import main
from screwkit.interface.report import analyze
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families.planar_3rrp.configuration import Planar3RRPConfiguration
from screwkit.robots.families.planar_3rrp.joints import JOINT_PAIRS, LINK_NAMES, joints
from screwkit.robots.families.planar_3rrp.kinematics import (
    WORKING_MODES,
    forward_kinematics,
    inverse_kinematics,
)
from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS, Planar3RRPParameters

from ..paper_003 import classify, jacobians

P = EXAMPLE_PARAMETERS


@pytest.fixture(scope="module")
def planar():
    return load_mechanism("planar_3rrp")


def bisect(function, lo, hi, iterations=100):
    """Scalar bisection on a sign change of ``function`` in [lo, hi]."""
    f_lo = function(lo)
    assert np.sign(f_lo) != np.sign(function(hi)), "no sign change in the bracket"
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        f_mid = function(mid)
        if np.sign(f_mid) == np.sign(f_lo):
            lo, f_lo = mid, f_mid
        else:
            hi = mid
    return lo


def kennedy_point(config):
    """The common point of the lines through the elbows perpendicular to the guides (limbs 1, 2),
    by hand: A_k + s_k E b_k, solved as a 2x2 linear system."""
    normals = np.stack([-config.guide_directions[:, 1], config.guide_directions[:, 0]], axis=-1)
    a = config.elbow_points
    s = np.linalg.solve(np.column_stack([normals[0], -normals[1]]), a[1] - a[0])
    return a[0] + s[0] * normals[0]


# -------------------------------------------------------------------------------------------------
# The entry and the twist graph
# -------------------------------------------------------------------------------------------------


def test_entry_is_the_family_example(planar):
    # paper 003 gives no dimensions: the entry copies EXAMPLE_PARAMETERS, documented as our choice
    for key in ("base_points", "link_lengths", "platform_points", "guide_angles"):
        np.testing.assert_allclose(getattr(planar.parameters, key), getattr(P, key), atol=1e-15)
        assert planar.parameter_sources[key]["source"].startswith(
            "our choice (paper 003 gives no dimensions)"
        )
    np.testing.assert_allclose(np.degrees(planar.parameters.guide_angles), [300.0, 60.0, 180.0])
    assert planar.pose_names == ("x", "y", "phi")
    np.testing.assert_array_equal(planar.default_pose, [0.0, 0.0, 0.0])


def test_twist_graph_structure(planar):
    config = planar.configuration([0.05, -0.03, 0.1])
    graph = joints(config).graph()
    assert set(graph.nodes) == set(LINK_NAMES)
    assert (graph.graph["base"], graph.graph["platform"], graph.graph["dof"]) == ("base", "platform", 3)
    # E - V + 1 = 9 - 8 + 1 = 2 independent loops
    assert graph.number_of_edges() == 9 and len(fundamental_loops(graph)) == 2
    centres = {"R1": config.base_points, "R2": config.elbow_points}  # M_k = C_1i, A_k = C_ij
    for k, pairs in enumerate(JOINT_PAIRS):
        for label, kind, (parent, child) in zip(("R1", "R2", "P"), "RRP", pairs, strict=True):
            edge = graph.edges[LINK_NAMES[parent - 1], LINK_NAMES[child - 1], f"limb{k + 1}_{label}"]["joint"]
            assert edge.type == kind and edge.actuated == (label == "R1")
            if kind == "R":  # axis z through the joint centre, pitch 0
                np.testing.assert_allclose(edge.screws[0][:3], [0.0, 0.0, 1.0])
                point, _ = S.axis(edge.screws[0])
                np.testing.assert_allclose(point[:2], centres[label][k], atol=1e-15)
            else:  # an infinite-pitch screw along the guide b_k
                np.testing.assert_allclose(edge.screws[0][:3], 0.0)
                np.testing.assert_allclose(edge.screws[0][3:], [*config.guide_directions[k], 0.0], atol=1e-15)
    # the catalog builds the same graph
    assert sorted(planar.twist_graph([0.05, -0.03, 0.1]).edges(keys=True)) == sorted(graph.edges(keys=True))


def test_twist_graph_of_a_batch_entry():
    config = Planar3RRPConfiguration.from_pose(P, np.array([[0.0, 0.0, 0.0], [0.05, -0.03, 0.1]]))
    single = joints(Planar3RRPConfiguration.from_pose(P, [0.05, -0.03, 0.1])).graph()
    batch = joints(config).graph((1,))
    for u, v, key, joint in single.edges(keys=True, data="joint"):
        np.testing.assert_allclose(batch.edges[u, v, key]["joint"].screws, joint.screws, atol=1e-15)


def test_wrench_systems_at_home(planar):
    # hand derivation: the planar twists (omega_z, v_x, v_y) have the reciprocal system of the force
    # along z and the couples about x and y; the home pose is symmetric under turns of 120 deg
    report = classify_graph(planar.twist_graph())
    assert report.labels == () and (report.constraint_order, report.global_order) == (3, 6)
    constraint = report.analysis.constraint_wrenches.basis
    assert np.abs(constraint[:, :2]).max() < 1e-12 and np.abs(constraint[:, 5]).max() < 1e-12
    directions = np.array([S.axis(limb.actuation_wrench)[1] for limb in report.analysis.limbs])
    np.testing.assert_allclose(
        np.abs(directions @ directions.T), [[1, 0.5, 0.5], [0.5, 1, 0.5], [0.5, 0.5, 1]], atol=1e-12
    )


@pytest.mark.parametrize("factor", [1e-3, 1e3])
def test_labels_and_closeness_do_not_depend_on_the_unit_or_frame(factor):
    turn = 0.7
    rotation = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    shift = np.array([0.4, -1.1])
    moved = Planar3RRPParameters(
        factor * (P.base_points @ rotation.T + shift),
        factor * P.link_lengths,
        factor * P.platform_points,
        P.guide_angles,
    )
    pose = np.array([0.05, -0.03, 0.1])
    moved_pose = np.append(factor * (rotation @ pose[:2] + shift), pose[2] + turn)
    one = classify_graph(joints(Planar3RRPConfiguration.from_pose(P, pose)).graph())
    two = classify_graph(joints(Planar3RRPConfiguration.from_pose(moved, moved_pose)).graph())
    assert one.labels == two.labels
    for key in one.closeness:
        assert two.closeness[key] == pytest.approx(one.closeness[key], abs=1e-9)


# -------------------------------------------------------------------------------------------------
# Paper 003's types <-> twist-graph labels, at configurations found by root search
# -------------------------------------------------------------------------------------------------


def _assembly(theta, det_k_sign):
    """The assembly mode of ``theta`` whose det K has the given sign."""
    fk = forward_kinematics(P, theta)
    both = Planar3RRPConfiguration(P, fk.poses, theta)
    pick = int(np.argmax(np.sign(np.linalg.det(jacobians(both)[1])) == det_k_sign))
    assert fk.valid[pick]
    return Planar3RRPConfiguration(P, fk.poses[pick], theta)


@pytest.fixture(scope="module")
def inverse_singular():
    """Sec. 4.1: lock actuators 2, 3 and turn actuator 1 until J_11 changes sign."""
    start = Planar3RRPConfiguration.from_pose(P, [0.05, -0.03, 0.1])
    sign = np.sign(np.linalg.det(jacobians(start)[1]))

    def j11(delta):
        return jacobians(_assembly(start.joint_angles + np.array([delta, 0.0, 0.0]), sign))[0][0, 0]

    return _assembly(start.joint_angles + np.array([bisect(j11, 0.5, 1.0), 0.0, 0.0]), sign)


@pytest.fixture(scope="module")
def direct_singular():
    """Sec. 4.2: turn the platform about a fixed position in working mode (+, +, -) until det K
    changes sign."""

    def det_k(phi):
        return np.linalg.det(
            jacobians(Planar3RRPConfiguration.from_pose(P, [0.05, -0.03, phi], (1, 1, -1)))[1]
        )

    return Planar3RRPConfiguration.from_pose(P, [0.05, -0.03, bisect(det_k, -0.6, 0.6)], (1, 1, -1))


@pytest.fixture(scope="module")
def combined_singular():
    """Sec. 4.3: link 1 perpendicular to its guide by construction (theta_1 = psi, phi = psi - 90 deg
    - beta_1), sliding the platform along guide 1 until det K changes sign."""
    psi = 1.0
    phi = psi - np.pi / 2 - P.guide_angles[0]
    elbow = P.base_points[0] + 0.9 * np.array([np.cos(psi), np.sin(psi)])
    guide = np.array([np.cos(psi - np.pi / 2), np.sin(psi - np.pi / 2)])
    rotation = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])

    def config(gamma):
        pose = [*(elbow - rotation @ P.platform_points[0] - gamma * guide), phi]
        theta = inverse_kinematics(P, pose, (1, 1, 1))
        return Planar3RRPConfiguration(P, pose, [psi, theta[1], theta[2]])

    return config(bisect(lambda g: np.linalg.det(jacobians(config(g))[1]), -0.8, -0.6))


def test_inverse_singularity_is_serial(inverse_singular):
    assert str(classify(inverse_singular).kind) == "inverse"
    report = classify_graph(joints(inverse_singular).graph())
    assert report.labels == ("serial",)
    assert [s.actuated_joint for s in report.serial] == ["limb1_R1"]
    # the limb locks one direction rather than leaving one uncontrolled: its actuation line t_1 (through
    # the elbow, normal to the guide) becomes a constraint wrench
    assert (report.lost_dof, report.global_order, report.uncontrolled_dof) == (1, 6, 0)
    elbow = np.append(inverse_singular.elbow_points[0], 0.0)
    normal = np.append(
        -inverse_singular.guide_directions[0, 1], [inverse_singular.guide_directions[0, 0], 0.0]
    )
    t1 = S.force(normal, elbow)
    limb_wrenches = report.serial[0].limb_wrenches.basis
    assert np.linalg.matrix_rank(np.vstack([limb_wrenches, t1]), tol=1e-9) == len(limb_wrenches) == 4
    assert report.closeness["serial"] < 1e-12


def test_direct_singularity_is_actuation(direct_singular):
    assert str(classify(direct_singular).kind) == "direct"
    report = classify_graph(joints(direct_singular).graph())
    assert report.labels == ("actuation",)
    assert (report.constraint_order, report.global_order, report.uncontrolled_dof) == (3, 5, 1)
    # Sec. 4.2: with the actuators locked the platform turns about D = C_18, the common point of t_k
    point, direction = S.axis(report.uncontrolled_twists[0])
    np.testing.assert_allclose(np.abs(direction), [0.0, 0.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(point[:2], kennedy_point(direct_singular), atol=1e-9)
    assert abs(S.pitch(report.uncontrolled_twists[0])) < 1e-9


def test_combined_singularity_is_both(combined_singular):
    assert str(classify(combined_singular).kind) == "combined"
    report = classify_graph(joints(combined_singular).graph())
    assert report.labels == ("actuation", "serial")
    assert [s.actuated_joint for s in report.serial] == ["limb1_R1"]


def test_trajectory_through_a_direct_singularity_vectorized(direct_singular):
    # a sweep of phi at fixed position in mode (+, +, -) with the root inserted: only the root is labelled
    root = direct_singular.pose[2]
    phis = np.sort(np.append(np.linspace(-0.6, 0.6, 41), root))
    poses = np.column_stack([np.full(42, 0.05), np.full(42, -0.03), phis])
    config = Planar3RRPConfiguration.from_pose(P, poses, (1, 1, -1))
    report = classify_table(joints(config))
    labels = report.labels.ravel().tolist()
    kinds = classify(config).kind
    at_root = int(np.flatnonzero(phis == root)[0])
    assert labels[at_root] == ("actuation",) and str(kinds[at_root]) == "direct"
    assert all(label == () for k, label in enumerate(labels) if k != at_root)
    assert all(str(kind) == "regular" for k, kind in enumerate(kinds) if k != at_root)
    # the actuation closeness is smallest at the root and grows away from it
    closeness = report.closeness["actuation"]
    assert int(np.argmin(closeness)) == at_root and closeness[at_root] < 1e-12


def test_regular_poses_in_every_working_mode(planar, rng):
    poses = planar.random_poses(rng, 30)
    config = Planar3RRPConfiguration.from_pose(P, poses[:, None, :], WORKING_MODES)
    assert np.all(classify(config).kind == "regular")
    report = classify_table(joints(config))
    assert report.labels.ravel().tolist() == [()] * 240
    for index in ((0, 0), (7, 3), (29, 7)):  # the vectorized verdicts are the single-pose ones
        assert classify_graph(joints(config).graph(index)).labels == ()


# -------------------------------------------------------------------------------------------------
# Report, command line, errors
# -------------------------------------------------------------------------------------------------


def test_cli_list_and_analyze_planar(capsys, planar):
    assert main(["list", "--json"]) == 0
    listed = {entry["name"]: entry for entry in json.loads(capsys.readouterr().out)}
    assert listed["planar_3rrp"]["family"] == "planar_3rrp" and listed["planar_3rrp"]["length_unit"] == "m"
    assert main(["analyze", "planar_3rrp", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    library = json.loads(json.dumps(analyze("planar_3rrp").to_dict()))
    assert printed["verdict"] == library["verdict"]
    assert (
        printed["superbracket"]["simplification"]["factored"]
        == library["superbracket"]["simplification"]["factored"]
    )
    labels = [condition["label"] for condition in printed["superbracket"]["conditions"]]
    assert labels == ["constraint", "actuation"]
    assert main(["analyze", "planar_3rrp", "--no-superbracket", "--pose", "0.05", "-0.03", "5"]) == 0
    assert "phi = 5 deg" in capsys.readouterr().out


def test_cli_planar_pose_needs_three_numbers(capsys):
    assert main(["analyze", "planar_3rrp", "--pose", "0", "0", "0", "0"]) == 2
    assert "--pose expects 3 finite numbers (X Y PHI)" in capsys.readouterr().err


def test_twist_graph_index_error():
    config = Planar3RRPConfiguration.from_pose(P, np.zeros((2, 3)))
    for index in ((), (2,), (0, 0), (True,)):
        with pytest.raises(
            ScrewkitValueError,
            match=r"Expected `index` to pick one configuration of the batch of shape \(2,\)",
        ):
            joints(config).graph(index)


def test_twist_graph_type_error():
    with pytest.raises(
        ScrewkitTypeError, match=r"Expected `config` to be a Planar3RRPConfiguration, got ndarray"
    ):
        joints(np.zeros(3))


def test_from_mapping_metadata_error():
    mapping = {
        "base_points": [[0, 0], [1, 0], [0, 1]],
        "link_lengths": [1, 1, 1],
        "platform_points": [[0, 0], [0, 0], [0, 0]],
        "guide_angles": [0, 1, 2],
    }
    assert Planar3RRPParameters.from_mapping(
        {**mapping, "name": "x", "length_unit": "m"}
    ).link_lengths.shape == (3,)
    with pytest.raises(CatalogError, match=r"p\.toml: field `length_unit` must be a non-empty string, got 3"):
        Planar3RRPParameters.from_mapping({**mapping, "length_unit": 3}, source="p.toml")
