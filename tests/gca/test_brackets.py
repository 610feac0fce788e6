"""Tests of screwkit.gca.brackets: brackets, monomials and polynomials, canonical forms, evaluation.

Every reference value is computed independently of the module (tests/gca_references.py: numpy
determinants, an exact integer 6×6 determinant, a literal implementation of the dotted-notation
definition, hand derivations written out in the test) or re-derived from gca.md / paper 002.
"""

from fractions import Fraction

import numpy as np
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from screwkit import gca
from screwkit.gca import (
    Bracket,
    BracketMonomial,
    BracketPolynomial,
)

from ..gca_references import (
    build,
    det4,
    generic_points,
    h4_sampler,
    parity,
    plucker,
    polynomials,
    reference_value,
    stacked,
)
from ..strategies import rigid_motions, seeds, unit_factors


def test_bracket_canonical_form_and_equality():
    b = Bracket("gikj")
    assert b.labels == ("g", "i", "k", "j")
    assert b.sorted_labels == ("g", "i", "j", "k") and b.sign == -1  # one inversion (k, j)
    assert Bracket(("a", "b", "c", "d")).sign == 1 and Bracket("badc").sign == 1
    assert Bracket("aabc").is_structurally_zero and Bracket("aabc") == 0
    assert Bracket("bacd") == -Bracket("abcd") and Bracket("bacd") != Bracket("abcd")
    assert Bracket("abdc") == Bracket("bacd")  # both −[abcd]
    assert hash(Bracket("abdc")) == hash(Bracket("bacd"))
    assert Bracket("abcd") == BracketMonomial(["abcd"]) == BracketPolynomial([Bracket("abcd")])
    assert Bracket("r1 r2 r3 r4").labels == ("r1", "r2", "r3", "r4")
    assert str(Bracket("r1 r2 r3 r4")) == "[r1 r2 r3 r4]" and str(b) == "[gikj]"
    assert b.to_latex() == "[gikj]" and Bracket("r1 r2 r3 r4").to_latex() == r"[r1\,r2\,r3\,r4]"


@given(st.permutations(range(4)), seeds)
def test_bracket_sign_is_the_determinant_sign_under_permutations(order, seed):
    rng = np.random.default_rng(seed)
    points = dict(zip("pqrs", rng.normal(size=(4, 4)), strict=True))
    labels = [("p", "q", "r", "s")[i] for i in order]
    bracket = Bracket(labels)
    assert bracket.sign == parity(order)
    expected = det4(*(points[x] for x in labels))
    assert bracket.evaluate(points) == pytest.approx(expected, rel=1e-12, abs=1e-12)
    assert bracket.sign * det4(*(points[x] for x in "pqrs")) == pytest.approx(expected, abs=1e-12)


def test_bracket_evaluation_is_batched_and_broadcast(rng):
    points = {"p": rng.normal(size=(5, 3, 4)), "q": rng.normal(size=4)}
    points |= {"r": rng.normal(size=(3, 4)), "s": rng.normal(size=(5, 1, 4))}
    value = Bracket("pqrs").evaluate(points)
    assert value.shape == (5, 3)
    np.testing.assert_allclose(
        value, det4(points["p"], points["q"], points["r"], points["s"]), rtol=1e-12, atol=1e-12
    )


def test_bracket_values_by_number_of_infinite_points(rng):
    """gca.md §5.1 table, finite points (r, 1), infinite points (d, 0)."""
    p, q, r, s = (np.r_[rng.normal(size=3), 1.0] for _ in range(4))
    u, v, w, x = (np.r_[rng.normal(size=3), 0.0] for _ in range(4))
    pts = {"p": p, "q": q, "r": r, "s": s, "u": u, "v": v, "w": w, "x": x}
    value = {
        lab: Bracket(lab).evaluate(pts)
        for lab in ("puvw", "quvw", "uxvw", "upvw", "pquv", "pqru", "pqrs")
    }
    d = np.linalg.det
    assert value["puvw"] == pytest.approx(-d(np.stack([u[:3], v[:3], w[:3]])), rel=1e-12)
    assert value["quvw"] == pytest.approx(value["puvw"], rel=1e-12)  # independent of the point
    assert value["uxvw"] == pytest.approx(0, abs=1e-14)  # four infinite points
    assert value["upvw"] == pytest.approx(d(np.stack([u[:3], v[:3], w[:3]])), rel=1e-12)
    assert value["pquv"] == pytest.approx(-(q - p)[:3] @ np.cross(u[:3], v[:3]), rel=1e-12)
    assert value["pqru"] == pytest.approx(-np.cross((q - p)[:3], (r - p)[:3]) @ u[:3], rel=1e-12)
    tetra = np.stack([(q - p)[:3], (r - p)[:3], (s - p)[:3]])
    assert value["pqrs"] == pytest.approx(-d(tetra), rel=1e-12)
    # [pqrs] = −L(p, q) ∘ L(r, s) (gca.md §1)
    lpq, lrs = plucker(p, q), plucker(r, s)
    assert value["pqrs"] == pytest.approx(-(lpq[:3] @ lrs[3:] + lpq[3:] @ lrs[:3]), rel=1e-12)


