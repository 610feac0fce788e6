"""readable_bases: each system's readable basis over a batch equals ScrewSystem.readable_basis's.

The expected bases are the per-pose method's, system by system (an independent path: the method's
own null spaces, rank tests and greedy picks, one system at a time). Batches hold systems of one,
two and three couples in general position, and systems placed at every decision the batch takes
near its threshold: a couple within ``1e3 rtol`` of a frame axis (the axis is then taken), a first
coordinate that round-off decides (the sign of the SVD's vector), directions just above and below
round-off (a couple or a screw), nearly dependent couples (the rank of the null spaces), lines and
screws of finite pitch (not couples: the method itself), and tolerances outside the batch's range.
"""

import numpy as np
import pytest

from screwkit.algebra import readable_bases as RB
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.exceptions import ScrewkitValueError

RTOL = 1e-9


def per_system(rows, orders, rtol, lengths):
    """The expected bases: ScrewSystem.readable_basis, one system at a time."""
    expected = np.full(rows.shape, np.nan)
    for i, (order, length) in enumerate(zip(orders, lengths, strict=True)):
        system = ScrewSystem.from_independent(rows[i, :order], rtol=rtol, length_scale=float(length))
        expected[i, :order] = system.readable_basis()
    return expected


class CountedSystems:
    """ScrewSystem for readable_bases, counting the systems it sends to the method one by one."""

    taken = 0

    @classmethod
    def from_independent(cls, *args, **kwargs):
        cls.taken += 1
        return ScrewSystem.from_independent(*args, **kwargs)


def assert_same_bases(rows, orders, lengths, rtol=RTOL):
    """The batch's bases equal the method's; returns how many systems went to the method."""
    expected = per_system(rows, orders, rtol, lengths)
    CountedSystems.taken = 0
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(RB, "ScrewSystem", CountedSystems)
        found = RB.readable_bases(rows, orders, rtol=rtol, length_scale=lengths)
    # unit rows: 1e-12 absolute is 1e-12 relative (and no sign or choice of row may differ)
    np.testing.assert_allclose(found, expected, rtol=0.0, atol=1e-12)
    assert np.array_equal(np.isnan(found), np.isnan(expected))
    return CountedSystems.taken


def couples(rng, count, order, moments=None, directions=1e-16):
    """Systems of ``order`` couples with round-off directions, in lengths 0.5 … 600."""
    lengths = rng.uniform(0.5, 600.0, count)
    moments = rng.normal(size=(count, order, 3)) if moments is None else moments
    noise = rng.normal(size=(count, order, 3)) * directions
    rows = np.concatenate([noise, moments * lengths[:, None, None]], axis=-1)
    return np.concatenate([rows, np.zeros((count, 6 - order, 6))], axis=1), np.full(count, order), lengths


@pytest.mark.parametrize("order", [1, 2, 3])
def test_couples_in_general_position(order):
    rng = np.random.default_rng(order)
    rows, orders, lengths = couples(rng, 300, order)
    assert assert_same_bases(rows, orders, lengths) == 0  # all over the batch
    if order > 1:  # the method's own steps over the batch: the same LAPACK calls, the same bits
        expected = per_system(rows, orders, RTOL, lengths)
        np.testing.assert_array_equal(
            RB.readable_bases(rows, orders, rtol=RTOL, length_scale=lengths), expected
        )


def test_one_couple_near_a_frame_axis_and_with_a_first_coordinate_round_off_decides():
    rng = np.random.default_rng(7)
    count = 400
    moments = rng.normal(size=(count, 1, 3))
    # within 1e3 rtol of an axis and around that threshold (1e-7 … 1e-5 from the x, y or z axis)
    near = moments[:200]
    axis = rng.integers(0, 3, 200)
    near[np.arange(200), 0, axis] = rng.choice([-1.0, 1.0], 200)
    others = np.ones((200, 3), dtype=bool)
    others[np.arange(200), axis] = False
    near[others.nonzero()[0], 0, others.nonzero()[1]] *= 10.0 ** rng.uniform(-13, -4, 400)
    # a first coordinate of 0, of round-off size, and around the batch's CLEAR (1e-6)
    moments[200:, 0, 0] = np.concatenate(
        [np.zeros(50), rng.normal(size=150) * 10.0 ** rng.uniform(-17, -4, 150)]
    )
    one_by_one = assert_same_bases(*couples(rng, count, 1, moments))
    assert 0 < one_by_one < count // 2  # the decisions near 1e3 rtol only


