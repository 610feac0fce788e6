"""Tests of screwkit.graphs.joints: hand-derived unit twists, invariants, independent spans, one test per error."""

import dataclasses
import json
import math

import numpy as np
import pytest
import sympy
from hypothesis import given, settings

from screwkit.algebra import screw as S
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.algebra.screwvalue import Screw
from screwkit.exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError
from screwkit.graphs.joints import (
    JOINT_TYPES,
    Joint,
    cylindrical,
    helical,
    lead_to_pitch,
    parallelogram,
    prismatic,
    revolute,
    spherical,
    universal,
    virtual,
)

from ..mechanisms import unit
from ..strategies import rigid_motions, seeds, unit_factors

ATOL = 1e-12


# known values (hand derivation: (s; r × s), (0; d), (s; r × s + h s)) -------------------------------
def test_revolute_is_the_unit_line_on_its_axis():
    # axis z through (1, 0, 0): r × s = (1, 0, 0) × (0, 0, 1) = (0, -1, 0)
    joint = revolute("R1", [0, 0, 1], [1, 0, 0], actuated=True)
    np.testing.assert_allclose(joint.screws, [[0, 0, 1, 0, -1, 0]], atol=ATOL)
    assert (joint.type, joint.dof, joint.actuated, joint.virtual) == ("R", 1, True, False)
    assert joint.geometry == {"axis": [0.0, 0.0, 1.0], "point": [1.0, 0.0, 0.0]}


def test_revolute_with_a_long_axis_still_gives_a_unit_twist():
    # the joint twists are *unit* twists (module docstring): an axis of length 2 is normalised
    np.testing.assert_allclose(revolute("R", [0, 0, 2], [1, 0, 0]).screws, [[0, 0, 1, 0, -1, 0]], atol=ATOL)
    rows = universal("U", [3, 0, 0], [0, 0.5, 0], [0, 0, 1]).screws
    np.testing.assert_allclose(np.linalg.norm(rows[:, :3], axis=1), [1, 1], atol=ATOL)
    # (1,0,0) and (0,1,0) through (0,0,1): r × s = (0, 1, 0) and (-1, 0, 0)
    np.testing.assert_allclose(rows, [[1, 0, 0, 0, 1, 0], [0, 1, 0, -1, 0, 0]], atol=ATOL)


def test_prismatic_is_the_unit_couple_along_its_direction():
    np.testing.assert_allclose(prismatic("P", [3, 0, 4]).screws, [[0, 0, 0, 0.6, 0, 0.8]], atol=ATOL)
    assert S.is_infinite_pitch(prismatic("P", [1, 2, 3]).screws[0])


def test_helical_pitch_is_the_lead_over_two_pi():
    assert lead_to_pitch(2 * math.pi) == pytest.approx(1.0, abs=1e-15)
    assert lead_to_pitch(20.0) == pytest.approx(20.0 / (2 * math.pi), rel=1e-15)
    # axis z through the origin, pitch 1: (0, 0, 1; 0, 0, 1)
    np.testing.assert_allclose(helical("H", [0, 0, 5], [0, 0, 0], 1.0).screws, [[0, 0, 1, 0, 0, 1]], atol=ATOL)
    # axis x through (0, 2, 0), pitch 0.25: r × s = (0, 2, 0) × (1, 0, 0) = (0, 0, -2); plus h s
    joint = helical("H", [1, 0, 0], [0, 2, 0], 0.25)
    np.testing.assert_allclose(joint.screws, [[1, 0, 0, 0.25, 0, -2]], atol=ATOL)
    assert S.pitch(joint.screws[0]) == pytest.approx(0.25, abs=ATOL)


def test_cylindrical_is_the_rotation_and_translation_of_one_axis():
    rows = cylindrical("C", [0, 2, 0], [1, 0, 0]).screws
    # axis y through (1, 0, 0): r × s = (1, 0, 0) × (0, 1, 0) = (0, 0, 1)
    np.testing.assert_allclose(rows, [[0, 1, 0, 0, 0, 1], [0, 0, 0, 0, 1, 0]], atol=ATOL)


def test_spherical_spans_every_rotation_about_its_centre():
    center = np.array([1.0, 2.0, 3.0])
    joint = spherical("S", center)
    np.testing.assert_allclose(joint.screws[:, :3], np.eye(3), atol=ATOL)
    np.testing.assert_allclose(joint.screws[:, 3:], np.cross(center, np.eye(3)), atol=ATOL)
    # its wrench system: the forces through the centre (a 3-system of lines through one point)
    wrenches = ScrewSystem.span(joint.screws).reciprocal()
    assert wrenches.order == 3
    assert wrenches.contains(Screw(S.force([0.3, -1, 2], center)))
    assert not wrenches.contains(Screw(S.force([0.3, -1, 2], center + np.array([0.0, 0.0, 1.0]))))


