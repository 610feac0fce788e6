"""The papers' Jacobians against those derived from the wrench systems (``jacobians_from_wrenches``).

Ours: ``A_w χ̇ = B_w θ̇`` with ``χ̇`` the rates of the pose coordinates (the family's twist basis),
``θ̇`` the actuated joints' rates in sorted joint-name order, rows the actuation wrenches as unit
forces signed so that ``B_w ≥ 0`` (``screwkit.core.jacobians``). Each paper uses its own variables; the
relations below are derived by hand and hold identically at every regular pose:

* **McGill SMG, paper 001, Eqs. (16)-(19)**: ``A t = B θ̇`` with ``t = (φ̇, ṗ/L) = T χ̇`` and 6×4
  matrices. Then ``A T = M A_w`` and ``B = M B_w`` with the 6×4 matrix
  ``M = -(l3/L²) blockdiag_J [pan_J ρ̂_J3, elbow_J f_J]`` (``ρ̂_J3`` the unit distal-link direction,
  ``f_J`` the hinge axis, ``pan_J = sgn κ_J`` and ``elbow_J = sgn sin θ_J3`` the working mode).
  Derivation: the components of leg ``J``'s three equations along ``f_J`` and ``ρ_J3`` are
  ``-ρ_J3·σ̇_J = Δ_J θ̇_J2`` and ``|ρ_J3|² f_J·σ̇_J = -(κ_J/L)|ρ_J3|² θ̇_J1`` (with ``v_J =
  -(κ_J/L) ρ_J3``), i.e. the tilt's and the pan's actuation-force equations (forces along the distal
  link, and along ``f_J`` through the wrist axis; ``B_w`` = ``l2 |sin θ_J3|`` and ``|κ_J|``); the
  component along ``φ_J = f_J × ρ_J3`` is ``0 = 0`` identically. ``M`` has orthogonal columns of
  norm ``l3/L²``, so the paper's redundant system has the same solutions as ours, and
  ``A_w = (L²/l3)² Mᵀ A T``.
* **Peppermill, paper 000, Eq. (47)**: ``A δx = B δθ`` with the same ``δx`` as ours and
  ``δθ = (δd_1, δd_2, r_1 δθ_1, r_2 δθ_2)``. Then ``A_w = D Π A`` and ``B_w = D Π B R Πᵀ``, with
  ``Π`` the row permutation to ``(1.slide, 1.turn, 2.slide, 2.turn)``, ``R = diag(1, 1, r_1, r_2)``
  and ``D = diag(1, sgn sin λ_1, 1, sgn sin λ_2)`` (the working mode). The rows are equal, not only
  proportional: the turn's actuation wrench is ``(v_i; P_i × v_i + (p_i/2π) v_iz k)`` modulo the
  limb's couple, whose products with the basis are ``[v_iᵀ, (p_i/2π) v_iz]``.
* **Planar 3-RRP, paper 003, Eq. (11)**: ``J θ̇ + K t = 0`` with ``t = (ω, ẋ, ẏ) = P χ̇`` (its ``J``
  multiplies the actuator rates). Then ``J = D B_w`` and ``K P = -D A_w``, ``D = diag(σ_k)`` (the
  working mode, the signs of ``J_kk``): our rows are the Kennedy lines through the elbows, normal to
  the guides.

At the singular poses located by tests/robots/test_two_limb_catalog.py and tests/robots/test_planar_catalog.py the
Gosselin–Angeles types agree; at the parallel ones the relations still hold and give the same
uncontrolled motion; at the serial ones the same actuator is the stuck one. (At a serial pose the
limb's twist system drops, so the other actuation wrenches of that limb are only defined modulo a
new constraint wrench: there only the other limbs' rows obey the relation, which is checked too.)
"""

from __future__ import annotations

import numpy as np
import pytest

from screwkit.core.jacobians import jacobians_from_wrenches
from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import UnreachablePoseError
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families import families
from screwkit.robots.families import peppermill as pm
from screwkit.robots.families.mcgill_smg.configuration import McGillConfiguration
from screwkit.robots.families.mcgill_smg.kinematics import inverse_kinematics
from screwkit.robots.families.mcgill_smg.parameters import LEGS, WORKING_MODES
from screwkit.robots.families.planar_3rrp.configuration import Planar3RRPConfiguration
from screwkit.robots.families.planar_3rrp.kinematics import WORKING_MODES as PLANAR_MODES
from screwkit.robots.families.planar_3rrp.kinematics import forward_kinematics

