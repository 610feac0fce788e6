"""Tests of screwkit.robots.families.peppermill: the CRRHHRRC SMG of paper 000 (Harada & Angeles 2014).

Known values come from the paper's equations as printed (Eqs. 14, 25, 31-35, 47-48) and from hand
derivations written out below; the three kinds of singularity are rebuilt and judged by ranks.
"""

from __future__ import annotations

import networkx as nx
import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from screwkit.algebra import screw as S
from screwkit.exceptions import (
    CatalogError,
    DegenerateGeometryError,
    ScrewkitValueError,
    UnreachablePoseError,
)
from screwkit.robots.families import peppermill as pm

from .. import paper_000 as paper
from ..two_limb_papers import bisect_segment, pick_and_place_cycle

# Paper 000 gives no dimensions: these are our choice (mm), with p2 = -p1 as in its Sec. 4.3.
PARAMS = pm.PeppermillParameters(r1=250.0, r2=250.0, l1=400.0, l2=400.0, b0=50.0, p1=40.0,
                                 p2=-40.0)
MAPPING = {"r1": 250, "r2": 250, "l1": 400, "l2": 400, "b0": 50, "p1": 40, "p2": -40}
K = np.array([0.0, 0.0, 1.0])
SINGULAR = 1e-12
REGULAR = 1e-2


def random_poses(rng: np.random.Generator, n: int) -> np.ndarray:
    """Poses reachable in all four working modes (‖q_1‖ in [310, 512], ‖q_2‖ in [410, 610])."""
    return np.column_stack([
        rng.uniform(-150, 150, n), rng.uniform(-150, 150, n), rng.uniform(-500, -400, n),
        rng.uniform(-2 * np.pi, 2 * np.pi, n),
    ])


def wrap(angle: np.ndarray) -> np.ndarray:
    return (angle + np.pi) % (2 * np.pi) - np.pi


def rank(matrix: np.ndarray) -> int:
    values = np.linalg.svd(matrix, compute_uv=False)
    return int(np.linalg.matrix_rank(matrix, tol=1e-9 * values[0]))


def closeness(matrix: np.ndarray) -> float:
    values = np.linalg.svd(matrix, compute_uv=False)
    return float(values[-1] / values[0])


# --------------------------------------------------------------------------------------------------
# Parameters
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("mapping", "error", "match"),
    [
        ({**MAPPING, "h": 1}, CatalogError, r"pm.toml: unknown field\(s\) \['h'\]"),
        ({k: v for k, v in MAPPING.items() if k != "b0"}, CatalogError,
         r"pm.toml: missing field\(s\) \['b0'\]"),
        ({**MAPPING, "p1": None}, CatalogError, r"field `p1` of PeppermillParameters to be a real"),
        ({**MAPPING, "r2": 0}, ScrewkitValueError, r"parameter `r2` of PeppermillParameters to be > 0"),
        ({**MAPPING, "b0": -5}, ScrewkitValueError, r"parameter `b0` of PeppermillParameters to be >="),
    ],
)
def test_from_mapping_errors(mapping, error, match):
    with pytest.raises(error, match=match):
        pm.PeppermillParameters.from_mapping(mapping, source="pm.toml")


def test_from_mapping_and_scaling():
    params = pm.PeppermillParameters.from_mapping(MAPPING)
    assert params == PARAMS
    assert params.scaled(2.0).p2 == -80.0
    with pytest.raises(ScrewkitValueError, match=r"Expected `factor` to be a number > 0"):
        params.scaled(-1.0)


# --------------------------------------------------------------------------------------------------
# Inverse kinematics, Eqs. (19)-(27)
# --------------------------------------------------------------------------------------------------


