"""A redundantly actuated mechanism's conditions (screwkit.gca.redundant_conditions): the superbrackets
of its six-line subsets, checked against the ranks of the subsets' lines computed here from the
diagram's points (a subset's superbracket vanishes exactly where its six lines are dependent) and
against the verdict (singular exactly where every subset vanishes)."""

import numpy as np
import pytest

import screwkit as sk
from screwkit.gca.redundant_conditions import RedundantSuperbracket, six_line_subsets
from tests.core.test_redundancy import elbow, five_bar

A1, A2, A3 = np.zeros(3), np.array([1.0, 0, 0]), np.array([0.5, -0.5, 0])


def plucker(p, q):
    """The line through two homogeneous points (finite weight 1 or at infinity): (p_w q − q_w p; p × q)."""
    return np.concatenate([p[3] * q[:3] - q[3] * p[:3], np.cross(p[:3], q[:3])])


def subset_ranks(result):
    coordinates = result.diagram.coordinates
    lines = np.array([plucker(coordinates[a], coordinates[b]) for a, b in result.diagram.lines])
    lines /= np.linalg.norm(lines, axis=1, keepdims=True)
    return [int(np.sum(np.linalg.svd(lines[list(s)], compute_uv=False) > 1e-7)) for s in result.subsets]


def in_line_five_bar():
    """The five-bar's actuation singularity for its platform (distal 1): B1, B2 and c in line."""
    b1 = np.array([np.cos(2.0), np.sin(2.0), 0.0])
    t2 = next(t for t in np.linspace(0.0, 1.6, 160001)
              if np.linalg.norm(A2 + np.array([np.cos(t), np.sin(t), 0]) - b1) < 2.4)
    b2 = A2 + np.array([np.cos(t2), np.sin(t2), 0.0])
    return b1, b2, (b1 + b2) / 2


def superbracket_of(legs, c):
    one = sk.mechanism(five_bar(c, legs)).at()[0]
    return one, one.superbracket


def test_at_a_regular_pose_no_subset_set_vanishes_entirely_and_the_ranks_agree():
    c = np.array([0.5, 1.5, 0.0])
    one, result = superbracket_of([(A1, elbow(A1, c, 1)), (A2, elbow(A2, c, -1)), (A3, elbow(A3, c, 1))], c)
    assert isinstance(result, RedundantSuperbracket) and len(result.diagram.lines) == 7
    assert result.subsets == six_line_subsets(result.diagram.roles) and len(result.subsets) == 3
    assert subset_ranks(result) == [6] * len(result.subsets) and not result.singular
    assert len(result.conditions) == len(result.labels) == len(result.values) == len(result.subset_of)
    assert one.singularity.labels == () and "all 3 superbrackets of the 4 constraint lines with 2 of the 3 actuation" in result.statement()


def test_where_the_five_bar_is_singular_the_third_leg_keeps_a_subset_regular():
    b1, b2, c = in_line_five_bar()
    one, result = superbracket_of([(A1, b1), (A2, b2), (A3, elbow(A3, c, 1))], c)
    ranks = subset_ranks(result)
    vanishing = [any(result.analyses[k].vanishing) for k in range(len(result.subsets))]
    assert vanishing == [rank < 6 for rank in ranks]  # the hand ranks decide each subset
    assert any(vanishing) and not all(vanishing) and not result.singular
    assert one.singularity.labels == ()


def test_where_every_subset_vanishes_the_redundant_robot_is_singular():
    # the third leg's elbow on the line B1 B2 c too (at B1's place, its base a unit away): every
    # actuation force passes through B1 with the constraint force of leg 1
    b1, b2, c = in_line_five_bar()
    a3 = b1 + np.array([0.0, -1.0, 0.0])
    one, result = superbracket_of([(A1, b1), (A2, b2), (a3, b1.copy())], c)
    assert one.singularity.labels == ("actuation",)
    assert all(rank < 6 for rank in subset_ranks(result)) and result.singular
    assert result.to_dict()["redundant"] is True


def test_six_lines_are_refused():
    diagram, _ = sk.load_mechanism("h4").wrench_diagram()
    from screwkit.gca.redundant_conditions import redundant_superbracket

    with pytest.raises(sk.ScrewkitValueError, match=r"Expected a wrench diagram of more than six lines, got 6"):
        redundant_superbracket(diagram, None, None)


def test_the_report_shows_the_subsets_conditions():
    c = np.array([0.5, 1.5, 0.0])
    one = sk.mechanism(five_bar(c, [(A1, elbow(A1, c, 1)), (A2, elbow(A2, c, -1)), (A3, elbow(A3, c, 1))])).at()[0]
    report = sk.analyze(one)
    assert isinstance(report.superbracket, RedundantSuperbracket)
    text = str(report)
    assert "redundantly actuated: singular where all 3 superbrackets" in text
    assert "degree of redundancy 1" in text and "actuation singularity when" not in text
    # each condition names its subset and says that alone it is no singularity (a new user read them
    # as singularities one by one)
    subset_lines = [line for line in text.splitlines() if line.startswith("  subset ")]
    assert len(subset_lines) >= 6 and all(
        "singular only where every subset has a vanishing factor" in line for line in subset_lines
    )
    assert report.to_dict()["superbracket"]["redundant"] is True


def test_a_redundant_twist_graph_gets_its_conditions_in_the_report():
    c = np.array([0.5, 1.5, 0.0])
    graph = five_bar(c, [(A1, elbow(A1, c, 1)), (A2, elbow(A2, c, -1)), (A3, elbow(A3, c, 1))])
    report = sk.analyze(graph)
    assert isinstance(report.superbracket, RedundantSuperbracket) and len(report.superbracket.subsets) == 3
    assert report.verdict.redundancy == 1 and not report.superbracket.singular


def redundant_diagram():
    """The three-leg five-bar's seven-line diagram and sampler at a regular pose."""
    return sk.graph_diagram(sk.wrench_analysis(three_leg_graph()))


def three_leg_graph():
    c = np.array([0.5, 1.2, 0.0])
    return five_bar(c, [(a, elbow(a, c, sign)) for a, sign in ((A1, 1), (A2, -1), (A3, 1))])


@pytest.mark.parametrize("n_samples", [0, -1, 2.5, True])
def test_the_number_of_samples_must_be_a_positive_integer(n_samples):
    """Zero samples once made every subset 'identically zero' and the robot 'not singular'."""
    diagram, sampler = redundant_diagram()
    assert len(diagram.lines) == 7
    with pytest.raises(sk.ScrewkitValueError, match=r"Expected `n_samples` to be an integer >= 1, got "):
        sk.superbracket_analysis(diagram, sampler, n_samples=n_samples)


def test_analyse_must_be_callable():
    from screwkit.gca.redundant_conditions import redundant_superbracket

    diagram, sampler = redundant_diagram()
    with pytest.raises(sk.ScrewkitTypeError, match=r"Expected `analyse` to be callable, got NoneType"):
        redundant_superbracket(diagram, sampler, None)


def test_no_subset_left_means_singular_everywhere():
    empty = RedundantSuperbracket(None, (), ())
    assert empty.singular and "architecturally singular" in empty.statement()


def test_graph_diagram_names_its_argument():
    with pytest.raises(sk.ScrewkitTypeError, match=r"`analysis`.*WrenchAnalysis"):
        sk.graph_diagram(three_leg_graph())
