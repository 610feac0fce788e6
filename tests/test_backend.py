"""Tests of screwkit._backend: promotion, rank decisions, unit invariance, errors."""

import numpy as np
import pytest
import sympy

from screwkit import _backend as B
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError


def test_promotion_turns_floats_into_exact_rationals():
    numeric, _ = B.promote(np.array([0.1, 2.5]), np.array([sympy.Symbol("x")], dtype=object))
    assert numeric.dtype == object and numeric[0] == sympy.Rational(1, 10) and numeric[1] == sympy.Rational(5, 2)


def test_rank_is_unit_invariant_with_derived_length_scale():
    # a line 500 mm from the origin and a couple: independent in any unit
    rows_mm = np.array([[0, 0, 1, 500.0, 0, 0], [0, 0, 0, 1.0, 0, 0], [0, 0, 2, 1000.0, 1.0, 0]])
    rows_m = rows_mm.copy()
    rows_m[:, 3:] /= 1000.0
    assert B.screw_rank(rows_mm) == B.screw_rank(rows_m) == 3
    assert B.scale_moments(rows_mm, None)[1] == pytest.approx(1000 * B.scale_moments(rows_m, None)[1])


def test_batched_rank():
    rows = np.zeros((2, 3, 6))
    rows[0, :, :3] = np.eye(3)
    rows[1, 0, 0] = rows[1, 1, 0] = 1.0
    np.testing.assert_array_equal(B.screw_rank(rows), [3, 1])


def test_symbolic_rank_is_generic():
    x = sympy.Symbol("x")
    rows = np.array([[1, x, 0, 0, 0, 0], [1, 1, 0, 0, 0, 0]], dtype=object)
    assert B.screw_rank(rows) == 2  # although x = 1 makes it 1: symbolic answers are conditions


def test_nullspace_is_reciprocal(rng):
    rows = rng.normal(size=(2, 6))
    basis = B.screw_nullspace(rows)
    products = rows[:, :3] @ basis[:, 3:].T + rows[:, 3:] @ basis[:, :3].T
    assert basis.shape == (4, 6) and np.abs(products).max() < 1e-12


def test_error_boolean_scalar():
    with pytest.raises(ScrewkitTypeError, match="Expected a number or a sympy expression, got a boolean True"):
        B.to_sympy(True)


def test_error_undecidable_symbolic_zero():
    with pytest.raises(ScrewkitValueError, match=r"Cannot decide whether x \+ 1 is zero: it depends on \['x'\]"):
        B.is_zero(sympy.Symbol("x") + 1, atol=0)


def test_error_length_scale():
    with pytest.raises(ScrewkitValueError, match="Expected `length_scale` to be a positive finite number or None, got 0"):
        B.scale_moments(np.zeros((1, 6)), 0)


def test_error_symbolic_batch_det():
    with pytest.raises(ScrewkitValueError, match=r"Expected a single symbolic square matrix, got shape \(2, 2, 2\)"):
        B.det(np.full((2, 2, 2), sympy.Integer(1), dtype=object))


def test_error_ragged_symbolic_array():
    with pytest.raises(ScrewkitTypeError, match=r"In `rows`: Expected a number or a sympy expression, got list \[x\]"):
        B.as_array([[sympy.Symbol("x")], [1, 2]], "rows", (None,))


def test_error_symbolic_nan():
    with pytest.raises(ScrewkitValueError, match="Expected `v` to hold finite expressions, got nan"):
        B.as_array([sympy.nan, sympy.Symbol("x")], "v", (2,))


def test_is_dof_accepts_numpy_integers_and_rejects_booleans():
    assert B.is_dof(np.int64(4)) and B.is_dof(0) and not B.is_dof(True) and not B.is_dof(np.bool_(True))
    assert not B.is_dof(4.0) and not B.is_dof(-1)