def test_inverse_kinematics_hand_values():
    # r = 3, l = 4, b0 = 1, φ = 0, pose (0, 5, -1): q_1 = (0, 5, 0) and the 3-4-5 triangle gives
    # u_1 = (0, 3/5, ∓4/5), v_1 = (0, 4/5, ±3/5), a right angle at B_1: λ_1 = ±π/2. Limb 2:
    # q_2 = (0, 0, -2), Eq. (24) reads -2 cos θ_2 + 1/2 = 0, so θ_2 = ±arccos(1/4).
    params = pm.PeppermillParameters(r1=3, r2=3, l1=4, l2=4, b0=1, p1=1, p2=-1)
    for mode in pm.WORKING_MODES:
        config = pm.inverse_kinematics(params, [0.0, 5.0, -1.0, 0.0], mode)
        np.testing.assert_allclose(config.actuated, [0.0, 5.0, -mode[0] * np.arccos(0.6),
                                                     mode[1] * np.arccos(0.25)], atol=1e-12)
        np.testing.assert_allclose(config.u[0], [0, 0.6, -0.8 * mode[0]], atol=1e-12)
        np.testing.assert_allclose(config.v[0], [0, 0.8, 0.6 * mode[0]], atol=1e-12)
        assert config.passive[0] == pytest.approx(mode[0] * np.pi / 2)
        np.testing.assert_allclose(config.elbow[0], [0.0, 1.8, -1.0 - 2.4 * mode[0]], atol=1e-12)
        assert np.sign(np.sin(config.passive[1])) == mode[1]


def test_inverse_kinematics_is_eq_25(rng):
    # Both roots of Eq. (25), θ = 2 arctan((-e1 ± sqrt(e1² + e2² - e3²)) / (e3 - e2)), are the two
    # working modes.
    poses = random_poses(rng, 20)
    radius, length, leads = PARAMS.lengths
    base = np.array([[0, 0, -PARAMS.b0], [0, 0, PARAMS.b0]])
    x_axes, y_axes = np.array([[0, 1, 0], [0, 0, 1]]), np.array([[0, 0, 1], [1, 0, 0]])
    a_axes = np.array([[1, 0, 0], [0, 1, 0]])
    ours = np.stack([pm.inverse_kinematics(PARAMS, poses, m).actuated[:, 2:]
                     for m in ((1, 1), (-1, -1))], axis=-1)
    for i in range(2):
        p = poses[:, None, :3] + leads[i] * poses[:, None, 3:] * K  # Eq. (13) with -o_i
        q = (p - base[i] - poses[:, i : i + 1, None] * a_axes[i])[:, 0]  # Eq. (20)
        e1, e2 = q @ y_axes[i], q @ x_axes[i]
        e3 = -(np.sum(q * q, axis=-1) + radius[i] ** 2 - length[i] ** 2) / (2 * radius[i])
        root = np.sqrt(e1**2 + e2**2 - e3**2)
        paper = np.stack([2 * np.arctan((-e1 + s * root) / (e3 - e2)) for s in (1, -1)], axis=-1)
        np.testing.assert_allclose(np.sort(wrap(paper), axis=-1),
                                   np.sort(wrap(ours[:, i]), axis=-1), atol=1e-10)


@pytest.mark.parametrize("mode", pm.WORKING_MODES)
def test_loop_closure_eq_14(rng, mode):
    poses = random_poses(rng, 30)
    config = pm.inverse_kinematics(PARAMS, poses, mode)
    radius, length, leads = PARAMS.lengths
    d = config.actuated[:, :2]
    lhs = d[..., None] * config.drive_axis + radius[:, None] * config.u + length[:, None] * config.v
    o = np.array([[0, 0, -PARAMS.b0], [0, 0, PARAMS.b0]])
    rhs = -o + poses[:, None, :3] + (leads * poses[:, 3:])[..., None] * K
    np.testing.assert_allclose(lhs, rhs, atol=1e-9)
    np.testing.assert_allclose(config.actuated[:, :2], poses[:, :2], atol=0)  # Eq. (19)
    assert np.all(np.sign(np.sin(config.passive)) == mode)
    np.testing.assert_allclose(np.linalg.norm(config.v, axis=-1), 1.0, atol=1e-12)
    assert "mode=" in str(config) and config.to_dict()["mode"] == list(mode)


@pytest.mark.parametrize(
    ("pose", "match"),
    [
        ([0.0, 0.0, -1000.0, 0.0], r"Limb 1 cannot reach the pose: .*‖q_1‖ \(Eq. 20\) is \[950"),
        ([700.0, 0.0, -450.0, 0.0], r"Limb 2 cannot reach the pose: .*expected within"),
        ([0.0, 0.0, -130.0, 0.0], r"Limb 1 cannot reach the pose: .*\[150, 650\]"),
    ],
)
def test_unreachable_poses_name_the_limb(pose, match):
    with pytest.raises(UnreachablePoseError, match=match):
        pm.inverse_kinematics(PARAMS, pose)


def test_nonexistent_mode():
    with pytest.raises(ScrewkitValueError, match=r"Expected `mode` to be a sequence of 2 signs"):
        pm.inverse_kinematics(PARAMS, [0, 0, -450, 0], (1, 1, 1))


