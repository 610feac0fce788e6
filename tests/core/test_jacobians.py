"""Jacobians from wrenches: paper 004's A and B, finite differences, Gosselin-Angeles types, the H4's
determinants (papers 002 and 004), invariance, batch parity and errors.

Geometry: paper 004 Table 3 (Quattro: α = -π/4, β = 3π/4; H4: α = 0, β = π/2; r = 80, c = 70 mm) and
Sec. 5 (R = 275, b = 375, l = 800 mm), working mode h_i < 0. Expected values come from the paper's
formulas evaluated here (Eqs. 6-8, 10, 12, 17-18; paper 002 Eqs. 6-7 via tests/robots/test_h4.py), from
central differences of the closed-form inverse kinematics, and from hand derivations (slider-crank).
"""

import functools
import math

import networkx as nx
import numpy as np
import pytest
from hypothesis import given, settings

from screwkit.algebra import screw as S
from screwkit.algebra.screwvalue import Screw
from screwkit.core.jacobian_matrices import GOSSELIN_ANGELES_TYPES, Jacobians
from screwkit.core.jacobians import (
    jacobians_from_wrenches,
    jacobians_over_poses,
    schoenflies_basis,
)
from screwkit.core.singularity import classify_poses
from screwkit.core.verdicts import classify_analysis
from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import (
    DegenerateGeometryError,
    ScrewkitTypeError,
    ScrewkitValueError,
    TwistGraphError,
)
from screwkit.graphs.joints import prismatic, revolute, spherical
from screwkit.graphs.twistgraph import twist_graph
from screwkit.papers.paper_004 import (
    four_limb_jacobians,
    transmission_indices,
)
from screwkit.robots.families.four_limb.joints import joints
from screwkit.robots.families.four_limb.kinematics import inverse_kinematics, reachable
from screwkit.robots.families.four_limb.parameters import FourLimbParameters

from ..robots.test_h4 import (
    H4,
    case_b_pose,
    paper_002_conditions,
    paper_wrench_matrix,
    random_poses,
    singular_pose,
)
from ..strategies import rigid_motions, seeds, unit_factors

QUATTRO = FourLimbParameters(  # paper 004, Table 3 row "Quattro" and Sec. 5
    name="Quattro", platform_kind="articulated_z", arm_length=375.0, rod_length=800.0, alpha=-math.pi / 4,
    beta=3 * math.pi / 4, platform_radius=80.0, platform_offset=70.0, base_radius=275.0,
)
ROBOTS = {"H4": H4, "Quattro": QUATTRO}
Z = np.array([0.0, 0.0, 1.0])


def central_poses(params, rng, count):
    poses = np.column_stack([
        rng.uniform(-300, 300, (4 * count, 2)), rng.uniform(-1000, -600, 4 * count),
        rng.uniform(-1.2, 1.2, 4 * count),
    ])
    return poses[reachable(params, poses)][:count]


def basis_of(cfg):
    return schoenflies_basis(cfg.pose[..., :3], cfg.platform_joint_axis)


def single(params, pose, **kwargs):
    cfg = inverse_kinematics(params, pose)
    analysis = wrench_analysis(joints(cfg).graph(), rtol=kwargs.pop("analysis_rtol", 1e-9))
    return cfg, analysis, jacobians_from_wrenches(analysis, basis_of(cfg), **kwargs)


def batch_inputs(params, poses):
    cfg = inverse_kinematics(params, poses)
    table = joints(cfg)
    graph = table.graph((0,) * (np.ndim(poses) - 1))
    screws = {spec.name: table.joint_screws(spec.name) for spec in table.specs}
    return cfg, graph, screws


def batch(params, poses, **kwargs):
    cfg, graph, screws = batch_inputs(params, poses)
    return cfg, jacobians_over_poses(graph, screws, basis_of(cfg), **kwargs)


def eq_12(cfg):
    """Paper 004 Eq. (12): |A| = 2r (w14 × w23)ᵀ s, evaluated here from w_i and s."""
    w = cfg.w
    normal = np.cross(np.cross(w[..., 0, :], w[..., 3, :]), np.cross(w[..., 1, :], w[..., 2, :]))
    return 2 * cfg.params.platform_radius * np.einsum("...i,...i", normal, cfg.platform_s)


def dtheta_dchi(params, poses, step=1e-5):
    """Central differences of the inverse kinematics, (..., 4 limbs, 4 pose coordinates)."""
    columns = []
    for k in range(4):
        delta = np.zeros(4)
        delta[k] = step
        plus, minus = inverse_kinematics(params, poses + delta).theta, inverse_kinematics(params, poses - delta).theta
        columns.append(((plus - minus + np.pi) % (2 * np.pi) - np.pi) / (2 * step))
    return np.stack(columns, axis=-1)


