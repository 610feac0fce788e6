"""One bracket of combined points (screwkit.gca.combined_brackets): recognised, stated, and checked
on configurations built by hand and on a general 3-UPU's actuation factor."""

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.gca import BracketMonomial, BracketPolynomial
from screwkit.gca.combined_brackets import combined_bracket, combined_bracket_form
from screwkit.gca.condition_patterns import vector_form
from screwkit.gca.vector_forms import PointKinds, form_value
from screwkit.graphs.joints import prismatic, universal
from tests.mechanisms import twist_graph, unit

UPU_FACTOR = "[abce] - [abcf] - [abde] + [abdf]"
LABELS = "abcdef"


def _homogeneous(points):
    return {x: np.r_[p, 1.0] for x, p in points.items()}


def _leg_directions_parallel_to_a_plane(rng):
    """Six points with the directions b − a, d − c, f − e parallel to one plane, by construction."""
    a, b, c, d, e = rng.normal(size=(5, 3))
    f = e + 0.7 * (b - a) - 1.3 * (d - c)
    return dict(zip("abcdef", (a, b, c, d, e, f), strict=True))


def test_the_three_upu_factor_is_one_bracket_of_differences():
    found = combined_bracket(BracketPolynomial.parse(UPU_FACTOR))
    assert [str(slot) for slot in found.slots] == ["a", "b", "c - d", "e - f"]
    assert found.coefficient == 1


def test_the_three_upu_factor_is_the_triple_product_of_the_leg_directions():
    """[abce] − [abcf] − [abde] + [abdf] = ±det(b − a, d − c, f − e) on random finite points (a hand
    expansion by multilinearity), and it vanishes when the three directions are parallel to a plane."""
    rng = np.random.default_rng(3)
    polynomial = BracketPolynomial.parse(UPU_FACTOR)
    ratios = []
    for _ in range(5):
        points = dict(zip("abcdef", rng.normal(size=(6, 3)), strict=True))
        triple = np.linalg.det(np.array([points["b"] - points["a"], points["d"] - points["c"], points["f"] - points["e"]]))
        ratios.append(float(polynomial.evaluate(_homogeneous(points))) / triple)
    assert np.allclose(np.abs(ratios), 1.0, rtol=1e-12) and len({np.sign(r) for r in ratios}) == 1
    form, statement = vector_form(polynomial, PointKinds("abcdef", ""))
    assert statement == "the directions of lines ab, cd and ef are parallel to one plane"
    on = _leg_directions_parallel_to_a_plane(rng)
    assert abs(float(polynomial.evaluate(_homogeneous(on)))) < 1e-12
    assert abs(float(form_value(form, on, float))) < 1e-12
    off = dict(on, f=on["f"] + np.array([0.0, 0.0, 0.1]))
    assert abs(float(form_value(form, off, float))) > 1e-3


def test_directions_given_as_points_at_infinity_are_named_as_such():
    found = combined_bracket(BracketPolynomial.parse(UPU_FACTOR))
    _, statement = combined_bracket_form(found, PointKinds("bcdef", "a"))
    assert statement == (
        "the direction a, the direction of line cd and the direction of line ef are parallel to one plane"
    )
    _, statement = combined_bracket_form(found, PointKinds("ab", "cdef"))
    assert statement == (
        "the direction of line ab, the direction c − d and the direction e − f are parallel to one plane"
    )


@pytest.mark.parametrize(
    "text",
    ["[abcd][efgh] - [abce][dfgh]", "[abcd] + [efgh]", "[abcd]", "[abce] - [abce]"],
)
def test_not_one_bracket_of_combined_points(text):
    """Products, a sum with an 8-dimensional support, a single bracket, zero: None."""
    assert combined_bracket(BracketPolynomial.parse(text)) is None


def test_a_sum_that_is_not_a_difference_keeps_the_generic_statement():
    found = combined_bracket(BracketPolynomial.parse("[abce] + [abde]"))
    assert [str(slot) for slot in found.slots] == ["a", "b", "c + d", "e"]
    assert combined_bracket_form(found, PointKinds("abcde", "")) is None


slot_coefficients = st.lists(st.integers(-2, 2), min_size=len(LABELS), max_size=len(LABELS))


