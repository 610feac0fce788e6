"""Compound legs analysed as a whole (screwkit.core._compound_legs.compound_legs): the H4 where the plane of
a parallelogram of sub-platform ``b_I`` contains the vertical.

Expected values come from outside the core: paper 004's Eq. (12) ``|A| = 2r (w_14 × w_23)·s`` and
Eq. (8) ``h_i = b w_i·(u_i × v_i)`` written out here; paper 002's Eq. (7)
(:func:`tests.robots.test_h4.paper_002_conditions`); the wrenches each leg transmits with its arms locked,
written out from the parallelograms' geometry, with their 6×6 rank from numpy's SVD; the nacelle's
spin about ``R_I`` checked against the parallelograms' wrenches by hand; and finite differences of
the inverse kinematics (``dθ/dχ = B⁻¹A``).
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.algebra import screw as S
from screwkit.core.singularity import classify
from screwkit.core.wrench_systems import analyze_table
from screwkit.robots.families.four_limb.kinematics import reachable

from ..mechanisms import bisect_root
from ..robots.test_h4 import moved_graph, normals, paper_002_conditions, paper_wrench_matrix
from ..strategies import rigid_motions, unit_factors

H4 = sk.load_mechanism("h4")
Z = np.array([0.0, 0.0, 1.0])
LEG_I, LEG_II = (0, 3), (1, 2)  # paper 004's limbs on b_I and b_II (0-based)
#: Found by the workspace loci (tests/analysis/test_workspace.py): n1·z ~ 1e-10, paper 004 |A| = -47.9;
#: refined to machine precision on z by bisection (module scope, below).
FOUND = np.array([300.0, 300.0, -473.8000726, np.radians(30.0)])
UP = np.array([0.0, 0.0, 1.0, 0.0])


def plane_normals_z(pose):
    return normals(H4.configuration(pose))[..., 2]


VERTICAL = FOUND + UP * (bisect_root(lambda z: plane_normals_z(FOUND + z * UP)[0], -1e-3, 1e-3))


@pytest.fixture(scope="module")
def both_vertical():
    """A pose with n1·z = n4·z = 0, by Newton's method on (x, z) from a pose found by sampling."""
    y, phi = 426.2, 1.1
    v = np.array([376.9, -807.8])

    def f(v):
        n = plane_normals_z(np.array([v[0], y, v[1], phi]))
        return np.array([n[0], n[3]])

    for _ in range(12):
        jacobian = np.column_stack([(f(v + e) - f(v - e)) / 2e-4 for e in np.eye(2) * 1e-4])
        v = v - np.linalg.solve(jacobian, f(v))
    pose = np.array([v[0], y, v[1], phi])
    assert np.abs(f(v)).max() < 1e-14
    return pose


def paper_004_det_A(cfg):
    """Paper 004 Eq. (12): |A| = 2r (w_14 × w_23)·s, w_ij = w_i × w_j."""
    w = cfg.w
    w14, w23 = np.cross(w[..., 0, :], w[..., 3, :]), np.cross(w[..., 1, :], w[..., 2, :])
    return 2 * 80.0 * np.einsum("...i,...i", np.cross(w14, w23), cfg.platform_s)


def paper_004_h(cfg):
    """Paper 004 Eq. (8): h_i = b w_i·(u_i × v_i), b = 375 mm."""
    return 375.0 * np.einsum("...i,...i", cfg.w, np.cross(cfg.u, cfg.v))


def rod_forces(cfg, limbs):
    """Unit forces along each limb's rods through its sub-platform corner."""
    return [S.line(cfg.w[i], cfg.platform_corners[i, 0]) for i in limbs]


