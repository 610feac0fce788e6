"""Wrench diagrams and the superbracket pipeline: the H4 of paper 002 §5, and mechanisms beyond SMGs.

Expected values come from the paper (Fig. 4c, Eqs. 5–7), from independent computations in this file
(6×6 determinants of the wrench lines, Eqs. (6)-(7) in vector form from the kinematics) and from
textbook results (a 3-RPR is singular when its legs are concurrent; Tsai's 3-UPU loses its
constraint when its three couples become dependent).
"""

import dataclasses

import numpy as np
import pytest

from screwkit.algebra import screw as S
from screwkit.core.singularity import classify
from screwkit.core.wrench_systems import analyze_table
from screwkit.core.wrenches import wrench_analysis
from screwkit.exceptions import DegenerateGeometryError, ScrewkitValueError
from screwkit.gca import BracketPolynomial, DottedMonomial, check_proportional
from screwkit.gca.diagram_placement import diagram_at, graph_diagram, graph_sampler
from screwkit.gca.diagram_points import batch_diagram_points, diagram_points
from screwkit.gca.diagram_recipes import wrench_diagram
from screwkit.gca.superbracket_analysis import superbracket_analysis
from screwkit.interface.cli import main
from screwkit.interface.export import save_snapshot
from screwkit.interface.report import analyze
from screwkit.robots.catalog import load_mechanism
from screwkit.robots.families.four_limb.joints import joints
from screwkit.robots.families.four_limb.kinematics import inverse_kinematics

from .. import mechanisms as M
from .. import mechanisms_extra as X
from ..robots.test_h4 import H4, case_b_pose, paper_002_conditions, random_poses, singular_pose


@pytest.fixture(scope="module")
def h4_result():
    h4 = load_mechanism("h4")
    diagram, sampler = h4.wrench_diagram(np.array([30.0, -20.0, -750.0, 0.3]))
    return h4, diagram, sampler, superbracket_analysis(diagram, sampler)


def six_by_six(points, lines):
    """The 6×6 determinant of the Plücker rows (p_w q − q_w p ; p × q), written here independently."""
    rows = []
    for p, q in lines:
        a, b = np.asarray(points[p]), np.asarray(points[q])
        rows.append(np.concatenate([a[3] * b[:3] - b[3] * a[:3], np.cross(a[:3], b[:3])]))
    return np.linalg.det(np.array(rows))


# the H4 (paper 002 §5) -------------------------------------------------------------------------
def test_h4_diagram_is_paper_figure_4c(h4_result):
    _, diagram, _, _ = h4_result
    assert diagram.line_text() == "[ab, cd, ef, gh, ij, kj]"
    assert diagram.finite == ("a", "c", "e", "g") and set(diagram.infinite) == set("bdfhijk")
    assert diagram.roles == ("actuation",) * 4 + ("constraint",) * 2
    described = {p.label: p.description for p in diagram.points}
    assert "meets the axis of R_I" in described["a"] and "meets the axis of R_I" in described["c"]
    assert "meets the axis of R_II" in described["e"] and "meets the axis of R_II" in described["g"]
    assert described["j"] == "the point at infinity of the axis of R_I"
    assert not diagram.degenerate
    # the diagram's lines are the paper's wrenches with unit directions: L(a, b) = ±τ0^1 and, i being
    # ±s12 = ±n1 × n2 (unit plane normals), L(i, j) = (0; i × z) = ∓τ∞I, so |superbracket| =
    # |det(paper's six wrenches)|, and test_h4 shows det(paper's six wrenches) = ±Eq. 6 × Eq. 7
    cfg = inverse_kinematics(H4, np.array([30.0, -20.0, -750.0, 0.3]))
    eq6, eq7, s12, s34 = paper_002_conditions(cfg)
    np.testing.assert_allclose(np.abs(diagram.coordinates["i"][:3]), np.abs(s12), rtol=1e-9)
    np.testing.assert_allclose(np.abs(diagram.coordinates["k"][:3]), np.abs(s34), rtol=1e-9)
    value = six_by_six(diagram.coordinates, diagram.lines)
    assert abs(value) == pytest.approx(abs(eq6 * eq7), rel=1e-8)