# paper 004: A and B up to a row scaling, Eqs. (6)-(8), (10), (12) -----------------------------------
@pytest.mark.parametrize("name", ROBOTS)
def test_paper_jacobians_up_to_row_scaling(name, rng):
    params = ROBOTS[name]
    poses = central_poses(params, rng, 40)
    cfg, result = batch(params, poses)
    A_paper, B_paper = four_limb_jacobians(cfg)
    h = np.diagonal(B_paper, axis1=-2, axis2=-1)
    ours = np.diagonal(result.B, axis1=-2, axis2=-1)
    D = h / ours  # A_paper = D A_ours, B_paper = D B_ours
    np.testing.assert_allclose(D[..., None] * result.A, A_paper, atol=1e-9 * 375)
    np.testing.assert_allclose(D[..., None] * result.B, B_paper, atol=1e-9 * 375)
    # unit-force rows with B_jj >= 0: D = sgn(h_i) = -1 in the paper's working mode (rows e_i have unit w_i)
    np.testing.assert_allclose(D, -1.0, atol=1e-12)
    np.testing.assert_allclose(result.wrenches[..., :3], -cfg.w, atol=1e-12)
    # same kinematic Jacobian A⁻¹B (Eq. 9); det A = Eq. (12) (det D = 1); det B = Π|h_i| (Eq. 10)
    np.testing.assert_allclose(result.kinematic_jacobian(), np.linalg.solve(A_paper, B_paper), rtol=1e-8, atol=1e-9)
    np.testing.assert_allclose(result.det_A, eq_12(cfg), rtol=1e-8, atol=1e-9)
    np.testing.assert_allclose(result.det_B, np.prod(np.abs(h), axis=-1), rtol=1e-10)


OTHER_PLATFORMS = {  # paper 004 Table 3 rows "V4" and "Veloce." (lead h = 20 mm, our choice), Sec. 5
    "V4": FourLimbParameters(name="V4", platform_kind="articulated_y", arm_length=375.0, rod_length=800.0,
                             alpha=0.0, beta=math.pi / 2, platform_radius=80.0, platform_offset=70.0,
                             base_radius=275.0),
    "Veloce": FourLimbParameters(name="Veloce", platform_kind="screw_pair", arm_length=375.0, rod_length=800.0,
                                 alpha=-math.pi / 4, beta=3 * math.pi / 4, platform_radius=100.0, lead=20.0,
                                 base_radius=275.0),
}


@pytest.mark.parametrize("name", OTHER_PLATFORMS)
def test_other_platforms_of_table_1(name, rng):
    # the rotation of the basis is about the platform joints' axis (j for the V4, k for the Veloce)
    params = OTHER_PLATFORMS[name]
    poses = central_poses(params, rng, 15)
    cfg, result = batch(params, poses)
    A_paper, B_paper = four_limb_jacobians(cfg)
    np.testing.assert_allclose(-result.A, A_paper, atol=1e-9 * 375)
    np.testing.assert_allclose(-result.B, B_paper, atol=1e-9 * 375)
    np.testing.assert_allclose(np.linalg.solve(result.B, result.A), dtheta_dchi(params, poses), atol=1e-6)


@pytest.mark.parametrize("name", ROBOTS)
def test_single_pose_path_matches_the_paper(name, rng):
    params = ROBOTS[name]
    for pose in central_poses(params, rng, 3):
        cfg, _, result = single(params, pose)
        A_paper, B_paper = four_limb_jacobians(cfg)
        assert result.actuated_joints == ("A1", "A2", "A3", "A4")
        np.testing.assert_allclose(-result.A, A_paper, atol=1e-9 * 375)
        np.testing.assert_allclose(-result.B, B_paper, atol=1e-9 * 375)
        assert result.type == "regular" and result.serial_limbs == ()


@pytest.mark.parametrize("name", ROBOTS)
def test_against_finite_differences_of_inverse_kinematics(name, rng):
    # A χ̇ = B θ̇ with χ̇ the coordinates on the Schoenflies basis, so B⁻¹A = dθ/dχ and A⁻¹B = dχ/dθ.
    params = ROBOTS[name]
    poses = central_poses(params, rng, 40)
    _, result = batch(params, poses)
    numeric = dtheta_dchi(params, poses)
    np.testing.assert_allclose(np.linalg.solve(result.B, result.A), numeric, atol=1e-6)
    np.testing.assert_allclose(result.kinematic_jacobian() @ numeric, np.broadcast_to(np.eye(4), numeric.shape),
                               atol=1e-5)


