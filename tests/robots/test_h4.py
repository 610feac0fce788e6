"""The H4 end to end: structure of its wrench systems (paper 002 §4) and its singularity labels (§5.3).

Geometry from paper 004 (Table 1 "Quattro, H4", Table 3 "H4": α = 0, β = π/2, r = 80, c = 70 mm;
R = 275, b = 375, l = 800 mm; working mode h_i < 0). Limbs use paper 004's numbering; paper 002's
legs (l1, l2 | l3, l4) are paper 004's limbs (1, 4 | 2, 3) (screwkit.robots.families.four_limb.joints.PAPER_002_LEGS).

Every expected value is computed here independently of the code under test: plane normals
n_i = u_i × w_i of the parallelograms, Eq. (6) and Eq. (7) of paper 002 in vector form, and the
6×6 determinant of the paper's six wrenches.
"""

import functools
import itertools

import networkx as nx
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.algebra import screw as S
from screwkit.algebra.incidence import lines_intersect
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.core.singularity import classify
from screwkit.core.wrenches import translated_graph, wrench_analysis
from screwkit.graphs.reduction import equivalent_twist_graph, platform_twist_system
from screwkit.graphs.twistgraph import twist_graph
from screwkit.robots.families.four_limb.joints import PAPER_002_LEGS, joints
from screwkit.robots.families.four_limb.kinematics import inverse_kinematics, reachable
from screwkit.robots.families.four_limb.parameters import FourLimbParameters

from ..strategies import rigid_motions, unit_factors

H4 = FourLimbParameters(
    name="H4", platform_kind="articulated_z", arm_length=375.0, rod_length=800.0, alpha=0.0,
    beta=np.pi / 2, platform_radius=80.0, platform_offset=70.0, base_radius=275.0,
)
Z = np.array([0.0, 0.0, 1.0])


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def random_poses(rng, count, *, edge=False):
    """Reachable poses; `edge` widens the box to the workspace's edge (where Eq. (6) changes sign)."""
    xy, top, angle = (400, -500, np.pi / 2) if edge else (350, -550, 1.2)
    poses = np.column_stack([
        rng.uniform(-xy, xy, 4 * count), rng.uniform(-xy, xy, 4 * count),
        rng.uniform(-1000, top, 4 * count), rng.uniform(-angle, angle, 4 * count),
    ])
    return poses[reachable(H4, poses)][:count]


def normals(cfg):
    """n_i: unit normal of the plane of parallelogram i (spanned by s_mn ∥ u_i and s_mp ∥ w_i)."""
    return unit(np.cross(cfg.u, cfg.w))


def axis_meets_plane(cfg, limb, point):
    """Where the vertical axis through `point` meets the plane of parallelogram `limb`."""
    n = normals(cfg)[..., limb, :]
    t = np.einsum("...i,...i", n, cfg.b[..., limb, :] - point) / n[..., 2]
    return point + t[..., None] * Z


def paper_002_conditions(cfg):
    """Eq. (6) (s12 × s34)·z and Eq. (7) (([s1 × s2] × [(r_g − r_c) × z])·(s3 × s4)) of paper 002.

    In paper 004's numbering, b_I carries limbs 1 and 4 (paper 002's l1, l2) and b_II limbs 2, 3
    (l3, l4); s_uv^i ∥ w_i; c is where l2's actuation force meets Z_I and g where l4's meets Z_II.
    """
    n = normals(cfg)
    leg = {k: v - 1 for k, v in PAPER_002_LEGS.items()}
    s12 = np.cross(n[..., leg["l1"], :], n[..., leg["l2"], :])
    s34 = np.cross(n[..., leg["l3"], :], n[..., leg["l4"], :])
    eq6 = np.cross(s12, s34) @ Z
    axis_I, axis_II = cfg.platform_joint_points[..., 0, :], cfg.platform_joint_points[..., 1, :]
    r_c = axis_meets_plane(cfg, leg["l2"], axis_I)
    r_g = axis_meets_plane(cfg, leg["l4"], axis_II)
    w = cfg.w
    left = np.cross(np.cross(w[..., leg["l1"], :], w[..., leg["l2"], :]), np.cross(r_g - r_c, Z))
    eq7 = np.einsum("...i,...i", left, np.cross(w[..., leg["l3"], :], w[..., leg["l4"], :]))
    return eq6, eq7, s12, s34


