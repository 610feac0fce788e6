"""Tests of screwkit.core.wrenches: paper 002 §4.2–4.3 values, reciprocity invariants, Eq. (2)–(4), errors."""

import numpy as np
import pytest
from hypothesis import given, settings

from screwkit.algebra import screw as S
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.algebra.screwvalue import Screw
from screwkit.core.wrenches import normalized_reciprocal_product, translated_graph, wrench_analysis
from screwkit.exceptions import ScrewkitValueError, TwistGraphError
from screwkit.graphs.joints import prismatic, revolute, spherical
from screwkit.graphs.reduction import equivalent_twist_graph
from screwkit.graphs.twistgraph import graph_frame, twist_graph

from ..mechanisms import (
    PLANAR_BASE,
    PLANAR_PLATFORM,
    Z,
    gough_stewart,
    gough_stewart_points,
    leg_lines,
    moved,
    planar_3rpr,
    planar_3rrr,
    r_4s_leg,
    rotation_about,
    rotation_z,
    tsai_3upu,
    tsai_constraint_couples,
    unit,
)
from ..strategies import rigid_motions, unit_factors

RTOL = 1e-9
UPU_POSE = np.array([0.1, 0.05, 0.8])
ELBOWS = np.array([[-0.5, 1.2, 0], [3.8, 1.5, 0], [0.8, 2.8, 0]])

# an H4 leg R-(4S) (paper 002 §4.1–4.3): hinge axis ∥ s_mn, parallelogram m n q p
M = np.array([1.2, 0.3, 0.1])
HINGE_AXIS = np.array([0.0, 1.0, 0.0])
N, ROD = M + 0.3 * HINGE_AXIS, np.array([0.2, -0.3, -0.9])
P, Q = M + ROD, N + ROD
S_MP, S_MN = unit(P - M), unit(N - M)
NORMAL = unit(np.cross(S_MN, S_MP))


def gs(angle=0.3, position=(0.1, -0.05, 1.0)):
    base, platform = gough_stewart_points(rotation_z(angle), position)
    return gough_stewart(base, platform), base, platform


def parallel_lines(a, b, atol=1e-9):
    """True if two screws are the same line up to a non-zero factor."""
    a, b = S.normalize(a), S.normalize(b)
    return bool(np.allclose(a, b, atol=atol) or np.allclose(a, -b, atol=atol))


# known values ----------------------------------------------------------------------------------
def test_normalized_reciprocal_product_of_two_lines_is_their_moment_over_the_length():
    # lines along x through (0, 0, d) and along (cos θ, sin θ, 0) through 0: distance d, angle θ;
    # a ∘ b = ± d sin θ
    d, theta, length = 0.7, 0.4, 2.5
    first = S.line([3.0, 0, 0], [0, 0, d])  # magnitude 3: normalised away
    second = S.line([np.cos(theta), np.sin(theta), 0], [0, 0, 0])
    value = normalized_reciprocal_product(first, second, length_scale=length)
    assert float(value) == pytest.approx(d * np.sin(theta) / length, rel=1e-12)
    # a line and a couple: the cosine of their directions; two couples: always reciprocal
    couple = S.couple([0, 2 * np.cos(0.3), 2 * np.sin(0.3)])
    assert float(normalized_reciprocal_product(S.line([0, 1, 0], [5, 5, 5]), couple, length_scale=length)) == pytest.approx(
        np.cos(0.3), rel=1e-12
    )
    assert float(normalized_reciprocal_product(couple, S.couple([1, 0, 0]), length_scale=length)) == 0.0
    # batched over leading axes
    values = normalized_reciprocal_product(np.stack([first, couple]), second, length_scale=length)
    assert values.shape == (2,)