@settings(max_examples=30, deadline=None)
@given(st.lists(slot_coefficients, min_size=4, max_size=4), st.integers(0, 10_000))
def test_any_bracket_of_combinations_is_recovered(slots, seed):
    """Expand [s₁ s₂ s₃ s₄] for random integer combinations sᵢ; whatever slots are found, the
    value equals the bracket of the combinations (numpy 4×4 determinant) on random points."""
    rng = np.random.default_rng(seed)
    samples = [{x: rng.normal(size=4) for x in LABELS} for _ in range(3)]

    def direct(points):
        rows = [sum(c * points[x] for c, x in zip(slot, LABELS, strict=True)) for slot in slots]
        return np.linalg.det(np.array(rows, dtype=float))

    sample_values = [direct(points) for points in samples]
    polynomial = BracketPolynomial(
        BracketMonomial([tuple(labels)], coefficient) for labels, coefficient in _expanded(slots) if coefficient
    )
    found = combined_bracket(polynomial)
    if all(abs(v) < 1e-9 for v in sample_values):
        assert found is None  # the combinations are dependent: the polynomial is zero
        return
    if len(polynomial.terms) < 2:
        return
    assert found is not None
    for points, expected in zip(samples, sample_values, strict=True):
        rows = [sum(float(c) * points[x] for x, c in slot.terms) for slot in found.slots]
        assert float(found.coefficient) * np.linalg.det(np.array(rows)) == pytest.approx(expected, rel=1e-9, abs=1e-9)


def _expanded(slots):
    """(labels, coefficient) of the multilinear expansion, one entry per choice of labels."""
    for choice in itertools.product(range(len(LABELS)), repeat=4):
        if len(set(choice)) == 4:
            coefficient = np.prod([slots[k][i] for k, i in enumerate(choice)])
            yield [LABELS[i] for i in choice], int(coefficient)


def general_three_upu(position):
    """A 3-UPU whose base and platform triangles are not similar (U axes as in Tsai's 3-UPU: outer
    axis tangent to the base circle, inner axis normal to it and the leg)."""
    angles = (0.0, 2.0, 4.3)
    joints = []
    for i, (angle, radius) in enumerate(zip(angles, (1.0, 1.2, 0.9), strict=True), start=1):
        radial = np.array([np.cos(angle), np.sin(angle), 0.0])
        a, c = radius * radial, np.asarray(position) + 0.5 * radial
        u = np.cross([0.0, 0.0, 1.0], radial)
        w = unit(np.cross(u, unit(c - a)))
        joints += [
            ("base", f"lower{i}", universal(f"Ub{i}", u, w, a)),
            (f"lower{i}", f"upper{i}", prismatic(f"P{i}", unit(c - a), actuated=True)),
            (f"upper{i}", "platform", universal(f"Up{i}", w, u, c)),
        ]
    return twist_graph("base", "platform", joints)


def test_a_general_three_upu_states_its_actuation_factor():
    report = sk.analyze(general_three_upu([0.1, 0.05, 0.8]))
    statements = {c.label: c.statement for c in report.superbracket.conditions}
    # on this design (a translating platform parallel to the base) the factor is a constant multiple
    # of [abce]: the leg directions are parallel to one plane only with the platform in the base plane
    assert statements["actuation"].startswith("the directions of lines ab, cd and ef are parallel to one plane; ")
    assert statements["actuation"].endswith(
        "on this mechanism it is a constant multiple of [abce] (the same ratio on all 12 sampled configurations: "
        "a relation of the design that is no incidence of the diagram, checked numerically), i.e. of "
        "((b − a) × (c − a))·(e − a), so it vanishes exactly where a, b, c and e are coplanar"
    )
    # a, c, e are the base U centres and b a platform one: with the platform lowered into the base
    # plane (z = 0) the three legs are horizontal, and the factor vanishes there
    lowered = sk.analyze(general_three_upu([0.1, 0.05, 0.0])).superbracket
    assert lowered.vanishing[[c.label for c in lowered.conditions].index("actuation")]
    assert not report.superbracket.vanishing[[c.label for c in report.superbracket.conditions].index("actuation")]
