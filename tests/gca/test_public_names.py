"""Issue 21 item 9: the condition interpreter, the generic-configuration sampler and the diagram's
points are public names (``screwkit.gca`` and, for the diagram, its sampler and its points, the top
level beside ``sk.diagram_at``), loaded on first use: ``import screwkit.gca`` still does not import sympy."""

import subprocess
import sys

import numpy as np

import screwkit as sk
import screwkit.gca as gca
from screwkit.gca import conditions, diagram_placement, diagram_points, factor_kinds


def test_the_names_are_the_functions():
    assert gca.condition is conditions.condition and gca.Condition is conditions.Condition
    assert gca.graph_sampler is sk.graph_sampler is diagram_placement.graph_sampler
    assert gca.graph_diagram is sk.graph_diagram is diagram_placement.graph_diagram
    assert sk.diagram_points is diagram_points.diagram_points  # gca.diagram_points is its module
    assert gca.vanishing_kind is factor_kinds.vanishing_kind
    assert {"condition", "graph_diagram", "graph_sampler"} <= set(gca.__all__) & set(dir(gca))


def test_a_user_session_with_the_public_names():
    """The custom-mechanism notebook's steps, through the public names only: the H4's diagram, its
    points at a moved pose, a generic sample and one factor's condition there."""
    h4 = sk.load_mechanism("h4")
    diagram, sampler = sk.graph_diagram(sk.wrench_analysis(h4.twist_graph()))
    moved = sk.diagram_points(diagram.points, sk.wrench_analysis(h4.twist_graph([50.0, 0, -700.0, 0.3])))
    sample = sampler(np.random.default_rng(0))
    assert set(moved) == set(sample) == {p.label for p in diagram.points}
    couples = gca.condition(gca.Bracket("gikj"), finite=diagram.finite, infinite=diagram.infinite)
    # [gikj] with i, k, j at infinity: −det(i, k, j) (gca.md §5.1 table), computed here with numpy
    expected = -np.linalg.det(np.array([moved[x][:3] for x in "ikj"]))
    assert np.isclose(float(couples.constant) * couples.evaluate(moved), expected, rtol=1e-12, atol=0)


def test_import_gca_does_not_import_sympy():
    code = "import sys, screwkit.gca\nprint('sympy' in sys.modules)"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert result.stdout.split()[-1] == "False"
