"""Tests of screwkit.algebra.screw: known values, invariants, numeric/symbolic parity, errors."""

import math

import numpy as np
import pytest
import sympy
from hypothesis import given

from screwkit.algebra import screw as S
from screwkit.algebra.screwvalue import Screw
from screwkit.exceptions import (
    DegenerateGeometryError,
    ScrewkitIndexError,
    ScrewkitTypeError,
    ScrewkitValueError,
)

from ..strategies import rigid_motions, seeds, unit_factors


# known values (hand derivation) ------------------------------------------------------------------
def test_line_is_direction_then_moment_about_origin():
    # r = (1, 2, 3), s = (0, 0, 1): r × s = (2·1 − 3·0, 3·0 − 1·1, 0) = (2, −1, 0)
    np.testing.assert_array_equal(S.line([0, 0, 1], [1, 2, 3]), [0, 0, 1, 2, -1, 0])


def test_helical_twist_adds_pitch_times_direction():
    np.testing.assert_allclose(S.helical_twist([0, 0, 2], [1, 0, 0], 0.5), [0, 0, 2, 0, -2, 1])


def test_pitch_of_helical_twist_is_independent_of_axis_length():
    # the architecture notes warn against a pitch that is right only for unit axes
    assert S.pitch(S.helical_twist([0, 0, 7], [3, 1, 0], 0.25)) == pytest.approx(0.25)


def test_pitch_infinite_for_couples_and_zero_for_lines():
    assert S.pitch(S.couple([1, 2, 3])) == math.inf
    assert S.pitch(S.line([1, 2, 3], [4, 5, 6])) == pytest.approx(0.0, abs=1e-15)


def test_axis_point_is_nearest_the_origin():
    point, unit = S.axis(S.helical_twist([0, 1, 0], [3, 7, -2], 1.5))
    np.testing.assert_allclose(point, [3, 0, -2], atol=1e-12)
    np.testing.assert_allclose(unit, [0, 1, 0])


def test_reciprocity_facts_of_paper_002_section_3():
    # two zero-pitch screws are reciprocal iff coplanar; zero/infinite iff orthogonal; two
    # infinite-pitch screws always (paper 002 §3)
    x_axis = S.line([1, 0, 0], [0, 0, 0])
    assert S.reciprocal_product(x_axis, S.line([0, 1, 0], [5, 0, 0])) == 0  # meet at (5, 0, 0)
    assert S.reciprocal_product(x_axis, S.line([0, 1, 0], [0, 0, 1])) != 0  # skew
    assert S.reciprocal_product(x_axis, S.couple([0, 1, 0])) == 0
    assert S.reciprocal_product(x_axis, S.couple([1, 0, 0])) != 0
    assert S.reciprocal_product(S.couple([1, 0, 0]), S.couple([1, 0, 0])) == 0


def test_transform_moves_a_line_with_its_point():
    rotation = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1.0]])
    moved = S.transform(S.line([1, 0, 0], [0, 0, 0]), rotation, [0, 0, 1])
    np.testing.assert_allclose(moved, S.line([0, 1, 0], [0, 0, 1]))


def test_kernels_accept_batches(rng):
    directions, points = rng.normal(size=(4, 5, 3)), rng.normal(size=(4, 5, 3))
    lines = S.line(directions, points)
    assert lines.shape == (4, 5, 6)
    np.testing.assert_allclose(lines[2, 3], S.line(directions[2, 3], points[2, 3]))
    assert S.pitch(lines).shape == (4, 5)
    assert S.is_zero_pitch(lines).all() and not S.is_infinite_pitch(lines).any()


def test_predicates_decide_by_tolerance():
    nearly_line = S.helical_twist([1, 0, 0], [0, 0, 0], 1e-12)
    assert S.is_zero_pitch(nearly_line, rtol=1e-9)
    assert not S.is_zero_pitch(nearly_line, rtol=1e-15)