def test_h4_superbracket_is_equation_5(h4_result):
    _, _, sampler, result = h4_result
    simplification = result.simplification
    # 19 of the 24 monomials vanish in the paper's order (paper 002 §5.2)
    assert simplification.ordering is None and len(simplification.survivors) == 5
    # the factored form is the paper's [gikj][a b d ḟ][c g ḣ j] up to the constant −1 (our convention)
    paper = BracketPolynomial.parse("[gikj]") * DottedMonomial.parse("[a b d ḟ][c g ḣ j]").expand()
    ratio = check_proportional(
        BracketPolynomial.parse("[gikj]") * simplification.factored.rest.expand(), paper, sampler, n_samples=8
    )
    assert ratio.constant == pytest.approx(1.0) and ratio.max_deviation < 1e-9
    assert str(simplification.factored) == "-[gikj][a b d ḟ][c g ḣ j]"
    # the printed second line of Eq. (5), [abdf][cghj] without dots, is not the same function
    undotted = BracketPolynomial.parse("[gikj][abdf][cghj]")
    assert check_proportional(undotted, paper, sampler, n_samples=8).max_deviation > 1e-3
    # every stage was checked against the 6×6 determinant
    assert all(check.max_deviation < 1e-9 for _, check in simplification.checks)


def test_h4_conditions_are_equations_6_and_7(h4_result, rng):
    h4, diagram, _, result = h4_result
    assert result.labels == ("constraint", "actuation")
    assert [c.statement for c in result.conditions] == [
        "i, k and j are collinear in the plane at infinity (the directions i, k, j are parallel to one plane)",
        "line fh meets the line where planes abd and cgj intersect",
    ]
    # vector forms against Eqs. (6) and (7) computed from the kinematics, as functions of the pose
    ratios = []
    for pose in random_poses(rng, 12):
        cfg = inverse_kinematics(H4, pose)
        eq6, eq7, _, _ = paper_002_conditions(cfg)
        points = diagram_points(diagram.points, wrench_analysis(h4.twist_graph(pose)))
        # i, k are s12, s34 of the parallelograms' oriented unit normals (one sign fixed at the
        # reference configuration); b, d, f, h unit directions of w_i
        ratios.append([result.conditions[0].evaluate(points) / eq6, result.conditions[1].evaluate(points) / eq7])
    # one sign per condition at every pose: the conditions are Eqs. (6) and (7), continuous
    np.testing.assert_allclose(np.abs(ratios), 1.0, rtol=1e-8)
    assert (np.sign(ratios) == np.sign(ratios[0])).all()


def test_h4_factors_vanish_exactly_where_the_labels_say(h4_result, rng):
    h4, diagram, _, result = h4_result
    for pose, expected in ((singular_pose(0), ("constraint",)), (singular_pose(1), ("actuation",))):
        graph = h4.twist_graph(pose)
        points = diagram_points(diagram.points, wrench_analysis(graph))
        values = [abs(c.evaluate(points)) for c in result.conditions]
        assert classify(graph).labels == expected
        vanishing = 0 if expected == ("constraint",) else 1
        assert values[vanishing] < 1e-9 and values[1 - vanishing] > 1e-3
    for pose in random_poses(rng, 10):
        graph = h4.twist_graph(pose)
        points = diagram_points(diagram.points, wrench_analysis(graph))
        values = [abs(c.evaluate(points)) for c in result.conditions]
        assert classify(graph).labels == () and min(values) > 1e-6


def _no_generic_configuration(rng):
    raise ScrewkitValueError("no generic pose gives this mechanism a wrench diagram to sample.")