def paper_wrench_matrix(cfg):
    """The six wrenches of paper 002 Eq. (4), paper normalisation: τ∞I, τ∞II, τ0^1..τ0^4."""
    _, _, s12, s34 = paper_002_conditions(cfg)
    axis_points = {1: 0, 4: 0, 2: 1, 3: 1}  # limb -> the vertical axis its actuation force meets
    rows = [S.couple(np.cross(Z, s12)) if np.linalg.norm(np.cross(Z, s12)) else np.zeros(6),
            S.couple(np.cross(Z, s34)) if np.linalg.norm(np.cross(Z, s34)) else np.zeros(6)]
    for paper_leg in ("l1", "l2", "l3", "l4"):
        limb = PAPER_002_LEGS[paper_leg]
        point = axis_meets_plane(cfg, limb - 1, cfg.platform_joint_points[axis_points[limb]])
        rows.append(S.line(cfg.w[limb - 1], point))
    return np.array(rows)


# structure at random poses (paper 002 §4.2–4.3) ------------------------------------------------
def test_structure_at_fifty_random_poses(rng):
    poses = random_poses(rng, 50)
    assert len(poses) == 50
    for pose in poses:
        cfg = inverse_kinematics(H4, pose)
        graph = joints(cfg).graph()
        analysis = wrench_analysis(graph)
        n = normals(cfg)
        # each leg R–(4S), base to its sub-platform: constraint system span(0, n_i)
        for limb in range(4):
            i = limb + 1
            sub = "b_I" if limb in (0, 3) else "b_II"
            names = {f"A{i}", f"S{i}m", f"S{i}p", f"S{i}n", f"S{i}q"}
            leg = nx.MultiDiGraph(graph.edge_subgraph((u, v, k) for u, v, k in graph.edges(keys=True) if k in names))
            leg.graph.update(base="base", platform=sub)
            constraint = platform_twist_system(leg).reciprocal()
            assert constraint.order == 1
            assert constraint.is_equivalent(ScrewSystem.span([S.couple(n[limb])]))
        # compound legs L_I, L_II: span(0, z × s12), span(0, z × s34)
        _, _, s12, s34 = paper_002_conditions(cfg)
        expected = {"R_I": S.couple(np.cross(Z, s12)), "R_II": S.couple(np.cross(Z, s34))}
        for leg in analysis.compound_legs:
            key = "R_I" if "R_I" in leg.joints else "R_II"
            assert leg.constraint_wrenches.order == 1
            assert leg.constraint_wrenches.is_equivalent(ScrewSystem.span([expected[key]]))
        # the platform: three translations and one rotation about z (Schoenflies)
        schoenflies = ScrewSystem.span([S.couple(np.eye(3)[k]) for k in range(3)] + [S.line(Z, [0, 0, 0])])
        assert analysis.platform_twists.is_equivalent(schoenflies)
        # actuation wrenches: zero-pitch lines ∥ the parallelogram direction w_i meeting Z_I or Z_II
        for limb in analysis.limbs:
            index = int(limb.actuated_joint[1]) - 1
            wrench = limb.actuation_wrench
            assert S.is_zero_pitch(wrench, length_scale=500.0)
            assert np.linalg.norm(np.cross(unit(wrench[:3]), cfg.w[index])) < 1e-9
            axis_point = cfg.platform_joint_points[0 if index in (0, 3) else 1]
            assert lines_intersect(wrench, S.line(Z, axis_point), length_scale=500.0)
        assert classify(graph).labels == () or abs(paper_002_conditions(cfg)[1]) < 1e-3


def test_equivalent_graph_has_virtual_rrpp_chains():
    graph = joints(inverse_kinematics(H4, [40.0, -30.0, -750.0, 0.4])).graph()
    equivalent = equivalent_twist_graph(graph)
    for i, sub in ((1, "b_I"), (2, "b_II"), (3, "b_II"), (4, "b_I")):
        path = nx.shortest_path(equivalent, f"arm{i}", sub)
        types = sorted(equivalent.edges[u, v, k]["joint"].type for u, v in itertools.pairwise(path)
                       for k in equivalent[u][v])
        assert types == ["vP", "vP", "vR", "vR"]  # paper 002 Fig. 2b: R1, R2, P1, P2 (virtual)
        assert all(equivalent.edges[u, v, k]["joint"].virtual for u, v in itertools.pairwise(path)
                   for k in equivalent[u][v])
    # the same platform twist system both ways, on the physical and on the equivalent graph
    for candidate in (graph, equivalent):
        by_reduction = platform_twist_system(candidate, method="reduction")
        assert platform_twist_system(candidate).is_equivalent(by_reduction) and by_reduction.order == 4


# labels at the roots of Eqs. (6) and (7) -------------------------------------------------------
def root_along(which, start, stop):
    """Bisection on paper 002's Eq. (6) (which=0) or (7) (which=1) along a straight path of poses."""
    path = start + np.linspace(0, 1, 101)[:, None] * (stop - start)
    assert reachable(H4, path).all()
    values = paper_002_conditions(inverse_kinematics(H4, path))[which]
    k = np.nonzero(np.sign(values[:-1]) != np.sign(values[1:]))[0]
    assert len(k), "no sign change along the path"
    low, high = path[k[0]], path[k[0] + 1]
    f_low = paper_002_conditions(inverse_kinematics(H4, low))[which]
    for _ in range(80):
        middle = (low + high) / 2
        f_middle = paper_002_conditions(inverse_kinematics(H4, middle))[which]
        if np.sign(f_middle) == np.sign(f_low):
            low, f_low = middle, f_middle
        else:
            high = middle
    return (low + high) / 2


