"""Tests of screwkit.gca.expansion: the superbracket, its 24-term expansion (gca.md §2) and the ordering
search (gca.md §6.4).

Every reference value is computed independently of the module (tests/gca_references.py: numpy
determinants, an exact integer 6×6 determinant, a literal implementation of the dotted-notation
definition, hand derivations written out in the test) or re-derived from gca.md / paper 002.
"""

import itertools

import numpy as np
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from screwkit.gca import (
    BracketPolynomial,
    best_ordering,
    check_proportional,
    structural_zeros,
    superbracket,
    superbracket_expansion,
    superbracket_grouped,
)

from ..gca_references import (
    GENERIC,
    H4,
    TEMPLATE,
    canonical_dict,
    det6,
    generic_points,
    h4_loose_sampler,
    h4_sampler,
    module_terms,
    parity,
    plucker,
    stacked,
    surviving_template_monomials,
    template_value,
)
from ..strategies import rigid_motions, seeds, unit_factors


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