def test_regular_where_the_paper_transmission_index_is_positive(rng):
    # paper 004 Eq. (16): η = min(κ, ζ) > 0 away from singularities; η > 0.05 must be "regular".
    for params in ROBOTS.values():
        poses = central_poses(params, rng, 100)
        cfg, result = batch(params, poses)
        clear = transmission_indices(cfg).eta > 0.05
        assert clear.sum() > 50
        assert set(result.types[clear]) == {"regular"}


# Gosselin-Angeles types at roots, against screwkit.core.singularity ---------------------------------------
def spiral(vartheta):
    """Paper 004 Eqs. (17)-(18), evaluated here."""
    rho = vartheta / (4 * np.pi)
    return np.stack([650 * rho * np.cos(vartheta), 650 * rho * np.sin(vartheta), -975 + 500 * rho,
                     np.pi * rho - np.pi / 2], axis=-1)


def bisect(function, low, high, steps=100):
    f_low = function(low)
    assert np.sign(f_low) != np.sign(function(high))
    for _ in range(steps):
        middle = (low + high) / 2
        if np.sign(function(middle)) == np.sign(f_low):
            low, f_low = middle, function(middle)
        else:
            high = middle
    return low, high


@functools.cache
def quattro_type_2_pose():
    """A root of Eq. (12) on the spiral near φ = -90° (Sec. 5.1: "Type-2 singularity when |φ| = π/2")."""
    vartheta = np.linspace(0, 4 * np.pi, 2001)
    det_a = eq_12(inverse_kinematics(QUATTRO, spiral(vartheta)))
    k = np.nonzero(np.sign(det_a[:-1]) != np.sign(det_a[1:]))[0]
    assert len(k) == 1  # one sign change along the path, at its start
    low, _ = bisect(lambda v: eq_12(inverse_kinematics(QUATTRO, spiral(np.array(v)))), vartheta[k[0]],
                    vartheta[k[0] + 1])
    return spiral(np.array(low)), spiral(vartheta[0])


def test_quattro_type_2_on_the_spiral_is_direct():
    pose, path_start = quattro_type_2_pose()
    assert math.degrees(pose[3]) == pytest.approx(-88.3, abs=0.1)
    cfg, analysis, result = single(QUATTRO, pose)
    assert abs(eq_12(cfg)) < 1e-9
    assert result.type == "direct" and result.closeness["direct"] < 1e-12
    assert classify_analysis(analysis).labels == ("actuation",)
    # A's null vector is the uncontrolled twist that screwkit.core.singularity reports
    null = np.linalg.svd(result.A)[2][-1]
    twist = null @ result.twist_basis
    uncontrolled = classify_analysis(analysis).uncontrolled_twists
    assert uncontrolled.shape == (1, 6)
    assert Screw(twist).is_equivalent(Screw(uncontrolled[0]), rtol=1e-6, length_scale=500.0)
    with pytest.raises(DegenerateGeometryError, match=r"A⁻¹B does not exist at this pose: A is singular"):
        result.kinematic_jacobian()
    # the spiral's first pose, φ = -90°, is beyond the root: regular, though close (paper: "at |φ| = π/2")
    assert single(QUATTRO, path_start)[2].type == "regular"


@functools.cache
def quattro_serial_pose():
    """The edge of the reachable workspace along a ray: there h_i = 0 for some limb (type 1, Fig. 4)."""
    start, direction = np.array([0.0, 0.0, -800.0, 0.3]), np.array([1.0, 0.3, 0.2, 0.0])
    low, high = 0.0, 2000.0
    assert reachable(QUATTRO, start + low * direction) and not reachable(QUATTRO, start + high * direction)
    for _ in range(200):
        middle = (low + high) / 2
        low, high = (middle, high) if reachable(QUATTRO, start + middle * direction) else (low, middle)
    return start + low * direction


