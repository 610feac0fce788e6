"""Generic (symbolic) analysis of families of mechanisms (screwkit.core.generic, screwkit.algebra.symbolic).

Expected values come from the mechanisms' known motion types (Delta-like 3-RUU: three
translations, Clavel 1988 / Tsai 1996; H4: Schoenflies 3T1R, paper 002 §4, paper 004 §1) and from
the numeric core at substituted values (parity), never from the generic code itself.
"""

import dataclasses
import random

import mpmath
import numpy as np
import pytest
import sympy
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.algebra import screw as S
from screwkit.algebra import symbolic as Y
from screwkit.algebra import symbolic_bases as YB
from screwkit.algebra.screwsystem import ScrewSystem
from screwkit.core.generic import GenericAnalysis, generic_analysis
from screwkit.core.singularity import classify
from screwkit.core.wrench_systems import WrenchAnalysis
from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import ScrewkitTypeError, ScrewkitValueError
from screwkit.graphs.joints import revolute, spherical
from screwkit.graphs.twistgraph import twist_graph


def point(name, values=None):
    symbols = sympy.symbols(f"{name}x {name}y {name}z")
    return symbols if values is None else tuple(values[s] for s in symbols)


def tilted(i, values=None):
    """The direction of limb i's second U axis: fixed for limbs 1, 2; ``(cos θ_3, sin θ_3, 1)``."""
    if i != 3:
        return (0, 0, 1)
    theta = sympy.Symbol(f"theta{i}")
    if values is not None:
        return (np.cos(values[theta]), np.sin(values[theta]), 1.0)
    return (sympy.cos(theta), sympy.sin(theta), 1)


def delta_3ruu(values=None):
    """Three R-U-U limbs: actuated R about u_i, then U (u_i, v_i) at b_i and U (v_i, u_i) at c_i.
    The U joints' positions and the angle θ_3 of v_3 are symbols; the u_i and the actuated joints'
    positions are fixed."""
    axes = [(1, 0, 0), (0, 1, 0), (1, 0, 0)]  # unit: numeric axes are normalised
    joints = []
    for i, u in enumerate(axes, start=1):
        a = (0, 2 * i, -i)
        b, c = (point(f"{name}{i}", values) for name in "bc")
        v = tilted(i, values)
        joints += [
            ("base", f"arm{i}", revolute(f"A{i}", u, a, actuated=True)),
            (f"arm{i}", f"k{i}", revolute(f"B{i}u", u, b)),
            (f"k{i}", f"rod{i}", revolute(f"B{i}v", v, b)),
            (f"rod{i}", f"l{i}", revolute(f"C{i}v", v, c)),
            (f"l{i}", "platform", revolute(f"C{i}u", u, c)),
        ]
    return twist_graph("base", "platform", joints, dof=3)


def r_4s_limbs(geometry, axis, values):
    """Four R-(4S) limbs on two sub-platforms joined to the end effector by revolute joints about
    ``axis`` through r_1, r_2 (paper 002 Fig. 2). ``geometry(i)`` gives limb i's actuated axis u,
    base point a, elbow m, short-side vector and rod vector: S joints at m, m + side, and both
    moved by the rod."""
    joints = []
    for i, sub in zip((1, 2, 3, 4), ("b_I", "b_II", "b_II", "b_I"), strict=True):
        u, a, m, side, rod = geometry(i)
        n = [mj + sj for mj, sj in zip(m, side, strict=True)]
        p = [mj + dj for mj, dj in zip(m, rod, strict=True)]
        q = [nj + dj for nj, dj in zip(n, rod, strict=True)]
        joints += [
            ("base", f"arm{i}", revolute(f"A{i}", u, a, actuated=True)),
            (f"arm{i}", f"rod{i}a", spherical(f"S{i}m", m)),
            (f"rod{i}a", sub, spherical(f"S{i}p", p)),
            (f"arm{i}", f"rod{i}b", spherical(f"S{i}n", n)),
            (f"rod{i}b", sub, spherical(f"S{i}q", q)),
        ]
    joints += [
        ("b_I", "ee", revolute("R_I", axis, point("r1", values))),
        ("b_II", "ee", revolute("R_II", axis, point("r2", values))),
    ]
    return twist_graph("base", "ee", joints, dof=4)