from .. import paper_000, paper_001, paper_003
from ..facts_two_limb import singular_configs
from ..robots import test_planar_catalog as planar_catalog

MCGILL = load_mechanism("mcgill_smg")
PEPPERMILL = load_mechanism("peppermill")
PLANAR = load_mechanism("planar_3rrp")

# the located planar singularities (fixtures of tests/robots/test_planar_catalog.py, reused as they are)
inverse_singular = planar_catalog.inverse_singular
direct_singular = planar_catalog.direct_singular
combined_singular = planar_catalog.combined_singular


def ours(name, config, rtol=1e-9):
    """The wrench-derived Jacobians of a configuration over its family's twist basis."""
    family = families()[name]
    graph = family.joints(config).graph()
    return jacobians_from_wrenches(wrench_analysis(graph, rtol=rtol), family.twist_basis(config))


def null_vector(matrix: np.ndarray) -> np.ndarray:
    vector = np.linalg.svd(matrix)[2][-1]
    return vector / vector[np.argmax(np.abs(vector))]


def close(a, b, scale):
    return np.abs(np.asarray(a) - np.asarray(b)).max() <= 1e-9 * scale


# --------------------------------------------------------------------------------------------------
# McGill SMG (paper 001)
# --------------------------------------------------------------------------------------------------

L = MCGILL.parameters.radius  # the default length_scale of paper_001.jacobians (paper 001's L)
#: t = (φ̇, ṗ/L) = T χ̇ with χ̇ = (ẋ, ẏ, ż, φ̇) (Eqs. 14, 17b)
T = np.zeros((4, 4))
T[0, 3], T[1:, :3] = 1.0, np.eye(3) / L
#: Boxes where each pair of pan branches (pan_I, pan_II) reaches (found by sampling; (1, -1), the
#: catalog's, reaches its whole workspace). The elbow branches do not change the reach.
PAN_BOXES = {
    (1, -1): [MCGILL.workspace[c] for c in MCGILL.pose_names],
    (1, 1): [(-500, 500), (0, 700), (-700, 300), (-3, 3)],
    (-1, -1): [(-500, 500), (-700, 0), (-700, 300), (-3, 3)],
    (-1, 1): [(-200, 80), (-60, 40), (-300, 200), (0, 1)],
}


def mcgill_m(config: McGillConfiguration) -> np.ndarray:
    """M = -(l3/L²) blockdiag_J [pan_J ρ̂_J3, elbow_J f_J], from the geometry and the working mode."""
    m = np.zeros((6, 4))
    l3 = MCGILL.parameters.l3
    for leg in range(2):
        pan, elbow = config.mode[2 * leg], config.mode[2 * leg + 1]
        distal = config.wrist[leg] - config.elbow[leg]
        m[3 * leg:3 * leg + 3, 2 * leg] = -(l3 / L**2) * pan * distal / np.linalg.norm(distal)
        m[3 * leg:3 * leg + 3, 2 * leg + 1] = -(l3 / L**2) * elbow * config.tilt_axis[leg]
    return m


def mcgill_poses(mode, rng, count):
    """Random poses reachable in a working mode (rejection sampling in its pan pair's box)."""
    low, high = np.array(PAN_BOXES[mode[0], mode[2]], dtype=float).T
    configs = []
    for pose in rng.uniform(low, high, (40 * count, 4)):
        try:
            configs.append(inverse_kinematics(MCGILL.parameters, pose, mode))
        except UnreachablePoseError:
            continue
        if len(configs) == count:
            return configs
    raise AssertionError(f"mode {mode}: fewer than {count} reachable poses in the box")


@pytest.mark.parametrize("mode", WORKING_MODES)
def test_mcgill_paper_jacobians_are_m_times_ours(mode, rng):
    for config in mcgill_poses(mode, rng, 2):
        paper, wrench = paper_001.jacobians(config), ours("mcgill_smg", config)
        assert wrench.type == str(paper_001.classify(config).types) == "regular"
        m = mcgill_m(config)
        assert close(paper.A @ T, m @ wrench.A, np.abs(paper.A).max())
        assert close(paper.B, m @ wrench.B, np.abs(paper.B).max())
        # the third equation of each leg (along φ_J = f_J × ρ_J3) is void: 6 equations, rank 4
        phi = np.cross(config.tilt_axis, config.wrist - config.elbow)
        for leg in range(2):
            rows = slice(3 * leg, 3 * leg + 3)
            assert close(phi[leg] @ paper.A[rows], 0.0, np.abs(paper.A).max() * L)
            assert close(phi[leg] @ paper.B[rows], 0.0, np.abs(paper.B).max() * L)
        # so the same kinematic map: our χ̇ = A_w⁻¹ B_w θ̇ solves the paper's six equations
        assert close(paper.A @ T @ wrench.kinematic_jacobian(), paper.B, np.abs(paper.B).max())