def test_quattro_serial_pose_is_inverse():
    # h_i ~ sqrt(distance to the reach boundary), so a root found in pose space only has |h_i|/b of
    # order sqrt(machine epsilon): the analysis and the labels use rtol = 1e-6 here.
    pose = quattro_serial_pose()
    cfg = inverse_kinematics(QUATTRO, pose)
    limb = int(np.argmin(np.abs(cfg.h)))
    assert abs(cfg.h[limb]) / 375 < 1e-7 and np.sort(np.abs(cfg.h))[1] / 375 > 0.1
    _, analysis, result = single(QUATTRO, pose, analysis_rtol=1e-6)
    assert result.type == "inverse" and result.serial_limbs == (f"A{limb + 1}",)
    assert result.B[limb, limb] == 0.0 and result.det_B == 0.0 and result.closeness["inverse"] == 0.0
    report = classify_analysis(analysis)
    assert report.labels == ("serial",) and [s.actuated_joint for s in report.serial] == [f"A{limb + 1}"]
    # A stays what it was: the row is the limit of the actuation wrench (the paper's e_i, up to sign)
    A_paper, _ = four_limb_jacobians(cfg)
    np.testing.assert_allclose(np.abs(result.A), np.abs(A_paper), atol=1e-6)
    # the kinematic Jacobian exists; its column for the stuck limb is zero (B_jj = 0)
    np.testing.assert_allclose(result.kinematic_jacobian()[:, limb], 0.0)
    _, batched = batch(QUATTRO, pose[None], rtol=1e-6)
    assert batched.types.tolist() == ["inverse"] and batched.serial[0].tolist() == [k == limb for k in range(4)]
    np.testing.assert_allclose(batched.A[0], result.A, atol=1e-6)


def test_h4_labels_agree_with_classify(rng):
    # serial ⇔ inverse, actuation ⇔ direct, and the constraint singularity is invisible to A.
    expected = {
        "eq6": ("regular", ("constraint",)),
        "eq7": ("direct", ("actuation",)),
        "case_b": ("combined", ("actuation", "serial")),
    }
    poses = {"eq6": singular_pose(0), "eq7": singular_pose(1), "case_b": case_b_pose()}
    for key, pose in poses.items():
        _, analysis, result = single(H4, pose)
        assert (result.type, classify_analysis(analysis).labels) == expected[key]
    for pose in random_poses(rng, 6):
        _, analysis, result = single(H4, pose)
        labels = classify_analysis(analysis).labels
        assert (result.type == "regular") == (labels == ())
        assert ("serial" in labels) == (result.type in ("inverse", "combined"))
        assert ("actuation" in labels) == (result.type in ("direct", "combined"))


def test_case_b_row_of_the_stuck_limb():
    # Paper 002 case (b), screwkit's reading (tests/robots/test_h4.py): limb 1 has no actuation force; its
    # passive wrench is the horizontal couple (0; n1), which does no work on the Schoenflies twists.
    _, _, result = single(H4, case_b_pose())
    assert result.serial_limbs == ("A1",) and result.B[0, 0] == 0.0
    assert np.linalg.norm(result.wrenches[0, :3]) < 1e-9 and abs(result.wrenches[0, 5]) < 1e-9
    np.testing.assert_allclose(result.A[0], 0.0, atol=1e-9)


def test_batch_agrees_with_classify_poses(rng):
    poses = np.vstack([random_poses(rng, 20), singular_pose(0), singular_pose(1), case_b_pose()])
    cfg, graph, screws = batch_inputs(H4, poses)
    result = jacobians_over_poses(graph, screws, basis_of(cfg))
    report = classify_poses(graph, screws)
    assert result.actuated_joints == report.actuated_joints
    np.testing.assert_array_equal(result.serial, report.serial_flags)
    np.testing.assert_array_equal(np.isin(result.types, ["direct", "combined"]), report.actuation)
    assert result.types[-3:].tolist() == ["regular", "direct", "combined"]
    assert report.labels.ravel().tolist()[-3:] == [("constraint",), ("actuation",), ("actuation", "serial")]
    np.testing.assert_allclose(result.closeness["inverse"], report.closeness["serial"], atol=1e-9)


def test_batch_agrees_with_single_pose_path(rng):
    poses = np.vstack([random_poses(rng, 3), singular_pose(0), singular_pose(1), case_b_pose()])
    _, result = batch(H4, poses)
    for i, pose in enumerate(poses):
        _, _, one = single(H4, pose)
        assert one.type == result.types[i]
        np.testing.assert_allclose(result.A[i], one.A, atol=1e-8 * 375)
        np.testing.assert_allclose(result.B[i], one.B, atol=1e-8 * 375)
        assert one.closeness["direct"] == pytest.approx(result.closeness["direct"][i], rel=1e-6, abs=1e-12)
        assert one.closeness["inverse"] == pytest.approx(result.closeness["inverse"][i], rel=1e-9)


