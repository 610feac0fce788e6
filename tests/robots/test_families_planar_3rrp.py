"""Tests of the planar 3-RRP family (paper 003, Zarkandi): kinematics and joint table; and of the
paper's instant centres, Jacobians and singularities (``tests/paper_003.py``). Expected values come from hand derivations (stated next to each) or from independent
computations (finite differences, Kennedy constructions with cross products, ranks)."""

import itertools

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from screwkit.algebra.ranks import screw_rank
from screwkit.exceptions import (
    CatalogError,
    DegenerateGeometryError,
    ScrewkitTypeError,
    ScrewkitValueError,
    UnreachablePoseError,
)
from screwkit.robots.families.planar_3rrp.configuration import Planar3RRPConfiguration
from screwkit.robots.families.planar_3rrp.joints import JOINT_PAIRS, LINK_NAMES, joints
from screwkit.robots.families.planar_3rrp.kinematics import (
    WORKING_MODES,
    forward_kinematics,
    inverse_kinematics,
    reach_margin,
)
from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS, Planar3RRPParameters

from ..paper_003 import classify, complete_velocity, instant_center, instant_centers, jacobians, link_twists

P = EXAMPLE_PARAMETERS
SQRT3 = np.sqrt(3.0)
#: Home pose of the example: |Q_k - M_k| = 0.75 along the radius, guide tangent, so
#: J_kk = ±sqrt(0.9² - 0.75²) (module docstring of EXAMPLE_PARAMETERS).
G_HOME = np.sqrt(0.81 - 0.5625)
EXAMPLE_MAPPING = {
    "base_points": [[-SQRT3 / 2, -0.5], [SQRT3 / 2, -0.5], [0.0, 1.0]],
    "link_lengths": [0.9, 0.9, 0.9],
    "platform_points": [[-0.25 * SQRT3 / 2, -0.125], [0.25 * SQRT3 / 2, -0.125], [0.0, 0.25]],
    "guide_angles": [5 * np.pi / 3, np.pi / 3, np.pi],
}
#: Tolerance of identities that hold up to rounding.
EXACT = 1e-12
#: Tolerance of central finite differences with step 1e-6 (error ~ h² times third derivatives).
FD_STEP = 1e-6
FD_TOL = 1e-6