def test_normalize_and_magnitude():
    np.testing.assert_allclose(S.normalize(S.line([0, 0, 4], [1, 0, 0])), [0, 0, 1, 0, -1, 0])
    assert S.magnitude(S.couple([3, 4, 0])) == pytest.approx(5.0)


def test_screw_value_class_is_immutable_and_hides_equality():
    twist = Screw.revolute([0, 0, 1], [1, 1, 0])
    with pytest.raises(ValueError, match="read-only"):
        twist.coords[0] = 1.0
    assert twist != Screw.revolute([0, 0, 1], [1, 1, 0])  # identity equality only
    assert twist.is_equivalent(Screw.revolute([0, 0, -3], [1, 1, 5]))
    assert not twist.is_equivalent(Screw.revolute([0, 0, 1], [1, 2, 0]))


def test_to_dict_describes_the_axis():
    described = Screw.force([0, 0, 2], [1, 2, 3]).to_dict()
    assert described["kind"] == "zero pitch"
    np.testing.assert_allclose(described["point"], [1, 2, 0])
    np.testing.assert_allclose(described["direction"], [0, 0, 1])


# invariants --------------------------------------------------------------------------------------
@given(rigid_motions(), seeds)
def test_reciprocal_product_is_invariant_under_rigid_motions(motion, seed):
    rotation, translation = motion
    a, b = np.random.default_rng(seed).normal(size=(2, 6))
    before = S.reciprocal_product(a, b)
    after = S.reciprocal_product(
        S.transform(a, rotation, translation), S.transform(b, rotation, translation)
    )
    assert after == pytest.approx(before, abs=1e-9 * (1 + np.abs(a).sum() * np.abs(b).sum() * 10))


@given(rigid_motions(), unit_factors, seeds)
def test_pitch_predicates_invariant_under_motion_and_unit(motion, unit, seed):
    rotation, translation = motion
    rng = np.random.default_rng(seed)
    screws = np.stack(
        [
            S.line(rng.normal(size=3), rng.normal(size=3)),
            S.couple(rng.normal(size=3)),
            S.helical_twist(rng.normal(size=3), rng.normal(size=3), 0.7),
        ]
    )
    moved = S.transform(screws, rotation, translation)
    # a change of unit multiplies lengths (moments of lines, translations) by `unit`
    rescaled = np.concatenate([moved[:, :3], moved[:, 3:] * unit], axis=1)
    for candidate, scale in ((screws, 1.0), (moved, 1.0), (rescaled, unit)):
        np.testing.assert_array_equal(S.is_zero_pitch(candidate, length_scale=scale), [1, 0, 0])
        np.testing.assert_array_equal(S.is_infinite_pitch(candidate, length_scale=scale), [0, 1, 0])
    assert S.pitch(rescaled[2]) == pytest.approx(0.7 * unit)


# parity ------------------------------------------------------------------------------------------
def test_symbolic_kernels_agree_with_numeric_at_rational_points(rng):
    symbols = sympy.symbols("a0:3 r0:3 h")
    direction, point, h = symbols[:3], symbols[3:6], symbols[6]
    symbolic = S.helical_twist(list(direction), list(point), h)
    assert symbolic.dtype == object
    for _ in range(5):
        values = [sympy.Rational(int(v), 7) for v in rng.integers(-20, 20, size=7)]
        if all(v == 0 for v in values[:3]):
            continue
        subs = dict(zip(symbols, values, strict=True))
        exact = np.array([float(e.subs(subs)) for e in symbolic])
        numeric = S.helical_twist(
            [float(v) for v in values[:3]], [float(v) for v in values[3:6]], float(values[6])
        )
        np.testing.assert_allclose(exact, numeric, rtol=1e-12, atol=1e-12)
        assert float(S.pitch(symbolic).subs(subs)) == pytest.approx(float(values[6]))
        other = rng.normal(size=6)
        sym_product = S.reciprocal_product(
            symbolic, [sympy.Rational(repr(float(v))) for v in other]
        )
        assert float(sym_product.subs(subs)) == pytest.approx(S.reciprocal_product(numeric, other))