# what each determinant sees (H4; paper 004 Eq. 12, paper 002 Eqs. 6-7) ---------------------------------
def test_det_A_is_minus_equation_7_and_the_global_determinant_is_equation_6_times_det_A(rng):
    poses = random_poses(rng, 20)
    cfg, result = batch(H4, poses)
    eq6, eq7, _, _ = paper_002_conditions(cfg)
    # Hand derivation: (r_g - r_c) × z = 2r s on the axes Z_II, Z_I, so Eq. (7) = -2r (w14 × w23)·s.
    np.testing.assert_allclose(result.det_A, -eq7, rtol=1e-8)
    np.testing.assert_allclose(eq_12(cfg), -eq7, rtol=1e-8)
    six = np.linalg.det(np.stack([paper_wrench_matrix(inverse_kinematics(H4, pose)) for pose in poses]))
    np.testing.assert_allclose(six, eq6 * result.det_A, rtol=1e-7)  # = -Eq.(6)·Eq.(7)


def test_block_factorization_with_the_analysis_own_wrenches(rng):
    # [C; W] ∘ [T; T'] = [[0, C∘T'], [A, W∘T']] with T' = rotations about x and y: the constraint
    # couples do no work on the Schoenflies twists, so det = det A · det(C∘T') up to a sign, and
    # det(C∘T') is paper 002's Eq. (6) up to the constraint basis's normalisation.
    for pose in random_poses(rng, 3):
        cfg, analysis, result = single(H4, pose)
        C = analysis.constraint_wrenches.basis
        T_prime = np.array([[1.0, 0, 0, 0, 0, 0], [0, 1.0, 0, 0, 0, 0]])
        swap = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])
        products = np.vstack([C, result.wrenches]) @ swap @ np.vstack([result.twist_basis, T_prime]).T
        np.testing.assert_allclose(products[:2, :4], 0.0, atol=1e-9)
        E = products[:2, 4:]
        assert abs(np.linalg.det(products)) == pytest.approx(abs(np.linalg.det(E) * result.det_A), rel=1e-8)
        # C spans the couples (0; z × s12), (0; z × s34): det(C∘T') ∝ Eq. (6) with a non-zero factor
        eq6 = paper_002_conditions(cfg)[0]
        couples = np.array([np.cross(Z, s) for s in paper_002_conditions(cfg)[2:]])
        change = np.linalg.lstsq(couples.T, C[:, 3:].T, rcond=None)[0]  # C_moments = change.T @ couples
        assert np.linalg.det(E) == pytest.approx(np.linalg.det(change) * eq6, rel=1e-8)


def test_constraint_singularity_is_invisible_to_A():
    pose = singular_pose(0)  # a root of paper 002's Eq. (6)
    cfg, analysis, result = single(H4, pose)
    eq6, eq7, _, _ = paper_002_conditions(cfg)
    assert abs(eq6) < 1e-12 and abs(np.linalg.det(paper_wrench_matrix(cfg))) < 1e-9  # 6×6 sees it
    assert result.det_A == pytest.approx(-eq7, rel=1e-8) and abs(result.det_A) > 1.0  # det A does not
    assert result.type == "regular" and result.closeness["direct"] > 0.01
    report = classify_analysis(analysis)
    assert report.labels == ("constraint",) and report.gained_dof == 1
    # the gained twist is no Schoenflies motion: it lies outside the span of A's basis
    gained = report.uncontrolled_twists[0]
    scale = np.array([1, 1, 1, 1 / 500, 1 / 500, 1 / 500])
    basis = result.twist_basis * scale
    residual = gained * scale - np.linalg.lstsq(basis.T, gained * scale, rcond=None)[0] @ basis
    assert np.linalg.norm(residual) > 0.1 * np.linalg.norm(gained * scale)


def test_actuation_singularity_is_seen_by_both():
    pose = singular_pose(1)  # a root of paper 002's Eq. (7)
    cfg, analysis, result = single(H4, pose)
    eq6, eq7, _, _ = paper_002_conditions(cfg)
    assert abs(eq7) < 1e-9 and abs(eq6) > 1e-3
    assert abs(result.det_A) < 1e-9 and result.type == "direct"
    assert abs(np.linalg.det(paper_wrench_matrix(cfg))) < 1e-9
    assert classify_analysis(analysis).labels == ("actuation",)


# hand derivation: the slider-crank ------------------------------------------------------------------
def slider_crank_screws(theta):
    pins = np.stack([np.cos(theta), np.sin(theta), 0 * theta], axis=-1)
    sliders = np.stack([pins[..., 0] + np.sqrt(4 - pins[..., 1] ** 2), 0 * theta, 0 * theta], axis=-1)
    return {
        "A": np.broadcast_to(S.revolute_twist(Z, [0, 0, 0]), (*theta.shape, 1, 6)),
        "R1": S.revolute_twist(Z, pins)[..., None, :],
        "R2": S.revolute_twist(Z, sliders)[..., None, :],
        "P": np.broadcast_to([0, 0, 0, 1.0, 0, 0], (*theta.shape, 1, 6)),
    }


