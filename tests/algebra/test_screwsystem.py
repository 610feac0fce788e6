"""Tests of screwkit.algebra.screwsystem: paper 002 §4.1 values, invariants, parity, errors."""

import numpy as np
import pytest
import sympy
from hypothesis import assume, given
from hypothesis import strategies as st

from screwkit.algebra import screw as S
from screwkit.algebra.motion_type import motion_type
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.algebra.screwvalue import Screw
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError

from ..strategies import rigid_motions, seeds, unit_factors


def spherical(center):
    """The 3-system of twists of a spherical joint: rotations about three axes through its centre."""
    return ScrewSystem.span([S.revolute_twist(axis, center) for axis in np.eye(3)])


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


# paper 002 §4.1: the 4S parallelogram from explicit points --------------------------------------
M = np.array([0.2, -0.1, 0.3])
N = M + np.array([0.1, 0.0, 0.0]) * 1.5  # mn: the short side
P = M + np.array([0.3, 0.5, -0.8])  # mp: the long side (a rod)
Q = P + (N - M)  # a parallelogram: mn ∥ pq and mp ∥ nq
S_MP, S_MN = unit(P - M), unit(N - M)
NORMAL = unit(np.cross(S_MN, S_MP))


def chain_wrenches(first, second):
    """Wrench system of the serial chain S–S: the intersection of the joints' wrench systems (Eq. 1)."""
    return (spherical(first) + spherical(second)).reciprocal()


def test_each_rod_transmits_only_the_force_along_it():
    # W_mp = span(τ01), τ01 = (s_mp, r_p × s_mp); W_nq = span(τ02), τ02 = (s_nq, r_q × s_nq)
    tau01 = S.line(S_MP, P)
    tau02 = S.line(S_MP, Q)
    w_mp, w_nq = chain_wrenches(M, P), chain_wrenches(N, Q)
    assert w_mp.order == 1 and w_mp.contains(Screw(tau01))
    assert w_nq.order == 1 and w_nq.contains(Screw(tau02))


def test_4s_wrench_system_is_a_force_and_a_couple():
    w_4s = chain_wrenches(M, P) + chain_wrenches(N, Q)  # Eq. (2): sum across parallel chains
    tau01 = S.line(S_MP, P)
    tau_inf1 = S.couple(np.cross(S_MP, S_MN))  # printed τ∞1 = (0, s_mp × s_mn)
    assert w_4s.order == 2
    assert w_4s.is_equivalent(ScrewSystem.span([tau01, tau_inf1]))
    # The paper writes τ∞1 = τ02 − τ01; that difference is (0, (r_q − r_p) × s_mp) =
    # −|mn| (0, s_mp × s_mn): the same line at infinity, with the opposite sign and length |mn|.
    difference = S.line(S_MP, Q) - S.line(S_MP, P)
    np.testing.assert_allclose(difference, -np.linalg.norm(N - M) * tau_inf1, atol=1e-12)
    # readable basis: the couple and a force (not two mixed screws)
    readable = w_4s.readable_basis()
    assert S.is_infinite_pitch(readable[0]) and S.is_zero_pitch(readable[1])
    np.testing.assert_allclose(np.abs(readable[0, 3:]), np.abs(NORMAL), atol=1e-12)


def test_4s_twist_system_is_the_printed_4_system():
    t_4s = (chain_wrenches(M, P) + chain_wrenches(N, Q)).reciprocal()
    printed = ScrewSystem.span(
        [
            S.line(S_MP, P),  # ε01 = (s_mp, r_p × s_mp)
            S.line(S_MN, N),  # ε02 = (s_mn, r_n × s_mn)
            S.couple(NORMAL),  # ε∞1 = (0, n)
            S.couple(np.cross(S_MP, NORMAL)),  # ε∞2 = (0, s_mp × n)
        ]
    )
    assert t_4s.order == 4 and printed.order == 4
    assert t_4s.is_equivalent(printed)


def test_readable_basis_of_a_mixed_force_couple_pair():
    force, couple = S.force([0, 0, 1], [1, 0, 0]), S.couple([0, 1, 0])
    mixed = ScrewSystem.span([force + 2 * couple, force - couple])
    readable = mixed.readable_basis()
    assert mixed.is_equivalent(ScrewSystem.span(readable))
    np.testing.assert_allclose(np.abs(readable[0]), [0, 0, 0, 0, 1, 0], atol=1e-12)
    assert S.is_zero_pitch(readable[1]) and abs(S.reciprocal_product(readable[1], force)) < 1e-12


