"""Tests of screwkit.conditions: statements and vector forms of bracket factors (gca.md §5).

Each vector form is compared, on random configurations, with its bracket factor computed here with
numpy determinants; the paper's Eqs. (6) and (7) (paper 002, §5.3) are written out independently.
"""

import itertools
import json
import re

import numpy as np
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from screwkit.conditions import Condition, condition, conditions
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError
from screwkit.gca import (
    Bracket,
    BracketPolynomial,
    DottedMonomial,
    DottedSum,
    collect_factors,
    simplify_superbracket,
)

from .strategies import seeds
from .test_gca import H4, H4_DECLARED, h4_sampler, stacked


def det4(*rows):
    return np.linalg.det(np.stack(np.broadcast_arrays(*rows), axis=-2))


def points_of(rng, finite, infinite, shape=(20,)):
    out = {
        x: np.concatenate([rng.normal(size=(*shape, 3)), np.ones((*shape, 1))], -1) for x in finite
    }
    out |= {
        x: np.concatenate([rng.normal(size=(*shape, 3)), np.zeros((*shape, 1))], -1)
        for x in infinite
    }
    return out


def value_of(poly_text, points):
    """A bracket polynomial with ±1 coefficients, evaluated with numpy from its text."""
    total = 0.0
    for sign, body in re.findall(r"([+-]?)\s*((?:\[\w{4}\])+)", poly_text):
        product = 1.0
        for b in re.findall(r"\[(\w{4})\]", body):
            product = product * det4(*(points[x] for x in b))
        total = total + (-1 if sign == "-" else 1) * product
    return total


def assert_proportional(cond: Condition, expected, points, constant):
    got = cond.evaluate(points)
    assert cond.constant == constant
    np.testing.assert_allclose(float(cond.constant) * got, expected, rtol=1e-9, atol=1e-12)


