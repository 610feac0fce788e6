"""Tests of screwkit.gca: bracket algebra, dotted notation, the superbracket and its simplification.

Every reference value is computed here independently of the module (numpy determinants, an exact
integer 6×6 determinant, a literal implementation of the dotted-notation definition, hand
derivations written out in the test) or re-derived from gca.md / paper 002 (Amine et al., ARK 2010).
"""

import itertools
import json
import math
import re
from fractions import Fraction

import numpy as np
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from screwkit import gca
from screwkit.exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError
from screwkit.gca import (
    Bracket,
    BracketMonomial,
    BracketPolynomial,
    DottedMonomial,
    DottedSum,
    best_ordering,
    check_proportional,
    collect_factors,
    drop_zero_subsums,
    simplify_superbracket,
    structural_zeros,
    superbracket,
    superbracket_expansion,
    superbracket_grouped,
)

from .strategies import rigid_motions, seeds, unit_factors

# --------------------------------------------------------------------------------------------------
# Independent references
# --------------------------------------------------------------------------------------------------

GENERIC = [("a", "b"), ("c", "d"), ("e", "f"), ("g", "h"), ("i", "j"), ("k", "l")]

# gca.md §2.1, copied verbatim; parsed below by a regex of this file (not by gca's parser).
GCA_24 = """
 +[abcd][efgi][hjkl] -[abcd][efgj][hikl] -[abcd][efhi][gjkl] +[abcd][efhj][gikl]
 -[abce][dfgh][ijkl] +[abce][dghi][fjkl] -[abce][dghj][fikl]
 +[abcf][degh][ijkl] -[abcf][dghi][ejkl] +[abcf][dghj][eikl]
 -[abcg][defi][hjkl] +[abcg][defj][hikl] +[abch][defi][gjkl] -[abch][defj][gikl]
 +[abde][cfgh][ijkl] -[abde][cghi][fjkl] +[abde][cghj][fikl]
 -[abdf][cegh][ijkl] +[abdf][cghi][ejkl] -[abdf][cghj][eikl]
 +[abdg][cefi][hjkl] -[abdg][cefj][hikl] -[abdh][cefi][gjkl] +[abdh][cefj][gikl]
"""
TEMPLATE = [
    (1 if sign == "+" else -1, brackets)
    for sign, *brackets in re.findall(r"([+-])\[(\w{4})\]\[(\w{4})\]\[(\w{4})\]", GCA_24)
]


def parity(sequence):
    """+1 / -1 for an even / odd arrangement of distinct items (by counting inversions)."""
    inversions = sum(a > b for a, b in itertools.combinations(sequence, 2))
    return -1 if inversions % 2 else 1


def det4(p, q, r, s):
    return np.linalg.det(np.stack(np.broadcast_arrays(p, q, r, s), axis=-2))


def plucker(p, q):
    """gca.md §1: L(p, q) = (p_w q - q_w p ; p x q)."""
    return np.concatenate(
        [p[..., 3:] * q[..., :3] - q[..., 3:] * p[..., :3], np.cross(p[..., :3], q[..., :3])],
        axis=-1,
    )


def det6(points, lines):
    rows = [plucker(*np.broadcast_arrays(points[x], points[y])) for x, y in lines]
    return np.linalg.det(np.stack(np.broadcast_arrays(*rows), axis=-2))


def template_value(points, lines):
    """The 24 terms of gca.md §2.1 evaluated with numpy determinants."""
    slot = dict(zip("abcdefghijkl", [x for line in lines for x in line], strict=True))
    return sum(
        sign * math.prod(det4(*(points[slot[c]] for c in b)) for b in brackets)
        for sign, brackets in TEMPLATE
    )


def generic_points(rng, shape=(), labels="abcdefghijkl", infinite=""):
    """Random points; the labels in `infinite` get weight 0, the others weight 1."""
    points = {}
    for x in labels:
        xyz = rng.normal(size=(*shape, 3))
        w = np.full((*shape, 1), 0.0 if x in infinite else 1.0)
        points[x] = np.concatenate([xyz, w], axis=-1)
    return points