# --------------------------------------------------------------------------------------------------
# Forward kinematics, Eqs. (28)-(35)
# --------------------------------------------------------------------------------------------------


def paper_forward(actuated: np.ndarray) -> np.ndarray:
    """Eqs. (28), (32), (33), (35) as printed (principal arcsin and arccos)."""
    d1, d2, t1, t2 = actuated.T
    r1, r2, l1, l2, b0 = PARAMS.r1, PARAMS.r2, PARAMS.l1, PARAMS.l2, PARAMS.b0
    lam2 = np.arcsin((d1 - r2 * np.sin(t2)) / l2) - t2  # Eq. (32)
    lam1 = np.arccos((d2 - r1 * np.cos(t1)) / l1) - t1  # Eq. (33)
    matrix = np.array([[1, PARAMS.p1 / (2 * np.pi)], [1, PARAMS.p2 / (2 * np.pi)]])
    rhs = np.stack([r1 * np.sin(t1) + l1 * np.sin(t1 + lam1) - b0,
                    r2 * np.cos(t2) + l2 * np.cos(t2 + lam2) + b0], axis=-1)  # Eq. (35)
    z, phi = np.linalg.solve(matrix, rhs.T)
    return np.column_stack([d1, d2, z, phi])


def test_forward_kinematics_slot_plus_plus_is_the_paper(rng):
    # Raise the plate so that both distal links climb to it (v_iz > 0), the branch of Eqs. (32)-(33).
    poses = random_poses(rng, 20) * [1, 1, 0, 1] + [0, 0, 300, 0]
    config = pm.inverse_kinematics(PARAMS, poses)
    assert np.all(config.v[..., 2] > 0)
    solutions = pm.forward_kinematics(PARAMS, config.actuated)
    np.testing.assert_allclose(solutions.poses[:, 0], paper_forward(config.actuated), atol=1e-9)
    np.testing.assert_allclose(solutions.poses[:, 0], poses, atol=1e-9)


def test_paper_branch_misses_a_hanging_plate(rng):
    # With the plate below the drives (v_iz < 0) Eqs. (32)-(33) return another assembly.
    poses = random_poses(rng, 20)
    config = pm.inverse_kinematics(PARAMS, poses)
    assert np.all(config.v[..., 2] < 0)
    assert np.all(np.abs(paper_forward(config.actuated) - poses).max(axis=-1) > 1.0)
    np.testing.assert_allclose(pm.forward_kinematics(PARAMS, config.actuated).poses[:, 3], poses,
                               atol=1e-9)


@pytest.mark.parametrize("mode", pm.WORKING_MODES)
def test_forward_kinematics_round_trip(rng, mode):
    poses = random_poses(rng, 30)
    poses[:, 2] *= rng.choice([-1.0, 1.0], size=30)  # plate below or above the drives
    config = pm.inverse_kinematics(PARAMS, poses, mode)
    solutions = pm.forward_kinematics(PARAMS, config.actuated)
    slot = [pm.ASSEMBLY_MODES.index(tuple(int(s) for s in np.sign(v))) for v in config.v[..., 2]]
    rows = np.arange(30), np.array(slot)
    np.testing.assert_allclose(solutions.poses[rows], poses, atol=1e-8)
    np.testing.assert_allclose(wrap(solutions.passive[rows] - config.passive), 0.0, atol=1e-10)
    assert np.all(solutions.working_modes[rows] == mode)
    for row, column in zip(*np.nonzero(solutions.valid), strict=True):  # every assembly closes
        again = pm.inverse_kinematics(PARAMS, solutions.poses[row, column],
                                      tuple(solutions.working_modes[row, column]))
        np.testing.assert_allclose(wrap(again.actuated - config.actuated[row]), 0.0, atol=1e-9)


def test_forward_kinematics_invalid_slots():
    # d_1 = 700 > r_2 + l_2: Eq. (31) has no solution, no assembly exists.
    solutions = pm.forward_kinematics(PARAMS, [700.0, 0.0, 0.3, 0.2])
    assert solutions.count == 0 and np.all(solutions.poses.mask) and np.isfinite(solutions.poses.data).all()