def test_readable_basis_finds_the_two_lines_of_a_cylindroid():
    a, b = S.line([1, 0, 0], [0, 0, 0]), S.line([0, 1, 0], [0, 0, 1])
    mixed = ScrewSystem.span([a + b, a - 2 * b])
    readable = mixed.readable_basis()
    assert S.is_zero_pitch(readable).all()
    assert mixed.is_equivalent(ScrewSystem.span(readable))


def test_pitch_range_of_a_cylindroid_and_couple_systems():
    # principal pitches of span((x; h1 x), (y; h2 y)) are h1 and h2
    pair = [S.helical_twist([1, 0, 0], [0, 0, 0], 3.0), S.helical_twist([0, 1, 0], [0, 0, 0], -1.0)]
    assert ScrewSystem.span(pair).pitch_range() == pytest.approx((-1.0, 3.0))
    # a line plus a couple along it: every pitch is reachable
    unbounded = ScrewSystem.span([S.line([0, 0, 1], [0, 0, 0]), S.couple([0, 0, 1])])
    assert unbounded.pitch_range() == (-np.inf, np.inf)
    # a line plus a couple orthogonal to it: only lines (pitch 0) and couples
    fixed = ScrewSystem.span([S.line([0, 0, 1], [0, 0, 0]), S.couple([1, 0, 0])])
    assert fixed.pitch_range() == pytest.approx((0.0, 0.0), abs=1e-12)
    assert fixed.contains_pitch(0.0) and fixed.contains_pitch(np.inf)
    assert not fixed.contains_pitch(1.0)


def test_sum_intersection_on_known_systems():
    xy_couples = ScrewSystem.span([S.couple([1, 0, 0]), S.couple([0, 1, 0])])
    z_line = ScrewSystem.span([S.line([0, 0, 1], [0, 0, 0])])
    assert (xy_couples + z_line).order == 3
    assert (xy_couples & z_line).order == 0
    assert ScrewSystem.full().intersection(z_line).is_equivalent(z_line)


# invariants (hypothesis) ------------------------------------------------------------------------
def structured_system(rng, order, extra):
    """`order + extra` screws of rank `order`: random combinations of lines, couples, helices."""
    kinds = [
        lambda: S.line(rng.normal(size=3), rng.normal(size=3)),
        lambda: S.couple(rng.normal(size=3)),
        lambda: S.helical_twist(rng.normal(size=3), rng.normal(size=3), rng.normal()),
    ]
    # at most three couples: four couples span only three dimensions
    picks = [int(rng.integers(3)) for _ in range(order)]
    picks = [k if k != 1 or picks[:i].count(1) < 3 else 0 for i, k in enumerate(picks)]
    generators = np.array([kinds[k]() for k in picks]).reshape(order, 6)
    combos = rng.normal(size=(extra, order)) @ generators if order else np.zeros((extra, 6))
    return np.vstack([generators, combos])


def moved(rows, motion, unit):
    rotation, translation = motion
    out = S.transform(rows, rotation, translation)
    return np.hstack([out[:, :3], out[:, 3:] * unit])


@given(st.integers(0, 6), st.integers(0, 3), rigid_motions(), unit_factors, seeds)
def test_order_and_reciprocal_orders_are_frame_and_unit_invariant(order, extra, motion, unit, seed):
    rows = structured_system(np.random.default_rng(seed), order, extra)
    for candidate in (rows, moved(rows, motion, unit)):
        system = ScrewSystem.span(candidate)
        assert system.order == order
        assert system.reciprocal().order == 6 - order
        assert system.reciprocal().reciprocal().is_equivalent(system)


@given(st.integers(0, 3), st.integers(0, 3), st.integers(0, 2), rigid_motions(), unit_factors, seeds)
def test_dimension_formula_for_sum_and_intersection(common, only_a, only_b, motion, unit, seed):
    assume(common + only_a + only_b <= 6)  # more would not be independent in the 6-space
    rng = np.random.default_rng(seed)
    rows = structured_system(rng, common + only_a + only_b, 0)
    shared, a_only, b_only = np.split(rows, [common, common + only_a])
    for transform in (lambda r: r, lambda r: moved(r, motion, unit) if len(r) else r):
        a = ScrewSystem.span(transform(np.vstack([shared, a_only]).reshape(-1, 6)))
        b = ScrewSystem.span(transform(np.vstack([shared, b_only]).reshape(-1, 6)))
        assert (a + b).order + (a & b).order == a.order + b.order
        assert (a & b).order == common


