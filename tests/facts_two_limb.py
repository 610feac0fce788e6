"""Family-specific [[expected]] facts of the two-limb SMGs (mcgill_smg.toml, peppermill.toml).

``FACTS = {fact: check(mechanism, fact) -> (got, expected)}`` (see ``tests/robots/test_catalog.py``). Each
check *computes* its answer (ranks, determinants, labels at poses found by root searches); nothing
is read back from the code under test's own printout.

The singular poses of each kind are found here by bisection on a singularity factor along a
segment, and shared with ``tests/robots/test_two_limb_catalog.py``:

* McGill SMG (paper 001): serial ``κ_I = 0`` (bisection on leg I's distal angle), serial
  ``sin θ_I3 = 0`` (leg I extended), parallel (``det[φ_I, φ_II, k × (σ_I − σ_II)] = 0`` along a turn
  of the plate from the default pose), combined (leg I extended, the plate turned about ``O_I3``);
* Peppermill (paper 000): first kind ``sin λ_1 = 0`` (forward kinematics along ``θ_1``), second kind
  ``v_1z = 0`` (inverse kinematics along ``y``), third kind (limb 1 extended, then the plate moved
  with ``q_1`` fixed until ``v_2z = 0``).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import numpy as np

from screwkit.core.jacobian_matrices import gosselin_angeles_label
from screwkit.core.singularity import classify as classify_graph
from screwkit.core.wrenches import wrench_analysis
from screwkit.gca.diagram_points import diagram_points
from screwkit.gca.superbracket_analysis import superbracket_analysis
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families import peppermill as pm
from screwkit.robots.families.mcgill_smg.configuration import McGillConfiguration, leg_pose
from screwkit.robots.families.mcgill_smg.kinematics import inverse_kinematics
from screwkit.robots.families.mcgill_smg.parameters import McGillParameters

from . import paper_000, paper_001
from .two_limb_papers import bisect_segment

# --------------------------------------------------------------------------------------------------
# McGill SMG: singular poses
# --------------------------------------------------------------------------------------------------


def mcgill_leg_one(params: McGillParameters, angles: Any, mode_two: tuple[int, int] = (-1, -1)):
    """Both legs at the pose set by leg I's joint angles (Eq. 1); leg I's mode from its angles."""
    angles = np.asarray(angles, dtype=float)
    t2, t3 = angles[1], angles[2]
    kappa = params.l1 + params.l2 * np.cos(t2) + params.l3 * np.cos(t2 + t3)
    mode = (1 if kappa >= 0 else -1, 1 if np.sin(t3) >= 0 else -1, *mode_two)
    return inverse_kinematics(params, leg_pose(params, "I", angles), mode)


def _on_leg_one(params: McGillParameters, factor: Callable[[Any], Any],
                start: list[float], end: list[float], mode_two: tuple[int, int] = (-1, -1)):
    """Bisection on leg I's joint angles for a sign change of ``factor(config)``."""

    def values(angles: np.ndarray) -> np.ndarray:
        rows = angles.reshape(-1, 4)
        out = [factor(mcgill_leg_one(params, row, mode_two)) for row in rows]
        return np.array(out).reshape(angles.shape[:-1])

    return mcgill_leg_one(params, bisect_segment(values, start, end), mode_two)


def mcgill_singular_configs(params: McGillParameters, default_pose: Any) -> dict[str, Any]:
    """Configurations at singularities of each kind (for the catalog's dimensions)."""
    deg = np.radians
    factors = paper_001.singularity_factors
    turned = np.array(default_pose, dtype=float)
    return {
        # O_I3 on the pan axis (κ_I = 0), leg I's distal link 25-30° from the vertical
        "serial_pan": _on_leg_one(params, lambda c: factors(c).reach[0],
                                  [0.2, deg(-150), deg(60), 0.3], [0.2, deg(-150), deg(90), 0.3]),
        # leg I fully extended (Δ_I = 0, Fig. 7c)
        "serial_tilt": _on_leg_one(params, lambda c: factors(c).delta[0],
                                   [0.1, deg(-60), 0.2, np.pi], [0.1, deg(-60), -0.2, np.pi]),
        # the plate turned from the default pose until A loses rank
        "direct": inverse_kinematics(params, paper_001.locate_direct_singularity(
            params, turned, turned + np.array([0.0, 0.0, 0.0, deg(80)]))),
        # leg I extended and the plate turned about O_I3 until A loses rank as well
        "combined": _on_leg_one(params, lambda c: factors(c).parallel,
                                [0.0, deg(-50), 0.0, deg(55)], [0.0, deg(-50), 0.0, deg(60)]),
    }


# --------------------------------------------------------------------------------------------------
# Peppermill: singular poses
# --------------------------------------------------------------------------------------------------

