"""The McGill SMG (paper 001) and Peppermill (paper 000) catalog entries through their twist graphs.

Known values: the joint and loop counts of the physical mechanisms, the Schönflies twist system,
each leg's constraint couples, the actuation lines of Eqs. (9)-(11) (paper 001) and (43) (paper
000). Invariants: labels against the families' Jacobian classification (``A t = B θ̇``), units,
the unpublished dimensions. Singular poses of each kind are found by bisection
(:mod:`tests.facts_two_limb`); the uncontrolled twist there is the null vector of ``A``.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json
import math

import numpy as np
import pytest

from screwkit.algebra import screw as S
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.algebra.screwvalue import Screw
from screwkit.core.jacobian_matrices import gosselin_angeles_label
from screwkit.core.singularity import classify
from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import CatalogError, ScrewkitValueError
from screwkit.gca.diagram_recipes import wrench_diagram
from screwkit.graphs.jointtable import JointTable
from screwkit.graphs.loops import fundamental_loops
from screwkit.graphs.reduction import equivalent_twist_graph, platform_twist_system
from screwkit.interface.cli import main
from screwkit.interface.report import analyze
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families import peppermill as pm
from screwkit.robots.families.mcgill_smg.configuration import McGillConfiguration
from screwkit.robots.families.mcgill_smg.joints import joints
from screwkit.robots.families.mcgill_smg.kinematics import inverse_kinematics
from screwkit.robots.families.mcgill_smg.parameters import DEFAULT_MODE, LEGS

from ..facts_two_limb import family_module, labels, paper_module, singular_configs
from ..two_limb_papers import bisect_segment

MCGILL = load_mechanism("mcgill_smg")
PEPPERMILL = load_mechanism("peppermill")
ROBOTS = {"mcgill_smg": MCGILL, "peppermill": PEPPERMILL}
K = np.array([0.0, 0.0, 1.0])
#: 3T1R about the vertical: the three translations and a rotation about z.
SCHOENFLIES = np.array([[0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1], [0, 0, 1, 0, 0, 0]], float)
HORIZONTAL_COUPLES = SCHOENFLIES[:2]


def meets(line: np.ndarray, point: np.ndarray, direction: np.ndarray, scale: float) -> bool:
    """Whether a zero-pitch wrench's line meets (or is parallel to) the line (point, direction)."""
    other = S.line(direction, point)
    product = line[:3] @ other[3:] + line[3:] @ other[:3]
    return bool(abs(product) <= 1e-9 * scale * np.linalg.norm(line[:3]))


def parallel(a: np.ndarray, b: np.ndarray) -> bool:
    return bool(np.linalg.norm(np.cross(a, b)) <= 1e-9 * np.linalg.norm(a) * np.linalg.norm(b))


# --------------------------------------------------------------------------------------------------
# The physical twist graphs
# --------------------------------------------------------------------------------------------------


def test_mcgill_twist_graph_has_four_parallelogram_loops_per_two_legs():
    graph = MCGILL.twist_graph()
    assert (graph.number_of_nodes(), graph.number_of_edges(), graph.graph["dof"]) == (16, 20, 4)
    assert len(fundamental_loops(graph)) == 5  # four parallelograms and the loop through both legs
    actuated = sorted(key for *_, key, joint in graph.edges(keys=True, data="joint") if joint.actuated)
    assert actuated == ["I.pan", "I.proximal.a", "II.pan", "II.proximal.a"]
    assert {joint.type for *_, joint in graph.edges(data="joint")} == {"R"}
    # the equivalent graph replaces each Π loop by one virtual translation, normal to the hinges
    # f_J and to the parallelogram's long links (paper 001's Π joint)
    config = MCGILL.configuration()
    equivalent = equivalent_twist_graph(graph)
    virtual = {key: joint for *_, key, joint in equivalent.edges(keys=True, data="joint") if joint.virtual}
    assert sorted(j.type for j in virtual.values()) == ["vP"] * 4
    links = {"I.carrier~I.elbow": (0, config.elbow[0] - config.shoulder[0]),
             "I.elbow~I.wrist": (0, config.wrist[0] - config.elbow[0]),
             "II.carrier~II.elbow": (1, config.elbow[1] - config.shoulder[1]),
             "II.elbow~II.wrist": (1, config.wrist[1] - config.elbow[1])}
    for key, joint in virtual.items():
        leg, rod = links[key[key.index("[") + 1:-1]]
        velocity = joint.screws[0, 3:]
        assert parallel(velocity, np.cross(config.tilt_axis[leg], rod))


