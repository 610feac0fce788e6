"""The constraint closeness near a leg's own loss of order (screwkit.core._leg_weights).

Expected values: orders from the joint screws written out in the certify tests (independent of the
wrench pass), the linear fall of a distance to a simple zero, and the weighted rows' definition
computed here with numpy.
"""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.core._leg_weights import TAPER, weighted_rows
from tests.analysis.test_certify_two_limb import MCGILL, distal_vertical_height, mcgill_constraint_orders


def orthonormal(rng, k):
    return np.linalg.qr(rng.normal(size=(6, k)))[0].T


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 4))
def test_well_conditioned_spans_leave_the_leg_as_it_is(seed, order):
    # every singular value of the span above TAPER of the largest: the same rows (C C^T = I)
    rng = np.random.default_rng(seed)
    span = orthonormal(rng, 5)
    rows = np.zeros((6, 6))
    rows[:order] = np.linalg.qr((rng.normal(size=(order, 5)) @ span).T)[0].T
    np.testing.assert_allclose(weighted_rows(rows, [(span, np.array(5))]), rows, atol=1e-12)


def test_a_direction_is_shrunk_by_the_span_s_small_singular_value_it_needs():
    # span of couples x and x' = (cos a, sin a): singular values sqrt(1 +- cos a) on the bisector
    # v+ = (cos a/2, sin a/2) and v- = (sin a/2, -cos a/2); weights 1 and tan(a/2) / TAPER. The couple
    # y has coordinates (sin a/2, -cos a/2 / (tan(a/2) / TAPER)): its row is y over their norm
    angle = 0.02
    branches = np.zeros((2, 6))
    branches[0, 3], branches[1, 3:5] = 1.0, (np.cos(angle), np.sin(angle))
    rows = np.zeros((6, 6))
    rows[0, 4] = 1.0
    weighted = weighted_rows(rows, [(branches, np.array(2))])
    half = angle / 2
    expected = 1 / np.hypot(np.sin(half), np.cos(half) * TAPER / np.tan(half))
    assert abs(weighted[0, 4] - expected) < 1e-12 * expected and expected < 0.2
    assert np.allclose(weighted[0, [0, 1, 2, 3, 5]], 0.0) and np.allclose(weighted[1:], 0.0)


def test_mcgill_closeness_falls_linearly_where_both_distal_links_turn_vertical_and_not_for_one():
    # both distal parallelograms flat in parallel planes: the plate's constraint order 1 (from the
    # joint screws); leg I alone flat: order 2, leg II holds both couples
    both, one = distal_vertical_height(0.0), distal_vertical_height(-20.0)
    assert mcgill_constraint_orders([0.0, 0.0, both, 0.0]) == ([1, 1], 1)
    assert mcgill_constraint_orders([0.0, -20.0, one, 0.0]) == ([1, 2], 2)
    offsets = np.array([1.0, 0.1, 0.01])
    near_both = np.stack([np.zeros(3), np.zeros(3), both + offsets, np.zeros(3)], axis=-1)
    closeness = MCGILL.at(near_both).singularities.closeness["constraint"]
    np.testing.assert_allclose(closeness[1:] / closeness[:-1], 0.1, rtol=0.05)
    at_one = MCGILL.at(np.array([[0.0, -20.0, one, 0.0]])).singularities
    assert at_one.closeness["constraint"][0] > 0.05 and at_one.codes[0] == 0