def E(v):
    """Rotation by +90° (Eq. 6)."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def wrap(angle):
    return np.angle(np.exp(1j * angle))


def random_reachable_poses(rng, count, margin=0.05):
    poses = np.column_stack(
        [
            rng.uniform(-0.2, 0.2, 4 * count),
            rng.uniform(-0.2, 0.2, 4 * count),
            rng.uniform(-0.5, 0.5, 4 * count),
        ]
    )
    keep = reach_margin(P, poses).min(axis=-1) > margin
    assert keep.sum() >= count
    return poses[keep][:count]


def projective_distance(p, q, length_scale):
    """|p × q| of unit-normalised points with lengths divided by ``length_scale`` (0 iff equal)."""
    scale = np.array([1 / length_scale, 1 / length_scale, 1.0])
    p, q = p * scale, q * scale
    p = p / np.linalg.norm(p, axis=-1, keepdims=True)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    return np.linalg.norm(np.cross(p, q), axis=-1)


def kennedy_lines(config):
    """Lines ``C_ij × C_j8`` through the elbows, perpendicular to the guides (paper's ``t_i``)."""
    elbows = np.concatenate([config.elbow_points, np.ones((*config.batch_shape, 3, 1))], -1)
    at_infinity = np.concatenate(
        [E(config.guide_directions), np.zeros((*config.batch_shape, 3, 1))], -1
    )
    return np.cross(elbows, at_infinity)


def bisect(function, lo, hi, iterations=80):
    """Scalar bisection on a sign change of ``function`` in [lo, hi]."""
    sign_lo = np.sign(function(lo))
    assert sign_lo != 0 and sign_lo != np.sign(function(hi))
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        if np.sign(function(mid)) == sign_lo:
            lo = mid
        else:
            hi = mid
    return lo


# --------------------------------------------------------------------------------------------------
# Parameters
# --------------------------------------------------------------------------------------------------


def test_from_mapping_matches_the_example():
    p = Planar3RRPParameters.from_mapping(EXAMPLE_MAPPING, source="example.toml")
    for name in EXAMPLE_MAPPING:
        np.testing.assert_allclose(getattr(p, name), getattr(P, name), atol=EXACT)
    assert p.length_scale == 0.9
    with pytest.raises(ValueError, match="read-only"):
        p.link_lengths[0] = 1.0


def _with(**changes):
    mapping = dict(EXAMPLE_MAPPING)
    mapping.update(changes)
    return mapping


MAPPING_ERRORS = [
    ([1, 2], CatalogError, r"demo\.toml: expected a mapping of the fields"),
    ({"link_lengths": [1, 1, 1]}, CatalogError, r"demo\.toml: missing field `base_points`"),
    (_with(colour="red"), CatalogError, r"demo\.toml: unknown field `colour`"),
    (
        _with(link_lengths=[1, "2", 1]),
        CatalogError,
        r"field `link_lengths` must be a list of 3 numbers, got str",
    ),
    (_with(link_lengths=[1, True, 1]), CatalogError, r"`link_lengths` must be .*got bool"),
    (
        _with(base_points=[[0, 0], [1, 0]]),
        CatalogError,
        r"`base_points` must be a list of 3 \[x, y\] pairs",
    ),
    (
        _with(link_lengths=[1, 0, 1]),
        ScrewkitValueError,
        r"demo\.toml: Expected `link_lengths` to be > 0",
    ),
    (
        _with(guide_angles=[0, np.pi, 2 * np.pi]),
        ScrewkitValueError,
        r"demo\.toml: Expected `guide_angles` not all parallel",
    ),
    (
        _with(link_lengths=[1, float("nan"), 1]),
        ScrewkitValueError,
        r"demo\.toml: Expected `link_lengths` to hold finite numbers",
    ),
]


@pytest.mark.parametrize(("mapping", "error", "match"), MAPPING_ERRORS)
def test_from_mapping_errors(mapping, error, match):
    with pytest.raises(error, match=match):
        Planar3RRPParameters.from_mapping(mapping, source="demo.toml")


def test_parameters_shape_error():
    with pytest.raises(
        ScrewkitValueError, match=r"`base_points` to have shape \(3, 2\), got \(2, 3, 2\)"
    ):
        Planar3RRPParameters(np.zeros((2, 3, 2)), [1, 1, 1], np.zeros((3, 2)), [0, 1, 2])


def test_parallel_guides_rejected_sec_4_2():
    """Sec. 4.2, second case: with parallel guides every pose would be a direct singularity."""
    with pytest.raises(ScrewkitValueError, match="translate freely"):
        Planar3RRPParameters(
            P.base_points, P.link_lengths, P.platform_points, [0.3, 0.3, 0.3 + np.pi]
        )


# --------------------------------------------------------------------------------------------------
# Position kinematics
# --------------------------------------------------------------------------------------------------


def test_inverse_kinematics_home_known_values():
    """Hand derivation: at the home pose A_k - M_k = 0.75 r̂_k + γ b_k with b_k = r̂_k rotated by
    -90°, so θ_k = α_k - σ_k atan(G / 0.75) with α = 30°, 150°, 270°."""
    alpha = np.radians([30.0, 150.0, 270.0])
    for mode in WORKING_MODES:
        theta = inverse_kinematics(P, [0.0, 0.0, 0.0], mode)
        expected = alpha - mode * np.arctan(G_HOME / 0.75)
        np.testing.assert_allclose(wrap(theta - expected), 0.0, atol=EXACT)


def test_inverse_kinematics_all_branches_broadcast(rng):
    poses = random_reachable_poses(rng, 5)
    theta = inverse_kinematics(P, poses[:, None, :], WORKING_MODES)
    assert theta.shape == (5, 8, 3)
    for k in range(8):
        np.testing.assert_allclose(
            theta[:, k], inverse_kinematics(P, poses, WORKING_MODES[k]), atol=0
        )
    # the two branches of a limb differ
    assert np.all(np.abs(wrap(theta[:, 0] - theta[:, 7])) > 1e-3)


def test_reach_margin_is_normalised_j_squared(rng):
    """l² - h² = J_kk² (Eq. 11a, hand derivation: J_kk = σ_k sqrt(l_k² - h_k²))."""
    poses = random_reachable_poses(rng, 20)
    for mode in WORKING_MODES:
        config = Planar3RRPConfiguration.from_pose(P, poses, mode)
        diagonal = np.diagonal(jacobians(config)[0], axis1=-2, axis2=-1)
        np.testing.assert_allclose((diagonal / 0.9) ** 2, reach_margin(P, poses), atol=EXACT)
        np.testing.assert_array_equal(np.sign(diagonal), np.broadcast_to(mode, diagonal.shape))


def test_ik_fk_round_trip(rng):
    poses = random_reachable_poses(rng, 30)
    for mode in WORKING_MODES:
        theta = inverse_kinematics(P, poses, mode)
        fk = forward_kinematics(P, theta)
        assert fk.valid.all()
        error = np.abs(fk.poses - poses[:, None, :])
        error[..., 2] = np.abs(wrap(error[..., 2]))
        assert error.max(axis=-1).min(axis=-1).max() < 1e-10
        # both assembly modes close (the constructor checks it) and are told apart by sign(det K)
        both = Planar3RRPConfiguration(P, fk.poses, theta[:, None, :])
        det_k = np.linalg.det(jacobians(both)[1])
        assert np.all(np.sign(det_k[:, 0]) != np.sign(det_k[:, 1]))
        # back through the inverse kinematics in each solution's own working mode
        signs = np.sign(np.diagonal(jacobians(both)[0], axis1=-2, axis2=-1))
        again = inverse_kinematics(P, fk.poses, signs)
        np.testing.assert_allclose(wrap(again - theta[:, None, :]), 0.0, atol=1e-10)


def test_forward_kinematics_no_solution_hand_derived():
    """All links pointing at the centre put the elbows on a circle of radius 0.1; then
    P cos φ + Q sin φ = -0.1 (3 sin 120°) cos φ while S = -0.25 (3 sin 120°): no root."""
    theta = np.radians([30.0, 150.0, 270.0])
    fk = forward_kinematics(P, [theta, theta + 0.0])
    assert not fk.valid.any()
    np.testing.assert_array_equal(fk.poses, 0.0)
    assert fk.to_dict()["valid"] == [[False, False], [False, False]]
    assert "0 valid of 4" in str(fk)


def test_forward_kinematics_self_motion_raises():
    """Concurrent guides and coincident elbows: the platform turns about the common point."""
    concurrent = Planar3RRPParameters(
        P.base_points, [1.0, 1.0, 1.0], np.zeros((3, 2)), P.guide_angles
    )
    theta = np.radians([30.0, 150.0, 270.0])  # every elbow at the origin
    with pytest.raises(DegenerateGeometryError, match="continuum of platform poses"):
        forward_kinematics(concurrent, theta)


def test_inverse_kinematics_unreachable_names_limb():
    with pytest.raises(UnreachablePoseError, match=r"Limb 1 cannot reach .*batch index \(1,\)"):
        inverse_kinematics(P, [[0.0, 0.0, 0.0], [5.0, 0.0, 0.0]])


def test_inverse_kinematics_bad_working_mode():
    with pytest.raises(ScrewkitValueError, match=r"`working_mode` entries to be \+1 or -1"):
        inverse_kinematics(P, [0.0, 0.0, 0.0], (1, 0, 1))


def test_rtol_errors():
    config = Planar3RRPConfiguration.from_pose(P, [0.0, 0.0, 0.0])
    with pytest.raises(ScrewkitValueError, match=r"`rtol` to be a number in \[0, 0\.1\], got 2"):
        classify(config, rtol=2)
    with pytest.raises(ScrewkitTypeError, match=r"`rtol` to be a number in \[0, 0\.1\], got 'x'"):
        classify(config, rtol="x")


# --------------------------------------------------------------------------------------------------
# Configurations
# --------------------------------------------------------------------------------------------------


def test_configuration_rejects_open_loop():
    theta = inverse_kinematics(P, [0.0, 0.0, 0.0])
    with pytest.raises(ScrewkitValueError, match="Expected the elbow of limb 2 on its guide line"):
        Planar3RRPConfiguration(P, [0.0, 0.0, 0.0], theta + np.array([0.0, 0.01, 0.0]))


def test_configuration_type_errors():
    with pytest.raises(
        ScrewkitTypeError, match="`parameters` to be Planar3RRPParameters, got dict"
    ):
        Planar3RRPConfiguration(EXAMPLE_MAPPING, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    with pytest.raises(ScrewkitTypeError, match="`config` to be a Planar3RRPConfiguration, got P"):
        jacobians(P)


def test_configuration_geometry_home():
    config = Planar3RRPConfiguration.from_pose(P, [0.0, 0.0, 0.0])
    # limb 1 (hand): M = u(210°), γ = +G along b = u(300°) from Q = 0.25 u(210°)
    m1 = np.array([-SQRT3 / 2, -0.5])
    b1 = np.array([0.5, -SQRT3 / 2])
    np.testing.assert_allclose(config.base_points[0], m1, atol=EXACT)
    np.testing.assert_allclose(config.guide_directions[0], b1, atol=EXACT)
    np.testing.assert_allclose(config.elbow_points[0], 0.25 * m1 + G_HOME * b1, atol=EXACT)
    np.testing.assert_allclose(config.slider_positions, G_HOME, atol=EXACT)


# --------------------------------------------------------------------------------------------------
# Jacobians, Eqs. (10)-(11)
# --------------------------------------------------------------------------------------------------


def test_jacobians_home_known_values():
    """Eq. (11) by hand at the home pose, working mode (+, +, +): J = G I and
    K_k = [b_k·(C - A_k), b_kᵀE] = [-G, sin β_k, -cos β_k] with β = 300°, 60°, 180°."""
    config = Planar3RRPConfiguration.from_pose(P, [0.0, 0.0, 0.0])
    for method in ("instant_centers", "velocity_loop"):
        J, K = jacobians(config, method=method)
        np.testing.assert_allclose(J, G_HOME * np.eye(3), atol=EXACT)
        expected = [[-G_HOME, -SQRT3 / 2, -0.5], [-G_HOME, SQRT3 / 2, -0.5], [-G_HOME, 0.0, 1.0]]
        np.testing.assert_allclose(K, expected, atol=EXACT)


def test_jacobian_methods_agree(rng):
    poses = random_reachable_poses(rng, 20)
    config = Planar3RRPConfiguration.from_pose(P, poses[:, None, :], WORKING_MODES)
    J1, K1 = jacobians(config, method="instant_centers")
    J2, K2 = jacobians(config, method="velocity_loop")
    assert J1.shape == K1.shape == (20, 8, 3, 3)
    np.testing.assert_allclose(J1, J2, atol=EXACT)
    np.testing.assert_allclose(K1, K2, atol=EXACT)


def test_jacobians_against_ik_finite_differences(rng):
    """-J⁻¹K is dθ/dt with t = (φ̇, ẋ, ẏ) (Eq. 10; Eq. 3 with the dot restored)."""
    poses = random_reachable_poses(rng, 10)
    pose_axis = {0: 2, 1: 0, 2: 1}  # twist component -> pose component
    for mode in WORKING_MODES:
        config = Planar3RRPConfiguration.from_pose(P, poses, mode)
        for method in ("instant_centers", "velocity_loop"):
            J, K = jacobians(config, method=method)
            gradient = -np.linalg.solve(J, K)
            for column, axis in pose_axis.items():
                step = FD_STEP * np.eye(3)[axis]
                plus = inverse_kinematics(P, poses + step, mode)
                minus = inverse_kinematics(P, poses - step, mode)
                fd = wrap(plus - minus) / (2 * FD_STEP)
                np.testing.assert_allclose(fd, gradient[..., column], atol=FD_TOL, rtol=FD_TOL)


def test_jacobians_against_fk_finite_differences(rng):
    """-K⁻¹J is dt/dθ: differentiate the forward kinematics on the pose's own assembly mode."""
    poses = random_reachable_poses(rng, 10)
    config = Planar3RRPConfiguration.from_pose(P, poses, (1, -1, 1))
    J, K = jacobians(config)
    expected = -np.linalg.solve(K, J)
    for joint in range(3):
        step = FD_STEP * np.eye(3)[joint]
        ends = []
        for sign in (1, -1):
            fk = forward_kinematics(P, config.joint_angles + sign * step)
            nearest = np.argmin(np.linalg.norm(fk.poses - poses[:, None, :], axis=-1), axis=-1)
            ends.append(fk.poses[np.arange(len(poses)), nearest])
        fd = (ends[0] - ends[1]) / (2 * FD_STEP)
        np.testing.assert_allclose(fd[:, [2, 0, 1]], expected[..., joint], atol=FD_TOL, rtol=FD_TOL)


def closure(theta, phi, centre):
    """Eq. (1) in our form, by hand: f_k = n_k·(A_k - C) - n⁰_k·P_k, n_k = E b_k."""
    elbows = P.base_points + 0.9 * np.stack([np.cos(theta), np.sin(theta)], -1)
    normals = E(np.stack([np.cos(phi + P.guide_angles), np.sin(phi + P.guide_angles)], -1))
    normals0 = E(np.stack([np.cos(P.guide_angles), np.sin(P.guide_angles)], -1))
    return np.sum(normals * (elbows - centre), -1) - np.sum(normals0 * P.platform_points, -1)


def test_jacobians_are_partial_derivatives_eq_3(rng):
    """Eq. (3): J = ∂f/∂θ, K = ∂f/∂X with X = (φ, x, y), by central differences of f."""
    for pose in random_reachable_poses(rng, 5):
        config = Planar3RRPConfiguration.from_pose(P, pose, (-1, 1, -1))
        theta = config.joint_angles
        assert np.abs(closure(theta, pose[2], pose[:2])).max() < EXACT
        J, K = jacobians(config)
        for m, step in enumerate(FD_STEP * np.eye(3)):
            fd = closure(theta + step, pose[2], pose[:2]) - closure(theta - step, pose[2], pose[:2])
            np.testing.assert_allclose(fd / (2 * FD_STEP), J[:, m], atol=FD_TOL)
            x_step = np.roll(step, -1)  # (φ, x, y) -> (x, y, φ) order of the pose
            plus = closure(theta, pose[2] + x_step[2], pose[:2] + x_step[:2])
            minus = closure(theta, pose[2] - x_step[2], pose[:2] - x_step[:2])
            np.testing.assert_allclose((plus - minus) / (2 * FD_STEP), K[:, m], atol=FD_TOL)


def test_jacobians_as_instant_centre_determinants(rng):
    """J_kk = det[C_1i; C_ij; C_j8] and det K = -det[L_1; L_2; L_3] (hand expansion, module doc)."""
    poses = random_reachable_poses(rng, 20)
    config = Planar3RRPConfiguration.from_pose(P, poses, (-1, 1, -1))
    J, K = jacobians(config)
    for k, pairs in enumerate(JOINT_PAIRS):
        centres = np.stack([instant_center(config, pair) for pair in pairs], axis=-2)
        np.testing.assert_allclose(np.linalg.det(centres), J[:, k, k], atol=EXACT)
    np.testing.assert_allclose(np.linalg.det(K), -np.linalg.det(kennedy_lines(config)), atol=EXACT)


def test_rows_of_k_never_vanish_sec_4_3(rng):
    """Sec. 4.3 asks that no row of K vanish; |b_kᵀE| = 1 makes that automatic."""
    config = Planar3RRPConfiguration.from_pose(P, random_reachable_poses(rng, 20))
    np.testing.assert_allclose(
        np.linalg.norm(jacobians(config)[1][..., 1:], axis=-1), 1.0, atol=EXACT
    )


def test_jacobians_unknown_method():
    config = Planar3RRPConfiguration.from_pose(P, [0.0, 0.0, 0.0])
    with pytest.raises(
        ScrewkitValueError, match="`method` to be 'instant_centers' or 'velocity_loop', got 'ik'"
    ):
        jacobians(config, method="ik")


# --------------------------------------------------------------------------------------------------
# Velocities and instant centres
# --------------------------------------------------------------------------------------------------


def test_complete_velocity_home_hand_values():
    """Turning the platform about C at ω = 1 at home: θ̇_k = -K_k1 / J_kk = G / G = 1."""
    config = Planar3RRPConfiguration.from_pose(P, [0.0, 0.0, 0.0])
    rates, twist = complete_velocity(config, twist=[1.0, 0.0, 0.0])
    np.testing.assert_allclose(rates, 1.0, atol=EXACT)
    rates, twist = complete_velocity(config, joint_rates=[1.0, 1.0, 1.0])
    np.testing.assert_allclose(twist, [1.0, 0.0, 0.0], atol=EXACT)
    complete_velocity(config, joint_rates=[1.0, 1.0, 1.0], twist=[1.0, 0.0, 0.0])


def test_joint_centres():
    config = Planar3RRPConfiguration.from_pose(P, [0.05, -0.03, 0.1], (1, -1, 1))
    for k, (actuated, passive, prismatic) in enumerate(JOINT_PAIRS):
        m, a, b = config.base_points[k], config.elbow_points[k], config.guide_directions[k]
        np.testing.assert_allclose(instant_center(config, actuated), [*m, 1.0], atol=EXACT)
        np.testing.assert_allclose(instant_center(config, passive), [*a, 1.0], atol=EXACT)
        np.testing.assert_allclose(
            instant_center(config, prismatic), [-b[1], b[0], 0.0], atol=EXACT
        )
        np.testing.assert_allclose(
            instant_center(config, prismatic[::-1]), -instant_center(config, prismatic), atol=0
        )
    assert LINK_NAMES[JOINT_PAIRS[2][2][1] - 1] == "platform"


def test_velocity_centres_of_joints_agree_with_joints(rng):
    """The centre computed from relative twists (Eq. 5) of two jointed links is the joint's."""
    poses = random_reachable_poses(rng, 10)
    config = Planar3RRPConfiguration.from_pose(P, poses, (1, 1, -1))
    rates, twist = complete_velocity(config, joint_rates=rng.normal(size=(10, 3)))
    twists = link_twists(config, rates, twist)
    for pairs in JOINT_PAIRS:
        for q, r in pairs:
            omega, v = (
                twists[:, r - 1, 0] - twists[:, q - 1, 0],
                twists[:, r - 1, 1:] - twists[:, q - 1, 1:],
            )
            from_motion = np.concatenate([E(v), omega[:, None]], axis=-1)
            assert (
                projective_distance(from_motion, instant_center(config, (q, r)), 0.9).max() < 1e-12
            )


def test_pure_rotation_about_c_home():
    config = Planar3RRPConfiguration.from_pose(P, [0.1, 0.05, 0.0], (1, 1, 1))
    centre = instant_center(config, (1, 8), twist=[2.0, 0.0, 0.0])
    np.testing.assert_allclose(centre / centre[2], [0.1, 0.05, 1.0], atol=EXACT)
    translation = instant_center(config, (1, 8), twist=[0.0, 1.0, 0.0])  # along x
    np.testing.assert_allclose(translation, [0.0, 1.0, 0.0], atol=EXACT)  # at infinity along y


def test_kennedy_three_centres_collinear(rng):
    """Aronhold-Kennedy (Sec. 2.1) for all 56 triples of links, random motions."""
    poses = random_reachable_poses(rng, 15)
    config = Planar3RRPConfiguration.from_pose(P, poses, (-1, 1, 1))
    centres = instant_centers(config, joint_rates=rng.normal(size=(15, 3)))
    assert centres.shape == (15, 8, 8, 3)
    scaled = centres / np.array([0.9, 0.9, 1.0])
    for q, r, s in itertools.combinations(range(8), 3):
        rows = np.stack([scaled[:, q, r], scaled[:, r, s], scaled[:, q, s]], axis=-2)
        rows = rows / np.linalg.norm(rows, axis=-1, keepdims=True)
        assert np.abs(np.linalg.det(rows)).max() < 1e-12, (q + 1, r + 1, s + 1)


def test_kennedy_construction_with_locked_actuators(rng):
    """Sec. 4.1: actuators 2, 3 locked, 1 driven. Kennedy: C_18 = L_2 ∩ L_3 (C_1j = C_ij for a
    locked limb), and C_28 = line(C_12, C_18) ∩ L_1."""
    poses = random_reachable_poses(rng, 10)
    config = Planar3RRPConfiguration.from_pose(P, poses, (1, -1, -1))
    centres = instant_centers(config, joint_rates=[1.0, 0.0, 0.0])
    lines = kennedy_lines(config)
    c18 = np.cross(lines[:, 1], lines[:, 2])
    assert projective_distance(centres[:, 0, 7], c18, 0.9).max() < 1e-10
    c28 = np.cross(np.cross(centres[:, 0, 1], c18), lines[:, 0])
    assert projective_distance(centres[:, 1, 7], c28, 0.9).max() < 1e-10


def test_links_at_rest_have_no_centre():
    config = Planar3RRPConfiguration.from_pose(P, [0.0, 0.0, 0.0])
    centres = instant_centers(config, joint_rates=[0.0, 0.0, 0.0])
    joint = {pair for pairs in JOINT_PAIRS for pair in pairs}
    for q, r in itertools.combinations(range(1, 9), 2):
        norm = np.linalg.norm(centres[q - 1, r - 1])
        assert (norm > 0) if (q, r) in joint else (norm == 0)


CENTRE_ERRORS = [
    ({"pair": (1, 9)}, r"`pair` to be two distinct link labels in 1\.\.8, got \(1, 9\)"),
    ({"pair": (1, 8)}, "C_18 of non-adjacent links depends on the motion"),
    (
        {"pair": (1, 8), "joint_rates": [1, 0, 0], "twist": [0, 0, 0]},
        r"satisfy J θ̇ \+ K t = 0 \(Eq\. 10\), but limb 1",
    ),
]


@pytest.mark.parametrize(("kwargs", "match"), CENTRE_ERRORS)
def test_instant_center_errors(kwargs, match):
    config = Planar3RRPConfiguration.from_pose(P, [0.0, 0.0, 0.0])
    with pytest.raises(ScrewkitValueError, match=match):
        instant_center(config, **kwargs)


def test_complete_velocity_needs_input():
    config = Planar3RRPConfiguration.from_pose(P, [0.0, 0.0, 0.0])
    with pytest.raises(ScrewkitValueError, match="Expected `joint_rates` or `twist`"):
        complete_velocity(config)


# --------------------------------------------------------------------------------------------------
# Singularities, Sec. 4: each constructed by bisection along a path, then checked by ranks
# --------------------------------------------------------------------------------------------------


def _fk_branch(theta, det_k_sign):
    """The assembly mode of ``theta`` whose det K has the given sign (they differ, see above)."""
    fk = forward_kinematics(P, theta)
    both = Planar3RRPConfiguration(P, fk.poses, theta)
    pick = int(np.argmax(np.sign(np.linalg.det(jacobians(both)[1])) == det_k_sign))
    assert fk.valid[pick]
    return Planar3RRPConfiguration(P, fk.poses[pick], theta)


@pytest.fixture(scope="module")
def inverse_singular():
    """Sec. 4.1, Fig. 2: lock actuators 2, 3, turn actuator 1 until J_11 changes sign."""
    start = Planar3RRPConfiguration.from_pose(P, [0.05, -0.03, 0.1])
    sign = np.sign(np.linalg.det(jacobians(start)[1]))

    def j11(delta):
        return jacobians(_fk_branch(start.joint_angles + np.array([delta, 0.0, 0.0]), sign))[0][
            0, 0
        ]

    grid = np.linspace(0.0, 2.0, 41)
    values = [j11(d) for d in grid]
    k = next(i for i in range(40) if np.sign(values[i]) != np.sign(values[i + 1]))
    root = bisect(j11, grid[k], grid[k + 1])
    return _fk_branch(start.joint_angles + np.array([root, 0.0, 0.0]), sign)


@pytest.fixture(scope="module")
def direct_singular():
    """Sec. 4.2: turn the platform at fixed position in working mode (+, +, -) until det K
    changes sign."""
    start, end = np.array([0.05, -0.03, -0.6]), np.array([0.05, -0.03, 0.6])

    def det_k(lam):
        pose = start + lam * (end - start)
        return np.linalg.det(jacobians(Planar3RRPConfiguration.from_pose(P, pose, (1, 1, -1)))[1])

    grid = np.linspace(0.0, 1.0, 41)
    values = [det_k(g) for g in grid]
    k = next(i for i in range(40) if np.sign(values[i]) != np.sign(values[i + 1]))
    root = bisect(det_k, grid[k], grid[k + 1])
    return Planar3RRPConfiguration.from_pose(P, start + root * (end - start), (1, 1, -1))


@pytest.fixture(scope="module")
def combined_singular():
    """Sec. 4.3: keep link 1 perpendicular to its guide (θ_1 = ψ = 1, φ = ψ - 90° - β_1) and slide
    the platform along guide 1 by γ until det K changes sign (limbs 2, 3 in mode +)."""
    psi = 1.0
    phi = psi - np.pi / 2 - P.guide_angles[0]
    elbow = P.base_points[0] + 0.9 * np.array([np.cos(psi), np.sin(psi)])
    guide = np.array([np.cos(psi - np.pi / 2), np.sin(psi - np.pi / 2)])
    rotation = np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])

    def config(gamma):
        pose = [*(elbow - rotation @ P.platform_points[0] - gamma * guide), phi]
        theta = inverse_kinematics(P, pose, (1, 1, 1))  # limb 1 on its boundary: θ_1 = ψ below
        return Planar3RRPConfiguration(P, pose, [psi, theta[1], theta[2]])

    def det_k(gamma):
        return np.linalg.det(jacobians(config(gamma))[1])

    grid = np.linspace(-0.8, -0.6, 41)  # limbs 2, 3 reach every pose of this stretch
    values = [det_k(g) for g in grid]
    k = next(i for i in range(40) if np.sign(values[i]) != np.sign(values[i + 1]))
    return config(bisect(det_k, grid[k], grid[k + 1]))