def test_h4_degenerate_representation_is_reported_and_still_factored():
    # paper 002 case (b), found in test_h4: s12 ∥ z, where the leg L_I has two constraint couples
    # and the limb of A1 is at a serial singularity: the generic diagram has no lines there
    h4 = load_mechanism("h4")
    generic, _ = h4.wrench_diagram()
    cfg = inverse_kinematics(H4, case_b_pose())
    diagram = diagram_at(generic, wrench_analysis(joints(cfg).graph()))
    assert any("the limb of A1 is at a serial singularity here" in reason for reason in diagram.degenerate)
    assert any("leg through A1, A4 is not one line here" in reason for reason in diagram.degenerate)
    with pytest.raises(ScrewkitValueError, match="The wrench diagram is degenerate at this pose"):
        superbracket_analysis(diagram, _no_generic_configuration)
    # the factored form is the design's (issue 21 item 1): the report still gives it, evaluates the
    # factor whose points exist and says which point the other lacks (b, on the limb of A1)
    report = analyze("h4", case_b_pose())
    result = report.superbracket
    assert str(result.simplification.factored) == "-[gikj][a b d ḟ][c g ḣ j]"
    assert any("serial singularity here" in reason for reason in result.representation)
    assert np.isnan(result.values[1]) and "no point b" in result.undefined[1]
    assert np.isfinite(result.values[0]) and result.undefined[0] == ""
    assert "the diagram does not hold at this pose" in str(report)
    assert report.to_dict()["superbracket"]["conditions"][1]["value_at_pose"] is None
    # the ranks decide what the pose is: an actuation and serial singularity, not a constraint one
    assert report.verdict.labels == ("actuation", "serial") and report.verdict.constraint_order == 2
    # the posed mechanism's superbracket is the same design's factored form there
    posed = h4.at([case_b_pose()])[0].superbracket
    assert str(posed.simplification.factored) == "-[gikj][a b d ḟ][c g ḣ j]"
    assert np.isnan(posed.values[1]) and np.isfinite(posed.values[0])


# beyond SMGs (custom twist graphs) ----------------------------------------------------------------
BASE_3RPR = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 1.0, 0.0]])


def rpr_platform(rng):
    """A random 3-RPR configuration: platform points near the centre."""
    return np.array([0.5, 0.4, 0.0]) + np.column_stack([rng.uniform(-0.25, 0.25, (3, 2)), np.zeros(3)])


def test_planar_3rpr_factor_is_concurrency_of_the_legs(rng):
    graph = M.planar_3rpr(BASE_3RPR, rpr_platform(rng))
    diagram = wrench_diagram(wrench_analysis(graph))
    assert not diagram.degenerate
    sampler = graph_sampler(diagram.points, lambda r: M.planar_3rpr(BASE_3RPR, rpr_platform(r)))
    result = superbracket_analysis(diagram, sampler)
    actuation = [c for c, label in zip(result.conditions, result.labels, strict=True) if label == "actuation"]
    assert len(actuation) == 1 and actuation[0].statement.startswith("line ")
    # concurrent legs: every leg line through one point O (the textbook singularity)
    centre = np.array([0.5, 0.45, 0.0])
    concurrent = M.planar_3rpr(BASE_3RPR, BASE_3RPR + 0.6 * (centre - BASE_3RPR))
    points = diagram_points(diagram.points, wrench_analysis(concurrent))
    assert abs(actuation[0].evaluate(points)) < 1e-12
    assert classify(concurrent).labels == ("actuation",)
    # and generic configurations are regular, with a non-vanishing factor
    for _ in range(5):
        generic = M.planar_3rpr(BASE_3RPR, rpr_platform(rng))
        points = diagram_points(diagram.points, wrench_analysis(generic))
        assert abs(actuation[0].evaluate(points)) > 1e-6 and classify(generic).labels == ()


def upu_position(rng):
    return np.array([rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(0.8, 1.2)])


def test_tsai_3upu_superbracket_has_a_constraint_factor(rng):
    graph = M.tsai_3upu(upu_position(rng))
    diagram = wrench_diagram(wrench_analysis(graph))
    assert not diagram.degenerate and diagram.roles.count("constraint") == 3
    sampler = graph_sampler(diagram.points, lambda r: M.tsai_3upu(upu_position(r)))
    result = superbracket_analysis(diagram, sampler)
    assert "constraint" in result.labels
    # each factor agrees with the independent 6×6 determinant's zero set at random configurations:
    # product of the factors ∝ det, checked by the pipeline; here the labels at the pose are regular
    assert all(abs(v) > 1e-9 for v in result.values) and classify(graph).labels == ()
    # the factored form equals the 6×6 determinant of the diagram's lines up to its constant
    for _ in range(4):
        points = sampler(rng)
        value = six_by_six(points, diagram.lines)
        factored = result.simplification.factored.evaluate(points)
        assert value == pytest.approx(float(factored), rel=1e-8, abs=1e-12)