def test_equal_leads_are_an_architecture_singularity(rng):
    params = pm.PeppermillParameters(250, 250, 400, 400, 50, 40, 40)
    config = pm.inverse_kinematics(params, random_poses(rng, 10))
    assert all(rank(a) == 3 for a in paper.jacobians(config).A)
    assert np.all(paper.classify(config).types == "direct")
    with pytest.raises(DegenerateGeometryError, match=r"Expected distinct leads p1 and p2"):
        pm.forward_kinematics(params, config.actuated)
    zero = pm.PeppermillParameters(250, 250, 400, 400, 50, 0, 0)
    assert np.all(paper.classify(pm.inverse_kinematics(zero, random_poses(rng, 3))).direct)


# --------------------------------------------------------------------------------------------------
# Jacobians, Eqs. (44)-(48)
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("mode", pm.WORKING_MODES)
def test_jacobians_against_finite_differences(rng, mode):
    poses = random_poses(rng, 20)
    rates = rng.normal(size=(20, 4))
    step = 1e-6
    ahead = pm.inverse_kinematics(PARAMS, poses + step * rates, mode).actuated
    behind = pm.inverse_kinematics(PARAMS, poses - step * rates, mode).actuated
    q_dot = (ahead - behind) / (2 * step)
    q_dot[:, 2:] = wrap(ahead[:, 2:] - behind[:, 2:]) / (2 * step) * [PARAMS.r1, PARAMS.r2]
    jac = paper.jacobians(pm.inverse_kinematics(PARAMS, poses, mode))
    lhs = np.einsum("nij,nj->ni", jac.A, rates)
    rhs = np.einsum("nij,nj->ni", jac.B, q_dot)  # δθ = (δd1, δd2, r1 δθ1, r2 δθ2), Eq. (44)
    assert np.abs(lhs - rhs).max() < 1e-6 * np.abs(lhs).max()


def test_jacobians_are_eq_47_entry_by_entry(rng):
    config = pm.inverse_kinematics(PARAMS, random_poses(rng, 10), (1, -1))
    jac = paper.jacobians(config)
    v1, v2 = config.v[:, 0], config.v[:, 1]
    zero, one = np.zeros(10), np.ones(10)
    lead1, lead2 = PARAMS.p1 / (2 * np.pi), PARAMS.p2 / (2 * np.pi)
    expected_a = np.stack([
        np.stack([one, zero, zero, zero], -1), np.stack([zero, one, zero, zero], -1),
        np.stack([zero, v1[:, 1], v1[:, 2], lead1 * v1[:, 2]], -1),
        np.stack([v2[:, 0], zero, v2[:, 2], lead2 * v2[:, 2]], -1),
    ], axis=1)
    np.testing.assert_allclose(jac.A, expected_a, atol=1e-15)
    np.testing.assert_allclose(v1[:, 0], 0.0, atol=0)  # Eq. (45): v_1 = (0, v_1y, v_1z)
    np.testing.assert_allclose(v2[:, 1], 0.0, atol=0)
    # Eq. (45) prints u_θ2 = (u_θ2z, 0, u_θ2z); Eq. (38) gives (cos θ_2, 0, -sin θ_2).
    theta2 = config.actuated[:, 3]
    np.testing.assert_allclose(config.u_theta[:, 1], np.column_stack(
        [np.cos(theta2), zero, -np.sin(theta2)]), atol=1e-15)
    assert np.abs(config.u_theta[:, 1, 0] - config.u_theta[:, 1, 2]).max() > 0.1
    # B = diag(1, 1, v_1·u_θ1, v_2·u_θ2) with v_i·u_θi = sin λ_i (hand: angle λ_i between u_i, v_i).
    np.testing.assert_allclose(jac.B, np.stack([np.diag([1, 1, *np.sin(lam)])
                                                for lam in config.passive]), atol=1e-15)


def test_determinants_eq_48(rng):
    config = pm.inverse_kinematics(PARAMS, random_poses(rng, 20), (-1, 1))
    jac, factors = paper.jacobians(config), paper.singularity_factors(config)
    v_z = config.v[..., 2]
    expected = v_z[:, 0] * v_z[:, 1] * (PARAMS.p2 - PARAMS.p1) / (2 * np.pi)
    np.testing.assert_allclose(np.linalg.det(jac.A), expected, rtol=1e-12)
    np.testing.assert_allclose(factors.det_a, expected, rtol=1e-12)
    np.testing.assert_allclose(np.linalg.det(jac.B), np.prod(np.sin(config.passive), axis=-1),
                               rtol=1e-12)
    np.testing.assert_allclose(factors.det_b, np.linalg.det(jac.B), rtol=1e-12)