def slider_crank_graph(screws=None, index=()):
    screws = screws or slider_crank_screws(np.array(1.0))
    joints = {"A": revolute("A", Z, [0, 0, 0], actuated=True), "P": prismatic("P", [1, 0, 0])}
    for name in ("R1", "R2"):
        row = screws[name][index][0]
        joints[name] = revolute(name, row[:3], np.cross(row[:3], row[3:]))
    return twist_graph("ground", "slider", [("ground", "crank", joints["A"]), ("crank", "coupler", joints["R1"]),
                                            ("coupler", "slider", joints["R2"]), ("ground", "slider", joints["P"])],
                       dof=1)


def test_slider_crank_hand_derivation(rng):
    # x = cos θ + sqrt(4 - sin²θ) (crank 1, coupler 2), so dx/dθ = -sin θ (1 + cos θ / sqrt(4 - sin²θ)).
    theta = np.concatenate([rng.uniform(-3, 3, 20), [0.0, np.pi]])
    screws = slider_crank_screws(theta)
    result = jacobians_over_poses(slider_crank_graph(), screws, [[0, 0, 0, 1, 0, 0]])
    expected = -np.sin(theta) * (1 + np.cos(theta) / np.sqrt(4 - np.sin(theta) ** 2))
    np.testing.assert_allclose(result.B[:, 0, 0] / result.A[:, 0, 0], expected, atol=1e-12)
    assert result.types.tolist() == ["regular"] * 20 + ["inverse", "inverse"]
    assert np.all(result.B >= 0)
    for k in (0, 20):
        graph = slider_crank_graph(screws, (k,))
        one = jacobians_from_wrenches(wrench_analysis(graph), [[0, 0, 0, 1, 0, 0]])
        assert one.type == result.types[k]
        np.testing.assert_allclose(one.A, result.A[k], atol=1e-12)


def test_non_square_A_has_no_kinematic_jacobian():
    # one actuated slider along x carrying a passive slider along y: dof 2, one actuator
    graph = twist_graph("B", "E", [("B", "L", prismatic("P1", [1, 0, 0], actuated=True)),
                                   ("L", "E", prismatic("P2", [0, 1, 0]))], dof=2)
    basis = [[0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0]]
    result = jacobians_from_wrenches(wrench_analysis(graph), basis)
    np.testing.assert_allclose(result.A, [[1.0, 0.0]], atol=1e-12)
    assert result.type == "direct" and result.closeness["direct"] == 0.0  # y is uncontrolled
    with pytest.raises(ScrewkitValueError, match=r"Expected a square A for A⁻¹B and det A, got A of shape \(1, 2\)"):
        result.kinematic_jacobian()
    assert result.to_dict()["A"] == [[1.0, 0.0]]
    assert str(result).startswith("direct singularity (Gosselin-Angeles): A 1x2")


def test_schoenflies_basis_known_values():
    basis = schoenflies_basis([[1.0, 2.0, 3.0], [0.0, 0.0, 0.0]], [[0, 0, 1.0], [0, 2.0, 0]])
    assert basis.shape == (2, 4, 6)
    np.testing.assert_array_equal(basis[:, :3, 3:], np.broadcast_to(np.eye(3), (2, 3, 3)))
    np.testing.assert_array_equal(basis[0, 3], [0, 0, 1, 2, -1, 0])  # (k; p × k)
    np.testing.assert_array_equal(basis[1, 3], [0, 2, 0, 0, 0, 0])
    assert GOSSELIN_ANGELES_TYPES == ("regular", "inverse", "direct", "combined")


# invariance (hypothesis) --------------------------------------------------------------------------------
@functools.cache
def invariance_inputs():
    poses = np.vstack([random_poses(np.random.default_rng(11), 3), singular_pose(1), case_b_pose()])
    cfg, graph, screws = batch_inputs(H4, poses)
    return graph, screws, basis_of(cfg), jacobians_over_poses(graph, screws, basis_of(cfg))


def moved(rows, rotation, translation, factor):
    out = S.transform(rows, rotation, translation)
    out[..., 3:] *= factor
    return out