def test_inverse_singularity(inverse_singular):
    result = classify(inverse_singular, rtol=1e-9)
    assert str(result.kind) == "inverse"
    assert (int(result.rank_j), int(result.rank_k)) == (2, 3)
    assert result.singular_limbs.tolist() == [True, False, False]
    assert result.inverse_closeness < 1e-12 and result.direct_closeness > 1e-3
    # Eq. (12): the first link is perpendicular to the guide; C_12, C_23, C_38 collinear
    link = inverse_singular.elbow_points[0] - inverse_singular.base_points[0]
    assert abs(link @ inverse_singular.guide_directions[0]) < 1e-12
    # Sec. 4.1: actuator 1 alone does not move the platform, and C_28 coincides with C_12
    twist = complete_velocity(inverse_singular, joint_rates=[1.0, 0.0, 0.0])[1]
    assert np.linalg.norm(twist) < 1e-12
    # "the EE cannot move in the direction of the first link": precisely, whatever the actuators
    # do, the platform point at the elbow C_23 has no velocity along the first link
    twists = complete_velocity(
        inverse_singular, joint_rates=np.eye(3) + np.array([0.3, -0.7, 0.5])
    )[1]
    arm = inverse_singular.elbow_points[0] - inverse_singular.platform_point
    at_elbow = twists[:, 1:] + twists[:, :1] * E(arm)
    assert np.abs(at_elbow @ link).max() < 1e-12 < np.abs(at_elbow @ E(link)).min()
    c28 = instant_center(inverse_singular, (2, 8), joint_rates=[1.0, 0.0, 0.0])
    assert projective_distance(c28, instant_center(inverse_singular, (1, 2)), 0.9) < 1e-12
    # ... which is special: at the regular start C_28 is elsewhere
    start = Planar3RRPConfiguration.from_pose(P, [0.05, -0.03, 0.1])
    far = instant_center(start, (2, 8), joint_rates=[1.0, 0.0, 0.0])
    assert projective_distance(far, instant_center(start, (1, 2)), 0.9) > 1e-2
    with pytest.raises(
        DegenerateGeometryError, match=r"rate of actuator 1 .* limb 1 is at an inverse"
    ):
        complete_velocity(inverse_singular, twist=[1.0, 0.0, 0.0])