def test_symbolic_pitch_is_exact_and_infinite_for_symbolic_couples():
    t = sympy.Symbol("t", positive=True)
    assert S.pitch(S.couple([t, 0, 0])) == sympy.oo
    assert S.pitch(S.helical_twist([0, 0, t], [0, 0, 0], sympy.Rational(1, 3))) == sympy.Rational(
        1, 3
    )
    assert Screw.revolute([0, 0, 1], [t, 0, 0]).is_symbolic


def test_mixed_numeric_and_symbolic_input_is_promoted_exactly():
    x = sympy.Symbol("x")
    result = S.line([0.5, 0, 0], [0, x, 0])
    assert all(isinstance(v, sympy.Basic) for v in result)
    assert result[5] == -x / 2  # r × s = (0, x, 0) × (1/2, 0, 0) = (0, 0, −x/2): 0.5 became 1/2


# errors: one per message -------------------------------------------------------------------------
def test_error_wrong_shape():
    with pytest.raises(
        ScrewkitValueError, match=r"Expected `point` to have shape \(\.\.\., 3\), got \(2,\)"
    ):
        S.line([0, 0, 1], [1, 2])


def test_error_nan_coordinates():
    with pytest.raises(
        ScrewkitValueError, match="Expected `direction` to hold finite numbers, got NaN"
    ):
        S.line([np.nan, 0, 1], [1, 2, 3])


def test_error_infinite_coordinates():
    with pytest.raises(ScrewkitValueError, match="Expected `screws` to hold finite numbers"):
        S.pitch([np.inf, 0, 0, 0, 0, 0])


def test_error_string_input():
    with pytest.raises(
        ScrewkitTypeError, match="Expected `direction` to be numeric, got the string"
    ):
        S.prismatic_twist("0 0 1")


def test_error_non_numeric_input():
    with pytest.raises(ScrewkitTypeError, match="Expected `point` to be an array of numbers"):
        S.line([0, 0, 1], [object(), 1, 2])


def test_error_zero_direction():
    with pytest.raises(
        DegenerateGeometryError, match="Expected `direction` to be a non-zero direction"
    ):
        S.line([0, 0, 0], [1, 2, 3])


def test_error_zero_screw_pitch():
    with pytest.raises(
        DegenerateGeometryError, match="Expected non-zero screws, got the zero screw"
    ):
        S.pitch(np.zeros(6))


def test_error_axis_of_couple():
    with pytest.raises(DegenerateGeometryError, match="Expected screws of finite pitch, got s = 0"):
        S.axis(S.couple([0, 0, 1]))


def test_error_bad_rotation():
    with pytest.raises(
        ScrewkitValueError, match="Expected `rotation` to be a proper rotation matrix"
    ):
        S.transform(S.couple([0, 0, 1]), np.diag([1.0, 1.0, -1.0]), [0, 0, 0])


def test_error_bad_length_scale():
    with pytest.raises(
        ScrewkitValueError, match="Expected `length_scale` to be a positive finite number"
    ):
        S.is_zero_pitch(S.couple([0, 0, 1]), length_scale=-1.0)


def test_symbolic_pitch_predicates_decide_generically():
    # By hand: a couple (0; m, 0, 1) has s = 0 (infinite pitch); a line (s; r × s) has s·(r × s) = 0
    # identically; a helical twist of symbolic pitch h has s·s0 = h |s|², generically non-zero.
    m, h, x, y = sympy.symbols("m h x y")
    couple = S.couple([m, 0, 1])
    line = S.line([x, 1, 0], [0, y, 1])
    helix = S.helical_twist([0, 0, 1], [x, y, 0], h)
    assert S.is_infinite_pitch(couple) and not S.is_zero_pitch(couple)
    assert S.is_zero_pitch(line) and not S.is_infinite_pitch(line)
    assert not S.is_zero_pitch(helix) and not S.is_infinite_pitch(helix)
    # a trigonometric identity: s·s0 = sin²t + cos²t − 1 vanishes identically
    t = sympy.Symbol("t")
    trig = Screw([1, 0, 0, sympy.sin(t) ** 2 + sympy.cos(t) ** 2 - 1, 1, 0])
    assert trig.is_zero_pitch() and not trig.is_infinite_pitch()


