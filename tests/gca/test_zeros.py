"""Tests of screwkit.gca.zeros: structural zeros and vanishing subsums on sampled configurations (gca.md §6).

Every reference value is computed independently of the module (tests/gca_references.py: numpy
determinants, an exact integer 6×6 determinant, a literal implementation of the dotted-notation
definition, hand derivations written out in the test) or re-derived from gca.md / paper 002.
"""


import numpy as np
import pytest

from screwkit.gca import (
    BracketPolynomial,
    check_proportional,
    drop_zero_subsums,
    structural_zeros,
    superbracket_expansion,
)

from ..gca_references import (
    GENERIC,
    H4,
    H4_SURVIVORS,
    TEMPLATE,
    det4,
    det6,
    generic_points,
    h4_sampler,
    stacked,
    surviving_template_monomials,
)


def test_h4_paper_order_19_of_24_monomials_vanish():
    samples = stacked(h4_sampler, 20, seed=11)
    survivors = surviving_template_monomials(H4, samples)
    assert len(TEMPLATE) - len(survivors) == 19
    # Each vanishing monomial has a bracket with a repeated point, four infinite points, or the
    # collinear a, c, j or e, g, j (gca.md §5.1); no surviving monomial has one.
    slot = dict(zip("abcdefghijkl", [x for line in H4 for x in line], strict=True))

    def reason(b):
        s = set(b)
        return len(s) < 4 or s <= set("bdfhijk") or {"a", "c", "j"} <= s or {"e", "g", "j"} <= s

    for sign, brackets in TEMPLATE:
        labelled = ["".join(slot[c] for c in b) for b in brackets]
        assert any(map(reason, labelled)) == ((sign, labelled) not in survivors)
    result = structural_zeros(superbracket_expansion(H4), h4_sampler)
    assert result == BracketPolynomial.parse(H4_SURVIVORS)
    ratio = check_proportional(lambda p: det6(p, H4), result, h4_sampler, rng=5)
    assert ratio.constant == pytest.approx(1, abs=1e-12) and ratio.max_deviation < 1e-12


def test_h4_three_monomials_sum_to_zero():
    """On the H4 variety [abcd][efhj][gikj] + [abcf][dghj][eikj] − [abch][defj][gikj] = 0.

    By hand: [eikj] = [gikj] (one finite, three infinite points); e = g + t·j and j is in
    [efhj], [defj], so e may be replaced by g there; c = a + s·j gives [abcX] = s[abjX]. What is
    left is s·[gikj]·Σ_alt [abjX][YZgj] over X, Y, Z ∈ {d, f, h} = s·[gikj]·((abj ∧ dfh) ∧ gj): the
    plane dfh is Π∞, it meets plane abj in a line through j, and line gj passes through j.
    """
    points = stacked(h4_sampler, 20, seed=12)
    terms = [
        det4(*(points[x] for x in "abcd"))
        * det4(*(points[x] for x in "efhj"))
        * det4(*(points[x] for x in "gikj")),
        det4(*(points[x] for x in "abcf"))
        * det4(*(points[x] for x in "dghj"))
        * det4(*(points[x] for x in "eikj")),
        -det4(*(points[x] for x in "abch"))
        * det4(*(points[x] for x in "defj"))
        * det4(*(points[x] for x in "gikj")),
    ]
    scale = np.abs(terms).sum(axis=0)
    assert np.all(np.abs(np.sum(terms, axis=0)) <= 1e-12 * scale) and np.all(scale > 1e-6)
    reduced = drop_zero_subsums(BracketPolynomial.parse(H4_SURVIVORS), h4_sampler)
    assert reduced == BracketPolynomial.parse("-[abdf][cghj][eikj] + [abdh][cefj][gikj]")


def test_structural_zero_decision_is_unit_invariant():
    def in_millimetres(rng):
        return {x: np.r_[p[:3] * 1000.0, p[3]] for x, p in h4_sampler(rng).items()}

    expansion = superbracket_expansion(H4)
    assert structural_zeros(expansion, in_millimetres) == structural_zeros(expansion, h4_sampler)


def test_drop_zero_subsums_keeps_long_polynomials():
    generic = superbracket_expansion(GENERIC)
    sampler = lambda rng: generic_points(rng)  # noqa: E731
    assert drop_zero_subsums(generic, sampler) == generic  # 24 > max_terms: unchanged
    assert drop_zero_subsums(BracketPolynomial.parse("[abcd] + [abce]"), sampler, max_terms=2) == (
        BracketPolynomial.parse("[abcd] + [abce]")
    )