#: Forward-kinematics slot (sgn v_1z, sgn v_2z) = (-1, -1): both distal links descend to the plate.
HANGING = pm.ASSEMBLY_MODES.index((-1, -1))


def peppermill_singular_configs(params: pm.PeppermillParameters, default_pose: Any) -> dict[str, Any]:
    """Configurations at singularities of the three kinds (for the catalog's dimensions)."""
    home = pm.inverse_kinematics(params, default_pose)
    start, end = home.actuated.copy(), home.actuated.copy()
    start[2], end[2] = np.radians(-100.0), np.radians(-90.0)

    def sin_lambda_one(actuated: np.ndarray) -> np.ndarray:
        passive = np.asarray(pm.forward_kinematics(params, actuated).passive.data)
        return np.sin(passive[..., HANGING, 0])

    actuated = bisect_segment(sin_lambda_one, start, end)
    extended = np.asarray(pm.forward_kinematics(params, actuated).poses.data)[HANGING]
    lead = params.p1 / (2.0 * np.pi)

    def keeping_q1(t: np.ndarray) -> np.ndarray:
        # x = 300 and (dz, dφ) = (-p_1/2π, 1) dt leave q_1 (Eq. 20), hence limb 1, unchanged
        t = np.asarray(t)[..., 0]
        pose = np.broadcast_to(extended, (*t.shape, 4)).copy()
        pose[..., 0] = 300.0
        pose[..., 2] -= lead * t
        pose[..., 3] += t
        return pose

    def v2z(t: np.ndarray) -> np.ndarray:
        return pm.inverse_kinematics(params, keeping_q1(t), (1, -1)).v[..., 1, 2]

    t = bisect_segment(v2z, [-21.75], [-21.5])
    return {
        "serial_turn": pm.inverse_kinematics(params, extended),
        "direct": pm.inverse_kinematics(params, paper_000.locate_direct_singularity(
            params, [0.0, 150.0, -150.0, 0.0], [0.0, 300.0, -150.0, 0.0])),
        "combined": pm.inverse_kinematics(params, keeping_q1(t), (1, -1)),
    }


# --------------------------------------------------------------------------------------------------
# Shared: configurations by mechanism, labels
# --------------------------------------------------------------------------------------------------


@functools.lru_cache(maxsize=8)
def _singular(family: str, params: Any, pose: tuple[float, ...]) -> dict[str, Any]:
    if family == "mcgill_smg":
        return mcgill_singular_configs(params, pose)
    if family == "peppermill":
        return peppermill_singular_configs(params, pose)
    raise AssertionError(f"no singular poses for family {family!r}")


def singular_configs(mechanism: Any) -> dict[str, Any]:
    """The located singular configurations of a catalog mechanism (cached)."""
    return _singular(mechanism.family, mechanism.parameters, tuple(mechanism.default_pose))


def family_module(mechanism: Any) -> Any:
    """The robot model: the :class:`~screwkit.robots.families.Family` of the McGill SMG or the Peppermill."""
    return mechanism.family_protocol


def paper_module(mechanism: Any) -> Any:
    """The paper's own Jacobians and their classification: :mod:`tests.paper_001` or :mod:`tests.paper_000`."""
    return {"mcgill_smg": paper_001, "peppermill": paper_000}[mechanism.family]


def labels(mechanism: Any, config: Any, *, rtol: float = 1e-9) -> tuple[Any, str]:
    """(twist-graph report, the paper's Jacobian label) at a configuration."""
    report = classify_graph(family_module(mechanism).joints(config).graph(), rtol=rtol)
    return report, str(paper_module(mechanism).classify(config, rtol=rtol).types)


# --------------------------------------------------------------------------------------------------
# Checks
# --------------------------------------------------------------------------------------------------


def _nonzero_columns(block: np.ndarray) -> list[int]:
    return [block.shape[0], int(np.any(block != 0.0, axis=0).sum())]


