"""Tests of screwkit.gca.design_factors: a factor that splits on a mechanism's configurations.

The configurations are built here with a relation that is no incidence (a point placed at a fixed
ratio along a segment, an affine relation between directions), and the expected ratio is derived by
hand from multilinearity of the bracket; brackets are numpy determinants."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError
from screwkit.gca import Bracket, BracketPolynomial
from screwkit.gca.design_factors import split_on_configurations


def det4(points, labels):
    return np.linalg.det(np.array([points[x] for x in labels]))


def ratio_samples(rng, ratio, n=6):
    """e = a + ratio·(d − a): [abce] = ratio·[abcd] by multilinearity (by hand)."""
    samples = []
    for _ in range(n):
        p = {x: np.r_[rng.normal(size=3), 1.0] for x in "abcd"}
        samples.append(p | {"e": p["a"] + ratio * (p["d"] - p["a"])})
    return samples


@settings(max_examples=25, deadline=None)
@given(st.floats(-3.0, 3.0).filter(lambda r: abs(r + 1) > 0.05 and abs(r) > 0.05), st.integers(0, 2**32 - 1))
def test_the_ratio_is_the_hand_derived_one(ratio, seed):
    samples = ratio_samples(np.random.default_rng(seed), ratio)
    split = split_on_configurations(BracketPolynomial.parse("[abcd] + [abce]"), samples)
    assert split is not None and split.n_samples == 6
    (bracket,) = split.brackets
    for points in samples:  # factor = ratio × product on each configuration (numpy determinants)
        value = det4(points, "abcd") + det4(points, "abce")
        assert value == pytest.approx(split.ratio * det4(points, bracket.labels), rel=1e-9)
    expected = 1 + ratio if bracket.sorted_labels == ("a", "b", "c", "d") else (1 + ratio) / ratio
    assert split.ratio == pytest.approx(expected, rel=1e-9)


def test_no_split_without_the_relation():
    rng = np.random.default_rng(2)
    samples = [{x: np.r_[rng.normal(size=3), 1.0] for x in "abcdef"} for _ in range(6)]
    assert split_on_configurations(BracketPolynomial.parse("[abcd] + [abce]"), samples) is None
    assert split_on_configurations(BracketPolynomial.parse("[abcd][abef] - [abce][abdf]"), samples) is None
    assert split_on_configurations(BracketPolynomial.parse("[abcd][abef]"), samples) is None  # a product


def test_a_product_of_two_brackets():
    """With d = a + 2 (c − a), [abdk] = 2 [abck] (by hand), so [abdk][abem] + [abck][abem] is
    3 [abck][abem] = 1.5 [abdk][abem] on these configurations: either product, with its ratio."""
    rng = np.random.default_rng(4)
    samples = []
    for _ in range(6):
        p = {x: np.r_[rng.normal(size=3), 1.0] for x in "abce"}
        p |= {"k": np.r_[0.0, 0.0, 1.0, 0.0], "m": np.r_[rng.normal(size=3), 0.0]}
        samples.append(p | {"d": p["a"] + 2.0 * (p["c"] - p["a"])})
    split = split_on_configurations(BracketPolynomial.parse("[abdk][abem] + [abck][abem]"), samples)
    assert split is not None
    first, second = sorted(b.sorted_labels for b in split.brackets)
    assert second == ("a", "b", "e", "m")
    assert (first, split.ratio) in [(("a", "b", "c", "k"), pytest.approx(3.0)), (("a", "b", "d", "k"), pytest.approx(1.5))]


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        (lambda s: split_on_configurations(Bracket("abcd"), s), ScrewkitTypeError, "Expected `factor` to be a BracketPolynomial, got Bracket"),
        (lambda s: split_on_configurations(BracketPolynomial.parse("[abcd] + [abce]"), s[:2]), ScrewkitValueError, "at least three `samples`, got 2"),
        (lambda s: split_on_configurations(BracketPolynomial.parse("[abcd] + [abcx]"), s), ScrewkitValueError, "hold the points x"),
    ],
)
def test_bad_input(call, error, match):
    with pytest.raises(error, match=match):
        call(ratio_samples(np.random.default_rng(0), 2.0))


def test_bad_samples_are_named():
    factor = BracketPolynomial.parse("[abcd][abef] - [abce][abdf]")
    rng = np.random.default_rng(1)
    good = [{x: np.r_[rng.normal(size=3), 1.0] for x in "abcdef"} for _ in range(4)]
    lacking = [*good[:3], {k: v for k, v in good[0].items() if k != "e"}]
    with pytest.raises(ScrewkitValueError, match=r"`samples\[3\]` to hold the points e"):
        split_on_configurations(factor, lacking)
    with pytest.raises(ScrewkitTypeError, match="`samples` to be a sequence of mappings, got generator"):
        split_on_configurations(factor, (s for s in good))
    with pytest.raises(ScrewkitValueError, match="point 'a' as 4 homogeneous numbers"):
        split_on_configurations(factor, [dict(good[0], a=np.zeros(3))] * 3)
    with pytest.raises(ScrewkitTypeError, match=r"`samples\[0\]` to map labels to points, got int"):
        split_on_configurations(factor, [1, 2, 3])
