"""More statements (issue 21 item 6): factors the interpreter used to call "the bracket expression …
vanishes", each tested on a configuration built by hand: the statement's geometry makes the factor
vanish, a perturbation does not. Brackets are evaluated here with numpy determinants of 4×4 rows
(gca.md §1: [pqrs] = det of the rows p, q, r, s), independently of screwkit's evaluator."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import screwkit as sk
from screwkit.gca import BracketPolynomial
from screwkit.gca.conditions import condition

from ..strategies import rotations, unit_factors


def bracket_sum(text, points):
    """A sum of single brackets with ±1 coefficients, e.g. '[abce] - [abcf]', with numpy."""
    total, sign = 0.0, 1.0
    for token in text.replace("[", " [").split():
        if token in "+-":
            sign = -1.0 if token == "-" else 1.0
            continue
        total += sign * np.linalg.det(np.array([points[x] for x in token.strip("[]")]))
    return total


def finite(v):
    return np.r_[v, 1.0]


def assert_zero_then_not(c, text, points, moved, scale=1.0):
    """The factor (numpy) and the condition vanish on the built geometry, not once perturbed, where the
    vector form times the proved constant is the bracket sum."""
    assert abs(bracket_sum(text, points)) < 1e-12 * scale and abs(c.evaluate(points)) < 1e-12 * scale
    assert abs(bracket_sum(text, moved)) > 1e-3 * scale
    assert float(c.constant) * c.evaluate(moved) == pytest.approx(bracket_sum(text, moved), rel=1e-10)


def test_three_leg_directions_parallel_to_one_plane():
    """The 3-UPU's [abce] − [abcf] − [abde] + [abdf] = [a b (c − d) (e − f)] (multilinearity): with
    a, b, …, f the legs' end points, zero iff the leg directions b − a, d − c, f − e are parallel to
    one plane (gca.md §5.1: [p q u v] = −(q − p)·(u × v))."""
    text = "[abce] - [abcf] - [abde] + [abdf]"
    c = condition(BracketPolynomial.parse(text), finite="abcdef", infinite="")
    assert c.statement == "the directions of lines ab, cd and ef are parallel to one plane"
    rng = np.random.default_rng(7)
    base = {x: rng.normal(size=3) for x in "ace"}
    u, v = rng.normal(size=3), rng.normal(size=3)  # the plane the three legs are parallel to
    legs = {"b": 1.3 * u - 0.4 * v, "d": -0.7 * u + 0.9 * v, "f": 0.2 * u + 1.1 * v}
    points = {x: finite(base[x]) for x in "ace"} | {
        top: finite(base[bottom] + legs[top]) for bottom, top in zip("ace", "bdf", strict=True)
    }
    scale = np.prod([np.linalg.norm(legs[x]) for x in "bdf"])
    moved = points | {"f": points["f"] + np.r_[0.05 * np.cross(u, v), 0.0]}
    assert_zero_then_not(c, text, points, moved, scale)


def test_a_line_parallel_to_a_plane_through_three_points():
    """[acef] − [bcef] = [(a − b) c e f]: zero iff line ab is parallel to plane cef."""
    text = "[acef] - [bcef]"
    c = condition(BracketPolynomial.parse(text), finite="abcef", infinite="")
    assert c.statement == "the direction of line ab is parallel to plane cef"
    rng = np.random.default_rng(8)
    plane = {x: rng.normal(size=3) for x in "cef"}
    a = rng.normal(size=3)
    points = {x: finite(p) for x, p in plane.items()} | {
        "a": finite(a),
        "b": finite(a + 0.8 * (plane["e"] - plane["c"]) - 0.3 * (plane["f"] - plane["c"])),
    }
    normal = np.cross(plane["e"] - plane["c"], plane["f"] - plane["c"])
    assert_zero_then_not(c, text, points, points | {"b": points["b"] + np.r_[0.1 * normal, 0.0]})


def test_a_leg_direction_and_two_directions_parallel_to_one_plane():
    """[gcuv] − [gduv] = [g (c − d) u v]: zero iff line cd is parallel to the plane of u and v."""
    text = "[gcuv] - [gduv]"
    c = condition(BracketPolynomial.parse(text), finite="gcd", infinite="uv")
    assert c.statement == "the direction of line cd, the direction u and the direction v are parallel to one plane"
    rng = np.random.default_rng(9)
    u, v, g, cpoint = (rng.normal(size=3) for _ in range(4))
    points = {"g": finite(g), "c": finite(cpoint), "d": finite(cpoint + 0.6 * u - 1.2 * v),
              "u": np.r_[u, 0.0], "v": np.r_[v, 0.0]}
    assert_zero_then_not(c, text, points, points | {"d": points["d"] + np.r_[0.1 * np.cross(u, v), 0.0]})


@pytest.mark.parametrize(
    "text",
    [
        "[abce] - [abcf] + [abde] + [abdf]",  # signs not those of a product of differences
        "[abce] - [abcf] - [abde]",  # not 2^k terms
        "[abcd][efgh] - [abce][dfgh]",  # products of brackets
    ],
)
def test_other_sums_keep_the_generic_statement(text):
    c = condition(BracketPolynomial.parse(text), finite="abcdefgh", infinite="")
    assert c.statement.startswith("the bracket expression")


def test_schoenflies_actuation_condition_given_the_couples():
    """The Ragnar's actuation factor (four actuation lines, two couples ij, kj normal to the rotation
    axis j) is proportional to the 4×4 determinant of the actuation lines (s; m) on the translations
    and the rotation about j, rows (s_x, s_y, s_z, j·m) (the reciprocal product ω·m + v·s with
    twists (0; e_x), (0; e_y), (0; e_z), (j; 0)), computed here: it vanishes exactly where a
    translation with a rotation about an axis parallel to j does no work on the four lines."""
    diagram, sampler = sk.load_mechanism("ragnar").wrench_diagram()
    result = sk.superbracket_analysis(diagram, sampler)
    (actuation,) = (c for c in result.conditions if c.label == "actuation")
    assert actuation.statement.startswith(
        "a translation combined with a rotation about an axis parallel to j does no work on any of the "
        "actuation lines ab, cd, ef, gh"
    )
    rng = np.random.default_rng(4)
    ratios = []
    for _ in range(5):
        points = sampler(rng)
        j = points["j"][:3] / np.linalg.norm(points["j"][:3])
        rows = []
        for (p, q), role in zip(diagram.lines, diagram.roles, strict=True):
            if role == "actuation":
                a, b = points[p], points[q]
                s, m = a[3] * b[:3] - b[3] * a[:3], np.cross(a[:3], b[:3])
                rows.append([*s, j @ m])
        ratios.append(actuation.evaluate(points) / np.linalg.det(np.array(rows)))
    assert np.allclose(ratios, ratios[0], rtol=1e-8, atol=0) and abs(ratios[0]) > 1e-6


def plane_through(p, u, v):
    """Plane coordinates (n, −n·p) of the plane through finite p spanned by directions u, v
    (π·x = 0 for the points x of the plane), by hand."""
    n = np.cross(u, v)
    return np.r_[n, -n @ p]


def test_leg_planes_and_platform_plane_through_one_point_at_a_singular_3prs_pose():
    """A 3-PRS (tests/mechanisms_extra.py) at a tilt where the 6×6 determinant of its lines vanishes,
    found by bisection on that determinant alone: the report names the vanishing factor with the
    four-planes statement (each leg's plane holds its rod force and its constraint force through the
    sphere centre, gca.md §5.2), and the four planes, computed here from the geometry, share a point
    there (det of their coordinates ≈ 0) and not 0.05 rad away. The diagram's points at infinity
    (rod directions, R axes) once kept the pattern from being recognised: it read "the six lines are
    linearly dependent"."""
    from tests import mechanisms as M
    from tests import mechanisms_extra as X

    tilt = X.singular_three_prs_tilt()
    determinants = []
    for angle in (tilt, tilt + 0.05):
        graph, _ = X.three_prs(M.rotation_about(X.PRS_TILT_AXIS, angle), X.PRS_POSITION, drop=X.PRS_DROP)
        result = sk.analyze(graph).superbracket
        (c,) = result.conditions
        assert c.statement.startswith(
            "planes abg, ace, cdh and efi pass through one point (possibly at infinity); abg is the plane "
            "of lines ab and ag, cdh is the plane of lines cd and ch, efi is the plane of lines ef and ei"
        )
        assert [tuple(line) for line in result.diagram.lines] == [tuple(x) for x in ["ab", "cd", "ef", "ag", "ch", "ei"]]
        p = {x: v[:3] / (v[3] or 1.0) for x, v in result.diagram.coordinates.items()}
        planes = [plane_through(p[o], p[u], p[v]) for o, u, v in ["abg", "cdh", "efi"]]
        planes.append(plane_through(p["a"], p["c"] - p["a"], p["e"] - p["a"]))
        unit_planes = [q / np.linalg.norm(q[:3]) for q in planes]
        determinants.append(np.linalg.det(np.array(unit_planes)))
        assert result.vanishing == ((angle == tilt),)
    assert abs(determinants[0]) < 1e-12 and abs(determinants[1]) > 1e-4