# --------------------------------------------------------------------------------------------------
# Singularities of the first, second and third kind (Secs. 4.2-4.4)
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("pose", "limb", "folded"),
    [
        # 3-4-5 triangles scaled by 130 and 30: ‖q_i‖ = r + l = 650 (extended), l - r = 150 (folded).
        ([0.0, 390.0, -570.0, 0.0], 0, False),  # q_1 = (0, 390, -520)
        ([0.0, 90.0, -170.0, 0.0], 0, True),  # q_1 = (0, 90, -120)
        ([390.0, 0.0, -470.0, 0.0], 1, False),  # q_2 = (390, 0, -520)
    ],
)
def test_first_kind_aligned_links(pose, limb, folded):
    configs = [pm.inverse_kinematics(PARAMS, pose, mode) for mode in ((1, 1), (-1, 1))]
    if limb == 1:
        configs = [pm.inverse_kinematics(PARAMS, pose, mode) for mode in ((1, 1), (1, -1))]
    # the two working modes of the limb meet: the proximal and distal links are aligned
    np.testing.assert_allclose(configs[0].actuated, configs[1].actuated, atol=1e-12)
    config = configs[0]
    assert abs(wrap(config.passive[limb] - (np.pi if folded else 0.0))) < 1e-12
    assert np.linalg.norm(np.cross(config.u[limb], config.v[limb])) < 1e-12
    jac = paper.jacobians(config)
    assert rank(jac.B) == 3 and rank(jac.A) == 4
    assert paper.classify(config).types.tolist() == "inverse"


@pytest.mark.parametrize(
    ("start", "end", "limb"),
    [([0.0, 150.0, -150.0, 0.0], [0.0, 300.0, -150.0, 0.0], 0),  # y moves limb 1 only
     ([-300.0, 300.0, -50.0, 0.0], [-150.0, 300.0, -50.0, 0.0], 1)],  # x: limb 2 only
)
def test_second_kind_horizontal_distal_link(start, end, limb):
    pose = paper.locate_direct_singularity(PARAMS, start, end)
    config = pm.inverse_kinematics(PARAMS, pose)
    assert abs(config.v[limb, 2]) < 1e-12  # the distal link lies in a horizontal plane
    jac = paper.jacobians(config)
    assert rank(jac.A) == 3 and rank(jac.B) == 4 and closeness(jac.B) > REGULAR
    result = paper.classify(config)
    assert result.types.tolist() == "direct" and result.closeness["direct"] < SINGULAR


def test_third_kind_within_one_limb():
    # q_1 = (0, 650, 0): limb 1 extended along +y, both links horizontal (λ_1 = 0 and v_1z = 0).
    config = pm.inverse_kinematics(PARAMS, [200.0, 650.0, -50.0, 0.0])
    np.testing.assert_allclose(config.v[0], [0, 1, 0], atol=1e-12)
    jac = paper.jacobians(config)
    assert rank(jac.A) == 3 and rank(jac.B) == 3
    assert paper.classify(config).types.tolist() == "combined"


def test_third_kind_across_the_limbs():
    # Limb 1 extended (‖q_1‖ = 650 with q_1z = -100), then x moved until limb 2's distal link is
    # horizontal.
    y = np.sqrt(650.0**2 - 100.0**2)

    def v2z(pose: np.ndarray) -> np.ndarray:
        return pm.inverse_kinematics(PARAMS, pose, (1, -1)).v[..., 1, 2]

    pose = bisect_segment(v2z, [240.0, y, -150.0, 0.0], [270.0, y, -150.0, 0.0])
    config = pm.inverse_kinematics(PARAMS, pose, (1, -1))
    assert abs(config.passive[0]) < 1e-7 and abs(config.v[1, 2]) < 1e-12  # ‖q_1‖ = 650 rounded
    jac = paper.jacobians(config)
    assert rank(jac.A) == 3 and rank(jac.B) == 3
    assert paper.classify(config, rtol=1e-7).types.tolist() == "combined"


def test_generic_poses_are_regular(rng):
    result = paper.classify(pm.inverse_kinematics(PARAMS, random_poses(rng, 50)))
    assert np.all(result.types == "regular")
    assert result.closeness["inverse"].min() > REGULAR and result.closeness["direct"].min() > REGULAR
    assert result.to_dict()["rtol"] == 1e-9