def test_direct_singularity(direct_singular):
    config = direct_singular
    result = classify(config, rtol=1e-9)
    assert str(result.kind) == "direct"
    assert (int(result.rank_j), int(result.rank_k)) == (3, 2)
    assert result.direct_closeness < 1e-12 and result.inverse_closeness > 1e-3
    K = jacobians(config)[1]
    # Sec. 4.2: the Kennedy lines L_k (paper's t_i) meet at D, and the null twist of K (actuators
    # locked) is a rotation about D = C_18
    lines = kennedy_lines(config)
    d_point = np.cross(lines[0], lines[1])
    assert (
        abs(np.dot(lines[2], d_point)) / (np.linalg.norm(lines[2]) * np.linalg.norm(d_point))
        < 1e-12
    )
    null_twist = np.linalg.svd(K)[2][-1]
    # a rotation, not a translation: a pure moment on the platform has power on it, so the locked
    # actuators cannot balance it (Sec. 4.2)
    assert abs(null_twist[0]) > 0.1
    complete_velocity(config, joint_rates=[0.0, 0.0, 0.0], twist=null_twist)
    c18 = instant_center(config, (1, 8), joint_rates=[0.0, 0.0, 0.0], twist=null_twist)
    assert projective_distance(c18, d_point, 0.9) < 1e-10
    # Eqs. (13), (18): the third row of K is α1 (row 1) + α2 (row 2), b_3 = α1 b_1 + α2 b_2
    b = config.guide_directions
    alpha = np.linalg.solve(b[:2].T, b[2])
    np.testing.assert_allclose(alpha @ K[:2], K[2], atol=1e-12)
    # Sec. 4.2: the two branches of the direct kinematics meet (double root, error ~ sqrt(eps))
    fk = forward_kinematics(P, config.joint_angles, rtol=1e-6)
    assert fk.valid.all()
    assert np.abs(fk.poses[0] - fk.poses[1]).max() < 1e-6
    with pytest.raises(DegenerateGeometryError, match="direct \\(type-2\\) singularity"):
        complete_velocity(config, joint_rates=[1.0, 0.0, 0.0])