def test_translated_graph_moves_every_axis():
    G = twist_graph("B", "E", [
        ("B", "L", revolute("R", [0, 0, 1], [1, 0, 0])),
        ("L", "E", prismatic("P", [0, 1, 0], actuated=True)),
    ])
    moved_graph = translated_graph(G, [0.5, 2.0, -1.0])
    np.testing.assert_allclose(
        moved_graph.edges["B", "L", "R"]["joint"].screws[0], S.line([0, 0, 1], [1.5, 2.0, -1.0]), atol=1e-12
    )
    np.testing.assert_allclose(moved_graph.edges["L", "E", "P"]["joint"].screws[0], S.couple([0, 1, 0]), atol=1e-12)
    assert moved_graph.edges["L", "E", "P"]["joint"].actuated
    assert moved_graph.graph == G.graph


def test_gough_stewart_actuation_wrenches_are_the_leg_lines():
    G, base, platform = gs()
    analysis = wrench_analysis(G)
    assert (analysis.dof, analysis.platform_twists.order, analysis.constraint_wrenches.order) == (6, 6, 0)
    assert analysis.global_wrenches.order == 6
    assert [limb.actuated_joint for limb in analysis.limbs] == [f"P{i}" for i in range(1, 7)]
    for limb, line in zip(analysis.limbs, leg_lines(base, platform), strict=True):
        # U and S leave the five twists of rotations through both ends: one wrench, the leg line
        assert limb.twist_system.order == 6 and limb.constraint_wrenches.order == 0
        assert limb.passive_wrenches.order == 1
        assert S.is_zero_pitch(limb.actuation_wrench, length_scale=analysis.length_scale)
        assert parallel_lines(limb.actuation_wrench, line)
        # a force along the leg and a translation along it: cosine 1
        assert limb.transmission == pytest.approx(1.0, abs=1e-9)
        assert set(limb.joints) == {f"U{limb.actuated_joint[1]}", limb.actuated_joint, f"S{limb.actuated_joint[1]}"}
    assert analysis.actuation_wrenches.shape == (6, 6)
    assert analysis.constraint_generators().shape == (0, 6)


def test_tsai_3upu_constraint_wrenches_are_three_couples():
    analysis = wrench_analysis(tsai_3upu(UPU_POSE))
    couples = tsai_constraint_couples(UPU_POSE)
    assert analysis.constraint_wrenches.order == 3
    assert analysis.constraint_wrenches.is_equivalent(ScrewSystem.span(couples))
    assert all(S.is_infinite_pitch(analysis.constraint_wrenches.readable_basis(), length_scale=analysis.length_scale))
    assert analysis.platform_twists.is_equivalent(ScrewSystem.span(np.hstack([np.zeros((3, 3)), np.eye(3)])))
    # each leg (a compound leg of the decomposition, and the limb of its P) applies its couple
    assert len(analysis.compound_legs) == 3
    for limb, couple in zip(analysis.limbs, couples, strict=True):
        assert limb.constraint_wrenches.order == 1
        assert limb.constraint_wrenches.is_equivalent(ScrewSystem.span([couple]))
    for leg in analysis.compound_legs:
        assert leg.twist_system.order == 5
        legs = [c for c in couples if leg.constraint_wrenches.contains(Screw(c))]
        assert len(legs) == 1
    assert analysis.global_wrenches.order == 6


def test_tsai_3upu_actuation_wrenches_are_the_leg_lines():
    # the passive twists are the two U joints: the wrenches reciprocal to both are the couple and
    # the line through both U centres (the leg); the line is the actuation wrench
    analysis = wrench_analysis(tsai_3upu(UPU_POSE))
    angles = np.deg2rad([90.0, 210.0, 330.0])
    for limb, angle in zip(analysis.limbs, angles, strict=True):
        radial = np.array([np.cos(angle), np.sin(angle), 0.0])
        a, c = radial, UPU_POSE + 0.5 * radial
        assert limb.passive_wrenches.order == 2
        assert parallel_lines(limb.actuation_wrench, S.line(c - a, a))


