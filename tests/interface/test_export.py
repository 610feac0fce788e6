"""Writing twist graphs: snapshot TOML round trips, DOT and JSON, and their errors (screwkit.interface.export)."""

import json
import math

import networkx as nx
import numpy as np
import pytest
import sympy as sp

import screwkit as sk
from screwkit.graphs.joints import Joint
from screwkit.graphs.twistgraph import from_data
from screwkit.interface.cli import main
from screwkit.interface.export import graph_dot, graph_json, save_snapshot, snapshot_text


def _screws_by_name(graph):
    return {joint.name: (u, v, joint.screws, joint.actuated) for u, v, joint in graph.edges(data="joint")}


@pytest.mark.parametrize("name", sk.list_mechanisms())
def test_every_catalog_robot_round_trips_exactly(name, tmp_path):
    graph = sk.load_mechanism(name).twist_graph()
    again = sk.load_snapshot(save_snapshot(graph, tmp_path / f"{name}.toml"))
    before, after = _screws_by_name(graph), _screws_by_name(again)
    assert before.keys() == after.keys()
    for joint, (u, v, screws, actuated) in before.items():
        assert (str(u), str(v), actuated) == (*after[joint][:2], after[joint][3])
        # family tables carry no geometry: written from the screws, read back to rounding
        np.testing.assert_allclose(after[joint][2], screws, rtol=0, atol=1e-12 * max(1.0, np.abs(screws).max()))
    assert again.graph["dof"] == graph.graph["dof"]


def test_a_written_snapshot_gets_the_same_verdict(tmp_path):
    h4 = sk.load_mechanism("h4")
    pose = [30.0, -20.0, -750.0, math.radians(17.0)]
    path = save_snapshot(h4.twist_graph(pose), tmp_path / "h4.toml")
    assert sk.classify(sk.load_snapshot(path)).labels == sk.classify(h4.twist_graph(pose)).labels


def test_virtual_joints_are_written_from_their_screws(tmp_path):
    # w = (0, 0, 2), axis point p = (1, 2, 0), pitch h = 0.5: v = p × w + h w = (4, -2, 1) (by hand)
    helix = Joint("v1", "vH", [0, 0, 2, 4, -2, 1], virtual=True)
    line = Joint("v2", "vR", [0, 2, 0, 0, 0, 2], virtual=True)  # p × w = (0, 0, 2) for p = (1, 0, 0)
    slide = Joint("v3", "vP", [0, 0, 0, 0, 3, 4], virtual=True)
    graph = sk.twist_graph("B", "E", [("B", "L1", helix), ("L1", "L2", line), ("L2", "E", slide)])
    text = snapshot_text(graph)
    data = __import__("tomllib").loads(text)
    by_name = {j["name"]: j for j in data["joints"]}
    assert by_name["v1"]["type"] == "H" and by_name["v1"]["pitch"] == pytest.approx(0.5)
    assert by_name["v1"]["point"] == pytest.approx([1.0, 2.0, 0.0])
    assert by_name["v1"]["axis"] == pytest.approx([0.0, 0.0, 1.0])
    assert by_name["v2"]["type"] == "R" and by_name["v2"]["point"] == pytest.approx([1.0, 0.0, 0.0])
    assert by_name["v3"] == {**by_name["v3"], "type": "P", "direction": pytest.approx([0, 0.6, 0.8])}
    again = sk.load_snapshot(save_snapshot(graph, tmp_path / "virtual.toml"))
    for joint, (_, _, screws, _) in _screws_by_name(graph).items():
        unit = screws / np.linalg.norm(screws[:, :3] if np.any(screws[:, :3]) else screws)
        np.testing.assert_allclose(_screws_by_name(again)[joint][2], unit, atol=1e-15)


def test_the_equivalent_graph_round_trips_with_the_same_platform_twists(tmp_path):
    h4 = sk.load_mechanism("h4")
    equivalent = sk.equivalent_twist_graph(h4.twist_graph())
    again = sk.load_snapshot(save_snapshot(equivalent, tmp_path / "eq.toml"))
    ours, theirs = sk.wrench_analysis(h4.twist_graph()), sk.wrench_analysis(again)
    assert ours.platform_twists.order == theirs.platform_twists.order == 4
    assert ours.constraint_wrenches.order == theirs.constraint_wrenches.order == 2


def test_raw_several_freedom_joints_are_written_from_their_axes(tmp_path):
    # by hand: axes x and y through c = (1, 2, 3): rows (e; c × e)
    c = np.array([1.0, 2.0, 3.0])
    rows = [np.r_[e, np.cross(c, e)] for e in np.eye(3)]
    graph = sk.twist_graph("B", "E", [("B", "L", Joint("U", "U", rows[:2])), ("L", "E", Joint("S", "S", rows)),
                                      ("B", "E", Joint("C", "C", [rows[2], [0, 0, 0, 0, 0, 1]]))])
    data = __import__("tomllib").loads(snapshot_text(graph))
    by_name = {j["name"]: j for j in data["joints"]}
    assert by_name["U"]["center"] == pytest.approx(c) and by_name["S"]["center"] == pytest.approx(c)
    assert by_name["U"]["first_axis"] == [1.0, 0.0, 0.0] and by_name["U"]["second_axis"] == [0.0, 1.0, 0.0]
    assert by_name["C"]["axis"] == [0.0, 0.0, 1.0] and by_name["C"]["point"] == pytest.approx([1, 2, 0])
    again = sk.load_snapshot(save_snapshot(graph, tmp_path / "raw.toml"))
    for joint, (_, _, screws, _) in _screws_by_name(graph).items():
        np.testing.assert_allclose(_screws_by_name(again)[joint][2], screws, atol=1e-14)