def scalar(name, values):
    symbol = sympy.Symbol(name)
    return symbol if values is None else values[symbol]


def four_limb_smg(values=None):
    """An H4-like family: every joint position a symbol (a_i, elbow m_i, rods of length l_i along
    the fixed direction d_i, short sides of length s_i along the fixed u_i), the sub-platform
    joints' points; directions are fixed numbers, the common axis is z."""
    us = [(1, 0, 0), (0, 1, 0), (0, 1, 0), (1, 0, 0)]
    ds = [(1, 2, -5), (-2, 1, -4), (3, -1, -5), (-1, -3, -6)]

    def geometry(i):
        u, d = us[i - 1], ds[i - 1]
        side, rod = scalar(f"s{i}", values), scalar(f"l{i}", values)
        return u, point(f"a{i}", values), point(f"m{i}", values), [side * x for x in u], [rod * x for x in d]

    return r_4s_limbs(geometry, (0, 0, 1), values)


def fully_symbolic_h4(values=None):
    """The same family with every position and direction a symbol (61 symbols): axes u_i, rods
    d_i, short sides λ_i u_i, a common axis k of R_I, R_II."""

    def geometry(i):
        u = point(f"u{i}", values)
        side = scalar(f"l{i}", values)
        return (
            u,
            point(f"a{i}", values),
            point(f"m{i}", values),
            [side * x for x in u],
            point(f"d{i}", values),
        )

    return r_4s_limbs(geometry, point("k", values), values)


def numeric_values(rng):
    """Random values for every symbol the builders use (some never reach a screw)."""
    names = [f"{n}{i}{c}" for n in "abcm" for i in (1, 2, 3, 4) for c in "xyz"] + [
        f"theta{i}" for i in (1, 2, 3)
    ]
    names += [f"r{i}{c}" for i in (1, 2) for c in "xyz"] + [f"{n}{i}" for n in "sl" for i in (1, 2, 3, 4)]
    names += [f"{n}{i}{c}" for n in "ud" for i in (1, 2, 3, 4) for c in "xyz"] + ["kx", "ky", "kz"]
    return {sympy.Symbol(name): float(rng.uniform(-2, 2)) for name in names}


@pytest.fixture(scope="module")
def delta():
    return generic_analysis(delta_3ruu())


@pytest.fixture(scope="module")
def smg():
    return generic_analysis(four_limb_smg())


@pytest.fixture(scope="module")
def h4():
    return generic_analysis(fully_symbolic_h4())


def test_delta_like_family_translates(delta):
    assert (delta.mobility, delta.motion_type) == (3, "3T")
    assert delta.constraint_order == 3 and delta.global_order == 6
    # each limb constrains the couple along u_i × v_i (a hand derivation: both U joints share u_i, v_i)
    for limb, u in zip(delta.limbs, [(1, 0, 0), (0, 1, 0), (1, 0, 0)], strict=True):
        assert limb.constraint_wrenches.order == 1
        row = limb.constraint_wrenches.basis[0]
        assert all(sympy.simplify(x) == 0 for x in row[:3])  # a couple
        v = tilted(int(limb.actuated_joint[1]))
        expected = np.cross(np.array(u, dtype=object), np.array(v, dtype=object))
        ratio = [
            sympy.simplify(row[3 + k] * expected[j] - row[3 + j] * expected[k])
            for j in range(3)
            for k in range(3)
        ]
        assert all(r == 0 for r in ratio)


def test_four_limb_smg_family_is_schoenflies(smg):
    assert (smg.mobility, smg.motion_type) == (4, "3T1R")
    assert smg.constraint_order == 2 and smg.global_order == 6 and smg.verdict == "generic: regular"
    assert smg.exact
    assert all(leg.constraint_wrenches.order == 1 for leg in smg.compound_legs)