def test_r_4s_leg_constraint_couple_and_actuation_line():
    # paper 002 §4.2: W_i = span((0, n_i)); §4.3: the actuation wrench of a leg is a force
    # parallel to s_mp lying in the plane of the parallelogram (spanned by mn and mp)
    G = twist_graph("base", "platform", r_4s_leg(1, [1.0, 0, 0], HINGE_AXIS, M, N, P, Q))
    analysis = wrench_analysis(G)
    assert analysis.dof == 5  # one leg alone: the platform is held by one couple
    (limb,) = analysis.limbs
    assert limb.constraint_wrenches.is_equivalent(ScrewSystem.span([S.couple(NORMAL)]))
    assert limb.passive_wrenches.order == 2
    wrench = limb.actuation_wrench
    assert S.is_zero_pitch(wrench, length_scale=analysis.length_scale)
    point, direction = S.axis(wrench)
    np.testing.assert_allclose(np.abs(direction @ S_MP), 1.0, atol=1e-9)
    assert (point - M) @ NORMAL == pytest.approx(0.0, abs=1e-9)


def test_planar_3rpr_wrenches():
    # the plane keeps its three constraints: forces along z and couples about x and y; the
    # actuation wrench of each leg is the leg line, up to those constraints
    analysis = wrench_analysis(planar_3rpr(PLANAR_BASE, PLANAR_PLATFORM))
    plane_constraints = ScrewSystem.span([S.couple([1, 0, 0]), S.couple([0, 1, 0]), S.line(Z, [0, 0, 0])])
    assert analysis.constraint_wrenches.is_equivalent(plane_constraints)
    for limb, a, c in zip(analysis.limbs, PLANAR_BASE, PLANAR_PLATFORM, strict=True):
        assert limb.constraint_wrenches.is_equivalent(plane_constraints)
        assert limb.passive_wrenches.is_equivalent(plane_constraints + ScrewSystem.span([S.line(c - a, a)]))
        assert limb.passive_wrenches.contains(Screw(limb.actuation_wrench))
        assert S.reciprocal_product(limb.actuation_wrench, limb.actuated_twist) != pytest.approx(0.0, abs=1e-6)


def test_planar_3rrr_transmission_is_the_distance_from_the_actuator_to_the_forearm():
    # the actuation wrench of an RRR limb is the force along its forearm B C; with the actuated
    # hinge at A (axis z) the reciprocal product is the distance from A to line BC (sin 90° = 1);
    # the length of graph_frame is the RMS distance of the nine (parallel) axes from their centroid
    analysis = wrench_analysis(planar_3rrr(PLANAR_BASE, ELBOWS, PLANAR_PLATFORM))
    points = np.vstack([PLANAR_BASE, ELBOWS, PLANAR_PLATFORM])
    length = np.sqrt(np.mean(np.sum((points - points.mean(axis=0)) ** 2, axis=1)))
    assert analysis.length_scale == pytest.approx(length, rel=1e-12)
    for limb, a, b, c in zip(analysis.limbs, PLANAR_BASE, ELBOWS, PLANAR_PLATFORM, strict=True):
        distance = np.linalg.norm(np.cross(a - b, unit(c - b)))
        assert limb.transmission == pytest.approx(distance / length, rel=1e-9)
        assert parallel_lines(limb.actuation_wrench, S.line(c - b, b))


def test_serial_singular_limb_has_no_actuation_wrench():
    # limb 1 fully stretched: A, B, C collinear; its actuated twist is in the span of the others
    elbows = ELBOWS.copy()
    elbows[0] = PLANAR_BASE[0] + 0.55 * (PLANAR_PLATFORM[0] - PLANAR_BASE[0])
    analysis = wrench_analysis(planar_3rrr(PLANAR_BASE, elbows, PLANAR_PLATFORM))
    first = analysis.limbs[0]
    assert first.actuation_wrench is None and first.transmission == pytest.approx(0.0, abs=1e-12)
    assert first.twist_system.order == 2 and first.constraint_wrenches.order == 4
    assert first.passive_wrenches.is_equivalent(first.constraint_wrenches)
    assert analysis.actuation_wrenches.shape == (2, 6)


