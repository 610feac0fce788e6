"""Tests of screwkit.gca.factored: collecting factors, dotted pairs and products of sums (gca.md §6.3).

Every reference value is computed independently of the module (tests/gca_references.py: numpy
determinants, an exact integer 6×6 determinant, a literal implementation of the dotted-notation
definition, hand derivations written out in the test) or re-derived from gca.md / paper 002.
"""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from screwkit.gca import (
    Bracket,
    BracketPolynomial,
    collect_factors,
    superbracket_expansion,
)

from ..gca_references import (
    H4_DECLARED,
    build,
    generic_points,
    h4_sampler,
    module_terms,
    polynomials,
    reference_value,
    stacked,
)


@given(polynomials, st.sampled_from(["abcd", "bcde", "aefb"]))
def test_collect_factors_without_declarations_is_exact(terms, factor):
    poly = Bracket(factor) * build(terms)
    factored = collect_factors(poly)
    assert factored.expand() == poly and factored.substitutions == ()
    if len(poly):
        assert Bracket(factor) in factored.common or -Bracket(factor) in factored.common


def test_collect_factors_content_sign_and_pairs():
    f = collect_factors(BracketPolynomial.parse("-2[abcd][efgh] + 4[abcd][efgi]"))
    assert f.coefficient == -2 and f.common == (Bracket("abcd"),)
    assert str(f.rest) == "[efgh] - 2 [efgi]" and str(f) == "-2 [abcd]([efgh] - 2 [efgi])"
    pair = collect_factors(BracketPolynomial.parse("[abdf][cghj] - [abdh][cgfj]"))
    assert str(pair) == "[a b d ḟ][c g ḣ j]" and pair.factors == (pair.rest,)
    assert pair.to_latex() == r"[abd\dot{f}][cg\dot{h}j]"
    single = collect_factors(BracketPolynomial.parse("3[abcd][efgh]"))
    assert single.factors == (Bracket("abcd"), Bracket("efgh")) and str(single) == "3 [abcd][efgh]"


def test_collect_factors_uses_the_declared_incidences():
    poly = BracketPolynomial.parse("[eikj] - [gikj]")
    assert str(collect_factors(poly, finite="eg", infinite="ijk")) == "0"
    assert len(collect_factors(poly).rest.terms) == 2  # [eikj] − [gikj] stays without them
    p = BracketPolynomial.parse("-[abdf][cghj][eikj] + [abdh][cefj][gikj]")
    without_collinear = collect_factors(p, finite="aceg", infinite="bdfhijk")
    assert len(without_collinear.rest.terms) == 2  # [cefj] = [cgfj] needs e, g, j collinear
    factored = collect_factors(p, **H4_DECLARED)
    samples = stacked(h4_sampler, 20, seed=21)
    np.testing.assert_allclose(factored.evaluate(samples), p.evaluate(samples), rtol=1e-12)


def test_collect_factors_pairs_a_term_whose_exchange_repeats_a_letter():
    """A 3-RPS superbracket (a, c, e the sphere centres; b, d, f the leg directions; g, h, i the R
    axes) once stopped with StopIteration: exchanging c and h in ``[abcg][dche][afei]`` writes the
    zero bracket [cefc], and the term it pairs with is another one of that dotted expansion. The
    factored form must equal the polynomial (numpy determinants on random points)."""
    poly = BracketPolynomial.parse(
        "[abcd][efac][ghei] - [abcd][efah][gcei] - [abcd][efgc][ahei] + [abcd][efgh][acei] "
        "- [abce][dfag][chei] + [abce][dagc][fhei] - [abce][dagh][fcei] + [abcf][deag][chei] "
        "+ [abcg][defc][ahei] - [abcg][defh][acei] + [abde][cfag][chei] + [abde][cagh][fcei] "
        "- [abdf][ceag][chei] + [abdg][cefh][acei]"
    )
    factored = collect_factors(poly, finite="ace", infinite="bdfghi")
    assert factored.expand() == poly
    points = generic_points(np.random.default_rng(5), (8,), labels="abcdefghi", infinite="bdfghi")
    expected = np.asarray(reference_value(module_terms(poly), points), dtype=float)
    np.testing.assert_allclose(factored.evaluate(points), expected, rtol=1e-10)