# known values: the H4 (paper 002 §5.3) ------------------------------------------------------------
def test_h4_conditions_are_the_papers_equations_6_and_7():
    result = simplify_superbracket(H4, h4_sampler, search=False, **H4_DECLARED)
    first, second = conditions(result.factored, finite="aceg", infinite="bdfhijk")
    assert first.statement == (
        "i, k and j are collinear in the plane at infinity "
        "(the directions i, k, j are parallel to one plane)"
    )
    assert second.statement == "line fh meets the line where planes abd and cgj intersect"
    assert str(first.expression) == "(i × k)·j"
    assert str(second.expression) == "((b × d) × ((g − c) × j))·(f × h)"
    assert first.to_latex() == r"\left(\mathbf{i} \times \mathbf{k}\right) \cdot \mathbf{j} = 0"
    assert second.vectors == ("b", "c", "d", "f", "g", "h", "j")
    assert json.loads(json.dumps(second.to_dict()))["constant"] == "-1"

    points = stacked(h4_sampler, 30, seed=31)
    v = {x: p[:, :3] for x, p in points.items()}
    # Eq. (6): (s12 × s34)·z with i = s12, k = s34, j = z
    eq6 = np.einsum("ni,ni->n", np.cross(v["i"], v["k"]), v["j"])
    # Eq. (7): ([s1 × s2] × [(r_g − r_c) × z])·(s3 × s4) with b, d, f, h = s1..s4
    eq7 = np.einsum(
        "ni,ni->n",
        np.cross(np.cross(v["b"], v["d"]), np.cross(v["g"] - v["c"], v["j"])),
        np.cross(v["f"], v["h"]),
    )
    np.testing.assert_allclose(first.evaluate(points), eq6, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(second.evaluate(points), eq7, rtol=1e-12, atol=1e-14)
    # [gikj] = −(i × k)·j, and [abdf][cghj] − [abdh][cgfj] = −Eq. (7) (Binet–Cauchy, by hand)
    assert_proportional(first, det4(*(points[x] for x in "gikj")), points, -1)
    assert_proportional(second, value_of("[abdf][cghj] - [abdh][cgfj]", points), points, -1)


# invariants: every table entry, every letter order ------------------------------------------------
@given(st.integers(0, 4), st.permutations(range(4)), seeds)
def test_single_bracket_forms_match_the_bracket(n_finite, order, seed):
    finite, infinite = list("pqrs"[:n_finite]), list("uvwx"[: 4 - n_finite])
    letters = [(finite + infinite)[i] for i in order]
    cond = condition(Bracket(letters), finite=finite, infinite=infinite)
    points = points_of(np.random.default_rng(seed), finite, infinite)
    # moving the finite letters to the front (orders kept) takes this many transpositions
    moves = sum(x in infinite and y in finite for x, y in itertools.combinations(letters, 2))
    if n_finite == 0:
        assert cond.constant == 0 and cond.expression == 0 and "always coplanar" in cond.statement
        assert cond.evaluate(points) == 0
        return
    # gca.md §5.1: [finite…, infinite…] = −V (letters of each kind in the bracket's order)
    assert_proportional(cond, det4(*(points[x] for x in letters)), points, -((-1) ** moves))


@pytest.mark.parametrize(
    ("text", "finite", "infinite"),
    [
        ("[a b d ḟ][c g ḣ j]", "acg", "bdfhj"),  # the H4 pattern, x and y infinite
        ("[a b d ḟ][c g ḣ j]", "acgf", "bdhj"),  # x finite
        ("[a b d ḟ][c g ḣ j]", "acgfh", "bdj"),  # x and y finite
        ("[ḟ a b d][c ḣ g j]", "abcdg", "fhj"),  # planes of three finite points, dots moved
        ("2[a ḃ c d][ė f g h]", "abcdefgh", ""),  # all finite, coefficient 2
    ],
)
def test_two_plane_pattern_matches_the_expansion(text, finite, infinite, rng):
    dotted = DottedMonomial.parse(text)
    cond = condition(DottedSum([dotted]), finite=finite, infinite=infinite)
    assert cond.statement.startswith("line ") and "intersect" in cond.statement
    points = points_of(rng, finite, infinite)
    expected = dotted.expand().evaluate(points)
    got = float(cond.constant) * cond.evaluate(points)
    np.testing.assert_allclose(got, expected, rtol=1e-9, atol=1e-12)
    assert cond.constant != 0


def test_generic_form_for_other_factors(rng):
    poly = BracketPolynomial.parse("[abcd][efgh] - [abce][dfgh]")
    cond = condition(poly, finite="ace", infinite="bdfgh")
    assert cond.statement == "the bracket expression [abcd][efgh] - [abce][dfgh] vanishes"
    assert cond.constant == 1
    points = points_of(rng, "ace", "bdfgh")
    np.testing.assert_allclose(cond.evaluate(points), value_of(str(poly), points), rtol=1e-9)


def test_evaluation_is_vectorised_and_broadcast(rng):
    cond = condition(Bracket("gikj"), finite="g", infinite="ijk")
    points = points_of(rng, "g", "ijk", shape=(4, 3))
    points["j"] = np.array([0.0, 0.0, 1.0, 0.0])  # one direction for the whole batch
    got = cond.evaluate(points)
    assert got.shape == (4, 3)
    expected = det4(points["g"], points["i"], points["k"], np.broadcast_to(points["j"], (4, 3, 4)))
    np.testing.assert_allclose(-got, expected, rtol=1e-12)
    assert isinstance(
        cond.evaluate({x: p[0] for x, p in points_of(rng, "g", "ijk").items()}), float
    )


def test_exact_constant_is_a_sympy_rational():
    cond = condition(DottedMonomial.parse("[a b d ḟ][c g ḣ j]"), finite="acg", infinite="bdfhj")
    assert isinstance(cond.constant, sympy.Rational) and cond.constant == -1
    assert "f × h" in str(cond) and str(cond).startswith("[a b d ḟ][c g ḣ j] = 0 ⇔ line fh")


def test_conditions_of_a_collected_form():
    p = BracketPolynomial.parse("-[abdf][cghj][eikj] + [abdh][cefj][gikj]")
    factored = collect_factors(p, **H4_DECLARED)
    found = conditions(factored, finite="aceg", infinite="bdfhijk")
    assert [str(c.factor) for c in found] == ["[gikj]", "[a b d ḟ][c g ḣ j]"]


# errors -------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (
            lambda: condition(Bracket("gikj"), finite="g", infinite="ij"),
            ScrewkitValueError,
            r"declared in `finite` or `infinite`, got \['k'\] undeclared",
        ),
        (
            lambda: condition(Bracket("gikj"), finite="gi", infinite="ijk"),
            ScrewkitValueError,
            r"disjoint, got \['i'\] in both",
        ),
        (
            lambda: condition(Bracket("gikj"), finite=5, infinite="ijk"),
            ScrewkitTypeError,
            r"`finite` to be a string of labels",
        ),
        (
            lambda: condition("gikj", finite="g", infinite="ijk"),
            ScrewkitTypeError,
            r"`factor` to be a Bracket, DottedMonomial, DottedSum or BracketPolynomial, got str",
        ),
        (
            lambda: conditions(Bracket("gikj"), finite="g", infinite="ijk"),
            ScrewkitTypeError,
            r"`factored` to be a FactoredForm, got Bracket",
        ),
        (
            lambda: condition(Bracket("gikj"), finite="g", infinite="ijk").evaluate([1]),
            ScrewkitTypeError,
            r"`points` to be a mapping",
        ),
        (
            lambda: condition(Bracket("gikj"), finite="g", infinite="ijk").evaluate(
                {"i": [1, 0, 0, 0]}
            ),
            ScrewkitValueError,
            r"missing \['j', 'k'\]",
        ),
        (
            lambda: condition(Bracket("gikj"), finite="g", infinite="ijk").evaluate(
                {"i": np.ones((2, 4)), "j": np.ones((3, 4)), "k": np.ones(4)}
            ),
            ScrewkitValueError,
            r"batch shapes of `points` to broadcast",
        ),
        (
            lambda: condition(Bracket("gikj"), finite="g", infinite="ijk").evaluate(
                {"i": [1, 0, 0], "j": np.ones(4), "k": np.ones(4)}
            ),
            ScrewkitValueError,
            r"`points\['i'\]` to have shape \(\.\.\., 4\)",
        ),
    ],
)
def test_errors(call, error, match):
    with pytest.raises(error, match=match):
        call()
