"""Factoring bracket polynomials over the rationals, brackets as independent variables: linear
factors found by exact long division (:func:`factor_polynomial`), then sympy's multivariate
factoring for what remains, after an exact irreducibility test for multilinear polynomials.

A polynomial is a :data:`Polynomial`: ``{monomial: coefficient}``, a monomial being the sorted tuple
of its variables (a bracket's sorted labels), repeated by their degree.

Examples
--------
>>> from screwkit.gca import BracketPolynomial
>>> content, factors = factor_polynomial(BracketPolynomial.parse("[abcd][efgh] + [abcd][efgi]"))
>>> content, [(len(f), k) for f, k in factors]
(Fraction(1, 1), [(2, 1), (1, 1)])
"""

from __future__ import annotations

import math
from collections import Counter
from fractions import Fraction

from ..algebra import backend as B
from .brackets import BracketPolynomial

__all__ = [
    "SYMPY_FACTOR_MAX_BRACKETS",
    "Monomial",
    "Polynomial",
    "factor_polynomial",
]

#: A monomial in bracket variables: the sorted tuple of its variables, repeated by their degree.
Monomial = tuple[tuple[str, ...], ...]
#: A polynomial in bracket variables: ``{monomial: coefficient}``.
Polynomial = dict[Monomial, Fraction]


def _leading(poly: Polynomial) -> Monomial:
    """The leading monomial in lex order (monomials are sorted tuples of variables; compared from
    their largest variable down, which is lex order of exponent vectors for equal degrees)."""
    return max(poly, key=lambda m: m[::-1])


def _quotient_monomial(monomial: Monomial, divisor: Monomial) -> Monomial | None:
    rest = Counter(monomial)
    rest.subtract(divisor)
    if any(count < 0 for count in rest.values()):
        return None
    return tuple(sorted(rest.elements()))


def _divide(poly: Polynomial, divisor: Polynomial) -> Polynomial | None:
    """``poly / divisor`` if the division is exact, else None (multivariate long division)."""
    remainder, quotient = dict(poly), Counter[Monomial]()
    lead = _leading(divisor)
    while remainder:
        top = _leading(remainder)
        q = _quotient_monomial(top, lead)
        if q is None:
            return None
        c = remainder[top] / divisor[lead]
        quotient[q] += c  # type: ignore[assignment]
        for m, cm in divisor.items():
            key = tuple(sorted(q + m))
            value = remainder.get(key, Fraction(0)) - c * cm
            if value:
                remainder[key] = value
            else:
                remainder.pop(key, None)
    return {m: Fraction(c) for m, c in quotient.items() if c}


def _primitive(poly: Polynomial) -> tuple[Fraction, Polynomial]:
    """``(content, primitive part)``, the primitive part's leading coefficient positive."""
    values = list(poly.values())
    content = Fraction(
        math.gcd(*(v.numerator for v in values)), math.lcm(*(v.denominator for v in values))
    )
    if poly[_leading(poly)] < 0:
        content = -content
    return content, {m: c / content for m, c in poly.items()}


def _split(poly: Polynomial) -> list[Polynomial]:
    """Factors of a homogeneous polynomial in bracket variables, found as linear factors.

    A bracket monomial of the 24-term expansion has three brackets, so a product of non-constant
    sums has a factor of degree 1 in the brackets. For each bracket ``b`` of the first monomial
    ``m``, the candidate linear factor collects the monomials ``(m / b)·b'``; it is accepted only if
    it divides ``poly`` exactly (long division over the rationals), then the quotient is split
    again. Factors that exist only modulo the syzygies among brackets are not found here (the
    ordering search exposes them, ``gca.md`` §6.4).
    """
    first = min(poly)
    if len(poly) < 2 or len(first) < 2:
        return [poly]
    for variable in sorted(set(first)):
        cofactor = _quotient_monomial(first, (variable,))
        assert cofactor is not None
        linear: Polynomial = {}
        for m, c in poly.items():
            q = _quotient_monomial(m, cofactor)
            if q is not None and len(q) == 1:
                linear[q] = c
        if len(linear) < 2:
            continue
        quotient = _divide(poly, linear)
        if quotient is not None:
            return [linear, *_split(quotient)]
    return [poly]


#: Largest number of distinct brackets for which sympy's multivariate factoring is tried on a factor
#: that :func:`_split` cannot split (it takes ~0.1 s there, seconds for 30 brackets).
SYMPY_FACTOR_MAX_BRACKETS = 12


def _derivative(poly: Polynomial, variable: tuple[str, ...]) -> Polynomial:
    """``∂poly/∂variable`` of a polynomial of degree at most 1 in ``variable``."""
    out: Polynomial = {}
    for m, c in poly.items():
        if variable in m:
            k = m.index(variable)
            out[m[:k] + m[k + 1 :]] = c
    return out


def _product(a: Polynomial, b: Polynomial) -> Polynomial:
    out: dict[Monomial, Fraction] = {}
    for ma, ca in a.items():
        for mb, cb in b.items():
            key = tuple(sorted(ma + mb))
            out[key] = out.get(key, Fraction(0)) + ca * cb
    return {m: c for m, c in out.items() if c}