def locked_leg_wrenches(cfg, limbs, axis_point):
    """The wrenches a leg R-(4S) ∥ R-(4S) — R transmits with both arms locked, written out:
    each parallelogram i transmits the forces along its rods F_i and the couple C_i about its
    plane's normal n_i; R (axis z through `axis_point`) passes those of zero moment about it. With
    b the limb whose n_b·z ≠ 0: C_{z × (n_a × n_b)}, F_a − (m_a / n_b·z) C_b, F_b − (m_b / n_b·z) C_b
    (m_i = F_i ∘ R)."""
    n = normals(cfg)
    a, b = sorted(limbs, key=lambda i: abs(n[i, 2]))
    spin = S.revolute_twist(Z, axis_point)
    forces = dict(zip(limbs, rod_forces(cfg, limbs), strict=True))
    couple_b = S.couple(n[b])
    rows = [S.couple(np.cross(Z, np.cross(n[a], n[b])))]
    for i in (a, b):
        moment = S.reciprocal_product(forces[i], spin)
        rows.append(forces[i] - moment / n[b, 2] * couple_b)
    return np.array(rows)


def scaled_singular_values(rows, length=1000.0):
    out = np.array(rows, dtype=float)
    out[..., 3:] /= length
    return np.linalg.svd(out / np.linalg.norm(out, axis=-1, keepdims=True), compute_uv=False)


# --- the pose where n1·z = 0 is regular ------------------------------------------------------------


def test_vertical_plane_pose_is_regular_by_papers_002_and_004():
    cfg = H4.configuration(VERTICAL)
    assert abs(plane_normals_z(VERTICAL)[0]) < 1e-15
    assert abs(paper_004_det_A(cfg)) > 40 and (np.abs(paper_004_h(cfg)) > 200).all()
    _, eq7, _, _ = paper_002_conditions(cfg)
    assert abs(eq7) > 40
    # the six wrenches the legs transmit with the four arms locked: rank 6
    rows = np.concatenate([
        locked_leg_wrenches(cfg, LEG_I, cfg.platform_joint_points[0]),
        locked_leg_wrenches(cfg, LEG_II, cfg.platform_joint_points[1]),
    ])
    for leg, axis in ((slice(0, 3), 0), (slice(3, 6), 1)):  # each reciprocal to its R axis
        spin = S.revolute_twist(Z, cfg.platform_joint_points[axis])
        assert np.abs(S.reciprocal_product(rows[leg], spin)).max() < 1e-9
    values = scaled_singular_values(rows)
    assert values[-1] / values[0] > 1e-2
    # the per-limb choice: limb 1's force along its rods through R_I's axis goes to infinity and
    # becomes C_n1, leg I's constraint couple: the six per-limb wrenches would have rank 5
    assert np.linalg.norm(np.cross(rows[0, 3:] / np.linalg.norm(rows[0, 3:]), normals(cfg)[0])) < 1e-12


def test_core_calls_the_vertical_plane_pose_regular_with_papers_jacobians():
    cfg = H4.configuration(VERTICAL)
    posed = H4.at(VERTICAL[None])
    assert posed.codes[0] == 0
    report = posed.singularities[0]
    assert report.global_order == 6 and not report.analysis.serial.any()
    jac = H4.jacobians(VERTICAL)
    assert jac.type == "regular"
    assert jac.det_A == pytest.approx(paper_004_det_A(cfg), rel=1e-9)
    # B = D B_paper with D = -I (jacobians module docstring): B_jj = -h_j
    np.testing.assert_allclose(np.diag(jac.B), -paper_004_h(cfg), rtol=1e-9)
    np.testing.assert_array_equal(jac.B, np.diag(np.diag(jac.B)))  # loads its own actuator only
    # limb 1's wrench loads A1 alone: a force along its rods plus a couple about n4 (not a line)
    wrench = report.analysis.actuation_rows[0]
    assert np.linalg.norm(np.cross(wrench[:3], cfg.w[0])) < 1e-9
    assert abs(S.pitch(wrench)) > 1.0
    # its part on A1's own branch is what arm 1 receives: paper 004's |cos μ_i| = |h_i| / b (Eq. 11)
    np.testing.assert_allclose(posed.wrench_transmission.input[0], np.abs(paper_004_h(cfg)) / 375.0, rtol=1e-9)


def test_kinematic_jacobian_matches_finite_differences_of_the_inverse_kinematics():
    jac = H4.jacobians(VERTICAL)
    steps = np.array([1e-4, 1e-4, 1e-4, 1e-7])
    expected = np.empty((4, 4))
    for k, step in enumerate(steps):
        e = np.zeros(4)
        e[k] = step
        plus, minus = H4.configuration(VERTICAL + e).theta, H4.configuration(VERTICAL - e).theta
        expected[:, k] = (plus - minus) / (2 * step)
    got = np.linalg.solve(jac.B, jac.A)  # dθ/dχ = B⁻¹A
    assert np.abs(got - expected).max() < 1e-6 * np.abs(expected).max()