@given(rigid_motions(), unit_factors, seeds)
def test_brackets_are_rigid_invariant_and_scale_with_the_unit_cubed(motion, unit, seed):
    rng = np.random.default_rng(seed)
    rotation, translation = motion
    points = generic_points(rng, labels="pqrs", infinite="s")
    moved = {
        x: np.r_[(v[:3] @ rotation.T + v[3] * translation) * unit, v[3]] for x, v in points.items()
    }
    before, after = Bracket("pqrs").evaluate(points), Bracket("pqrs").evaluate(moved)
    assert after == pytest.approx(before * unit**3, rel=1e-9, abs=1e-9 * unit**3)


def test_polynomial_combines_like_terms_and_keeps_the_first_letter_order():
    p = BracketPolynomial.parse("[abdf][cghj] - [abdh][cgfj] + [bacd][efgh] + [abcd][hgfe]")
    assert str(p) == "[abdf][cghj] - [abdh][cgfj]"  # [bacd][efgh] = −[abcd][hgfe]
    q = BracketPolynomial.parse("[badf][cghj] + 2 [abdf][cghj]")  # = [abdf][cghj]
    assert str(q) == "-[badf][cghj]" and q == BracketPolynomial.parse("[abdf][cghj]")
    assert len(BracketPolynomial.parse("[abcd] - [bacd] - 2[abcd]")) == 0
    assert str(BracketPolynomial()) == "0" and BracketPolynomial.parse("0") == 0
    assert str(BracketPolynomial.parse("1/2 [abcd] - 3/4")) == "1/2 [abcd] - 3/4"
    assert BracketPolynomial.parse("[aabc][defg] + [abcd]") == Bracket("abcd")
    assert p.labels == ("a", "b", "c", "d", "f", "g", "h", "j")
    assert BracketPolynomial.parse("[abcd] + [abce]").relabel({"e": "d"}) == 2 * Bracket("abcd")
    assert repr(p) == "BracketPolynomial('[abdf][cghj] - [abdh][cgfj]')"


def test_polynomial_latex():
    p = BracketPolynomial.parse("[abdf][cghj] - 1/2 [abdh][cgfj] + 3[r1 r2 r3 r4]")
    assert p.to_latex() == r"[abdf][cghj] - \tfrac{1}{2} [abdh][cgfj] + 3 [r1\,r2\,r3\,r4]"
    assert BracketMonomial(["abcd"], -2).to_latex() == "-2 [abcd]"


@given(polynomials, polynomials, seeds)
def test_ring_operations_agree_with_evaluation(left, right, seed):
    points = generic_points(np.random.default_rng(seed), shape=(3,), labels="abcdef")
    a, b = build(left), build(right)
    va, vb = reference_value(left, points), reference_value(right, points)
    tol = {"rel": 1e-9, "abs": 1e-9}
    for expr, expected in [
        (a + b, va + vb),
        (a - b, va - vb),
        (a * b, va * vb),
        (-a, -va),
        (3 - a, 3 - va),
        (Fraction(1, 2) * b, vb / 2),
    ]:
        got = np.broadcast_to(expr.evaluate(points), (3,))
        assert got == pytest.approx(np.broadcast_to(expected, (3,)), **tol)
    assert a + b == b + a and a * b == b * a and (a - a) == 0


def test_exact_evaluation_with_sympy_points(rng):
    ints = {x: rng.integers(-5, 6, size=4) for x in "abcdefgh"}
    exact = {x: [sympy.Integer(int(v)) for v in p] for x, p in ints.items()}
    poly = BracketPolynomial.parse("[abcd][efgh] - 1/3 [abce][dfgh]")
    value = poly.evaluate(exact)
    matrix = {
        b: sympy.Matrix([exact[x] for x in b]).det() for b in ("abcd", "efgh", "abce", "dfgh")
    }
    expected = (
        matrix["abcd"] * matrix["efgh"] - sympy.Rational(1, 3) * matrix["abce"] * matrix["dfgh"]
    )
    assert value == expected
    assert float(value) == pytest.approx(
        poly.evaluate({x: p.astype(float) for x, p in ints.items()})
    )
    assert poly.to_sympy({x: p.astype(float) for x, p in ints.items()}) == expected
    t = sympy.Symbol("t")
    pts = {"a": [0, 0, 0, 1], "b": [t, 0, 0, 1], "c": [0, 1, 0, 1], "d": [0, 0, 1, 1]}
    assert sympy.expand(Bracket("abcd").evaluate(pts)) == -t  # −det(b−a, c−a, d−a)


def test_h4_bracket_with_one_finite_point_is_independent_of_it():
    """gca.md §5.1 / paper 002: [eikj] = [gikj] = [aikj] for finite points of weight 1."""
    points = stacked(h4_sampler, 10, seed=13)
    values = [det4(*(points[x] for x in lab)) for lab in ("gikj", "eikj", "aikj")]
    np.testing.assert_allclose(values[1], values[0], rtol=1e-12)
    np.testing.assert_allclose(values[2], values[0], rtol=1e-12)


def test_floats_are_refused_in_equality_quietly():
    assert (Bracket("abcd") == 1.0) is False
    assert gca.BracketPolynomial() == 0
