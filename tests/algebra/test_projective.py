"""Tests of screwkit.algebra.projective: known values, incidence invariants, parity, errors."""

import numpy as np
import pytest
import sympy
from hypothesis import given

from screwkit.algebra import projective as P
from screwkit.algebra import screw as S
from screwkit.algebra.incidence import (
    are_collinear,
    are_coplanar,
    is_at_infinity,
    lines_intersect,
    point_on_line,
)
from screwkit.exceptions import DegenerateGeometryError, ScrewkitTypeError, ScrewkitValueError

from ..strategies import rigid_motions, seeds, unit_factors


def homogeneous_motion(points, motion, unit):
    """Apply a rigid motion and a change of unit to homogeneous points (w untouched)."""
    rotation, translation = motion
    xyz = points[..., :3] @ rotation.T + points[..., 3:] * translation
    return np.concatenate([xyz * unit, points[..., 3:]], axis=-1)


# known values ------------------------------------------------------------------------------------
def test_join_of_finite_and_infinite_point_is_the_papers_zero_pitch_wrench():
    r, s = np.array([1.0, -2.0, 0.5]), np.array([0.3, 0.4, 1.2])
    np.testing.assert_allclose(P.join(P.finite_point(r), P.infinite_point(s)), S.line(s, r))


def test_join_of_two_infinite_points_is_a_couple():
    u, v = np.array([1.0, 0, 0]), np.array([0, 2.0, 0])
    line = P.join(P.infinite_point(u), P.infinite_point(v))
    np.testing.assert_allclose(line, S.couple(np.cross(u, v)))
    assert S.is_infinite_pitch(line)


def test_bracket_of_two_lines_is_minus_their_reciprocal_product(rng):
    # gca.md §1: [pqrs] = −L(p,q) ∘ L(r,s)
    p, q, r, s = rng.normal(size=(4, 4))
    assert P.bracket(p, q, r, s) == pytest.approx(-S.reciprocal_product(P.join(p, q), P.join(r, s)))


def test_bracket_table_of_gca_md_section_5_1(rng):
    p, q, r, s = rng.normal(size=(4, 3))
    u, v, w = rng.normal(size=(3, 3))
    F, Inf = P.finite_point, P.infinite_point
    assert P.bracket(F(p), Inf(u), Inf(v), Inf(w)) == pytest.approx(-np.linalg.det([u, v, w]))
    assert P.bracket(F(p), F(q), Inf(u), Inf(v)) == pytest.approx(-(q - p) @ np.cross(u, v))
    assert P.bracket(F(p), F(q), F(r), Inf(u)) == pytest.approx(-np.cross(q - p, r - p) @ u)
    assert P.bracket(F(p), F(q), F(r), F(s)) == pytest.approx(-np.linalg.det([q - p, r - p, s - p]))
    assert P.bracket(Inf(u), Inf(v), Inf(w), Inf(p)) == pytest.approx(0.0, abs=1e-12)


def test_plane_through_three_points_is_the_bracket_functional(rng):
    p, q, r, x = rng.normal(size=(4, 4))
    assert P.plane_through(p, q, r) @ x == pytest.approx(P.bracket(p, q, r, x))


def test_meet_of_line_and_plane_and_of_two_planes():
    point = P.meet_line_plane(S.line([1, 1, 0], [0, 0, 3]), P.plane([1, 0, 0], [2, 0, 0]))
    np.testing.assert_allclose(point / point[3], [2, 2, 3, 1])
    line = P.meet_planes(P.plane([1, 0, 0], [1, 0, 0]), P.plane([0, 1, 0], [0, 2, 0]))
    np.testing.assert_allclose(line, S.line([0, 0, 1], [1, 2, 0]))


def test_parallel_line_meets_plane_at_infinity_when_allowed():
    point = P.meet_line_plane(S.line([1, 0, 0], [0, 0, 1]), [0, 0, 1, 0], allow_infinite=True)
    assert is_at_infinity(point)
    np.testing.assert_allclose(point[:3] / np.linalg.norm(point[:3]), [-1, 0, 0])


def test_parallel_planes_meet_at_infinity_when_allowed():
    line = P.meet_planes([0, 0, 1, 0], [0, 0, 1, -1], allow_infinite=True)
    assert S.is_infinite_pitch(line)


def test_line_points_reproduce_the_line(rng):
    finite = S.line(rng.normal(size=3), rng.normal(size=3))
    at_infinity = S.couple(rng.normal(size=3))
    for line in (finite, at_infinity):
        np.testing.assert_allclose(P.join(*P.line_points(line)), line, atol=1e-12)