@pytest.mark.parametrize("predicate", [S.is_zero_pitch, S.is_infinite_pitch])
def test_error_symbolic_pitch_predicates_check_their_input_as_the_numeric_ones_do(predicate):
    # An identically zero symbolic screw is the zero screw (it read as a couple: s = 0), and a bad
    # length scale is refused whatever the screws (it was ignored for symbolic ones).
    x = sympy.Symbol("x")
    with pytest.raises(DegenerateGeometryError, match="Expected non-zero screws, got the zero screw"):
        predicate(np.array([x - x, 0, 0, 0, (x + 1) ** 2 - x**2 - 2 * x - 1, 0], dtype=object))
    with pytest.raises(ScrewkitValueError, match="Expected `length_scale` to be a positive finite number"):
        predicate(S.couple([x, 0, 1]), length_scale=-1.0)


# batches of Screw (one class for one screw and for many): every method equals a loop over singles --------
BATCH_SHAPES = [(), (3,), (2, 4)]


def _batch_coords(shape, symbolic, seed=0):
    """Screws of every kind (finite, zero, infinite pitch) filling a batch of `shape`."""
    rng = np.random.default_rng(seed)
    rows = rng.integers(-3, 4, size=(*shape, 6)).astype(float)
    flat = rows.reshape(-1, 6)
    flat[::3, :3] = 0.0  # couples (infinite pitch)
    flat[1::3, 3:] = np.cross(flat[1::3, :3] * 0 + [1.0, 2.0, 0.0], flat[1::3, :3])  # lines (zero pitch)
    flat[np.all(flat[:, :3] == 0, axis=1) & np.all(flat[:, 3:] == 0, axis=1), 3] = 1.0
    flat[1::3][np.all(flat[1::3, :3] == 0, axis=1), 2] = 1.0
    if symbolic:
        x = sympy.Symbol("x", positive=True)
        return (rows.astype(int).astype(object) * x).reshape(rows.shape)  # exact, scaled by a symbol
    return rows


def _singles(coords):
    return [Screw(coords[i]) for i in np.ndindex(coords.shape[:-1])]


def _as_batch(values, shape):
    return np.array(values, dtype=object).reshape(shape)


@pytest.mark.parametrize("symbolic", [False, True])
@pytest.mark.parametrize("shape", BATCH_SHAPES)
def test_batch_has_shape_length_and_indexes_to_its_single_screws(shape, symbolic):
    coords = _batch_coords(shape, symbolic)
    batch = Screw(coords)
    assert batch.shape == shape and batch.single == (shape == ())
    assert batch.is_symbolic == symbolic and not batch.coords.flags.writeable
    assert bool(batch)  # truthy whatever its length, as before batches
    if shape == ():
        with pytest.raises(TypeError, match="a single Screw has no length"):
            len(batch)
        with pytest.raises(TypeError, match="a single Screw has no length"):
            list(batch)
        return
    assert len(batch) == shape[0]
    assert [element.shape for element in batch] == [shape[1:]] * shape[0]
    for i in np.ndindex(shape):
        element = batch[i]
        assert element.shape == () and element.single
        np.testing.assert_array_equal(element.coords, coords[i])
    np.testing.assert_array_equal(batch[1:].coords, coords[1:])
    np.testing.assert_array_equal(np.asarray(batch), coords)