# invariants ------------------------------------------------------------------------------------
def _orders(analysis):
    return (
        analysis.platform_twists.order,
        analysis.constraint_wrenches.order,
        analysis.global_wrenches.order,
        len(analysis.actuation_wrenches),
        tuple(limb.passive_wrenches.order for limb in analysis.limbs),
        tuple(leg.constraint_wrenches.order for leg in analysis.compound_legs),
    )


MECHANISMS = {
    "gough-stewart": lambda: gs()[0],
    "3-upu": lambda: tsai_3upu(UPU_POSE),
    "3-upu-singular": lambda: tsai_3upu([np.cos(0.3), np.sin(0.3), 0.8]),
    "3-rpr": lambda: planar_3rpr(PLANAR_BASE, PLANAR_PLATFORM),
    "3-rrr": lambda: planar_3rrr(PLANAR_BASE, ELBOWS, PLANAR_PLATFORM),
}


@pytest.mark.parametrize("name", sorted(MECHANISMS))
@settings(max_examples=10)
@given(motion=rigid_motions(), factor=unit_factors)
def test_wrench_systems_follow_rigid_motions_and_units(name, motion, factor):
    rotation, translation = motion
    G = MECHANISMS[name]()
    before, after = wrench_analysis(G), wrench_analysis(moved(G, rotation, translation, factor))
    assert _orders(after) == _orders(before)
    assert after.length_scale == pytest.approx(factor * before.length_scale, rel=1e-9)
    # the constraint wrenches are carried along by the motion (an equivariant result)
    if before.constraint_wrenches.order:
        rows = S.transform(before.constraint_wrenches.basis, rotation, translation)
        rows[:, 3:] *= factor
        assert after.constraint_wrenches.is_equivalent(ScrewSystem.span(rows, length_scale=after.length_scale))
    if name in ("gough-stewart", "3-upu"):  # actuation wrenches unique up to scale here
        for one, other in zip(before.limbs, after.limbs, strict=True):
            assert other.transmission == pytest.approx(one.transmission, abs=1e-9)


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_reciprocity_of_the_analysis(name):
    analysis = wrench_analysis(MECHANISMS[name]())
    L = analysis.length_scale
    twists, constraints = analysis.platform_twists, analysis.constraint_wrenches
    assert twists.order + constraints.order == 6
    if twists.order and constraints.order:
        products = normalized_reciprocal_product(
            constraints.basis[:, None, :], twists.basis[None, :, :], length_scale=L
        )
        assert np.max(products) <= 1e-9
    for limb in analysis.limbs:
        # the limb's constraints are the platform's constraints through that limb
        assert analysis.constraint_wrenches.contains(limb.constraint_wrenches)
        assert limb.passive_wrenches.contains(limb.constraint_wrenches)
        assert limb.passive_wrenches.order == limb.constraint_wrenches.order + 1
        products = normalized_reciprocal_product(limb.actuation_wrench, limb.twist_system.basis, length_scale=L)
        assert np.max(products) > 1e-6  # it does work on some twist of the limb: the actuated one
    # Eq. (4): global = constraints + actuation wrenches
    expected = constraints + ScrewSystem.span(analysis.actuation_wrenches, length_scale=L)
    assert analysis.global_wrenches.is_equivalent(expected)


# independent computations ----------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_constraint_system_is_the_sum_over_compound_legs(name):
    # paper 002 Eq. (2)-(3): W = Σ W_i across the parallel legs
    analysis = wrench_analysis(MECHANISMS[name]())
    total = analysis.compound_legs[0].constraint_wrenches
    for leg in analysis.compound_legs[1:]:
        total = total + leg.constraint_wrenches
    assert total.is_equivalent(analysis.constraint_wrenches)
    generators = ScrewSystem.span(analysis.constraint_generators(), length_scale=analysis.length_scale)
    assert generators.is_equivalent(analysis.constraint_wrenches)