@pytest.mark.parametrize("seed", [0, 1])
def test_four_planes_with_points_at_infinity_vanish_where_built_concurrent(seed):
    """The 3-RPS/3-PRS diagram [ab, cd, ef, ag, ch, ei] (centres a, c, e; directions b, d, f, g, h, i)
    built with its leg planes a + ⟨b, g⟩, … and platform plane ace through one point X: the factor
    and the 6×6 determinant of the lines (numpy) vanish; turning one R axis out of its plane does not."""
    from screwkit.gca import simplify_superbracket
    from screwkit.gca.conditions import conditions

    lines = ["ab", "cd", "ef", "ag", "ch", "ei"]
    rng = np.random.default_rng(seed)

    def sampler(r):
        return {x: np.r_[r.normal(size=3), 1.0 if x in "ace" else 0.0] for x in "abcdefghi"}

    result = simplify_superbracket(lines, sampler, finite="ace", infinite="bdfghi")
    (c,) = conditions(result.factored, finite="ace", infinite="bdfghi", lines=lines)
    centres = {x: rng.normal(size=3) for x in "ace"}
    common = centres["a"] + 0.7 * (centres["c"] - centres["a"]) - 0.4 * (centres["e"] - centres["a"])
    points = {x: finite(v) for x, v in centres.items()}
    for centre, leg, axis in ["abg", "cdh", "efi"]:
        direction = rng.normal(size=3)
        points[leg] = np.r_[direction, 0.0]
        points[axis] = np.r_[(common - centres[centre]) + 0.8 * direction, 0.0]

    def six_by_six(pts):
        rows = [np.r_[pts[q][:3] * pts[p][3] - pts[p][:3] * pts[q][3], np.cross(pts[p][:3], pts[q][:3])] for p, q in lines]
        return np.linalg.det(np.array(rows))

    moved = points | {"i": points["i"] + np.r_[0.3 * np.cross(points["f"][:3], points["i"][:3]), 0.0]}
    scale = abs(c.evaluate(moved))
    assert scale > 1e-6 and abs(six_by_six(moved)) > 1e-6
    assert abs(c.evaluate(points)) < 1e-12 * scale and abs(six_by_six(points)) < 1e-12 * abs(six_by_six(moved))


