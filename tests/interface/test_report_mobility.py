"""The report states the instantaneous and finite mobility when they differ (issue 20 item 2)."""

from screwkit.graphs.joints import revolute
from screwkit.graphs.twistgraph import twist_graph
from screwkit.interface.report import analyze


def fourbar(points):
    return twist_graph("ground", "coupler", [
        ("ground", "crank", revolute("A", [0, 0, 1], points[0])),
        ("crank", "coupler", revolute("B", [0, 0, 1], points[1])),
        ("coupler", "rocker", revolute("C", [0, 0, 1], points[2])),
        ("rocker", "ground", revolute("D", [0, 0, 1], points[3]))])


def test_a_flat_fourbar_report_says_instantaneous_2_finite_0():
    # links 1, 1, 2 and ground 4 in line: rigid (1 + 1 + 2 = 4), two first-order freedoms (four planar
    # twists (1, 0, -x) through points of one line span two dimensions)
    report = analyze(fourbar([[0, 0, 0], [1, 0, 0], [2, 0, 0], [4, 0, 0]]), superbracket=False)
    assert (report.mobility.instantaneous, report.mobility.finite) == (2, 0)
    assert "mobility: instantaneous 2, finite 0 (" in str(report)


def test_a_moving_fourbar_report_has_no_mobility_line():
    report = analyze(fourbar([[0, 0, 0], [1, 0, 0], [3, 2, 0], [3, 0, 0]]), superbracket=False)
    assert (report.mobility.instantaneous, report.mobility.finite) == (1, 1)
    assert "mobility: instantaneous" not in str(report)


def test_a_screw_freedom_reads_1h_with_its_pitch_in_the_report_unit():
    from screwkit.graphs.joints import helical

    graph = twist_graph("B", "E", [("B", "E", helical("H", [0, 0, 1], [10, 0, 0], 5.0, actuated=True))])
    graph.graph["length_unit"] = "mm"
    text = str(analyze(graph, superbracket=False))
    assert "platform twist system: 1H (pitch 5 mm/rad) (order 1)" in text  # not "1R"
    # a graph without a unit: the pitch says so (a catalog robot's reads its unit, e.g. mm)
    del graph.graph["length_unit"]
    text = str(analyze(graph, superbracket=False))
    assert "platform twist system: 1H (pitch 5 length units/rad) (order 1)" in text