# invariants --------------------------------------------------------------------------------------
@given(rigid_motions(), unit_factors, seeds)
def test_coplanarity_and_collinearity_are_invariant(motion, unit, seed):
    rng = np.random.default_rng(seed)
    a, b, c = rng.normal(size=(3, 3))
    on_plane = a + 0.7 * (b - a) - 1.3 * (c - a)
    off_plane = on_plane + np.cross(b - a, c - a)
    on_line = a + 2.5 * (b - a)
    pts = P.finite_point(np.array([a, b, c, on_plane, off_plane, on_line]))
    direction = P.infinite_point(b - a)
    cases = (
        (1.0, pts, direction),
        (unit, homogeneous_motion(pts, motion, unit), homogeneous_motion(direction, motion, unit)),
    )
    for scale, moved, d in cases:
        assert are_coplanar(*moved[[0, 1, 2, 3]], length_scale=scale)
        assert not are_coplanar(*moved[[0, 1, 2, 4]], length_scale=scale)
        assert are_collinear(moved[0], moved[1], moved[5], length_scale=scale)
        assert not are_collinear(moved[0], moved[1], moved[2], length_scale=scale)
        assert are_collinear(moved[0], moved[1], d, length_scale=scale)


@given(rigid_motions(), unit_factors, seeds)
def test_two_lines_are_reciprocal_iff_coplanar(motion, unit, seed):
    rng = np.random.default_rng(seed)
    a, b, c, d = P.finite_point(rng.normal(size=(4, 3)))
    shared = P.finite_point(rng.normal(size=3))
    for scale, tf in ((1.0, lambda x: x), (unit, lambda x: homogeneous_motion(x, motion, unit))):
        skew = (P.join(tf(a), tf(b)), P.join(tf(c), tf(d)))
        meeting = (P.join(tf(a), tf(shared)), P.join(tf(c), tf(shared)))
        assert not lines_intersect(*skew, length_scale=scale)
        assert lines_intersect(*meeting, length_scale=scale)
        assert not are_coplanar(tf(a), tf(b), tf(c), tf(d), length_scale=scale)


@given(rigid_motions(), seeds)
def test_zero_and_infinite_pitch_reciprocal_iff_orthogonal(motion, seed):
    rng = np.random.default_rng(seed)
    s, r = rng.normal(size=(2, 3))
    rotation, translation = motion
    line = S.transform(S.line(s, r), rotation, translation)
    orthogonal = S.couple(rotation @ np.cross(s, rng.normal(size=3)))
    oblique = S.couple(rotation @ (s + np.cross(s, rng.normal(size=3))))
    assert abs(S.reciprocal_product(line, orthogonal)) < 1e-9 * np.linalg.norm(orthogonal) * 10
    assert abs(S.reciprocal_product(line, oblique)) > 1e-6
    assert S.reciprocal_product(S.couple(s), S.couple(r)) == 0


@given(seeds)
def test_a_meet_lies_on_both_operands(seed):
    rng = np.random.default_rng(seed)
    line = P.join(P.finite_point(rng.normal(size=3)), P.finite_point(rng.normal(size=3)))
    first, second = (
        P.plane(rng.normal(size=3), rng.normal(size=3)),
        P.plane(rng.normal(size=3), rng.normal(size=3)),
    )
    point = P.meet_line_plane(line, first)
    assert point_on_line(point, line, rtol=1e-8)
    assert abs(point @ first) <= 1e-9 * np.linalg.norm(point) * np.linalg.norm(first)
    common = P.meet_planes(first, second)
    for p in P.line_points(common):
        for pl in (first, second):
            assert abs(p @ pl) <= 1e-9 * np.linalg.norm(p) * np.linalg.norm(pl) * 10


@given(rigid_motions(), unit_factors, seeds)
def test_bracket_vanishes_iff_coplanar(motion, unit, seed):
    rng = np.random.default_rng(seed)
    a, b, c = rng.normal(size=(3, 3))
    coplanar = P.finite_point(np.array([a, b, c, a + 0.3 * (b - a) + 0.4 * (c - a)]))
    general = P.finite_point(rng.normal(size=(4, 3)))
    moved_coplanar = homogeneous_motion(coplanar, motion, unit)
    moved_general = homogeneous_motion(general, motion, unit)
    size = np.prod(np.linalg.norm(moved_coplanar, axis=1))
    assert abs(P.bracket(*moved_coplanar)) <= 1e-10 * size
    # a rigid motion keeps the bracket of finite points; a change of unit multiplies it by unit³
    assert P.bracket(*moved_general) == pytest.approx(P.bracket(*general) * unit**3, rel=1e-8)


