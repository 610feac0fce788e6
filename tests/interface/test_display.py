"""What a notebook shows: one-line reprs for values, a few lines for reports, HTML and LaTeX renderings,
screws printed as screws with rounding noise shown as 0 (display only), nothing lost from str()."""

from html.parser import HTMLParser

import numpy as np
import pytest

import screwkit as sk
from screwkit.algebra.display import ScrewArray, clean, screw_text


class _Checker(HTMLParser):
    """Counts tags and checks that every opened tag is closed in order (well-formed fragments)."""

    VOID = frozenset({"br"})

    def __init__(self):
        super().__init__()
        self.stack, self.counts, self.text = [], {}, []

    def handle_starttag(self, tag, attrs):
        self.counts[tag] = self.counts.get(tag, 0) + 1
        if tag not in self.VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag):
        assert self.stack and self.stack[-1] == tag, (tag, self.stack[-5:])
        self.stack.pop()

    def handle_data(self, data):
        self.text.append(data)


def parsed(page):
    checker = _Checker()
    checker.feed(page)
    checker.close()
    assert checker.stack == []
    return checker


@pytest.fixture(scope="module")
def h4_report():
    return sk.analyze("h4", [30, -20, -750, 17], angles="deg")


@pytest.fixture(scope="module")
def posed():
    return sk.load_mechanism("h4").at([[0, 0, -750, 0], [30, -20, -750, 0.3]])


def test_values_have_one_line_reprs(posed, h4_report):
    values = {
        "Screw": sk.Screw.force([1, 0, 0], [0, 1, 2]),
        "ScrewSystem": sk.ScrewSystem.span(np.eye(6)),
        "SingularityReport": posed[0].singularity,
        "SingularityReport batch": posed.singularities,
        "Jacobians": posed[0].jacobians,
        "Jacobians batch": posed.jacobians,
        "PosedMechanism": posed,
        "PosedMechanism pose": posed[1],
        "Mechanism": posed.mechanism,
        "WrenchAnalysis": posed[0].analysis,
        "Transmission": posed[0].wrench_transmission,
        "JointTable": posed.mechanism.joints(),
        "WrenchDiagram": h4_report.diagram,
        "FactoredForm": h4_report.superbracket.simplification.factored,
        "Condition": h4_report.superbracket.conditions[0],
        "SuperbracketAnalysis": h4_report.superbracket,
    }
    for name, value in values.items():
        text = repr(value)
        assert "\n" not in text and len(text) <= 300, (name, len(text), text)
        assert "array(" not in text, name  # screws as screws, not numpy dumps


def test_the_issue_examples(posed):
    # the issue's wording: "SingularityReport('regular', dof=4, constraint 2/2, global 6/6)"
    assert repr(posed[0].singularity) == "SingularityReport('regular', dof=4, constraint 2/2, global 6/6)"
    assert repr(posed.singularities) == "SingularityReport(shape=(2,): regular 2)"
    assert "phi = 17.19 deg" in repr(posed[1])  # 0.3 rad, the echo states its unit
    assert "z = -750 mm" in repr(posed[1])


def test_a_report_repr_is_a_few_lines_and_str_keeps_everything(h4_report):
    short, full = repr(h4_report), str(h4_report)
    assert len(short.splitlines()) <= 5 and len(short) < 600  # was 11,089 characters
    assert "phi = 17 deg" in short and "regular" in short
    assert "-[gikj][a b d ḟ][c g ḣ j]" in short  # paper 002's factored superbracket of the H4
    # nothing lost from str(): every section and every condition's statement
    for section in ("twist graph", "wrench systems", "wrench diagram", "superbracket", "conditions", "verdict"):
        assert section in full
    for condition in h4_report.superbracket.conditions:
        assert condition.statement in full
    assert len(full) > 3000


