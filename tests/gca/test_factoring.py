"""Tests of screwkit.gca.factoring: the exact irreducibility test of multilinear polynomials.

Every reference value is computed independently of the module (tests/gca_references.py: numpy
determinants, an exact integer 6×6 determinant, a literal implementation of the dotted-notation
definition, hand derivations written out in the test) or re-derived from gca.md / paper 002.
"""

from fractions import Fraction

import numpy as np
import sympy


def _random_multilinear(rng, variables, terms):
    """A random multilinear polynomial (monomials: sorted tuples of distinct variables)."""
    poly = {}
    for _ in range(terms):
        chosen = rng.choice(len(variables), size=int(rng.integers(1, min(4, len(variables)) + 1)), replace=False)
        monomial = tuple(sorted(variables[i] for i in chosen))
        poly[monomial] = poly.get(monomial, Fraction(0)) + Fraction(int(rng.integers(-3, 4)) or 1)
    return {m: c for m, c in poly.items() if c}


def _sympy_irreducible(poly):
    """Independent reference: sympy's factor_list over the rationals."""
    variables = sorted({v for m in poly for v in m})
    symbols = sympy.symbols(f"x0:{len(variables)}")
    index = dict(zip(variables, symbols, strict=True))
    expr = sum(sympy.Rational(c.numerator, c.denominator) * sympy.Mul(*(index[v] for v in m)) for m, c in poly.items())
    factors = sympy.factor_list(expr)[1]
    return len(factors) == 1 and factors[0][1] == 1


def test_multilinear_irreducibility_agrees_with_sympy():
    from screwkit.gca.factoring import _multilinear_irreducible, _product

    rng = np.random.default_rng(7)
    names = [(c,) for c in "abcdefgh"]
    seen = {True: 0, False: 0}
    for trial in range(60):
        if trial % 2:  # a product of two sums in disjoint variables: reducible
            split = int(rng.integers(1, 7))
            poly = _product(_random_multilinear(rng, names[:split], 3), _random_multilinear(rng, names[split:], 3))
        else:
            poly = _random_multilinear(rng, names, int(rng.integers(2, 9)))
        if len(poly) < 2:
            continue
        expected = _sympy_irreducible(poly)
        assert _multilinear_irreducible(poly) == expected, poly
        seen[expected] += 1
    assert seen[True] >= 10 and seen[False] >= 10  # both answers exercised


def test_multilinear_irreducibility_declines_squares():
    from screwkit.gca.factoring import _multilinear_irreducible

    a, b = ("a",), ("b",)
    assert not _multilinear_irreducible({(a, a): Fraction(1), (b,): Fraction(1)})  # a² + b: sympy decides
    assert _multilinear_irreducible({(a, b): Fraction(1), (b,): Fraction(1), (a,): Fraction(1)})  # ab + a + b
    assert not _multilinear_irreducible({(a, b): Fraction(1), (a,): Fraction(1)})  # a(b + 1)
