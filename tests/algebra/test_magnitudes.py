"""The algebra layer over the whole float range (issue 24): screws of magnitude 1e-300 to 1e300.

Every rank decision scales each row by a power of two before it squares anything
(:func:`screwkit.algebra.ranks.unit_rows`), so a system's order, its reciprocal and its membership
tests do not depend on the size of its generators. The expected values here come from an independent
computation: the exact rank and null space of the small-integer rows (sympy, rational arithmetic),
and hand formulas for the magnitude, the unit screw and the pitch in :class:`fractions.Fraction`.
"""

import math
import warnings
from fractions import Fraction

import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.algebra import screw as S
from screwkit.algebra.incidence import lines_intersect as sk_lines_intersect
from screwkit.algebra.incidence import point_on_line as sk_point_on_line
from screwkit.algebra.motion_type import motion_type
from screwkit.algebra.ranks import SWAP, screw_rank
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.algebra.screwvalue import Screw
from screwkit.exceptions import ScrewkitValueError

MAGNITUDES = settings(max_examples=60, deadline=None, derandomize=True, database=None)
small_rows = st.lists(
    st.lists(st.integers(-3, 3), min_size=6, max_size=6).filter(any), min_size=1, max_size=7
)
exponents = st.integers(-300, 300)


def exact_rank(rows):
    return sympy.Matrix(rows).rank()


def exact_reciprocal(rows):
    """Rows spanning the screws reciprocal to ``rows``: the exact null space of ``rows @ SWAP``."""
    swapped = sympy.Matrix(rows) * sympy.Matrix(SWAP.astype(int))
    return np.array([[float(v) for v in vector] for vector in swapped.nullspace()]).reshape(-1, 6)


def scaled(rows, row_exponents):
    """Each integer row times its own power of ten (exactly representable up to rounding of 10**e)."""
    return np.array([np.array(row, dtype=float) * 10.0**e for row, e in zip(rows, row_exponents, strict=False)])


@MAGNITUDES
@given(rows=small_rows, data=st.data())
def test_orders_and_reciprocals_do_not_depend_on_the_generators_sizes(rows, data):
    row_exponents = data.draw(st.lists(exponents, min_size=len(rows), max_size=len(rows)))
    big = scaled(rows, row_exponents)
    rank = exact_rank(rows)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an overflow warning is a failure
        system = ScrewSystem.span(big)
        assert system.order == rank
        assert screw_rank(big) == rank
        reciprocal = system.reciprocal()
        assert reciprocal.order == 6 - rank
        assert reciprocal.is_equivalent(ScrewSystem.span(exact_reciprocal(rows))) if rank < 6 else True
        # every generator, at unit size, lies in the system built from the scaled ones
        assert system.contains(np.array(rows, dtype=float))
        assert (system + ScrewSystem.span(np.array(rows, dtype=float))).order == rank


@pytest.mark.parametrize("size", [1e-160, 1e153, 1e155, 1e200, 1e300])
def test_two_independent_screws_span_a_two_system_at_any_size(size):
    """The issue's case: entries 1e155 gave order 0 (squares overflowed to infinity)."""
    pair = size * np.array([[1.0, 0, 0, 0, 0, 0], [0, 1.0, 0, 0, 0, 0]])
    assert ScrewSystem.span(pair).order == 2
    assert ScrewSystem.span(pair).reciprocal().order == 4
    assert ScrewSystem.span(size * np.array([[1.0, 0, 0, 0, 0, 1], [0, 1.0, 0, 0, 0, 1]])).order == 2


def hand_magnitude(row):
    """|s|, or |s0| when s = 0, as the square root of an exact integer sum (the row's integers)."""
    s, s0 = row[:3], row[3:]
    return math.sqrt(sum(v * v for v in s)) if any(s) else math.sqrt(sum(v * v for v in s0))


@MAGNITUDES
@given(row=st.lists(st.integers(-3, 3), min_size=6, max_size=6).filter(any), exponent=exponents)
def test_magnitude_normalisation_and_pitch_at_any_size(row, exponent):
    factor = 10.0**exponent
    screw = Screw(np.array(row, dtype=float) * factor)
    size = hand_magnitude(row)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert math.isclose(float(screw.magnitude), size * factor, rel_tol=1e-12)
        np.testing.assert_allclose(screw.normalized().coords, np.array(row) / size, rtol=1e-12, atol=1e-15)
        s, s0 = row[:3], row[3:]
        if any(s):
            expected = Fraction(sum(a * b for a, b in zip(s, s0, strict=True)), sum(a * a for a in s))
            assert math.isclose(float(screw.pitch), float(expected), rel_tol=1e-12, abs_tol=1e-15)
            point, _ = screw.axis
            cross = np.cross(s, s0) / sum(a * a for a in s)  # the axis point nearest the origin, s × s0 / s·s
            np.testing.assert_allclose(point, cross, rtol=1e-12, atol=1e-12)
        else:
            assert screw.pitch == math.inf


def test_a_reciprocal_product_beyond_the_float_range_is_refused_not_infinite():
    big = Screw([1e200, 0, 0, 0, 0, 0])
    other = Screw([0, 0, 0, 1e200, 0, 0])
    with pytest.raises(ScrewkitValueError, match=r"reciprocal product .* overflows the float range"):
        big.reciprocal_product(other)
    assert float(S.reciprocal_product(big.coords * 1e-100, other.coords)) == 1e300


def signed(rows):
    """Each row times the sign of its first entry larger than 1e-9 in magnitude."""
    firsts = [row[np.abs(row) > 1e-9][0] for row in rows]
    return rows * np.sign(firsts)[:, None]


@MAGNITUDES
@given(rows=small_rows, exponent=exponents)
def test_readable_bases_pitch_ranges_and_motion_types_match_those_at_unit_size(rows, exponent):
    """The same system given by generators 10**exponent times larger reads the same (the unit-size
    system is the independent reference: its rows' squares are small integers)."""
    unit = ScrewSystem.span(np.array(rows, dtype=float))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        big = ScrewSystem.span(np.array(rows, dtype=float) * 10.0**exponent)
        # the readable basis is defined up to each row's sign (a completed couple's orientation)
        np.testing.assert_allclose(signed(big.readable_basis()), signed(unit.readable_basis()), atol=1e-9)
        assert motion_type(big.basis) == motion_type(unit.basis)
        if unit.couple_subsystem().order < unit.order:
            np.testing.assert_allclose(big.pitch_range(), unit.pitch_range(), rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("size", [1e-200, 1e155, 1e250])
def test_incidence_tests_at_any_size(size):
    x_axis, y_axis, offset_y = (size * np.array(v, dtype=float) for v in ([1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 1, 0, -1, 0, 0]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert sk_lines_intersect(x_axis, y_axis) and not sk_lines_intersect(x_axis, offset_y)
        assert sk_point_on_line(size * np.array([3.0, 0, 0, 1]), x_axis)
        assert not sk_point_on_line(size * np.array([0.0, 1, 0, 1]), x_axis)
