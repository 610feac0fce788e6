"""Tests of screwkit.robots.families.mcgill_smg: the McGill SMG of paper 001 (Angeles et al. 2006).

Known values come from Eqs. (1)-(2) as printed and from hand derivations written out below; the
singularity cases of Sec. 4.2 (Figs. 7 and 8) are rebuilt one by one and judged by ranks.
"""

from __future__ import annotations

import networkx as nx
import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from screwkit.algebra import screw as S
from screwkit.core.jacobian_matrices import classify_jacobians
from screwkit.exceptions import (
    CatalogError,
    DegenerateGeometryError,
    ScrewkitTypeError,
    ScrewkitValueError,
    UnreachablePoseError,
)
from screwkit.robots.families.mcgill_smg.configuration import McGillConfiguration, leg_pose
from screwkit.robots.families.mcgill_smg.joints import joints
from screwkit.robots.families.mcgill_smg.kinematics import forward_kinematics, inverse_kinematics
from screwkit.robots.families.mcgill_smg.parameters import DEFAULT_MODE, LEGS, WORKING_MODES, McGillParameters
from screwkit.robots.two_limb import checked_mode, joint_row

from .. import paper_001 as paper
from ..two_limb_papers import bisect_segment, pick_and_place_cycle

# R, l2 and l3 = √2 R: paper 001, Sec. 6. l0, l1, b4, b5 and the widths: our choice (not published).
PARAMS = McGillParameters(
    l0=600.0, l1=100.0, l2=600.0, l3=200.0 * np.sqrt(2.0), radius=200.0, b4=-50.0, b5=-50.0,
    proximal_width=80.0, distal_width=60.0,
)
MAPPING = {
    "l0": 600, "l1": 100, "l2": 600, "l3": 282.843, "radius": 200, "b4": -50, "b5": -50,
    "proximal_width": 80, "distal_width": 60,
}
HOME = np.array([0.0, 0.0, -600.0, 0.0])
K = np.array([0.0, 0.0, 1.0])
SINGULAR = 1e-12  # closeness of a constructed singular pose (σ_min/σ_max)
REGULAR = 1e-3  # closeness well clear of a singularity


def random_poses(rng: np.random.Generator, n: int) -> np.ndarray:
    """Poses reachable in all 16 working modes for PARAMS (checked by the IK itself)."""
    return np.column_stack([
        rng.uniform(-100, 100, n), rng.uniform(-100, 100, n), rng.uniform(-650, -550, n),
        rng.uniform(-np.pi, np.pi, n),
    ])


def wrap(angle: np.ndarray) -> np.ndarray:
    return (angle + np.pi) % (2 * np.pi) - np.pi