def test_peppermill_factor_is_the_distal_links_horizontal_as_paper_000_eq_48():
    """The Peppermill's actuation factor F = [abfd][eghi] − [abfh][ecdi] does not split in the bracket
    ring, but on the mechanism lines cd, gh are reciprocal to the plate's helical joints (axis ei,
    pitches p₁, p₂ per turn): by hand, [eghi] = −p₂ (i·h)/2π and [ecdi] = −p₁ (i·d)/2π with
    [abfd] = −(b × f)·d, b = x, f = y the elbow axes, i = z. So F = v₁z v₂z (p₂ − p₁)/2π with
    v₁ = d, v₂ = h the distal links: paper 000's det A, Eq. (48), whose zeros (a distal link
    horizontal) the statement names. Checked with numpy determinants on fresh configurations, and at
    the pose where the paper's det A vanishes (found by bisection on Eq. 48, tests/paper_000.py)."""
    from tests import paper_000 as paper

    m = sk.load_mechanism("peppermill")
    diagram, sampler = m.wrench_diagram()
    result = sk.superbracket_analysis(diagram, sampler)
    (actuation,) = (c for c in result.conditions if c.label == "actuation")
    assert str(actuation.factor) == "[abfd][eghi] - [abfh][ecdi]"
    assert actuation.statement.endswith(
        "on this mechanism it is a constant multiple of [abfd][abfh] (the same ratio on all 12 sampled "
        "configurations: a relation of the design that is no incidence of the diagram, checked numerically), "
        "i.e. of ((b × f)·d) · ((b × f)·h), so it vanishes exactly where b, f and d are collinear in the plane "
        "at infinity (the directions b, f, d are parallel to one plane) or where b, f and h are collinear in "
        "the plane at infinity (the directions b, f, h are parallel to one plane)"
    )
    p1, p2 = m.parameters.p1, m.parameters.p2
    rng = np.random.default_rng(11)
    for _ in range(5):
        points = sampler(rng)
        np.testing.assert_allclose([points[x] for x in "bfi"], [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]], atol=1e-12)
        v1, v2 = points["d"][:3] / np.linalg.norm(points["d"][:3]), points["h"][:3] / np.linalg.norm(points["h"][:3])
        moved = points | {"d": np.r_[v1, 0.0], "h": np.r_[v2, 0.0]}
        det_a = v1[2] * v2[2] * (p2 - p1) / (2 * np.pi)  # paper 000, Eq. (48)
        b = {x: np.linalg.det(np.array([moved[y] for y in x])) for x in ["abfd", "eghi", "abfh", "ecdi"]}
        # the hand derivation's steps, then the factor
        assert b["eghi"] == pytest.approx(-p2 * v2[2] / (2 * np.pi), rel=1e-9)
        assert b["ecdi"] == pytest.approx(-p1 * v1[2] / (2 * np.pi), rel=1e-9)
        assert b["abfd"] == pytest.approx(-v1[2], rel=1e-9) and b["abfh"] == pytest.approx(-v2[2], rel=1e-9)
        assert b["abfd"] * b["eghi"] - b["abfh"] * b["ecdi"] == pytest.approx(det_a, rel=1e-9)

    pose = paper.locate_direct_singularity(m.parameters, [0.0, 150.0, -150.0, 0.0], [0.0, 300.0, -150.0, 0.0])
    at_pose = sk.analyze("peppermill", pose).superbracket
    assert at_pose.vanishing == (False, True) and at_pose.constant == (True, False)
    assert abs(at_pose.values[1]) < 1e-12 * abs(result.values[1])


