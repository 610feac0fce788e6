"""Tests of screwkit.algebra.backend: promotion, rank decisions, unit invariance, errors."""

import warnings

import numpy as np
import pytest
import sympy

from screwkit.algebra import backend as B
from screwkit.algebra.branch_values import ones_like, zeros_like
from screwkit.algebra.checks import check_rotation
from screwkit.algebra.ranks import scale_moments, screw_nullspace, screw_rank
from screwkit.algebra.zero_tests import (
    is_exactly_zero,
    is_zero,
    ratio,
    unit_directions,
    vanishes,
    where_zero,
    zero_vectors,
)
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError


def test_promotion_turns_floats_into_exact_rationals():
    numeric, _ = B.promote(np.array([0.1, 2.5]), np.array([sympy.Symbol("x")], dtype=object))
    assert numeric.dtype == object and numeric[0] == sympy.Rational(1, 10) and numeric[1] == sympy.Rational(5, 2)


def test_rank_is_unit_invariant_with_derived_length_scale():
    # a line 500 mm from the origin and a couple: independent in any unit
    rows_mm = np.array([[0, 0, 1, 500.0, 0, 0], [0, 0, 0, 1.0, 0, 0], [0, 0, 2, 1000.0, 1.0, 0]])
    rows_m = rows_mm.copy()
    rows_m[:, 3:] /= 1000.0
    assert screw_rank(rows_mm) == screw_rank(rows_m) == 3
    assert scale_moments(rows_mm, None)[1] == pytest.approx(1000 * scale_moments(rows_m, None)[1])


def test_batched_rank():
    rows = np.zeros((2, 3, 6))
    rows[0, :, :3] = np.eye(3)
    rows[1, 0, 0] = rows[1, 1, 0] = 1.0
    np.testing.assert_array_equal(screw_rank(rows), [3, 1])


def test_symbolic_rank_is_generic():
    x = sympy.Symbol("x")
    rows = np.array([[1, x, 0, 0, 0, 0], [1, 1, 0, 0, 0, 0]], dtype=object)
    assert screw_rank(rows) == 2  # although x = 1 makes it 1: symbolic answers are conditions


def test_nullspace_is_reciprocal(rng):
    rows = rng.normal(size=(2, 6))
    basis = screw_nullspace(rows)
    products = rows[:, :3] @ basis[:, 3:].T + rows[:, 3:] @ basis[:, :3].T
    assert basis.shape == (4, 6) and np.abs(products).max() < 1e-12


def test_error_boolean_scalar():
    with pytest.raises(ScrewkitTypeError, match="Expected a number or a sympy expression, got a boolean True"):
        B.to_sympy(True)


def test_error_undecidable_symbolic_zero():
    with pytest.raises(ScrewkitValueError, match=r"Cannot decide whether x \+ 1 is zero: it depends on \['x'\]"):
        is_zero(sympy.Symbol("x") + 1, atol=0)


def test_error_length_scale():
    with pytest.raises(ScrewkitValueError, match=r"Expected `length_scale` to be a positive finite number in \[1e-100, 1e\+100\] or None, got 0"):
        scale_moments(np.zeros((1, 6)), 0)


def test_error_symbolic_batch_det():
    with pytest.raises(ScrewkitValueError, match=r"Expected a single symbolic square matrix, got shape \(2, 2, 2\)"):
        B.det(np.full((2, 2, 2), sympy.Integer(1), dtype=object))


def test_error_ragged_symbolic_array():
    with pytest.raises(ScrewkitTypeError, match=r"In `rows`: Expected a number or a sympy expression, got list \[x\]"):
        B.as_array([[sympy.Symbol("x")], [1, 2]], "rows", (None,))


def test_error_symbolic_nan():
    with pytest.raises(ScrewkitValueError, match="Expected `v` to hold finite expressions, got nan"):
        B.as_array([sympy.nan, sympy.Symbol("x")], "v", (2,))