def pose_error(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Largest difference of position (mm) and angle (rad, modulo 2π)."""
    d = a - b
    return np.maximum(np.abs(d[..., :3]).max(axis=-1), np.abs(wrap(d[..., 3])))


def rank(matrix: np.ndarray) -> int:
    values = np.linalg.svd(matrix, compute_uv=False)
    return int(np.linalg.matrix_rank(matrix, tol=1e-9 * values[0]))


def closeness(matrix: np.ndarray) -> float:
    values = np.linalg.svd(matrix, compute_uv=False)
    return float(values[-1] / values[0])


def leg_vectors(config: McGillConfiguration, leg: int) -> dict[str, np.ndarray]:
    """ρ_J1, ρ_J2, ρ_J3 (with L = R), f_J, φ_J of Eqs. (8a), (17b)."""
    r = PARAMS.radius
    rho1 = (config.wrist[..., leg, :] - config.pan_point[..., leg, :]) / r
    rho2 = (config.wrist[..., leg, :] - config.shoulder[..., leg, :]) / r
    rho3 = (config.wrist[..., leg, :] - config.elbow[..., leg, :]) / r
    f = config.tilt_axis[..., leg, :]
    return {"rho1": rho1, "rho2": rho2, "rho3": rho3, "f": f, "phi": np.cross(f, rho3)}


def leg_mode(angles: np.ndarray, leg: int) -> tuple[int, int]:
    """(pan, elbow) signs of one leg's joint angles (module docstring); +1 on a tie."""
    t2, t3 = angles[1:3]
    kappa = (1 - 2 * leg) * PARAMS.l1 + PARAMS.l2 * np.cos(t2) + PARAMS.l3 * np.cos(t2 + t3)
    return (1 if kappa >= 0 else -1), (1 if np.sin(t3) >= 0 else -1)


def config_from_leg_one(angles: list[float], mode_two: tuple[int, int]) -> McGillConfiguration:
    """The pose set by leg I's four joint angles (Eq. 1), solved for both legs."""
    pose = leg_pose(PARAMS, "I", np.array(angles))
    return inverse_kinematics(PARAMS, pose, (*leg_mode(np.array(angles), 0), *mode_two))


# --------------------------------------------------------------------------------------------------
# Parameters
# --------------------------------------------------------------------------------------------------


def test_from_mapping_builds_floats():
    params = McGillParameters.from_mapping(MAPPING, source="mcgill.toml")
    assert params.l3 == 282.843 and isinstance(params.l0, float)


@pytest.mark.parametrize(
    ("mapping", "error", "match"),
    [
        ([("l0", 1)], CatalogError, r"mcgill.toml: expected a mapping of McGillParameters"),
        ({**MAPPING, "a4": 0}, CatalogError, r"mcgill.toml: unknown field\(s\) \['a4'\]"),
        ({k: v for k, v in MAPPING.items() if k != "l3"}, CatalogError,
         r"mcgill.toml: missing field\(s\) \['l3'\]"),
        ({**MAPPING, "l2": "600"}, CatalogError, r"field `l2` of McGillParameters to be a real"),
        ({**MAPPING, "b4": True}, CatalogError, r"field `b4` of McGillParameters to be a real"),
        ({**MAPPING, "l2": -600}, ScrewkitValueError, r"parameter `l2` of McGillParameters to be > 0"),
        ({**MAPPING, "l0": -1}, ScrewkitValueError, r"parameter `l0` of McGillParameters to be >= 0"),
        ({**MAPPING, "b5": float("inf")}, ScrewkitValueError, r"`b5` of McGillParameters to be fin"),
    ],
)
def test_from_mapping_errors(mapping, error, match):
    with pytest.raises(error, match=match):
        McGillParameters.from_mapping(mapping, source="mcgill.toml")


def test_constructor_refuses_non_numbers():
    with pytest.raises(ScrewkitTypeError, match=r"parameter `radius` of McGillParameters to be a real"):
        McGillParameters(600, 100, 600, 283, "200", 0, 0, 80, 60)


def test_scaled_refuses_non_positive_factor():
    with pytest.raises(ScrewkitValueError, match=r"Expected `factor` to be a number > 0, got 0"):
        PARAMS.scaled(0)


# --------------------------------------------------------------------------------------------------
# Eqs. (1)-(2) and the inverse kinematics
# --------------------------------------------------------------------------------------------------


def test_leg_pose_is_eqs_1_and_2_as_printed(rng):
    t = rng.uniform(-np.pi, np.pi, (20, 4))
    l0, l1, l2, l3, r = PARAMS.l0, PARAMS.l1, PARAMS.l2, PARAMS.l3, PARAMS.radius
    b = PARAMS.b4 + PARAMS.b5
    t1, t2, t3, t4 = t.T
    t23, phi = t2 + t3, t1 + t4
    reach_one = l1 + l2 * np.cos(t2) + l3 * np.cos(t23)
    eq1 = np.column_stack([
        -reach_one * np.sin(t1) - r * np.sin(phi),  # (1a)
        -l0 / 2 + reach_one * np.cos(t1) + r * np.cos(phi),  # (1b)
        l2 * np.sin(t2) + l3 * np.sin(t23) + b,  # (1c)
        phi,  # (1d)
    ])
    reach_two = l1 - l2 * np.cos(t2) - l3 * np.cos(t23)
    eq2 = np.column_stack([
        reach_two * np.sin(t1) + r * np.sin(phi),  # (2a)
        l0 / 2 - reach_two * np.cos(t1) - r * np.cos(phi),  # (2b)
        l2 * np.sin(t2) + l3 * np.sin(t23) + b,  # (2c)
        phi,  # (2d)
    ])
    np.testing.assert_allclose(leg_pose(PARAMS, "I", t), eq1, atol=1e-9)
    np.testing.assert_allclose(leg_pose(PARAMS, "II", t), eq2, atol=1e-9)


def test_home_pose_hand_values():
    # P = (0, 0, -600), φ = 0: O_I3 = P - R j - (b4 + b5) k = (0, -200, -500), O_II3 = (0, 200, -500);
    # O_I0 = (0, -300, 0): the pan angles are 0 and the legs are mirror images, which in Eq. (2)'s
    # convention means θ_II2 = π - θ_I2 and θ_II3 = -θ_I3 (default mode (1, 1, -1, -1)).
    config = inverse_kinematics(PARAMS, HOME)
    np.testing.assert_allclose(config.wrist, [[0, -200, -500], [0, 200, -500]], atol=1e-9)
    angles = config.joint_angles
    np.testing.assert_allclose(angles[:, [0, 3]], 0.0, atol=1e-12)
    assert wrap(angles[1, 1] - (np.pi - angles[0, 1])) == pytest.approx(0.0, abs=1e-12)
    assert angles[1, 2] == pytest.approx(-angles[0, 2], abs=1e-12)
    assert np.linalg.norm(config.elbow[0] - config.shoulder[0]) == pytest.approx(600.0)
    assert np.linalg.norm(config.wrist[0] - config.elbow[0]) == pytest.approx(PARAMS.l3)
    assert config.actuated.shape == (4,) and "mode=(1, 1, -1, -1)" in str(config)
    assert config.to_dict()["mode"] == [1, 1, -1, -1]


@pytest.mark.parametrize("mode", WORKING_MODES)
def test_inverse_kinematics_closes_both_legs(rng, mode):
    poses = random_poses(rng, 30)
    config = inverse_kinematics(PARAMS, poses, mode)
    for leg, name in enumerate(LEGS):
        assert pose_error(leg_pose(PARAMS, name, config.joint_angles[:, leg]), poses).max() < 1e-9
        signs = np.array([leg_mode(a, leg) for a in config.joint_angles[:, leg]])
        assert np.all(signs == mode[2 * leg : 2 * leg + 2])
    assert config.batch_shape == (30,) and config.wrist.shape == (30, 2, 3)


def test_inverse_kinematics_batches_over_leading_axes(rng):
    poses = random_poses(rng, 6).reshape(2, 3, 4)
    batched = inverse_kinematics(PARAMS, poses).joint_angles
    single = inverse_kinematics(PARAMS, poses[1, 2]).joint_angles
    np.testing.assert_allclose(batched[1, 2], single, atol=0)


@pytest.mark.parametrize(
    ("pose", "match"),
    [
        ([0.0, 900.0, -600.0, 0.0], r"Leg I cannot reach the pose: .* distance from O_I1 to O_I3"),
        ([0.0, -900.0, -600.0, 0.0], r"Leg II cannot reach the pose: .* expected within"),
        ([[0.0, 0.0, -600.0, 0.0], [0.0, 0.0, -1600.0, 0.0]], r"Leg I .* at batch index \(1,\)"),
    ],
)
def test_unreachable_poses_name_the_leg(pose, match):
    with pytest.raises(UnreachablePoseError, match=match):
        inverse_kinematics(PARAMS, pose)


@pytest.mark.parametrize("mode", [(1, 1, -1), (1, 1, 0, 1), "++--", 3])
def test_nonexistent_modes(mode):
    with pytest.raises(ScrewkitValueError, match=r"Expected `mode` to be a sequence of 4 signs"):
        inverse_kinematics(PARAMS, HOME, mode)


def test_bad_arguments():
    with pytest.raises(ScrewkitValueError, match=r"Expected `pose` to have shape \(\.\.\., 4\)"):
        inverse_kinematics(PARAMS, [0.0, 0.0, -600.0])
    with pytest.raises(ScrewkitValueError, match=r"Expected `leg` to be one of \('I', 'II'\)"):
        leg_pose(PARAMS, "III", [0, 0, 0, 0])
    with pytest.raises(ScrewkitValueError, match=r"Expected `pose` to hold finite numbers"):
        inverse_kinematics(PARAMS, [0.0, 0.0, np.nan, 0.0])


# --------------------------------------------------------------------------------------------------
# Forward kinematics
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("mode", WORKING_MODES)
def test_forward_kinematics_finds_the_pose_of_every_mode(rng, mode):
    poses = random_poses(rng, 25)
    config = inverse_kinematics(PARAMS, poses, mode)
    solutions = forward_kinematics(PARAMS, config.actuated)
    error = np.where(solutions.valid, pose_error(solutions.poses, poses[:, None, :]), np.inf)
    best = np.argmin(error, axis=-1)
    assert error[np.arange(25), best].max() < 1e-8
    picked = np.arange(25), best
    assert np.all(solutions.working_modes[picked] == mode)
    passive = config.joint_angles[:, :, 2:].reshape(25, 4)
    assert np.abs(wrap(solutions.passive[picked] - passive)).max() < 1e-9
    assert np.all((solutions.count >= 1) & (solutions.count <= 8))


def test_every_forward_solution_closes_the_loop(rng):
    actuated = inverse_kinematics(PARAMS, random_poses(rng, 20)).actuated
    solutions = forward_kinematics(PARAMS, actuated)
    rows, slots = np.nonzero(solutions.valid)
    for row, slot in zip(rows, slots, strict=True):
        mode = tuple(int(s) for s in solutions.working_modes[row, slot])
        again = inverse_kinematics(PARAMS, solutions.poses[row, slot], mode).actuated
        assert np.abs(wrap(again - actuated[row])).max() < 1e-9
    assert np.all(solutions.poses.mask[~solutions.valid]) and np.isfinite(solutions.poses.data).all()


def test_forward_kinematics_continuum_is_refused():
    # Hand construction: equal pan angles θ (parallel leg planes), elbows at equal height with
    # O_I2 - O_II2 = (0, -l0, 0) + Δκ e(θ) normal to the planes and of length 2R:
    # sin θ = 2R / l0, Δκ = 2 l1 + l2 (cos θ_I2 - cos θ_II2) = l0 cos θ, θ_II2 = π - θ_I2.
    # Then O_I3 and O_II3 run on congruent circles 2R apart: the bar translates freely.
    theta = np.arcsin(2 * PARAMS.radius / PARAMS.l0)
    tilt = -np.arccos((PARAMS.l0 * np.cos(theta) - 2 * PARAMS.l1) / (2 * PARAMS.l2))
    actuated = [theta, tilt, theta, np.pi - tilt]
    with pytest.raises(DegenerateGeometryError, match=r"admit a continuum of assemblies"):
        forward_kinematics(PARAMS, actuated)
    # Along that self-motion (O_II3 = O_I3 - (O_I2 - O_II2), the bar normal to the planes) Eq. (24)
    # holds: A is rank-deficient at every assembly.
    gap = np.array([0.0, -PARAMS.l0, 0.0]) + PARAMS.l0 * np.cos(theta) * np.array(
        [-np.sin(theta), np.cos(theta), 0.0]
    )
    bar = -gap / (2 * PARAMS.radius)
    phi = np.arctan2(-bar[0], bar[1])
    for distal in (-1.2, -0.5):
        leg_one = np.array([theta, tilt, distal - tilt, phi - theta])
        leg_two = np.array([theta, np.pi - tilt, distal - np.pi + tilt])
        pose = leg_pose(PARAMS, "I", leg_one)
        config = inverse_kinematics(PARAMS, pose, (*leg_mode(leg_one, 0), *leg_mode(leg_two, 1)))
        np.testing.assert_allclose(wrap(config.actuated - actuated), 0.0, atol=1e-9)
        assert rank(paper.jacobians(config).A) == 3


# --------------------------------------------------------------------------------------------------
# Jacobians, Eqs. (16)-(19)
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("mode", WORKING_MODES)
def test_jacobians_against_finite_differences(rng, mode):
    poses = random_poses(rng, 20)
    rates = rng.normal(size=(20, 4))
    step = 1e-6
    ahead = inverse_kinematics(PARAMS, poses + step * rates, mode).actuated
    behind = inverse_kinematics(PARAMS, poses - step * rates, mode).actuated
    theta_dot = wrap(ahead - behind) / (2 * step)
    jac = paper.jacobians(inverse_kinematics(PARAMS, poses, mode))
    twist = np.column_stack([rates[:, 3], rates[:, :3] / PARAMS.radius])  # t = (φ̇, ṗ/L)
    lhs = np.einsum("nij,nj->ni", jac.A, twist)
    rhs = np.einsum("nij,nj->ni", jac.B, theta_dot)
    assert np.abs(lhs - rhs).max() < 1e-7 * np.abs(lhs).max()


def test_jacobian_blocks_have_the_shapes_eq_19_needs(rng):
    # Eq. (17a) prints A_J ∈ R^{3×2} and B_J ∈ R^{2×4}; A_J t must equal φ_J × σ̇_J (Eq. 15) for
    # t ∈ R^4, so A_J is 3×4, and B_J γ̇_J ∈ R^3 with γ̇_J ∈ R^2, so B_J is 3×2.
    config = inverse_kinematics(PARAMS, random_poses(rng, 5))
    jac = paper.jacobians(config)
    assert jac.A.shape == (5, 6, 4) and jac.B.shape == (5, 6, 4)
    np.testing.assert_array_equal(jac.B[:, :3, 2:], 0.0)
    np.testing.assert_array_equal(jac.B[:, 3:, :2], 0.0)
    t = rng.normal(size=(5, 4))
    sigma_dot = t[:, 1:]
    gap = (config.wrist[:, 0] - config.wrist[:, 1]) / PARAMS.radius
    for leg, sign in ((0, 1.0), (1, -1.0)):
        v = leg_vectors(config, leg)
        sigma_leg = sigma_dot + 0.5 * t[:, :1] * sign * np.cross(K, gap)  # Eq. (12)
        expected = np.cross(v["phi"], sigma_leg)
        actual = np.einsum("nij,nj->ni", jac.A[:, 3 * leg : 3 * leg + 3], t)
        np.testing.assert_allclose(actual, expected, atol=1e-12)
        # Sec. 4.2: N(Φ_J) is spanned by φ_J (printed "Φ_J"); Φ_J has rank 2.
        cross_matrix = jac.A[:, 3 * leg : 3 * leg + 3, 1:]
        np.testing.assert_allclose(np.einsum("nij,nj->ni", cross_matrix, v["phi"]), 0.0,
                                   atol=1e-12)
        assert all(rank(m) == 2 for m in cross_matrix)


def test_v_and_delta_hand_identities(rng):
    # From Eq. (10): v_J = (ρ_J1 × k) × φ_J = -(κ_J/L) ρ_J3; from Eq. (11): Δ_J = -(l2 l3/L²) sin θ_J3.
    config = inverse_kinematics(PARAMS, random_poses(rng, 10), (1, -1, -1, 1))
    jac = paper.jacobians(config)
    factors = paper.singularity_factors(config)
    r = PARAMS.radius
    for leg in (0, 1):
        v = leg_vectors(config, leg)
        block = jac.B[:, 3 * leg : 3 * leg + 3, 2 * leg : 2 * leg + 2]
        kappa = np.einsum("ni,ni->n", v["rho1"], np.cross(K, v["f"])) * r
        np.testing.assert_allclose(block[..., 0], -(kappa / r)[:, None] * v["rho3"], atol=1e-12)
        delta = -PARAMS.l2 * PARAMS.l3 / r**2 * np.sin(config.joint_angles[:, leg, 2])
        np.testing.assert_allclose(block[..., 1], delta[:, None] * v["f"], atol=1e-12)
        np.testing.assert_allclose(factors.delta[:, leg], delta, atol=1e-12)
        np.testing.assert_allclose(factors.reach[:, leg], kappa / r, atol=1e-12)


def test_length_scale(rng):
    config = inverse_kinematics(PARAMS, random_poses(rng, 5))
    default, other = paper.classify(config), paper.classify(config, length_scale=650.0)
    # B's entries all scale as 1/L², A's first column as 1/L² and the rest as 1/L.
    np.testing.assert_allclose(other.closeness["inverse"], default.closeness["inverse"], rtol=1e-12)
    assert np.abs(other.closeness["direct"] - default.closeness["direct"]).max() > 1e-3
    jac = paper.jacobians(config, length_scale=400.0)
    np.testing.assert_allclose(jac.B, paper.jacobians(config).B / 4.0, atol=1e-15)
    with pytest.raises(ScrewkitValueError, match=r"Expected `length_scale` to be a positive"):
        paper.jacobians(config, length_scale=-1.0)


# --------------------------------------------------------------------------------------------------
# Serial singularities, Eqs. (20)-(21) and Fig. 7
# --------------------------------------------------------------------------------------------------


def test_fig_7a_aligned_points_are_not_singular():
    # Rotate the distal link of leg I until O_I0, O_I2, O_I3 are aligned (ρ_I3 ∥ ρ_I1, Eq. 21a).
    def alignment(angles: np.ndarray) -> np.ndarray:
        config = config_from_leg_one(list(angles), (-1, -1))
        v = leg_vectors(config, 0)
        return np.einsum("i,i->", v["f"], np.cross(v["rho3"], v["rho1"]))

    angles = bisect_segment(alignment, [0.0, -1.3, 0.05, 0.0], [0.0, -1.3, 0.4, 0.0])
    config = config_from_leg_one(list(angles), (-1, -1))
    v = leg_vectors(config, 0)
    aligned = np.linalg.norm(np.cross(v["rho3"], v["rho1"])) / np.linalg.norm(v["rho1"])
    assert aligned < 1e-10
    jac = paper.jacobians(config)
    assert rank(jac.B) == 4 and closeness(jac.B) > REGULAR  # the paper's Fig. 7(a) is regular
    assert paper.classify(config).types.tolist() == "regular"


def test_fig_7b_vertical_distal_link_is_not_singular():
    config = config_from_leg_one([0.2, -0.6, -np.pi / 2 + 0.6, 0.0], (-1, -1))  # θ_I23 = -π/2
    v = leg_vectors(config, 0)
    assert np.linalg.norm(np.cross(v["rho3"], K)) < 1e-12  # ρ_I3 ∥ k (Eq. 21b)
    jac = paper.jacobians(config)
    assert rank(jac.B) == 4 and closeness(jac.B) > REGULAR


def test_eqs_21a_and_21b_together_are_singular():
    # Distal link vertical and κ_I = l1 + l2 cos θ_I2 = 0: O_I3 on the pan axis; (21a) and (21b).
    tilt = -np.arccos(-PARAMS.l1 / PARAMS.l2)
    config = config_from_leg_one([0.0, tilt, -np.pi / 2 - tilt, 0.0], (-1, -1))
    v = leg_vectors(config, 0)
    assert abs(np.dot(v["f"], np.cross(v["rho3"], v["rho1"]))) < 1e-12
    assert abs(np.dot(v["f"], np.cross(v["rho3"], K))) < 1e-12
    jac = paper.jacobians(config)
    assert rank(jac.B) == 3 and closeness(jac.B) < SINGULAR
    assert np.linalg.norm(jac.B[:3, 0]) < 1e-12  # v_I = 0


def test_wrist_on_the_pan_axis_is_singular_at_any_inclination():
    # κ_I = l1 + l2 cos θ_I2 + l3 cos θ_I23 = 0 with the distal link 58° from the vertical:
    # B loses rank although (21b) fails; the paper's "(20a) iff (21a) and (21b)" is wrong.
    tilt = -2.0
    distal = -np.arccos(-(PARAMS.l1 + PARAMS.l2 * np.cos(tilt)) / PARAMS.l3)
    config = config_from_leg_one([0.0, tilt, distal - tilt, 0.4], (-1, -1))
    v = leg_vectors(config, 0)
    assert abs(np.dot(v["f"], np.cross(v["rho3"], K))) > 0.5 * np.linalg.norm(v["rho3"])
    factors = paper.singularity_factors(config)
    assert abs(factors.reach[0]) < 1e-12
    jac = paper.jacobians(config)
    assert rank(jac.B) == 3 and closeness(jac.B) < SINGULAR
    assert paper.classify(config).types.tolist() == "inverse"


@pytest.mark.parametrize(
    ("distal", "described"), [(0.0, "Fig. 7(c): fully extended"), (np.pi, "folded: not in paper")]
)
def test_extended_or_folded_leg_is_singular(distal, described):
    config = config_from_leg_one([0.3, -1.0, distal, 0.2], (-1, -1))
    factors = paper.singularity_factors(config)
    assert abs(factors.delta[0]) < 1e-12, described  # Δ_I = 0 (Eq. 20b)
    jac = paper.jacobians(config)
    assert rank(jac.B) == 3 and closeness(jac.B) < SINGULAR
    assert rank(jac.A) == 4


# --------------------------------------------------------------------------------------------------
# Parallel singularities, Eqs. (22)-(24) and Fig. 8
# --------------------------------------------------------------------------------------------------


def distal_direction(
    pose: np.ndarray, component: str, mode: tuple[int, ...] = DEFAULT_MODE
) -> np.ndarray:
    """Horizontal (along e(θ_I1)) or vertical component of leg I's unit distal direction."""
    config = inverse_kinematics(PARAMS, pose, mode)
    rho3 = (config.wrist[..., 0, :] - config.elbow[..., 0, :]) / PARAMS.l3
    along = np.cross(K, config.tilt_axis[..., 0, :]) if component == "horizontal" else K
    return np.asarray(np.sum(rho3 * along, axis=-1))


def parallel_check(config: McGillConfiguration) -> tuple[float, float]:
    """(sine of the angle between φ_I and φ_II, closeness of A)."""
    phi_one, phi_two = leg_vectors(config, 0)["phi"], leg_vectors(config, 1)["phi"]
    sine = np.linalg.norm(np.cross(phi_one, phi_two)) / np.linalg.norm(phi_one)
    return float(sine / np.linalg.norm(phi_two)), closeness(paper.jacobians(config).A)


@pytest.mark.parametrize("x", [0.0, 150.0])
def test_fig_8a_two_vertical_distal_links(x):
    # φ = π and y = 0 make the legs mirror images (mode (1, -1, -1, 1)); moving down, both distal
    # links become vertical together. x = 0: parallel leg planes (Fig. 8a, Eq. 24); x = 150: the planes
    # are not parallel and φ_I ∦ φ_II, yet A is singular: Eq. (22) is not necessary.
    mode = (1, -1, -1, 1)
    pose = bisect_segment(
        lambda p: distal_direction(p, "horizontal", mode), [x, 0.0, -870.0, np.pi],
        [x, 0.0, -760.0, np.pi],
    )
    config = inverse_kinematics(PARAMS, pose, mode)
    for leg in (0, 1):
        assert np.linalg.norm(np.cross(leg_vectors(config, leg)["rho3"], K)) < 1e-9
    sine, a_closeness = parallel_check(config)
    planes = np.linalg.norm(np.cross(config.tilt_axis[0], config.tilt_axis[1]))
    assert a_closeness < SINGULAR and rank(paper.jacobians(config).A) == 3
    if x == 0.0:
        assert planes < 1e-12 and sine < 1e-9
    else:
        assert planes > 0.1 and sine > 0.1


@pytest.mark.parametrize("x", [0.0, 150.0])
def test_fig_8b_two_horizontal_distal_links(x):
    # Both distal links horizontal: φ_J ∥ k whatever the leg planes, so Eq. (22) holds and A is
    # singular; Eq. (24)'s proviso f_I = -f_II is not needed.
    pose = bisect_segment(
        lambda p: distal_direction(p, "vertical"), [x, 0.0, -730.0, np.pi], [x, 0.0, -630.0, np.pi]
    )
    config = inverse_kinematics(PARAMS, pose)
    for leg in (0, 1):
        assert abs(leg_vectors(config, leg)["rho3"][2]) < 1e-9
    sine, a_closeness = parallel_check(config)
    assert a_closeness < SINGULAR and sine < 1e-9
    assert paper.classify(config).types.tolist() == "direct"


@pytest.mark.parametrize(
    ("mode", "z", "ends"),
    [((1, 1, -1, 1), -700.0, (225.0, 245.0)), ((1, 1, 1, -1), -500.0, (-175.0, -155.0))],
)
def test_eq_24_holds_at_any_common_inclination(mode, z, ends):
    # Parallel leg planes (x = 0, φ = π) and y swept until ρ_I3 = ±ρ_II3 at a slant (33° and 45°
    # here; the second case with opposite directions): singular, although the distal links are
    # neither vertical nor horizontal as the text after Eq. (24) says.
    def parallelism(p: np.ndarray) -> np.ndarray:
        config = inverse_kinematics(PARAMS, p, mode)
        rho3 = config.wrist - config.elbow
        return np.cross(rho3[..., 0, :], rho3[..., 1, :])[..., 0]

    pose = bisect_segment(parallelism, [0.0, ends[0], z, np.pi], [0.0, ends[1], z, np.pi])
    config = inverse_kinematics(PARAMS, pose, mode)
    direction = leg_vectors(config, 0)["rho3"] / np.linalg.norm(leg_vectors(config, 0)["rho3"])
    assert 0.5 < abs(direction[2]) < 0.75
    sine, a_closeness = parallel_check(config)
    assert sine < 1e-9 and a_closeness < SINGULAR


def test_eq_22_is_sufficient_but_not_necessary():
    pose = paper.locate_direct_singularity(PARAMS, [30.0, -20.0, -600.0, 0.2],
                                         [30.0, -20.0, -600.0, 1.2])
    config = inverse_kinematics(PARAMS, pose)
    sine, a_closeness = parallel_check(config)
    assert a_closeness < SINGULAR and rank(paper.jacobians(config).A) == 3
    assert sine > 0.1  # φ_I ∦ φ_II
    assert abs(paper.singularity_factors(config).parallel) < 1e-12


def test_parallel_factor_vanishes_exactly_where_a_loses_rank(rng):
    config = inverse_kinematics(PARAMS, random_poses(rng, 40), (1, -1, -1, 1))
    factor = paper.singularity_factors(config).parallel
    a_closeness = paper.classify(config).closeness["direct"]
    assert np.all((np.abs(factor) > 1e-4) == (a_closeness > 1e-4))
    # The two measures vanish to the same (first) order along a path through a singularity.
    start, end = np.array([30.0, -20.0, -600.0, 0.2]), np.array([30.0, -20.0, -600.0, 1.2])
    pose = paper.locate_direct_singularity(PARAMS, start, end)
    near = pose + np.outer([1e-4, 2e-4], end - start)
    near_config = inverse_kinematics(PARAMS, near)
    ratio = paper.singularity_factors(near_config).parallel / paper.classify(near_config).closeness["direct"]
    assert ratio[1] / ratio[0] == pytest.approx(1.0, rel=1e-3)


def test_combined_singularity():
    # Leg I extended (B singular) and the bar turned about O_I3 until A is singular.
    def parallel(angles: np.ndarray) -> np.ndarray:
        return paper.singularity_factors(config_from_leg_one(list(angles), (-1, -1))).parallel

    angles = bisect_segment(parallel, [0.0, -1.0, 0.0, -1.5], [0.0, -1.0, 0.0, -1.0])
    config = config_from_leg_one(list(angles), (-1, -1))
    label = paper.classify(config)
    assert label.types.tolist() == "combined"
    assert label.closeness["inverse"] < SINGULAR and label.closeness["direct"] < SINGULAR


# --------------------------------------------------------------------------------------------------
# Invariants
# --------------------------------------------------------------------------------------------------


@given(scale=st.floats(1e-3, 1e3), index=st.integers(0, 15))
def test_change_of_length_unit(scale, index):
    poses = random_poses(np.random.default_rng(index), 4)
    mode = WORKING_MODES[index]
    config = inverse_kinematics(PARAMS, poses, mode)
    scaled_poses = poses * np.array([scale, scale, scale, 1.0])
    scaled = inverse_kinematics(PARAMS.scaled(scale), scaled_poses, mode)
    np.testing.assert_allclose(wrap(scaled.joint_angles - config.joint_angles), 0.0, atol=1e-9)
    np.testing.assert_allclose(paper.jacobians(scaled).A, paper.jacobians(config).A, atol=1e-9)
    one, two = paper.classify(config), paper.classify(scaled)
    np.testing.assert_allclose(two.closeness["direct"], one.closeness["direct"], rtol=1e-8)
    np.testing.assert_allclose(two.closeness["inverse"], one.closeness["inverse"], rtol=1e-8)


def rotation_from(quaternion: list[float]) -> np.ndarray:
    w, x, y, z = np.array(quaternion) / np.linalg.norm(quaternion)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


@given(
    quaternion=st.lists(st.floats(-1, 1), min_size=4, max_size=4).filter(
        lambda q: np.linalg.norm(q) > 0.1
    ),
    shift=st.lists(st.floats(-1e3, 1e3), min_size=3, max_size=3),
    index=st.integers(0, 15),
)
def test_rigid_motion_of_the_base_frame(quaternion, shift, index):
    config = inverse_kinematics(PARAMS, random_poses(np.random.default_rng(index), 3),
                                    WORKING_MODES[index])
    rotation = rotation_from(quaternion)
    moved = {
        name: getattr(config, name) @ rotation.T + (0.0 if name in ("pan_axis", "tilt_axis") else
                                                     np.array(shift))
        for name in ("pan_point", "shoulder", "elbow", "wrist", "wrist_joint", "pan_axis",
                     "tilt_axis", "platform_point")
    }
    other = McGillConfiguration(config.params, config.mode, config.pose, config.joint_angles,
                                    **moved)
    for a, b in zip((paper.jacobians(config).A, paper.jacobians(config).B),
                    (paper.jacobians(other).A, paper.jacobians(other).B), strict=True):
        np.testing.assert_allclose(np.linalg.svd(b, compute_uv=False),
                                   np.linalg.svd(a, compute_uv=False), atol=1e-9)
    f_one, f_two = paper.singularity_factors(config), paper.singularity_factors(other)
    np.testing.assert_allclose(f_two.parallel, f_one.parallel, atol=1e-9)
    np.testing.assert_allclose(f_two.reach, f_one.reach, atol=1e-9)


# --------------------------------------------------------------------------------------------------
# The physical joints
# --------------------------------------------------------------------------------------------------


def test_joint_graph_has_the_expected_loops():
    specs = joints(inverse_kinematics(PARAMS, HOME)).specs
    graph = nx.MultiGraph()
    for joint in specs:
        graph.add_edge(joint.parent, joint.child, key=joint.name)
    assert len({j.name for j in specs}) == 20 and graph.number_of_nodes() == 16
    # E - V + 1 = 5 independent loops: four parallelograms and the loop through both legs.
    assert graph.number_of_edges() - graph.number_of_nodes() + 1 == 5
    assert [j.name for j in specs if j.actuated] == ["I.pan", "I.proximal.a", "II.pan",
                                                      "II.proximal.a"]


def test_parallelogram_corners(rng):
    # each hinge's point nearest the origin: the corners differ by vectors normal to the hinges f_J
    table = joints(inverse_kinematics(PARAMS, random_poses(rng, 3)))
    for leg in LEGS:
        for part, length, width in (("proximal", PARAMS.l2, PARAMS.proximal_width),
                                    ("distal", PARAMS.l3, PARAMS.distal_width)):
            a, b, c, d = (S.axis(table.joint_screws(f"{leg}.{part}.{t}")[:, 0])[0] for t in "abcd")
            np.testing.assert_allclose(c - a, d - b, atol=1e-9)
            np.testing.assert_allclose(np.linalg.norm(c - a, axis=-1), length)
            np.testing.assert_allclose(np.linalg.norm(b - a, axis=-1), width)


def test_joint_screws_reproduce_the_platform_twist(rng):
    # Twist of the plate (ω; v_O) by finite differences of the pose, against Σ rate_j $_j along
    # each leg, through side a and through side b of both parallelograms.
    pose, rates, step = random_poses(rng, 1)[0], rng.normal(size=4), 1e-6
    mode = (1, -1, -1, 1)
    config = inverse_kinematics(PARAMS, pose, mode)
    angles_rate = wrap(
        inverse_kinematics(PARAMS, pose + step * rates, mode).joint_angles
        - inverse_kinematics(PARAMS, pose - step * rates, mode).joint_angles
    ) / (2 * step)
    omega = rates[3] * K
    twist = np.concatenate([omega, rates[:3] - np.cross(omega, pose[:3])])
    table = joints(config)
    for leg, name in enumerate(LEGS):
        t1, t2, t3, t4 = angles_rate[leg]
        for side in (("a", "c"), ("b", "d")):
            chain = [(f"{name}.pan", t1), (f"{name}.proximal.{side[0]}", t2),
                     (f"{name}.proximal.{side[1]}", -t2), (f"{name}.distal.{side[0]}", t2 + t3),
                     (f"{name}.distal.{side[1]}", -(t2 + t3)), (f"{name}.wrist", t4)]
            total = sum(rate * table.joint_screws(joint)[0] for joint, rate in chain)
            np.testing.assert_allclose(total, twist, atol=1e-6)


def test_joint_row_errors():
    with pytest.raises(ScrewkitValueError, match=r"Expected `kind` of joint 'x' to be one of"):
        joint_row("a", "b", "x", "C", [0, 0, 0], [0, 0, 1])
    with pytest.raises(ScrewkitValueError, match=r"Expected `pitch` of R joint 'x' to be 0, got 1"):
        joint_row("a", "b", "x", "R", [0, 0, 0], [0, 0, 1], pitch=1.0)
    with pytest.raises(ScrewkitValueError, match=r"Expected `point` to have shape"):
        joint_row("a", "b", "x", "R", [0, 0], [0, 0, 1])
    prismatic = joint_row("a", "b", "x", "P", [1, 2, 3], [0, 1, 0])
    np.testing.assert_array_equal(prismatic[4], [[0, 0, 0, 0, 1, 0]])


# --------------------------------------------------------------------------------------------------
# Classification helpers, root search, test cycle
# --------------------------------------------------------------------------------------------------


def test_classification_to_dict_and_errors():
    result = classify_jacobians(np.eye(4), np.diag([1.0, 0.0, 1.0, 1.0]), rtol=1e-9)
    assert result.to_dict()["type"] == "inverse" and "inverse" in str(result)
    with pytest.raises(ScrewkitValueError, match=r"Expected `rtol` to be a number in \[0, 0\.1\]"):
        paper.classify(inverse_kinematics(PARAMS, HOME), rtol=1.5)
    with pytest.raises(ScrewkitValueError, match=r"signs \(\+1 or -1\), got 5"):
        checked_mode(5, "mode", 2)


def test_bisect_segment_requires_a_sign_change():
    with pytest.raises(ScrewkitValueError, match=r"Expected `function` to change sign"):
        bisect_segment(lambda p: p[..., 0] + 1.0, [0.0], [1.0])
    assert bisect_segment(lambda p: p[..., 0], [0.0], [1.0]).tolist() == [0.0]


def test_pick_and_place_cycle_waypoints():
    # Paper 001, Sec. 6: up 25, across 300 with a 180° turn, down 25, and back.
    path = pick_and_place_cycle([10.0, 20.0, -500.0, 0.5], np.pi / 2, samples_per_segment=2)
    assert path.shape == (13, 4)
    np.testing.assert_allclose(path[[0, 2, 4, 6, 8, 10, 12]], [
        [10, 20, -500, 0.5], [10, 20, -475, 0.5], [10, 320, -475, 0.5 - np.pi],
        [10, 320, -500, 0.5 - np.pi], [10, 320, -475, 0.5 - np.pi], [10, 20, -475, 0.5],
        [10, 20, -500, 0.5],
    ], atol=1e-12)
    np.testing.assert_allclose(path[3], [10, 170, -475, 0.5 - np.pi / 2], atol=1e-12)
    with pytest.raises(ScrewkitValueError, match=r"Expected `samples_per_segment` to be an integer"):
        pick_and_place_cycle([0, 0, 0, 0], samples_per_segment=0)
    with pytest.raises(ScrewkitValueError, match=r"Expected `start` to have shape \(4,\)"):
        pick_and_place_cycle([[0, 0, 0, 0]])


def test_test_cycle_with_our_dimensions():
    # Our dimensions (l0 = 600, l1 = 100, b4 + b5 = -100): the cycle along y through the middle,
    # in working mode (1, 1, -1, 1), stays reachable and clear of every singularity. This depends
    # on those unpublished dimensions; in the mirror-symmetric modes the 180° turn comes close to,
    # or crosses, a parallel singularity.
    path = pick_and_place_cycle([0.0, -150.0, -500.0, 0.0], np.pi / 2, samples_per_segment=40)
    result = paper.classify(inverse_kinematics(PARAMS, path, (1, 1, -1, 1)))
    assert result.closeness["direct"].min() > 0.1 and result.closeness["inverse"].min() > 0.1
    symmetric = paper.classify(inverse_kinematics(PARAMS, path, DEFAULT_MODE))
    assert symmetric.closeness["direct"].min() < 0.05


# --------------------------------------------------------------------------------------------------
# What depends on the dimensions we chose (l0, l1, b4, b5, widths)
# --------------------------------------------------------------------------------------------------


def with_changes(**changes: float) -> McGillParameters:
    return McGillParameters(**{**{name: getattr(PARAMS, name) for name in MAPPING}, **changes})


def test_what_depends_on_our_choices(rng):
    poses = random_poses(rng, 10)
    reference = inverse_kinematics(PARAMS, poses)
    jac = paper.jacobians(reference)
    # Widths: only the corner axes of the parallelograms move.
    wide = inverse_kinematics(with_changes(proximal_width=10.0, distal_width=200.0), poses)
    np.testing.assert_array_equal(wide.joint_angles, reference.joint_angles)
    np.testing.assert_array_equal(paper.jacobians(wide).A, jac.A)
    # b4 + b5: a vertical translation of the workspace; the split only moves O_J4 on its axis.
    shifted = inverse_kinematics(with_changes(b4=-150.0, b5=20.0), poses - [0, 0, 30.0, 0])
    np.testing.assert_allclose(shifted.joint_angles, reference.joint_angles, atol=1e-12)
    np.testing.assert_allclose(paper.jacobians(shifted).A, jac.A, atol=1e-12)
    # l0 and l1 change the joint angles, the Jacobians and so the singularity loci.
    for changes in ({"l0": 500.0}, {"l1": 50.0}):
        other = inverse_kinematics(with_changes(**changes), poses)
        assert np.abs(paper.jacobians(other).A - jac.A).max() > 1e-2


@given(
    dims=st.tuples(st.floats(0, 800), st.floats(0, 200), st.floats(300, 900),
                   st.floats(150, 500), st.floats(50, 300)),
    angles=st.tuples(st.floats(-np.pi, np.pi), st.floats(-2.5, -0.5), st.floats(0.3, 2.8),
                     st.floats(-np.pi, np.pi)),
    mode_two=st.sampled_from([(1, 1), (1, -1), (-1, 1), (-1, -1)]),
)
def test_jacobian_identities_hold_for_any_dimensions(dims, angles, mode_two):
    l0, l1, l2, l3, radius = dims
    params = McGillParameters(l0, l1, l2, l3, radius, -50.0, -50.0, 80.0, 60.0)
    pose = leg_pose(params, "I", np.array(angles))
    kappa = l1 + l2 * np.cos(angles[1]) + l3 * np.cos(angles[1] + angles[2])
    try:
        config = inverse_kinematics(params, pose, (1 if kappa >= 0 else -1, 1, *mode_two))
    except UnreachablePoseError:
        assume(False)  # leg II cannot reach this pose with these dimensions
    rates, step = np.array([0.3, -0.2, 0.5, 0.7]), 1e-7 * (l2 + l3)
    delta = rates * [step, step, step, step / (l2 + l3)]
    ahead = inverse_kinematics(params, pose + delta, config.mode).actuated
    behind = inverse_kinematics(params, pose - delta, config.mode).actuated
    jac = paper.jacobians(config)
    twist = np.concatenate([[delta[3]], delta[:3] / radius])
    lhs, rhs = jac.A @ twist, jac.B @ (wrap(ahead - behind) / 2)
    assert np.abs(lhs - rhs).max() <= 1e-5 * (np.abs(lhs).max() + np.abs(rhs).max()) + 1e-12
    factors = paper.singularity_factors(config)
    np.testing.assert_allclose(factors.delta, -l2 * l3 / radius**2 * np.sin(
        config.joint_angles[:, 2]), atol=1e-9 * l2 * l3 / radius**2)