def stacked(sampler, n, seed):
    rng = np.random.default_rng(seed)
    draws = [sampler(rng) for _ in range(n)]
    return {x: np.stack([d[x] for d in draws]) for x in draws[0]}


# The H4 wrench diagram (paper 002, §5.1, Fig. 4c): a, c finite on the vertical axis Z_I, e, g
# finite on the parallel axis Z_II, b, d, f, h the actuation force directions, i = n1 x n2 and
# k = n3 x n4 (random directions), j = (z, 0); lines ab, cd, ef, gh (forces), ij, kj (couples).
Z = np.array([0.0, 0.0, 1.0])
H4 = [("a", "b"), ("c", "d"), ("e", "f"), ("g", "h"), ("i", "j"), ("k", "j")]
H4_DECLARED = {"finite": "aceg", "infinite": "bdfhijk", "collinear": ["acj", "egj"]}


def h4_sampler(rng):
    a = np.r_[rng.normal(size=3), 1.0]
    e = np.r_[rng.normal(size=3), 1.0]
    points = {"a": a, "c": a + np.r_[rng.normal() * Z, 0.0], "e": e, "j": np.r_[Z, 0.0]}
    points["g"] = e + np.r_[rng.normal() * Z, 0.0]
    for x in "bdfhik":
        points[x] = np.r_[rng.normal(size=3), 0.0]
    return points


def h4_loose_sampler(rng):
    """The H4 diagram without the collinearity of a, c, j and of e, g, j."""
    points = h4_sampler(rng)
    for x in "aceg":
        points[x] = np.r_[rng.normal(size=3), 1.0]
    return points


def vanishing_quads(points, rtol=1e-9):
    """Label 4-sets whose bracket is zero on every sample (relative to the Hadamard bound)."""
    zero = set()
    for quad in itertools.combinations(sorted(points), 4):
        rows = [points[x] for x in quad]
        bound = math.prod(np.linalg.norm(r, axis=-1) for r in rows)
        if np.all(np.abs(det4(*rows)) <= rtol * bound):
            zero.add(quad)
    return zero


def surviving_template_monomials(lines, points):
    """Template monomials (not combined) none of whose brackets vanishes on all samples."""
    zero = vanishing_quads(points)
    slot = dict(zip("abcdefghijkl", [x for line in lines for x in line], strict=True))
    out = []
    for sign, brackets in TEMPLATE:
        labelled = ["".join(slot[c] for c in b) for b in brackets]
        if not any(len(set(b)) < 4 or tuple(sorted(b)) in zero for b in labelled):
            out.append((sign, labelled))
    return out


# --------------------------------------------------------------------------------------------------
# Brackets and the algebra
# --------------------------------------------------------------------------------------------------


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


polynomials = st.lists(
    st.tuples(
        st.integers(-3, 3),
        st.lists(st.lists(st.sampled_from("abcdef"), min_size=4, max_size=4), max_size=3),
    ),
    max_size=4,
)


def build(terms):
    return BracketPolynomial(BracketMonomial(brackets, c) for c, brackets in terms)


def reference_value(terms, points):
    return sum(
        c * math.prod((det4(*(points[x] for x in b)) for b in brackets), start=1.0)
        for c, brackets in terms
    )


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


# --------------------------------------------------------------------------------------------------
# Dotted notation (gca.md §3, McMillan & White 1991)
# --------------------------------------------------------------------------------------------------


def canonical_dict(terms):
    """{sorted bracket label sets: signed coefficient} computed here (test-local sign rules)."""
    out = {}
    for coefficient, brackets in terms:
        if any(len(set(b)) < 4 for b in brackets):
            continue
        key = tuple(sorted(tuple(sorted(b)) for b in brackets))
        signed = Fraction(coefficient) * math.prod(parity([ord(x) for x in b]) for b in brackets)
        out[key] = out.get(key, 0) + signed
    return {k: v for k, v in out.items() if v}


def module_terms(poly):
    return [(m.coefficient, [b.labels for b in m.brackets]) for m in poly]


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


# --------------------------------------------------------------------------------------------------
# The superbracket and its 24-term expansion (gca.md §2)
# --------------------------------------------------------------------------------------------------