@pytest.mark.parametrize("value", [sympy.I * sympy.Symbol("t"), sympy.I, sympy.sqrt(-2)])
def test_error_complex_symbolic_entry(value):
    with pytest.raises(ScrewkitValueError, match=r"Expected `point` to hold real expressions, got .*I"):
        B.as_array([value, 0, 0], "point", (3,))


def test_real_symbolic_entries_are_accepted():
    t = sympy.Symbol("t")
    assert list(B.as_array([sympy.sqrt(t), t, sympy.Rational(1, 2)], "point", (3,))) == [sympy.sqrt(t), t, sympy.Rational(1, 2)]


def test_is_dof_accepts_numpy_integers_and_rejects_booleans():
    assert B.is_dof(np.int64(4)) and B.is_dof(0) and not B.is_dof(True) and not B.is_dof(np.bool_(True))
    assert not B.is_dof(4.0) and not B.is_dof(-1)


# --- the named numeric/symbolic branch points (docs/architecture.md §4) ---------------------------------------

x = sympy.Symbol("x")


def test_exact_fraction_known_values():
    from fractions import Fraction

    assert B.exact_fraction(sympy.Rational(-3, 4)) == Fraction(-3, 4)
    assert B.exact_fraction(np.int32(5)) == Fraction(5) and B.exact_fraction(Fraction(1, 3)) == Fraction(1, 3)
    for not_exact in (0.5, True, np.bool_(False), x, sympy.sqrt(2), "1"):
        assert B.exact_fraction(not_exact) is None


def test_from_fraction_parity():
    from fractions import Fraction

    exact = B.from_fraction(Fraction(-7, 8), symbolic=True)
    assert isinstance(exact, sympy.Rational) and exact == sympy.Rational(-7, 8)
    assert B.from_fraction(Fraction(-7, 8), symbolic=False) == float(exact) == -0.875


def test_infinity_and_is_infinite_parity():
    assert B.infinity(symbolic=True) is sympy.oo and B.infinity(symbolic=False) == float("inf")
    for symbolic in (True, False):
        assert B.is_infinite(B.infinity(symbolic=symbolic)) and B.is_infinite(-B.infinity(symbolic=symbolic))
    assert not B.is_infinite(x) and not B.is_infinite(sympy.Integer(3)) and not B.is_infinite(3.0)


def test_is_exactly_zero_is_generic_and_exact():
    assert is_exactly_zero((x + 1) ** 2 - x**2 - 2 * x - 1)
    assert not is_exactly_zero(x)  # generically non-zero: decided, unlike is_zero which refuses
    assert is_exactly_zero(0.0) and is_exactly_zero(np.float64(-0.0))
    assert not is_exactly_zero(1e-300)  # no tolerance


def test_is_exactly_zero_proves_non_zero_at_a_point_without_simplifying(monkeypatch):
    # a non-zero exact value at the random point proves the expression is not identically zero, so
    # sympy's simplify is not needed; identities still go to expand / simplify
    calls = []
    real_simplify = sympy.simplify
    monkeypatch.setattr(sympy, "simplify", lambda e, *a, **k: calls.append(e) or real_simplify(e, *a, **k))
    y = sympy.Symbol("y")
    assert not is_exactly_zero(sympy.sin(x) * y**3 - sympy.cos(y) * x + 7)
    assert not calls
    assert is_exactly_zero(sympy.sin(x) ** 2 + sympy.cos(x) ** 2 - 1) and calls
    assert not is_exactly_zero(sympy.sqrt(x**2 + 1) - x)  # not rational at the point: simplify decides
    # one-off decisions do not grow the random point's cache (a long session makes many)
    from screwkit.algebra import symbolic
    z = sympy.Symbol("z_cache")
    point = symbolic.generic_point(np.array([z], dtype=object))
    before = len(point._cache)
    assert not any(is_exactly_zero(z**k + k) for k in range(1, 50))
    assert len(point._cache) == before