def test_universal_is_two_rotations_through_its_centre():
    joint = universal("U", [1, 0, 0], [0, 1, 1], [0, 0, 1])
    assert joint.dof == 2
    for row in joint.screws:
        assert S.is_zero_pitch(row)
        point, _ = S.axis(row)
        # the axis passes through the centre: (centre - point) is parallel to the direction
        np.testing.assert_allclose(np.cross(np.array([0, 0, 1.0]) - point, row[:3]), 0, atol=ATOL)
    # its wrench system: the forces through the centre normal to both axes, and the couple along
    # that normal (Hunt): a 4-system holding the force (1, 0, 0) x (0, 1, 1) through the centre
    wrenches = ScrewSystem.span(joint.screws).reciprocal()
    assert wrenches.order == 4
    assert wrenches.contains(Screw(S.couple(np.cross([1, 0, 0], [0, 1, 1]))))


def test_parallelogram_translates_along_hinge_cross_rod():
    # paper 004 §2: hinge x, rods along -z: the coupler translates along x × (-z) = +y
    joint = parallelogram("Pi", [1, 0, 0], [0, 0, -1], actuated=True)
    np.testing.assert_allclose(joint.screws + 0.0, [[0, 0, 0, 0, 1, 0]], atol=ATOL)
    assert (joint.type, joint.actuated) == ("Pa", True)
    np.testing.assert_allclose(
        parallelogram("Pi", [0, 0, 2], [3, 0, 0]).screws, [[0, 0, 0, 0, 1, 0]], atol=ATOL
    )


@pytest.mark.parametrize(
    ("screw", "kind"),
    [
        (S.line([0, 1, 0], [1, 2, 3]), "vR"),
        (S.couple([0, 0, 2]), "vP"),
        (S.helical_twist([0, 1, 0], [1, 2, 3], 0.5), "vH"),
    ],
)
def test_virtual_joints_are_typed_by_pitch(screw, kind):
    joint = virtual("v1", screw)
    assert (joint.type, joint.dof, joint.virtual, joint.actuated) == (kind, 1, True, False)
    np.testing.assert_allclose(joint.screws[0], screw, atol=ATOL)


def test_symbolic_virtual_joints_are_typed_exactly():
    x = sympy.Symbol("x", real=True)
    assert virtual("v", [0, 0, 1, x, 0, 0]).type == "vR"
    assert virtual("v", [0, 0, 0, 1, x, 0]).type == "vP"
    assert virtual("v", [0, 0, 1, 0, 0, x**2 + 1]).type == "vH"


def test_joint_types_table_matches_the_constructors():
    built = [
        revolute("a", [0, 0, 1], [0, 0, 0]),
        prismatic("b", [1, 0, 0]),
        helical("c", [0, 0, 1], [0, 0, 0], 0.1),
        cylindrical("d", [0, 0, 1], [0, 0, 0]),
        universal("e", [1, 0, 0], [0, 1, 0], [0, 0, 0]),
        spherical("f", [0, 0, 0]),
        parallelogram("g", [1, 0, 0], [0, 0, 1]),
        virtual("h", [0, 0, 1, 0, 0, 0]),
        virtual("i", [0, 0, 0, 0, 0, 1]),
        virtual("j", [0, 0, 1, 0, 0, 1]),
    ]
    assert sorted(j.type for j in built) == sorted(JOINT_TYPES)
    for joint in built:
        assert joint.dof == JOINT_TYPES[joint.type]


def test_joints_are_immutable_values():
    joint = revolute("R", [0, 0, 1], [0, 0, 0])
    with pytest.raises(ValueError, match="read-only"):
        joint.screws[0, 0] = 5.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        joint.actuated = True  # type: ignore[misc]
    source = np.array([[0.0, 0, 1, 0, 0, 0]])
    copy = Joint("R2", "R", source)
    source[0, 0] = 1.0
    assert copy.screws[0, 0] == 0.0  # the joint holds its own copy


def test_str_names_type_and_flags():
    assert str(revolute("A1", [0, 0, 1], [0, 0, 0], actuated=True)) == "R joint 'A1' actuated"
    assert str(virtual("v1", [0, 0, 0, 0, 0, 1])) == "vP joint 'v1' virtual"