def test_peppermill_twist_graph_is_one_loop_with_coaxial_screws():
    graph = PEPPERMILL.twist_graph()
    assert (graph.number_of_nodes(), graph.number_of_edges(), graph.graph["dof"]) == (10, 10, 4)
    assert len(fundamental_loops(graph)) == 1
    kinds = sorted(joint.type for *_, joint in graph.edges(data="joint"))
    assert kinds == ["H", "H", "P", "P", "R", "R", "R", "R", "R", "R"]
    actuated = sorted(key for *_, key, joint in graph.edges(keys=True, data="joint") if joint.actuated)
    assert actuated == ["1.slide", "1.turn", "2.slide", "2.turn"]
    assert not any(joint.virtual for *_, joint in equivalent_twist_graph(graph).edges(data="joint"))
    # the two H joints: axis k through C (Eq. 11), pitches -p_i/2π of opposite hands (Sec. 4.3)
    params, centre = PEPPERMILL.parameters, PEPPERMILL.default_pose[:3]
    for limb, lead in (("1", params.p1), ("2", params.p2)):
        screw = graph.edges[f"{limb}.nut", "platform", f"{limb}.screw"]["joint"].screws[0]
        assert S.pitch(screw) == pytest.approx(-lead / (2 * np.pi), rel=1e-12)
        point, direction = S.axis(screw)
        assert parallel(direction, K) and np.allclose(point[:2], centre[:2], rtol=0, atol=1e-9)


@pytest.mark.parametrize("name", ["mcgill_smg", "peppermill"])
def test_platform_twist_system_is_schoenflies_at_random_poses(name, rng):
    mechanism = ROBOTS[name]
    modes = pm.WORKING_MODES if name == "peppermill" else (DEFAULT_MODE,)
    for index, pose in enumerate(mechanism.random_poses(rng, 6)):
        graph = family_module(mechanism).joints(
            mechanism.configuration(pose, mode=modes[index % len(modes)])).graph()
        for method in ("loop_closure", "reduction"):
            system = platform_twist_system(graph, method=method)
            assert system.order == 4 and system.is_equivalent(ScrewSystem.span(SCHOENFLIES)), method


def test_each_mcgill_leg_transmits_the_two_horizontal_couples(rng):
    for pose in MCGILL.random_poses(rng, 3):
        analysis = wrench_analysis(MCGILL.twist_graph(pose))
        assert len(analysis.compound_legs) == 2
        for leg in analysis.compound_legs:
            assert leg.twist_system.order == 4
            assert leg.constraint_wrenches.is_equivalent(ScrewSystem.span(HORIZONTAL_COUPLES))
        assert analysis.constraint_wrenches.is_equivalent(ScrewSystem.span(HORIZONTAL_COUPLES))


def test_each_peppermill_limb_transmits_one_couple_along_a_i_cross_k(rng):
    couples = {"1": np.cross([1.0, 0, 0], K), "2": np.cross([0, 1.0, 0], K)}  # a_1 = i, a_2 = j
    for pose in PEPPERMILL.random_poses(rng, 3):
        analysis = wrench_analysis(PEPPERMILL.twist_graph(pose))
        for leg in analysis.compound_legs:
            limb = leg.joints[0][0]
            assert all(joint.startswith(limb) for joint in leg.joints)
            assert leg.twist_system.order == 5
            expected = ScrewSystem.span([np.concatenate([np.zeros(3), couples[limb]])])
            assert leg.constraint_wrenches.is_equivalent(expected)