def test_gough_stewart_3_2_1_uses_the_shared_joint_centres():
    base = np.array([[1.0, 0, 0], [-0.5, 0.866, 0], [-0.5, -0.866, 0], [0.9, 0.3, 0], [-0.2, 0.9, 0], [0.1, -0.9, 0]])
    # 3-2-1 platform: legs 1-3 meet at P1, legs 4-5 at P2, leg 6 alone at P3 (one S centre each)

    def platform(rng):
        lift = np.array([0.0, 0.0, 1.0]) + np.append(rng.uniform(-0.1, 0.1, 2), rng.uniform(-0.1, 0.1))
        offsets = np.array([[0.3, 0.0, 0.0], [-0.2, 0.25, 0.0], [-0.2, -0.25, 0.05]])
        p1, p2, p3 = lift + offsets
        return np.array([p1, p1, p1, p2, p2, p3])

    rng = np.random.default_rng(5)
    graph = M.gough_stewart(base, platform(rng))
    diagram = wrench_diagram(wrench_analysis(graph))
    assert not diagram.degenerate
    described = [p.description for p in diagram.points]
    assert sum("centre of joint" in d for d in described) >= 8  # the lines are joins of joint centres
    sampler = graph_sampler(diagram.points, lambda r: M.gough_stewart(base, platform(r)))
    result = superbracket_analysis(diagram, sampler)
    assert result.labels and all(label == "actuation" for label in result.labels)
    for _ in range(4):
        points = sampler(rng)
        assert six_by_six(points, diagram.lines) == pytest.approx(
            float(result.simplification.factored.evaluate(points)), rel=1e-8, abs=1e-12
        )


# diagrams of any mechanism, chosen at generic configurations (screwkit.core.motion) -------------------
def plucker_rows(points, lines):
    """The diagram's lines as Plücker rows (p_w q − q_w p ; p × q), written here independently."""
    rows = []
    for p, q in lines:
        a, b = np.asarray(points[p]), np.asarray(points[q])
        rows.append(np.concatenate([a[3] * b[:3] - b[3] * a[:3], np.cross(a[:3], b[:3])]))
    return np.array(rows)


def unit_rows(rows):
    """Each row scaled to a unit direction (a force) or a unit moment (a couple)."""
    rows = np.asarray(rows, dtype=float)
    size = np.linalg.norm(rows[:, :3], axis=1)
    size = np.where(size > 1e-12 * np.linalg.norm(rows, axis=1), size, np.linalg.norm(rows[:, 3:], axis=1))
    return rows / size[:, None]


def rank(rows, tol=1e-8):
    """Rank of unit rows (every test mechanism is about one unit in size, near the origin)."""
    return int(np.linalg.matrix_rank(unit_rows(rows), tol=tol))


def upu_lines(position):
    graph = M.tsai_3upu(position)
    centres = {k: np.asarray(j.geometry["center"]) for _, _, k, j in graph.edges(keys=True, data="joint") if j.type == "U"}
    legs = [S.line(M.unit(centres[f"Up{i}"] - centres[f"Ub{i}"]), centres[f"Ub{i}"]) for i in (1, 2, 3)]
    return graph, np.concatenate([legs, M.tsai_constraint_couples(position)])


def delta_lines(position):
    graph = X.delta(position)
    return graph, np.concatenate([X.delta_actuation_lines(graph), X.delta_couples(graph)])