def test_eq_17_sign_is_garbled(direct_singular):
    """Eq. (17) prints C - C_ij = d + t_i with d = CD; the vectors give C - C_ij = t_i - d, and
    Eq. (18) still holds because b_iᵀ(C - C_ij) = -b_iᵀ d for every i."""
    config = direct_singular
    lines = kennedy_lines(config)
    homogeneous = np.cross(lines[0], lines[1])
    d_point = homogeneous[:2] / homogeneous[2]
    c = config.platform_point
    d = d_point - c
    t = d_point - config.elbow_points
    printed = np.linalg.norm((c - config.elbow_points) - (d + t), axis=-1)
    np.testing.assert_allclose(printed, 2 * np.linalg.norm(d), rtol=1e-9)
    assert printed.min() > 0.1
    np.testing.assert_allclose(c - config.elbow_points, t - d, atol=1e-12)
    b = config.guide_directions
    np.testing.assert_allclose(np.sum(b * (c - config.elbow_points), -1), -(b @ d), atol=1e-12)


def test_combined_singularity(combined_singular):
    result = classify(combined_singular, rtol=1e-9)
    assert str(result.kind) == "combined"
    assert (int(result.rank_j), int(result.rank_k)) == (2, 2)
    assert result.singular_limbs.tolist() == [True, False, False]