def sign_change_pairs(rng, which, count):
    poses = random_poses(rng, 20000, edge=True)  # Eq. (6) changes sign in ~0.1 % of them, near the edge
    values = paper_002_conditions(inverse_kinematics(H4, poses))[which]
    positive, negative = poses[values > 0], poses[values < 0]
    pairs = []
    for start in positive[:40]:
        scaled = (negative - start) / [400, 400, 250, np.pi / 2]
        stop = negative[np.argmin(np.linalg.norm(scaled, axis=1))]
        path = start + np.linspace(0, 1, 101)[:, None] * (stop - start)
        if reachable(H4, path).all():
            pairs.append((start, stop))
        if len(pairs) == count:
            break
    return pairs


def test_constraint_singularities_where_equation_6_holds(rng):
    pairs = sign_change_pairs(rng, 0, 3)
    assert len(pairs) == 3
    for start, stop in pairs:
        pose = root_along(0, start, stop)
        cfg = inverse_kinematics(H4, pose)
        eq6, eq7, _, _ = paper_002_conditions(cfg)
        assert abs(eq6) < 1e-12 and abs(eq7) > 1.0  # on (6) only
        report = classify(joints(cfg).graph())
        assert report.labels == ("constraint",)
        assert report.constraint_order == 1 and report.gained_dof == 1 and report.global_order == 5
        # the gained twist is reciprocal to the remaining constraint couple and every actuation force
        gained = report.uncontrolled_twists
        assert gained.shape == (1, 6)
        wrenches = np.vstack([report.analysis.constraint_wrenches.basis, report.analysis.actuation_wrenches])
        assert np.abs(S.reciprocal_product(wrenches, gained[0])).max() < 1e-9 * 1000
        # and it is not a Schoenflies motion: it tilts the end effector (its rotation is not ∥ z)
        assert np.linalg.norm(np.cross(unit(gained[0, :3]), Z)) > 1e-3
        # the regular neighbour on the path is labelled regular
        assert classify(joints(inverse_kinematics(H4, start)).graph()).labels == ()


def test_actuation_singularities_where_equation_7_holds(rng):
    pairs = sign_change_pairs(rng, 1, 3)
    assert len(pairs) == 3
    for start, stop in pairs:
        pose = root_along(1, start, stop)
        cfg = inverse_kinematics(H4, pose)
        eq6, eq7, _, _ = paper_002_conditions(cfg)
        assert abs(eq7) < 1e-9 and abs(eq6) > 1e-3
        report = classify(joints(cfg).graph())
        assert report.labels == ("actuation",)
        assert report.constraint_order == 2 and report.global_order == 5 and report.gained_dof == 0
        assert report.uncontrolled_dof == 1
        assert classify(joints(inverse_kinematics(H4, start)).graph()).labels == ()


def test_six_by_six_determinant_is_equation_6_times_equation_7(rng):
    # Hand derivation (gca.md §5.1): with the lines in the order [ab, cd, ef, gh, ij, kj] the
    # superbracket is [gikj]([abdf][cghj] − [abdh][cgfj]) = (−Eq. 6)(−Eq. 7); the paper's rows
    # (τ∞I, τ∞II, τ0^1..τ0^4) differ from those lines by a permutation and two sign flips.
    # Compare the functions: the ratio is the same constant at every pose.
    ratios = []
    for pose in random_poses(rng, 60):
        cfg = inverse_kinematics(H4, pose)
        eq6, eq7, _, _ = paper_002_conditions(cfg)
        ratios.append(np.linalg.det(paper_wrench_matrix(cfg)) / (eq6 * eq7))
    np.testing.assert_allclose(ratios, ratios[0], rtol=1e-8)
    assert abs(ratios[0]) == pytest.approx(1.0, rel=1e-9)


@functools.cache
def case_b_pose():
    """A reachable pose of paper 002's case (b): n1, n4 horizontal, so s12 = n1 × n4 ∥ z."""

    def residual(pose):  # w1 ⟂ y and w4 ⟂ x make n1 = u1 × w1 and n4 = u4 × w4 horizontal
        cfg = inverse_kinematics(H4, pose)
        return np.array([cfg.w[0, 1], cfg.w[3, 0]])

    pose, scale = np.array([271.96, 370.79, -924.77, 1.1541]), np.array([100.0, 100.0, 100.0, 1.0])
    for _ in range(30):  # minimum-norm Newton on the 2-dimensional solution surface, from a grid seed
        value = residual(pose)
        jac = np.column_stack([(residual(pose + e * 1e-5 * k) - value) / (1e-5 * k) for e, k in zip(np.eye(4), scale, strict=True)])
        pose = pose - np.linalg.pinv(jac * scale) @ value * scale
    assert np.abs(residual(pose)).max() < 1e-12
    return pose