@pytest.mark.parametrize("symbolic", [False, True])
@pytest.mark.parametrize("shape", BATCH_SHAPES)
def test_batch_properties_and_predicates_equal_a_loop_over_single_screws(shape, symbolic):
    coords = _batch_coords(shape, symbolic)
    batch, singles = Screw(coords), _singles(coords)
    for name in ["pitch", "magnitude"]:
        expected = _as_batch([getattr(one, name) for one in singles], shape)
        got = np.asarray(getattr(batch, name), dtype=object)
        assert got.shape == shape
        assert all(g == e or sympy.simplify(g - e) == 0 for g, e in zip(got.flat, expected.flat, strict=True))
    for name in ["is_zero_pitch", "is_infinite_pitch"]:
        got = getattr(batch, name)()
        expected = [getattr(one, name)() for one in singles]
        assert np.shape(got) == shape and np.ravel(got).tolist() == expected
        if shape == ():
            assert type(got) is bool
    np.testing.assert_array_equal(batch.direction, coords[..., :3])
    np.testing.assert_array_equal(batch.moment, coords[..., 3:])


@pytest.mark.parametrize("shape", BATCH_SHAPES)
def test_batch_axis_normalized_transformed_and_products_equal_a_loop(shape):
    coords = _batch_coords(shape, False)
    coords[..., :3] += [0.0, 0.0, 5.0]  # finite pitch everywhere, for the axis
    batch, singles = Screw(coords), _singles(coords)
    point, unit = batch.axis
    assert point.shape == unit.shape == (*shape, 3)
    np.testing.assert_allclose(point.reshape(-1, 3), [one.axis[0] for one in singles])
    np.testing.assert_allclose(unit.reshape(-1, 3), [one.axis[1] for one in singles])
    np.testing.assert_allclose(batch.normalized().coords.reshape(-1, 6), [one.normalized().coords for one in singles])
    quarter_turn = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
    moved = batch.transformed(quarter_turn, [1.0, 2.0, 3.0])
    assert moved.shape == shape
    np.testing.assert_allclose(
        moved.coords.reshape(-1, 6), [one.transformed(quarter_turn, [1.0, 2.0, 3.0]).coords for one in singles]
    )
    other = Screw.force([1, 2, 0], [0, 1, 4])
    products = batch.reciprocal_product(other)
    assert np.shape(products) == shape
    np.testing.assert_allclose(np.ravel(products), [one.reciprocal_product(other) for one in singles])
    scaled = Screw(-2.5 * coords)
    equivalent = batch.is_equivalent(scaled)
    assert np.shape(equivalent) == shape and np.all(equivalent)
    mixed = batch.is_equivalent(Screw(coords[..., ::-1]))
    assert np.ravel(mixed).tolist() == [a.is_equivalent(Screw(a.coords[::-1])) for a in singles]


@pytest.mark.parametrize("shape", BATCH_SHAPES)
def test_symbolic_batch_equivalence_and_product_equal_a_loop(shape):
    coords = _batch_coords(shape, True)
    batch, singles = Screw(coords), _singles(coords)
    reversed_batch = Screw(coords[..., ::-1])
    got = batch.is_equivalent(reversed_batch)
    assert np.ravel(got).tolist() == [a.is_equivalent(Screw(a.coords[::-1])) for a in singles]
    assert np.all(batch.is_equivalent(Screw(coords * 3)))
    other = Screw([1, sympy.Symbol("y"), 0, 0, 0, 1])
    products = np.asarray(batch.reciprocal_product(other), dtype=object)
    assert products.shape == shape
    assert all(sympy.simplify(p - one.reciprocal_product(other)) == 0 for p, one in zip(products.flat, singles, strict=True))