# products of sums and powers (collect_factors, step 4) ---------------------------------------------
def test_collect_factors_splits_a_product_of_sums_exactly():
    a = BracketPolynomial.parse("[abcd] - [abce]")
    b = BracketPolynomial.parse("[efgh] + 2[efgi]")
    c = BracketPolynomial.parse("[ijkl] - [ijkm]")
    f = collect_factors(-3 * a * b * c)
    assert f.expand() == -3 * a * b * c
    found = [p.expand() for p, _ in f.parts]
    assert len(found) == 3 and all(e in found or -1 * e in found for e in (a, b, c))
    assert f.multiplicities == (1, 1, 1)
    product = BracketPolynomial.parse("1")
    for part, power in f.parts:
        product = product * part.expand() ** power if power > 1 else product * part.expand()
    assert f.coefficient * product == f.expand()


def test_collect_factors_keeps_a_power_once():
    a = BracketPolynomial.parse("[abcd] - [abce]")  # shares its variables with itself: sympy's factoring
    b = BracketPolynomial.parse("[efgh] + 2[efgi]")
    f = collect_factors(a * a * b)
    assert [(str(p), k) for p, k in f.parts] == [("[efgh] + 2 [efgi]", 1), ("[abcd] - [abce]", 2)]
    assert str(f) == "([efgh] + 2 [efgi])([abcd] - [abce])^2"
    assert f.to_latex() == r"\left([efgh] + 2 [efgi]\right)\left([abcd] - [abce]\right)^{2}"
    square = collect_factors(Bracket("abcd") * Bracket("abcd") * b)
    assert [str(x) for x in square.factors] == ["[abcd]", "[efgh] + 2 [efgi]"]
    assert square.multiplicities == (2, 1)


def test_collect_factors_leaves_an_irreducible_sum_whole():
    poly = superbracket_expansion(["ab", "cd", "ef", "gh", "ij", "kl"])  # the general 6-6 platform
    f = collect_factors(poly)
    assert f.parts == () and len(f.factors) == 1 and f.expand() == poly


@given(
    orders=st.lists(st.permutations("abcd"), min_size=2, max_size=3),
    negate=st.booleans(),
)
def test_coefficient_times_factors_is_the_value(orders, negate):
    """coefficient × ∏ factor ** multiplicity equals the polynomial on random points, also when a
    bracket divides it several times written in different orders ([abcd][bacd] = −[abcd]²; the
    factors once merged them and lost the sign)."""
    from screwkit.gca import BracketMonomial

    head = BracketMonomial([Bracket("".join(o)) for o in orders], -1 if negate else 1)
    poly = head * (Bracket("efgh") - Bracket("efgi"))
    form = collect_factors(poly, finite="abcdefghi", infinite="", collinear=[])
    points = {k: v for k, v in zip("abcdefghi", np.random.default_rng(7).normal(size=(9, 4)), strict=True)}
    product = float(form.coefficient)
    for factor, multiplicity in zip(form.factors, form.multiplicities, strict=True):
        product *= float(factor.evaluate(points)) ** multiplicity
    expected = float(np.prod([np.linalg.det(np.stack([points[x] for x in o])) for o in orders]))
    expected *= (-1 if negate else 1) * (
        np.linalg.det(np.stack([points[x] for x in "efgh"]))
        - np.linalg.det(np.stack([points[x] for x in "efgi"]))
    )
    assert product == pytest.approx(expected, rel=1e-9)
    assert float(form.evaluate(points)) == pytest.approx(expected, rel=1e-9)