def test_regular_poses_are_regular(rng):
    poses = random_reachable_poses(rng, 50)
    config = Planar3RRPConfiguration.from_pose(P, poses[:, None, :], WORKING_MODES)
    result = classify(config)
    assert result.kind.shape == (50, 8)
    assert np.all(result.kind == "regular")
    assert np.all(result.rank_j == 3) and np.all(result.rank_k == 3)
    assert "{'regular': 400}" in str(result)


def test_classification_report():
    result = classify(Planar3RRPConfiguration.from_pose(P, [0.0, 0.0, 0.0]))
    data = result.to_dict()
    assert data["kind"] == "regular" and data["rank_j"] == 3
    np.testing.assert_allclose(data["inverse_closeness"], G_HOME / 0.9, atol=EXACT)
    assert str(result).startswith("regular: rank J = 3, rank K = 3")


# --------------------------------------------------------------------------------------------------
# Invariance under rigid motions of the base frame and changes of the length unit
# --------------------------------------------------------------------------------------------------

POSES = np.array([[0.0, 0.0, 0.0], [0.05, -0.03, 0.1], [-0.1, 0.08, -0.3]])


@given(
    rho=st.floats(-np.pi, np.pi),
    shift=st.tuples(st.floats(-10, 10), st.floats(-10, 10)),
    log_scale=st.floats(-3, 3),
    mode=st.sampled_from([tuple(m) for m in WORKING_MODES]),
)