@settings(max_examples=8)
@given(rigid_motions(), unit_factors)
def test_invariant_under_rigid_motion_and_unit(motion, factor):
    # Moving every screw and the basis by (R, t) and changing the unit by `factor` multiplies every
    # reciprocal product with a unit force by `factor`: A and B scale by it, A⁻¹B and the types do not.
    graph, screws, basis, reference = invariance_inputs()
    rotation, translation = motion
    new_screws = {key: moved(value, rotation, 500 * translation, factor) for key, value in screws.items()}
    result = jacobians_over_poses(graph, new_screws, moved(basis, rotation, 500 * translation, factor))
    assert result.types.tolist() == reference.types.tolist() == ["regular"] * 3 + ["direct", "combined"]
    np.testing.assert_allclose(result.A, factor * reference.A, atol=1e-8 * 375 * factor)
    np.testing.assert_allclose(result.B, factor * reference.B, atol=1e-8 * 375 * factor)
    np.testing.assert_allclose(result.wrenches[..., :3], reference.wrenches[..., :3] @ rotation.T, atol=1e-8)
    for key in ("direct", "inverse"):
        np.testing.assert_allclose(result.closeness[key], reference.closeness[key], rtol=1e-6, atol=1e-12)


@settings(max_examples=3)
@given(seeds)
def test_row_scaling_convention(seed):
    # every row is a unit force (|f| = 1) with B_jj >= 0, at any pose
    poses = central_poses(QUATTRO, np.random.default_rng(seed), 10)
    _, result = batch(QUATTRO, poses)
    np.testing.assert_allclose(np.linalg.norm(result.wrenches[..., :3], axis=-1), 1.0)
    assert np.all(np.diagonal(result.B, axis1=-2, axis2=-1) > 0)


# errors: one per message ----------------------------------------------------------------------------------
@functools.cache
def h4_regular():
    cfg = inverse_kinematics(H4, [30.0, -20.0, -750.0, 0.3])
    return cfg, wrench_analysis(joints(cfg).graph())


def test_error_analysis_type():
    with pytest.raises(ScrewkitTypeError, match="Expected `analysis` to be a WrenchAnalysis, got dict"):
        jacobians_from_wrenches({}, np.eye(6)[:4])


@pytest.mark.parametrize("name", ["rtol", "basis_rtol"])
def test_error_tolerance(name):
    cfg, analysis = h4_regular()
    with pytest.raises(ScrewkitValueError, match=rf"Expected `{name}` to be a number in \[0, 0\.1\], got 2"):
        jacobians_from_wrenches(analysis, basis_of(cfg), **{name: 2})


def test_error_basis_shape():
    _, analysis = h4_regular()
    with pytest.raises(ScrewkitValueError, match=r"Expected `twist_basis` to have shape \(\.\.\., 4, 6\), one twist per"):
        jacobians_from_wrenches(analysis, np.zeros((3, 6)))


def test_error_basis_not_finite():
    cfg, analysis = h4_regular()
    basis = basis_of(cfg).copy()
    basis[0, 0] = np.nan
    with pytest.raises(ScrewkitValueError, match="Expected `twist_basis` to hold finite numbers"):
        jacobians_from_wrenches(analysis, basis)


def test_error_basis_dependent():
    cfg, analysis = h4_regular()
    basis = basis_of(cfg).copy()
    basis[1] = 2 * basis[0]
    with pytest.raises(ScrewkitValueError, match=r"Expected the 4 rows of `twist_basis` to be independent twists, got rank 3"):
        jacobians_from_wrenches(analysis, basis)


def test_error_basis_outside_the_platform_twists():
    cfg, analysis = h4_regular()
    basis = basis_of(cfg).copy()
    basis[3] = S.revolute_twist([1.0, 0, 0], cfg.pose[:3])  # a tilt: no Schoenflies motion
    with pytest.raises(ScrewkitValueError, match=r"Expected `twist_basis` to lie in the platform's twist system, got a twist with a relative residual"):
        jacobians_from_wrenches(analysis, basis)
    poses = np.array([[30.0, -20.0, -750.0, 0.3], [0.0, 0.0, -700.0, 0.0]])
    cfg, graph, screws = batch_inputs(H4, poses)
    tilted = basis_of(cfg).copy()
    tilted[1, 3] = S.revolute_twist([1.0, 0, 0], cfg.pose[1, :3])
    with pytest.raises(ScrewkitValueError, match=r"outside it at batch indices \[\(1,\)\]"):
        jacobians_over_poses(graph, screws, tilted)


def limb_with_a_loop_through_the_actuator():
    """Two paths through the actuated joint A (B-X-A-Y-E and B-Y-A-X-E) close a loop through it."""
    return twist_graph("B", "E", [
        ("B", "X", spherical("S0", [0, 0, 0])), ("X", "Y", revolute("A", Z, [1, 0, 0], actuated=True)),
        ("Y", "E", spherical("S3", [2, 1, 0])), ("B", "Y", spherical("S6", [2, -1, 0.5])),
        ("X", "E", spherical("S7", [1, 2, 0.3])),
    ])