# parity ------------------------------------------------------------------------------------------
def test_symbolic_join_bracket_meet_match_numeric(rng):
    x, y, t = sympy.symbols("x y t")
    p = np.array([x, y, 1, 1], dtype=object)
    q = np.array([1, t, 0, 0], dtype=object)
    r, s = rng.integers(-5, 5, size=(2, 4)).astype(float)
    r[3], s[3] = 1.0, 0.0
    line = P.join(p, q)
    value = P.bracket(p, q, r, s)
    # the line is horizontal (q is the direction (1, t, 0)), so it meets z = 3 at infinity for every
    # x, y, t: the symbolic path refuses that as the numeric one does, unless allowed
    with pytest.raises(DegenerateGeometryError, match="got a line parallel to the plane"):
        P.meet_line_plane(line, np.array([0, 0, 1, -3], dtype=object))
    meet = P.meet_line_plane(line, np.array([0, 0, 1, -3], dtype=object), allow_infinite=True)
    for _ in range(4):
        subs = {v: sympy.Rational(int(rng.integers(-9, 9)), 5) for v in (x, y, t)}
        pn = np.array([float(subs[x]), float(subs[y]), 1, 1])
        qn = np.array([1, float(subs[t]), 0, 0])
        np.testing.assert_allclose([float(e.subs(subs)) for e in line], P.join(pn, qn))
        assert float(value.subs(subs)) == pytest.approx(P.bracket(pn, qn, r, s))
        expected = P.meet_line_plane(P.join(pn, qn), [0, 0, 1, -3], allow_infinite=True)
        np.testing.assert_allclose([float(e.subs(subs)) for e in meet], expected)


def test_symbolic_degeneracies_are_decided_identically_not_refused():
    # A join of two generic symbolic points is a line (it raised "Cannot decide whether -a is zero"
    # before); coincident symbolic points, identically equal planes and a line in its plane are refused
    # as in the numeric path. By hand: join((a,0,0,1), (0,b,0,1)) = (−a, b, 0; 0, 0, a·b).
    a, b = sympy.symbols("a b")
    line = P.join([a, 0, 0, 1], [0, b, 0, 1])
    assert [sympy.expand(v) for v in line] == [-a, b, 0, 0, 0, a * b]
    with pytest.raises(DegenerateGeometryError, match="distinct points"):
        P.join([a, b, 0, 1], [2 * a, 2 * b, 0, 2])
    with pytest.raises(DegenerateGeometryError, match="the same plane twice"):
        P.meet_planes([a, 0, 1, b], [2 * a, 0, 2, 2 * b])
    with pytest.raises(DegenerateGeometryError, match="a line lying in the plane"):
        P.meet_line_plane(line, [0, 0, 1, 0])  # the line lies in z = 0
    assert P.plane_through([a, 0, 0, 1], [0, b, 0, 1], [0, 0, 1, 1]).shape == (4,)


# errors ------------------------------------------------------------------------------------------
def test_error_coincident_points():
    with pytest.raises(DegenerateGeometryError, match="Expected `p` and `q` to be distinct points"):
        P.join(P.finite_point([1, 2, 3]), P.finite_point([1, 2, 3]))


def test_error_zero_infinite_point():
    with pytest.raises(DegenerateGeometryError, match="Expected `direction` to be non-zero"):
        P.infinite_point([0, 0, 0])


def test_error_parallel_planes():
    with pytest.raises(DegenerateGeometryError, match="got parallel planes"):
        P.meet_planes(P.plane([0, 0, 1], [0, 0, 0]), P.plane([0, 0, 2], [0, 0, 5]))


def test_error_same_plane_twice():
    with pytest.raises(DegenerateGeometryError, match="got the same plane twice"):
        P.meet_planes([0, 0, 1, -1], [0, 0, 2, -2])


def test_error_line_in_plane():
    with pytest.raises(DegenerateGeometryError, match="got a line lying in the plane"):
        P.meet_line_plane(S.line([1, 0, 0], [0, 0, 0]), [0, 0, 1, 0])


def test_error_line_parallel_to_plane():
    with pytest.raises(DegenerateGeometryError, match="got a line parallel to the plane"):
        P.meet_line_plane(S.line([1, 0, 0], [0, 0, 1]), [0, 0, 1, 0])