TILT = M.rotation_about([0.2, 1.0, 0.1], 0.1)
#: Each mechanism at a regular configuration, with its six wrench lines written independently here
#: (leg lines, constraint couples/forces from the geometry); None where the constraint system has
#: no canonical basis (the planar 3-RPR's is the plane's 3-system).
MECHANISMS = {
    "delta": lambda: delta_lines([0.1, -0.05, -1.8]),
    "3-UPU": lambda: upu_lines([0.05, 0.1, 1.0]),
    "3-PRS": lambda: X.three_prs_lines(M.rotation_about([1.0, 0.3, 0.0], 0.15), [0.02, 0.03, 1.0]),
    "octahedral Gough-Stewart": lambda: (
        M.gough_stewart(*X.octahedral_points(TILT, [0.05, 0.02, 1.0])),
        M.leg_lines(*X.octahedral_points(TILT, [0.05, 0.02, 1.0])),
    ),
    "6-6 Gough-Stewart": lambda: (
        M.gough_stewart(*M.gough_stewart_points(TILT, [0.05, 0.02, 1.0])),
        M.leg_lines(*M.gough_stewart_points(TILT, [0.05, 0.02, 1.0])),
    ),
    "planar 3-RPR": lambda: (M.planar_3rpr(M.PLANAR_BASE, M.PLANAR_PLATFORM), None),
}


@pytest.mark.parametrize("name", sorted(MECHANISMS))
def test_every_mechanism_gets_a_diagram_spanning_its_wrench_system(name):
    graph, independent = MECHANISMS[name]()
    analysis = wrench_analysis(graph)
    diagram, sampler = graph_diagram(analysis)
    assert not diagram.degenerate and len(diagram.lines) == 6 and sampler is not None
    rows = plucker_rows(diagram.coordinates, diagram.lines)
    # the six lines span the core's global wrench system, and its constraint lines the core's W^c
    core = analysis.global_wrenches.basis
    assert rank(rows) == rank(np.concatenate([rows, core])) == analysis.global_order == 6
    constraint = rows[[role == "constraint" for role in diagram.roles]]
    wc = analysis.constraint_wrenches.basis
    assert len(constraint) == rank(constraint) == rank(np.concatenate([constraint, wc.reshape(-1, 6)])) == len(wc)
    if independent is None:
        return
    assert abs(np.linalg.det(unit_rows(independent))) > 1e-6  # a regular configuration
    # each line of the diagram is the one written here (legs in order), its actuation lines up to
    # the constraint wrench of their own leg
    n_act = diagram.roles.count("actuation")
    for k, row in enumerate(rows):
        own = independent[[k, n_act + k]] if k < n_act and len(independent) > n_act else independent[[k]]
        assert rank(np.concatenate([own, row[None]])) == rank(own)
    if name != "3-PRS":
        # forces change only by couples (constraint systems of couples, or none), which leave the
        # unit direction alone: the diagram's superbracket (6×6 determinant of its joins) is the
        # determinant of the unit lines written here times the joins' own scales
        joins = np.linalg.det(rows) / np.linalg.det(unit_rows(rows))
        assert abs(six_by_six(diagram.coordinates, diagram.lines)) == pytest.approx(
            abs(np.linalg.det(unit_rows(independent)) * joins), rel=1e-8
        )
    else:  # its actuation lines are defined up to the leg's constraint force: up to a nonzero scalar
        ratio = six_by_six(diagram.coordinates, diagram.lines) / np.linalg.det(independent)
        assert np.isfinite(ratio) and abs(ratio) > 1e-6


def test_delta_superbracket_has_the_constraint_factor_of_its_three_couples():
    graph, independent = delta_lines([0.1, -0.05, -1.8])
    diagram, sampler = graph_diagram(wrench_analysis(graph))
    # the three couple lines meet pairwise in the plane at infinity: a triangle of shared points
    couples = [line for line, role in zip(diagram.lines, diagram.roles, strict=True) if role == "constraint"]
    labels = "".join("".join(line) for line in couples)
    assert len(set(labels)) == 3 and all(p in diagram.infinite for p in labels)
    result = superbracket_analysis(diagram, sampler)
    assert "constraint" in result.labels and "actuation" in result.labels
    value = six_by_six(diagram.coordinates, diagram.lines)
    assert float(result.simplification.factored.evaluate(diagram.coordinates)) == pytest.approx(value, rel=1e-8)
    # hand derivation: the couple line through the unit directions p, q has moment p × q = ±|p × q| n
    # (n its leg's parallelogram normal), and det(g × h, g × i, h × i) = det(g, h, i)², so the
    # product of the constraint factors ([e g h i] = ±det(g, h, i), e of weight 1) is
    # ±det(n1, n2, n3) times the three |p × q|
    normals = unit_rows(independent[3:])[:, 3:]
    sizes = [np.linalg.norm(np.cross(diagram.coordinates[p][:3], diagram.coordinates[q][:3])) for p, q in couples]
    # the squared [e g h i] is one condition with multiplicity 2 (issue 9, item 3)
    found = zip(result.values, result.labels, result.conditions, strict=True)
    product = np.prod([v**c.multiplicity for v, label, c in found if label == "constraint"])
    assert abs(product) == pytest.approx(abs(np.linalg.det(normals)) * np.prod(sizes), rel=1e-8)


