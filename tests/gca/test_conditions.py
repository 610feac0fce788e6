"""Tests of screwkit.gca.conditions: statements and vector forms of bracket factors (gca.md §5).

Each vector form is compared, on random configurations, with its bracket factor computed here with
numpy determinants; the paper's Eqs. (6) and (7) (paper 002, §5.3) are written out independently.
"""

import itertools
import json
import random
import re

import numpy as np
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError
from screwkit.gca import (
    Bracket,
    BracketPolynomial,
    DottedMonomial,
    DottedSum,
    collect_factors,
    simplify_superbracket,
)
from screwkit.gca.conditions import Condition, condition, conditions, label
from screwkit.gca.vector_forms import VectorDot

from ..gca_references import H4, H4_DECLARED, h4_sampler, stacked
from ..strategies import seeds


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


# patterns of the literature on mechanisms where they are known --------------------------------------
# Each diagram is built here from its points (gca level); the factored superbracket is compared, at
# exact random rational configurations, with the 6×6 determinant of the lines' Plücker vectors
# (gca.md §1) computed independently with sympy, and with the hand-derived product.


def rational_points(rng, finite, infinite, planar=()):
    def number():
        return sympy.Rational(int(rng.integers(-60, 61)), int(rng.integers(1, 8)))

    out = {x: [number(), number(), sympy.Integer(0) if x in planar else number(), 1] for x in finite}
    out |= {x: [number(), number(), number(), 0] for x in infinite}
    return out


def plucker_det(points, lines):
    rows = []
    for p, q in lines:
        a, b = sympy.Matrix(points[p]), sympy.Matrix(points[q])
        direction = a[3] * b[:3, 0] - b[3] * a[:3, 0]
        rows.append([*direction, *a[:3, 0].cross(b[:3, 0])])
    return sympy.Matrix(rows).det()


def factored_value(factored, points):
    value = sympy.Rational(factored.coefficient.numerator, factored.coefficient.denominator)
    for factor, power in zip(factored.factors, factored.multiplicities, strict=True):
        poly = factor if isinstance(factor, Bracket) else factor.expand()
        value *= poly.to_sympy(points) ** power
    return sympy.expand(value)


def vec(points, x):
    return sympy.Matrix(points[x][:3])


def plane(points, triple):
    """Plane coordinates π with π·x = [p q r x], as cofactors (independent of the package)."""
    rows = sympy.Matrix([points[x] for x in triple])
    return [(-1) ** (k + 1) * rows[:, [j for j in range(4) if j != k]].det() for k in range(4)]


def random_sampler(finite, infinite, planar=()):
    def sampler(rng):
        out = {x: np.r_[rng.normal(size=3), 1.0] for x in finite}
        for x in planar:
            out[x][2] = 0.0
        return out | {x: np.r_[rng.normal(size=3), 0.0] for x in infinite}

    return sampler


UPU_LINES = ["ab", "cd", "ef", "gh", "ij", "kl"]  # legs a + t·b …; couples at infinity gh, ij, kl
UPU_ROLES = ["actuation"] * 3 + ["constraint"] * 3


def test_3upu_factors_as_actuation_times_constraint(rng):
    """Tsai's 3-UPU: three leg forces (a_i; direction s_i) and three couples (0; m_i). The 6×6 matrix
    is block triangular, so det = det(s₁, s₂, s₃)·det(m₁, m₂, m₃) (by hand), m_i = g×h, i×j, k×l."""
    finite, infinite = "ace", "bdfghijkl"
    result = simplify_superbracket(UPU_LINES, random_sampler(finite, infinite), finite=finite, infinite=infinite)
    found = conditions(result.factored, finite=finite, infinite=infinite, lines=UPU_LINES, roles=UPU_ROLES)
    assert [c.label for c in found] == ["actuation", "constraint"]
    assert [c.multiplicity for c in found] == [1, 1]
    assert found[0].statement.startswith("b, d and f are collinear in the plane at infinity")
    assert found[0].evidence == "involves lines ab, cd, ef (actuation); b, d, f lie only on actuation lines"
    assert found[1].statement.endswith(
        "i.e. the lines at infinity gh, ij and kl are concurrent (the normals g × h, i × j and k × l "
        "are parallel to one plane)"
    )
    assert found[1].evidence == (
        "involves lines gh, ij, kl (constraint); its points lie on constraint lines"
    )
    for seed in range(3):
        points = rational_points(np.random.default_rng(seed), finite, infinite)
        det = plucker_det(points, UPU_LINES)
        s = sympy.Matrix.hstack(*(vec(points, x) for x in "bdf")).det()
        moments = [vec(points, x).cross(vec(points, y)) for x, y in ["gh", "ij", "kl"]]
        assert det == s * sympy.Matrix.hstack(*moments).det() != 0
        assert factored_value(result.factored, points) == det


