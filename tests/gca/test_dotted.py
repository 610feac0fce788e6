"""Tests of screwkit.gca.dotted: the dotted notation of McMillan & White (gca.md §3).

Every reference value is computed independently of the module (tests/gca_references.py: numpy
determinants, an exact integer 6×6 determinant, a literal implementation of the dotted-notation
definition, hand derivations written out in the test) or re-derived from gca.md / paper 002.
"""

import itertools
import math
from fractions import Fraction

from hypothesis import given
from hypothesis import strategies as st

from screwkit.gca import (
    Bracket,
    BracketPolynomial,
    DottedMonomial,
    DottedSum,
)

from ..gca_references import (
    canonical_dict,
    module_terms,
    parity,
)


def definition_expansion(brackets, dots, divide_per_kind=True):
    """gca.md §3 literally: all permutations of each kind's letters with sign, divided by k!."""
    kinds = sorted({k for row in dots for k in row if k})
    per_kind = []
    for kind in kinds:
        places = [(b, s) for b, row in enumerate(dots) for s, k in enumerate(row) if k == kind]
        letters = [brackets[b][s] for b, s in places]
        per_kind.append(
            [
                (parity(perm), {pl: letters[i] for pl, i in zip(places, perm, strict=True)})
                for perm in itertools.permutations(range(len(places)))
            ]
        )
    if divide_per_kind:
        divisor = math.prod(
            math.factorial(sum(k == kind for k in row)) for row in dots for kind in kinds
        )
    else:  # gca.md's wording: ∏_b k_b!, k_b = number of dotted positions in bracket b
        divisor = math.prod(math.factorial(sum(1 for k in row if k)) for row in dots)
    terms = []
    for combination in itertools.product(*per_kind):
        sign = math.prod(s for s, _ in combination)
        assignment = {pl: x for _, part in combination for pl, x in part.items()}
        terms.append(
            (
                Fraction(sign, divisor),
                [
                    tuple(assignment.get((b, s), x) for s, x in enumerate(row))
                    for b, row in enumerate(brackets)
                ],
            )
        )
    return canonical_dict(terms)


def test_h4_dotted_example():
    """gca.md §3 / paper 002 Eq. (5): [a b d ḟ][c g ḣ j] = [abdf][cghj] − [abdh][cgfj]."""
    dotted = DottedMonomial.parse("[a b d ḟ][c g ḣ j]")
    assert dotted.expand() == BracketPolynomial.parse("[abdf][cghj] - [abdh][cgfj]")
    assert str(dotted) == "[a b d ḟ][c g ḣ j]"
    assert dotted.to_latex() == r"[abd\dot{f}][cg\dot{h}j]"


def test_two_kind_example_is_the_first_group_of_gca_2_2():
    """[e f ġ ï][ḣ j̈ k l] = Alt{g↔h, i↔j}[efgi][hjkl], written out by hand."""
    dotted = DottedMonomial.parse("[e f ġ ï][ḣ j̈ k l]")
    by_hand = "[efgi][hjkl] - [efhi][gjkl] - [efgj][hikl] + [efhj][gikl]"
    assert dotted.expand() == BracketPolynomial.parse(by_hand)
    assert dotted.dots == ((0, 0, 1, 2), (1, 2, 0, 0))


def test_gca_md_divisor_per_bracket_is_wrong_for_two_kinds():
    """gca.md §3 divides by ∏_b k_b! (dotted positions per bracket); with two kinds in a bracket
    that gives 1/4 of the right answer: the divisor must be taken per bracket *and kind*."""
    brackets, dots = [tuple("efgi"), tuple("hjkl")], [(0, 0, 1, 2), (1, 2, 0, 0)]
    right = definition_expansion(brackets, dots)
    wrong = definition_expansion(brackets, dots, divide_per_kind=False)
    assert all(v in (1, -1) for v in right.values()) and len(right) == 4
    assert {k: 4 * v for k, v in wrong.items()} == right


def test_three_letter_shuffle_by_hand():
    """[a ḃ c d][ė ḟ g h]: b, e, f shuffled into 1 + 2 places (signs of (b e f), (e b f), (f b e))."""
    by_hand = "[abcd][efgh] - [aecd][bfgh] + [afcd][begh]"
    assert DottedMonomial.parse("[a ḃ c d][ė ḟ g h]").expand() == BracketPolynomial.parse(by_hand)


def test_alternation_inside_one_bracket_is_the_identity():
    assert DottedMonomial.parse("[ȧ ḃ c d][e f g h]").expand() == Bracket("abcd") * Bracket("efgh")


@st.composite
def dotted_monomials(draw):
    n = draw(st.integers(2, 3))
    letters = draw(st.permutations("abcdefghijkl"))
    brackets = [tuple(letters[4 * i : 4 * i + 4]) for i in range(n)]
    dots = [list(draw(st.lists(st.integers(0, 2), min_size=4, max_size=4))) for _ in range(n)]
    seen = {1: 0, 2: 0}
    for row in dots:  # at most 4 letters per kind: the definition enumerates all k! orders
        for s, kind in enumerate(row):
            if kind:
                seen[kind] += 1
                row[s] = kind if seen[kind] <= 4 else 0
    for kind in (1, 2):
        if sum(row.count(kind) for row in dots) == 1:
            for row in dots:
                row[:] = [0 if k == kind else k for k in row]
    return brackets, [tuple(row) for row in dots], draw(st.integers(-2, 2).filter(bool))


@given(dotted_monomials())
def test_dotted_expansion_matches_the_definition(case):
    brackets, dots, coefficient = case
    monomial = DottedMonomial(brackets, dots, coefficient)
    expected = {k: coefficient * v for k, v in definition_expansion(brackets, dots).items()}
    assert canonical_dict(module_terms(monomial.expand())) == expected
    assert DottedMonomial.parse(str(monomial)) == monomial  # the printed form round-trips


def test_dotted_parse_accepts_precomposed_and_combining_marks():
    precomposed = DottedMonomial.parse("[e f ġ ï][ḣ j̈ k l]")
    combining = DottedMonomial.parse("[e f g\u0307 i\u0308][h\u0307 j\u0308 k l]")
    assert precomposed == combining
    assert DottedMonomial.parse("[a b ċ d][ė f g h]").relabel({"e": "x"}).brackets[1][0] == "x"
    assert str(DottedMonomial.from_monomial(-Bracket("gikj"))) == "-[gikj]"
    assert DottedMonomial.parse("[a b c\u20db d][e\u20db f g h]").to_latex() == (
        r"[ab\dddot{c}d][\dddot{e}fgh]"
    )


def test_dotted_sum():
    s = DottedSum.parse("[a b d ḟ][c g ḣ j] - 2[abcd][efgh]")
    assert s.expand() == BracketPolynomial.parse("[abdf][cghj] - [abdh][cgfj] - 2[abcd][efgh]")
    assert str(s) == "[a b d ḟ][c g ḣ j] - 2 [abcd][efgh]"
    assert s.to_latex() == r"[abd\dot{f}][cg\dot{h}j] - 2 [abcd][efgh]"
    assert s.relabel({"a": "x"}).expand() == s.expand().relabel({"a": "x"})
