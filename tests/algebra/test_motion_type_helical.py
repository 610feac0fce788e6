"""Helical freedoms in motion types (with their pitch) and the rtol-aware length scale.

Hand derivations: a screw ``(s; r × s + h s)`` has pitch ``h = s·s0 / s·s`` (Ball 1900 §13; Hunt 1978
§5.3). Adding a translation ``v`` of the system changes it by ``s·v / s·s``: a translation along the
screw's axis turns the helical freedom into a rotation (a cylindrical pair, 1T1R), one perpendicular to
it leaves the pitch as it is.
"""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from screwkit.algebra import screw as S
from screwkit.algebra.motion_type import motion_type
from screwkit.algebra.ranks import characteristic_length
from screwkit.algebra.rigid_motions import adjoint, rotation_matrix

HELIX = S.helical_twist([0, 0, 1], [1, 2, 0], 5.0)  # pitch 5 about the line x = 1, y = 2


@pytest.mark.parametrize(
    ("generators", "expected"),
    [
        ([HELIX], "1H (pitch 5 mm/rad)"),
        ([S.helical_twist([0, 0, 1], [0, 0, 0], -0.25)], "1H (pitch -0.25 mm/rad)"),  # left-handed
        ([HELIX, S.prismatic_twist([1, 0, 0])], "1T1H (pitch 5 mm/rad)"),  # s·v = 0: pitch kept
        ([HELIX, S.prismatic_twist([1, 0, 0]), S.prismatic_twist([0, 1, 0])], "2T1H (pitch 5 mm/rad)"),
        ([HELIX, S.prismatic_twist([0, 0, 1])], "1T1R"),  # cylindrical: the translation cancels the pitch
        ([HELIX, S.prismatic_twist([1, 0, 1])], "1T1R"),  # s·v ≠ 0 is enough
        ([S.revolute_twist([0, 0, 1], [1, 2, 0])], "1R"),
        ([HELIX, S.revolute_twist([1, 0, 0], [0, 0, 0])], "2R"),  # two freedoms: no single pitch
    ],
)
def test_helical_freedoms_read_with_their_pitch(generators, expected):
    assert motion_type(np.array(generators), length_unit="mm") == expected


def test_a_near_couple_gives_no_length_scale_at_a_looser_rtol():
    # a rotation about z and a screw whose direction is 1e-8 of its moment: at rtol 1e-9 the direction
    # counts (an axis 1e8 away: two rotations), at rtol 1e-6 it is round-off and the screw a translation
    rows = np.array([[0, 0, 1, 0, 0, 0], [1e-8, 0, 0, 0, 1, 0]], dtype=float)
    assert characteristic_length(rows, None, rtol=1e-6) == 1.0
    assert characteristic_length(rows, None, rtol=1e-9) == pytest.approx(1e8)
    assert motion_type(rows, rtol=1e-6) == "1T1R"
    assert motion_type(rows, rtol=1e-9) == "2R"


angles = st.floats(-3.0, 3.0)
offsets = st.floats(-50.0, 50.0)


@given(angle=angles, axis=st.sampled_from([(1, 0, 0), (0, 1, 0), (0, 0, 1), (0.6, 0, 0.8)]), shift=st.tuples(offsets, offsets, offsets),
       unit=st.sampled_from([1e-3, 1.0, 25.4, 1e3]), pitch=st.floats(0.1, 20.0))
def test_helical_label_is_invariant_under_frame_change_and_scales_with_the_unit(angle, axis, shift, unit, pitch):
    rows = np.array([S.helical_twist([0, 0, 1], [1, 2, 0], pitch), S.prismatic_twist([1, 0, 0])])
    g = np.eye(4)[None].repeat(len(rows), axis=0)
    g[:, :3, :3] = rotation_matrix(np.asarray(axis, dtype=float), np.asarray(angle))
    g[:, :3, 3] = shift
    moved = adjoint(g, rows)
    moved[:, 3:] *= unit  # lengths in a unit `unit` times smaller: pitch numbers `unit` times larger
    label = motion_type(moved, length_unit="u")
    assert label.startswith("1T1H (pitch ")
    read = float(label.removeprefix("1T1H (pitch ").removesuffix(" u/rad)"))
    assert read == pytest.approx(pitch * unit, rel=1e-5)