def test_length_scale():
    config = pm.inverse_kinematics(PARAMS, [10.0, 20.0, -450.0, 0.3])
    # default: mean lead per radian, 40/2π; the δφ column becomes (0, 0, v_1z, -v_2z)
    scaled = paper.jacobians(config).A[:, 3] / (40.0 / (2 * np.pi))
    np.testing.assert_allclose(scaled, [0, 0, config.v[0, 2], -config.v[1, 2]], atol=1e-15)
    explicit = paper.classify(config, length_scale=40.0 / (2 * np.pi))
    assert explicit.closeness["direct"] == pytest.approx(paper.classify(config).closeness["direct"])
    with pytest.raises(ScrewkitValueError, match=r"Expected `length_scale` to be a positive"):
        paper.classify(config, length_scale=0.0)


# --------------------------------------------------------------------------------------------------
# Invariants
# --------------------------------------------------------------------------------------------------


@given(scale=st.floats(1e-3, 1e3), index=st.integers(0, 3))
def test_change_of_length_unit(scale, index):
    poses = random_poses(np.random.default_rng(index), 4)
    mode = pm.WORKING_MODES[index]
    config = pm.inverse_kinematics(PARAMS, poses, mode)
    scaled = pm.inverse_kinematics(PARAMS.scaled(scale), poses * [scale, scale, scale, 1], mode)
    np.testing.assert_allclose(scaled.actuated[:, 2:], config.actuated[:, 2:], atol=1e-9)
    np.testing.assert_allclose(scaled.passive, config.passive, atol=1e-9)
    one, two = paper.classify(config), paper.classify(scaled)
    np.testing.assert_allclose(two.closeness["direct"], one.closeness["direct"], rtol=1e-9)
    np.testing.assert_allclose(two.closeness["inverse"], one.closeness["inverse"], rtol=1e-9)


@given(
    quaternion=st.lists(st.floats(-1, 1), min_size=4, max_size=4).filter(
        lambda q: np.linalg.norm(q) > 0.1
    ),
    index=st.integers(0, 3),
)
def test_rotation_of_the_base_frame(quaternion, index):
    w, x, y, z = np.array(quaternion) / np.linalg.norm(quaternion)
    rotation = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])
    config = pm.inverse_kinematics(PARAMS, random_poses(np.random.default_rng(index), 3),
                                   pm.WORKING_MODES[index])
    turned = {name: getattr(config, name) @ rotation.T
              for name in ("drive_point", "drive_axis", "slider_point", "elbow", "wrist", "u",
                           "u_theta", "v", "platform_point", "platform_axis")}
    other = pm.PeppermillConfiguration(config.params, config.mode, config.pose, config.actuated,
                                       config.passive, **turned)
    one, two = paper.classify(config), paper.classify(other)
    np.testing.assert_allclose(two.closeness["direct"], one.closeness["direct"], rtol=1e-9)
    np.testing.assert_allclose(two.closeness["inverse"], one.closeness["inverse"], rtol=1e-9)
    np.testing.assert_allclose(np.linalg.det(paper.jacobians(other).A),
                               np.linalg.det(paper.jacobians(config).A), rtol=1e-9)


# --------------------------------------------------------------------------------------------------
# The physical joints
# --------------------------------------------------------------------------------------------------


def test_joints_form_a_single_loop():
    table = pm.joints(pm.inverse_kinematics(PARAMS, [0.0, 0.0, -450.0, 0.0]))
    joints = table.specs
    graph = nx.MultiGraph()
    for joint in joints:
        graph.add_edge(joint.parent, joint.child, key=joint.name)
    assert graph.number_of_edges() - graph.number_of_nodes() + 1 == 1  # one loop (Sec. 1)
    assert [j.type for j in joints] == ["P", "R", "R", "R", "H"] * 2
    assert [j.name for j in joints if j.actuated] == ["1.slide", "1.turn", "2.slide", "2.turn"]
    pitches = [float(S.pitch(table.joint_screws(j.name)[0])) for j in joints if j.type == "H"]
    assert pitches == [-40 / (2 * np.pi), 40 / (2 * np.pi)]