def test_mcgill_actuation_wrenches_are_the_lines_of_eqs_9_to_11(rng):
    # pan J: a force along f_J meeting the wrist axis (it does no work on the tilt, the distal Π
    # or the wrist); tilt J: a force along the distal link O_J2 O_J3 (no work on the pan, the distal
    # Π, the wrist, nor the far hinges of the proximal Π)
    for pose in MCGILL.random_poses(rng, 3):
        config = MCGILL.configuration(pose)
        scale = MCGILL.parameters.l2
        for limb in wrench_analysis(joints(config).graph()).limbs:
            leg = LEGS.index(limb.actuated_joint.split(".")[0])
            wrench = limb.actuation_wrench
            assert abs(S.pitch(wrench)) < 1e-9 * scale
            if limb.actuated_joint.endswith("pan"):
                assert parallel(wrench[:3], config.tilt_axis[leg])
                assert meets(wrench, config.wrist_joint[leg], K, scale)
            else:
                distal = config.wrist[leg] - config.elbow[leg]
                assert parallel(wrench[:3], distal)
                assert meets(wrench, config.elbow[leg], config.tilt_axis[leg], scale)
                assert meets(wrench, config.wrist[leg], config.tilt_axis[leg], scale)


def test_peppermill_actuation_wrenches_are_the_lines_of_eq_43(rng):
    # slide i: a force along a_i through the plate axis (δd_i = a_i · δc); turn i: a force along the
    # distal link v_i meeting the elbow and wrist axes (r_i v_i · u_θi δθ_i = v_i · δc + ...)
    for pose in PEPPERMILL.random_poses(rng, 3):
        config = PEPPERMILL.configuration(pose)
        scale = PEPPERMILL.parameters.l1
        for limb in wrench_analysis(pm.joints(config).graph()).limbs:
            index = int(limb.actuated_joint[0]) - 1
            wrench, axis = limb.actuation_wrench, config.drive_axis[index]
            assert abs(S.pitch(wrench)) < 1e-9 * scale
            if limb.actuated_joint.endswith("slide"):
                assert parallel(wrench[:3], axis)
                assert meets(wrench, config.platform_point, K, scale)
            else:
                assert parallel(wrench[:3], config.v[index])
                assert meets(wrench, config.elbow[index], axis, scale)
                assert meets(wrench, config.wrist[index], axis, scale)


# --------------------------------------------------------------------------------------------------
# The operational workspace
# --------------------------------------------------------------------------------------------------


def box_corners(mechanism) -> np.ndarray:
    bounds = [mechanism.workspace[c] for c in mechanism.pose_names]
    return np.array(np.meshgrid(*bounds, indexing="ij")).reshape(4, -1).T


@pytest.mark.parametrize("name", ["mcgill_smg", "peppermill"])
def test_workspace_is_reachable_and_free_of_singularities(name, rng):
    mechanism = ROBOTS[name]
    family = family_module(mechanism)
    poses = np.vstack([mechanism.random_poses(rng, 2000), box_corners(mechanism)])
    modes = pm.WORKING_MODES if name == "peppermill" else (DEFAULT_MODE,)
    for mode in modes:
        config = family.inverse_kinematics(mechanism.parameters, poses, mode)  # raises if out of reach
        result = paper_module(mechanism).classify(config)
        assert np.all(result.types == "regular")
        assert result.closeness["direct"].min() > 0.05 and result.closeness["inverse"].min() > 0.2
        if name == "mcgill_smg":
            factors = paper_module(mechanism).singularity_factors(config)
            assert len(np.unique(np.sign(factors.parallel))) == 1
            # no flat parallelogram: long links at least 10° away from the (vertical) short sides
            for lower, upper in ((config.shoulder, config.elbow), (config.elbow, config.wrist)):
                rod = upper - lower
                sine = np.linalg.norm(np.cross(rod, K), axis=-1) / np.linalg.norm(rod, axis=-1)
                assert sine.min() > np.sin(np.radians(10))
    # the twist graph agrees at a sample of them
    for pose in poses[:6]:
        report, jacobian = labels(mechanism, mechanism.configuration(pose))
        assert report.labels == () and jacobian == "regular"


# --------------------------------------------------------------------------------------------------
# Singular poses of each kind (found by bisection in tests/facts_two_limb.py)
# --------------------------------------------------------------------------------------------------