def test_to_dict_from_dict_round_trip_through_json():
    joints = [
        revolute("R", [0, 1, 1], [1, 2, 3], actuated=True),
        helical("H", [1, 0, 0], [0, 2, 0], 0.25),
        spherical("S", [0.5, 0, -1]),
        virtual("v", [0, 0, 0, 0, 1, 0]),
    ]
    for joint in joints:
        data = json.loads(json.dumps(joint.to_dict()))
        back = Joint.from_dict(data)
        assert (back.name, back.type, back.actuated, back.virtual) == (
            joint.name, joint.type, joint.actuated, joint.virtual
        )
        np.testing.assert_array_equal(back.screws, joint.screws)
        assert back.geometry == joint.geometry


# invariants ------------------------------------------------------------------------------------
@settings(max_examples=25)
@given(motion=rigid_motions(), seed=seeds)
def test_joints_follow_rigid_motions(motion, seed):
    rotation, translation = motion
    rng = np.random.default_rng(seed)
    axis, other, point = rng.normal(size=3), rng.normal(size=3), rng.normal(size=3)
    pitch = rng.uniform(-1, 1)

    def moved(p):
        return rotation @ p + translation

    pairs = [
        (revolute("R", axis, point), revolute("R", rotation @ axis, moved(point))),
        (prismatic("P", axis), prismatic("P", rotation @ axis)),
        (helical("H", axis, point, pitch), helical("H", rotation @ axis, moved(point), pitch)),
        (cylindrical("C", axis, point), cylindrical("C", rotation @ axis, moved(point))),
        (
            universal("U", axis, other, point),
            universal("U", rotation @ axis, rotation @ other, moved(point)),
        ),
        (parallelogram("Pa", axis, other), parallelogram("Pa", rotation @ axis, rotation @ other)),
    ]
    for before, after in pairs:
        np.testing.assert_allclose(
            after.screws, S.transform(before.screws, rotation, translation), atol=1e-9
        )
    # the spherical joint's axes are the frame's: the same 3-system, not the same rows
    before, after = spherical("S", point), spherical("S", moved(point))
    moved_rows = S.transform(before.screws, rotation, translation)
    assert ScrewSystem.span(after.screws).is_equivalent(ScrewSystem.span(moved_rows))


@settings(max_examples=25)
@given(factor=unit_factors, seed=seeds)
def test_a_change_of_unit_scales_moments_and_keeps_pitch_types(factor, seed):
    rng = np.random.default_rng(seed)
    axis, point, pitch = rng.normal(size=3), rng.normal(size=3), rng.uniform(-1, 1)
    # lines and helices: (s; k s0); the translation (0; d) of a C joint keeps its unit direction
    for make in (
        lambda k: revolute("R", axis, k * point),
        lambda k: helical("H", axis, k * point, k * pitch),
        lambda k: cylindrical("C", axis, k * point),
    ):
        base, scaled = make(1.0).screws, make(factor).screws
        finite = np.linalg.norm(base[:, :3], axis=1) > 0
        expected = np.where(finite[:, None], np.hstack([base[:, :3], factor * base[:, 3:]]), base)
        np.testing.assert_allclose(scaled, expected, rtol=1e-12, atol=1e-12 * max(1.0, factor))
    assert S.pitch(helical("H", axis, factor * point, factor * pitch).screws[0]) == pytest.approx(
        factor * pitch, rel=1e-9, abs=1e-12 * factor
    )
    assert virtual("v", revolute("R", axis, factor * point).screws[0]).type == "vR"
    assert virtual("v", prismatic("P", axis).screws[0]).type == "vP"


@settings(max_examples=25)
@given(seed=seeds)
def test_a_revolute_does_not_depend_on_which_axis_point_is_given(seed):
    rng = np.random.default_rng(seed)
    axis, point, shift = rng.normal(size=3), rng.normal(size=3), rng.uniform(-5, 5)
    # another point of the axis, and the axis reversed and shortened: the opposite unit twist
    other = revolute("R", -0.5 * axis, point + shift * axis)
    np.testing.assert_allclose(other.screws, -revolute("R", axis, point).screws, atol=1e-9)


# independent computations ----------------------------------------------------------------------
def test_spherical_equals_three_independent_revolutes_through_its_centre(rng):
    center = rng.normal(size=3)
    axes = rng.normal(size=(3, 3))
    revolutes = np.vstack([revolute(f"R{i}", a, center).screws for i, a in enumerate(axes)])
    assert ScrewSystem.span(revolutes).is_equivalent(ScrewSystem.span(spherical("S", center).screws))