@pytest.mark.parametrize("step", [1e-9, 1e-6, 1e-3, 1.0])
@pytest.mark.parametrize("side", [-1, 1])
def test_poses_beside_the_vertical_plane_are_regular(step, side):
    pose = VERTICAL + side * step * UP
    assert np.sign(plane_normals_z(pose)[0]) == np.sign(side * plane_normals_z(VERTICAL + UP)[0])
    cfg = H4.configuration(pose)
    posed = H4.at(pose[None])
    assert posed.codes[0] == 0
    jac = H4.jacobians(pose)
    assert jac.det_A == pytest.approx(paper_004_det_A(cfg), rel=1e-7)
    np.testing.assert_allclose(np.diag(jac.B), -paper_004_h(cfg), rtol=1e-7)
    # no fake dip of the actuation closeness on approach (it stays near its value on the plane)
    on_plane = H4.at(VERTICAL[None]).closeness["actuation"][0]
    assert posed.closeness["actuation"][0] == pytest.approx(on_plane, rel=0.2 if step == 1.0 else 1e-3)


# --- a genuine serial singularity of the compound leg ---------------------------------------------


def test_both_planes_of_leg_I_vertical_is_a_serial_singularity_of_A1(both_vertical):
    """With n1·z = n4·z = 0 the nacelle's spin about R_I is reciprocal to both parallelograms'
    couples, so it is a motion of leg I with the end effector fixed. Parallelogram 4 allows it
    alone (the spin is reciprocal to its rods' forces too: R_I's axis lies in plane 4), so A4 stays
    locked; parallelogram 1 does not (the spin has a moment about its rods), so A1 must turn: A1
    moves with the platform fixed, a serial singularity of A1 only."""
    cfg = H4.configuration(both_vertical)
    n = normals(cfg)
    spin = S.revolute_twist(Z, cfg.platform_joint_points[0])
    force_1, force_4 = rod_forces(cfg, LEG_I)
    assert abs(S.reciprocal_product(S.couple(n[0]), spin)) < 1e-12
    assert abs(S.reciprocal_product(S.couple(n[3]), spin)) < 1e-12
    assert abs(S.reciprocal_product(force_4, spin)) < 1e-9 * 1000
    assert abs(S.reciprocal_product(force_1, spin)) > 10.0
    report = H4.at(both_vertical[None]).singularities[0]
    assert "serial" in report.labels
    assert [s.actuated_joint for s in report.serial] == ["A1"]
    jac = H4.jacobians(both_vertical)
    assert jac.type in ("inverse", "combined") and jac.serial_limbs == ("A1",)
    assert jac.det_B == 0.0


# --- invariance and parity --------------------------------------------------------------------------


@settings(max_examples=10, deadline=None)
@given(rigid_motions(), unit_factors, st.booleans())
def test_leg_analysis_invariant_under_motion_and_unit(both_vertical, motion, unit_factor, both):
    pose = both_vertical if both else VERTICAL
    graph = H4.twist_graph(pose)
    reference = classify(graph)
    rotation, translation = motion
    report = classify(moved_graph(graph, (rotation, translation * 500), unit_factor))
    assert report.labels == reference.labels
    assert [s.actuated_joint for s in report.serial] == [s.actuated_joint for s in reference.serial]
    assert (report.constraint_order, report.global_order) == (reference.constraint_order, reference.global_order)
    for key in ("constraint", "actuation", "serial"):
        assert report.closeness[key] == pytest.approx(reference.closeness[key], rel=1e-6, abs=1e-9)


def test_single_and_batched_answers_are_bit_identical(both_vertical):
    poses = np.array([[30.0, -20.0, -750.0, 0.3], VERTICAL, VERTICAL + 1e-6 * UP, both_vertical])
    batch = analyze_table(H4.joints(poses))
    for k, pose in enumerate(poses):
        one = analyze_table(H4.joints(pose[None]))
        for field in ("serial", "transmissions", "actuation_rows", "branch_rows", "global_order"):
            np.testing.assert_array_equal(getattr(batch, field)[k], getattr(one, field)[0], err_msg=field)
        for key, value in batch.closeness.items():
            assert value[k] == one.closeness[key][0], key