@given(rigid_motions(), unit_factors, seeds)
def test_reciprocal_screws_are_reciprocal_to_every_basis_screw(motion, unit, seed):
    rows = moved(structured_system(np.random.default_rng(seed), 3, 1), motion, unit)
    system = ScrewSystem.span(rows)
    products = S.reciprocal_product(rows[:, None, :], system.reciprocal().basis[None, :, :])
    scale = np.linalg.norm(rows, axis=1)[:, None] * np.linalg.norm(system.reciprocal().basis, axis=1)
    assert np.all(np.abs(products) <= 1e-9 * scale)


# parity ------------------------------------------------------------------------------------------
def test_symbolic_reciprocal_matches_numeric_at_rational_points(rng):
    a, b = sympy.symbols("a b")
    symbolic = ScrewSystem.span(
        [S.line([1, 0, 0], [0, a, 0]), S.line([0, 1, 0], [b, 0, 0]), S.couple([0, 0, 1])]
    )
    assert symbolic.is_symbolic and symbolic.order == 3
    reciprocal = symbolic.reciprocal()
    assert reciprocal.order == 3
    for _ in range(4):
        values = {
            a: sympy.Rational(int(rng.integers(-9, 9)), 4),
            b: sympy.Rational(int(rng.integers(1, 9)), 3),
        }
        exact = np.array([[float(e.subs(values)) for e in row] for row in reciprocal.basis])
        numeric = ScrewSystem.span(
            [
                S.line([1, 0, 0], [0, float(values[a]), 0]),
                S.line([0, 1, 0], [float(values[b]), 0, 0]),
                S.couple([0, 0, 1]),
            ]
        ).reciprocal()
        assert numeric.is_equivalent(ScrewSystem.span(exact))


# errors ------------------------------------------------------------------------------------------
def test_error_dependent_basis():
    with pytest.raises(
        ScrewkitValueError,
        match="Expected `basis` to hold independent screws, got 2 rows of rank 1",
    ):
        ScrewSystem(np.array([S.couple([0, 0, 1]), S.couple([0, 0, 2])]))


def test_error_wrong_operand():
    with pytest.raises(ScrewkitTypeError, match="Expected `other` to be a ScrewSystem, got list"):
        ScrewSystem.full().sum([1, 2, 3])


def test_error_pitch_range_of_couples():
    with pytest.raises(ScrewkitValueError, match="Expected a system holding a screw of finite pitch"):
        ScrewSystem.span([S.couple([0, 0, 1])]).pitch_range()


def test_error_bad_rtol():
    with pytest.raises(ScrewkitValueError, match=r"Expected `rtol` to be a number in \[0, 0\.1\], got 2"):
        ScrewSystem.span([S.couple([0, 0, 1])], rtol=2)


def test_error_bad_screws_shape():
    with pytest.raises(
        ScrewkitValueError, match=r"Expected `screws` to have shape \(\.\.\., 6\), got \(3,\)"
    ):
        ScrewSystem.span([1.0, 2.0, 3.0])


# --- readable bases and motion types (issue 9 item 6) -----------------------------------------


def _independent_pitch(row):
    """Pitch numerator over direction norm: s·s0 / s·s (screw.py conventions), by hand."""
    return float(row[:3] @ row[3:] / (row[:3] @ row[:3]))


def test_readable_basis_of_three_skew_lines_reciprocal_is_three_transversal_lines():
    # constraint lines: the x axis, a line along y through (0, 0, 1), a line along z through (1, 2, 0)
    constraints = [S.line([1, 0, 0], [0, 0, 0]), S.line([0, 1, 0], [0, 0, 1]), S.line([0, 0, 1], [1, 2, 0])]
    twists = ScrewSystem.span(constraints).reciprocal()
    assert twists.order == 3
    readable = twists.readable_basis()
    assert readable.shape == (3, 6)
    assert np.linalg.matrix_rank(readable) == 3 and twists.is_equivalent(ScrewSystem.span(readable))
    for row in readable:
        assert np.linalg.norm(row[:3]) == pytest.approx(1.0)
        assert abs(_independent_pitch(row)) < 1e-9  # a rotation about a line
        for line in constraints:  # meets (or is parallel to) each constraint line: mutual moment 0
            assert abs(row[:3] @ line[3:] + row[3:] @ line[:3]) < 1e-9
    # by hand: the line through (2, 0, 0) [on the x axis] and (1, 2, 1/2) [on the z line] passes
    # through (0, 4, 1) [on the y line], so it meets all three: a rotation the system must allow
    transversal = S.line([-1, 2, 0.5], [2, 0, 0])
    assert twists.contains(Screw(transversal))
    # the old basis paired generators once and reported a screw of pitch ≠ 0; every row is a line now
    assert all(abs(_independent_pitch(row)) < 1e-9 for row in readable)