SINGULAR_CASES = [
    ("mcgill_smg", "serial_pan", ("serial",), "I.pan"),
    ("mcgill_smg", "serial_tilt", ("serial",), "I.proximal.a"),
    ("mcgill_smg", "direct", ("actuation",), None),
    ("mcgill_smg", "combined", ("actuation", "serial"), "I.proximal.a"),
    ("peppermill", "serial_turn", ("serial",), "1.turn"),
    ("peppermill", "direct", ("actuation",), None),
    ("peppermill", "combined", ("actuation", "serial"), "1.turn"),
]
#: Actuated joints in the order of θ̇ in A t = B θ̇ (paper 001 Eq. 19; paper 000 Eq. 44).
B_COLUMNS = {"mcgill_smg": ("I.pan", "I.proximal.a", "II.pan", "II.proximal.a"),
             "peppermill": ("1.slide", "2.slide", "1.turn", "2.turn")}


def platform_twist_from_a(mechanism, config) -> np.ndarray:
    """The null vector of A as a twist (ω; v_O): the motion left with the actuators locked."""
    jac = paper_module(mechanism).jacobians(config)
    null = np.linalg.svd(jac.A)[2][-1]
    if mechanism.family == "mcgill_smg":  # t = (φ̇, ṗ/L) with L = R (Eq. 17b)
        rate, velocity = null[0], null[1:] * mechanism.parameters.radius
    else:  # δx = (δx, δy, δz, δφ) (Eq. 46)
        rate, velocity = null[3], null[:3]
    omega = rate * K
    return np.concatenate([omega, velocity - np.cross(omega, config.pose[:3])])


@pytest.mark.parametrize(("name", "kind", "expected", "serial_joint"), SINGULAR_CASES)
def test_singular_poses_are_labelled_like_the_jacobians(name, kind, expected, serial_joint):
    mechanism = ROBOTS[name]
    config = singular_configs(mechanism)[kind]
    report, jacobian = labels(mechanism, config, rtol=1e-7)
    assert report.labels == expected
    assert gosselin_angeles_label(report) == jacobian
    jac = paper_module(mechanism).jacobians(config)
    if "serial" in expected:
        # the platform loses a freedom, and the disabled actuator is B's null direction
        assert report.lost_dof == 1 and [s.actuated_joint for s in report.serial] == [serial_joint]
        null = np.linalg.svd(jac.B)[2][-1]
        assert B_COLUMNS[name][int(np.argmax(np.abs(null)))] == serial_joint
        assert np.abs(null).max() > 1 - 1e-6
    if "actuation" in expected:
        # with the actuators locked the plate keeps one twist: the null vector of A
        assert report.uncontrolled_dof == 1 and report.gained_dof == 0
        twist = Screw(platform_twist_from_a(mechanism, config))
        assert twist.is_equivalent(Screw(report.uncontrolled_twists[0]), rtol=1e-6,
                                   length_scale=mechanism.parameters.l2)
    else:
        assert report.uncontrolled_dof == 0


def global_wrench_determinant(mechanism, pose) -> float:
    """|det| of the two horizontal couples and the four actuation wrenches (unit forces): it does
    not depend on which representative (modulo the couples) the analysis picked for each wrench."""
    analysis = wrench_analysis(mechanism.twist_graph(pose))
    assert analysis.constraint_wrenches.is_equivalent(ScrewSystem.span(HORIZONTAL_COUPLES))
    forces = [w / np.linalg.norm(w[:3]) for w in analysis.actuation_wrenches]
    return abs(float(np.linalg.det(np.vstack([HORIZONTAL_COUPLES, *forces]))))


@pytest.mark.parametrize("name", ["mcgill_smg", "peppermill"])
def test_global_wrench_system_degenerates_like_det_a(name):
    # Finite steps h, 2h away from the located parallel singularity: the 6×6 determinant of the
    # global wrench system vanishes to first order, in a constant ratio to the Jacobian's factor.
    mechanism = ROBOTS[name]
    paper = paper_module(mechanism)
    pose = singular_configs(mechanism)["direct"].pose
    step = np.array([0, 0, 0, 1e-4]) if name == "mcgill_smg" else np.array([0, 1e-2, 0, 0])
    near = [pose + h * step for h in (1, 2)]
    wrenches = [global_wrench_determinant(mechanism, p) for p in near]
    jacobian = [abs(float(paper.singularity_factors(mechanism.configuration(p)).parallel
                          if name == "mcgill_smg" else
                          paper.singularity_factors(mechanism.configuration(p)).det_a)) for p in near]
    assert wrenches[0] > 1e-9 and global_wrench_determinant(mechanism, pose) < 1e-9 * wrenches[0] * 1e4
    assert wrenches[1] / wrenches[0] == pytest.approx(2.0, rel=1e-3)
    assert wrenches[1] / jacobian[1] == pytest.approx(wrenches[0] / jacobian[0], rel=1e-3)