def test_general_gough_stewart_at_a_singular_pose_names_its_factor_and_the_complex():
    """The general 6-6 platform turned about z to where the 6×6 determinant of its leg lines vanishes
    (bisection on that determinant, tests/mechanisms_extra.py): its one factor, the superbracket
    itself, vanishes there (and not 0.05 rad away) with the linear-complex statement, and the lines'
    Grassmann class is a linear complex read at the pose (rank 5: classes 5a or 5b)."""
    from tests import mechanisms as M
    from tests import mechanisms_extra as X

    angle = X.singular_gough_stewart_angle()
    for turn, singular in ((angle, True), (angle + 0.05, False)):
        report = sk.analyze(M.gough_stewart(*M.gough_stewart_points(M.rotation_z(turn))))
        (c,) = report.superbracket.conditions
        assert c.statement.startswith("the six lines ab, cd, ef, gh, ij and kl are linearly dependent")
        assert report.superbracket.vanishing == (singular,)
        grassmann, _ = report.grassmann()
        assert (grassmann is not None and grassmann.name in ("5a", "5b")) == singular


def test_the_report_says_which_distal_link_is_horizontal():
    """At the paper's second-kind pose of limb 1 (y moves limb 1 only; bisection on Eq. 48), the
    report's line for the split factor says [abfd] (d: limb 1's distal link) vanishes and [abfh] does
    not; the JSON has the same; at a regular pose nothing vanishes. The distal link directions are
    read from the diagram here: d horizontal (|d_z| < 1e-9), h not."""
    import json

    from tests import paper_000 as paper

    m = sk.load_mechanism("peppermill")
    pose = paper.locate_direct_singularity(m.parameters, [0.0, 150.0, -150.0, 0.0], [0.0, 300.0, -150.0, 0.0])
    report = sk.analyze("peppermill", pose)
    result = report.superbracket
    d, h = (result.diagram.coordinates[x][:3] for x in "dh")
    assert abs(d[2]) < 1e-9 * np.linalg.norm(d) and abs(h[2]) > 0.1 * np.linalg.norm(h)
    line = result.split_at_pose[1]
    assert line.startswith("here [abfd] = ") and "(vanishes), [abfh] = " in line and line.count("(vanishes)") == 1
    assert "    " + line in str(report).splitlines()
    printed = json.loads(json.dumps(report.to_dict()))["superbracket"]["conditions"]
    assert [c["split_on_mechanism"] for c in printed] == [[], ["[abfd]", "[abfh]"]]
    assert [c["split_at_pose"] for c in printed] == ["", line]
    regular = sk.analyze("peppermill").superbracket.split_at_pose[1]
    assert regular.startswith("here [abfd] = ") and "vanishes" not in regular