def test_global_order_of_the_gough_stewart_against_the_plucker_determinant(rng):
    # 6-UPS: W^c = 0, so the global system is the six leg lines; its order is 6 exactly when the
    # 6x6 determinant of the unit leg lines does not vanish (a generic pose has |det| ≫ 1e-6)
    for _ in range(5):
        rotation = rotation_about(rng.normal(size=3), rng.uniform(-0.5, 0.5))
        position = np.array([*rng.uniform(-0.2, 0.2, size=2), rng.uniform(0.7, 1.3)])
        base, platform = gough_stewart_points(rotation, position)
        determinant = np.linalg.det(leg_lines(base, platform))
        assert abs(determinant) > 1e-3
        assert wrench_analysis(gough_stewart(base, platform)).global_wrenches.order == 6
    base, platform = gough_stewart_points(rotation_z(np.pi / 2))  # Fichter's singular pose
    assert abs(np.linalg.det(leg_lines(base, platform))) < 1e-12
    assert wrench_analysis(gough_stewart(base, platform)).global_wrenches.order == 5


def test_equivalent_graph_gives_the_same_wrench_systems():
    # paper 002 Fig. 3: the constraint analysis can be run on the twist graph with virtual chains
    second_axis = unit([0.1, 1, 0.2])
    m2 = np.array([-1.2, 0.3, 0.1])
    n2, rod2 = m2 + 0.3 * second_axis, np.array([0.3, 0.1, -0.9])
    legs = r_4s_leg(1, [1.0, 0, 0], HINGE_AXIS, M, N, P, Q) + r_4s_leg(
        2, [-1.0, 0, 0], second_axis, m2, n2, m2 + rod2, n2 + rod2
    )
    G = twist_graph("base", "platform", legs)
    physical, virtual = wrench_analysis(G), wrench_analysis(equivalent_twist_graph(G))
    assert _orders(virtual) == _orders(physical)
    assert virtual.constraint_wrenches.is_equivalent(physical.constraint_wrenches)
    for one, other in zip(physical.limbs, virtual.limbs, strict=True):
        assert one.actuated_joint == other.actuated_joint
        assert other.constraint_wrenches.is_equivalent(one.constraint_wrenches)
        assert other.passive_wrenches.is_equivalent(one.passive_wrenches)


# bugs ------------------------------------------------------------------------------------------
def test_actuation_wrench_of_a_planar_leg_does_not_depend_on_the_frame():
    # In its own frame each 3-RPR leg gets the leg line and transmission 1. Turned by 0.7 rad
    # about x, limb P1 gets a tilted line (the leg line plus a force normal to the plane, another
    # representative modulo the limb's constraints) and transmission 0.896.
    G = planar_3rpr(PLANAR_BASE, PLANAR_PLATFORM)
    rotation = rotation_about([1, 0, 0], 0.7)
    before, after = wrench_analysis(G), wrench_analysis(moved(G, rotation))
    for one, other in zip(before.limbs, after.limbs, strict=True):
        assert other.transmission == pytest.approx(one.transmission, abs=1e-9)
        assert parallel_lines(other.actuation_wrench, S.transform(one.actuation_wrench, rotation, [0, 0, 0]))


def test_planar_mechanism_turned_by_a_tiny_angle():
    # Regression (was a strict xfail): turned by ~1e-7 rad, the passive 4-system of a 3-RPR leg has a
    # screw that is a couple plus ~1e-8 of a line; ScrewSystem.readable_basis shifted it "to zero
    # pitch", a line ~1e8 lengths away, which became the actuation wrench (then an independence
    # error, or "Internal error: readable basis of order 5 != 4"). The core no longer goes through it.
    G = planar_3rpr(PLANAR_BASE, PLANAR_PLATFORM)
    expected = _orders(wrench_analysis(G))
    near_identity = [rotation_about(axis, tilt) for axis in ([1, 0, 0], [1, 0.3, 0], [0.2, 1, 0.5]) for tilt in (3e-8, 1e-7)]
    internal_error = np.array([[-0.6, 8e-10, 0.8], [8e-10, -1.0, 1.6e-9], [0.8, 1.6e-9, 0.6]])
    for rotation in [*near_identity, internal_error]:
        analysis = wrench_analysis(moved(G, rotation))
        assert _orders(analysis) == expected
        for limb in analysis.limbs:
            point, _ = S.axis(limb.actuation_wrench)
            assert np.linalg.norm(point - analysis.reference_point) < 10 * analysis.length_scale