def test_paper_case_b_is_an_actuation_and_serial_singularity_not_a_constraint_one():
    # Paper 002 §5.3 case (b): s12 ∥ z "the constraint wrench system becomes a 1-system". A rank
    # computation disagrees: with n1, n4 horizontal, l14's constraint couples are both horizontal,
    # so W_I is the 2-system of horizontal couples (not τ∞I = 0) and W^c stays of order 2. What does
    # happen: Z_I is parallel to the plane of parallelogram 1, so limb 1's actuation force (in that
    # plane, meeting Z_I) does not exist; its passive wrenches shrink to the couple (0, n1), which is
    # reciprocal to the actuated twist (n1 ⟂ u1): a serial singularity of limb 1, and an actuation
    # singularity of the mechanism (the rotation about z is uncontrolled). The paper's 6×6
    # determinant vanishes too (its τ∞I row is zero), for the wrong reason.
    pose = case_b_pose()
    cfg = inverse_kinematics(H4, pose)
    _, _, s12, _ = paper_002_conditions(cfg)
    assert np.linalg.norm(np.cross(unit(s12), Z)) < 1e-9
    assert abs(np.linalg.det(paper_wrench_matrix(cfg))) < 1e-9
    report = classify(joints(cfg).graph())
    assert report.constraint_order == 2 and report.labels == ("actuation", "serial")
    leg_I = next(leg for leg in report.analysis.compound_legs if "R_I" in leg.joints)
    assert leg_I.constraint_wrenches.order == 2
    assert [s.actuated_joint for s in report.serial] == ["A1"]
    uncontrolled = report.uncontrolled_twists[0]
    assert np.linalg.norm(np.cross(unit(uncontrolled[:3]), Z)) < 1e-9  # a rotation about a vertical axis


# invariance (hypothesis) -------------------------------------------------------------------------
def moved_graph(graph, motion, unit_factor):
    rotation, translation = motion
    moved = nx.MultiDiGraph(**graph.graph)
    for u, v, key, joint in graph.edges(keys=True, data="joint"):
        screws = S.transform(joint.screws, rotation, translation)
        screws[:, 3:] *= unit_factor
        moved.add_edge(u, v, key=key, joint=type(joint)(joint.name, joint.type, screws, joint.actuated))
    return moved


@settings(max_examples=12)
@given(rigid_motions(), unit_factors, st.sampled_from(["regular", "eq6", "eq7"]))
def test_labels_invariant_under_motion_and_unit(motion, unit_factor, which):
    poses = {"regular": np.array([30.0, -20.0, -750.0, 0.3]), "eq6": singular_pose(0), "eq7": singular_pose(1)}
    graph = joints(inverse_kinematics(H4, poses[which])).graph()
    reference = classify(graph)
    rotation, translation = motion
    report = classify(moved_graph(graph, (rotation, translation * 500), unit_factor))
    assert report.labels == reference.labels
    assert (report.constraint_order, report.global_order, report.gained_dof, report.uncontrolled_dof) == (
        reference.constraint_order, reference.global_order, reference.gained_dof, reference.uncontrolled_dof)
    for key in ("constraint", "actuation", "serial"):
        assert report.closeness[key] == pytest.approx(reference.closeness[key], rel=1e-6, abs=1e-9)


@functools.cache
def singular_pose(which):
    """A root of paper 002's Eq. (6) (which=0) or Eq. (7) (which=1), found once per session."""
    start, stop = sign_change_pairs(np.random.default_rng(7), which, 1)[0]
    return root_along(which, start, stop)


def test_translated_graph_keeps_the_analysis():
    graph = joints(inverse_kinematics(H4, [10.0, 20.0, -700.0, -0.5])).graph()
    moved = translated_graph(graph, [1e4, -3e3, 2e3])
    assert classify(moved).labels == classify(graph).labels == ()
    assert wrench_analysis(moved).platform_twists.order == 4


def test_error_no_actuated_joint_path():
    from screwkit.exceptions import TwistGraphError
    from screwkit.graphs.joints import revolute

    graph = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0])),
                                   ("B", "X", revolute("A", [0, 0, 1], [1, 0, 0], actuated=True)),
                                   ("X", "Y", revolute("R2", [1, 0, 0], [1, 0, 0]))])
    with pytest.raises(TwistGraphError, match="Actuated joint 'A' lies on no path from the base to the platform"):
        wrench_analysis(graph)