def test_leg_partners_are_the_actuators_sharing_a_sub_platform():
    top = analyze_table(H4.joints(VERTICAL[None])).topology
    assert {p.actuated_joint: [top.limbs[k].actuated_joint for k in p.partners] for p in top.limbs} == {
        "A1": ["A4"], "A2": ["A3"], "A3": ["A2"], "A4": ["A1"],
    }
    for name in ("mcgill_smg", "peppermill"):  # their legs' actuators are in series: no partners
        mechanism = sk.load_mechanism(name)
        assert not any(p.partners for p in analyze_table(mechanism.joints()).topology.limbs)


def test_paper_002_superbracket_lines_coincide_on_the_vertical_plane():
    """Paper 002's actuation line of limb 1 (along its rods through the point where they meet R_I's
    axis) is at infinity there, the line of leg I's constraint couple: the six lines' superbracket
    (unit Plücker rows) vanishes at this regular pose. Eq. (7) takes its points from limbs 4 and 3
    only, so ``Eq.(6)·Eq.(7)`` (the paper-normalised determinant) does not; the core's diagram
    reports the pose degenerate (limb 1's wrench has a pitch) rather than singular."""
    cfg = H4.configuration(VERTICAL)
    rows = paper_wrench_matrix(cfg)
    eq6, eq7, _, _ = paper_002_conditions(cfg)
    assert np.linalg.det(rows) == pytest.approx(-eq6 * eq7, rel=1e-9) and abs(eq6 * eq7) > 0.5
    unit = rows / np.linalg.norm(rows * [1, 1, 1, 1e-3, 1e-3, 1e-3], axis=1, keepdims=True)
    unit[:, 3:] *= 1e-3
    assert abs(np.linalg.det(unit)) < 1e-12
    diagram, _ = H4.wrench_diagram(VERTICAL)
    assert diagram.degenerate and all("actuation A1" in problem for problem in diagram.degenerate)


def test_poses_on_and_beside_every_vertical_plane_are_regular_with_papers_jacobians(rng):
    """Roots of n_i·z = 0 for each limb (bisection along z from random reachable poses, all at once),
    and poses 1e-9 … 1e-3 mm beside them: regular, det A = paper 004 Eq. (12), B = diag(−h_i)."""
    starts = rng.uniform([-400, -400, -1000, -1.5], [400, 400, -450, 1.5], size=(400, 4))
    ends = starts + 60.0 * UP
    keep = reachable(H4.parameters, starts) & reachable(H4.parameters, ends)
    starts, ends = starts[keep], ends[keep]
    roots = []
    for limb in range(4):
        low, high = np.zeros(len(starts)), np.ones(len(starts))
        sign = np.sign(plane_normals_z(starts)[:, limb])
        crossing = sign != np.sign(plane_normals_z(ends)[:, limb])
        for _ in range(60):
            middle = (low + high) / 2
            same = np.sign(plane_normals_z(starts + middle[:, None] * (ends - starts))[:, limb]) == sign
            low, high = np.where(same, middle, low), np.where(same, high, middle)
        roots.append((starts + low[:, None] * (ends - starts))[crossing][:4])
    roots = np.concatenate(roots)
    assert len(roots) >= 8
    poses = np.concatenate([roots + d * UP for d in (-1e-3, -1e-6, -1e-9, 0.0, 1e-9, 1e-6, 1e-3)])
    poses = poses[reachable(H4.parameters, poses)]
    cfg = H4.configuration(poses)
    assert (np.abs(normals(cfg)[..., 2]).min(axis=-1) < 1e-5).all()
    posed = H4.at(poses)
    assert (posed.codes == 0).all()
    jac = posed.jacobians
    np.testing.assert_allclose(jac.det_A, paper_004_det_A(cfg), rtol=1e-6)
    np.testing.assert_allclose(np.diagonal(jac.B, axis1=-2, axis2=-1), -paper_004_h(cfg), rtol=1e-8)