def test_peppermill_equal_leads_are_an_actuation_singularity_everywhere(rng):
    # paper 000, Sec. 4.3, condition 2 (architecture singularity): with p1 = p2 the plate screws
    # along its axis relative to both nuts with every actuator locked
    params = dataclasses.replace(PEPPERMILL.parameters, p2=PEPPERMILL.parameters.p1)
    for pose in PEPPERMILL.random_poses(rng, 3):
        graph = pm.joints(pm.inverse_kinematics(params, pose)).graph()
        report = classify(graph)
        assert report.labels == ("actuation",) and report.uncontrolled_dof == 1
        nut = graph.edges["1.nut", "platform", "1.screw"]["joint"].screws[0]
        assert Screw(report.uncontrolled_twists[0]).is_equivalent(Screw(nut), rtol=1e-6,
                                                                     length_scale=params.l1)


# --------------------------------------------------------------------------------------------------
# McGill, Fig. 8: flat parallelograms, and what depends on the short sides we chose
# --------------------------------------------------------------------------------------------------


def distal_pose(x: float, component: str) -> np.ndarray:
    """Default working mode, φ = 0: both distal links horizontal ('v') or vertical ('h')."""

    def value(pose: np.ndarray) -> np.ndarray:
        config = inverse_kinematics(MCGILL.parameters, pose)
        rho3 = config.wrist[..., 0, :] - config.elbow[..., 0, :]
        if component == "v":
            return rho3[..., 2]
        return np.sum(rho3 * np.cross(K, config.tilt_axis[..., 0, :]), axis=-1)

    z = (-600.0, -450.0) if component == "v" else (-968.0, -940.0)
    return bisect_segment(value, [x, 0.0, z[0], 0.0], [x, 0.0, z[1], 0.0])


def tilted_short_sides(config: McGillConfiguration, degrees: float) -> JointTable:
    """The joints with every parallelogram's short sides turned by ``degrees`` from the vertical,
    within the leg plane (the hinges b, d move; the kinematics and A, B do not change)."""
    params, angle = config.params, np.radians(degrees)
    table = joints(config)
    rows = []
    for spec in table.specs:
        leg, part, *tag = spec.name.split(".")
        screws = table.joint_screws(spec.name)
        if tag and tag[0] in "bd":
            index = LEGS.index(leg)
            width = params.proximal_width if part == "proximal" else params.distal_width
            side = np.cos(angle) * K + np.sin(angle) * np.cross(K, config.tilt_axis[index])
            shift = width * side - width * K  # the hinge's point moves by this: (s; r × s) gains shift × s
            direction = screws[..., :3]
            screws = np.concatenate([direction, screws[..., 3:] + np.cross(shift, direction)], axis=-1)
        rows.append((spec.parent, spec.child, spec.name, spec.type, screws, spec.actuated))
    return JointTable.from_rows(table.base, table.platform, rows, dof=table.dof)


def test_fig_8a_flat_parallelograms_are_a_constraint_singularity_of_the_physical_legs():
    # Both distal links vertical with parallel leg planes (x = 0): A is singular (Eq. 24). With
    # vertical short sides both distal parallelograms are flat, each leg lets its plate turn about
    # f_J, and the twist graph finds the platform gaining that rotation: "constraint".
    config = inverse_kinematics(MCGILL.parameters, distal_pose(0.0, "h"))
    assert np.linalg.norm(np.cross(config.tilt_axis[0], config.tilt_axis[1])) < 1e-12
    report, jacobian = labels(MCGILL, config)
    assert report.labels == ("constraint",) and jacobian == "direct"
    assert report.gained_dof == 1 and report.constraint_order == 1
    assert parallel(report.uncontrolled_twists[0][:3], config.tilt_axis[0])
    # with short sides 45° from the vertical no parallelogram is flat: an actuation singularity
    tilted = classify(tilted_short_sides(config, 45.0).graph())
    assert tilted.labels == ("actuation",) and tilted.gained_dof == 0