def test_rigid_motion_and_unit_invariance(rho, shift, log_scale, mode):
    scale = 10.0**log_scale
    rotation = np.array([[np.cos(rho), -np.sin(rho)], [np.sin(rho), np.cos(rho)]])
    shift = np.array(shift)
    moved = Planar3RRPParameters(
        scale * (P.base_points @ rotation.T + shift),
        scale * P.link_lengths,
        scale * P.platform_points,
        P.guide_angles,
    )
    poses = np.column_stack([scale * (POSES[:, :2] @ rotation.T + shift), POSES[:, 2] + rho])
    before = Planar3RRPConfiguration.from_pose(P, POSES, mode)
    after = Planar3RRPConfiguration.from_pose(moved, poses, mode)
    np.testing.assert_allclose(wrap(after.joint_angles - before.joint_angles - rho), 0.0, atol=1e-9)
    J, K = jacobians(before)
    J2, K2 = jacobians(after)
    np.testing.assert_allclose(J2, scale * J, rtol=1e-9, atol=1e-9 * scale)
    np.testing.assert_allclose(K2[..., 0], scale * K[..., 0], rtol=1e-9, atol=1e-9 * scale)
    np.testing.assert_allclose(K2[..., 1:], K[..., 1:] @ rotation.T, atol=1e-9)
    one, two = classify(before), classify(after)
    np.testing.assert_array_equal(one.kind, two.kind)
    np.testing.assert_allclose(two.inverse_closeness, one.inverse_closeness, atol=1e-9)
    np.testing.assert_allclose(two.direct_closeness, one.direct_closeness, atol=1e-9)
    # instant centres move with the frame: a motion and its image
    twist = np.array([0.7, 0.2, -0.4])
    moved_twist = np.concatenate([twist[:1], scale * rotation @ twist[1:]])
    frame = np.block(
        [[scale * rotation, scale * shift[:, None]], [np.zeros((1, 2)), np.ones((1, 1))]]
    )
    centres = instant_centers(before, twist=twist) @ frame.T
    moved_centres = instant_centers(after, twist=moved_twist)
    off_diagonal = ~np.eye(8, dtype=bool)
    distance = projective_distance(
        centres[:, off_diagonal], moved_centres[:, off_diagonal], scale * 0.9
    )
    assert distance.max() < 1e-8
    # both assembly modes move with the frame too
    fk = forward_kinematics(moved, after.joint_angles)
    fk_before = forward_kinematics(P, before.joint_angles)
    np.testing.assert_allclose(
        fk.poses[..., :2],
        scale * (fk_before.poses[..., :2] @ rotation.T + shift),
        atol=1e-8 * scale,
    )