def balanced_basis_tuples():
    """All 12-tuples of indices 0..3 with each index exactly 3 times (12!/3!^4 = 369600)."""
    first = np.array(list(itertools.combinations(range(12), 3)))  # places of 0
    rest1 = np.array([[i for i in range(12) if i not in c] for c in first])
    second = np.array(list(itertools.combinations(range(9), 3)))  # places of 1 among the rest
    rest2 = np.array([[i for i in range(9) if i not in c] for c in second])
    third = np.array(list(itertools.combinations(range(6), 3)))  # places of 2
    out = np.full((len(first), len(second), len(third), 12), 3, dtype=np.int8)
    i = np.arange(len(first))[:, None, None, None]
    j = np.arange(len(second))[None, :, None, None]
    k = np.arange(len(third))[None, None, :, None]
    out[i, j, k, first[:, None, None, :]] = 0
    out[i, j, k, rest1[:, second][:, :, None, :]] = 1
    out[i, j, k, rest1[:, rest2][:, :, third]] = 2
    return out.reshape(-1, 12)


def exact_det6(m):
    """Exact integer determinant of (N, 6, 6) integer matrices: Laplace along rows 0, 1, 2."""
    m = m.astype(np.int64)

    def det3(rows, cols):
        a = [[m[:, r, c] for c in cols] for r in rows]
        return (
            a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
        )

    total = np.zeros(len(m), dtype=np.int64)
    for cols in itertools.combinations(range(6), 3):
        other = [c for c in range(6) if c not in cols]
        total += (-1) ** (sum(cols) + 1) * det3((0, 1, 2), cols) * det3((3, 4, 5), other)
    return total


def test_exact_det6_reference(rng):
    matrices = rng.integers(-2, 3, size=(200, 6, 6))
    np.testing.assert_array_equal(exact_det6(matrices), np.rint(np.linalg.det(matrices)))


def test_expansion_equals_the_6x6_determinant_exactly():
    """A proof, in exact integer arithmetic, that the 24 terms equal the superbracket.

    Both sides are multilinear in the 12 points, so each is fixed by its values on the 4^12 tuples
    of basis vectors. Scaling coordinate i by t_i multiplies every bracket by t0·t1·t2·t3, hence a
    product of three brackets by (t0 t1 t2 t3)^3; each Plücker coordinate is a 2×2 minor
    p_i q_j − p_j q_i scaling by t_i t_j, and the six index pairs use every index three times, so
    the 6×6 determinant also scales by (t0 t1 t2 t3)^3. By multilinearity a basis tuple scales by
    ∏ t_(index), so both sides vanish unless every index occurs exactly three times. The 369 600
    balanced tuples are checked here; a random sample of unbalanced ones confirms they vanish.
    """
    tuples = balanced_basis_tuples()
    assert len(np.unique(tuples, axis=0)) == 369600
    assert np.all(np.sort(tuples, axis=1) == np.repeat(np.arange(4), 3))
    expansion = superbracket_expansion(GENERIC)
    eye = np.eye(4, dtype=np.int8)
    for chunk in np.array_split(tuples, 8):
        points = {x: eye[chunk[:, s]] for s, x in enumerate("abcdefghijkl")}
        rows = np.stack([plucker(points[x], points[y]) for x, y in GENERIC], axis=1)
        exact = exact_det6(rows)
        values = expansion.evaluate({x: p.astype(float) for x, p in points.items()})
        np.testing.assert_array_equal(values, exact.astype(float))
        assert np.count_nonzero(exact) > 0
    rng = np.random.default_rng(3)
    unbalanced = rng.integers(0, 4, size=(3000, 12))
    unbalanced = unbalanced[
        [np.bincount(t, minlength=4).tolist() != [3, 3, 3, 3] for t in unbalanced]
    ]
    points = {x: eye[unbalanced[:, s]].astype(float) for s, x in enumerate("abcdefghijkl")}
    assert np.all(expansion.evaluate(points) == 0) and np.all(det6(points, GENERIC) == 0)