def test_fig_8_other_cases_are_actuation_singularities():
    for x, component in ((60.0, "h"), (0.0, "v"), (60.0, "v")):
        config = inverse_kinematics(MCGILL.parameters, distal_pose(x, component))
        report, jacobian = labels(MCGILL, config)
        assert report.labels == ("actuation",) and jacobian == "direct", (x, component)


# --------------------------------------------------------------------------------------------------
# What depends on the dimensions we chose
# --------------------------------------------------------------------------------------------------


def wrench_summary(graph):
    report = classify(graph)
    analysis = report.analysis
    constraints = analysis.constraint_wrenches.basis
    spans = [ScrewSystem.span(np.vstack([constraints, limb.actuation_wrench]), length_scale=analysis.length_scale)
             for limb in analysis.limbs if limb.actuation_wrench is not None]
    return report, spans


@pytest.mark.parametrize("widths", [(10.0, 200.0), (300.0, 5.0)])
def test_mcgill_results_do_not_depend_on_the_parallelogram_widths(widths):
    changed = dataclasses.replace(MCGILL.parameters, proximal_width=widths[0], distal_width=widths[1])
    configs = [MCGILL.configuration(), *(singular_configs(MCGILL)[k] for k in ("serial_pan", "direct"))]
    for config in configs:
        other = inverse_kinematics(changed, config.pose, config.mode)
        (one, spans_one), (two, spans_two) = (wrench_summary(joints(c).graph()) for c in (config, other))
        assert two.labels == one.labels
        assert (two.constraint_order, two.global_order) == (one.constraint_order, one.global_order)
        # each actuation wrench is the same line modulo the constraint couples
        assert all(a.is_equivalent(b) for a, b in zip(spans_one, spans_two, strict=True))


@pytest.mark.parametrize(
    ("name", "changes"),
    [("mcgill_smg", {"l0": 600.0, "l1": 100.0, "b4": -150.0, "b5": 20.0}),
     ("peppermill", {"r1": 300.0, "l2": 350.0, "b0": 0.0, "p1": 25.0, "p2": -60.0})],
)
def test_structural_results_hold_for_other_dimensions(name, changes, rng):
    # Our unpublished dimensions place the singular loci (tests/test_families_*.py) but not the
    # reported structure: Schönflies motion, two constraint couples, four actuation lines, and the
    # twist-graph labels agreeing with the Jacobians.
    mechanism = ROBOTS[name]
    params = dataclasses.replace(mechanism.parameters, **changes)
    family, paper = family_module(mechanism), paper_module(mechanism)
    poses = mechanism.random_poses(rng, 4)
    if name == "mcgill_smg":
        poses = poses * [1, 1, 0, 1] + [0, 0, -600.0, 0]  # reachable with l0 = 600, l1 = 100
    for pose in poses:
        config = family.inverse_kinematics(params, pose)
        report = classify(family.joints(config).graph())
        analysis = report.analysis
        scale = analysis.length_scale
        assert analysis.platform_twists.is_equivalent(ScrewSystem.span(SCHOENFLIES))
        assert S.is_infinite_pitch(analysis.constraint_wrenches.basis, length_scale=scale).sum() == 2
        assert S.is_zero_pitch(analysis.actuation_wrenches, length_scale=scale).sum() == 4
        assert gosselin_angeles_label(report) == str(paper.classify(config).types)


@pytest.mark.parametrize("name", ["mcgill_smg", "peppermill"])
def test_labels_and_closeness_do_not_depend_on_the_unit_of_length(name):
    mechanism = ROBOTS[name]
    family = family_module(mechanism)
    for config in (mechanism.configuration(), singular_configs(mechanism)["direct"]):
        metres = family.inverse_kinematics(mechanism.parameters.scaled(1e-3),
                                           config.pose * [1e-3, 1e-3, 1e-3, 1.0], config.mode)
        one, two = classify(family.joints(config).graph()), classify(family.joints(metres).graph())
        assert one.labels == two.labels
        assert (one.constraint_order, one.global_order) == (two.constraint_order, two.global_order)
        # (the actuation closeness needs each actuation wrench's representative modulo the
        # constraint couples to be canonical: screwkit.core.wrenches picks the one orthogonal to them)
        for key in ("constraint", "serial", "actuation"):
            assert two.closeness[key] == pytest.approx(one.closeness[key], rel=1e-6, abs=1e-12)