def test_wrench_analysis_of_a_mechanism_far_from_the_origin():
    # ranks are decided about graph_frame's point (module docstring), but the results are rebuilt
    # as ScrewSystem in the user's frame, whose constructor re-checks independence there:
    # 1e5 lengths away it raises "Expected `basis` to hold independent screws"
    G = tsai_3upu(UPU_POSE)
    far = moved(G, None, [1e5, 3e4, 0.0])
    assert _orders(wrench_analysis(far)) == _orders(wrench_analysis(G))


def test_translated_graph_moves_the_joint_geometry_too():
    G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [1, 0, 0]))])
    joint = translated_graph(G, [0.5, 2.0, -1.0]).edges["B", "E", "R"]["joint"]
    assert joint.geometry["point"] == pytest.approx([1.5, 2.0, -1.0])


# errors: one per message -----------------------------------------------------------------------
@pytest.mark.parametrize("dof", [7, -1, 1.5])
def test_error_bad_dof(dof):
    G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
    with pytest.raises(TwistGraphError, match=r"Expected `dof` to be an integer in 0\.\.6, got"):
        wrench_analysis(G, dof=dof)


def test_error_actuated_joint_on_no_path_to_the_platform():
    G = twist_graph("B", "E", [
        ("B", "E", prismatic("P", [1, 0, 0], actuated=True)),
        ("E", "tool", revolute("R", [0, 0, 1], [0, 0, 0], actuated=True)),  # beyond the platform
    ])
    with pytest.raises(TwistGraphError, match="Actuated joint 'R' lies on no path from the base to the platform"):
        wrench_analysis(G)


def test_error_translated_graph_offset_shape():
    G = twist_graph("B", "E", [("B", "E", spherical("S", [0, 0, 0]))])
    with pytest.raises(ScrewkitValueError, match=r"Expected `offset` to have shape \(\.\.\., 3\), got \(2,\)"):
        translated_graph(G, [1.0, 2.0])


def test_error_normalized_reciprocal_product_shape():
    with pytest.raises(ScrewkitValueError, match=r"Expected `second` to have shape \(\.\.\., 6\), got \(5,\)"):
        normalized_reciprocal_product(np.ones(6), np.ones(5), length_scale=1.0)


def test_graph_frame_is_the_analysis_frame():
    G = tsai_3upu(UPU_POSE)
    point, length = graph_frame(G)
    analysis = wrench_analysis(G)
    np.testing.assert_allclose(analysis.reference_point, point, atol=1e-12)
    assert analysis.length_scale == length and analysis.rtol == RTOL
    assert analysis.graph is G


def test_error_normalized_reciprocal_product_of_a_zero_screw():
    from screwkit.core.wrenches import normalized_reciprocal_product
    from screwkit.exceptions import DegenerateGeometryError

    with pytest.raises(DegenerateGeometryError, match="Expected `second` to hold non-zero screws, got the zero screw"):
        normalized_reciprocal_product([0, 0, 1, 0, 0, 0], [0, 0, 0, 0, 0, 0], length_scale=1.0)