def test_report_html_has_the_sections_and_tables(h4_report):
    page = h4_report._repr_html_()
    checker = parsed(page)
    text = "".join(checker.text)
    assert checker.counts["table"] >= 6  # twists, wrenches, lines, points, conditions, verdict tables
    for heading in ("twist graph", "wrench systems", "superbracket", "singularity: regular"):
        assert heading in text
    # one row per wrench on the platform: 2 constraint wrenches per leg pair and 4 actuation wrenches
    wrenches = h4_report.wrenches()
    rows = text.count("constraint") >= len(wrenches["constraint"])
    assert rows and all(item["joint"] in text for item in wrenches["actuation"])
    for condition in h4_report.superbracket.conditions:
        assert condition.statement in text
    assert "<script" not in page


def test_posed_and_singularity_html(posed):
    batch = parsed(posed._repr_html_())
    assert batch.counts["tr"] == 3 and "phi (deg)" in "".join(batch.text)
    one = parsed(posed[1]._repr_html_())
    assert "17.1887" in "".join(one.text)  # 0.3 rad in degrees
    parsed(posed.singularities._repr_html_())


def test_latex_of_the_superbracket_and_its_conditions(h4_report):
    result = h4_report.superbracket
    block = result._repr_latex_()
    assert block.startswith("\\begin{align*}") and block.rstrip().endswith("\\end{align*}")
    assert "\\dot{f}" in block and "\\text{constraint}" in block and "\\text{actuation}" in block
    factored = result.simplification.factored._repr_latex_()
    assert factored.startswith("$") and factored.endswith("$") and "[gikj]" in factored
    condition = result.conditions[0]._repr_latex_()
    assert "\\iff" in condition and "\\mathbf{i}" in condition


def test_rounding_noise_is_hidden_in_display_only():
    # the 3-RPR of the README at its actuation singularity: one uncontrolled twist, the rotation about z
    # through (0.5, 0.4), whose computed coordinates carry ~1e-17 noise
    base = np.array([[0, 0, 0], [1, 0, 0], [0.5, 1, 0]], dtype=float)
    centre = np.array([0.5, 0.4, 0.0])
    joints = []
    for i, a in enumerate(base, start=1):
        c = a + 0.6 * (centre - a)
        joints += [
            ("base", f"cylinder{i}", sk.revolute(f"A{i}", [0, 0, 1], a)),
            (f"cylinder{i}", f"piston{i}", sk.prismatic(f"P{i}", c - a, actuated=True)),
            (f"piston{i}", "platform", sk.revolute(f"C{i}", [0, 0, 1], c)),
        ]
    report = sk.classify(sk.twist_graph("base", "platform", joints, dof=3))
    twists = report.uncontrolled_twists
    assert isinstance(twists, np.ndarray) and twists.shape == (1, 6)
    # by hand: the rotation about z through (0.5, 0.4): (0, 0, 1; 0.4, -0.5, 0) up to scale
    direction = twists[0, 2]
    np.testing.assert_allclose(np.asarray(twists[0]) / direction, [0, 0, 1, 0.4, -0.5, 0], atol=1e-12)
    shown = str(twists)
    assert "e-1" not in shown and "e-2" not in shown  # no 1e-17 noise printed
    assert str(sk.Screw(np.asarray(twists[0]))).count("e-") == 0


def test_display_cleaning_keeps_values():
    noisy = np.array([0.0, 0.0, 1.0, 0.4, -0.5, 5e-18])
    assert screw_text(noisy) == "(0, 0, 1; 0.4, -0.5, 0)"
    assert noisy[5] == 5e-18  # display only
    arr = ScrewArray([noisy])
    assert float(arr[0, 5]) == 5e-18 and "5e-18" not in repr(arr)
    assert repr(ScrewArray(np.zeros((0, 6)))) == "ScrewArray([])"
    # a genuinely small coordinate next to small ones is kept
    assert clean([1e-9, 2e-9, 0.0]).tolist() == [1e-9, 2e-9, 0.0]
    # a batch of screws prints as screws
    batch = sk.Screw.couple(np.eye(3))
    assert str(batch) == "[Screw(0, 0, 0, 1, 0, 0), Screw(0, 0, 0, 0, 1, 0), Screw(0, 0, 0, 0, 0, 1)]"