def test_expansion_matches_gca_md_text():
    expected = canonical_dict([(s, list(b)) for s, b in TEMPLATE])
    assert canonical_dict(module_terms(superbracket_expansion(GENERIC))) == expected
    assert len(superbracket_expansion(GENERIC)) == 24


def test_exact_rational_points_finite_and_infinite(rng):
    for weights in ([1] * 12, [1, 0] * 6, [0, 1, 1, 0, 2, 0, 1, 1, 0, 0, 3, 1]):
        ints = {
            x: np.r_[rng.integers(-4, 5, size=3), w]
            for x, w in zip("abcdefghijkl", weights, strict=True)
        }
        exact = {x: [sympy.Integer(int(v)) for v in p] for x, p in ints.items()}
        value = superbracket(exact, GENERIC)
        assert isinstance(value, sympy.Integer)
        assert superbracket_expansion(GENERIC).evaluate(exact) == value
        rows = np.stack([plucker(ints[x], ints[y]) for x, y in GENERIC])[None]
        assert int(exact_det6(rows)[0]) == value


def test_random_floats_with_finite_and_infinite_points(rng):
    points = generic_points(rng, shape=(200,), infinite="bdfhjl")
    points |= {x: np.r_[rng.normal(size=3), 0.0] for x in "ai"}  # also two infinite lines
    truth = det6(points, GENERIC)
    np.testing.assert_allclose(superbracket(points, GENERIC), truth, rtol=1e-12, atol=1e-12)
    values = superbracket_expansion(GENERIC).evaluate(points)
    np.testing.assert_allclose(values, truth, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(template_value(points, GENERIC), truth, rtol=1e-9, atol=1e-12)


def test_superbracket_known_value():
    """Forces along x, y, z through the origin and couples about x, y, z: identity rows, det 1."""
    e = np.eye(4)
    points = {"o": e[3], "x": e[0], "y": e[1], "z": e[2]}
    lines = ["ox", "oy", "oz", "yz", "zx", "xy"]
    assert superbracket(points, lines) == pytest.approx(1.0, abs=1e-15)
    assert superbracket_expansion(lines).evaluate(points) == pytest.approx(1.0, abs=1e-15)


@given(st.permutations(range(6)), st.lists(st.booleans(), min_size=6, max_size=6), seeds)
def test_reordering_lines_flips_the_sign(order, flips, seed):
    points = generic_points(np.random.default_rng(seed), shape=(2,), infinite="dhk")
    new = [GENERIC[i][::-1] if f else GENERIC[i] for i, f in zip(order, flips, strict=True)]
    sign = parity(order) * (-1) ** sum(flips)
    truth = det6(points, GENERIC)
    np.testing.assert_allclose(superbracket(points, new), sign * truth, rtol=1e-9, atol=1e-12)
    values = superbracket_expansion(new).evaluate(points)
    np.testing.assert_allclose(values, sign * truth, rtol=1e-8, atol=1e-12)


@given(rigid_motions(), unit_factors, seeds)
def test_superbracket_is_rigid_invariant_and_scales_with_unit_to_the_ninth(motion, unit, seed):
    """A rigid motion has det 1 on (x, y, z, w); the unit change diag(k, k, k, 1) has det k^3 and
    acts on lines with det (k^3)^3."""
    rotation, translation = motion
    points = generic_points(np.random.default_rng(seed), infinite="bfk")
    moved = {
        x: np.r_[(v[:3] @ rotation.T + v[3] * translation) * unit, v[3]] for x, v in points.items()
    }
    before, after = superbracket(points, GENERIC), superbracket(moved, GENERIC)
    assert after == pytest.approx(before * unit**9, rel=1e-7, abs=1e-9 * unit**9)


def test_constant_for_other_conventions(rng):
    """gca.md §2.3: det(rows in convention X) = c × (24-term sum), re-derived here."""
    points = generic_points(rng, shape=(50,), infinite="cfk")
    reference = superbracket_expansion(GENERIC).evaluate(points)

    def rows(convention):
        out = []
        for x, y in GENERIC:
            p, q = points[x], points[y]
            direction = p[:, 3:] * q[:, :3] - q[:, 3:] * p[:, :3]
            moment = np.cross(p[:, :3], q[:, :3])
            if convention == "A":
                out.append(np.concatenate([direction, moment], axis=1))
            elif convention == "B":
                out.append(np.concatenate([moment, direction], axis=1))
            elif convention == "C":
                out.append(np.concatenate([-direction, moment], axis=1))
            else:  # lexicographic minors of (x, y, z, w) or of (w, x, y, z)
                a, b = (p, q) if convention == "D" else (np.roll(p, 1, axis=1), np.roll(q, 1, 1))
                out.append(
                    np.stack(
                        [
                            a[:, i] * b[:, j] - a[:, j] * b[:, i]
                            for i, j in itertools.combinations(range(4), 2)
                        ],
                        axis=1,
                    )
                )
        return np.stack(out, axis=1)

    for convention, constant in {"A": 1, "B": -1, "C": -1, "D": -1, "E": 1}.items():
        np.testing.assert_allclose(
            np.linalg.det(rows(convention)),
            constant * reference,
            rtol=1e-9,
            atol=1e-12,
            err_msg=convention,
        )
    weight_first = {x: np.roll(p, 1, axis=1) for x, p in points.items()}
    np.testing.assert_allclose(
        superbracket_expansion(GENERIC).evaluate(weight_first), -reference, rtol=1e-9, atol=1e-12
    )


def test_grouped_form_has_the_same_24_terms():
    grouped = superbracket_grouped(GENERIC)
    assert grouped.expand() == superbracket_expansion(GENERIC)
    assert [len(t.expand()) for t in grouped.terms] == [4, 8, 4, 4, 4]
    assert str(grouped.terms[0]) == "[abcd][e f ġ ï][ḣ j̈ k l]"
    # Alt{c↔d, g↔h, i↔j}[abdg][cefi][hjkl] as three dot kinds
    assert str(grouped.terms[1]) == "[a b ḋ g̈][ċ e f i\u20db][ḧ j\u20db k l]"
    assert superbracket_grouped(H4).expand() == superbracket_expansion(H4)


# --------------------------------------------------------------------------------------------------
# Simplification on the H4 (paper 002 §5, Fig. 4c, Eq. 5)
# --------------------------------------------------------------------------------------------------

H4_SURVIVORS = (  # the 24 terms with the slots of [ab, cd, ef, gh, ij, kj], read off by hand
    "[abcd][efhj][gikj] + [abcf][dghj][eikj] - [abch][defj][gikj]"
    " - [abdf][cghj][eikj] + [abdh][cefj][gikj]"
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


def test_h4_bracket_with_one_finite_point_is_independent_of_it():
    """gca.md §5.1 / paper 002: [eikj] = [gikj] = [aikj] for finite points of weight 1."""
    points = stacked(h4_sampler, 10, seed=13)
    values = [det4(*(points[x] for x in lab)) for lab in ("gikj", "eikj", "aikj")]
    np.testing.assert_allclose(values[1], values[0], rtol=1e-12)
    np.testing.assert_allclose(values[2], values[0], rtol=1e-12)


def test_h4_alternative_ordering_count():
    """gca.md §6.4 says [ab, ij, cd, kj, ef, gh] leaves 13 monomials. With the H4's incidences
    (a, c, j and e, g, j collinear) 9 template monomials survive and they combine into 5
    distinct ones; 13 is the count when the collinearity is ignored (and like terms not combined).
    """
    alternative = [("a", "b"), ("i", "j"), ("c", "d"), ("k", "j"), ("e", "f"), ("g", "h")]
    assert len(surviving_template_monomials(alternative, stacked(h4_sampler, 20, seed=1))) == 9
    assert len(surviving_template_monomials(alternative, stacked(h4_loose_sampler, 20, 1))) == 13
    assert best_ordering(alternative, h4_sampler).caller_count == 5
    assert best_ordering(alternative, h4_loose_sampler).caller_count == 9
    assert len(structural_zeros(superbracket_expansion(alternative), h4_sampler)) == 5


def test_h4_exhaustive_ordering_search():
    result = best_ordering(H4, h4_sampler)
    histogram = dict(result.histogram)
    assert sum(histogram.values()) == 46080
    assert (min(histogram), max(histogram)) == (4, 18)  # gca.md says 5..20: see the loose case
    assert result.caller_count == 5 and result.count == 4 == len(result.polynomial)
    np.testing.assert_allclose(  # the sign relating the orderings, with the 6×6 determinant
        det6(stacked(h4_sampler, 5, 2), result.lines),
        result.sign * det6(stacked(h4_sampler, 5, 2), H4),
        rtol=1e-10,
    )
    ratio = check_proportional(lambda p: det6(p, H4), result.polynomial, h4_sampler, rng=3)
    assert ratio.constant == pytest.approx(result.sign, abs=1e-12) and ratio.max_deviation < 1e-12
    loose = dict(best_ordering(H4, h4_loose_sampler).histogram)
    assert (min(loose), max(loose)) == (5, 20)


def test_vectorised_counts_agree_with_direct_counts(rng):
    """The vectorised score of an ordering is the length of its surviving polynomial."""
    reference = dict(best_ordering(H4, h4_sampler).histogram)
    for _ in range(6):
        order, flips = rng.permutation(6), rng.integers(0, 2, size=6)
        lines = [H4[i][::-1] if f else H4[i] for i, f in zip(order, flips, strict=True)]
        search = best_ordering(lines, h4_sampler)
        direct = structural_zeros(superbracket_expansion(lines), h4_sampler)
        assert search.caller_count == len(direct)
        assert dict(search.histogram) == reference  # the set of orderings does not depend on it


def test_simplify_with_search_h4():
    result = simplify_superbracket(H4, h4_sampler, **H4_DECLARED)
    assert result.ordering is not None and len(result.survivors) == 4
    assert result.factored.common == (Bracket("gikj"),)
    ratio = check_proportional(lambda p: det6(p, H4), result.factored, h4_sampler, rng=8)
    assert ratio.constant == pytest.approx(1, abs=1e-12) and ratio.max_deviation < 1e-12
    assert "superbracket = " in str(result) and "ordering: [ab, ef, cd, gh, ij, kj]" in str(result)
    ordering = json.loads(json.dumps(result.to_dict()))["ordering"]
    assert ordering["count"] == 4 and ordering["lines"][1] == ["e", "f"]


def test_structural_zero_decision_is_unit_invariant():
    def in_millimetres(rng):
        return {x: np.r_[p[:3] * 1000.0, p[3]] for x, p in h4_sampler(rng).items()}

    expansion = superbracket_expansion(H4)
    assert structural_zeros(expansion, in_millimetres) == structural_zeros(expansion, h4_sampler)


def test_always_singular_diagram_vanishes():
    """Six lines through one point: the superbracket is identically zero."""

    def concurrent(rng):
        return {x: np.r_[rng.normal(size=3), 1.0] for x in "oabcdef"}

    result = simplify_superbracket(["oa", "ob", "oc", "od", "oe", "of"], concurrent)
    assert str(result.factored) == "0" and len(result.reduced) == 0
    assert result.checks[0][0] == "vanishes" and result.checks[0][1].max_deviation < 1e-12


# --------------------------------------------------------------------------------------------------
# Factoring and the numeric helpers
# --------------------------------------------------------------------------------------------------


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


def test_drop_zero_subsums_keeps_long_polynomials():
    generic = superbracket_expansion(GENERIC)
    sampler = lambda rng: generic_points(rng)  # noqa: E731
    assert drop_zero_subsums(generic, sampler) == generic  # 24 > max_terms: unchanged
    assert drop_zero_subsums(BracketPolynomial.parse("[abcd] + [abce]"), sampler, max_terms=2) == (
        BracketPolynomial.parse("[abcd] + [abce]")
    )


def test_check_proportional_known_constants():
    sampler = lambda rng: generic_points(rng, labels="abcde")  # noqa: E731
    r = check_proportional(Bracket("bacd"), Bracket("abcd"), sampler)
    assert r.constant == pytest.approx(-1, abs=1e-12) and r.max_deviation < 1e-12
    r = check_proportional(lambda p: 2.5 * Bracket("abcd").evaluate(p), Bracket("abcd"), sampler)
    assert r.constant == pytest.approx(2.5) and r.n_samples == 20
    r = check_proportional(Bracket("abce"), Bracket("abcd"), sampler)
    assert r.max_deviation > 0.1
    assert "constant" in str(r)


# --------------------------------------------------------------------------------------------------
# Errors: one test per message
# --------------------------------------------------------------------------------------------------


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


def test_floats_are_refused_in_equality_quietly():
    assert (Bracket("abcd") == 1.0) is False
    assert gca.BracketPolynomial() == 0


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


def test_collect_factors_leaves_an_irreducible_sum_whole():
    poly = superbracket_expansion(["ab", "cd", "ef", "gh", "ij", "kl"])  # the general 6-6 platform
    f = collect_factors(poly)
    assert f.parts == () and len(f.factors) == 1 and f.expand() == poly


def test_the_template_is_the_same_up_to_sign_under_every_flip():
    # what the ordering search scores on (_ordering_counts): exchanging the two points of any
    # subset of lines maps the 24 template monomials onto themselves, one common sign for all;
    # relabelled monomial by monomial (BracketPolynomial sorts each bracket, sign included)
    from screwkit.gca.expansion import _EXPANSION

    template = {keys: value for value, keys in (m.canonical for m in _EXPANSION)}  # sorted brackets
    assert len(template) == 24
    for flips in itertools.product((0, 1), repeat=6):
        mapping = {}
        for k, flip in enumerate(flips):
            first, second = "abcdefghijkl"[2 * k : 2 * k + 2]
            mapping[first], mapping[second] = (second, first) if flip else (first, second)
        image = dict(m.relabel(mapping).canonical[::-1] for m in _EXPANSION)
        assert image.keys() == template.keys(), flips  # the same 24 monomials
        ratios = {image[keys] / template[keys] for keys in template}
        assert ratios == {(-1) ** sum(flips)}, flips  # the superbracket's sign change, for every monomial


@pytest.mark.parametrize(
    ("seed", "shape"),
    [(0, "none shared"), (1, "one twice"), (2, "one twice"), (3, "one thrice"), (4, "two twice"),
     (5, "one twice")],
)
def test_ordering_counts_against_the_expansion(seed, shape):
    # against the expansion in each sampled ordering, its like terms combined by BracketPolynomial
    # and its monomials with a zero bracket dropped: a shared label (a diagram's shared point, the
    # H4's j, the planar robot's g thrice) makes like terms combine
    from screwkit.gca.expansion import _EXPANSION, _ordering, _ordering_counts

    rng = np.random.default_rng(seed)
    labels = list("abcdefghijkl")
    rng.shuffle(labels)
    repeated = {"none shared": [], "one twice": [0], "one thrice": [0, 0], "two twice": [0, 1]}[shape]
    positions = labels[: 12 - len(repeated)]
    for label in [positions[k] for k in repeated]:
        positions.insert(int(rng.integers(0, len(positions) + 1)), label)
    assert len(positions) == 12 and len(set(positions)) == 12 - len(repeated)
    quads = list(itertools.combinations(sorted(set(positions)), 4))
    zero = {quad: bool(rng.random() < [0.0, 0.05, 0.2, 0.1, 0.1, 0.4][seed]) for quad in quads}
    counts = _ordering_counts(positions, zero)  # per line permutation: ordering 64 π + f has count π
    assert counts.shape == (720,)
    merged = 0
    sampled = rng.choice(46080, size=150, replace=False)
    for index in [0, 1, 63, 64, *sampled]:  # 1, 63: flips of the caller's order; 64: the next permutation
        mapping = dict(zip("abcdefghijkl", (positions[k] for k in _ordering(index)[0]), strict=True))
        monomials = [m.relabel(mapping) for m in _EXPANSION]  # the 24 template monomials, one by one
        kept = [
            m for m in monomials
            if all(len(set(b.labels)) == 4 and not zero[b.sorted_labels] for b in m.brackets)
        ]
        assert counts[index // 64] == len(BracketPolynomial(kept)), index  # like terms combined
        merged += len(kept) > counts[index // 64]
    assert merged > 0 or not repeated  # like terms did combine in some sampled ordering