def check_jacobian_shapes(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """Shapes of A and B; for McGill also of the leg blocks A_J, B_J (their non-zero columns)."""
    config = mechanism.configuration()
    jac = paper_module(mechanism).jacobians(config)
    got: dict[str, list[Any]] = {"A": list(jac.A.shape), "B": list(jac.B.shape)}
    if mechanism.family == "mcgill_smg":
        # leg I's rows: A_I acts on all of t; B_I only on (θ_I1, θ_I2) (Eq. 19's zero blocks)
        got["A_J"] = _nonzero_columns(jac.A[:3])
        got["B_J"] = _nonzero_columns(jac.B[:3])
        if _nonzero_columns(jac.B[3:]) != got["B_J"] or np.any(jac.B[3:, :2] != 0.0):
            got["B_J"] = ["leg II's block is not where Eq. (19) puts it"]
    return got, fact["value"]


def check_det_a(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """Peppermill Eq. (48): det A = v_1z v_2z (p_2 − p_1)/2π at random poses, every working mode."""
    params = mechanism.parameters
    poses = mechanism.random_poses(np.random.default_rng(0), 20)
    for mode in pm.WORKING_MODES:
        config = pm.inverse_kinematics(params, poses, mode)
        expected = config.v[:, 0, 2] * config.v[:, 1, 2] * (params.p2 - params.p1) / (2 * np.pi)
        got = np.linalg.det(paper_000.jacobians(config).A)
        if not np.allclose(got, expected, rtol=1e-12, atol=1e-12 * abs(params.p2 - params.p1)):
            return f"differs in mode {mode}: {got[:2]} vs {expected[:2]}", fact["value"]
    return fact["value"], fact["value"]


def check_det_b(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """Peppermill: det B = sin λ_1 sin λ_2 at random poses, every working mode."""
    poses = mechanism.random_poses(np.random.default_rng(1), 20)
    for mode in pm.WORKING_MODES:
        config = pm.inverse_kinematics(mechanism.parameters, poses, mode)
        got = np.linalg.det(paper_000.jacobians(config).B)
        if not np.allclose(got, np.prod(np.sin(config.passive), axis=-1), rtol=0, atol=1e-12):
            return f"differs in mode {mode}", fact["value"]
    return fact["value"], fact["value"]


#: The condition that holds at each located serial singularity (for leg/limb 1, i.e. I).
_SERIAL_CONDITIONS = {
    "mcgill_smg": {"serial_pan": "kappa_J = 0", "serial_tilt": "sin theta_J3 = 0"},
    "peppermill": {"serial_turn": "sin lambda_i = 0"},
}
_ROLES = {"I.pan": "pan", "I.proximal.a": "tilt", "1.turn": "turn", "1.slide": "slide"}


def check_serial_joint(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """At each located serial singularity: which actuator the twist graph finds disabled."""
    configs = singular_configs(mechanism)
    got = {}
    for key, condition in _SERIAL_CONDITIONS[mechanism.family].items():
        report, _ = labels(mechanism, configs[key])
        got[condition] = "+".join(_ROLES.get(s.actuated_joint, s.actuated_joint) for s in report.serial)
    return got, fact["value"]


def check_twist_graph_labels(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """``{twist-graph labels joined by '+': the family's Jacobian label}`` at the located poses."""
    got: dict[str, str] = {}
    for config in singular_configs(mechanism).values():
        report, jacobian = labels(mechanism, config, rtol=1e-7)
        key = "+".join(report.labels)
        if got.get(key, jacobian) != jacobian:
            jacobian = f"both {got[key]} and {jacobian}"
        got[key] = jacobian
    report, jacobian = labels(mechanism, mechanism.configuration())
    got["+".join(report.labels) or "regular"] = jacobian
    return got, fact["value"]


def check_paper_eq_22(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """McGill: is φ_I ∥ φ_II (Eq. 22) necessary? At the located parallel singularity it fails."""
    config = singular_configs(mechanism)["direct"]
    f, rho3 = config.tilt_axis, config.wrist - config.elbow
    phi = np.cross(f, rho3)
    sine = np.linalg.norm(np.cross(phi[0], phi[1])) / np.prod(np.linalg.norm(phi, axis=-1))
    singular = paper_001.classify(config).types == "direct"
    return {"necessary": bool(singular and sine < 1e-6), "direct_singular_here": bool(singular)}, fact["value"]


def check_fig_7(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """McGill Figs. 7(a), 7(b): O_I0, O_I2, O_I3 aligned; distal link vertical. Labels there."""
    params = mechanism.parameters

    def alignment(config: Any) -> float:
        # (O_I2 - O_I0) × (O_I3 - O_I2) · f_I: zero when O_I0, O_I2, O_I3 are aligned (Eq. 21a)
        a = config.elbow[0] - config.pan_point[0]
        b = config.wrist[0] - config.elbow[0]
        return float(np.dot(np.cross(a, b), config.tilt_axis[0]))

    def vertical(config: Any) -> float:  # ρ_I3 · e(θ_I1): zero when the distal link is vertical
        along = np.cross(config.pan_axis[0], config.tilt_axis[0])
        return float(np.dot(config.wrist[0] - config.elbow[0], along))

    deg = np.radians
    fig_7a = _on_leg_one(params, alignment, [0.0, deg(-130), deg(20), 0.0], [0.0, deg(-130), deg(60), 0.0])
    fig_7b = _on_leg_one(params, vertical, [0.0, deg(-130), deg(20), 0.0], [0.0, deg(-130), deg(60), 0.0])
    got = {}
    for name, config in (("7a", fig_7a), ("7b", fig_7b)):
        report, jacobian = labels(mechanism, config)
        got[name] = gosselin_angeles_label(report) if gosselin_angeles_label(report) == jacobian else "disagree"
    return got, fact["value"]


# --------------------------------------------------------------------------------------------------
# Superbracket (screwkit.interface.report.analyze)
# --------------------------------------------------------------------------------------------------


@functools.lru_cache(maxsize=4)
def superbracket(source: str) -> tuple[Any, Any]:
    """The wrench diagram and superbracket analysis of an entry at its default pose (cached)."""
    mechanism = load_mechanism(source)
    diagram, sampler = mechanism.wrench_diagram()
    return diagram, superbracket_analysis(diagram, sampler)


def condition_values(mechanism: Any, configs: list[Any]) -> np.ndarray:
    """Each superbracket condition's vector form at the given configurations, ``(n, factors)``."""
    diagram, result = superbracket(mechanism.source)
    family = family_module(mechanism)
    rows = []
    for config in configs:
        points = diagram_points(diagram.points, wrench_analysis(family.joints(config).graph()))
        rows.append([float(c.evaluate(points)) for c in result.conditions])
    return np.array(rows)


def random_configs(mechanism: Any, count: int = 8, seed: int = 3) -> list[Any]:
    poses = mechanism.random_poses(np.random.default_rng(seed), count)
    return [mechanism.configuration(pose) for pose in poses]


def direct_factor(config: Any) -> float:
    """The Jacobian's direct factor: McGill det[φ_I, φ_II, ½ k × (σ_I − σ_II)]; Peppermill det A."""
    if isinstance(config, McGillConfiguration):
        return float(paper_001.singularity_factors(config).parallel)
    return float(paper_000.singularity_factors(config).det_a)


def check_superbracket_factor_labels(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """The labels of the factors of the simplified superbracket, in order."""
    return list(superbracket(mechanism.source)[1].labels), fact["value"]


def _column(mechanism: Any, label: str) -> int:
    columns = [i for i, x in enumerate(superbracket(mechanism.source)[1].labels) if x == label]
    assert len(columns) == 1, columns
    return columns[0]


def check_superbracket_constraint_never_vanishes(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """The constraint factor is ±1 (three orthonormal directions) at random workspace poses and at
    the located parallel singularity: the two horizontal constraint couples never degenerate."""
    configs = [*random_configs(mechanism), singular_configs(mechanism)["direct"]]
    values = condition_values(mechanism, configs)[:, _column(mechanism, "constraint")]
    return bool(np.allclose(np.abs(values), 1.0, rtol=0, atol=1e-12)), fact["value"]


def check_superbracket_actuation_factor(mechanism: Any, fact: dict[str, Any]) -> tuple[Any, Any]:
    """|actuation factor| over the Jacobian's |direct factor| times a hand-derived scale at random
    poses (McGill: ``2 R³ / l3²``, unit directions in the diagram against ``|φ_J| = l3 / R`` with
    ``L = R``; Peppermill: 1), and whether the factor vanishes at the located parallel singularity."""
    configs = random_configs(mechanism)
    values = condition_values(mechanism, configs)[:, _column(mechanism, "actuation")]
    params = mechanism.parameters
    scale = 2 * params.radius**3 / params.l3**2 if mechanism.family == "mcgill_smg" else 1.0
    ratio = np.abs(values) / (scale * np.abs([direct_factor(c) for c in configs]))
    singular = condition_values(mechanism, [singular_configs(mechanism)["direct"]])[0]
    vanishes = abs(singular[_column(mechanism, "actuation")]) < 1e-12 * np.abs(values).max()
    constant = np.ptp(ratio) <= 1e-9
    return {"factor_over_formula": float(np.round(ratio.mean(), 9)) if constant else "not constant",
            "zero_at_parallel_singularity": bool(vanishes)}, fact["value"]


FACTS = {
    "two_limb_jacobian_shapes": check_jacobian_shapes,
    "det_a_factors": check_det_a,
    "det_b_factors": check_det_b,
    "two_limb_serial_singular_joint": check_serial_joint,
    "two_limb_twist_graph_labels": check_twist_graph_labels,
    "paper_eq_22_necessary": check_paper_eq_22,
    "paper_fig_7_labels": check_fig_7,
    "two_limb_superbracket_factor_labels": check_superbracket_factor_labels,
    "two_limb_superbracket_constraint_factor_never_vanishes": check_superbracket_constraint_never_vanishes,
    "two_limb_superbracket_actuation_factor": check_superbracket_actuation_factor,
}