def test_error_collinear_points_span_no_plane():
    with pytest.raises(DegenerateGeometryError, match="Expected `p`, `q`, `r` to span a plane"):
        P.plane_through([0, 0, 0, 1], [1, 0, 0, 1], [2, 0, 0, 1])


def test_error_not_a_line():
    with pytest.raises(ScrewkitValueError, match="Expected `line` to be a line"):
        P.line_points(S.helical_twist([0, 0, 1], [0, 0, 0], 1.0))


def test_error_point_shape():
    with pytest.raises(
        ScrewkitValueError, match=r"Expected `p` to have shape \(\.\.\., 4\), got \(3,\)"
    ):
        P.join([0, 0, 0], [1, 0, 0, 1])


def test_error_nan_point():
    with pytest.raises(ScrewkitValueError, match="Expected `q` to hold finite numbers"):
        P.join([0, 0, 0, 1], [np.nan, 0, 0, 1])


def test_error_zero_normal():
    with pytest.raises(DegenerateGeometryError, match="Expected `normal` to be non-zero"):
        P.plane([0, 0, 0], [1, 1, 1])


def test_bracket_kernel_matches_the_determinant_and_is_exact(rng):
    from screwkit.algebra.projective import bracket_unchecked, join_unchecked

    points = rng.normal(size=(4, 5, 4))  # a batch of 5 quadruples
    expected = np.linalg.det(np.stack(list(points), axis=-2))
    np.testing.assert_allclose(bracket_unchecked(*points), expected, rtol=1e-12, atol=1e-12)
    t = sympy.Symbol("t")
    exact = [np.array(v, dtype=object) for v in ([t, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1], [0, 0, 0, 1])]
    assert sympy.expand(bracket_unchecked(*exact) - sympy.Matrix(np.stack(exact)).det()) == 0
    np.testing.assert_array_equal(join_unchecked(points[0], points[0]), np.zeros((5, 6)))


def test_line_points_decides_lines_at_the_ends_of_the_coordinate_range():
    # The line test |s·m| <= rtol |s| |m| took |s·m| as the norm of a 1-vector, whose square
    # overflows for a line with |s| |m| ≈ 1e185 (coordinates within the README's 1e100: a
    # RuntimeWarning, then "not a line") and underflows for a 1e-85-sized helix (read as a line).
    # By hand: m = p × s is a line through p (s·m = 0), its point at infinity (s, 0); the helix
    # (1, 0, 0; 1, 1, 0)·1e-85 has s·m = 1e-170 = |s| |m| / √2.
    rng = np.random.default_rng(3)
    for _ in range(20):
        s, p = rng.normal(size=3) * 1e85, rng.normal(size=3) * 1e15
        _, at_infinity = P.line_points(np.concatenate([s, np.cross(p, s)]))
        np.testing.assert_array_equal(at_infinity, np.append(s, 0.0))
    with pytest.raises(ScrewkitValueError, match=r"Expected `line` to be a line \(s·m = 0\), got s·m = 1e-170"):
        P.line_points(np.array([1.0, 0, 0, 1, 1, 0]) * 1e-85)


@pytest.mark.parametrize(
    ("test", "args", "name"),
    [
        (are_coplanar, ([0, 0, 0, 1], [1, 0, 0, 1], [0, 1, 0, 1], ["a", 0, 0, 1]), "s"),
        (are_collinear, (["a", 0, 0, 1], [1, 0, 0, 1], [2, 0, 0, 1]), "p"),
        (is_at_infinity, (["a", 0, 0, 1],), "points"),
        (lines_intersect, ([1, 0, 0, 0, 0, 0], [0, 1, 0, "a", 0, 0]), "second"),
        (point_on_line, (["a", 0, 0, 1], [1, 0, 0, 0, 0, 0]), "point"),
        (point_on_line, ([0, 0, 0, 1], [1, 0, 0, 0, 0, "a"]), "line"),
    ],
)
def test_tolerance_predicates_refuse_symbolic_coordinates_by_name(test, args, name):
    # they decide with rtol on floats; before, a symbol gave sympy's "Cannot convert expression to float"
    symbolic = [[sympy.Symbol(v) if v == "a" else v for v in arg] for arg in args]
    with pytest.raises(ScrewkitTypeError, match=rf"Expected `{name}` to hold numbers \({test.__name__} decides with a tolerance; .*got symbols\.$"):
        test(*symbolic)