# --------------------------------------------------------------------------------------------------
# Wrench diagram, report, CLI
# --------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["mcgill_smg", "peppermill"])
def test_diagram_exists_at_the_default_pose_and_degenerates_at_a_serial_singularity(name):
    mechanism = ROBOTS[name]
    diagram, _ = mechanism.wrench_diagram()
    assert diagram.degenerate == () and len(diagram.lines) == 6
    assert diagram.roles.count("actuation") == 4 and diagram.roles.count("constraint") == 2
    serial = next(v for k, v in singular_configs(mechanism).items() if k.startswith("serial"))
    broken = wrench_diagram(wrench_analysis(family_module(mechanism).joints(serial).graph()))
    joint = {"mcgill_smg": "I.pan", "peppermill": "1.turn"}[name]
    assert f"the limb of {joint} is at a serial singularity: it has no actuation wrench" in broken.degenerate


@pytest.fixture(scope="module")
def peppermill_json():
    output = io.StringIO()
    with contextlib.redirect_stdout(output):
        status = main(["analyze", "peppermill", "--json"])
    return status, json.loads(output.getvalue())


def test_cli_analyze_peppermill_json_is_the_library_report(peppermill_json):
    status, printed = peppermill_json
    assert status == 0
    report = analyze("peppermill")
    assert printed == json.loads(json.dumps(report.to_dict(), ensure_ascii=False))
    assert printed["verdict"]["verdict"] == "regular"
    assert printed["superbracket"] is not None and printed["wrenches"]["global_order"] == 6
    assert printed["twist_graph"]["joints"] == {"H": 2, "P": 2, "R": 6}


def test_cli_analyze_mcgill_at_a_pose_and_list(capsys):
    assert main(["analyze", "mcgill_smg", "--pose", "30", "-20", "-790", "10", "--no-superbracket"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("McGill SMG") and "16 links, joints: 20 R; 5 loops" in text
    assert "regular (dof 4)" in text
    pose = np.array([30.0, -20.0, -790.0, math.radians(10.0)])
    assert str(analyze("mcgill_smg", pose, superbracket=False)) == text.rstrip("\n")
    assert main(["list"]) == 0
    listing = capsys.readouterr().out.splitlines()
    assert any(line.startswith("mcgill_smg") and "family mcgill_smg, lengths in mm" in line for line in listing)
    assert any(line.startswith("peppermill") and "family peppermill, lengths in mm" in line for line in listing)


def test_cli_analyze_out_of_reach_names_the_leg(capsys):
    assert main(["analyze", "mcgill_smg", "--pose", "0", "0", "-2000", "0"]) == 1
    assert "Leg I cannot reach the pose" in capsys.readouterr().err


# --------------------------------------------------------------------------------------------------
# Errors
# --------------------------------------------------------------------------------------------------


def test_twist_graph_index_must_pick_one_pose():
    table = joints(MCGILL.configuration(MCGILL.random_poses(np.random.default_rng(0), 2)))
    assert table.graph((1,)).number_of_edges() == 20
    with pytest.raises(ScrewkitValueError, match=r"Expected `index` to pick one configuration of the batch "
                                                 r"of shape \(2,\), got \(2,\)"):
        table.graph((2,))


def test_gosselin_angeles_label_refuses_unknown_labels():
    with pytest.raises(ScrewkitValueError, match=r"Expected labels among .*, got \['locked'\]"):
        gosselin_angeles_label(dataclasses.make_dataclass("R", ["labels"])(("locked",)))


def test_catalog_metadata_must_be_strings():
    mapping = {key: entry["value"] for key, entry in PEPPERMILL.parameter_sources.items()}
    assert pm.PeppermillParameters.from_mapping({**mapping, "name": "P", "length_unit": "mm"}).p2 == -40.0
    with pytest.raises(CatalogError, match=r"p\.toml: expected metadata field `name` to be a non-empty "
                                           r"string, got 3"):
        pm.PeppermillParameters.from_mapping({**mapping, "name": 3}, source="p.toml")
