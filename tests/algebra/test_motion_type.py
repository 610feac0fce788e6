"""motion_type: the derived length scale ignores round-off directions at rtol; helical freedoms
(``1H``, ``2T1H``) with their pitch (Hunt 1978: ``h = s·s0 / s·s``), hand-built screws."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.algebra import screw as S
from screwkit.algebra.motion_type import motion_type
from screwkit.algebra.ranks import characteristic_length
from screwkit.algebra.screwsystem import ScrewSystem
from tests.strategies import rigid_motions, unit_factors

# A translation along z whose direction carries a 1e-8 round-off component along x (a "screw with a
# 1e-8 component"), beside a rotation about z through (1, 0, 0): the 1e-8 is a direction only at a
# tolerance finer than 1e-8; at 1e-9 the pair is two rotations (the second about an x-parallel axis
# 1e8 from the origin: s0 / |s| = (0, 0, 1) / 1e-8).
NOISY_TRANSLATION = np.array([1e-8, 0, 0, 0, 0, 1.0])
HINGE = S.revolute_twist([0, 0, 1], [1, 0, 0])


@pytest.mark.parametrize("rtol", [1e-7, 1e-6, 1e-3, 0.1])
def test_a_round_off_direction_does_not_set_the_length_scale(rtol):
    rows = np.array([HINGE, NOISY_TRANSLATION])
    # the hinge's |s0| / |s| = 1 (axis 1 from the origin) is the length; 1e8 would be the noise's
    assert characteristic_length(rows, None, rtol) == pytest.approx(1.0)
    assert motion_type(rows, rtol=rtol) == "1T1R"
    assert motion_type(ScrewSystem.span(rows, rtol=rtol)) == "1T1R"


def test_a_direction_above_rtol_is_a_direction():
    rows = np.array([HINGE, NOISY_TRANSLATION])
    assert characteristic_length(rows, None, 1e-9) == pytest.approx(1e8)
    assert motion_type(rows, rtol=1e-9) == "2R"


def test_through_the_origin_the_data_unit_is_the_reference():
    # a rotation about z through the origin has no length: the 1e-8 is compared with the unit 1
    rows = np.array([S.revolute_twist([0, 0, 1], [0, 0, 0]), NOISY_TRANSLATION])
    assert motion_type(rows, rtol=1e-6) == "1T1R"
    assert characteristic_length(rows, None, 1e-6) == 1.0


def test_a_single_row_sets_its_own_length():
    # nothing to compare a lone screw with: its own |s0| / |s| is the length (a rotation)
    assert characteristic_length(NOISY_TRANSLATION[None], None, 0.1) == pytest.approx(1e8)
    assert motion_type(NOISY_TRANSLATION[None], rtol=0.1) == "1R"


@pytest.mark.parametrize(
    ("generators", "expected"),
    [
        # a lone screw of pitch 5 about z through (1, 2, 0): (z; r × z + 5 z), pitch z·(5 z) = 5
        ([S.helical_twist([0, 0, 1], [1, 2, 0], 5.0)], "1H (pitch 5 mm/rad)"),
        ([S.helical_twist([0, 0, 1], [1, 2, 0], -0.25)], "1H (pitch -0.25 mm/rad)"),
        # translations across the axis leave the pitch: (z; m + v) with v ⟂ z has z·(m + v) = z·m
        ([S.helical_twist([0, 0, 1], [1, 0, 0], 5.0), S.prismatic_twist([1, 0, 0])], "1T1H (pitch 5 mm/rad)"),
        (
            [
                S.helical_twist([0, 1, 0], [0, 0, 3], 2.0),
                S.prismatic_twist([1, 0, 0]),
                S.prismatic_twist([0, 0, 1]),
            ],
            "2T1H (pitch 2 mm/rad)",
        ),
        # a translation along the axis: helix − 5 × translation is a pure rotation (a cylindrical pair)
        ([S.helical_twist([0, 0, 1], [1, 0, 0], 5.0), S.prismatic_twist([0, 0, 1])], "1T1R"),
        # a translation with a component along the axis, (1, 0, 1): helix − 5√2 × it is a rotation
        (
            [
                S.helical_twist([0, 0, 1], [1, 0, 0], 5.0),
                S.prismatic_twist([1, 0, 1]),
                S.prismatic_twist([0, 1, 0]),
            ],
            "2T1R",
        ),
        # all three translations: any moment, so the rotation is free (a helix + 3T is 3T1R)
        ([S.helical_twist([0, 0, 1], [1, 0, 0], 5.0), *(S.prismatic_twist(e) for e in np.eye(3))], "3T1R"),
        # two freedoms other than translations: counted as rotations (the system holds many pitches)
        ([S.helical_twist([0, 0, 1], [0, 0, 0], 1.0), S.helical_twist([1, 0, 0], [0, 0, 0], 1.0)], "2R"),
        # a pitch below rtol × length (1e-12 on an axis 5 from the origin) is a rotation
        ([S.helical_twist([1, 1, 1], [1, 5, 0], 1e-12)], "1R"),
    ],
)
def test_helical_freedoms_are_labelled_with_their_pitch(generators, expected):
    rows = np.array(generators, dtype=float)
    assert motion_type(rows, length_unit="mm") == expected
    assert motion_type(ScrewSystem.span(rows), length_unit="mm") == expected


def test_helical_labels_are_batched():
    helix = np.array([S.helical_twist([0, 0, 1], [1, 0, 0], 5.0)])
    hinge = np.array([S.revolute_twist([0, 0, 1], [1, 0, 0])])
    assert motion_type(np.stack([helix, hinge])).tolist() == ["1H (pitch 5 length units/rad)", "1R"]


@settings(max_examples=40, deadline=None)
@given(rigid_motions(), unit_factors, st.floats(0.1, 10.0), st.sampled_from([0, 1, 2]))
def test_helical_pitch_is_invariant_under_frame_and_unit(motion, unit, pitch, translations):
    rotation, translation = motion
    rows = np.array(
        [
            S.helical_twist([0, 0, 1], [1, 2, 0], pitch),
            *(S.prismatic_twist(e) for e in np.eye(3)[:translations]),  # across the axis: kept
        ]
    )
    moved = S.transform(rows, rotation, translation) * np.r_[np.ones(3), np.full(3, unit)]
    # a rigid motion keeps the pitch (Hunt 1978), a unit change multiplies it by the factor
    label = motion_type(moved)
    kind, _, rest = label.partition(" (pitch ")
    assert kind == f"{translations}T1H" * bool(translations) + "1H" * (not translations)
    assert float(rest.removesuffix(" length units/rad)")) == pytest.approx(pitch * unit, rel=1e-3)  # 4 digits shown


@pytest.mark.parametrize("unit", [1.0, 1000.0])
def test_far_axes_are_not_round_off_in_any_unit(unit):
    # two hinges 10 and 12 metres from the origin (10,000 mm): their directions are not round-off at
    # a loose rtol in millimetres (a rule "direction below rtol × moment" would call them couples)
    rows = np.array([S.revolute_twist([0, 0, 1], [10, 0, 0]), S.revolute_twist([1, 0, 0], [0, 12, 0])])
    scaled = rows * np.r_[np.ones(3), np.full(3, unit)]
    assert motion_type(scaled, rtol=1e-3) == "2R"
    assert motion_type(scaled[:1], rtol=1e-3) == "1R"