# --------------------------------------------------------------------------------------------------
# The joint table
# --------------------------------------------------------------------------------------------------


def limb_screws(table, k):
    """The screws of limb ``k`` (0-based), base to platform (actuated R, passive R, P): (..., 3, 6)."""
    return np.stack([table.joint_screws(f"limb{k + 1}_{label}")[..., 0, :] for label in ("R1", "R2", "P")], -2)


def test_joints_layout():
    config = Planar3RRPConfiguration.from_pose(P, POSES)
    table = joints(config)
    limbs = [table.specs[3 * k : 3 * k + 3] for k in range(3)]
    assert [[j.type for j in limb] for limb in limbs] == [["R", "R", "P"]] * 3
    assert [[j.actuated for j in limb] for limb in limbs] == [[True, False, False]] * 3
    labels = tuple(tuple((LINK_NAMES.index(j.parent) + 1, LINK_NAMES.index(j.child) + 1) for j in limb)
                   for limb in limbs)
    assert labels == JOINT_PAIRS
    first = limb_screws(table, 0)  # R: (z; r × z), r × z = (r_y, -r_x, 0) = -E r; P: (0; b)
    np.testing.assert_allclose(first[..., 0, 3:5], -E(config.base_points[:, 0]), atol=0)
    np.testing.assert_allclose(first[..., 1, 3:5], -E(config.elbow_points[:, 0]), atol=0)
    np.testing.assert_allclose(first[..., 2, 3:5], config.guide_directions[:, 0], atol=0)
    np.testing.assert_allclose(first[..., :2, :3], np.broadcast_to([0.0, 0.0, 1.0], (3, 2, 3)), atol=0)
    np.testing.assert_allclose(first[..., 2, :3], 0.0, atol=0)
    assert first.shape == (3, 3, 6) and table.screws.shape == (3, 9, 6)
    # the anchor: a point of the plane z = 0, the mean of the six revolute centres
    centres = np.concatenate([config.base_points, config.elbow_points], axis=-2).mean(axis=-2)
    np.testing.assert_allclose(table.anchor, np.column_stack([centres, np.zeros(3)]), atol=1e-15)


def test_limb_joint_screws_span_the_platform_twist(rng):
    """Each limb is a serial chain: the platform twist, as a screw (0, 0, ω; v_O), is a combination
    of the limb's three joint screws (rank 3 with it, 3 without it); and the pitches are 0 for R."""
    poses = random_reachable_poses(rng, 5)
    config = Planar3RRPConfiguration.from_pose(P, poses, (1, -1, 1))
    rates, twist = complete_velocity(config, joint_rates=rng.normal(size=(5, 3)))
    platform = link_twists(config, rates, twist)[:, 7]
    platform_screw = np.column_stack(
        [np.zeros((5, 2)), platform[:, :1], platform[:, 1:], np.zeros(5)]
    )
    table = joints(config)
    for k in range(3):
        screws = limb_screws(table, k)
        np.testing.assert_allclose(
            np.sum(screws[:, :2, :3] * screws[:, :2, 3:], -1), 0.0, atol=EXACT
        )
        assert np.all(screw_rank(screws, rtol=1e-9) == 3)
        stacked = np.concatenate([screws, platform_screw[:, None, :]], axis=-2)
        assert np.all(screw_rank(stacked, rtol=1e-9) == 3)