def test_cylindrical_equals_a_revolute_plus_a_prismatic_on_its_axis(rng):
    axis, point = rng.normal(size=3), rng.normal(size=3)
    pair = np.vstack([revolute("R", axis, point).screws, prismatic("P", axis).screws])
    np.testing.assert_allclose(cylindrical("C", axis, point).screws, pair, atol=ATOL)


def test_parallelogram_coupler_twist_from_its_four_hinges(rng):
    # the four hinges of a planar parallelogram: the coupler's twist relative to the ground link,
    # with the rods' rotation cancelled, is the translation a × w (here from explicit hinge lines)
    a, w = unit(rng.normal(size=3)), rng.normal(size=3)
    w = w - (w @ a) * a  # rods normal to the hinges
    p0, side = rng.normal(size=3), np.cross(a, w)
    ground = [S.line(a, p0), S.line(a, p0 + side)]
    coupler = [S.line(a, p0 + w), S.line(a, p0 + side + w)]
    # rod rotation rate +1 about a ground hinge and -1 about the coupler hinge of the same rod
    twist = ground[0] - coupler[0]
    np.testing.assert_allclose(unit(twist[3:]), unit(np.cross(a, w)), atol=1e-9)
    np.testing.assert_allclose(twist[:3], 0, atol=1e-12)
    np.testing.assert_allclose(parallelogram("Pa", a, w).screws[0], [0, 0, 0, *unit(np.cross(a, w))], atol=1e-9)
    np.testing.assert_allclose(ground[1] - coupler[1], twist, atol=1e-9)


def test_symbolic_degenerate_joints_are_refused_like_numeric_ones():
    # identically parallel axes / rods along the hinges / a zero row: refused whatever the symbols
    t = sympy.Symbol("t")
    with pytest.raises(ScrewkitValueError, match="expected two non-parallel axes"):
        universal("U", [t, 0, 1], [2 * t, 0, 2], [0, t, 0])
    with pytest.raises(ScrewkitValueError, match="expected rods not parallel to the hinge axes"):
        parallelogram("Pa", [0, t, 1], [0, 3 * t, 3])
    with pytest.raises(ScrewkitValueError, match="expected non-zero screws, got a zero row"):
        Joint("X", "vR", np.array([[t - t, 0, 0, 0, 0, 0]], dtype=object))
    assert universal("U", [t, 0, 1], [0, 1, 0], [0, 0, 0]).dof == 2  # generically not parallel


def test_symbolic_joints_agree_with_numeric_ones_after_substitution():
    x, y, h = sympy.symbols("x y h", real=True)
    values = {x: 0.7, y: -1.3, h: 0.25}
    pairs = [
        (revolute("R", [0, 0, 2], [x, y, 0]), revolute("R", [0, 0, 2], [0.7, -1.3, 0])),
        (helical("H", [1, 0, 0], [0, x, y], h), helical("H", [1, 0, 0], [0, 0.7, -1.3], 0.25)),
        (spherical("S", [x, 1, y]), spherical("S", [0.7, 1, -1.3])),
        (universal("U", [1, 0, 0], [0, 1, 0], [x, y, 1]), universal("U", [1, 0, 0], [0, 1, 0], [0.7, -1.3, 1])),
    ]
    for symbolic, numeric in pairs:
        assert symbolic.screws.dtype == object and symbolic.geometry == {}
        substituted = np.array([[float(sympy.sympify(v).subs(values)) for v in row] for row in symbolic.screws])
        np.testing.assert_allclose(substituted, numeric.screws, atol=ATOL)


# errors: one per message -----------------------------------------------------------------------
SCREW = [[0.0, 0, 1, 0, 0, 0]]


@pytest.mark.parametrize("name", [3, ""])
def test_error_name_must_be_a_non_empty_string(name):
    with pytest.raises(ScrewkitTypeError, match="Expected the joint `name` to be a non-empty string"):
        Joint(name, "R", SCREW)


def test_error_unknown_joint_type():
    with pytest.raises(ScrewkitValueError, match=r"Joint 'X': expected `type` to be one of .*got 'Q'"):
        Joint("X", "Q", SCREW)


def test_error_wrong_screw_count():
    with pytest.raises(ScrewkitValueError, match=r"Joint 'X' of type R: expected 1 screw\(s\), got 2"):
        Joint("X", "R", SCREW * 2)


def test_error_screw_shape():
    with pytest.raises(ScrewkitValueError, match=r"Expected `screws of joint 'X'` to have shape \(\.\.\., 6\)"):
        Joint("X", "R", [[0.0, 0, 1, 0, 0]])