def test_singular_gough_stewart_keeps_six_lines_and_values_the_vanishing_factor():
    angle = X.singular_gough_stewart_angle()
    base, platform = M.gough_stewart_points(M.rotation_z(angle))
    assert abs(np.linalg.det(M.leg_lines(base, platform))) < 1e-12  # the independent determinant
    graph = M.gough_stewart(base, platform)
    analysis = wrench_analysis(graph)
    diagram, _ = graph_diagram(analysis)
    assert not diagram.degenerate and len(diagram.lines) == 6
    rows = plucker_rows(diagram.coordinates, diagram.lines)
    assert rank(rows, 1e-7) == rank(np.concatenate([rows, analysis.global_wrenches.basis]), 1e-7) == 5
    regular, _ = graph_diagram(wrench_analysis(M.gough_stewart(*M.gough_stewart_points(TILT, [0.05, 0.02, 1.0]))))
    scale = abs(six_by_six(regular.coordinates, regular.lines))
    assert abs(six_by_six(diagram.coordinates, diagram.lines)) < 1e-10 * scale


@pytest.mark.parametrize(("which", "vanishing"), [(0, "constraint"), (1, "actuation")])
def test_h4_at_a_singularity_has_the_regular_factored_form_with_the_factor_valued(which, vanishing):
    h4 = load_mechanism("h4")
    pose = singular_pose(which)
    diagram, sampler = h4.wrench_diagram(pose)
    assert not diagram.degenerate and diagram.line_text() == "[ab, cd, ef, gh, ij, kj]"
    if which == 0:  # the two legs' constraint couples coincide: both lines are still there
        rows = unit_rows(plucker_rows(diagram.coordinates, diagram.lines))
        assert np.allclose(np.abs(rows[4]), np.abs(rows[5]), atol=1e-9)
    result = superbracket_analysis(diagram, sampler)
    assert str(result.simplification.factored) == "-[gikj][a b d ḟ][c g ḣ j]"
    values = dict(zip(result.labels, result.values, strict=True))
    other = "actuation" if vanishing == "constraint" else "constraint"
    assert abs(values[vanishing]) < 1e-8 * abs(values[other]) and abs(values[other]) > 1e-6
    assert result.vanishing == tuple(label == vanishing for label in result.labels)
    labels = analyze("h4", pose, superbracket=False).verdict.labels
    assert vanishing in labels and other not in labels


def test_singular_snapshot_through_the_cli_shows_the_factor_of_its_verdict(tmp_path, capsys):
    # a 3-PRS where the determinant of its six lines (written from the geometry) vanishes
    angle = X.singular_three_prs_tilt()
    graph, lines = X.three_prs_lines(M.rotation_about(X.PRS_TILT_AXIS, angle), X.PRS_POSITION, drop=X.PRS_DROP)
    assert abs(np.linalg.det(lines)) < 1e-12
    graph.graph["dof"] = 3
    path = save_snapshot(graph, tmp_path / "prs_singular.toml", name="3-PRS at an actuation singularity")
    assert main(["analyze", str(path)]) == 0
    text = capsys.readouterr().out
    # structural zeros come from generic configurations: no factor is "0 = 0" here
    assert "0 = 0" not in text and "constraint singularity when" not in text
    statements = [line for line in text.splitlines() if "vector form:" in line]
    assert len(statements) == 1 and "actuation singularity when" in text
    assert any(line.startswith("  actuation singularity when") and line.endswith("<- vanishes at this pose")
               for line in text.splitlines())
    assert abs(float(statements[0].rsplit("(here: ", 1)[1].rstrip(")"))) < 1e-9
    assert text.split("verdict", 1)[1].splitlines()[1].strip().startswith("actuation singularity")