def test_readable_basis_puts_concurrent_lines_through_their_point_along_the_axes():
    centre = np.array([0.3, -1.2, 2.0])
    mixed = [
        S.revolute_twist([1, 1, 0], centre),
        S.revolute_twist([0, 1, 1], centre),
        S.revolute_twist([1, 2, 3], centre),
    ]
    readable = ScrewSystem.span(mixed).readable_basis()
    for row, axis in zip(readable, np.eye(3), strict=True):
        np.testing.assert_allclose(row, np.concatenate([axis, np.cross(centre, axis)]), atol=1e-12)


def test_readable_basis_gives_translations_along_xyz_and_the_rotation_axis_near_a_point():
    # a Schoenflies system whose rotation generator passes 4.9 m away (the 4-PRRU report)
    generators = [
        S.prismatic_twist([1, 1, 0]) + S.revolute_twist([0, 0, 1], [4.9, 0, 0]),
        S.prismatic_twist([0, 1, 1]),
        S.prismatic_twist([1, 0, 1]),
        S.prismatic_twist([1, 1, 0]),
    ]
    system = ScrewSystem.span(generators)
    near = np.array([0.2, 0.1, -0.5])
    readable = system.readable_basis(near=near)
    np.testing.assert_allclose(readable[:3], np.hstack([np.zeros((3, 3)), np.eye(3)]), atol=1e-12)
    np.testing.assert_allclose(
        readable[3], np.concatenate([[0, 0, 1], np.cross(near, [0, 0, 1])]), atol=1e-12
    )
    assert system.is_equivalent(ScrewSystem.span(readable))


def test_readable_basis_is_a_basis_of_the_same_system_on_random_systems(rng):
    for order in range(1, 6):
        for _ in range(5):
            system = ScrewSystem.span(rng.normal(size=(order, 6)))
            readable = system.readable_basis(near=rng.normal(size=3))
            assert readable.shape == (order, 6)
            assert system.is_equivalent(ScrewSystem.span(readable))


def test_span_and_reciprocal_bases_pass_the_constructors_independence_check(rng):
    # span and reciprocal build their systems unchecked (independent by construction: the ranks
    # were taken of those very rows, the reciprocal's rows are orthonormal in scaled coordinates);
    # the checked constructor accepts every one, with the same length scale
    for order in range(7):
        for repeat in range(6):
            rows = rng.normal(size=(order, 6)) * [1, 1, 1, 300, 300, 300]
            if order > 1 and repeat % 2:  # dependent generators: a combination of the first two
                rows = np.vstack([rows, rows[0] - 2.5 * rows[1]])
            system = ScrewSystem.span(rows)
            for made in (system, system.reciprocal(), system.reciprocal().reciprocal()):
                checked = ScrewSystem(made.basis, rtol=made.rtol, length_scale=made.length_scale)
                assert checked.length_scale == made.length_scale and checked.order == made.order
            assert system.order == min(order, 6) and system.reciprocal().order == 6 - system.order


def test_readable_basis_is_remembered_by_value_and_handed_out_as_a_fresh_array(rng):
    # the diagram and the report ask for the readable basis of the same system rebuilt from the
    # same rows: one computation, each caller its own writable copy; a different point, rtol or
    # length scale is another question
    from screwkit.algebra.screwsystem import _readable

    rows = rng.normal(size=(3, 6)) * [1, 1, 1, 40, 40, 40]  # axes tens of lengths away too
    system = ScrewSystem.span(rows, length_scale=2.0)
    first = system.readable_basis()
    hits = _readable.cache_info().hits
    again = ScrewSystem.from_independent(system.basis.copy(), length_scale=2.0).readable_basis()
    assert _readable.cache_info().hits == hits + 1
    np.testing.assert_array_equal(again, first)
    assert again.flags.writeable and not np.shares_memory(again, first)
    again[:] = 0.0  # the caller's copy: the next answer is unchanged
    np.testing.assert_array_equal(system.readable_basis(), first)
    near = system.readable_basis(near=[0.0, 0.0, 0.0])  # given, even at the origin: not the default
    fresh = ScrewSystem._readable_about(system, np.zeros(3))
    np.testing.assert_array_equal(near, fresh)
    assert system.is_equivalent(ScrewSystem.span(near))
    other = ScrewSystem.span(rows, length_scale=3.0).readable_basis()
    np.testing.assert_array_equal(other, ScrewSystem.span(rows, length_scale=3.0)._readable_about(None))