def test_error_actuated_joint_in_a_loop_of_its_limb():
    graph = limb_with_a_loop_through_the_actuator()
    analysis = wrench_analysis(graph)
    twist = analysis.platform_twists.basis[: analysis.dof]
    with pytest.raises(TwistGraphError, match="Expected actuated joint 'A' to be in series in its limb"):
        jacobians_from_wrenches(analysis, twist)
    screws = {key: joint.screws[None] for _, _, key, joint in graph.edges(keys=True, data="joint")}
    with pytest.raises(TwistGraphError, match="Expected actuated joint 'A' to be in series in its limb"):
        jacobians_over_poses(graph, screws, twist)


def test_error_batch_basis_shape(rng):
    cfg, graph, screws = batch_inputs(H4, random_poses(rng, 3))
    with pytest.raises(ScrewkitValueError, match=r"Expected `twist_basis` to have shape \(..., 4, 6\) broadcastable to the batch shape \(3,\), got \(2, 4, 6\)"):
        jacobians_over_poses(graph, screws, basis_of(cfg)[:2])


def test_error_batch_dof(rng):
    cfg, graph, screws = batch_inputs(H4, random_poses(rng, 2))
    with pytest.raises(TwistGraphError, match=r"Expected `dof` to be an integer in 0\.\.6, got 7"):
        jacobians_over_poses(graph, screws, basis_of(cfg), dof=7)


def test_error_batch_actuated_joint_off_the_paths():
    graph = twist_graph("B", "E", [("B", "E", revolute("R", Z, [0, 0, 0])),
                                   ("B", "X", revolute("A", Z, [1, 0, 0], actuated=True))], dof=1)
    screws = {key: joint.screws[None] for _, _, key, joint in graph.edges(keys=True, data="joint")}
    with pytest.raises(TwistGraphError, match="Actuated joint 'A' lies on no path from the base to the platform"):
        jacobians_over_poses(graph, screws, [[0, 0, 1, 0, 0, 0]])


def test_error_batch_kinematic_jacobian_at_a_singular_pose(rng):
    _, result = batch(H4, np.vstack([random_poses(rng, 2), singular_pose(1)]))
    with pytest.raises(DegenerateGeometryError, match=r"A⁻¹B does not exist at 1 poses of the batch \(first batch indices \[\(2,\)\]\)"):
        result.kinematic_jacobian()


def test_error_schoenflies_zero_axis():
    with pytest.raises(DegenerateGeometryError, match=r"Expected `axis` to be a non-zero direction, got \[0.0, 0.0, 0.0\]"):
        schoenflies_basis([0, 0, 0], [0, 0, 0])


def test_result_is_read_only_and_serialisable():
    cfg, analysis = h4_regular()
    result = jacobians_from_wrenches(analysis, basis_of(cfg))
    with pytest.raises(ValueError, match="read-only"):
        result.A[0, 0] = 1.0
    data = result.to_dict()
    assert data["type"] == "regular" and len(data["A"]) == 4 and data["actuated_joints"][0] == "A1"
    assert nx.utils.graphs_equal(result.analysis.graph, analysis.graph)


def test_a_pose_out_of_reach_is_typed_unreachable_never_regular():
    # a batch's pose out of reach has NaN matrices (screwkit.robots.pose_batch.reached_view): its
    # type says so, its closeness and determinants are NaN, and no singularity is claimed there
    A = np.stack([np.eye(2), np.full((2, 2), np.nan), np.diag([1.0, 0.0])])
    B = np.stack([np.diag([2.0, 3.0]), np.full((2, 2), np.nan), np.eye(2)])
    jac = Jacobians(A, B)
    assert jac.types.tolist() == ["regular", "unreachable", "direct"]
    assert jac.reached.tolist() == [True, False, True]
    assert np.isnan(jac.closeness["direct"][1]) and np.isnan(jac.closeness["inverse"][1])
    assert jac.closeness["direct"][2] == 0.0 and jac.closeness["inverse"][0] == pytest.approx(2 / 3)
    det_a, det_b = jac.det_A, jac.det_B
    assert det_a[0] == 1.0 and np.isnan(det_a[1]) and det_a[2] == 0.0
    assert det_b[0] == 6.0 and np.isnan(det_b[1]) and det_b[2] == 1.0
    assert jac.direct.tolist() == [False, False, True] and jac.inverse.tolist() == [False, False, False]
    assert jac[1].type == "unreachable" and jac[1].to_dict()["B"] == [[None, None], [None, None]]