def test_squared_factor_is_one_condition_with_multiplicity_two():
    """3-UPU with its couples as a triangle of lines at infinity gh, hi, ig: det(m₁, m₂, m₃) =
    det(g×h, h×i, i×g) = det(g, h, i)² (gca.md §5.2, triangle of infinite lines)."""
    lines, finite, infinite = ["ab", "cd", "ef", "gh", "hi", "ig"], "ace", "bdfghi"
    result = simplify_superbracket(lines, random_sampler(finite, infinite), finite=finite, infinite=infinite)
    found = conditions(result.factored, finite=finite, infinite=infinite, lines=lines, roles=UPU_ROLES)
    assert [(c.label, c.multiplicity) for c in found] == [("actuation", 1), ("constraint", 2)]
    assert str(found[1].expression) == "(g × h)·i" and "(multiplicity 2)" in str(found[1])
    assert found[1].factor_latex().endswith("^{2} = 0")
    for seed in range(3):
        points = rational_points(np.random.default_rng(seed), finite, infinite)
        s = sympy.Matrix.hstack(*(vec(points, x) for x in "bdf")).det()
        ghi = sympy.Matrix.hstack(*(vec(points, x) for x in "ghi")).det()
        assert plucker_det(points, lines) == s * ghi**2 == factored_value(result.factored, points)


@pytest.mark.parametrize(
    ("name", "lines", "finite", "infinite", "planes"),
    [
        # octahedral (3-3) Gough–Stewart: base a, b, c; platform d, e, f; the alternate faces
        ("octahedral", ["ad", "ae", "be", "bf", "cf", "cd"], "abcdef", "", ["abc", "ade", "bef", "cdf"]),
        # 3-RPS: base joints a, b, c, sphere centres p, q, r, R-axis directions u, v, w; constraint
        # forces through the sphere centres along the R axes; leg planes apu, … and the platform
        ("3-RPS", ["ap", "bq", "cr", "pu", "qv", "rw"], "abcpqr", "uvw", ["apu", "bqv", "crw", "pqr"]),
        # the same pencils written from the sphere centres a, c, e with the leg directions b, d, f and
        # the R axes g, h, i at infinity (a 3-RPS or 3-PRS twist graph's diagram): each leg plane holds
        # one finite point, and its degenerate position (g onto the point at infinity of ab) is b itself
        ("3-RPS/3-PRS from the centres", ["ab", "cd", "ef", "ag", "ch", "ei"], "ace", "bdfghi",
         ["abg", "ace", "cdh", "efi"]),
    ],
)
def test_four_planes_through_one_point(name, lines, finite, infinite, planes):
    result = simplify_superbracket(lines, random_sampler(finite, infinite), finite=finite, infinite=infinite)
    (found,) = conditions(result.factored, finite=finite, infinite=infinite)
    assert found.statement == (
        f"planes {', '.join(planes[:3])} and {planes[3]} pass through one point (possibly at infinity)"
    )
    ratios = set()
    for seed in range(3):
        points = rational_points(np.random.default_rng(seed), finite, infinite)
        det = plucker_det(points, lines)
        assert factored_value(result.factored, points) == det
        ratios.add(det / sympy.Matrix([plane(points, p) for p in planes]).det())
    assert len(ratios) == 1 and 0 not in ratios  # det of the 6 lines = constant × det of the 4 planes


def test_planar_legs_concurrent_is_a_line_meeting_three_lines():
    """3-RPR (legs ab, cd, ef in the plane z = 0; planar constraint force oz, couples yz, zx): the
    textbook condition, the three legs concurrent."""
    lines, finite, infinite = ["ab", "cd", "ef", "oz", "yz", "zx"], "abcdefo", "xyz"

    def sampler(rng):
        points = random_sampler("abcdefo", "", planar="abcdef")(rng)
        return points | {x: np.r_[np.eye(3)[k], 0.0] for k, x in enumerate("xyz")}

    result = simplify_superbracket(lines, sampler, finite=finite, infinite=infinite)
    found = conditions(result.factored, finite=finite, infinite=infinite)
    legs = next(c for c in found if "a" in c.vectors)
    assert legs.statement.endswith(
        "i.e. a line parallel to direction z meets the three lines ab, ef and cd (if these lie in one "
        "plane not containing z: they are concurrent)"
    )
    # concurrent legs through (1, 2, 0) make it vanish; moving one leg off makes it non-zero
    o = np.array([1.0, 2.0, 0.0, 1.0])
    points = sampler(np.random.default_rng(3))
    for first, second in ["ab", "cd", "ef"]:
        points[second] = o + 1.7 * (points[first] - o)
    assert abs(legs.evaluate(points)) < 1e-9
    points["f"] = points["f"] + np.array([0.3, 0.0, 0.0, 0.0])
    assert abs(legs.evaluate(points)) > 1e-3


