"""Grassmann-geometry classes (Merlet 1989; Merlet, Parallel Robots, 2006, §6.2) on line sets built
from each class's definition, and on Gough–Stewart singular poses.

Every expected class comes from the construction (which variety the lines were drawn from), every
witness is checked by incidence computed here (Klein products, point-on-line, line-in-plane), not
by the code under test.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from screwkit.exceptions import ScrewkitValueError
from screwkit.gca.grassmann import CLASS_DESCRIPTIONS, grassmann_class

from ..strategies import rigid_motions

RNG = np.random.default_rng(20260)


def line(p, d):
    """The line through p with direction d, (d; p × d)."""
    p, d = np.asarray(p, float), np.asarray(d, float)
    return np.r_[d, np.cross(p, d)]


def joining(p, q):
    return line(p, np.asarray(q, float) - np.asarray(p, float))


def klein(x, y):
    """The reciprocal product: zero exactly when two lines meet (or are parallel)."""
    return float(x[:3] @ y[3:] + x[3:] @ y[:3])


def unit(v):
    return np.asarray(v, float) / np.linalg.norm(v)


def meets(x, y, atol=1e-9):
    return abs(klein(x, y)) <= atol * np.linalg.norm(x) * np.linalg.norm(y)


def on_line(point, ell, atol=1e-9):
    """A projective point (x, w) on the line (s; m): x × s = w m and m·x = 0."""
    x, w = point[:3], point[3]
    s, m = ell[:3], ell[3:]
    return np.allclose(np.cross(x, s), w * m, atol=atol) and abs(m @ x) < atol


def in_plane(ell, plane, atol=1e-9):
    """The line (s; m) in the plane n·x + d = 0: n·s = 0 and m × n + d s = 0."""
    n, d = plane[:3], plane[3]
    s, m = ell[:3], ell[3:]
    return abs(n @ s) < atol and np.allclose(np.cross(m, n) + d * s, 0, atol=atol)


def same_line(x, y, atol=1e-8):
    return np.linalg.matrix_rank(np.stack([unit(x), unit(y)]), tol=atol) == 1


def random_points(k):
    return RNG.normal(size=(k, 3))


def through(point, k):
    return np.array([line(point, d) for d in RNG.normal(size=(k, 3))])


def in_plane_lines(origin, u, v, k):
    """k random lines of the plane through origin spanned by u, v."""
    a, b = RNG.normal(size=(k, 2)), RNG.normal(size=(k, 2))
    return np.array(
        [joining(origin + x[0] * u + x[1] * v, origin + y[0] * u + y[1] * v) for x, y in zip(a, b, strict=False)]
    )


def test_rank_one_and_two():
    ell = line([1, 2, 3], [0, 1, 1])
    found = grassmann_class([ell, 2 * ell, -ell])
    assert found.name == "1" and same_line(found.witness["line"], ell)
    skew = [line([0, 0, 0], [1, 0, 0]), line([0, 0, 1], [0, 1, 0])]
    assert grassmann_class(skew).name == "2"
    pencil = [line([1, 1, 0], d) for d in ([1, 0, 0], [0, 1, 0], [1, 1, 0], [1, -2, 0])]  # flat pencil
    assert grassmann_class(pencil).rank == 2


def test_star_finite_and_at_infinity():
    centre = np.array([0.3, -1.0, 2.0])
    star = through(centre, 5)
    found = grassmann_class(star)
    assert found.name == "3a"
    assert all(on_line(found.witness["point"], x) for x in star)
    assert np.allclose(found.witness["point"], np.r_[centre, 1.0])
    direction = unit([1.0, 2.0, -1.0])  # parallel lines: a star about a point at infinity
    parallel = np.array([line(p, direction) for p in random_points(4)])
    found = grassmann_class(parallel)
    assert found.name == "3a" and found.witness["point"][3] == 0
    assert all(on_line(found.witness["point"], x) for x in parallel)
    assert np.allclose(np.abs(found.witness["point"][:3]), np.abs(direction))


def test_planar_field_finite_and_at_infinity():
    origin, u, v = np.array([0.0, 0, 1]), np.array([1.0, 0, 0]), np.array([0.0, 1, 1])
    lines = in_plane_lines(origin, u, v, 5)
    found = grassmann_class(lines)
    assert found.name == "3b"
    assert all(in_plane(x, found.witness["plane"]) for x in lines)
    assert np.allclose(
        np.abs(found.witness["plane"]), np.abs(np.r_[unit(np.cross(u, v)), -unit(np.cross(u, v)) @ origin])
    )
    couples = np.c_[np.zeros((4, 3)), RNG.normal(size=(4, 3))]  # lines at infinity: the plane at infinity
    found = grassmann_class(couples)
    assert found.name == "3b" and found.witness["plane"].tolist() == [0, 0, 0, 1]


def test_two_flat_pencils_sharing_a_line():
    p1, p2 = np.array([0.0, 0, 0]), np.array([2.0, 0, 0])  # the common line is the x axis
    lines = [
        joining(p1, p2),
        line(p1, [1, 1, 0]),
        line(p1, [3, -1, 0]),
        line(p2, [0, 1, 1]),
        line(p2, [1, 2, 2]),
    ]
    found = grassmann_class(lines)
    assert found.name == "3c"
    assert same_line(found.witness["line"], joining(p1, p2))
    points = sorted(found.witness["points"].tolist())
    assert np.allclose(points, [[0, 0, 0, 1], [2, 0, 0, 1]])
    normals = {tuple(np.round(np.abs(unit(p[:3])), 9)) for p in found.witness["planes"]}
    assert normals == {(0, 0, 1), (0, round(2**-0.5, 9), round(2**-0.5, 9))}


def test_regulus_and_its_transversals():
    t = RNG.uniform(0, 2 * np.pi, 5)  # one ruling of x² + y² − z² = 1
    feet = np.c_[np.cos(t), np.sin(t), 0 * t]
    lines = np.array([line(p, [-np.sin(a), np.cos(a), 1]) for p, a in zip(feet, t, strict=False)])
    found = grassmann_class(lines)
    assert found.name == "3d"
    for transversal in found.witness["transversals"]:
        assert abs(klein(transversal, transversal)) < 1e-9  # a line
        assert all(meets(transversal, x) for x in lines)
        s, m = transversal[:3], transversal[3:]
        foot = np.cross(s, m) / (s @ s)
        assert abs(foot[0] ** 2 + foot[1] ** 2 - foot[2] ** 2 - 1) < 1e-9  # on the hyperboloid


def test_hyperbolic_congruence_meets_two_skew_lines():
    d1, d2 = line([0, 0, 0], [1, 0, 0]), line([0, 0, 1], [0, 1, 1])
    a, b = RNG.normal(size=5), RNG.normal(size=5)
    lines = [joining([x, 0, 0], [0, y, 1 + y]) for x, y in zip(a, b, strict=False)]
    found = grassmann_class(lines)
    assert found.name == "4a"
    got = found.witness["lines"]
    assert (same_line(got[0], d1) and same_line(got[1], d2)) or (
        same_line(got[0], d2) and same_line(got[1], d1)
    )


def test_degenerate_congruence_plane_or_point_of_it():
    centre = np.array([1.0, 1.0, 0.0])  # in the plane z = 0
    lines = np.r_[
        through(centre, 2), in_plane_lines(np.zeros(3), np.array([1.0, 0, 0]), np.array([0.0, 1, 0]), 3)
    ]
    found = grassmann_class(lines)
    assert found.name == "4b"
    assert np.allclose(found.witness["point"], [1, 1, 0, 1])
    assert np.allclose(np.abs(found.witness["plane"]), [0, 0, 1, 0])


def test_parabolic_congruence_one_directrix():
    # lines meeting the x axis d and reciprocal to the screw c (z axis, pitch p), which contains d
    p = 0.7
    lines = []
    for t, sx, sy in RNG.normal(size=(5, 3)):
        lines.append(line([t, 0, 0], [sx, sy, -t * sy / p]))
    assert all(abs(x[:3] @ [0, 0, p] + x[3:] @ [0, 0, 1]) < 1e-12 for x in lines)
    found = grassmann_class(lines)
    assert found.name == "4c"
    assert same_line(found.witness["line"], line([0, 0, 0], [1, 0, 0]))


@pytest.mark.parametrize(("p", "q", "name"), [(0.5, 0.8, "4d"), (0.5, -0.8, "4a")])
def test_lines_of_two_complexes(p, q, name):
    """The lines reciprocal to the z-axis screw of pitch p and the x-axis screw of pitch q: the
    Klein form on their span is diag(2p, 2q), definite (no real directrix, elliptic) when p q > 0
    and indefinite (two real directrices, hyperbolic) when p q < 0."""
    lines = []
    for r in random_points(6):
        s = np.cross([-r[1], r[0], p], [q, -r[2], r[1]])
        lines.append(line(r, s))
    found = grassmann_class(lines)
    assert found.name == name
    c1, c2 = np.array([0, 0, 1, 0, 0, p]), np.array([1, 0, 0, q, 0, 0])
    if name == "4a":
        for directrix in found.witness["lines"]:
            assert all(meets(directrix, x) for x in lines)
            assert np.linalg.matrix_rank(np.stack([c1, c2, directrix]), tol=1e-9) == 2
    else:
        assert np.linalg.matrix_rank(np.r_[found.witness["complexes"], [c1, c2]], tol=1e-9) == 2


def test_complexes_general_and_singular():
    lines = np.array([line(p, d) for p, d in zip(random_points(5), RNG.normal(size=(5, 3)), strict=False)])
    found = grassmann_class(lines)
    assert found.name == "5a"
    axis, pitch = found.witness["axis"], found.witness["pitch"]
    screw = np.r_[axis[:3], axis[3:] + pitch * axis[:3]]
    assert all(abs(klein(screw, x)) < 1e-9 for x in lines)
    ell = line([1, 0, 2], [0, 1, 1])  # lines meeting ell
    lines = [
        line(np.array([1, 0, 2]) + t * np.array([0, 1, 1]), d)
        for t, d in zip(RNG.normal(size=5), RNG.normal(size=(5, 3)), strict=False)
    ]
    found = grassmann_class(lines)
    assert found.name == "5b" and same_line(found.witness["line"], ell)
    flat = [
        line(p, [d[0], d[1], 0]) for p, d in zip(random_points(5), RNG.normal(size=(5, 3)), strict=False)
    ]  # directions ⟂ z
    found = grassmann_class(flat)
    assert found.name == "5b"
    assert np.allclose(np.abs(found.witness["line"]), [0, 0, 0, 0, 0, 1])  # the line at infinity of z = const


def test_six_independent_lines():
    lines = np.array([line(p, d) for p, d in zip(random_points(6), RNG.normal(size=(6, 3)), strict=False)])
    found = grassmann_class(lines)
    assert found.name == "6" and not found.is_singular and dict(found.witness) == {}


def gough_63(psi, height=1.0):
    """A 6-3 Gough–Stewart platform: base points on the unit circle in pairs about 120° j, platform
    vertices A_j on a circle of radius 0.5, each joined to one base point of two adjacent pairs;
    the platform turned by psi about z at the given height."""
    c, s = np.cos(psi), np.sin(psi)
    turn = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    angles = np.radians(60 + 120 * np.arange(3))
    flat = np.c_[0.5 * np.cos(angles), 0.5 * np.sin(angles), 0 * angles]
    vertices = flat @ turn.T + np.array([0.0, 0.0, height])
    bases = []
    for j in range(3):
        for a in (120 * j + 20, 120 * (j + 1) - 20):
            bases.append([np.cos(np.radians(a)), np.sin(np.radians(a)), 0.0])
    return vertices, np.array(bases)


def reciprocal_pitch(lines):
    """The pitch of the screw reciprocal to five independent lines (an SVD of the lines with the
    halves swapped: r ∘ x = r_s·x_m + r_m·x_s)."""
    swapped = np.c_[lines[:, 3:], lines[:, :3]]
    r = np.linalg.svd(swapped)[2][-1]
    return r[:3] @ r[3:] / (r[:3] @ r[:3])


def gough_lines(vertices, bases):
    return np.array([joining(bases[k], vertices[k // 2]) for k in range(6)])


def test_gough_63_turned_a_quarter_turn_is_a_general_complex():
    """Merlet (1989): the 6-3 platform turned ±90° about z is singular at every height. The pose is
    invariant under the 120° turn about z, so the one complex of the six lines is too: its axis
    is the z axis; its pitch is that of the reciprocal screw found here by an SVD."""
    for psi in (np.pi / 2, -np.pi / 2):
        lines = gough_lines(*gough_63(psi))
        assert abs(np.linalg.det(lines)) < 1e-12
        found = grassmann_class(lines)
        assert found.name == "5a"
        assert same_line(found.witness["axis"], [0, 0, 1, 0, 0, 0])
        assert found.witness["pitch"] == pytest.approx(reciprocal_pitch(lines))
    assert grassmann_class(gough_lines(*gough_63(np.radians(80)))).name == "6"


def test_gough_63_platform_plane_through_two_base_points():
    """When the platform plane contains the base points of the two legs at A₂ (so both legs lie in
    it), every leg meets the edge A₀A₁: the singular complex of that line (5b)."""
    _, bases = gough_63(0.0)
    b4, b5 = bases[4], bases[5]  # the legs at vertex 2
    normal = unit(np.cross(b5 - b4, [0.3, 0.2, 1.0]))
    u = unit(b5 - b4)
    v = np.cross(normal, u)
    centre = (b4 + b5) / 2 + 0.9 * v
    angles = np.radians([90, 210, 330])
    vertices = centre + 0.5 * (np.outer(np.cos(angles), u) + np.outer(np.sin(angles), v))
    lines = gough_lines(vertices, bases)
    found = grassmann_class(lines)
    assert found.name == "5b"
    assert same_line(found.witness["line"], joining(vertices[0], vertices[1]))


@settings(max_examples=25, deadline=None)
@given(motion=rigid_motions(), unit_factor=st.sampled_from([1e-3, 1.0, 1e3]))
def test_frame_and_unit_invariance(motion, unit_factor):
    rotation, translation = motion
    cases = {
        "3a": through(np.array([0.2, 0.1, -0.3]), 4),
        "3d": np.array(
            [line([np.cos(a), np.sin(a), 0], [-np.sin(a), np.cos(a), 1]) for a in (0.1, 1.3, 2.2, 4.0)]
        ),
        "5b": np.array(
            [
                line([0, 0, t], d)
                for t, d in zip((0.1, -0.4, 0.9, 1.5, -1.1), np.random.default_rng(3).normal(size=(5, 3)), strict=False)
            ]
        ),
        "5a": gough_lines(*gough_63(np.pi / 2)),
    }
    for name, lines in cases.items():
        s = lines[:, :3] @ rotation.T
        feet = np.cross(lines[:, :3], lines[:, 3:]) / np.sum(lines[:, :3] ** 2, axis=1)[:, None]
        moved = (feet @ rotation.T + translation) * unit_factor
        found = grassmann_class(np.c_[s, np.cross(moved, s)])
        assert found.name == name
        if name == "3a":
            centre = (rotation @ [0.2, 0.1, -0.3] + translation) * unit_factor
            assert np.allclose(found.witness["point"][:3], centre, atol=1e-6 * max(1.0, np.abs(centre).max()))
        if name == "5a":
            assert found.witness["pitch"] == pytest.approx(reciprocal_pitch(lines) * unit_factor, rel=1e-6)


@pytest.mark.parametrize(
    ("value", "message"),
    [
        ([[0, 0, 1, 0, 0, 1]], "to be lines"),
        ([[0, 0, 0, 0, 0, 0]], "non-zero rows"),
        (np.zeros((0, 6)), "n >= 1"),
        ([[0, 0, 1, 0, 0]], "shape"),
        ([[0, 0, np.nan, 0, 0, 0]], "finite"),
    ],
)
def test_bad_lines(value, message):
    with pytest.raises(ScrewkitValueError, match=message):
        grassmann_class(value)


def test_report_forms():
    found = grassmann_class(through(np.array([1.0, 2.0, 3.0]), 3))
    assert set(found.to_dict()) == {"name", "rank", "description", "witness"}
    assert found.to_dict()["witness"]["point"] == pytest.approx([1, 2, 3, 1])
    assert "3a" in str(found) and "(1, 2, 3, 1)" in str(found)
    assert set(CLASS_DESCRIPTIONS) == {
        "1",
        "2",
        "3a",
        "3b",
        "3c",
        "3d",
        "4a",
        "4b",
        "4c",
        "4d",
        "5a",
        "5b",
        "6",
    }


def test_in_the_report_at_a_singular_pose():
    """The 6-3 platform (6-UPS legs) at the quarter turn: the report's text and JSON give the class
    of its six leg lines, with the z axis as the complex's axis; at a regular pose, none."""
    from screwkit.interface.report import analyze

    from .. import mechanisms as M

    def report(psi):
        vertices, bases = gough_63(psi)
        return analyze(M.gough_stewart(bases, vertices[np.arange(6) // 2]), superbracket=False)

    singular = report(np.pi / 2)
    data = singular.to_dict()["grassmann"]
    assert data["name"] == "5a"
    assert same_line(np.array(data["witness"]["axis"]), [0, 0, 1, 0, 0, 0])
    assert data["witness"]["pitch"] == pytest.approx(reciprocal_pitch(gough_lines(*gough_63(np.pi / 2))))
    assert "Grassmann class 5a" in str(singular)
    regular = report(0.3)
    assert regular.to_dict()["grassmann"] is None and "Grassmann class" not in str(regular)
    assert regular.grassmann()[1].startswith("regular pose")