@given(seeds)
def test_batched_constructors_equal_a_loop_over_single_constructors(seed):
    rng = np.random.default_rng(seed)
    directions, points, pitches = rng.normal(size=(3, 3)), rng.normal(size=(3, 3)), rng.normal(size=3)
    cases = [
        (Screw.revolute(directions, points), [Screw.revolute(d, p) for d, p in zip(directions, points, strict=True)]),
        (Screw.force(directions, points), [Screw.force(d, p) for d, p in zip(directions, points, strict=True)]),
        (Screw.prismatic(directions), [Screw.prismatic(d) for d in directions]),
        (Screw.couple(directions), [Screw.couple(d) for d in directions]),
        (Screw.from_plucker(directions, points), [Screw.from_plucker(d, p) for d, p in zip(directions, points, strict=True)]),
        (
            Screw.helical(directions, points, pitches),
            [Screw.helical(d, p, h) for d, p, h in zip(directions, points, pitches, strict=True)],
        ),
    ]
    for batch, singles in cases:
        assert batch.shape == (3,)
        np.testing.assert_allclose(batch.coords, [one.coords for one in singles], rtol=0, atol=0)


def test_batch_str_lists_its_screws_and_to_dict_describes_its_elements():
    batch = Screw(_batch_coords((2, 4), False))
    assert str(batch) == "[" + ", ".join("[" + ", ".join(str(s) for s in row) + "]" for row in batch) + "]"
    assert str(batch[0, 1]) == str(Screw(batch.coords[0, 1]))
    assert [one.to_dict() for one in batch[1]] == [Screw(c).to_dict() for c in batch.coords[1]]


def test_screw_system_spans_a_batch_as_its_screws():
    from screwkit.algebra.screwsystem import ScrewSystem

    batch = Screw.couple(np.eye(3))
    assert ScrewSystem.span(list(batch)).order == ScrewSystem.span(np.eye(6)[3:]).order == 3


def test_error_single_screw_cannot_be_indexed():
    with pytest.raises(ScrewkitTypeError, match=r"Expected `index` to index a batch of screws, got a single Screw \(shape \(\)\)"):
        Screw.couple([0, 0, 1])[0]


def test_error_batch_index_out_of_range():
    with pytest.raises(ScrewkitIndexError, match=r"Expected `index` to index the batch of shape \(2, 4\), got \(2, 0\)"):
        Screw(np.ones((2, 4, 6)))[2, 0]
    with pytest.raises(ScrewkitIndexError, match=r"Expected `index` to index the batch of shape \(3,\), got \(0, 0\)"):
        Screw(np.ones((3, 6)))[0, 0]  # the coordinates are not a batch axis


def test_error_batch_to_dict():
    with pytest.raises(ScrewkitValueError, match=r"Expected a single Screw to describe, got a batch of shape \(3,\); index it"):
        Screw(np.ones((3, 6))).to_dict()


def test_error_reciprocal_with_non_screw():
    with pytest.raises(ScrewkitTypeError, match="Expected `other` to be a Screw, got list"):
        Screw.couple([0, 0, 1]).reciprocal_product([0, 0, 0, 0, 0, 1])


def test_screw_objects_are_arrays_for_every_kernel():
    # docs/architecture.md §1a: np.asarray(screw) is its (6,) array, and functions taking screws accept Screws
    force, couple = Screw.force([1, 0, 0], [0, 0, 2.0]), Screw.couple([0, 1, 0])
    assert np.asarray(force).dtype == float and np.asarray(force).shape == (6,)
    assert float(S.reciprocal_product(force, Screw.revolute([0, 1, 0], [0, 0, 0]))) == pytest.approx(2.0)  # (0, 2, 0)·(0, 1, 0)
    assert float(S.reciprocal_product(force, couple)) == 0.0
    np.testing.assert_array_equal(S.reciprocal_product([force, couple], np.asarray(couple)), [0.0, 0.0])
    symbol = sympy.Symbol("h")
    symbolic = Screw([1, 0, 0, symbol, 0, 0])
    assert sympy.simplify(S.reciprocal_product(symbolic, Screw.force([1, 0, 0], [0, 0, 0])) - symbol) == 0