def test_general_gough_stewart_names_the_linear_complex():
    labels = "abcdefghijkl"
    result = simplify_superbracket(UPU_LINES, random_sampler(labels, ""), finite=labels)
    (found,) = conditions(result.factored, finite=labels, infinite="", lines=UPU_LINES, roles=["actuation"] * 6)
    assert found.statement.startswith(
        "the six lines ab, cd, ef, gh, ij and kl are linearly dependent (they belong to one linear line complex)"
    )
    assert found.label == "actuation"
    points = rational_points(np.random.default_rng(0), labels, "")
    assert factored_value(result.factored, points) == plucker_det(points, UPU_LINES)


def test_generic_statement_names_the_lines_and_points():
    poly = BracketPolynomial.parse("[abcd][efgh] - [abce][dfgh]")
    cond = condition(poly, finite="ace", infinite="bdfgh", lines=["ab", "cd", "ef", "gh", "xy", "zw"])
    assert cond.statement == (
        "the bracket expression [abcd][efgh] - [abce][dfgh] vanishes (it involves lines ab, cd, ef, gh "
        "through the points a, b, c, d, e, f, g, h)"
    )


H4_LIKE = ["ab", "cd", "ef", "gk", "ij", "kj"]  # k on the actuation line gk and on a couple
SHARED = ["ab", "cd", "ef", "gk", "dk", "kj"]  # d and k each on lines of both kinds


@pytest.mark.parametrize(
    ("lines", "vectors", "expected"),
    [
        (H4_LIKE, "ij", ("constraint", "involves lines ij, kj (constraint); its points lie on constraint lines")),
        (H4_LIKE, "ik", ("constraint", "involves lines gk (actuation), ij, kj (constraint); its points lie on "
                         "constraint lines (k on actuation lines too)")),
        (H4_LIKE, "bj", ("actuation", "involves lines ab (actuation), ij, kj (constraint); b lies only on "
                         "actuation lines")),
        (SHARED, "kd", ("constraint or actuation", "involves lines cd, gk (actuation), dk, kj (constraint); each "
                        "of its points, d, k, lies on constraint and on actuation lines")),
    ],
)
def test_labels_follow_the_roles_of_the_lines(lines, vectors, expected):
    assert label(list(vectors), lines, ["actuation"] * 4 + ["constraint"] * 2) == expected


def test_label_errors():
    with pytest.raises(ScrewkitValueError, match=r"`roles` to give 'constraint' or 'actuation' for each of the 2 lines"):
        label(["a"], ["ab", "cd"], ["constraint"])
    with pytest.raises(ScrewkitTypeError, match=r"`lines` to be a sequence of pairs of labels, got str"):
        label(["a"], "abcd", ["constraint"])


def test_proof_rejects_a_wrong_vector_form():
    from screwkit.gca.exact_proofs import prove_proportional
    from screwkit.gca.vector_forms import PointKinds

    wrong = sympy.Symbol("b")  # not a scalar form of [abcd]: fails at the exact configurations
    with pytest.raises(ScrewkitValueError, match="to be proportional to"):
        prove_proportional(BracketPolynomial.parse("[abcd]"), VectorDot(wrong, wrong), PointKinds("abcd", ""))


def test_sum_of_vector_forms_is_sympys_canonical_add():
    # vector_forms.vector_sum skips Add.flatten when there is nothing to collect: against sympy.Add
    # (same args in the same order, so the same text and the same left-to-right evaluation), on
    # random sums of the vector forms' products, with like terms, zeros and cancelling pairs
    from screwkit.gca.vector_forms import VectorCross, VectorDiff, vector_sum

    rng = random.Random(7)
    names = sympy.symbols("a b c d e f")
    factors = [
        VectorDot(VectorCross(names[0], names[1]), names[2]),
        VectorDot(VectorDiff(names[3], names[0]), VectorCross(names[4], names[5])),
        VectorDot(names[1], names[4]),
        VectorDot(VectorCross(names[2], names[5]), VectorDiff(names[1], names[3])),
    ]
    flattened = []
    flatten = sympy.Add.flatten.__func__

    def counted(cls, seq):
        flattened.append(len(seq))
        return flatten(cls, seq)

    fast = 0
    for _ in range(300):
        terms = []
        for _ in range(rng.randint(0, 5)):
            chosen = rng.sample(factors, rng.randint(1, 3))
            coefficient = sympy.Rational(rng.choice([-3, -1, 0, 1, 2]), rng.choice([1, 2]))
            terms.append(sympy.Mul(coefficient, *chosen))
        flattened.clear()
        sympy.core.cache.clear_cache()  # Add(*args) is cached: a cache hit would not call flatten
        with pytest.MonkeyPatch.context() as patch:
            patch.setattr(sympy.Add, "flatten", classmethod(counted))
            got = vector_sum(terms)
        expected = sympy.Add(*terms)
        assert got == expected and got.args == expected.args and str(got) == str(expected), terms
        fast += isinstance(got, sympy.Add) and not flattened
    assert fast > 50  # the path without Add.flatten is taken (watched), not only the fallback