def _multilinear_irreducible(poly: Polynomial) -> bool:
    """True if ``poly`` is multilinear (degree ≤ 1 in each variable) and irreducible over the
    rationals; False says nothing (sympy decides then).

    Derivation: if a multilinear ``p = f g`` then ``deg_x p = deg_x f + deg_x g ≤ 1``, so the
    factors have disjoint variables. For ``x`` in ``f`` and ``y`` in ``g``,
    ``p ∂²p/∂x∂y = f g f_x g_y = ∂p/∂x ∂p/∂y``. Conversely, inside one irreducible factor ``h`` (``p = h r``,
    ``r`` free of ``x, y``), write ``h = a x y + b x + c y + d``: ``p p_xy − p_x p_y = r² (a d − b c)``,
    and ``a d = b c`` would give ``a h = (a x + c)(a y + b)`` (or, for ``a = 0``, ``b c = 0``: ``h``
    free of ``x`` or ``y``), each factor missing ``x`` or ``y``, so not divisible by the prime ``h``:
    a contradiction. Hence ``x, y`` share an irreducible factor iff ``p p_xy ≠ p_x p_y`` (the pairwise
    test of Shpilka & Volkovich, read-once polynomial identity testing, STOC 2008), and ``p`` is
    irreducible iff the graph of those pairs on its variables is connected. Exact arithmetic over
    the rationals throughout.
    """
    if any(len(set(m)) != len(m) for m in poly):
        return False
    variables = sorted({v for m in poly for v in m})
    reached, frontier = {variables[0]}, [variables[0]]
    while frontier:
        x = frontier.pop()
        p_x = _derivative(poly, x)
        for y in variables:
            if y in reached:
                continue
            if _product(poly, _derivative(p_x, y)) != _product(p_x, _derivative(poly, y)):
                reached.add(y)
                frontier.append(y)
    return len(reached) == len(variables)


def _sympy_factors(poly: Polynomial) -> list[Polynomial]:
    """Irreducible factors over the rationals (sympy ``factor_list``), repeated by multiplicity;
    brackets are independent variables there, so a factorisation found is exact. A multilinear
    polynomial proved irreducible exactly (:func:`_multilinear_irreducible`) is returned as it is
    without calling sympy."""
    variables = sorted({v for m in poly for v in m})
    if len(poly) < 3 or len(variables) > SYMPY_FACTOR_MAX_BRACKETS or _multilinear_irreducible(poly):
        return [poly]
    sympy = B.sympy_module()
    symbols = sympy.symbols(f"x0:{len(variables)}")
    index = {v: s for v, s in zip(variables, symbols, strict=True)}
    expr = sympy.Add(
        *(
            sympy.Rational(c.numerator, c.denominator) * sympy.Mul(*(index[v] for v in m))
            for m, c in poly.items()
        )
    )
    content, factors = sympy.factor_list(expr, *symbols)
    if len(factors) == 1 and factors[0][1] == 1:
        return [poly]
    found: list[Polynomial] = [{(): Fraction(int(content.p), int(content.q))}]
    for factor, multiplicity in factors:
        terms = sympy.Poly(factor, *symbols).terms()
        converted = {
            tuple(v for v, e in zip(variables, exponents, strict=True) for _ in range(e)): Fraction(
                int(c.p), int(c.q)
            )
            for exponents, c in terms
        }
        found += [converted] * multiplicity
    return found


def factor_polynomial(poly: BracketPolynomial) -> tuple[Fraction, list[tuple[Polynomial, int]]]:
    """``poly = content × ∏ factor**multiplicity`` (primitive factors, each listed once).

    Linear factors are found by exact long division (:func:`_split`), the rest by sympy's
    ``factor_list`` when it has at most :data:`SYMPY_FACTOR_MAX_BRACKETS` brackets and is not
    proved irreducible first (:func:`_multilinear_irreducible`).

    Parameters
    ----------
    poly : BracketPolynomial

    Returns
    -------
    content : fractions.Fraction
    factors : list of (Polynomial, int)
        Each primitive factor (leading coefficient positive) and its multiplicity.

    Examples
    --------
    >>> from screwkit.gca import BracketPolynomial
    >>> content, factors = factor_polynomial(BracketPolynomial.parse("2[abcd][efgh] + 2[abcd][efgi]"))
    >>> content, factors[1]
    (Fraction(2, 1), ({(('a', 'b', 'c', 'd'),): Fraction(1, 1)}, 1))
    """
    content = Fraction(1)
    found: list[tuple[Polynomial, int]] = []
    for factor in (f for part in _split(dict(poly._canonical())) for f in _sympy_factors(part)):
        if set(factor) == {()}:
            content *= factor[()]
            continue
        scale, primitive = _primitive(factor)
        content *= scale
        for k, (known, multiplicity) in enumerate(found):
            if known == primitive:
                found[k] = (known, multiplicity + 1)
                break
        else:
            found.append((primitive, 1))
    return content, found

