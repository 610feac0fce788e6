"""Tests of The error messages of the gca algebra modules (brackets, dotted, expansion, zeros, factored,
simplify): one case per message.

Every reference value is computed independently of the module (tests/gca_references.py: numpy
determinants, an exact integer 6×6 determinant, a literal implementation of the dotted-notation
definition, hand derivations written out in the test) or re-derived from gca.md / paper 002.
"""


import numpy as np
import pytest
import sympy

from screwkit.exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError
from screwkit.gca import (
    Bracket,
    BracketMonomial,
    BracketPolynomial,
    DottedMonomial,
    DottedSum,
    check_proportional,
    collect_factors,
    drop_zero_subsums,
    simplify_superbracket,
    structural_zeros,
    superbracket,
    superbracket_expansion,
)

from ..gca_references import (
    GENERIC,
    H4,
    H4_DECLARED,
    generic_points,
    h4_loose_sampler,
    h4_sampler,
)


def good(rng):
    return generic_points(rng, labels="abcd")


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (lambda: Bracket("abc"), ScrewkitValueError, r"`labels` to hold 4 labels, got 3"),
        (lambda: Bracket(["a", 1, "c", "d"]), ScrewkitTypeError, r"`labels\[1\]` to be a label st"),
        (lambda: Bracket("ab1d"), ScrewkitValueError, r"a letter followed by letters or digits"),
        (lambda: Bracket(5), ScrewkitTypeError, r"`labels` to be a string or a sequence of labels"),
        (lambda: Bracket("abcd") * 0.5, ScrewkitTypeError, r"integer or a fraction .*float 0.5"),
        (lambda: BracketMonomial(["abcd"], True), ScrewkitTypeError, r"`coefficient`.*True"),
        (lambda: BracketPolynomial(["abcd"]), ScrewkitTypeError, r"`terms` to hold bracket mon"),
        (lambda: BracketPolynomial.parse("[abcd] x"), ScrewkitValueError, r"from position 7"),
        (lambda: BracketPolynomial.parse("[abcd] [abc]"), ScrewkitValueError, r"4 labels, got \["),
        (
            lambda: BracketPolynomial.parse("[a b c\u0307\u0308 d]"),
            ScrewkitValueError,
            r"at most one dot each",
        ),
        (lambda: BracketPolynomial.parse("[a b ċ ḋ]"), ScrewkitValueError, r"without dots"),
        (lambda: BracketPolynomial.parse(5), ScrewkitTypeError, r"`text` to be a string"),
        (lambda: Bracket("abcd").evaluate([1, 2]), ScrewkitTypeError, r"`points` to be a mapping"),
        (
            lambda: Bracket("abcd").evaluate({"a": [1, 0, 0, 0]}),
            ScrewkitValueError,
            r"missing \['b', 'c', 'd'\]",
        ),
        (
            lambda: Bracket("abcd").evaluate(
                {"a": [1, 0, 0], "b": [0] * 4, "c": [0] * 4, "d": [0] * 4}
            ),
            ScrewkitValueError,
            r"`points\['a'\]` to have shape \(\.\.\., 4\), got \(3,\)",
        ),
        (
            lambda: Bracket("abcd").evaluate({x: [np.nan, 0, 0, 1] for x in "abcd"}),
            ScrewkitValueError,
            r"finite numbers",
        ),
        (
            lambda: Bracket("abcd").evaluate(
                {"a": np.ones((2, 4)), "b": np.ones((3, 4)), "c": np.ones(4), "d": np.ones(4)}
            ),
            ScrewkitValueError,
            r"batch shapes of `points` to broadcast",
        ),
        (
            lambda: BracketPolynomial.parse("[abcd]").to_sympy(
                {x: np.ones((2, 4)) for x in "abcd"}
            ),
            ScrewkitValueError,
            r"single points of shape \(4,\) for to_sympy",
        ),
        (lambda: Bracket("abcd").relabel({"a": "1x"}), ScrewkitValueError, r"`mapping\['a'\]`"),
        (
            lambda: DottedMonomial(["abcd", "efgh"], [(1, 0, 0, 0), (0, 0, 0, 0)]),
            ScrewkitValueError,
            r"at least two letters, got kinds \[1\]",
        ),
        (
            lambda: DottedMonomial(["abcd"], [(1, 1, 0)]),
            ScrewkitValueError,
            r"`dots` to give 4 dot kinds for each of the 1 brackets",
        ),
        (
            lambda: DottedMonomial(["abcd"], [(5, 5, 0, 0)]),
            ScrewkitValueError,
            r"integers 0 \(none\) to 4",
        ),
        (
            lambda: DottedMonomial.parse("[abcd] + [abce]"),
            ScrewkitValueError,
            r"one dotted monomial, got 2",
        ),
        (lambda: DottedMonomial.from_monomial("abcd"), ScrewkitTypeError, r"`monomial` to be a Br"),
        (lambda: DottedSum([Bracket("abcd")]), ScrewkitTypeError, r"DottedMonomial values, got Br"),
        (lambda: superbracket_expansion(GENERIC[:5]), ScrewkitValueError, r"6 lines, got 5"),
        (
            lambda: superbracket_expansion("abcdefghijkl"),
            ScrewkitTypeError,
            r"sequence of six pairs",
        ),
        (
            lambda: superbracket_expansion([*GENERIC[:5], "klm"]),
            ScrewkitValueError,
            r"`lines\[5\]` to hold 2 labels, got 3",
        ),
        (
            lambda: superbracket(
                {x: [sympy.Integer(1)] * 4 for x in "abcdefghijkl"}
                | {"a": [[1, 0, 0, 1], [sympy.Integer(1), 0, 0, 1]]},
                GENERIC,
            ),
            ScrewkitValueError,
            r"sympy `points` to be single points",
        ),
        (
            lambda: structural_zeros(Bracket("abcd").__mul__(1), 5),
            ScrewkitTypeError,
            r"`sampler` to be a callable",
        ),
        (
            lambda: structural_zeros(BracketPolynomial([Bracket("abcd")]), lambda rng: [1]),
            ScrewkitTypeError,
            r"`sampler\(rng\)` to return a mapping",
        ),
        (
            lambda: structural_zeros(BracketPolynomial([Bracket("abce")]), good),
            ScrewkitValueError,
            r"point for label 'e', missing in draw 0",
        ),
        (
            lambda: structural_zeros(
                BracketPolynomial([Bracket("abcd")]),
                lambda rng: {x: np.ones((2, 4)) for x in "abcd"},
            ),
            ScrewkitValueError,
            r"one point of shape \(4,\), got \(2, 4\)",
        ),
        (
            lambda: structural_zeros(
                BracketPolynomial([Bracket("abcd")]), lambda rng: good(rng) | {"a": np.zeros(4)}
            ),
            DegenerateGeometryError,
            r"`sampler\(rng\)\['a'\]` to be a projective point",
        ),
        (
            lambda: structural_zeros(BracketPolynomial([Bracket("abcd")]), good, n_samples=0),
            ScrewkitValueError,
            r"`n_samples` to be a positive integer, got 0",
        ),
        (
            lambda: structural_zeros(BracketPolynomial([Bracket("abcd")]), good, rtol=2),
            ScrewkitValueError,
            r"`rtol` to be a number in \[0, 0\.1\], got 2",
        ),
        (
            lambda: check_proportional(Bracket("abcd"), Bracket("aabc"), good),
            DegenerateGeometryError,
            r"`expr_b` to be non-zero on some sample",
        ),
        (
            lambda: check_proportional("x", Bracket("abcd"), good),
            ScrewkitTypeError,
            r"`expr_a` to have an evaluate",
        ),
        (
            lambda: check_proportional(lambda p: np.full(20, np.inf), Bracket("abcd"), good),
            ScrewkitValueError,
            r"`expr_a` to give finite values",
        ),
        (
            lambda: collect_factors(Bracket("abcd").__mul__(1), finite="ab", infinite="bc"),
            ScrewkitValueError,
            r"disjoint, got \['b'\] in both",
        ),
        (
            lambda: collect_factors(
                Bracket("abcd").__mul__(1), finite="ab", infinite="c", collinear=["acb"]
            ),
            ScrewkitValueError,
            r"`collinear\[0\]` to be \(finite, finite, infinite\)",
        ),
        (
            lambda: collect_factors(Bracket("abcd").__mul__(1), collinear="abc"),
            ScrewkitTypeError,
            r"`collinear` to be a sequence of triples",
        ),
        (
            lambda: simplify_superbracket(H4, h4_sampler, finite="abceg", infinite="dfhijk"),
            ScrewkitValueError,
            r"finite point 'b' weight 1",
        ),
        (
            lambda: simplify_superbracket(H4, h4_sampler, finite="ce", infinite="abdfhijk"),
            ScrewkitValueError,
            r"infinite point 'a' weight 0",
        ),
        (
            lambda: simplify_superbracket(H4, h4_loose_sampler, search=False, **H4_DECLARED),
            ScrewkitValueError,
            r"stage 'factored' to equal the superbracket",
        ),
        (
            lambda: simplify_superbracket(H4, h4_sampler, check_rtol=-1),
            ScrewkitValueError,
            r"`check_rtol` to be a number",
        ),
        (
            lambda: drop_zero_subsums(Bracket("abcd").__mul__(1), good, max_terms=0),
            ScrewkitValueError,
            r"`max_terms` to be a positive integer",
        ),
    ],
)
def test_errors(call, error, match):
    with pytest.raises(error, match=match):
        call()