def planar_2r(a):
    """Two parallel hinges a apart: a planar 2R chain (one rotation, one translation along y)."""
    return twist_graph(
        "B",
        "E",
        [
            ("B", "arm", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
            ("arm", "E", revolute("R", [0, 0, 1], [a, 0, 0])),
        ],
        dof=2,
    )


def test_wrench_analysis_and_classify_dispatch_symbolic_graphs():
    a = sympy.Symbol("a")
    for result in (wrench_analysis(planar_2r(a)), classify(planar_2r(a))):
        assert isinstance(result, GenericAnalysis)
        assert (result.mobility, result.motion_type) == (2, "1T1R")
    assert isinstance(wrench_analysis(planar_2r(1.0)), WrenchAnalysis)  # numbers: the numeric core
    generic = classify(planar_2r(a))
    assert "no pose verdict" in str(generic) and "1T1R" in str(generic)
    data = generic.to_dict()
    assert data["generic"] is True and data["mobility"] == 2 and data["symbols"] == ["a"]
    # one actuator for two freedoms: the global system is generically of order 5 (4 constraints + 1)
    assert data["global_order"] == 5 and generic.verdict.startswith("generic: actuation")


@pytest.mark.parametrize(
    ("rtol", "error", "message"),
    [
        (5, ScrewkitValueError, r"Expected `rtol` to be a number in \[0, 0\.1\], got 5\."),
        (-1, ScrewkitValueError, r"Expected `rtol` to be a number in \[0, 0\.1\], got -1\."),
        (float("nan"), ScrewkitValueError, r"Expected `rtol` to be a number in \[0, 0\.1\], got nan\."),
        ("x", ScrewkitTypeError, r"Expected `rtol` to be a number"),
    ],
)
def test_error_rtol_is_checked_for_symbolic_graphs_too(rtol, error, message):
    graph = planar_2r(sympy.Symbol("a"))
    for analyse in (wrench_analysis, classify):
        with pytest.raises(error, match=message):
            analyse(graph, rtol=rtol)


def test_generic_rank_is_exact_at_a_random_point():
    x, y = sympy.symbols("x y")
    rows = np.array(
        [[x, y, 0], [x**2, x * y, 0], [0, 0, sympy.sin(x) ** 2 + sympy.cos(x) ** 2 - 1]], dtype=object
    )
    assert YB.generic_rank(rows) == 1  # row 2 = x · row 1; the trigonometric zero is exact
    assert Y.GenericRows.from_exprs(rows, Y.generic_point(rows)).exact


def test_error_loop_closure_graph_is_refused_symbolically():
    a = sympy.Symbol("a")
    # a Wheatstone bridge of hinges does not reduce to series and parallel parts
    edges = [("B", "L1", "R1"), ("B", "L2", "R2"), ("L1", "L2", "R3"), ("L1", "E", "R4"), ("L2", "E", "R5")]
    joints = [
        (u, v, revolute(k, [0, 0, 1], [a * i, i, 0], actuated=i == 0)) for i, (u, v, k) in enumerate(edges)
    ]
    with pytest.raises(ScrewkitTypeError, match="reduces to series and parallel parts"):
        generic_analysis(twist_graph("B", "E", joints, dof=1))


def test_fully_symbolic_h4_family_is_schoenflies(h4):
    # the H4 is a Schoenflies (3T1R) robot (paper 002 §4, paper 004 §1) for every geometry of its
    # kind: with every position and direction a symbol the generic answer is the same
    assert len(h4.symbols) == 61
    assert (h4.mobility, h4.motion_type) == (4, "3T1R")
    assert h4.constraint_order == 2 and h4.global_order == 6 and h4.verdict == "generic: regular"
    assert h4.exact
    assert [leg.constraint_wrenches.order for leg in h4.compound_legs] == [1, 1]
    # a limb's path: A_i (1) + the parallelogram's two S-S rods (4 freedoms: 6 − 2 forces along the
    # rods) + R_I or R_II (1): 6 generically independent twists, no constraint left
    assert [limb.twist_system.order for limb in h4.limbs] == [6, 6, 6, 6]
    assert [limb.constraint_wrenches.order for limb in h4.limbs] == [0, 0, 0, 0]


@pytest.mark.parametrize(
    ("family", "build"), [("delta", delta_3ruu), ("smg", four_limb_smg), ("h4", fully_symbolic_h4)]
)
def test_generic_results_match_the_numeric_core_at_substituted_values(family, build, rng, request):
    generic = request.getfixturevalue(family)
    values = numeric_values(rng)
    numeric = wrench_analysis(build(values))  # the same builder fed numbers
    assert isinstance(numeric, WrenchAnalysis)

    def at(system):
        rows = np.array([[float(sympy.sympify(x).xreplace(values)) for x in row] for row in system.basis])
        return ScrewSystem.span(rows.reshape(-1, 6), length_scale=float(numeric.length_scale))

    assert at(generic.platform_twists).is_equivalent(numeric.platform_twists)
    assert at(generic.constraint_wrenches).is_equivalent(numeric.constraint_wrenches)
    assert int(numeric.global_order) == generic.global_order
    for generic_leg, leg in zip(generic.compound_legs, numeric.compound_legs, strict=True):
        assert generic_leg.joints == leg.joints
        assert at(generic_leg.twist_system).is_equivalent(leg.twist_system)
        assert at(generic_leg.constraint_wrenches).is_equivalent(leg.constraint_wrenches)
    for generic_limb, limb in zip(generic.limbs, numeric.limbs, strict=True):
        assert at(generic_limb.twist_system).is_equivalent(limb.twist_system)
        assert at(generic_limb.constraint_wrenches).is_equivalent(limb.constraint_wrenches)
        assert at(generic_limb.passive_wrenches).is_equivalent(limb.passive_wrenches)


def systems_and_reciprocals(result):
    """(twists, wrenches) pairs that must be reciprocal: platform, compound legs, limbs."""
    yield result.platform_twists, result.constraint_wrenches
    for leg in result.compound_legs:
        yield leg.twist_system, leg.constraint_wrenches
    for limb in result.limbs:
        yield limb.twist_system, limb.constraint_wrenches


def reciprocal_products(twists, wrenches):
    return [sum(w[j] * t[(j + 3) % 6] for j in range(6)) for t in twists.basis for w in wrenches.basis]


@pytest.mark.parametrize("family", ["delta", "smg"])
def test_returned_bases_are_reciprocal_symbolically(family, request):
    result = request.getfixturevalue(family)
    for twists, wrenches in systems_and_reciprocals(result):
        assert all(sympy.expand(p) == 0 for p in reciprocal_products(twists, wrenches))


def test_h4_bases_are_reciprocal_and_of_their_order_at_random_exact_points(h4):
    # an independent check of what the kernels return: at random rational points (drawn here,
    # not the kernels' point) the products vanish exactly and each basis has full rank
    generator = random.Random(7)
    for _ in range(2):
        values = {
            s: sympy.Rational(generator.randrange(-999, 1000), generator.randrange(1, 1000))
            for s in h4.symbols
        }
        for twists, wrenches in systems_and_reciprocals(h4):
            assert all(p.xreplace(values) == 0 for p in reciprocal_products(twists, wrenches))
            for system in (twists, wrenches):
                assert sympy.Matrix(system.basis.tolist()).xreplace(values).rank() == system.order


def test_generic_rows_values_are_the_polynomials_at_the_point():
    x, y, z = sympy.symbols("x y z")
    twists = np.array([[0, 0, 1, y, -x, 0], [1, 0, 0, 0, z, -y], [0, 1, x, z, 0, x * y]], dtype=object)
    point = Y.generic_point(twists)
    rows = Y.GenericRows.from_exprs(twists, point)
    wrenches = YB.reciprocal_within(rows.identity(), rows, point)
    assert len(wrenches) == 3
    for exprs, values in zip(wrenches.exprs(), wrenches.values, strict=True):
        assert [sympy.sympify(e).xreplace(point.values) for e in exprs] == values
    products = [sum(w[j] * t[(j + 3) % 6] for j in range(6)) for w in wrenches.exprs() for t in twists]
    assert all(sympy.expand(p) == 0 for p in products)


def test_nullspace_vectors_annihilate_the_matrix_and_count_its_corank():
    x, y = sympy.symbols("x y")
    first, second = [1, x, y, 0, x * y, 2], [0, y, 1, x, 0, x**2]
    matrix = np.array([first, second, [x * a + b for a, b in zip(first, second, strict=True)]], dtype=object)
    vectors = YB.nullspace(matrix)
    assert vectors.shape == (4, 6)  # 6 − rank 2 (the third row is x·first + second)
    assert all(
        sympy.expand(v) == 0 for v in (sympy.Matrix(matrix.tolist()) * sympy.Matrix(vectors.tolist()).T)
    )
    values = {x: sympy.Rational(3, 7), y: sympy.Rational(-5, 2)}
    assert sympy.Matrix(vectors.tolist()).xreplace(values).rank() == 4


def test_nullspace_of_rank_above_six_goes_to_sympy_and_is_made_polynomial():
    x, y = sympy.symbols("x y")
    # rank 7 (a loop-closure size): the upper triangle below is invertible, the last column free
    matrix = np.array(
        [
            [1 if j == i else (x if j == i + 1 else 0) for j in range(7)] + [y if i == 6 else 0]
            for i in range(7)
        ],
        dtype=object,
    )
    (vector,) = YB.nullspace(matrix)
    assert all(sympy.expand(v) == 0 for v in sympy.Matrix(matrix.tolist()) * sympy.Matrix(vector))
    # by hand: x_7 = −1 gives x_6 = y, x_i = −x·x_{i+1}; sign: the first entry's leading coefficient > 0
    assert list(vector) == [x**6 * y, -(x**5) * y, x**4 * y, -(x**3) * y, x**2 * y, -x * y, y, -1]


def test_an_entry_that_is_not_rational_at_the_point_is_decided_in_60_digits():
    w = sympy.Symbol("w_irrational")
    root = sympy.sqrt(w)
    dependent = np.array([[root, 1, 0], [w, root, 0]], dtype=object)  # row 2 = √w · row 1
    assert YB.generic_rank(dependent) == 1
    assert not Y.GenericRows.from_exprs(dependent, Y.generic_point(dependent)).exact
    assert YB.generic_rank(np.array([[root, 1, 0], [1, root, 0]], dtype=object)) == 2
    polynomial = np.array([[w, 1, 0]], dtype=object)  # the same symbol, no root: exact again
    assert Y.GenericRows.from_exprs(polynomial, Y.generic_point(polynomial)).exact


def test_generic_rows_work_in_60_digits_without_the_callers_context():
    # row 2 = √w · row 1: at 15 digits the elimination leaves ~1e-15 relative round-off, far above
    # FLOAT_RTOL (1e-40), and the rows looked independent; the methods enter 60 digits themselves
    w = sympy.Symbol("w_irrational")
    root = sympy.sqrt(w)
    dependent = np.array([[root, 1, 0], [w, root, 0]], dtype=object)
    rows = Y.GenericRows.from_exprs(dependent, Y.generic_point(dependent))
    assert not rows.exact and mpmath.mp.dps == 15
    assert rows.independent() == [0]
    assert rows.scaled(3).independent() == [0]
    with mpmath.workdps(60):
        tripled = 3 * rows.values[1][1]
    assert rows.scaled(3).values[1][1] == tripled != 3 * rows.values[1][1]  # the product kept 60 digits


def test_null_spaces_and_reciprocal_systems_in_60_digits():
    # a Cramer minor that is identically zero has a round-off value in 60 digits: it must not be
    # taken for the common factor (it was: ZeroDivisionError). Hand: [1, -√a, 0, 0] and e4 span
    # the null space of [[√a, 1, x, 0], [√a (y + z), y + z, 1, 0]] (rows independent: x (y + z) ≠ 1)
    a, x, y, z = sympy.symbols("a x y z")
    root = sympy.sqrt(a)
    matrix = np.array([[root, 1, x, 0], [sympy.expand(root * (y + z)), y + z, 1, 0]], dtype=object)
    kernel = YB.nullspace(matrix)
    assert kernel.shape == (2, 4)
    assert all(sympy.expand(v) == 0 for v in (sympy.Matrix(matrix) * sympy.Matrix(kernel).T))
    assert sympy.Matrix(kernel).rank() == 2
    wrenches = np.array([[0, 0, 0, root, 1, x], [0, 0, 0, sympy.expand(root * (y + z)), y + z, 1]], dtype=object)
    twists = ScrewSystem.span(wrenches).reciprocal()
    assert twists.order == 4
    assert all(sympy.expand(S.reciprocal_product(t, w)) == 0 for t in twists.basis for w in wrenches)


def test_a_line_is_chosen_first_when_its_60_digit_test_carries_round_off():
    # rows derived in 60 digits carry round-off: a line's w·w0 is then ~1e-60 of its size, not 0;
    # the actuation wrench must still be the line (the pitched row comes first in the system)
    from screwkit.core.generic import _actuation_wrench

    a, y, z, q = sympy.symbols("a_root y z q")
    root = sympy.sqrt(a)
    passive = np.array([[1, 0, 0, 1, 0, 0], [root, 1, 0, y + z, -sympy.expand(root * (y + z)), 0]], dtype=object)
    twist = np.array([[0, 0, 1, q, 1, 0]], dtype=object)  # reciprocal to neither row
    point = Y.generic_point(np.vstack([passive, twist]))
    rows, actuated = Y.GenericRows.from_exprs(passive, point), Y.GenericRows.from_exprs(twist, point)
    assert not rows.exact
    with rows.precision():
        line = rows.values[1]
        rows.values[1] = line[:3] + [v * (1 + mpmath.mpf("1e-55")) for v in line[3:]]  # round-off
        assert sum(rows.values[1][j] * rows.values[1][j + 3] for j in range(3)) != 0
        chosen = _actuation_wrench(rows, actuated)
    assert chosen is not None and chosen.exprs().tolist() == [passive[1].tolist()]


def test_error_complex_screw_coordinates_are_refused():
    x = sympy.Symbol("x")
    with pytest.raises(ScrewkitValueError, match="real for real symbols, got I "):
        YB.generic_rank(np.array([[sympy.I * x, 1]], dtype=object))


def moved(graph, rotation, translation, unit):
    """The same twist graph moved by a rigid motion (:func:`screwkit.algebra.screw.transform`), its lengths
    then given in another unit (moments × unit)."""
    joints = []
    for u, v, joint in graph.edges(data="joint"):
        screws = S.transform(joint.screws, rotation, translation)
        screws[:, 3:] = screws[:, 3:] * unit
        joints.append((u, v, dataclasses.replace(joint, screws=screws)))
    return twist_graph(graph.graph["base"], graph.graph["platform"], joints, dof=graph.graph.get("dof"))


@settings(max_examples=5, deadline=None)
@given(
    quaternion=st.tuples(*[st.integers(-3, 3)] * 4).filter(any),
    translation=st.tuples(*[st.integers(-5, 5)] * 3),
    unit=st.sampled_from([sympy.Rational(1, 1000), sympy.Integer(1), sympy.Integer(1000)]),
)
def test_generic_answers_do_not_depend_on_the_frame_or_the_length_unit(delta, quaternion, translation, unit):
    a, b, c, d = (sympy.Integer(q) for q in quaternion)
    norm = a**2 + b**2 + c**2 + d**2  # an exact rotation from a quaternion (Euler–Rodrigues)
    rotation = [
        [(a**2 + b**2 - c**2 - d**2) / norm, 2 * (b * c - a * d) / norm, 2 * (b * d + a * c) / norm],
        [2 * (b * c + a * d) / norm, (a**2 - b**2 + c**2 - d**2) / norm, 2 * (c * d - a * b) / norm],
        [2 * (b * d - a * c) / norm, 2 * (c * d + a * b) / norm, (a**2 - b**2 - c**2 + d**2) / norm],
    ]
    result = generic_analysis(moved(delta_3ruu(), rotation, translation, unit))
    assert (result.mobility, result.motion_type, result.constraint_order, result.global_order) == (
        delta.mobility,
        delta.motion_type,
        delta.constraint_order,
        delta.global_order,
    )
    # the moved family's constraint system (couples) is the original one moved (rank of both
    # together, at a random exact point drawn here)
    expected = S.transform(delta.constraint_wrenches.basis, rotation, translation)
    expected[:, 3:] = expected[:, 3:] * unit
    generator = random.Random(3)
    values = {s: sympy.Rational(generator.randrange(1, 10**6), 997) for s in delta.symbols}
    both = sympy.Matrix([*expected.tolist(), *result.constraint_wrenches.basis.tolist()]).xreplace(values)
    assert both.rank() == delta.constraint_order