def test_names_and_strings_are_escaped(tmp_path):
    graph = sk.twist_graph('base "0"', "plate\\1", [
        ('base "0"', "plate\\1", sk.revolute('R "odd"\tname', [0, 0, 1], [0, 0, 0], actuated=True))])
    graph.graph["name"] = "ünïcode ḟ"
    again = sk.load_snapshot(save_snapshot(graph, tmp_path / "odd.toml"))
    assert again.graph["name"] == "ünïcode ḟ"
    assert again.graph["base"] == 'base "0"' and again.graph["platform"] == "plate\\1"
    assert list(_screws_by_name(again)) == ['R "odd"\tname']


def test_integer_link_names_are_written_as_text(tmp_path):
    graph = sk.twist_graph(0, 1, [(0, 1, sk.prismatic("P", [1, 0, 0], actuated=True))])
    again = sk.load_snapshot(save_snapshot(graph, tmp_path / "ints.toml"))
    assert (again.graph["base"], again.graph["platform"]) == ("0", "1")


def test_dot_draws_every_joint_with_its_style():
    graph = sk.equivalent_twist_graph(sk.load_mechanism("h4").twist_graph())
    dot = graph_dot(graph)
    assert dot.startswith('digraph "H4" {') and dot.endswith("}")
    edges = [line for line in dot.splitlines() if "->" in line]
    assert len(edges) == graph.number_of_edges()
    assert sum("style=bold" in e for e in edges) == 4  # the four actuated arms
    assert sum("style=dashed" in e for e in edges) == sum(j.virtual for _, _, j in graph.edges(data="joint")) > 0
    assert '"end_effector" [shape=box, peripheries=2];' in dot


def test_json_round_trips_through_from_data():
    graph = sk.load_mechanism("v4").twist_graph()
    again = from_data(json.loads(graph_json(graph)))
    for joint, (_, _, screws, _) in _screws_by_name(graph).items():
        np.testing.assert_array_equal(screws, _screws_by_name(again)[joint][2])


def test_errors_name_what_was_expected():
    x = sp.Symbol("x")
    symbolic = sk.twist_graph("B", "E", [("B", "E", sk.revolute("R", [0, 0, 1], [x, 0, 0]))])
    with pytest.raises(sk.ScrewkitValueError, match="Joint 'R': expected numeric screws"):
        snapshot_text(symbolic)
    with pytest.raises(sk.ScrewkitValueError, match="Expected a numeric twist graph to write JSON, got symbolic screws"):
        graph_json(symbolic)
    skew = sk.twist_graph("B", "E", [("B", "E", Joint("S", "S", [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0],
                                                                  [0, 0, 1, 1, 0, 0]]))])
    with pytest.raises(sk.ScrewkitValueError, match="Joint 'S': expected axes through one point"):
        snapshot_text(skew)
    tuple_links = sk.twist_graph(("a",), ("b",), [(("a",), ("b",), sk.prismatic("P", [1, 0, 0]))])
    with pytest.raises(sk.ScrewkitTypeError, match="expected link names that are strings or integers"):
        snapshot_text(tuple_links)
    with pytest.raises(sk.TwistGraphError):
        graph_dot(nx.Graph())
    with pytest.raises(sk.ScrewkitValueError, match="cannot write the snapshot"):
        save_snapshot(sk.load_mechanism("h4").twist_graph(), "/nonexistent-folder/x.toml")


def test_colliding_link_names_are_refused():
    graph = sk.twist_graph(1, "1", [(1, "1", sk.prismatic("P", [1, 0, 0]))])
    with pytest.raises(sk.ScrewkitValueError, match="names collide"):
        snapshot_text(graph)


# the command line -----------------------------------------------------------------------------------
@pytest.mark.parametrize("fmt", ["dot", "json", "toml"])
def test_cli_graph_writes_each_format(fmt, capsys, tmp_path):
    assert main(["graph", "h4", "--format", fmt, "--pose", "30", "-20", "-750", "17"]) == 0
    text = capsys.readouterr().out
    graph = sk.load_mechanism("h4").twist_graph([30.0, -20.0, -750.0, math.radians(17.0)])
    if fmt == "dot":
        assert text.strip() == graph_dot(graph)
    elif fmt == "json":
        assert json.loads(text) == json.loads(graph_json(graph))
    else:
        out = tmp_path / "h4.toml"
        assert main(["graph", "h4", "--format", "toml", "--pose", "30", "-20", "-750", "17", "--out", str(out)]) == 0
        assert out.read_text() == text
        assert main(["analyze", str(out), "--no-superbracket"]) == 0


def test_cli_graph_equivalent_and_snapshot_input(capsys, tmp_path):
    out = tmp_path / "eq.toml"
    assert main(["graph", "h4", "--equivalent", "--format", "toml", "--out", str(out)]) == 0
    assert main(["graph", str(out), "--format", "dot"]) == 0
    assert capsys.readouterr().out.count("->") == sk.equivalent_twist_graph(
        sk.load_mechanism("h4").twist_graph()).number_of_edges()
    assert main(["graph", str(out), "--pose", "0", "0", "-750", "0"]) == 2
    assert "is a snapshot (one configuration); --pose does not apply" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("argv", "status", "message"),
    [
        (["graph", "nosuch"], 2, "screwkit graph: error: unknown mechanism 'nosuch'"),
        (["graph", "h4", "--format", "png"], 2, "invalid choice: 'png'"),
        (["graph", "h4", "--pose", "1", "2"], 2, "screwkit graph: error: --pose expects 4 finite numbers"),
        (["graph", "h4", "--out", "/nonexistent-folder/x.dot"], 2, "--out /nonexistent-folder/x.dot: cannot write"),
    ],
)
def test_cli_graph_errors_are_one_line(argv, status, message, capsys):
    assert main(argv) == status
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