def test_error_zero_screw_row():
    with pytest.raises(ScrewkitValueError, match="Joint 'X': expected non-zero screws, got a zero row"):
        Joint("X", "U", [[0.0, 0, 1, 0, 0, 0], [0.0] * 6])


def test_error_actuated_multi_dof_joint():
    with pytest.raises(
        ScrewkitValueError, match="Joint 'X': only one-degree-of-freedom joints can be actuated, got a S joint with 3"
    ):
        Joint("X", "S", spherical("S", [0, 0, 0]).screws, actuated=True)


def test_error_from_dict_missing_fields():
    with pytest.raises(ScrewkitValueError, match=r"Expected joint data with fields \['screws'\], got \['name', 'type'\]"):
        Joint.from_dict({"name": "X", "type": "R"})


def test_error_from_dict_symbolic_screws_are_not_loaded():
    data = json.loads(json.dumps(revolute("X", [0, 0, 1], [sympy.Symbol("x"), 0, 0]).to_dict()))
    with pytest.raises(ScrewkitValueError, match=r"Joint 'X': expected numeric screws.*nothing is evaluated"):
        Joint.from_dict(data)


def test_error_universal_parallel_axes():
    with pytest.raises(ScrewkitValueError, match="Universal joint 'U': expected two non-parallel axes"):
        universal("U", [1, 0, 0], [-2, 0, 0], [0, 0, 0])


def test_error_parallelogram_rods_parallel_to_hinges():
    with pytest.raises(ScrewkitValueError, match="Parallelogram 'Pi': expected rods not parallel to the hinge axes"):
        parallelogram("Pi", [1, 0, 0], [3, 0, 0])


@pytest.mark.parametrize(
    "make",
    [
        lambda: revolute("R", [0, 0, 0], [1, 0, 0]),
        lambda: prismatic("P", [0, 0, 0]),
        lambda: helical("H", [0, 0, 0], [1, 0, 0], 0.1),
        lambda: cylindrical("C", [0, 0, 0], [1, 0, 0]),
    ],
)
def test_error_zero_axis(make):
    with pytest.raises(DegenerateGeometryError, match="non-zero direction"):
        make()


def test_error_symbolic_screws_in_the_analysis_core():
    import sympy

    from screwkit.core.singularity import classify
    from screwkit.graphs.joints import revolute
    from screwkit.graphs.jointtable import JointTable
    from screwkit.graphs.twistgraph import twist_graph

    graph = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [sympy.Symbol("a"), 0, 0], actuated=True))])
    # classify gives a symbolic graph's generic answers (screwkit.core.generic); the numeric table refuses it
    assert classify(graph).motion_type == "1R"
    with pytest.raises(ScrewkitTypeError, match=r"Expected numeric joint screws for the analysis core, got symbolic"):
        JointTable.from_graph(graph)
    with pytest.raises(ScrewkitTypeError, match=r"substitute values for the symbols .* or use screwkit.generic_analysis"):
        JointTable.from_graph(graph)


@pytest.mark.parametrize("flag", ["no", 1, None])
def test_error_actuated_flag_must_be_a_bool(flag):
    from screwkit.graphs.joints import revolute

    with pytest.raises(ScrewkitTypeError, match=rf"Joint 'R': expected `actuated` to be True or False, got {flag!r}"):
        revolute("R", [0, 0, 1], [0, 0, 0], actuated=flag)


def test_an_axis_whose_squared_length_underflows_gets_its_unit_vector():
    # (3, 0, 4)·2^-565 ≈ 1e-170: its squared length underflows to 0, and the axis was divided by a
    # zero norm (a RuntimeWarning, then an error about infinite numbers the caller never gave). A
    # power-of-two multiple of an axis is the same axis, bit for bit; by hand the unit axis
    # (0.6, 0, 0.8) through (1, 0, 0) has the moment (1, 0, 0) × (0.6, 0, 0.8) = (0, -0.8, 0).
    tiny = np.ldexp([3.0, 0.0, 4.0], -565)
    np.testing.assert_array_equal(
        revolute("R", tiny, [1.0, 0, 0]).screws, revolute("R", [3.0, 0, 4], [1.0, 0, 0]).screws
    )
    np.testing.assert_allclose(
        revolute("R", tiny, [1.0, 0, 0]).screws, [[0.6, 0, 0.8, 0, -0.8, 0]], rtol=0, atol=1e-15
    )
    np.testing.assert_array_equal(
        universal("U", tiny, [0, 2.0**-600, 0], [1.0, 0, 0]).screws,
        universal("U", [3.0, 0, 4], [0, 1.0, 0], [1.0, 0, 0]).screws,
    )
