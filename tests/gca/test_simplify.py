"""Tests of screwkit.gca.simplify: the whole simplification on the H4 (paper 002 §5, Eq. 5) and the
proportionality check.

Every reference value is computed independently of the module (tests/gca_references.py: numpy
determinants, an exact integer 6×6 determinant, a literal implementation of the dotted-notation
definition, hand derivations written out in the test) or re-derived from gca.md / paper 002.
"""

import json

import numpy as np
import pytest

from screwkit.gca import (
    Bracket,
    BracketMonomial,
    BracketPolynomial,
    DottedMonomial,
    check_proportional,
    simplify_superbracket,
)

from ..gca_references import (
    H4,
    H4_DECLARED,
    det6,
    generic_points,
    h4_sampler,
)


def test_h4_simplifies_to_the_papers_dotted_form():
    """Paper 002 Eq. (5): [abcdefghijkj] = [gikj][a b d ḟ][c g ḣ j] up to a constant (−1 here)."""
    result = simplify_superbracket(H4, h4_sampler, search=False, **H4_DECLARED)
    assert str(result.factored) == "-[gikj][a b d ḟ][c g ḣ j]"
    assert (len(result.expansion), len(result.survivors), len(result.reduced)) == (10, 5, 2)
    assert [f"{old} = {new}" for old, new in result.factored.substitutions] == [
        "[eikj] = [gikj]",
        "[cefj] = [cgfj]",
    ]
    assert all(
        c.constant == pytest.approx(1, abs=1e-9) and c.max_deviation < 1e-9
        for _, c in result.checks
    )
    factors = result.factored.factors
    assert factors[0] == Bracket("gikj") and str(factors[1]) == "[a b d ḟ][c g ḣ j]"
    summary = json.loads(json.dumps(result.to_dict()))
    assert summary["factored"]["text"] == "-[gikj][a b d ḟ][c g ḣ j]"
    assert summary["factored"]["latex"] == r"-[gikj][abd\dot{f}][cg\dot{h}j]"
    assert summary["checks"]["factored"]["constant"] == pytest.approx(1)
    # independently: the 6×6 determinant against the paper's expression
    paper = DottedMonomial.parse("[g i k j][a b d ḟ][c g ḣ j]")
    ratio = check_proportional(lambda p: det6(p, H4), paper, h4_sampler, n_samples=30, rng=9)
    assert ratio.constant == pytest.approx(-1, abs=1e-12) and ratio.max_deviation < 1e-12
    assert paper.expand() == BracketPolynomial.parse("[gikj][abdf][cghj] - [gikj][abdh][cgfj]")


def test_paper_eq5_second_line_lost_its_dots():
    """Printed second line of Eq. (5): [gikj][abdf][cghj] (no dots) is not the superbracket."""
    undotted = BracketMonomial(["gikj", "abdf", "cghj"])
    ratio = check_proportional(lambda p: det6(p, H4), undotted, h4_sampler, rng=4)
    assert ratio.max_deviation > 0.1
    first_line = Bracket("gikj") * (
        Bracket("abdf") * Bracket("cghj") - Bracket("abdh") * Bracket("cgfj")
    )
    assert DottedMonomial.parse("[gikj][a b d ḟ][c g ḣ j]").expand() == first_line


def test_simplify_with_search_h4():
    result = simplify_superbracket(H4, h4_sampler, **H4_DECLARED)
    assert result.ordering is not None and len(result.survivors) == 4
    assert result.factored.common == (Bracket("gikj"),)
    ratio = check_proportional(lambda p: det6(p, H4), result.factored, h4_sampler, rng=8)
    assert ratio.constant == pytest.approx(1, abs=1e-12) and ratio.max_deviation < 1e-12
    assert "superbracket = " in str(result) and "ordering: [ab, ef, cd, gh, ij, kj]" in str(result)
    ordering = json.loads(json.dumps(result.to_dict()))["ordering"]
    assert ordering["count"] == 4 and ordering["lines"][1] == ["e", "f"]


def test_always_singular_diagram_vanishes():
    """Six lines through one point: the superbracket is identically zero."""

    def concurrent(rng):
        return {x: np.r_[rng.normal(size=3), 1.0] for x in "oabcdef"}

    result = simplify_superbracket(["oa", "ob", "oc", "od", "oe", "of"], concurrent)
    assert str(result.factored) == "0" and len(result.reduced) == 0
    assert result.checks[0][0] == "vanishes" and result.checks[0][1].max_deviation < 1e-12


def test_check_proportional_known_constants():
    sampler = lambda rng: generic_points(rng, labels="abcde")  # noqa: E731
    r = check_proportional(Bracket("bacd"), Bracket("abcd"), sampler)
    assert r.constant == pytest.approx(-1, abs=1e-12) and r.max_deviation < 1e-12
    r = check_proportional(lambda p: 2.5 * Bracket("abcd").evaluate(p), Bracket("abcd"), sampler)
    assert r.constant == pytest.approx(2.5) and r.n_samples == 20
    r = check_proportional(Bracket("abce"), Bracket("abcd"), sampler)
    assert r.max_deviation > 0.1
    assert "constant" in str(r)