def test_closeness_is_computed_only_when_asked_and_a_batch_agrees_with_its_poses(monkeypatch):
    from screwkit.core import _closing as CK
    from screwkit.robots.catalog import load_mechanism

    calls = []
    ratio = CK.singular_ratio
    monkeypatch.setattr(CK, "singular_ratio", lambda rows, index: calls.append(index) or ratio(rows, index))
    h4 = load_mechanism("h4")
    report = h4.at([[0, 0, -750, 0], [30, -20, -750, 0.3], [300, 300, -473.8, np.radians(30)]]).singularities
    assert report.verdict.tolist() == ["regular"] * 3 and report.global_order.tolist() == [6, 6, 6]
    assert calls == []  # the labels need no SVD
    closeness = report.closeness
    assert sorted(calls) == [2, 6]  # σ_(6 − dof) and σ_6 over σ_1, once each for the whole batch
    assert report.closeness is closeness  # kept
    for index in range(3):  # a pose of the batch: its own factors, the same bits
        one = report[index].closeness
        assert {k: float(v[index]) for k, v in closeness.items()} == one
        assert 0.0 < one["constraint"] <= 1.0 and 0.0 < one["actuation"] <= 1.0 and one["serial"] > 0.0


@pytest.mark.parametrize("name", ["mcgill_smg", "h4"])
def test_a_batch_without_views_gives_the_same_bits(monkeypatch, name):
    # without views the limbs' constraint systems are computed only where an actuation wrench is
    # searched for a line (the McGill SMG has such poses), and the closeness when asked
    from screwkit.core import _wrench_pass as P
    from screwkit.core import wrench_systems as W
    from screwkit.robots.catalog import load_mechanism

    searched = []
    search = P.line_search
    monkeypatch.setattr(P, "line_search", lambda *args: searched.append(len(args[0])) or search(*args))
    mechanism = load_mechanism(name)
    table = mechanism.at(mechanism.random_poses(np.random.default_rng(1), 300)).joints
    full, lean = W.analyze_table(table), W.analyze_table(table, views=False)
    assert (sum(searched) > 0) == (name == "mcgill_smg")
    assert "limb0:W" in full.frames and "limb0:W" not in lean.frames
    for key in ("global_order", "serial", "transmissions", "actuation_rows", "branch_rows"):
        np.testing.assert_array_equal(getattr(full, key), getattr(lean, key))
    for key, value in full.closeness.items():
        np.testing.assert_array_equal(value, lean.closeness[key])


def test_closeness_in_chunks_gives_the_same_bits(monkeypatch):
    from screwkit.core import wrench_systems as W
    from screwkit.robots.catalog import load_mechanism

    h4 = load_mechanism("h4")
    poses = h4.random_poses(np.random.default_rng(2), 5)
    whole = h4.at(poses).closeness
    monkeypatch.setattr(W, "CLOSENESS_CHUNK", 2)  # three chunks: 2, 2, 1 poses
    chunked = h4.at(poses).closeness
    for key, value in whole.items():
        assert value.shape == (5,)
        np.testing.assert_array_equal(chunked[key], value)


# a given length scale ------------------------------------------------------------------------------
def _two_parallel_hinges(spacing):
    """Two revolute joints about z, ``spacing`` apart, both between base and platform."""
    from screwkit.graphs.jointtable import JointTable

    rows = [("B", "E", "R1", "R", [[[0, 0, 1.0, 0, 0, 0]]], False)]
    rows.append(("B", "E", "R2", "R", [[[0, 0, 1.0, 0, -spacing, 0]]], False))
    return JointTable.from_rows("B", "E", rows)


def test_a_given_length_scale_is_the_one_every_rank_decision_uses():
    # By hand: the frame's point is midway between the axes and its length spacing/2, so the scaled
    # moments are ±1 and the hinges lock the platform (order 0). Judged by a length 1e10 times the
    # spacing, the axes are 5e-11 apart (< rtol = 1e-9): one hinge, a platform rotation (order 1).
    from screwkit.core.wrench_systems import analyze_table

    table = _two_parallel_hinges(1e-3)
    derived = analyze_table(table, dof=0)
    given = analyze_table(table, dof=0, length_scale=1e7)
    assert derived.length_scale.tolist() == [5e-4] and derived.platform_order.tolist() == [0]
    assert given.length_scale.tolist() == [1e7] and given.platform_order.tolist() == [1]
    assert given.constraint_order.tolist() == [5]
    assert analyze_table(table, dof=0, length_scale=[1e7]).platform_order.tolist() == [1]  # per pose