def test_a_mechanism_without_a_diagram_says_why_as_a_property_of_the_mechanism():
    # the Ragnar read with horizontal actuated axes (ragnar.toml's header) keeps an uncontrolled
    # rotation about x at every pose: its global wrench system is never a 6-system
    ragnar = load_mechanism("ragnar")
    horizontal = dataclasses.replace(ragnar, parameters=dataclasses.replace(ragnar.parameters, axis_inclination=0.0))
    diagram, _ = horizontal.wrench_diagram()
    assert diagram.degenerate and all(r.startswith("the mechanism has no wrench diagram") for r in diagram.degenerate)
    assert any("global wrench system has order 5, not 6" in r for r in diagram.degenerate)
    report = analyze(horizontal)
    assert report.superbracket is None and "the mechanism has no wrench diagram" in report.superbracket_note
    # the catalog's Ragnar (inclined axes) is a Schönflies-motion generator: it has one
    assert not ragnar.wrench_diagram()[0].degenerate


def test_constraint_lines_are_named_after_the_actuated_joints_of_their_leg():
    diagram, _ = load_mechanism("mcgill_smg").wrench_diagram()
    constraint = [n for n, r in zip(diagram.line_names, diagram.roles, strict=True) if r == "constraint"]
    assert constraint and all("leg through I.pan, I.proximal.a" in n or "leg through II.pan" in n for n in constraint)


@pytest.mark.parametrize("name", ["delta", "3-PRS"])
def test_generic_diagram_follows_rigid_motions_and_units(name):
    graph, _ = MECHANISMS[name]()
    rotation, translation = M.rotation_about([1.0, -2.0, 0.5], 1.1), np.array([3.0, -1.0, 0.5])
    plain, _ = graph_diagram(wrench_analysis(graph))
    moved, _ = graph_diagram(wrench_analysis(M.moved(graph, rotation, translation, 1000.0)))
    assert moved.line_text() == plain.line_text() and moved.line_names == plain.line_names
    assert [p.key for p in moved.points] == [p.key for p in plain.points] and not moved.degenerate
    for label, point in plain.coordinates.items():  # points at infinity turn; finite ones move and scale
        expected = rotation @ point[:3] if point[3] == 0 else (rotation @ point[:3] + translation) * 1000.0
        assert np.allclose(np.abs(moved.coordinates[label][:3]), np.abs(expected), rtol=1e-7, atol=1e-6)


def test_mcgill_smg_10_km_from_the_origin_keeps_its_diagram_and_superbracket():
    # issue 11: a robot far from the origin keeps its labels and diagram. The McGill SMG's graph
    # (mm) moved ~12 km away: the readable constraint bases used to be decided about the far origin
    # (an internal error from 1 km on); now about the mechanism's own axes
    graph = load_mechanism("mcgill_smg").twist_graph()
    rotation = np.eye(3)  # a translation only: the readable bases put the frame's axes first
    far = M.moved(graph, rotation, np.array([1e7, -1e7, 3e6]))
    near_report, far_report = analyze(graph), analyze(far)
    assert far_report.verdict.labels == near_report.verdict.labels == ()
    assert not far_report.diagram.degenerate
    assert far_report.diagram.line_names == near_report.diagram.line_names
    assert [p.key for p in far_report.diagram.points] == [p.key for p in near_report.diagram.points]
    factors = [str(c.factor) for c in near_report.superbracket.conditions]
    assert factors and [str(c.factor) for c in far_report.superbracket.conditions] == factors
    for label, point in near_report.diagram.coordinates.items():  # finite points moved, others turned
        moved = far_report.diagram.coordinates[label]
        expected = rotation @ point[:3] if point[3] == 0 else rotation @ point[:3] + [1e7, -1e7, 3e6]
        scale = 1.0 if point[3] == 0 else 1e3
        assert np.allclose(np.abs(moved[:3]), np.abs(expected), rtol=1e-9, atol=1e-6 * scale)