def test_joint_screws_reproduce_the_platform_twist(rng):
    # The plate twist (ω; v_O) by finite differences of the pose equals, along each limb,
    # ḋ $_slide + θ̇ $_turn + λ̇ $_elbow - (θ̇ + λ̇) $_wrist + φ̇ $_screw: this fixes the sign of the
    # H pitch, -p_i/2π.
    pose, rates, step = random_poses(rng, 1)[0], rng.normal(size=4), 1e-6
    config = pm.inverse_kinematics(PARAMS, pose)
    ahead, behind = (pm.inverse_kinematics(PARAMS, pose + s * step * rates) for s in (1, -1))
    d_dot = (ahead.actuated[:2] - behind.actuated[:2]) / (2 * step)
    theta_dot = wrap(ahead.actuated[2:] - behind.actuated[2:]) / (2 * step)
    lam_dot = wrap(ahead.passive - behind.passive) / (2 * step)
    omega = rates[3] * K
    twist = np.concatenate([omega, rates[:3] - np.cross(omega, pose[:3])])
    table = pm.joints(config)
    for i, limb in enumerate(("1", "2")):
        total = (d_dot[i] * table.joint_screws(f"{limb}.slide")[0]
                 + theta_dot[i] * table.joint_screws(f"{limb}.turn")[0]
                 + lam_dot[i] * table.joint_screws(f"{limb}.elbow")[0]
                 - (theta_dot[i] + lam_dot[i]) * table.joint_screws(f"{limb}.wrist")[0]
                 + rates[3] * table.joint_screws(f"{limb}.screw")[0])
        np.testing.assert_allclose(total, twist, atol=1e-6)


# --------------------------------------------------------------------------------------------------
# Test cycle (paper 000, Sec. 1)
# --------------------------------------------------------------------------------------------------


def test_test_cycle_with_our_dimensions():
    # 25 mm up, 300 mm across with a 180° clockwise turn, down, and back. With our dimensions it
    # stays reachable and regular in all four working modes: the turn only moves the nuts by
    # ±p/2 = ±20 mm along the plate's axis.
    path = pick_and_place_cycle([-150.0, 0.0, -450.0, 0.0], samples_per_segment=40)
    for mode in pm.WORKING_MODES:
        result = paper.classify(pm.inverse_kinematics(PARAMS, path, mode))
        assert result.closeness["direct"].min() > 0.3 and result.closeness["inverse"].min() > 0.9


# --------------------------------------------------------------------------------------------------
# What depends on the dimensions we chose (all of them: paper 000 gives none)
# --------------------------------------------------------------------------------------------------


# random dimensions put many random poses out of reach (rejected with assume): not a health problem
@settings(suppress_health_check=[HealthCheck.filter_too_much])
@given(
    dims=st.tuples(st.floats(50, 500), st.floats(50, 500), st.floats(50, 500), st.floats(50, 500),
                   st.floats(0, 200), st.floats(-100, 100), st.floats(-100, 100)),
    pose=st.tuples(st.floats(-300, 300), st.floats(-300, 300), st.floats(-600, 600),
                   st.floats(-10, 10)),
    mode=st.sampled_from(pm.WORKING_MODES),
)
def test_eq_47_48_hold_for_any_dimensions(dims, pose, mode):
    # The structure of A and B, det A = v_1z v_2z (p_2 - p_1)/2π and det B = sin λ_1 sin λ_2 do not
    # depend on our dimensions; where the singular loci lie does.
    params = pm.PeppermillParameters(*dims)
    try:
        config = pm.inverse_kinematics(params, list(pose), mode)
    except UnreachablePoseError:
        assume(False)
    jac = paper.jacobians(config)
    v_z = config.v[:, 2]
    scale = np.abs(params.p2 - params.p1) / (2 * np.pi) + 1.0
    assert np.linalg.det(jac.A) == pytest.approx(
        v_z[0] * v_z[1] * (params.p2 - params.p1) / (2 * np.pi), abs=1e-12 * scale)
    assert np.linalg.det(jac.B) == pytest.approx(np.prod(np.sin(config.passive)), abs=1e-12)
    # Round trip away from singularities (there the forward problem is ill-conditioned).
    assume(np.abs(np.sin(config.passive)).min() > 1e-3 and np.abs(v_z).min() > 1e-3)
    assume(abs(params.p2 - params.p1) > 1.0)
    solutions = pm.forward_kinematics(params, config.actuated)
    slot = pm.ASSEMBLY_MODES.index(tuple(1 if v >= 0 else -1 for v in v_z))
    np.testing.assert_allclose(solutions.poses[slot], pose, atol=1e-7 * (1 + np.abs(pose).max()))