def test_an_analysis_length_scale_given_back_reproduces_it_bit_for_bit():
    from screwkit.core.wrench_systems import analyze_table
    from screwkit.robots.catalog import load_mechanism

    table = load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3], [10, 5, -700, -0.2]]).joints
    derived = analyze_table(table)
    again = analyze_table(table, length_scale=derived.length_scale)
    for field in ("platform_order", "constraint_order", "global_order", "actuation_rows", "transmissions"):
        np.testing.assert_array_equal(getattr(again, field), getattr(derived, field))
    for key, value in derived.closeness.items():
        np.testing.assert_array_equal(again.closeness[key], value)
    other = analyze_table(table, length_scale=10 * derived.length_scale)  # another length, other sizes
    assert not np.array_equal(other.closeness["constraint"], derived.closeness["constraint"])


@settings(max_examples=10)
@given(motion=rigid_motions(), factor=unit_factors)
def test_a_given_length_scale_in_the_new_unit_keeps_the_answers(motion, factor):
    rotation, translation = motion
    G = gs()[0]
    length = 3.0 * wrench_analysis(G).length_scale
    before = wrench_analysis(G, length_scale=length)
    after = wrench_analysis(moved(G, rotation, translation, factor), length_scale=factor * length)
    assert _orders(after) == _orders(before) and after.length_scale == factor * length
    for key, value in before.closeness.items():
        assert after.closeness[key] == pytest.approx(value, rel=1e-7, abs=1e-12)


@pytest.mark.parametrize(
    "value, message",
    [
        (-1.0, r"Expected `length_scale` to be a positive finite number in \[1e-100, 1e\+100\] or None, got -1.0"),
        (0, r"Expected `length_scale` to be a positive finite number in \[1e-100, 1e\+100\] or None, got 0"),
        (float("nan"), r"Expected `length_scale` to be a positive finite number in \[1e-100, 1e\+100\] or None, got nan"),
        ("1", r"Expected `length_scale` to be a positive finite number in \[1e-100, 1e\+100\] or None, got '1'"),
        (1e200, r"Expected `length_scale` to be a positive finite number in \[1e-100, 1e\+100\] or None, got 1e\+200"),
        ([-1.0], r"Expected `length_scale` to be positive finite numbers in \[1e-100, 1e\+100\], got \[-1\.\]"),
        ([1.0, 2.0], r"Expected `length_scale` to be a positive number or an array of the batch shape \(1,\)"),
    ],
)
def test_error_bad_length_scale(value, message):
    from screwkit.core.wrench_systems import analyze_table

    with pytest.raises(ScrewkitValueError, match=message):
        analyze_table(_two_parallel_hinges(1.0), dof=0, length_scale=value)


def test_a_given_length_scale_is_kept_by_the_views_of_a_batch_analysed_without_them():
    # The views=False batch (classify_table, a posed mechanism's verdicts) recomputes a pose's frames
    # when a view asks: with the given length, or the constraint system reads the derived length's
    # decision (order 6, see the hand derivation above) against the batch's own order 5.
    from screwkit.core.singularity import classify_table
    from screwkit.core.wrench_systems import analyze_table

    table = _two_parallel_hinges(1e-3)
    full = analyze_table(table, dof=0, length_scale=1e7)[0]
    lean = analyze_table(table, dof=0, length_scale=1e7, views=False)[0]
    assert lean.constraint_order == 5 and lean.constraint_wrenches.order == 5
    np.testing.assert_array_equal(lean.constraint_wrenches.basis, full.constraint_wrenches.basis)
    report = classify_table(table, dof=0, length_scale=1e7)
    assert report[0].analysis.global_wrenches.order == int(report.analysis.global_order[0]) == 5