def _expanded_value(factor, points):
    """A factor's expansion on points, each bracket a numpy determinant of 4×4 rows (the monomials
    read from the printed expansion: ±coefficient followed by brackets)."""
    from screwkit.gca.condition_patterns import bracket_polynomial

    total = 0.0
    for monomial in bracket_polynomial(factor).terms:
        value = float(monomial.coefficient)
        for bracket in monomial.brackets:
            value *= np.linalg.det(np.array([points[x] for x in bracket.labels]))
        total += value
    return total


FACTORS = {  # factor text, finite, infinite, lines
    "3-RPS/3-PRS four planes": ("[abcd][aghe][cfei] - [abhd][agce][cfei] + [abcg][dche][afei] - [abch][dage][cfei]",
                                "ace", "bdfghi", ["ab", "cd", "ef", "ag", "ch", "ei"]),
    "Peppermill actuation": ("[abfd][eghi] - [abfh][ecdi]", "aceg", "bdfhi", None),
    "general 6-6": (None, "abcdefghijkl", "", ["ab", "cd", "ef", "gh", "ij", "kl"]),
}
STATEMENTS = {"3-RPS/3-PRS four planes": "planes abg, ace, cdh and efi pass through one point",
              "Peppermill actuation": "the bracket expression",  # generic here: no mechanism, no couples
              "general 6-6": "the six lines ab, cd, ef, gh, ij and kl are linearly dependent"}


@pytest.mark.parametrize("name", list(FACTORS))
@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_vector_form_times_constant_is_the_factor(name, seed):
    """The statement's vector form times its proved constant equals the factor's bracket expansion
    (numpy determinants) on random points of the declared kinds."""
    from screwkit.gca import superbracket_expansion

    text, finite_labels, infinite_labels, lines = FACTORS[name]
    factor = superbracket_expansion(lines) if text is None else BracketPolynomial.parse(text)
    c = _conditions_cache(name, factor, finite_labels, infinite_labels, lines)
    assert c.statement.startswith(STATEMENTS[name])
    rng = np.random.default_rng(seed)
    points = {x: np.r_[rng.normal(size=3), 1.0] for x in finite_labels}
    points |= {x: np.r_[rng.normal(size=3), 0.0] for x in infinite_labels}
    expected = _expanded_value(factor, points)
    assert float(c.constant) * c.evaluate(points) == pytest.approx(expected, rel=1e-8, abs=1e-10)


_CACHE: dict = {}


def _conditions_cache(name, factor, finite_labels, infinite_labels, lines):
    if name not in _CACHE:
        _CACHE[name] = condition(factor, finite=finite_labels, infinite=infinite_labels, lines=lines)
    return _CACHE[name]


@settings(max_examples=3, deadline=None)
@given(rotation=rotations(), translation=st.lists(st.floats(-2, 2), min_size=3, max_size=3), factor=unit_factors)
def test_the_3prs_statement_is_frame_and_unit_free(rotation, translation, factor):
    """The same 3-PRS moved rigidly and described in another length unit reads the same statement."""
    from tests import mechanisms as M
    from tests import mechanisms_extra as X

    graph, _ = X.three_prs(M.rotation_about([1, 0.3, 0], 0.2), [0.02, 0.03, 1.0])
    moved = M.moved(graph, rotation, np.array(translation), factor)
    (c,) = sk.analyze(moved).superbracket.conditions
    assert c.statement.startswith("planes abg, ace, cdh and efi pass through one point (possibly at infinity)")