def test_directions_around_round_off_and_nearly_dependent_couples():
    rng = np.random.default_rng(11)
    rows, orders, lengths = couples(rng, 300, 2, directions=0.0)
    # directions of the unit rows from 1e-18 to 1e-6: couples for the method below about rtol
    rows[:, :2, :3] = rng.normal(size=(300, 2, 3)) * 10.0 ** rng.uniform(-18, -6, (300, 1, 1))
    rows[:, :2, :3] *= np.linalg.norm(rows[:, :2, 3:], axis=-1, keepdims=True) / lengths[:, None, None]
    # the second couple within 1e-12 … 1e-6 of the first's direction (the null spaces' rank)
    close = (
        rows[150:, 0, 3:]
        + rng.normal(size=(150, 3)) * 10.0 ** rng.uniform(-12, -6, (150, 1)) * lengths[150:, None]
    )
    rows[150:, 1, 3:] = close
    one_by_one = assert_same_bases(rows, orders, lengths)
    assert 0 < one_by_one < 250


def test_lines_screws_and_mixed_systems_take_the_method():
    rng = np.random.default_rng(3)
    count = 60
    lengths = rng.uniform(0.5, 10.0, count)
    directions = rng.normal(size=(count, 3, 3))
    points = rng.normal(size=(count, 3, 3))
    pitches = np.where(rng.random((count, 3, 1)) < 0.5, 0.0, rng.normal(size=(count, 3, 1)))
    rows = np.concatenate([directions, np.cross(points, directions) + pitches * directions], axis=-1)
    rows[:20, 1] = np.concatenate(
        [np.zeros((20, 3)), rng.normal(size=(20, 3))], axis=-1
    )  # a couple and a screw
    rows = np.concatenate([rows, np.zeros((count, 3, 6))], axis=1)
    orders = rng.integers(0, 4, count)
    assert assert_same_bases(rows, orders, lengths) == np.count_nonzero(orders)


@pytest.mark.parametrize("rtol", [1e-3, 1e-14])
def test_tolerances_outside_the_batchs_range_take_the_method(rtol):
    rng = np.random.default_rng(5)
    assert assert_same_bases(*couples(rng, 20, 2), rtol=rtol) == 20


def test_the_svd_of_a_row_is_the_householder_vector_on_this_numpy():
    # what the closed form for one couple reads of LAPACK; were it not so, one couple would take
    # the method's steps over the batch (the tests above then check those)
    rows = np.random.default_rng(2).normal(size=(500, 1, 3))
    vt = np.linalg.svd(rows)[2][:, 0]
    np.testing.assert_allclose(
        vt, -np.sign(rows[:, :, 0]) * rows[:, 0] / np.linalg.norm(rows[:, 0], axis=-1)[:, None], atol=1e-15
    )
    np.testing.assert_array_equal(np.linalg.svd(-rows)[2], np.linalg.svd(rows)[2])
    assert RB._svd_of_a_row_is_householder()


def test_zero_order_systems_and_padding():
    rows = np.zeros((2, 3, 6))
    rows[1, 0, 5] = 2.0
    found = RB.readable_bases(rows, [0, 1], rtol=RTOL, length_scale=[1.0, 1.0])
    assert np.isnan(found[0]).all() and np.isnan(found[1, 1:]).all()
    np.testing.assert_array_equal(found[1, 0], [0, 0, 0, 0, 0, 1.0])


@pytest.mark.parametrize(
    ("rows", "orders", "lengths", "match"),
    [
        (np.zeros((2, 6)), [1, 1], [1.0, 1.0], "shape"),
        (np.zeros((2, 1, 6)), [1], [1.0, 1.0], "shape"),
        (np.zeros((2, 1, 6)), [1, 2], [1.0, 1.0], "orders"),
        (np.zeros((2, 1, 6)), [1.0, 1.0], [1.0, 1.0], "orders"),
    ],
)
def test_bad_arrays_are_refused_by_name(rows, orders, lengths, match):
    with pytest.raises(ScrewkitValueError, match=match):
        RB.readable_bases(rows, orders, rtol=RTOL, length_scale=lengths)


@pytest.mark.parametrize("factor", [1e-200, 1e200])
def test_couples_of_any_magnitude(factor):
    # the method scales each row by a power of two before any square; the batch's closed form
    # takes its sizes without squares: the same bases for rows of 1e-200 or 1e200
    rng = np.random.default_rng(9)
    for order in (1, 2):
        rows, orders, lengths = couples(rng, 40, order)
        assert assert_same_bases(rows * factor, orders, lengths) == 0


@pytest.mark.parametrize(
    ("rows", "length", "message"),
    [
        (np.full((1, 2, 6), np.nan), [1.0], r"finite `rows`"),
        (np.ones((1, 2, 6)), [0.0], r"`length_scale` to be positive and finite"),
        (np.ones((1, 2, 6)), [np.nan], r"`length_scale` to be positive and finite"),
        (np.ones((1, 2, 6)), [-1.0], r"`length_scale` to be positive and finite"),
    ],
)
def test_rows_and_lengths_that_a_screw_system_refuses_are_refused(rows, length, message):
    with pytest.raises(ScrewkitValueError, match=message):
        RB.readable_bases(rows, [2], rtol=1e-9, length_scale=length)