def test_vanishes_is_scale_invariant_numerically_and_exact_symbolically():
    a, b = np.array([1.0, 2.0, 3.0]), np.array([2.0, 4.0, 6.0 + 1e-8])
    for scale in (1e-6, 1.0, 1e6):  # |a × b| / (|a| |b|) ≈ 4e-10 whatever the unit
        assert vanishes(np.cross(a * scale, b), a * scale, b, rtol=1e-9)
        assert not vanishes(np.cross(a * scale, b), a * scale, b, rtol=1e-10)
    batch = np.stack([a, b])
    np.testing.assert_array_equal(vanishes(batch - batch[::-1], batch, rtol=1e-9), [False, False])
    t = sympy.Symbol("t")
    parallel = B.cross(np.array([t, 2 * t, 0], dtype=object), np.array([1, 2, 0], dtype=object))
    assert vanishes(parallel, rtol=0.5) and zero_vectors(parallel)
    assert not vanishes(np.array([t - 1, 0, 0], dtype=object), rtol=0.5)  # generic: t ≠ 1


def test_ratio_where_zero_and_unit_directions_keep_the_branch():
    np.testing.assert_array_equal(ratio(np.array([1.0, -2.0]), np.array([2.0, 0.0])), [0.5, np.inf])
    assert ratio(x * (x + 1), x + 1) == x and ratio(x, x - x) is sympy.oo
    assert where_zero(0.0, 1.0, 2.0) == 1.0 and where_zero(x, 1, 2) == 2
    np.testing.assert_array_equal(unit_directions(np.array([[0.0, 3, 4]])), [[0, 0.6, 0.8]])
    symbolic = np.array([x, 0, 1], dtype=object)
    assert unit_directions(symbolic) is symbolic  # stays polynomial


def test_check_rotation_refuses_numeric_non_rotations_and_takes_symbolic_ones_as_given():
    # symbolic entries may obey relations the symbols do not state (c² + s² = 1): not refused
    c, s = sympy.symbols("c s")
    assert check_rotation(np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], dtype=object)) is None
    assert check_rotation(np.eye(3)[None].repeat(2, 0)) is None
    for bad, det in ((2 * np.eye(3), "7.99"), (np.diag([1.0, 1.0, -1.0]), "-1.0")):
        with pytest.raises(ScrewkitValueError, match=rf"Expected `R` to be a proper rotation matrix .* det = {det}"):
            check_rotation(bad, "R")


def test_zeros_and_ones_like_keep_the_branch():
    numeric = np.array([[2.0, 3.0]])
    symbolic = np.array([[x, sympy.Integer(3)]], dtype=object)
    np.testing.assert_array_equal(zeros_like(numeric), [[0.0, 0.0]])
    np.testing.assert_array_equal(ones_like(numeric), [[1.0, 1.0]])
    for made, value in ((zeros_like(symbolic), 0), (ones_like(symbolic), 1)):
        assert made.dtype == object and made.shape == (1, 2)
        assert all(isinstance(v, sympy.Integer) and v == value for v in made.flat)
    assert zeros_like(numeric).dtype == ones_like(numeric).dtype == np.float64


def test_is_symbolic_without_sympy_objects_is_false():
    assert not B.is_symbolic(np.array([1, 2], dtype=object), [1.0, (2, 3)], 4)
    assert B.is_symbolic([1.0, (2, x)])


def test_median_is_numpy_median():
    # the reports' typical magnitudes and proportionality constants: numpy.median's value exactly
    rng = np.random.default_rng(11)
    for n in (0, 1, 2, 3, 6, 7, 12, 25):
        for _ in range(20):
            values = rng.standard_normal(n) * 10.0 ** rng.uniform(-6, 6, n)
            if n and rng.random() < 0.2:
                values[rng.integers(n)] = np.nan
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore")  # numpy.median warns on an empty array
                expected = float(np.median(values))
            got = B.median(values)
            assert got == expected or (np.isnan(expected) and np.isnan(got))