def test_a_structural_factor_is_reported_as_never_vanishing():
    # a planar mechanism in the xy-plane is constrained by the couples about x and y and a force
    # along z at every configuration (its constraint lines never move), so the factor made of their
    # points takes one value everywhere; the H4's factors change sign across its surfaces
    from screwkit.interface.report import analyze

    planar = analyze(load_mechanism("planar_3rrp"))
    kinds = dict(zip((str(c.factor) for c in planar.superbracket.conditions), planar.superbracket.constant,
                     strict=True))
    assert sorted(kinds.values()) == [False, True]
    text = str(planar)
    assert "never vanishes on this mechanism" in text and text.count("singularity when") == 1
    assert not any(analyze(load_mechanism("h4")).superbracket.constant)
    listed = planar.to_dict()["superbracket"]["conditions"]
    assert [c["never_vanishes"] for c in listed] == list(planar.superbracket.constant)
    assert [c["factor"] for c in listed if c["never_vanishes"]] == ["[hijg]"]


def test_batch_diagram_points_is_nan_only_where_a_recipe_has_no_point():
    # paper 002 case (b): the limb of A1 at a serial singularity has no actuation line, so the
    # points on it do not exist there; the other pose of the batch is the single-pose evaluation
    h4 = load_mechanism("h4")
    diagram, _ = h4.wrench_diagram()
    poses = np.array([[30.0, -20.0, -750.0, 0.3], case_b_pose()])
    posed = h4.at(poses)
    with_views = batch_diagram_points(diagram.points, analyze_table(posed.joints))
    without = batch_diagram_points(diagram.points, posed.singularities.analysis)  # kept no views
    single = diagram_points(diagram.points, posed[0].analysis)
    missing = {label for label, value in with_views.items() if np.isnan(value[1]).any()}
    assert {"a", "b"} <= missing and "j" not in missing
    for label, value in with_views.items():
        assert value.shape == (2, 4)
        np.testing.assert_array_equal(value[0], single[label])
        np.testing.assert_array_equal(value, without[label])
        assert np.isnan(value[1]).all() or np.isfinite(value[1]).all()
    with pytest.raises(DegenerateGeometryError, match=r"point a .* does not exist at this pose"):
        diagram_points(diagram.points, posed[1].analysis)


def test_catalog_sampler_replays_the_generic_samples_batch_after_batch():
    # the sampler's first batch is analysed together with the generic draws, the next ones on their
    # own: both must be generic_samples' batches from one generator seeded 0, in order
    from screwkit.robots.generic_poses import SAMPLES, generic_samples

    h4 = load_mechanism("h4")
    diagram, sampler = h4.wrench_diagram()
    stream = np.random.default_rng(0)
    first, second = (generic_samples(h4, diagram.points, stream, SAMPLES) for _ in range(2))
    expected = [*first, *second[:2]]
    drawn = [sampler(None) for _ in range(SAMPLES + 2)]
    for got, want in zip(drawn, expected, strict=True):
        assert got.keys() == want.keys()
        for label in want:
            np.testing.assert_array_equal(got[label], want[label])
    assert not np.array_equal(drawn[0]["a"], drawn[SAMPLES]["a"])


def test_a_pose_report_is_the_same_whether_its_analysis_was_read_first():
    # the report analyses the pose together with the generic draws unless the pose's own analysis
    # is already there: both routes give the same report, to the last digit of the JSON
    import json

    h4 = load_mechanism("h4")
    fresh, read = h4.at([[20.0, -10.0, -720.0, 0.2]])[0], h4.at([[20.0, -10.0, -720.0, 0.2]])[0]
    assert read.singularity.verdict == "regular"  # reads the pose's analysis first
    assert json.dumps(analyze(fresh).to_dict(), default=str) == json.dumps(analyze(read).to_dict(), default=str)
