"""The structure analysed once: series-parallel tree, legs, limbs, the loop-closure fallback."""

import networkx as nx
import numpy as np
import pytest

from screwkit.core.singularity import classify
from screwkit.exceptions import TwistGraphError
from screwkit.graphs.joints import revolute
from screwkit.graphs.jointtable import JointSpec, JointTable
from screwkit.graphs.reduction import platform_twist_system
from screwkit.graphs.topology import network_layout, topology
from screwkit.graphs.twistgraph import twist_graph
from screwkit.robots.catalog import load_mechanism

from ..mechanisms import wheatstone_bridge

H4 = load_mechanism("h4")


def specs_of(graph):
    return JointTable.from_graph(graph).specs


def test_h4_tree_legs_and_limbs():
    graph = H4.twist_graph()
    top = topology("base", "end_effector", specs_of(graph))
    root = top.nodes[top.root]
    assert root.kind == "parallel" and len(top.legs) == 2  # L_I, L_II (paper 002 Eq. 2)
    assert [top.nodes[leg].kind for leg in top.legs] == ["series", "series"]
    assert top.actuated == ("A1", "A2", "A3", "A4")
    for limb in top.limbs:  # A_i, its parallelogram's four spheres, and its sub-platform's R
        i = limb.actuated_joint[1]
        spheres = {f"S{i}{c}" for c in "mnpq"}
        assert set(limb.joints) == {limb.actuated_joint, *spheres, {"1": "R_I", "4": "R_I"}.get(i, "R_II")}
        assert limb.sign == 1  # A_i points from the base to the arm
    # each limb's locked twist system is its parallelogram plus R_I/R_II: two siblings
    assert all(len(limb.siblings) == 2 for limb in top.limbs)


def test_topology_is_cached_on_the_structure():
    first = topology("base", "end_effector", specs_of(H4.twist_graph()))
    again = topology("base", "end_effector", specs_of(H4.twist_graph([40.0, 10.0, -800.0, 0.2])))
    assert first is again


def test_series_of_coaxial_pairs_reduces_without_enumerating_paths():
    # 24 links in series, each pair joined by two coaxial hinges: 2**24 simple paths, one tree
    joints = []
    for i in range(24):
        a, b = ("base" if i == 0 else f"L{i}"), ("platform" if i == 23 else f"L{i + 1}")
        axis = [0, 0, 1] if i % 2 == 0 else [1, 0, 0]
        joints += [(a, b, revolute(f"R{i}a", axis, [i, 0, 0], actuated=i == 0)),
                   (a, b, revolute(f"R{i}b", axis, [i, 0, 0]))]
    graph = twist_graph("base", "platform", joints)
    top = topology("base", "platform", specs_of(graph))
    assert not top.network and len(top.nodes) == 48 + 24 + 1
    report = classify(graph)
    assert report.analysis.platform_order == platform_twist_system(graph).order == 3  # here
    # generic mobility 6: turning an x hinge tilts the z hinges after it (a 24R chain); here 3
    assert report.dof == 6 and report.lost_dof == 3


def test_bridge_falls_back_to_loop_closure():
    graph = wheatstone_bridge()
    top = topology("base", "platform", specs_of(graph))
    assert top.network and top.root is None
    analysis = classify(graph).analysis  # no actuator: a mobility analysis, dof derived (0)
    assert analysis.dof == 0
    # planar Grübler count 3(4 - 1) - 2·5 = -1: the bridge is rigid, as loop closure finds too
    assert analysis.platform_order == platform_twist_system(graph).order == 0


def test_network_layout_loops_count():
    graph = wheatstone_bridge()
    specs = specs_of(graph)
    loops, path = network_layout("base", "platform", specs, tuple(range(len(specs))))
    undirected = nx.MultiGraph(graph)
    assert len(loops) == undirected.number_of_edges() - undirected.number_of_nodes() + 1
    # walking the path from the base reaches the platform
    link = "base"
    for joint, sign in path:
        spec = specs[joint]
        assert (spec.parent if sign == 1 else spec.child) == link
        link = spec.child if sign == 1 else spec.parent
    assert link == "platform"


def test_error_actuated_joint_on_no_path():
    specs = (JointSpec("R", "R", "B", "E", 1), JointSpec("D", "R", "B", "dangling", 1, True))
    with pytest.raises(TwistGraphError, match=r"Actuated joint 'D' lies on no path from the base"):
        topology("B", "E", specs)


def test_joint_table_round_trip_keeps_the_screws():
    table = H4.joints(np.array([[0.0, 0.0, -750.0, 0.0], [30.0, -20.0, -800.0, 0.3]]))
    again = JointTable.from_graph(table.graph(1))
    order = {spec.name: k for k, spec in enumerate(again.specs)}
    for spec in table.specs:
        np.testing.assert_array_equal(again.joint_screws(spec.name), table[1].joint_screws(spec.name))
        assert again.specs[order[spec.name]] == spec
