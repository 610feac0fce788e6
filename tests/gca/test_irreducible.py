"""Tests of screwkit.gca.exact_proofs.is_irreducible_in_points: the general Gough–Stewart factor (the
superbracket of six lines through twelve free points) is irreducible; products are not.

Why the test is a proof (checked here by its consequences): a bracket polynomial linear in each of
its points can only factor into polynomials in disjoint groups of points, and such a factorization
f = g(S) h(S') makes f(x_S, x_S') f(y_S, y_S') − f(x_S, y_S') f(y_S, x_S') vanish for all x, y
(shown below numerically for products built here)."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.gca import BracketPolynomial, superbracket_expansion
from screwkit.gca.exact_proofs import is_irreducible_in_points
from screwkit.gca.vector_forms import PointKinds

LINES = ["ab", "cd", "ef", "gh", "ij", "kl"]


def test_general_gough_stewart_superbracket_is_irreducible():
    assert is_irreducible_in_points(superbracket_expansion(LINES), PointKinds("abcdefghijkl", ""))
    # with points at infinity too (legs through a finite and an infinite point each)
    assert is_irreducible_in_points(superbracket_expansion(LINES), PointKinds("acegik", "bdfhjl"))


def test_two_planes_and_a_line_is_irreducible():
    """[abcḋ][ėfgh] = (abc ∧ fgh) ∧ de: a line meeting the line of two planes (gca.md §5.2)."""
    assert is_irreducible_in_points(BracketPolynomial.parse("[abcd][efgh] - [abce][dfgh]"), PointKinds("abcdefgh", ""))


def test_split_identity_holds_for_a_product():
    """The identity behind the proof, on a product built here: f = [abcd]·[efgh] with S = {a, b, c, d}."""
    rng = np.random.default_rng(0)
    x, y = ({z: np.r_[rng.normal(size=3), 1.0] for z in "abcdefgh"} for _ in range(2))

    def f(p):
        return np.linalg.det(np.array([p[z] for z in "abcd"])) * np.linalg.det(np.array([p[z] for z in "efgh"]))

    mixed = {z: (x if z in "abcd" else y)[z] for z in "abcdefgh"}
    swapped = {z: (y if z in "abcd" else x)[z] for z in "abcdefgh"}
    assert np.isclose(f(x) * f(y), f(mixed) * f(swapped), rtol=1e-10)


PLANE_LINE = ["[{0}{1}{2}{3}][{4}{5}{6}{7}]", "-[{0}{1}{2}{4}][{3}{5}{6}{7}]"]


@settings(max_examples=20, deadline=None)
@given(st.permutations("abcdefghijkl"))
def test_products_in_disjoint_points_are_not_irreducible(order):
    """An irreducible factor in eight of the points times a bracket of the other four: the product,
    expanded, is refused (its split is never refuted)."""
    first = BracketPolynomial.parse(" ".join(t.format(*order[:8]) for t in PLANE_LINE))
    second = BracketPolynomial.parse(f"[{''.join(order[8:])}]")
    product = first * second
    assert is_irreducible_in_points(first, PointKinds("abcdefghijkl", ""))
    assert not is_irreducible_in_points(product, PointKinds("abcdefghijkl", ""))


def test_not_attempted_when_a_point_is_missing_from_a_monomial():
    """The Peppermill's factor: c is in one monomial only (not linear in every point): not attempted."""
    assert not is_irreducible_in_points(BracketPolynomial.parse("[abfd][eghi] - [abfh][ecdi]"), PointKinds("aceg", "bdfhi"))