@pytest.mark.parametrize(
    ("generators", "expected"),
    [
        ([S.prismatic_twist(e) for e in np.eye(3)], "3T"),
        ([*(S.prismatic_twist(e) for e in np.eye(3)), S.revolute_twist([0, 0, 1], [1, 0, 0])], "3T1R"),
        # 3-RPS-like: rotations about x and y through the origin and a translation along z
        (
            [
                S.revolute_twist([1, 0, 0], [0, 0, 0]),
                S.revolute_twist([0, 1, 0], [0, 0, 0]),
                S.prismatic_twist([0, 0, 1]),
            ],
            "1T2R",  # translations first, whichever count is larger
        ),
        ([S.revolute_twist(e, [1, 2, 3]) for e in np.eye(3)], "3R"),
        (np.eye(6), "3T3R"),
        ([S.helical_twist([0, 0, 1], [0, 0, 0], 0.5)], "1H (pitch 0.5 length units/rad)"),
    ],
)
def test_motion_type_known_values(generators, expected):
    assert motion_type(np.array(generators)) == expected
    assert motion_type(ScrewSystem.span(generators)) == expected


def test_motion_type_is_batched_and_symbolic():
    planar = np.array([S.revolute_twist([0, 0, 1], [0, 0, 0]), S.revolute_twist([0, 0, 1], [1, 0, 0])])
    spatial = np.array([S.revolute_twist([0, 0, 1], [0, 0, 0]), S.revolute_twist([1, 0, 0], [0, 0, 0])])
    assert motion_type(np.stack([planar, spatial])).tolist() == ["1T1R", "2R"]
    a = sympy.Symbol("a")
    symbolic = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -a, 0]], dtype=object)
    assert motion_type(symbolic) == "1T1R"  # generic: a ≠ 0
    assert motion_type(ScrewSystem.zero()) == "0"


def test_motion_type_is_invariant_under_rigid_motions_and_units(rng):
    systems = [
        [*(S.prismatic_twist(e) for e in np.eye(3)), S.revolute_twist([0, 0, 1], [1, 0, 0])],
        [
            S.revolute_twist([1, 0, 0], [0, 0, 0]),
            S.revolute_twist([0, 1, 0], [0, 0, 0]),
            S.prismatic_twist([0, 0, 1]),
        ],
        [S.revolute_twist([0, 0, 1], [0, 0, 0]), S.revolute_twist([0, 0, 1], [1, 0, 0])],
    ]
    for generators in systems:
        rows = np.array(generators)
        expected = motion_type(rows)
        for _ in range(5):
            rotation, _ = np.linalg.qr(rng.normal(size=(3, 3)))
            rotation *= np.sign(np.linalg.det(rotation))  # a proper rotation
            moved = S.transform(rows, rotation, rng.normal(size=3) * 10)
            scaled = moved * np.r_[np.ones(3), np.full(3, 1000.0)]  # metres to millimetres
            assert motion_type(moved) == expected and motion_type(scaled) == expected


def test_in_is_contains_for_screws_arrays_and_systems():
    plane = ScrewSystem.span([S.couple([1, 0, 0]), S.couple([0, 1, 0])])
    assert Screw.couple([1, 1, 0]) in plane and [0, 0, 0, 2, -1, 0] in plane
    assert Screw.couple([0, 0, 1]) not in plane and Screw.force([1, 0, 0], [0, 0, 0]) not in plane
    assert ScrewSystem.span([S.couple([1, -1, 0])]) in plane
    with pytest.raises(ScrewkitValueError, match="Expected `item`"):
        _ = [1, 2, 3] in plane


def test_symbolic_couple_subsystem_is_the_intersection_with_the_couples():
    # by hand: a line (1, a, 0) through (0, b, 1), the couple (a, 1, b) and the line z through (a, 0, 0)
    # hold one couple generically (two lines of different directions hold none); adding (1, 0, 0)
    # couple gives two
    a, b = sympy.symbols("a b")
    rows = [S.line([1, a, 0], [0, b, 1]), S.couple([a, 1, b]), S.line([0, 0, 1], [a, 0, 0])]
    couples = ScrewSystem(np.hstack([np.zeros((3, 3)), np.eye(3)]).astype(int))
    for extra, order in (([], 1), ([S.couple([1, 0, 0])], 2)):
        system = ScrewSystem.span(np.array(rows + extra))
        found = system.couple_subsystem()
        assert found.order == order and found.is_symbolic
        assert all(all(v == 0 for v in row[:3]) for row in found.basis)
        assert found.is_equivalent(system.intersection(couples))