MCGILL_CASES = {  # located pose -> (type, the stuck actuator)
    "serial_pan": ("inverse", "I.pan"),
    "serial_tilt": ("inverse", "I.proximal.a"),
    "direct": ("direct", None),
    "combined": ("combined", "I.proximal.a"),
}


@pytest.mark.parametrize("kind", MCGILL_CASES)
def test_mcgill_types_agree_at_the_located_singularities(kind):
    config = singular_configs(MCGILL)[kind]
    paper, wrench = paper_001.jacobians(config), ours("mcgill_smg", config, rtol=1e-7)
    expected, stuck = MCGILL_CASES[kind]
    assert wrench.type == str(paper_001.classify(config, rtol=1e-7).types) == expected
    m = mcgill_m(config)
    if stuck is None:  # the relation holds, and gives the same motion with the actuators locked
        assert close(paper.A @ T, m @ wrench.A, np.abs(paper.A).max())
        np.testing.assert_allclose(null_vector(wrench.A), null_vector(paper.A @ T), atol=1e-6)
    else:  # the same actuator is stuck; leg II (regular) still obeys the relation
        assert wrench.serial_limbs == (stuck,)
        assert LEGS[int(np.argmax(np.abs(null_vector(paper.B))) // 2)] == "I"
        assert wrench.actuated_joints[int(np.argmax(np.abs(null_vector(paper.B))))] == stuck
        assert close(paper.A[3:] @ T, m[3:] @ wrench.A, np.abs(paper.A).max())
        assert close(paper.B[3:], m[3:] @ wrench.B, np.abs(paper.B).max())


# --------------------------------------------------------------------------------------------------
# Peppermill (paper 000)
# --------------------------------------------------------------------------------------------------

#: Our rows (1.slide, 1.turn, 2.slide, 2.turn) are the paper's rows (d1, d2, θ1, θ2) in this order.
PI = np.eye(4)[[0, 2, 1, 3]]


def peppermill_relation(config, wrench):
    paper = paper_000.jacobians(config)
    params = config.params
    d = np.diag([1.0, config.mode[0], 1.0, config.mode[1]])
    r = np.diag([1.0, 1.0, params.r1, params.r2])
    assert close(wrench.A, d @ PI @ paper.A, np.abs(paper.A).max())
    assert close(wrench.B, d @ PI @ paper.B @ r @ PI.T, params.r1 + params.r2)
    return paper, d, r


def peppermill_configs(rng):
    """Random workspace poses in the four working modes, and the four assembly modes of one set of
    actuator values (forward kinematics, Eqs. 32-33 completed)."""
    poses = PEPPERMILL.random_poses(rng, 2)
    configs = [pm.inverse_kinematics(PEPPERMILL.parameters, pose, mode) for mode in pm.WORKING_MODES for pose in poses]
    actuated = pm.inverse_kinematics(PEPPERMILL.parameters, poses[0]).actuated
    solutions = pm.forward_kinematics(PEPPERMILL.parameters, actuated)
    assert solutions.valid.all()
    for pose, mode in zip(solutions.poses, solutions.working_modes, strict=True):
        config = pm.inverse_kinematics(PEPPERMILL.parameters, pose, tuple(int(s) for s in mode))
        np.testing.assert_allclose(config.actuated, actuated, atol=1e-9)
        configs.append(config)
    assert {tuple(np.sign(c.v[:, 2]).astype(int)) for c in configs} == set(pm.ASSEMBLY_MODES)
    return configs


def test_peppermill_paper_jacobians_equal_ours_up_to_signs_order_and_r(rng):
    for config in peppermill_configs(rng):
        wrench = ours("peppermill", config)
        assert wrench.type == str(paper_000.classify(config).types) == "regular"
        paper, _, r = peppermill_relation(config, wrench)
        # the same kinematic map: δx = A⁻¹B δθ with δθ = R Πᵀ θ̇
        np.testing.assert_allclose(wrench.kinematic_jacobian(), np.linalg.solve(paper.A, paper.B) @ r @ PI.T,
                                   rtol=1e-9, atol=1e-9)


PEPPERMILL_CASES = {"serial_turn": ("inverse", "1.turn"), "direct": ("direct", None), "combined": ("combined", "1.turn")}


@pytest.mark.parametrize("kind", PEPPERMILL_CASES)
def test_peppermill_types_agree_at_the_located_singularities(kind):
    config = singular_configs(PEPPERMILL)[kind]
    wrench = ours("peppermill", config, rtol=1e-7)
    expected, stuck = PEPPERMILL_CASES[kind]
    assert wrench.type == str(paper_000.classify(config, rtol=1e-7).types) == expected
    paper = paper_000.jacobians(config)
    if stuck is None:
        peppermill_relation(config, wrench)
        np.testing.assert_allclose(null_vector(wrench.A), null_vector(paper.A), atol=1e-6)
    else:
        assert wrench.serial_limbs == (stuck,)
        r = np.diag([1.0, 1.0, config.params.r1, config.params.r2])
        null = null_vector(PI @ paper.B @ r @ PI.T)  # in our actuator order
        assert wrench.actuated_joints[int(np.argmax(np.abs(null)))] == stuck
        # limb 2's rows (the regular limb) still obey the relation
        d = np.diag([1.0, config.mode[0], 1.0, config.mode[1]])
        assert close(wrench.A[2:], (d @ PI @ paper.A)[2:], np.abs(paper.A).max())


# --------------------------------------------------------------------------------------------------
# Planar 3-RRP (paper 003)
# --------------------------------------------------------------------------------------------------

#: t = (ω, ẋ, ẏ) = P χ̇ with χ̇ = (ẋ, ẏ, φ̇)
P = np.eye(3)[[2, 0, 1]]


def planar_relation(config, wrench):
    j, k = paper_003.jacobians(config)
    d = np.diag(np.sign(np.diag(j)))
    assert close(j, d @ wrench.B, PLANAR.parameters.length_scale)
    assert close(k @ P, -d @ wrench.A, PLANAR.parameters.length_scale)
    return j, k


def test_planar_paper_jacobians_equal_ours_up_to_the_working_mode(rng):
    poses = PLANAR.random_poses(rng, 2)
    cases = [(Planar3RRPConfiguration.from_pose(PLANAR.parameters, pose, mode), mode)
             for mode in PLANAR_MODES for pose in poses]
    theta = cases[0][0].joint_angles  # and both assembly modes of one set of actuator values
    solutions = forward_kinematics(PLANAR.parameters, theta)
    cases += [(Planar3RRPConfiguration(PLANAR.parameters, pose, theta), None)
              for pose, valid in zip(solutions.poses, solutions.valid, strict=True) if valid]
    assert len(cases) == 18
    for config, mode in cases:
        wrench = ours("planar_3rrp", config)
        assert wrench.type == str(paper_003.classify(config).kind) == "regular"
        j, k = planar_relation(config, wrench)
        # D is the working mode (σ_k = sgn J_kk), and the same kinematic map t = -K⁻¹J θ̇
        if mode is not None:
            np.testing.assert_array_equal(np.sign(np.diag(j)), mode)
        np.testing.assert_allclose(P @ wrench.kinematic_jacobian(), -np.linalg.solve(k, j), rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize(("case", "expected"), [("inverse", "inverse"), ("direct", "direct"), ("combined", "combined")])
def test_planar_types_agree_at_the_located_singularities(case, expected, request):
    config = request.getfixturevalue(f"{case}_singular")
    wrench = ours("planar_3rrp", config)
    assert wrench.type == str(paper_003.classify(config).kind) == expected
    j, k = paper_003.jacobians(config)
    if expected == "direct":
        planar_relation(config, wrench)
        np.testing.assert_allclose(null_vector(wrench.A), null_vector(k @ P), atol=1e-6)
    else:  # limb 1 is stuck (J_11 = 0); limbs 2, 3 still obey the relation
        assert wrench.serial_limbs == ("limb1_R1",) and abs(j[0, 0]) < 1e-9
        d = np.sign(np.diag(j))[1:, None]
        assert close(k[1:] @ P, -d * wrench.A[1:], PLANAR.parameters.length_scale)
